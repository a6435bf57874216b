// The weighted gaps of the energy-momentum contact (gap_blocks) where a segment end of the
// 2D segmentation meets a slave facet's end (docs/contact_dynamics.md, "Diagnosing a stalled
// Newton step" and "The kink where a master node passes a slave end node"):
// - continuous where a master end node's projection onto a slave facet leaves the range the
//   segmentation accepts, xi = 1 + tol (tol = projection_range_tolerance = 0.05): there the
//   segment's end switches from the node's clamped projection to the slave's end node, which
//   must be 1 exactly (clamped too, it sat inside and g~ jumped; the 200 rings of
//   examples/rings stalled at t = 0.645);
// - where the master side ends at a node that passes a slave end node at a nonzero gap, g~ of
//   the slave facet's nodes changes slope by the gap times their dual basis function at the
//   end (-1 and 2): the clamp spreads that over 2 w of the slave parameter (w = tol / 2), so
//   the curvature stays near 3 / (4 w) of the slope's change (the old rounding over 1e-4 gave
//   170 times more, and Newton cycled on the 200 rings at t = 0.789);
// - where an interior master node passes a slave node, the two master facets share its
//   clamped projection and still tile the slave facet: g~ of a constant gap is exact.
#include "two_blocks_2d.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace seam::contact {
namespace {

/// The weighted gaps (summed over the blocks) with the master side shifted along x by
/// `shift` and the slave side pressed 0.01 into it.
std::vector<double> gaps(const mesh::Mesh& mesh, ContactInterface& itf, double shift,
                         double lift = -0.01) {
  std::vector<double> u(mesh.x.size(), 0.0);
  for (const auto n : itf.master_nodes()) u[static_cast<std::size_t>(n) * 2] = shift;
  for (const auto n : itf.slave().mesh_nodes) u[static_cast<std::size_t>(n) * 2 + 1] = lift;
  return two_blocks_2d::gaps(itf, u);
}

/// The slave node (index into gaps()) at x in the reference configuration.
std::size_t slave_at(const mesh::Mesh& mesh, const ContactInterface& itf, double x) {
  const auto& nodes = itf.slave().mesh_nodes;
  for (std::size_t j = 0; j < nodes.size(); ++j)
    if (std::abs(mesh.x[static_cast<std::size_t>(nodes[j]) * 2] - x) < 1e-9) return j;
  ADD_FAILURE() << "no slave node at x = " << x;
  return 0;
}

TEST(GapBlockEnds, ContinuousWhereAMasterNodeLeavesTheProjectionRange) {
  const auto mesh = two_blocks_2d::mesh("gap_block_ends");
  const io::Interface c = two_blocks_2d::contact();
  ContactInterface itf(c, mesh);
  // The master node at x = 0.6 moved to b + tol (b - a) for the slave facet [a, b] =
  // [0.325, 0.52], where its projection is xi = 1 + tol: g~ on both sides of that point.
  const double a = 0.325, b = 0.52, tol = 0.05;
  const double at = b + 0.5 * tol * (b - a) - 0.6;
  const double eps = 1e-7;
  const auto g1p = gaps(mesh, itf, at + eps), g1m = gaps(mesh, itf, at - eps);
  const auto g2p = gaps(mesh, itf, at + 2 * eps), g2m = gaps(mesh, itf, at - 2 * eps);
  // Continuous: the differences over 2 eps and 4 eps agree to O(eps^2) (a jump J makes them
  // differ by J / 2).
  double worst = 0.0, scale = 0.0;
  for (std::size_t j = 0; j < g1p.size(); ++j) {
    worst = std::max(worst, std::abs((g1p[j] - g1m[j]) - 0.5 * (g2p[j] - g2m[j])));
    scale = std::max(scale, std::abs(g1p[j]));
  }
  std::printf("  largest jump of g~ where a master node's projection leaves the range: %.3e "
              "(of max |g~| %.3e)\n",
              2.0 * worst, scale);
  EXPECT_GT(scale, 1e-3);
  EXPECT_LT(2.0 * worst, 1e-11 * scale);
}

TEST(GapBlockEnds, CurvatureBoundedWhereTheMasterSideEndsAtASlaveEndNode) {
  const auto mesh = two_blocks_2d::mesh("gap_block_kink");
  const io::Interface c = two_blocks_2d::contact();
  ContactInterface itf(c, mesh);
  // The slave side 0.05 above the master; the master's last node (x = 1) shifted across the
  // slave's last node (x = 0.91, the end of the slave facet [0.715, 0.91]) at shift -0.09.
  const double gap = 0.05, length = 0.195, kink = -0.09, w = 0.025;
  const std::size_t inner = slave_at(mesh, itf, 0.715), end = slave_at(mesh, itf, 0.91);
  const double h = 2e-6;
  const int n = 2500; // shifts kink -+ n h: -+ 5e-3, about twice the rounding's half width
  std::vector<std::vector<double>> g;
  for (int k = -n - 1; k <= n + 1; ++k) g.push_back(gaps(mesh, itf, kink + k * h, gap));
  double curvature[2] = {0.0, 0.0};
  const std::size_t nodes[2] = {inner, end};
  for (int i = 0; i < 2; ++i)
    for (std::size_t k = 1; k + 1 < g.size(); ++k)
      curvature[i] = std::max(
          curvature[i],
          std::abs(g[k + 1][nodes[i]] - 2 * g[k][nodes[i]] + g[k - 1][nodes[i]]) / (h * h));
  // The slopes on both sides (beyond the rounding) differ by gap * Phi_j(1) * (2 / length) *
  // (length / 2): -1 * gap for the facet's other node, 2 * gap for the end node.
  const auto slope = [&](std::size_t k, std::size_t j) {
    return (g[k + 1][j] - g[k - 1][j]) / (2 * h);
  };
  const std::size_t last = g.size() - 2;
  const double change[2] = {slope(last, inner) - slope(1, inner), slope(last, end) - slope(1, end)};
  std::printf("  master side's end across the slave end node at gap %.2f: slope change of g~ %.4e "
              "(node 0.715), %.4e (node 0.91); largest |d2 g~ / ds2| %.3e, %.3e\n",
              gap, change[0], change[1], curvature[0], curvature[1]);
  // The slope is gap * Phi_j(e) (e the master end's projection, 1 + (s - kink) / (length /
  // 2) on the facet); at the start of the sweep Phi = (1 - 3 e) / 2, (1 + 3 e) / 2; beyond
  // the kink 0 (the facet is covered).
  const double e = 1.0 - n * h / (0.5 * length);
  EXPECT_NEAR(change[0], -gap * 0.5 * (1.0 - 3.0 * e), 1e-8);
  EXPECT_NEAR(change[1], -gap * 0.5 * (1.0 + 3.0 * e), 1e-8);
  // The rounding's curvature bound: slope change * 3 / (4 w) per unit of xi, 2 / length per
  // unit of shift; 1.25 for the nonlinear parts.
  for (int i = 0; i < 2; ++i)
    EXPECT_LT(curvature[i], 1.25 * std::abs(change[i]) * 0.75 / w * 2.0 / length);
}

TEST(GapBlockEnds, MasterFacetsStillTileTheSlaveWhereAnInnerMasterNodePassesASlaveNode) {
  const auto mesh = two_blocks_2d::mesh("gap_block_tiling");
  const io::Interface c = two_blocks_2d::contact();
  ContactInterface itf(c, mesh);
  // The master node at x = 0.6 near the slave node at x = 0.52 (shift -0.08), within the
  // clamp's rounding of the ends of both slave facets there, at a constant gap 0.05: g~_j is
  // 0.05 times the integral of the dual basis function (0.195 at inner nodes, half at the
  // ends), as with the master node 0.03 away (beyond the rounding).
  const double gap = 0.05;
  const auto far = gaps(mesh, itf, -0.05, gap);
  double worst = 0.0, consistency = 0.0;
  for (std::size_t j = 0; j < far.size(); ++j) {
    const double x = mesh.x[static_cast<std::size_t>(itf.slave().mesh_nodes[j]) * 2];
    const double weight = std::abs(x - 0.13) < 1e-9 || std::abs(x - 0.91) < 1e-9 ? 0.0975 : 0.195;
    consistency = std::max(consistency, std::abs(far[j] - gap * weight));
  }
  for (const double d : {0.0, 3e-4, -3e-4, 1e-3, -1e-3, 2e-3, -2e-3}) {
    const auto g = gaps(mesh, itf, -0.08 + d, gap);
    for (std::size_t j = 0; j < g.size(); ++j) worst = std::max(worst, std::abs(g[j] - far[j]));
  }
  std::printf("  g~ of a constant gap with a master node at a slave node: %.3e from the one with "
              "the node 0.03 away (%.3e from gap * D_jj, the mesh's coordinates)\n",
              worst, consistency);
  EXPECT_LT(worst, 1e-16);
  EXPECT_LT(consistency, 1e-13);
}

} // namespace
} // namespace seam::contact
