// Interface assembly in 2D: non-matching straight and curved interfaces.
#include <numbers>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/common/error.hpp"

using namespace seam::mortar;
using seam::local_index;
using seam::fem::CellType;
using test::Surface;

namespace {

// Slave body below y = 0 (facets run right to left, normal +y), master body above at y = h
// (facets run left to right, normal -y), both over x in [0, 1].
Surface straight(int n, CellType type, double y, bool slave) {
  return test::line_mesh(
      n, type, [y](double s) { return Eigen::Vector2d(s, y); }, slave);
}

// Quarter arcs of radius r: slave (inner body, normal outward) and master (outer body).
Surface arc(int n, CellType type, double r, bool slave) {
  return test::line_mesh(
      n, type,
      [r](double s) {
        const double t = 0.5 * std::numbers::pi * s;
        return Eigen::Vector2d(r * std::cos(t), r * std::sin(t));
      },
      !slave);
}

void expect_row_sums(const MortarOperators& ops, const Surface& s, const Surface& m) {
  const Eigen::MatrixXd D = test::dense(ops.D, s.n_nodes(), s.n_nodes());
  const Eigen::MatrixXd M = test::dense(ops.M, s.n_nodes(), m.n_nodes());
  const double scale = D.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LE((D.rowwise().sum() - M.rowwise().sum()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  if (ops.multiplier == Multiplier::dual) {
    EXPECT_EQ((D - Eigen::MatrixXd(D.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 0.0);
  }
}

} // namespace

TEST(Interface2D, StraightNonMatchingLinearAndQuadratic) {
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const Surface s = straight(7, type, 0.0, true);
    const Surface m = straight(5, type, 0.0, false);
    const auto pairs = test::all_pairs(s, m);
    for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
      const MortarOperators ops = assemble_mortar_operators(s.view(), m.view(), pairs, {mult, {}});
      expect_row_sums(ops, s, m);
      EXPECT_EQ(ops.n_projection_failures, 0);
      EXPECT_NEAR(ops.integrated_area, 1.0, 1e-14);
      EXPECT_EQ(ops.n_pairs_integrated, 7 + 5 - 1); // cuts at all distinct node positions
      const Eigen::MatrixXd D = test::dense(ops.D, s.n_nodes(), s.n_nodes());
      const Eigen::MatrixXd M = test::dense(ops.M, s.n_nodes(), m.n_nodes());
      if (mult == Multiplier::standard) {
        EXPECT_NEAR(D.sum(), 1.0, 1e-14);
      }
      // Linear fields are reproduced: D X_s = M X_m for x, y and any affine combination.
      const Eigen::VectorXd fs = (3.0 * s.coordinate(0) - s.coordinate(1)).array() + 2.0;
      const Eigen::VectorXd fm = (3.0 * m.coordinate(0) - m.coordinate(1)).array() + 2.0;
      EXPECT_LE((D * fs - M * fm).cwiseAbs().maxCoeff(), 1e-14);
      EXPECT_LE((D * s.coordinate(0) - M * m.coordinate(0)).cwiseAbs().maxCoeff(), 1e-14);
    }
  }
}

TEST(Interface2D, WeightedGapOfParallelLines) {
  // g~_j = h int Phi_j, and int Phi_j = int N_j (dual: biorthogonality with sum_k N_k = 1):
  // for line2 elements of length 1/n: 1/(2n) at the ends, 1/n inside.
  const double h = 0.05;
  const int n = 6;
  const Surface s = straight(n, CellType::line2, -h, true);
  const Surface m = straight(4, CellType::line2, 0.0, false);
  for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
    const MortarOperators ops =
        assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
    for (local_index j = 0; j <= n; ++j) {
      const double integral = (j == 0 || j == n) ? 0.5 / n : 1.0 / n;
      EXPECT_NEAR(ops.weighted_gap[static_cast<std::size_t>(j)], h * integral, 1e-15);
    }
  }
}

TEST(Interface2D, CurvedInterfaceRowSums) {
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const Surface s = arc(9, type, 1.0, true);
    const Surface m = arc(5, type, 1.0, false);
    for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
      const MortarOperators ops =
          assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
      expect_row_sums(ops, s, m);
      EXPECT_EQ(ops.n_projection_failures, 0);
      // The covered length approximates the quarter circle.
      EXPECT_NEAR(ops.integrated_area, 0.5 * std::numbers::pi,
                  type == CellType::line2 ? 5e-3 : 1e-4);
    }
  }
}

TEST(Interface2D, MeshInitializationMovesSlaveOntoMaster) {
  // Slave a distance h below the master line: after initialization D X_s = M X_m puts it on
  // y = 0 and keeps its x coordinates (the projection along the normal is vertical).
  for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
    const Surface s = straight(7, CellType::line2, -0.1, true);
    const Surface m = straight(4, CellType::line2, 0.0, false);
    const MortarOperators ops =
        assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
    const auto x = initialize_slave_coordinates(ops, s.coordinates, m.coordinates);
    for (local_index i = 0; i < s.n_nodes(); ++i) {
      EXPECT_NEAR(x[static_cast<std::size_t>(2 * i)],
                  s.coordinates[static_cast<std::size_t>(2 * i)], 1e-14);
      EXPECT_NEAR(x[static_cast<std::size_t>(2 * i + 1)], 0.0, 1e-14);
    }
  }
}

TEST(Interface2D, InputErrors) {
  const Surface s = straight(3, CellType::line2, 0.0, true);
  const Surface m = straight(2, CellType::line2, 0.0, false);
  const std::vector<CandidatePair> bad = {{0, 7}};
  EXPECT_THROW(assemble_mortar_operators(s.view(), m.view(), bad), seam::InputError);
  const Surface m3 = test::grid(
      1, 1, CellType::quad4, [](double u, double v) { return Eigen::Vector3d(u, v, 0); }, true);
  EXPECT_THROW(assemble_mortar_operators(s.view(), m3.view(), {}), seam::InputError);
}
