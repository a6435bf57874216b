// Master ghosting: each rank gets exactly the masters whose boxes meet its published region,
// which covers every master that any of its slave facets can pair with.
#include "parallel_test_support.hpp"
#include "seam/parallel/ghosting.hpp"
#include "seam/parallel/rcb.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

namespace seam::parallel::test {
namespace {

TEST(Ghosting, FacetBoxesAreTheAxisSlabsOfTheSearchVolumes) {
  for (int dim : {2, 3}) {
    const Mesh mesh = search::test::random_facets(dim, 200, 0.05, 3u);
    search::TreeOptions o;
    o.inflation = 0.01;
    const search::Tree tree(mesh.view(), o);
    std::vector<float> lo, hi;
    tree.facet_boxes(lo, hi);
    std::vector<Box> boxes;
    facet_boxes(mesh.view(), o.inflation, boxes);
    ASSERT_EQ(boxes.size() * dim, lo.size());
    for (std::size_t f = 0; f < boxes.size(); ++f)
      for (int d = 0; d < dim; ++d) {
        EXPECT_EQ(boxes[f].lo[d], lo[f * dim + d]);
        EXPECT_EQ(boxes[f].hi[d], hi[f * dim + d]);
      }
  }
}

TEST(Ghosting, ClustersCoverTheirBoxes) {
  const Mesh mesh = search::test::random_facets(3, 500, 0.02, 4u);
  std::vector<Box> boxes;
  facet_boxes(mesh.view(), 0.0, boxes);
  const std::vector<Box> clusters = cluster_boxes(3, boxes, 16);
  EXPECT_EQ(clusters.size(), 16u);
  for (const Box& b : boxes) {
    bool covered = false;
    for (const Box& c : clusters) {
      bool inside = true;
      for (int d = 0; d < 3; ++d) inside &= c.lo[d] <= b.lo[d] && b.hi[d] <= c.hi[d];
      covered |= inside;
    }
    EXPECT_TRUE(covered);
  }
  EXPECT_EQ(cluster_boxes(3, std::span(boxes).first(5), 16).size(), 5u);
}

// The slave part of this rank after an RCB of the round-robin input.
SurfacePart rcb_part(const Mesh& mesh) {
  const SurfacePart input = round_robin_part(mesh);
  Points pts(input);
  Rcb rcb(mesh.dim);
  rcb.partition(world(), pts.x, {}, input.facet_ids, pts.parts);
  return migrate(world(), input, pts.parts);
}

TEST(Ghosting, EachRankGetsExactlyTheMastersMeetingItsRegion) {
  for (int dim : {2, 3}) {
    const Mesh slave_mesh = search::test::random_facets(dim, 600, 0.03, 21u);
    const Mesh master_mesh = search::test::random_facets(dim, 700, 0.03, 22u);
    const SurfacePart slave = rcb_part(slave_mesh);
    const SurfacePart master = block_part(master_mesh);
    const double inflation = 0.004;

    std::vector<Box> boxes;
    facet_boxes(slave.view(), inflation, boxes);
    const std::vector<Box> region = cluster_boxes(dim, boxes, 8);
    ExchangeStats stats;
    const SurfacePart ghosts = ghost_overlapping(world(), region, master, inflation, &stats);

    // Reference from the whole master surface.
    std::vector<Box> all;
    facet_boxes(master_mesh.view(), inflation, all);
    std::vector<global_index> expected;
    for (std::size_t m = 0; m < all.size(); ++m)
      for (const Box& r : region)
        if (overlap(all[m], r, dim)) {
          expected.push_back(static_cast<global_index>(m));
          break;
        }
    EXPECT_EQ(ghosts.facet_ids, expected) << dim << "D";

    // Every master that a local slave pairs with (brute force on the whole surfaces) is here.
    const std::set<global_index> have(ghosts.facet_ids.begin(), ghosts.facet_ids.end());
    const std::set<global_index> mine(slave.facet_ids.begin(), slave.facet_ids.end());
    for (const auto& p : brute_force_pairs(slave_mesh, master_mesh, inflation))
      if (mine.count(p.slave)) {
        EXPECT_TRUE(have.count(p.master)) << p.slave << " " << p.master;
      }
    // Not the whole master surface once the slave surface is split.
    if (size() > 1) {
      EXPECT_LT(ghosts.n_facets(), static_cast<local_index>(all.size()));
    }
    EXPECT_EQ(stats.facets_received, ghosts.n_facets());
  }
}

// Every node moved by `length` in a direction of its own.
void move_nodes(Mesh& mesh, double length) {
  const auto n = mesh.coords.size() / static_cast<std::size_t>(mesh.dim);
  for (std::size_t i = 0; i < n; ++i) {
    const double a = 1.3 * static_cast<double>(i), b = 0.7 * static_cast<double>(i);
    double d[3] = {std::sin(a) * std::cos(b), std::cos(a) * std::cos(b), std::sin(b)};
    if (mesh.dim == 2) d[0] = std::sin(a), d[1] = std::cos(a);
    double norm = 0.0;
    for (int c = 0; c < mesh.dim; ++c) norm += d[c] * d[c];
    for (int c = 0; c < mesh.dim; ++c)
      mesh.coords[i * mesh.dim + c] += length * d[c] / std::sqrt(norm);
  }
}

TEST(Ghosting, VerletGhostsAreReusedWhileNodesMoveLessThanHalfTheSkin) {
  for (int dim : {2, 3}) {
    Mesh slave_mesh = search::test::random_facets(dim, 600, 0.03, 31u);
    Mesh master_mesh = search::test::random_facets(dim, 700, 0.03, 32u);
    SurfacePart slave = rcb_part(slave_mesh);
    SurfacePart master = block_part(master_mesh);
    const double inflation = 0.004, skin = 0.01;
    VerletGhosts ghosts(world(), inflation, skin);
    VerletGhosts every(world(), inflation, 0.0);
    EXPECT_TRUE(ghosts.update(slave, master, master_mesh.coords));
    // Moved by 0.45 skin: reused, at the new positions, and still holding every master a
    // local slave pairs with now (brute force on the whole moved surfaces).
    move_nodes(slave_mesh, 0.45 * skin);
    move_nodes(master_mesh, 0.45 * skin);
    refresh_coords(slave, slave_mesh);
    refresh_coords(master, master_mesh);
    EXPECT_FALSE(ghosts.update(slave, master, master_mesh.coords)) << dim << "D";
    const SurfacePart& g = ghosts.ghosts();
    for (local_index n = 0; n < g.n_nodes(); ++n)
      for (int d = 0; d < dim; ++d)
        EXPECT_EQ(g.coords[n * dim + d], master_mesh.coords[g.node_ids[n] * dim + d]);
    const std::set<global_index> have(g.facet_ids.begin(), g.facet_ids.end());
    const std::set<global_index> mine(slave.facet_ids.begin(), slave.facet_ids.end());
    std::int64_t checked = 0;
    for (const auto& p : brute_force_pairs(slave_mesh, master_mesh, inflation))
      if (mine.count(p.slave)) {
        EXPECT_TRUE(have.count(p.master)) << p.slave << " " << p.master;
        ++checked;
      }
    EXPECT_GT(checked, 0);
    // Reused again, the positions now taken by global id from a table of the ghosts' nodes
    // only (position_ids: the nodes a rank holds), not from an array over every node id.
    std::vector<global_index> ids(g.node_ids.begin(), g.node_ids.end());
    std::sort(ids.begin(), ids.end());
    ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
    std::vector<double> positions;
    for (const auto id : ids)
      for (int d = 0; d < dim; ++d)
        positions.push_back(master_mesh.coords[static_cast<std::size_t>(id) * dim + d]);
    EXPECT_FALSE(ghosts.update(slave, master, positions, ids)) << dim << "D";
    for (local_index n = 0; n < g.n_nodes(); ++n)
      for (int d = 0; d < dim; ++d)
        EXPECT_EQ(g.coords[n * dim + d], master_mesh.coords[g.node_ids[n] * dim + d]);
    // Without a skin every update exchanges.
    EXPECT_TRUE(every.update(slave, master, master_mesh.coords));
    EXPECT_TRUE(every.update(slave, master, master_mesh.coords));
    // Moved by 0.45 skin more (0.9 from the exchange, on some node more than half): exchanged.
    move_nodes(master_mesh, 0.45 * skin);
    refresh_coords(master, master_mesh);
    EXPECT_TRUE(ghosts.update(slave, master, master_mesh.coords)) << dim << "D";
    // Another slave part (a redistribution): exchanged.
    EXPECT_FALSE(ghosts.update(slave, master, master_mesh.coords));
    SurfacePart other = round_robin_part(slave_mesh);
    if (size() > 1) {
      EXPECT_TRUE(ghosts.update(other, master, master_mesh.coords));
    }
    EXPECT_EQ(ghosts.n_updates(), size() > 1 ? 6 : 5);
    EXPECT_EQ(ghosts.n_exchanges(), size() > 1 ? 3 : 2);
  }
}

} // namespace
} // namespace seam::parallel::test
