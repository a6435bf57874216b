// The condensed fluid-structure Newton system (FsiSystem) against finite differences: for
// random directions v, J v (the assembled R^T J T_c) equals the fourth-order central difference
// of the condensed residual R^T r(T_c x + g) along v. Every block enters: the structure's
// tangent, the fluid by (u, p), the fluid by the mesh (shape derivatives), the pseudo-elastic
// mesh, and the chain rules of the coupling (m_G = P d_G, the fluid's interface rows moved to
// the structure by P^T). The same check without the shape derivatives must fail: the test
// can tell. The same in a generalized-alpha step (inertia of both fields, the mesh velocity,
// the interface velocity u_G = P v(d_{n+1})). Also: the force the structure receives through P^T
// equals the fluid's interface force (the rows of P sum to one), on a non-matching interface.
// The Jacobian checked is one made at rest and refreshed in place (the pattern is built once).
//
// The case: a channel [0, 1] x [0, 0.4] whose bottom has an elastic block [0.3, 0.7] x
// [-0.1, 0] (own nodes) under it; the fluid's bottom segment over the block and the block's
// top are the fsi interface, with 6 fluid and 4 structure facets (non-matching). In 3D: a
// duct [0, 1] x [0, 0.4] x [0, 0.3] on an elastic slab [0, 1] x [-0.1, 0] x [0, 0.3] (own
// nodes), the duct's whole floor wet: the slab tet10 (size 0.35), the duct tet10 (size 0.25) or
// hex27 (3 x 3 x 3): non-matching tri6 : tri6 or quad9 : tri6 facets.
#include "seam/common/mpi.hpp"
#include "seam/common/timer.hpp"
#include "seam/fsi/fsi_system.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/meshtying/tied_interface.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <numeric>
#include <string>
#include <vector>

namespace seam::fsi {
namespace {

double noise(std::int64_t i, int k) {
  const double v = std::sin(12.9898 * static_cast<double>(i) + 78.233 * k) * 43758.5453;
  return 2.0 * (v - std::floor(v)) - 1.0;
}

const char* channel_geo = R"(
h = 0.1;
Point(1) = {0, 0, 0, h}; Point(2) = {0.3, 0, 0, h}; Point(3) = {0.7, 0, 0, h};
Point(4) = {1, 0, 0, h}; Point(5) = {1, 0.4, 0, h}; Point(6) = {0, 0.4, 0, h};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 5}; Line(5) = {5, 6};
Line(6) = {6, 1};
Curve Loop(1) = {1, 2, 3, 4, 5, 6}; Plane Surface(1) = {1};
Transfinite Curve{2} = 7;
Point(11) = {0.3, -0.1, 0}; Point(12) = {0.7, -0.1, 0}; Point(13) = {0.7, 0, 0};
Point(14) = {0.3, 0, 0};
Line(11) = {11, 12}; Line(12) = {12, 13}; Line(13) = {13, 14}; Line(14) = {14, 11};
Curve Loop(11) = {11, 12, 13, 14}; Plane Surface(11) = {11};
Transfinite Curve{11, 13} = 5; Transfinite Curve{12, 14} = 3;
Transfinite Surface{11}; Recombine Surface{11};
Physical Surface("fluid") = {1};
Physical Curve("inflow") = {6};
Physical Curve("walls") = {1, 3, 5};
Physical Curve("wet_fluid") = {2};
Physical Surface("block") = {11};
Physical Curve("base") = {11};
Physical Curve("wet") = {13};
)";

// The 3D case: a box of fluid over an elastic slab, built apart (the slab at y - 1, so that the
// groups can be told by bounding boxes) and moved into place; `hexes` is set before.
const char* duct_geo = R"(
SetFactory("OpenCASCADE");
Box(1) = {0, 0, 0, 1, 0.4, 0.3};
Box(2) = {0, -1.1, 0, 1, 0.1, 0.3};
MeshSize{PointsOf{Volume{1};}} = 0.25;
MeshSize{PointsOf{Volume{2};}} = 0.35;
e = 1e-6;
If (hexes)
  Transfinite Curve{Curve In BoundingBox{-e, -e, -e, 1 + e, 0.4 + e, 0.3 + e}} = 4;
  Transfinite Surface{Surface In BoundingBox{-e, -e, -e, 1 + e, 0.4 + e, 0.3 + e}};
  Recombine Surface{Surface In BoundingBox{-e, -e, -e, 1 + e, 0.4 + e, 0.3 + e}};
  Transfinite Volume{1};
EndIf
Physical Volume("fluid") = {1};
Physical Surface("inflow") = {Surface In BoundingBox{-e, -e, -e, e, 0.4 + e, 0.3 + e}};
Physical Surface("walls") = {Surface In BoundingBox{-e, 0.4 - e, -e, 1 + e, 0.4 + e, 0.3 + e},
                             Surface In BoundingBox{-e, -e, -e, 1 + e, 0.4 + e, e},
                             Surface In BoundingBox{-e, -e, 0.3 - e, 1 + e, 0.4 + e, 0.3 + e}};
Physical Surface("wet_fluid") = {Surface In BoundingBox{-e, -e, -e, 1 + e, e, 0.3 + e}};
Physical Volume("block") = {2};
Physical Surface("base") = {Surface In BoundingBox{-e, -1.1 - e, -e, 1 + e, -1.1 + e, 0.3 + e}};
Physical Surface("wet") = {Surface In BoundingBox{-e, -1 - e, -e, 1 + e, -1 + e, 0.3 + e}};
Translate {0, 1, 0} { Volume{2}; }
)";

enum class Shape { plane, tet, hex };

struct Errors {
  double with_shape = 0.0, without_shape = 0.0, force = 0.0;
  /// The unknowns, and the norm of the condensed residual at x = 0 (which does not depend on
  /// the numbering of the unknowns).
  long long n_unknowns = 0;
  double rest_norm = 0.0;
};

/// `distributed`: on each rank's part of the distributed mesh (mesh::distribute_mesh, its own
/// cells and a ghost layer; the couplings set up distributed), else on the replicated mesh.
Errors check(int order, bool dynamic = false, Shape shape_of = Shape::plane,
             bool distributed = false) {
  Comm comm;
  const int dim = shape_of == Shape::plane ? 2 : 3;
  const char* tag[] = {"2d", "tet", "hex"};
  const auto folder = std::filesystem::temp_directory_path() /
                      ("seam_fsi_fd_" + std::to_string(order) + tag[static_cast<int>(shape_of)] +
                       "_np" + std::to_string(comm.size()));
  const std::string yaml =
      "dimension: " + std::to_string(dim) + (dim == 2 ? "\nplane: strain" : "") +
      "\nmesh: {geo: case.geo, order: " + std::to_string(order) +
      "}\n"
      "materials:\n"
      "  f: {model: newtonian_fluid, density: 1.0, viscosity: 0.05}\n"
      "  s: {model: saint_venant_kirchhoff, young: 50.0, poisson: 0.3}\n"
      "bodies:\n  - {region: fluid, material: f}\n  - {region: block, material: s}\n"
      "boundary_conditions:\n" +
      (dim == 2 ? "  - {region: inflow, type: velocity, value: ['y*(0.4-y)', 0]}\n"
                  "  - {region: walls, type: velocity, value: [0, 0]}\n"
                  "  - {region: base, type: dirichlet, value: [0, 0]}\n"
                : "  - {region: inflow, type: velocity, value: ['30*y*(0.4-y)*z*(0.3-z)', 0, 0]}\n"
                  "  - {region: walls, type: velocity, value: [0, 0, 0]}\n"
                  "  - {region: base, type: dirichlet, value: [0, 0, 0]}\n") +
      "interfaces:\n  - {name: wall, type: fsi, fluid: wet_fluid, structure: wet}\n"
      "time: {integrator: static, end: 1, steps: 1}\n";
  if (comm.is_root()) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "case.geo") << (dim == 2                 ? ""
                                           : shape_of == Shape::hex ? "hexes = 1;\n"
                                                                    : "hexes = 0;\n")
                                       << (dim == 2 ? channel_geo : duct_geo);
    std::ofstream(folder / "case.yaml") << yaml;
  }
  comm.barrier();
  const auto config = io::load_config(folder / "case.yaml");
  mesh::ReadOptions opts;
  opts.dim = dim;
  opts.order = order;
  auto whole = mesh::read_mesh(folder / "case.geo", opts);
  mesh::DistributedMesh part;
  if (distributed) {
    if (!comm.is_root()) whole = mesh::Mesh{};
    part = mesh::distribute_mesh(whole, comm.get());
  }
  auto& mesh = distributed ? part.mesh : whole;
  PhaseTimers timers;
  const auto tied =
      distributed
          ? meshtying::setup_mesh_tying(config, part, comm.get(), timers, io::InterfaceType::fsi)
          : meshtying::setup_mesh_tying(config, mesh, timers, io::InterfaceType::fsi);
  FsiSystem sys(config, mesh, tied, comm, distributed ? &part : nullptr);
  // Dynamics: a step from a state at t_n that is not at rest (random, the same on every rank):
  // the inertia of both fields, the mesh velocity's derivatives and u_G = P v(d) enter.
  FsiSystem::History history;
  if (dynamic) {
    history = FsiSystem::History::from_rho_inf(0.5, 0.05, sys.n_raw());
    for (std::size_t k = 0; k < sys.n_raw(); ++k) {
      // By a number of the raw dof that every rank holding it shares.
      const auto id = sys.raw_id(k);
      history.old[k] = 0.003 * noise(id, 3);
      history.rate[k] = 0.01 * noise(id, 4);
      history.accel[k] = 0.1 * noise(id, 5);
    }
    sys.set_history(&history);
  }
  const auto N = static_cast<std::size_t>(sys.n_unknowns());
  // A state away from rest: every unknown perturbed (mesh and structure by a few percent of
  // a cell, so that no cell inverts), the same on every rank.
  std::vector<double> x(N);
  for (std::size_t k = 0; k < N; ++k) x[k] = 0.004 * noise(static_cast<std::int64_t>(k), 1);
  const auto g = sys.prescribed(1.0);

  std::vector<PetscInt> owned(static_cast<std::size_t>(sys.n_owned()));
  std::iota(owned.begin(), owned.end(), sys.first_owned());
  const auto residual = [&](const std::vector<double>& state, la::Matrix* J, bool shape,
                            FsiSystem::Result* out = nullptr) {
    std::vector<double> raw;
    // expand takes the held unknowns (the state is the same on every rank).
    std::vector<double> held;
    for (auto k : sys.held_unknowns()) held.push_back(state[static_cast<std::size_t>(k)]);
    sys.expand(held, g, raw);
    la::Vector r;
    FsiSystem::Options o;
    o.shape_derivatives = shape;
    auto res = sys.assemble(raw, 1.0, r, J, o);
    EXPECT_FALSE(res.inverted);
    if (out) *out = res;
    std::vector<double> values(owned.size());
    VecGetValues(r.get(), static_cast<PetscInt>(owned.size()), owned.data(), values.data());
    return values;
  };
  Errors e;
  e.n_unknowns = static_cast<long long>(N);
  {
    la::Vector r;
    std::vector<double> raw;
    sys.expand(std::vector<double>(sys.held_unknowns().size(), 0.0), g, raw);
    sys.assemble(raw, 1.0, r, nullptr, {});
    e.rest_norm = r.norm();
  }
  for (int shape = 1; shape >= 0; --shape) {
    la::Matrix J;
    FsiSystem::Result res;
    // With the shape derivatives the Jacobian is first made at rest, where many of its entries
    // (the shape derivatives among them) are zero, and then refreshed in place at x: the
    // pattern made once must hold every entry of J at x.
    if (shape) residual(std::vector<double>(N, 0.0), &J, true);
    residual(x, &J, shape != 0, &res);
    if (shape) {
      // Force conservation through P^T (the raw residual summed on the owners of the nodes:
      // each rank's sums over its nodes, summed over ranks).
      std::array<double, 3> ff{}, fs{};
      for (const auto& cp : sys.couplings())
        for (std::size_t j = 0; j < cp.fluid_nodes.size(); ++j)
          for (int i = 0; i < dim; ++i) {
            const double f = -res.raw_residual[sys.f_dof(cp.fluid_nodes[j], i)];
            ff[i] += f;
            for (auto q = cp.offsets[j]; q < cp.offsets[j + 1]; ++q) fs[i] += cp.weights[q] * f;
          }
      comm.sum_in_place(ff);
      comm.sum_in_place(fs);
      e.force =
          std::hypot(ff[0] - fs[0], ff[1] - fs[1], ff[2] - fs[2]) / std::hypot(ff[0], ff[1], ff[2]);
    }
    double worst = 0.0;
    for (int dir = 0; dir < 3; ++dir) {
      std::vector<double> v(N);
      for (std::size_t k = 0; k < N; ++k) v[k] = noise(static_cast<std::int64_t>(k), 10 + dir);
      la::Vector vv(comm.get(), sys.n_owned()), Jv(comm.get(), sys.n_owned());
      {
        std::vector<double> mine(owned.size());
        for (std::size_t q = 0; q < owned.size(); ++q) mine[q] = v[owned[q]];
        vv.set_values(owned, mine);
        vv.assemble();
      }
      J.mult(vv, Jv);
      std::vector<double> jv(owned.size());
      VecGetValues(Jv.get(), static_cast<PetscInt>(owned.size()), owned.data(), jv.data());
      const double h = 1e-5;
      std::vector<std::vector<double>> rs;
      for (double s : {2.0, 1.0, -1.0, -2.0}) {
        auto xs = x;
        for (std::size_t k = 0; k < N; ++k) xs[k] += s * h * v[k];
        rs.push_back(residual(xs, nullptr, true));
      }
      double num = 0.0, den = 0.0;
      for (std::size_t q = 0; q < owned.size(); ++q) {
        const double fd = (-rs[0][q] + 8.0 * rs[1][q] - 8.0 * rs[2][q] + rs[3][q]) / (12.0 * h);
        num += (jv[q] - fd) * (jv[q] - fd);
        den += fd * fd;
      }
      num = comm.sum(num);
      den = comm.sum(den);
      worst = std::max(worst, std::sqrt(num / den));
    }
    (shape ? e.with_shape : e.without_shape) = worst;
  }
  if (comm.is_root())
    std::printf("fsi Jacobian, %s, order %d%s%s: %d unknowns, relative error %.3e with the shape "
                "derivatives, %.3e without; force transfer %.3e\n",
                tag[static_cast<int>(shape_of)], order, dynamic ? ", dynamic" : "",
                distributed ? ", distributed mesh" : "", static_cast<int>(N), e.with_shape,
                e.without_shape, e.force);
  return e;
}

TEST(FsiJacobian, QuadraticNonMatchingAgreesWithFiniteDifferences) {
  const auto e = check(2);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5); // fails the 1e-6 test by far
  EXPECT_LT(e.force, 1e-10);
}

TEST(FsiJacobian, LinearStabilizedAgreesWithFiniteDifferences) {
  const auto e = check(1);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5); // fails the 1e-6 test by far
  EXPECT_LT(e.force, 1e-10);
}

TEST(FsiJacobian, DynamicQuadraticAgreesWithFiniteDifferences) {
  const auto e = check(2, true);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5);
  EXPECT_LT(e.force, 1e-10);
}

TEST(FsiJacobian, DynamicLinearStabilizedAgreesWithFiniteDifferences) {
  const auto e = check(1, true);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5);
  EXPECT_LT(e.force, 1e-10);
}

// On each rank's part of the distributed mesh: the same Jacobian check, and the same unknowns
// and rest residual as on the replicated mesh (the numbering differs, the norm does not).
void check_distributed(int order, bool dynamic, Shape shape_of) {
  const auto e = check(order, dynamic, shape_of, true);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5);
  EXPECT_LT(e.force, 1e-10);
  const auto replicated = check(order, dynamic, shape_of);
  EXPECT_EQ(e.n_unknowns, replicated.n_unknowns);
  EXPECT_NEAR(e.rest_norm, replicated.rest_norm, 1e-12 * replicated.rest_norm);
  EXPECT_GT(e.rest_norm, 0.0);
}

TEST(FsiJacobian, DistributedQuadraticAgreesWithFiniteDifferences) {
  check_distributed(2, false, Shape::plane);
}

TEST(FsiJacobian, DistributedDynamicLinearStabilizedAgreesWithFiniteDifferences) {
  check_distributed(1, true, Shape::plane);
}

TEST(FsiJacobian, DistributedDynamicTet10AgreesWithFiniteDifferences) {
  check_distributed(2, true, Shape::tet);
}

// 3D: hex27 and tet10 fluid over a non-matching tet10 slab, static and in a
// generalized-alpha step.
TEST(FsiJacobian, Hex27NonMatching3dAgreesWithFiniteDifferences) {
  const auto e = check(2, false, Shape::hex);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5);
  EXPECT_LT(e.force, 1e-10);
}

TEST(FsiJacobian, DynamicTet10NonMatching3dAgreesWithFiniteDifferences) {
  const auto e = check(2, true, Shape::tet);
  EXPECT_LT(e.with_shape, 1e-6);
  EXPECT_GT(e.without_shape, 1e-5);
  EXPECT_LT(e.force, 1e-10);
}

} // namespace
} // namespace seam::fsi
