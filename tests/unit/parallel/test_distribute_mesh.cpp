// The distributed mesh, checked against the whole mesh (built identically on every rank) by
// brute force: the owned cells cover the mesh exactly once, the ghosts are exactly the cells
// sharing a node with an owned cell, nodes, coordinates, regions and the global node numbering
// match the whole mesh, and no rank holds more than its cells, their ghost layer and the
// interface cells (the memory assertion).
#include "block_meshes.hpp"
#include "distribution_check.hpp"
#include "seam/common/error.hpp"

namespace seam::parallel::test {
namespace {

using mesh::distribute_mesh;

/// Distributes `g` from rank 0 and checks every rank's part (distribution_check.hpp).
void check_distribution(const mesh::Mesh& g, const std::vector<std::string>& interfaces,
                        double max_held_fraction = 1.0) {
  mesh::Mesh copy = rank() == 0 ? g : mesh::Mesh{};
  const DistributedMesh d = distribute_mesh(copy, world(), interfaces);
  EXPECT_EQ(copy.n_cells(), 0) << "rank 0 still holds the whole mesh";
  EXPECT_EQ(copy.x.size(), 0u);
  check_part(g, d, interfaces, max_held_fraction);
}

TEST(DistributeMesh, HexBlockCoveredOnceWithOneGhostLayer) {
  mesh::Mesh g;
  g.dim = 3;
  add_block(g, {6, 5, 4}, {0, 0, 0}, false, "block");
  add_point_region(g, "corner");
  check_distribution(g, {});
}

TEST(DistributeMesh, TwoBlocksWithInterfaceCellsOnEveryRank) {
  // Hexes below, tets above with their own nodes: the tied pair lower_top / upper_bottom.
  mesh::Mesh g;
  g.dim = 3;
  add_block(g, {5, 4, 3}, {0, 0, 0}, false, "lower");
  add_block(g, {3, 3, 2}, {0.5, 0.5, 3}, true, "upper");
  check_distribution(g, {"lower_top", "upper_bottom", "no_such_region"});
}

TEST(DistributeMesh, TwoDimensionalQuadsAndTriangles) {
  for (bool simplices : {false, true}) {
    mesh::Mesh g;
    g.dim = 2;
    add_block(g, {9, 7, 0}, {0, 0, 0}, simplices, "plate");
    add_point_region(g, "corner");
    check_distribution(g, {"plate_top"});
  }
}

// The memory assertion on a 3D mesh at np 3: every rank holds at most
// (its cells + ghosts) * 1.1 (checked in check_distribution) and so far less than the mesh.
TEST(DistributeMesh, NoRankHoldsTheWholeMeshAtThreeRanks) {
  if (size() != 3) GTEST_SKIP() << "runs at np 3";
  mesh::Mesh g;
  g.dim = 3;
  add_block(g, {14, 14, 14}, {0, 0, 0}, false, "cube");
  check_distribution(g, {}, 0.5);
  mesh::Mesh tets;
  tets.dim = 3;
  add_block(tets, {8, 8, 8}, {0, 0, 0}, true, "cube");
  check_distribution(tets, {}, 0.5);
}

TEST(DistributeMesh, MoreRanksThanCellsThrowsOnEveryRank) {
  mesh::Mesh g;
  g.dim = 2;
  add_block(g, {1, 1, 0}, {0, 0, 0}, false, "one");
  mesh::Mesh copy = rank() == 0 ? g : mesh::Mesh{};
  if (size() > 1) {
    EXPECT_THROW(distribute_mesh(copy, world()), InputError);
  } else {
    EXPECT_EQ(distribute_mesh(copy, world()).n_cells(), 1);
  }
}

} // namespace
} // namespace seam::parallel::test
