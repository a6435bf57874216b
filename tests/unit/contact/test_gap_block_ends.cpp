// The weighted gaps of the energy-momentum contact (gap_blocks) are continuous where a master
// end node's projection onto a slave facet leaves the range the segmentation accepts, xi = 1 +
// tol (tol = projection_range_tolerance = 0.05). There the overlap segment's end switches from
// the node's projection (clamped to the slave facet with rounded corners) to the slave's end
// node. The rounded clamp of a projection just inside the range is within smoothing^2 / (4 tol)
// (5e-8) of 1, so the slave end must be 1 exactly: clamped too, it sat at 1 - smoothing / 2 and
// g~ jumped by the integrand over half the smoothing width (the 200 rings of examples/rings:
// Newton stalled at a residual of 4e-2 for 30 iterations at t = 0.645, docs/contact_dynamics.md
// "Diagnosing a stalled Newton step").
#include "seam/contact/contact_interface.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

namespace seam::contact {
namespace {

// A lower block whose top (master) has facets 0.2 long at x = 0, 0.2, ..., 1 and an upper
// block whose bottom (slave) has facets 0.195 long at x = 0.13, 0.325, 0.52, 0.715, 0.91.
constexpr const char* geo = R"(
Point(1) = {0, -0.5, 0}; Point(2) = {1, -0.5, 0}; Point(3) = {1, 0, 0}; Point(4) = {0, 0, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Transfinite Curve{1, 3} = 6; Transfinite Curve{2, 4} = 3; Transfinite Surface{1}; Recombine Surface{1};
Point(5) = {0.13, 0, 0}; Point(6) = {0.91, 0, 0}; Point(7) = {0.91, 0.4, 0}; Point(8) = {0.13, 0.4, 0};
Line(5) = {5, 6}; Line(6) = {6, 7}; Line(7) = {7, 8}; Line(8) = {8, 5};
Curve Loop(2) = {5, 6, 7, 8}; Plane Surface(2) = {2};
Transfinite Curve{5, 7} = 5; Transfinite Curve{6, 8} = 3; Transfinite Surface{2}; Recombine Surface{2};
Physical Surface("lower") = {1}; Physical Surface("upper") = {2};
Physical Curve("master") = {3}; Physical Curve("slave") = {5};
)";

/// The weighted gaps (summed over the blocks) with the master side shifted along x by
/// `shift` and the slave side pressed 0.01 into it.
std::vector<double> gaps(const mesh::Mesh& mesh, ContactInterface& itf, double shift) {
  std::vector<double> u(mesh.x.size(), 0.0);
  for (const auto n : itf.master_nodes()) u[static_cast<std::size_t>(n) * 2] = shift;
  for (const auto n : itf.slave().mesh_nodes) u[static_cast<std::size_t>(n) * 2 + 1] = -0.01;
  itf.update(u, 0.0);
  std::vector<GapBlock> blocks;
  itf.gap_blocks(u, GapOrder::value, blocks);
  std::vector<double> g(static_cast<std::size_t>(itf.n_slave_nodes()), 0.0);
  for (const auto& b : blocks)
    for (std::size_t r = 0; r < b.slave.size(); ++r)
      g[static_cast<std::size_t>(b.slave[r])] += b.gap[r];
  return g;
}

TEST(GapBlockEnds, ContinuousWhereAMasterNodeLeavesTheProjectionRange) {
  const auto path = std::filesystem::temp_directory_path() / "gap_block_ends.geo";
  std::ofstream(path) << geo;
  mesh::ReadOptions options;
  options.dim = 2;
  const auto mesh = mesh::read_mesh(path, options);
  io::Interface c;
  c.multiplier = io::Multiplier::dual;
  c.name.assign("contact");
  c.type = io::InterfaceType::contact;
  c.slave.name.assign("slave");
  c.master = io::RegionRef{"master", {}};
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
