// Kernels of the moving fluid mesh: the mesh position and velocity of a generalized-alpha step
// (exact for a motion linear in time, second order otherwise), the inversion check, and the
// Jacobian-based stiffening (smallest cell 1, the others (V_min / V)^chi).
#include "seam/ale/mesh_motion.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

using namespace seam;
using fem::CellType;

TEST(StepMesh, LinearMotionGivesItsVelocity) {
  // d(t) = a + b t per entry, the rate at t_n exact: the recursion keeps d_dot = b, and the
  // configuration is X + d(t_n + alpha_f h).
  const auto ga = ale::GeneralizedAlpha::from_rho_inf(0.5);
  const std::vector<double> X{0.0, 1.0, 2.0, -1.0}, a{0.1, -0.2, 0.3, 0.0}, b{1.0, 2.0, -3.0, 0.5};
  const double tn = 0.7, h = 0.05;
  std::vector<double> d_old(4), d_new(4), x(4), w(4), d_dot_new(4);
  for (int k = 0; k < 4; ++k) {
    d_old[k] = a[k] + b[k] * tn;
    d_new[k] = a[k] + b[k] * (tn + h);
  }
  ale::step_mesh(ga, h, X, d_old, d_new, b, x, w, d_dot_new);
  for (int k = 0; k < 4; ++k) {
    EXPECT_NEAR(d_dot_new[k], b[k], 1e-12);
    EXPECT_NEAR(w[k], b[k], 1e-12);
    EXPECT_NEAR(x[k], X[k] + a[k] + b[k] * (tn + ga.alpha_f * h), 1e-14);
  }
}

TEST(StepMesh, MeshVelocityIsSecondOrder) {
  // d(t) = sin t from d_dot(0) = 1: the error of w_{n+alpha_m} against d'(t_{n+alpha_f}) at
  // t = 1 falls by ~4 when h halves.
  const auto ga = ale::GeneralizedAlpha::from_rho_inf(0.3);
  std::vector<double> errors;
  for (int steps : {20, 40, 80}) {
    const double h = 1.0 / steps;
    std::vector<double> X{0.0}, d{0.0}, d_dot{1.0}, d_new(1), x(1), w(1), d_dot_new(1);
    double err = 0.0;
    for (int n = 0; n < steps; ++n) {
      d_new[0] = std::sin((n + 1) * h);
      ale::step_mesh(ga, h, X, d, d_new, d_dot, x, w, d_dot_new);
      err = std::abs(w[0] - std::cos((n + ga.alpha_f) * h));
      d = d_new;
      d_dot = d_dot_new;
    }
    errors.push_back(err);
  }
  EXPECT_GT(errors[0] / errors[1], 3.5);
  EXPECT_GT(errors[1] / errors[2], 3.5);
}

TEST(Inverted, DetectsCollapsedAndFoldedCells) {
  for (auto type : {CellType::quad9, CellType::tri3, CellType::hex27, CellType::tet10}) {
    const auto ref = fem::reference_nodes(type);
    std::vector<double> x(ref.begin(), ref.end());
    EXPECT_FALSE(ale::inverted(type, x)) << fem::name(type);
    auto flat = x; // squeezed to zero width in x
    for (std::size_t k = 0; k < flat.size(); k += fem::dimension(type)) flat[k] *= 0.0;
    EXPECT_TRUE(ale::inverted(type, flat)) << fem::name(type);
    auto mirrored = x; // reflected: negative det everywhere
    for (std::size_t k = 0; k < mirrored.size(); k += fem::dimension(type)) mirrored[k] *= -1.0;
    EXPECT_TRUE(ale::inverted(type, mirrored)) << fem::name(type);
  }
  // A quad4 with one corner pushed past the diagonal: positive at the centre, folded at the
  // corner.
  std::vector<double> folded{-1, -1, 1, -1, -0.2, -0.2, -1, 1};
  EXPECT_TRUE(ale::inverted(CellType::quad4, folded));
}

TEST(JacobianStiffening, SmallCellsAreStiffer) {
  // Three quad4 cells of widths 1, 2, 4 in a row.
  mesh::Mesh m;
  m.dim = 2;
  const double xs[] = {0, 1, 3, 7};
  for (double x : xs) {
    m.x.push_back(x);
    m.x.push_back(0);
    m.x.push_back(x);
    m.x.push_back(1);
  }
  for (std::int32_t c = 0; c < 3; ++c) {
    const std::int32_t n[] = {2 * c, 2 * c + 2, 2 * c + 3, 2 * c + 1};
    m.add_cell(CellType::quad4, n);
  }
  const std::vector<std::int32_t> cells{0, 1, 2};
  const auto f1 = ale::jacobian_stiffening(m, cells, 1.0);
  EXPECT_NEAR(f1[0], 1.0, 1e-14);
  EXPECT_NEAR(f1[1], 0.5, 1e-14);
  EXPECT_NEAR(f1[2], 0.25, 1e-14);
  const auto f2 = ale::jacobian_stiffening(m, cells, 2.0);
  EXPECT_NEAR(f2[2], 1.0 / 16, 1e-14);
  for (double f : ale::jacobian_stiffening(m, cells, 0.0)) EXPECT_EQ(f, 1.0);
  // A part of a distributed mesh: its cells 1 and 2 against the smallest volume of all ranks
  // (cell 0's, 1), not of its own cells (2).
  const std::vector<std::int32_t> part{1, 2};
  const auto fp = ale::jacobian_stiffening(m, part, 1.0, 1.0);
  EXPECT_NEAR(fp[0], 0.5, 1e-14);
  EXPECT_NEAR(fp[1], 0.25, 1e-14);
  EXPECT_NEAR(ale::jacobian_stiffening(m, part, 1.0)[0], 1.0, 1e-14);
}
