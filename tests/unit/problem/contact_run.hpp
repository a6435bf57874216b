#pragma once
// The objects of a contact computation for the unit tests of the Newton system
// (test_friction_tangent.cpp, test_released_nodes.cpp): case.yaml and case.geo of a folder
// read, and the constraints, the output and the Newton solver over them.
#include "seam/common/mpi.hpp"
#include "seam/common/timer.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/tying_constraint.hpp"

#include <filesystem>
#include <vector>

namespace seam::problem {

struct ContactRun {
  /// `serendipity`: the mesh's quadratic cells are serendipity ones (quad8, hex20).
  ContactRun(const Comm& comm, const std::filesystem::path& folder, bool serendipity)
      : config(io::load_config(folder / "case.yaml")),
        mesh(mesh::read_mesh(folder / "case.geo", options(config, serendipity))), disc(mesh, comm),
        model(build_model(config, disc)), tied(meshtying::setup_mesh_tying(config, mesh, timers)),
        tying(tied, disc, model), saddle(tied, disc, model), contact(config, disc, model),
        out(config, disc, model, tied, folder / "out", true),
        newton(config, model, disc, tying, saddle, contact, out) {}
  ContactRun(const ContactRun&) = delete;
  ContactRun& operator=(const ContactRun&) = delete;

  /// The bulk residual and tangent at time t (no inertia).
  auto evaluator(double t) {
    return [this, t](const la::Vector& state, la::Vector& r, la::Matrix* K, la::Vector& f_ext) {
      return assemble(model, disc, state, t, r, K, &f_ext);
    };
  }

  io::Config config;
  mesh::Mesh mesh;
  Discretization disc;
  Model model;
  PhaseTimers timers;
  std::vector<meshtying::TiedInterface> tied;
  TyingConstraint tying;
  SaddlePoint saddle;
  ContactConstraint contact;
  Output out;
  NewtonSolver newton;

private:
  static mesh::ReadOptions options(const io::Config& config, bool serendipity) {
    mesh::ReadOptions o;
    o.dim = config.dimension;
    o.order = config.mesh.order;
    o.serendipity = serendipity;
    return o;
  }
};

} // namespace seam::problem
