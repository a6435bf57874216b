// The weighted gaps of the energy-momentum contact (gap_blocks) are continuous where a master
// end node's projection onto a slave facet leaves the range the segmentation accepts, xi = 1 +
// tol (tol = projection_range_tolerance = 0.05). There the overlap segment's end switches from
// the node's projection (clamped to the slave facet with rounded corners) to the slave's end
// node. The rounded clamp of a projection just inside the range is within smoothing^2 / (4 tol)
// (5e-8) of 1, so the slave end must be 1 exactly: clamped too, it sat at 1 - smoothing / 2 and
// g~ jumped by the integrand over half the smoothing width (the 200 rings of examples/rings:
// Newton stalled at a residual of 4e-2 for 30 iterations at t = 0.645, docs/contact_dynamics.md
// "Diagnosing a stalled Newton step").
#include "two_blocks_2d.hpp"

#include <gtest/gtest.h>

#include <cmath>

namespace seam::contact {
namespace {

/// The weighted gaps (summed over the blocks) with the master side shifted along x by
/// `shift` and the slave side pressed 0.01 into it.
std::vector<double> gaps(const mesh::Mesh& mesh, ContactInterface& itf, double shift) {
  std::vector<double> u(mesh.x.size(), 0.0);
  for (const auto n : itf.master_nodes()) u[static_cast<std::size_t>(n) * 2] = shift;
  for (const auto n : itf.slave().mesh_nodes) u[static_cast<std::size_t>(n) * 2 + 1] = -0.01;
  return two_blocks_2d::gaps(itf, u);
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

} // namespace
} // namespace seam::contact
