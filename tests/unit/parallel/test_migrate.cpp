// Migration of facets to new owners: every facet arrives once, with its nodes and coordinates.
#include "parallel_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/parallel/surface_part.hpp"

#include <gtest/gtest.h>

namespace seam::parallel::test {
namespace {

TEST(Migrate, FacetsArriveWithTheirNodesAndCoordinates) {
  for (bool quads : {false, true}) {
    const Mesh mesh = search::test::wavy_surface(9, 7, 0.0, 0.2, 0.0, quads);
    const SurfacePart part = round_robin_part(mesh);
    std::vector<int> dest(part.n_facets());
    for (local_index f = 0; f < part.n_facets(); ++f)
      dest[f] = static_cast<int>((part.facet_ids[f] * 7 + 3) % size());
    ExchangeStats stats;
    const SurfacePart got = migrate(world(), part, dest, &stats);

    // Exactly the facets destined here, in id order, each with the nodes of the whole mesh.
    std::vector<global_index> expected;
    const auto n_facets = static_cast<global_index>(mesh.offsets.size() - 1);
    for (global_index f = 0; f < n_facets; ++f)
      if ((f * 7 + 3) % size() == rank()) expected.push_back(f);
    EXPECT_EQ(got.facet_ids, expected);
    ASSERT_EQ(got.offsets.size(), expected.size() + 1);
    for (local_index f = 0; f < got.n_facets(); ++f) {
      const global_index g = got.facet_ids[f];
      ASSERT_EQ(got.offsets[f + 1] - got.offsets[f], mesh.offsets[g + 1] - mesh.offsets[g]);
      for (local_index k = 0; k < got.offsets[f + 1] - got.offsets[f]; ++k) {
        const local_index n = got.connectivity[got.offsets[f] + k];
        const global_index node = mesh.conn[mesh.offsets[g] + k];
        EXPECT_EQ(got.node_ids[n], node);
        for (int d = 0; d < 3; ++d) EXPECT_EQ(got.coords[n * 3 + d], mesh.coords[node * 3 + d]);
      }
    }
    // Nodes are kept once each.
    EXPECT_TRUE(std::is_sorted(got.node_ids.begin(), got.node_ids.end()));
    EXPECT_EQ(std::adjacent_find(got.node_ids.begin(), got.node_ids.end()), got.node_ids.end());

    // Counts: facets sent elsewhere, summed, equal those that changed rank.
    std::int64_t sent = stats.facets_sent, moved = 0;
    for (local_index f = 0; f < part.n_facets(); ++f) moved += dest[f] != rank();
    MPI_Allreduce(MPI_IN_PLACE, &sent, 1, MPI_INT64_T, MPI_SUM, world());
    MPI_Allreduce(MPI_IN_PLACE, &moved, 1, MPI_INT64_T, MPI_SUM, world());
    EXPECT_EQ(sent, moved);
    EXPECT_EQ(stats.facets_received, got.n_facets());
    // Per facet: id, count, and per node its id and 3 coordinates, 8 bytes each.
    if (size() == 1) {
      EXPECT_EQ(stats.bytes_sent, 0);
    }
  }
}

TEST(Migrate, ABadDestinationOnOneRankThrowsOnEveryRank) {
  const Mesh mesh = search::test::wavy_surface(4, 4, 0.0, 0.0, 0.0);
  const SurfacePart part = round_robin_part(mesh);
  std::vector<int> dest(part.n_facets(), rank());
  if (rank() == size() - 1 && !dest.empty()) dest[0] = size(); // no such rank
  EXPECT_THROW(migrate(world(), part, dest), InputError);
  dest.assign(part.n_facets(), 0);
  EXPECT_EQ(migrate(world(), part, dest).n_facets(), rank() == 0 ? 32 : 0);
}

TEST(Migrate, AnEmptyPartTakesTheDimensionOfTheOthers) {
  // Rank 0 holds a default (3D, empty) part; the others hold segments of a 2D polyline.
  const Mesh mesh = search::test::wavy_polyline(12, 0.0, 0.1, 0.0);
  const SurfacePart part = rank() == 0 ? SurfacePart{} : round_robin_part(mesh);
  const SurfacePart got = migrate(world(), part, std::vector<int>(part.n_facets(), 0));
  if (rank() == 0 && size() > 1) {
    EXPECT_EQ(got.dim, 2);
    EXPECT_EQ(got.n_facets(), 12 - (12 + size() - 1) / size());
    EXPECT_EQ(got.coords.size(), 2 * got.node_ids.size());
  }
}

TEST(Migrate, CentroidsAreTheMeanOfTheNodes) {
  const Mesh mesh = search::test::wavy_polyline(10, 1.0, 0.0, 0.0);
  const SurfacePart part =
      extract_part(2, mesh.coords, mesh.offsets, mesh.conn, std::vector<local_index>{3, 7});
  std::vector<double> c;
  facet_centroids(part, c);
  ASSERT_EQ(c.size(), 4u);
  EXPECT_DOUBLE_EQ(c[0], 0.35);
  EXPECT_DOUBLE_EQ(c[1], 1.0);
  EXPECT_DOUBLE_EQ(c[2], 0.75);
}

} // namespace
} // namespace seam::parallel::test
