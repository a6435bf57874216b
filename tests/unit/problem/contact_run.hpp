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
#include <fstream>
#include <string>
#include <vector>

namespace seam::problem {

/// A block [0, 1] x [0, 0.25] of 16 x 4 quad4 (h = 0.0625; Gmsh text): groups bottom, top,
/// body.
inline constexpr const char* kBlock =
    "h = 0.0625;\n"
    "Point(1) = {0, 0, 0, h}; Point(2) = {1, 0, 0, h};\n"
    "Point(3) = {1, 0.25, 0, h}; Point(4) = {0, 0.25, 0, h};\n"
    "Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};\n"
    "Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};\n"
    "Transfinite Curve{1, 3} = 17; Transfinite Curve{2, 4} = 5;\n"
    "Transfinite Surface{1}; Recombine Surface{1};\n"
    "Physical Curve(\"bottom\") = {1}; Physical Curve(\"top\") = {3};\n"
    "Physical Surface(\"body\") = {1};\n";

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

/// A folder seam_NAME_np<ranks> in the temporary directory (made anew by the root) holding
/// case.geo, kBlock on kWideBase, and case.yaml: both neo-Hookean, the block's top held at
/// (0, top_y), the base's bottom fixed, one contact interface `joint` [bottom, base_top], then
/// `rest` (the time and solver sections). Collective.
inline std::filesystem::path write_block_on_base(const Comm& comm, const std::string& name,
                                                 const std::string& top_y,
                                                 const std::string& rest) {
  const auto folder = std::filesystem::temp_directory_path() /
                      ("seam_" + name + "_np" + std::to_string(comm.size()));
  const std::string yaml =
      "dimension: 2\nmesh: {geo: case.geo}\n"
      "materials:\n  m: {model: neo_hooke, young: 100.0, poisson: 0.3, density: 1.0}\n"
      "bodies:\n  - {region: body, material: m}\n  - {region: base, material: m}\n"
      "boundary_conditions:\n"
      "  - {region: top, type: dirichlet, components: [x, y], value: [0, " +
      top_y +
      "]}\n"
      "  - {region: base_bottom, type: dirichlet, components: [x, y], value: [0, 0]}\n"
      "interfaces:\n  - {name: joint, type: contact, surface: [bottom, base_top]}\n" +
      rest;
  if (comm.is_root()) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "case.geo") << kBlock << kWideBase;
    std::ofstream(folder / "case.yaml") << yaml;
  }
  comm.barrier();
  return folder;
}

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
