// Mass matrix tests: total mass, closed-form simplex mass matrices, lumping.
#include "test_util.hpp"

#include "seam/solid/mass.hpp"

#include <gtest/gtest.h>

using namespace seam;
using namespace seam::solid;
using namespace seam::solid::test;

namespace {

bool simplex(fem::CellType c) {
  return c == fem::CellType::tri3 || c == fem::CellType::tri6 || c == fem::CellType::tet4 ||
         c == fem::CellType::tet10;
}

// Exact measure of an undistorted cell_coordinates() cell: det(A) |reference cell|.
double affine_measure(fem::CellType c, int dim) {
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, -0.15, 0.9, 0.2, 0.1, -0.05, 1.2;
  const double ref = dim == 2 ? (simplex(c) ? 0.5 : 4.0) : (simplex(c) ? 1.0 / 6 : 8.0);
  return ref * (dim == 2 ? A.topLeftCorner<2, 2>().determinant() : A.determinant());
}

std::vector<std::pair<fem::CellType, int>> all_cells() {
  std::vector<std::pair<fem::CellType, int>> v;
  for (auto c : cells_2d) v.emplace_back(c, 2);
  for (auto c : cells_3d) v.emplace_back(c, 3);
  return v;
}

} // namespace

TEST(Mass, TotalMassAndBlockStructure) {
  const double rho = 7.8;
  for (auto [cell, dim] : all_cells()) {
    const std::vector<double> X = cell_coordinates(cell, dim, 0.0);
    const std::size_t nd = X.size();
    std::vector<double> M(nd * nd);
    ASSERT_EQ(consistent_mass(cell, dim, X, rho, M), KernelStatus::ok);
    double total = 0.0;
    for (std::size_t i = 0; i < nd; ++i)
      for (std::size_t j = 0; j < nd; ++j) {
        total += M[i * nd + j];
        if (i % dim != j % dim) {
          EXPECT_EQ(M[i * nd + j], 0.0); // identity blocks
        }
        EXPECT_EQ(M[i * nd + j], M[j * nd + i]);
      }
    const double V = affine_measure(cell, dim);
    EXPECT_NEAR(total, rho * V * dim, 1e-12 * rho * V) << fem::name(cell);

    for (auto scheme : {Lumping::row_sum, Lumping::diagonal_scaling}) {
      std::vector<double> m(nd);
      ASSERT_EQ(lumped_mass(cell, dim, X, rho, m, scheme), KernelStatus::ok);
      double sum = 0.0;
      for (double x : m) sum += x;
      EXPECT_NEAR(sum, rho * V * dim, 1e-12 * rho * V) << fem::name(cell);
      if (scheme == Lumping::diagonal_scaling) {
        for (double x : m) EXPECT_GT(x, 0.0) << fem::name(cell);
      }
    }
  }
}

TEST(Mass, ClosedFormSimplexMatrices) {
  // Linear simplices: int N_a N_b dV = V (1 + delta_ab) / 12 (triangle), / 20 (tetrahedron).
  // Row-sum lumping of quadratic simplices: tri6 corners 0 and edges V/3; tet10 corners
  // -V/20 and edges V/5.
  const double rho = 2.5;
  for (auto [cell, dim] : {std::pair{fem::CellType::tri3, 2}, std::pair{fem::CellType::tet4, 3}}) {
    const std::vector<double> X = cell_coordinates(cell, dim, 0.1, 4);
    const int n = dim + 1;
    Eigen::MatrixXd edges(dim, dim);
    for (int k = 0; k < dim; ++k)
      for (int i = 0; i < dim; ++i) edges(i, k) = X[(k + 1) * dim + i] - X[i];
    const double V = edges.determinant() / (dim == 2 ? 2.0 : 6.0);
    std::vector<double> M(n * dim * n * dim);
    ASSERT_EQ(consistent_mass(cell, dim, X, rho, M), KernelStatus::ok);
    const double denom = dim == 2 ? 12.0 : 20.0;
    for (int a = 0; a < n; ++a)
      for (int b = 0; b < n; ++b)
        EXPECT_NEAR(M[(a * dim) * n * dim + b * dim], rho * V * (1 + (a == b)) / denom,
                    1e-14 * rho * V);
  }
  for (auto [cell, dim] : {std::pair{fem::CellType::tri6, 2}, std::pair{fem::CellType::tet10, 3}}) {
    const std::vector<double> X = cell_coordinates(cell, dim, 0.0);
    const double V = affine_measure(cell, dim);
    std::vector<double> m(X.size());
    ASSERT_EQ(lumped_mass(cell, dim, X, rho, m), KernelStatus::ok);
    const double corner = dim == 2 ? 0.0 : -rho * V / 20,
                 edge = dim == 2 ? rho * V / 3 : rho * V / 5;
    for (int a = 0; a < fem::n_nodes(cell); ++a)
      EXPECT_NEAR(m[a * dim], a <= dim ? corner : edge, 1e-14 * rho * V) << fem::name(cell);
  }
}

TEST(Mass, DefaultDegreeIsExactForMultilinearCells) {
  // Distorted quad4/hex8 have a non-constant Jacobian; the default rule must agree with a
  // much higher one (a polynomial integrand, so both are exact if the default suffices).
  for (auto [cell, dim] : {std::pair{fem::CellType::quad4, 2}, std::pair{fem::CellType::hex8, 3},
                           std::pair{fem::CellType::quad9, 2}}) {
    std::vector<double> X = cell_coordinates(cell, dim, 0.15, 9);
    if (cell == fem::CellType::quad9) {
      // Straight-sided (bilinear) quad9: edge and centre nodes at their bilinear positions.
      const auto ref = fem::reference_nodes(cell);
      for (int a = 4; a < 9; ++a)
        for (int i = 0; i < 2; ++i) {
          double v = 0;
          for (int c = 0; c < 4; ++c) {
            const double w =
                0.25 * (1 + ref[2 * c] * ref[2 * a]) * (1 + ref[2 * c + 1] * ref[2 * a + 1]);
            v += w * X[c * 2 + i];
          }
          X[a * 2 + i] = v;
        }
    }
    const std::size_t nd = X.size();
    std::vector<double> M(nd * nd), M_hi(nd * nd);
    ASSERT_EQ(consistent_mass(cell, dim, X, 1.0, M), KernelStatus::ok);
    ASSERT_EQ(consistent_mass(cell, dim, X, 1.0, M_hi, 12), KernelStatus::ok);
    for (std::size_t i = 0; i < nd * nd; ++i) EXPECT_NEAR(M[i], M_hi[i], 1e-14) << fem::name(cell);
  }
  // Shoelace area of the distorted quad4 (its edges are straight, so it is exact).
  const std::vector<double> X = cell_coordinates(fem::CellType::quad4, 2, 0.15, 9);
  double area = 0;
  for (int a = 0; a < 4; ++a) {
    const int b = (a + 1) % 4;
    area += 0.5 * (X[2 * a] * X[2 * b + 1] - X[2 * b] * X[2 * a + 1]);
  }
  std::vector<double> m(8);
  ASSERT_EQ(lumped_mass(fem::CellType::quad4, 2, X, 3.0, m), KernelStatus::ok);
  EXPECT_NEAR(m[0] + m[2] + m[4] + m[6], 3.0 * area, 1e-13);
}

TEST(Mass, InvertedReferenceIsReported) {
  const std::vector<double> X = {0, 0, 0, 1, 1, 0}; // clockwise triangle
  std::vector<double> M(36);
  EXPECT_EQ(consistent_mass(fem::CellType::tri3, 2, X, 1.0, M), KernelStatus::inverted_reference);
}
