// The pressure-space operators of the PCD preconditioner on affine Taylor-Hood cells of every
// type, against exact integrals: the mass matrix sums to the cell's measure, the Laplacian and
// the convection matrix annihilate constants, and for a linear pressure p = g . x (exact in
// the P1/Q1 pressure space on affine cells) p^T A p = |g|^2 |cell| and
// 1^T N p = (c . g) |cell| for a constant velocity c.
#include "seam/fluid/pressure_operators.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

using namespace seam;
using fem::CellType;

namespace {

class PressureOperators : public ::testing::TestWithParam<CellType> {};

TEST_P(PressureOperators, ExactOnAffineCells) {
  const auto type = GetParam();
  const int dim = fem::dimension(type);
  const int n = fem::n_nodes(type);
  const int nv = fem::n_vertices(type);
  // x = B xi + b: stretched and sheared, so that no identity hides in the geometry.
  const double B[3][3] = {{1.3, 0.4, -0.2}, {0.1, 0.9, 0.3}, {0.2, -0.1, 1.1}};
  const double b[3] = {0.5, -0.7, 0.2};
  const auto ref = fem::reference_nodes(type);
  std::vector<double> x(n * dim), c(n * dim);
  const std::array<double, 3> velocity = {0.7, -1.1, 0.4}, g = {2.0, -0.5, 1.5};
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      x[a * dim + i] = b[i];
      for (int j = 0; j < dim; ++j) x[a * dim + i] += B[i][j] * ref[a * dim + j];
      c[a * dim + i] = velocity[i];
    }
  double det = dim == 2 ? B[0][0] * B[1][1] - B[0][1] * B[1][0]
                        : B[0][0] * (B[1][1] * B[2][2] - B[1][2] * B[2][1]) -
                              B[0][1] * (B[1][0] * B[2][2] - B[1][2] * B[2][0]) +
                              B[0][2] * (B[1][0] * B[2][1] - B[1][1] * B[2][0]);
  const double reference_measure = type == CellType::tri6    ? 0.5
                                   : type == CellType::tet10 ? 1.0 / 6.0
                                   : type == CellType::quad9 ? 4.0
                                                             : 8.0;
  const double measure = det * reference_measure;
  std::vector<double> M(nv * nv), A(nv * nv), N(nv * nv);
  ASSERT_TRUE(fluid::pressure_operators(type, x, c, {}, M, A, N));
  std::vector<double> p(nv);
  for (int k = 0; k < nv; ++k)
    for (int i = 0; i < dim; ++i) p[k] += g[i] * x[k * dim + i];
  double mass = 0.0, energy = 0.0, transport = 0.0, cg = 0.0, g2 = 0.0;
  for (int i = 0; i < dim; ++i) {
    cg += velocity[i] * g[i];
    g2 += g[i] * g[i];
  }
  for (int k = 0; k < nv; ++k) {
    double a_row = 0.0, n_row = 0.0;
    for (int l = 0; l < nv; ++l) {
      mass += M[k * nv + l];
      a_row += A[k * nv + l];
      n_row += N[k * nv + l];
      energy += p[k] * A[k * nv + l] * p[l];
      transport += N[k * nv + l] * p[l];
      EXPECT_NEAR(M[k * nv + l], M[l * nv + k], 1e-14);
      EXPECT_NEAR(A[k * nv + l], A[l * nv + k], 1e-13);
    }
    EXPECT_NEAR(a_row, 0.0, 1e-12) << "row " << k;
    EXPECT_NEAR(n_row, 0.0, 1e-12) << "row " << k;
  }
  EXPECT_NEAR(mass, measure, 1e-12 * measure);
  EXPECT_NEAR(energy, g2 * measure, 1e-11 * g2 * measure);
  EXPECT_NEAR(transport, cg * measure, 1e-11 * std::abs(cg) * measure);
}

TEST_P(PressureOperators, InvertedCellIsReported) {
  const auto type = GetParam();
  const int dim = fem::dimension(type);
  const int n = fem::n_nodes(type);
  const int nv = fem::n_vertices(type);
  const auto ref = fem::reference_nodes(type);
  std::vector<double> x(ref.begin(), ref.end()), c(n * dim, 0.0);
  for (int a = 0; a < n; ++a) x[a * dim] = -x[a * dim]; // mirrored: det J < 0
  std::vector<double> M(nv * nv), A(nv * nv), N(nv * nv);
  EXPECT_FALSE(fluid::pressure_operators(type, x, c, {}, M, A, N));
}

// ALE: on a rigidly translated cell whose fluid moves with the mesh (u = w, not uniform), the
// convection u - w vanishes: N = 0, and M and A are those of the cell before the translation.
// With u = w + c0 (c0 constant) N is the fixed cell's N at the velocity c0.
TEST_P(PressureOperators, MovingMeshConvectsWithTheRelativeVelocity) {
  const auto type = GetParam();
  const int dim = fem::dimension(type);
  const int n = fem::n_nodes(type);
  const int nv = fem::n_vertices(type);
  const auto ref = fem::reference_nodes(type);
  const double B[3][3] = {{1.3, 0.4, -0.2}, {0.1, 0.9, 0.3}, {0.2, -0.1, 1.1}};
  const double shift[3] = {3.5, -1.25, 0.75};
  const std::array<double, 3> c0 = {0.7, -1.1, 0.4};
  std::vector<double> X(n * dim), x(n * dim), w(n * dim), u(n * dim), c(n * dim);
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      for (int j = 0; j < dim; ++j) X[a * dim + i] += B[i][j] * ref[a * dim + j];
      x[a * dim + i] = X[a * dim + i] + shift[i];
      w[a * dim + i] = std::sin(1.0 + a + 2.0 * i) + X[a * dim + i] * X[a * dim + i];
      u[a * dim + i] = w[a * dim + i] + c0[i];
      c[a * dim + i] = c0[i];
    }
  std::vector<double> M(nv * nv), A(nv * nv), N(nv * nv), M0(nv * nv), A0(nv * nv), N0(nv * nv);
  ASSERT_TRUE(fluid::pressure_operators(type, x, w, w, M, A, N));
  ASSERT_TRUE(fluid::pressure_operators(type, X, c, {}, M0, A0, N0));
  double scale = 0.0;
  for (int kl = 0; kl < nv * nv; ++kl) scale = std::max(scale, std::abs(N0[kl]));
  for (int kl = 0; kl < nv * nv; ++kl) {
    EXPECT_EQ(N[kl], 0.0) << kl;
    EXPECT_NEAR(M[kl], M0[kl], 1e-13 * std::abs(M0[kl]) + 1e-15) << kl;
    EXPECT_NEAR(A[kl], A0[kl], 1e-12 * std::abs(A0[kl]) + 1e-13) << kl;
  }
  ASSERT_TRUE(fluid::pressure_operators(type, x, u, w, M, A, N));
  for (int kl = 0; kl < nv * nv; ++kl) EXPECT_NEAR(N[kl], N0[kl], 1e-12 * scale) << kl;
}

INSTANTIATE_TEST_SUITE_P(TaylorHood, PressureOperators,
                         ::testing::Values(CellType::tri6, CellType::quad9, CellType::tet10,
                                           CellType::hex27));

} // namespace
