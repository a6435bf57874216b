// METIS cell partitions (range, balance, determinism) and the per-part node numbering
// (bijection, contiguity, owner rule), checked by brute force.
#include "mesh_test_support.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/mesh/partition.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <climits>

namespace seam::mesh {
namespace {

// Brute-force check of the numbering rules against the definition.
void check_numbering(const Mesh& mesh, const std::vector<int>& part, int n_parts) {
  const auto numbering = number_nodes(mesh, part, n_parts);
  const auto n = static_cast<std::size_t>(mesh.n_nodes());
  ASSERT_EQ(numbering.owner.size(), n);
  ASSERT_EQ(numbering.new_index.size(), n);
  ASSERT_EQ(numbering.offsets.size(), static_cast<std::size_t>(n_parts) + 1);
  EXPECT_EQ(numbering.offsets.front(), 0);
  EXPECT_EQ(numbering.offsets.back(), static_cast<std::int64_t>(n));

  // Owner = smallest part among the cells touching the node.
  std::vector<int> owner(n, INT_MAX);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (auto node : mesh.cell(c))
      owner[static_cast<std::size_t>(node)] =
          std::min(owner[static_cast<std::size_t>(node)], part[static_cast<std::size_t>(c)]);
  EXPECT_EQ(numbering.owner, owner);

  // A bijection onto [0, n), each node inside its owner's range, increasing with the old index
  // within a part, and old_index its inverse.
  std::vector<char> hit(n, 0);
  for (std::size_t i = 0; i < n; ++i) {
    const auto g = numbering.new_index[i];
    ASSERT_GE(g, 0);
    ASSERT_LT(g, static_cast<std::int64_t>(n));
    EXPECT_EQ(hit[static_cast<std::size_t>(g)], 0) << "index " << g << " used twice";
    hit[static_cast<std::size_t>(g)] = 1;
    const auto p = static_cast<std::size_t>(owner[i]);
    EXPECT_GE(g, numbering.offsets[p]);
    EXPECT_LT(g, numbering.offsets[p + 1]);
    EXPECT_EQ(numbering.old_index[static_cast<std::size_t>(g)], static_cast<std::int32_t>(i));
  }
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i + 1; j < n; ++j)
      if (owner[i] == owner[j] && numbering.new_index[i] >= numbering.new_index[j])
        FAIL() << "nodes " << i << " < " << j << " of part " << owner[i] << " out of order";
  for (int p = 0; p < n_parts; ++p)
    EXPECT_EQ(numbering.offsets[static_cast<std::size_t>(p) + 1] -
                  numbering.offsets[static_cast<std::size_t>(p)],
              std::count(owner.begin(), owner.end(), p));
}

class Partition : public ::testing::Test {
protected:
  static void SetUpTestSuite() {
    test::ScratchDir dir("partition_setup");
    ReadOptions o;
    o.order = 1;
    cube_ = new Mesh(read_mesh(dir.write("cube.geo", test::unit_cube_geo(10)), o));
    o.order = 2;
    o.size = 0.15;
    square_ = new Mesh(read_mesh(dir.write("square.geo", test::unit_square_geo(0, false)), o));
  }
  static void TearDownTestSuite() {
    delete cube_;
    delete square_;
  }
  static Mesh* cube_;
  static Mesh* square_;
};
Mesh* Partition::cube_ = nullptr;
Mesh* Partition::square_ = nullptr;

TEST_F(Partition, BalancedDeterministicInRange) {
  const Mesh& mesh = *cube_;
  ASSERT_EQ(mesh.n_cells(), 1000);
  const int n_parts = 3;
  const auto part = partition_cells(mesh, n_parts);
  ASSERT_EQ(part.size(), 1000u);
  std::vector<int> count(n_parts, 0);
  for (int p : part) {
    ASSERT_GE(p, 0);
    ASSERT_LT(p, n_parts);
    ++count[static_cast<std::size_t>(p)];
  }
  for (int c : count) EXPECT_LE(std::abs(c - 1000.0 / n_parts), 0.1 * 1000.0 / n_parts) << c;
  EXPECT_EQ(partition_cells(mesh, n_parts), part);
  check_numbering(mesh, part, n_parts);
}

// The weights sum to the nodes, each counted with the nodes of its cells (partition.hpp):
// 8 per node of an all-hexahedral mesh.
TEST_F(Partition, CellWeightsCountNodes) {
  const Mesh& mesh = *cube_;
  std::vector<int> around(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (auto n : mesh.cell(c)) ++around[n];
  double total = 0.0;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    double shares = 0.0;
    for (auto n : mesh.cell(c)) shares += 1.0 / around[n];
    total += cell_weight(static_cast<int>(mesh.cell(c).size()), shares);
  }
  EXPECT_NEAR(total, 8.0 * mesh.n_nodes(), 1e-9 * total);
  EXPECT_EQ(integer_weight(8.0, 1e3), 128);
  EXPECT_EQ(integer_weight(1e-3, 1e3), 1);
  EXPECT_EQ(integer_weight(800.0, 16.0 * 0x1p30), 50); // scaled to keep the sum below 2^30
}

// Hexahedra beside tetrahedra (about 5.5 tetrahedra per node): the weighted partition
// balances the parts' nodes, each counted with the nodes of its cells (8 for a hexahedron's,
// 4 for a tetrahedron's: the length of its matrix rows), so the part with the tetrahedra has
// several times the cells. Partitioned by cell count, the cells would be balanced and the
// part of hexahedra would have about three times the nodes of the other.
TEST_F(Partition, MixedHexTetBalancesNodes) {
  test::ScratchDir dir("partition_mixed");
  const std::string geo = "SetFactory(\"OpenCASCADE\");\n"
                          "Box(1) = {0, 0, 0, 1, 1, 1};\n"
                          "Box(2) = {1, 0, 0, 1, 1, 1};\n"
                          "Transfinite Curve{1:12} = 9;\n"
                          "Transfinite Surface{1:6};\n"
                          "Recombine Surface{1:6};\n"
                          "Transfinite Volume{1};\n"
                          "MeshSize{PointsOf{Volume{2};}} = 0.12;\n"
                          "Physical Volume(\"hex\") = {1};\n"
                          "Physical Volume(\"tet\") = {2};\n";
  ReadOptions o;
  o.order = 1;
  const Mesh mesh = read_mesh(dir.write("mixed.geo", geo), o);
  const int n_parts = 2;
  const auto part = partition_cells(mesh, n_parts);
  std::vector<std::vector<char>> held(n_parts, std::vector<char>(mesh.n_nodes(), 0));
  std::vector<int> cells(n_parts, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    ++cells[part[c]];
    for (auto n : mesh.cell(c)) held[part[c]][n] = 1;
  }
  // Each node counted with the mean node count of its cells.
  std::vector<double> sum(static_cast<std::size_t>(mesh.n_nodes()), 0.0), around(sum);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (auto n : mesh.cell(c)) {
      sum[n] += static_cast<double>(mesh.cell(c).size());
      around[n] += 1.0;
    }
  std::vector<double> nodes(n_parts, 0.0);
  for (int p = 0; p < n_parts; ++p)
    for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
      if (held[p][n]) nodes[p] += sum[n] / around[n];
  const auto [lo, hi] = std::minmax_element(nodes.begin(), nodes.end());
  EXPECT_LE(*hi / *lo, 1.15) << nodes[0] << " and " << nodes[1] << " weighted nodes";
  const auto [cl, ch] = std::minmax_element(cells.begin(), cells.end());
  EXPECT_GE(static_cast<double>(*ch) / *cl, 2.0) << cells[0] << " and " << cells[1] << " cells";
  check_numbering(mesh, part, n_parts);
}

TEST_F(Partition, QuadraticTrianglesSeveralPartCounts) {
  const Mesh& mesh = *square_;
  for (int n_parts : {1, 2, 4, 7}) {
    const auto part = partition_cells(mesh, n_parts);
    ASSERT_EQ(part.size(), static_cast<std::size_t>(mesh.n_cells()));
    std::vector<int> count(static_cast<std::size_t>(n_parts), 0);
    for (int p : part) ++count[static_cast<std::size_t>(p)];
    for (int c : count) EXPECT_GT(c, 0) << n_parts << " parts";
    check_numbering(mesh, part, n_parts);
  }
}

TEST_F(Partition, OnePartIsTrivial) {
  const auto part = partition_cells(*cube_, 1);
  EXPECT_TRUE(std::all_of(part.begin(), part.end(), [](int p) { return p == 0; }));
  const auto numbering = number_nodes(*cube_, part, 1);
  for (std::int32_t n = 0; n < cube_->n_nodes(); ++n)
    EXPECT_EQ(numbering.new_index[static_cast<std::size_t>(n)], n);
}

TEST_F(Partition, BadArguments) {
  EXPECT_THROW((void)partition_cells(*cube_, 0), InputError);
  EXPECT_THROW((void)partition_cells(*cube_, 1001), InputError);
  std::vector<int> part(static_cast<std::size_t>(cube_->n_cells()), 0);
  part[5] = 3;
  EXPECT_THROW((void)number_nodes(*cube_, part, 3), InputError);
  part.pop_back();
  EXPECT_THROW((void)number_nodes(*cube_, part, 3), InputError);
}

} // namespace
} // namespace seam::mesh
