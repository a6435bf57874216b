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

/// A wider base block below the cases' body (Gmsh text; h is the body's mesh size), meshed
/// independently (non-matching, 0.7 h): groups base_bottom, base_top, base.
inline constexpr const char* kWideBase =
    "Point(11) = {-0.3, -0.25, 0, 0.7*h}; Point(12) = {1.3, -0.25, 0, 0.7*h};\n"
    "Point(13) = {1.3, 0, 0, 0.7*h}; Point(14) = {-0.3, 0, 0, 0.7*h};\n"
    "Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};\n"
    "Curve Loop(11) = {11, 12, 13, 14}; Plane Surface(11) = {11};\n"
    "Recombine Surface{11};\n"
    "Physical Curve(\"base_bottom\") = {11}; Physical Curve(\"base_top\") = {13};\n"
    "Physical Surface(\"base\") = {11};\n";

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
