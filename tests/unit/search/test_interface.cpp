// InterfaceSearch: the inflation rule, motion over the step, and the slave/master API.
#include "seam/search/interface_search.hpp"
#include "surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

using namespace seam::search;
using seam::search::test::Mesh;

TEST(InterfaceSearch, AnAbsoluteInflationReplacesTheFactor) {
  // A rank's part of a distributed interface passes the inflation of the whole surfaces.
  const Mesh slave = test::wavy_surface(10, 10, 0.0, 0.0, 0.0);
  const Mesh master = test::wavy_surface(7, 9, 0.07, 0.0, 0.013);
  SearchOptions opt;
  opt.inflation = 0.04; // the factor alone would give 0.03: no pair across the gap 0.07
  InterfaceSearch s(slave.view(), master.view(), opt);
  EXPECT_EQ(s.inflation(), 0.04);
  EXPECT_GT(s.find_pairs().size(), 0u);
  opt.inflation = -1.0;
  InterfaceSearch f(slave.view(), master.view(), opt);
  EXPECT_NEAR(f.inflation(), 0.03, 1e-15);
  EXPECT_EQ(f.find_pairs().size(), 0u);
}

TEST(InterfaceSearch, FlatPlatesPairIffTheGapIsBelowTwiceTheInflation) {
  // Slave: z = 0, 10 x 10 cells; master z = gap, 7 x 9 cells. Shortest edge 1/10, so with
  // factor 0.3 the inflation is 0.03 and the volumes meet across the gap iff gap <= 0.06.
  const Mesh slave = test::wavy_surface(10, 10, 0.0, 0.0, 0.0);
  for (auto volume : {BoundingVolume::kdop, BoundingVolume::aabb}) {
    SearchOptions opt;
    opt.volume = volume;
    opt.inflation_factor = 0.3;
    const Mesh touching = test::wavy_surface(7, 9, 0.0599, 0.0, 0.013);
    InterfaceSearch near(slave.view(), touching.view(), opt);
    EXPECT_NEAR(near.inflation(), 0.03, 1e-15);
    const auto& pairs = near.find_pairs();
    EXPECT_GT(pairs.size(), 0u);
    // Each slave facet whose centroid lies over the master grid is paired with a facet of the
    // master cell right above it.
    for (seam::local_index f = 0; f < slave.view().n_facets(); ++f) {
      double cx = 0, cy = 0;
      for (int k = 0; k < 3; ++k) {
        cx += slave.coords[3 * slave.conn[3 * f + k]] / 3;
        cy += slave.coords[3 * slave.conn[3 * f + k] + 1] / 3;
      }
      const int i = static_cast<int>(std::floor((cx - 0.013) * 7));
      const int j = static_cast<int>(std::floor((cy - 0.013) * 9));
      if (i < 0 || j < 0 || i >= 7 || j >= 9) continue;
      const seam::local_index cell = j * 7 + i;
      const bool hit = std::any_of(pairs.begin(), pairs.end(), [&](const CandidatePair& p) {
        return p.slave == f && (p.master == 2 * cell || p.master == 2 * cell + 1);
      });
      EXPECT_TRUE(hit) << "slave facet " << f;
    }
    const Mesh apart = test::wavy_surface(7, 9, 0.0601, 0.0, 0.013);
    InterfaceSearch far(slave.view(), apart.view(), opt);
    EXPECT_TRUE(far.find_pairs().empty());
  }
}

TEST(InterfaceSearch, MotionOverTheStepIsCovered) {
  // The master was touching at the step start (z = 0.01) and is now far away (z = 0.5): with
  // the step-start positions every overlap of the start is still reported, without none.
  const Mesh slave = test::wavy_surface(8, 8, 0.0, 0.0, 0.0);
  const Mesh start = test::wavy_surface(6, 6, 0.01, 0.0, 0.0);
  Mesh now = start;
  for (std::size_t i = 2; i < now.coords.size(); i += 3) now.coords[i] = 0.5;
  InterfaceSearch search(slave.view(), start.view());
  const auto at_start = search.find_pairs();
  ASSERT_GT(at_start.size(), 0u);
  search.update(slave.coords, now.coords);
  EXPECT_TRUE(search.find_pairs().empty());
  search.update(slave.coords, now.coords, {}, start.coords);
  auto swept = search.find_pairs();
  std::sort(swept.begin(), swept.end());
  auto expected = at_start;
  std::sort(expected.begin(), expected.end());
  EXPECT_TRUE(std::includes(swept.begin(), swept.end(), expected.begin(), expected.end()));
}

TEST(InterfaceSearch, NewtonIterationsRefitWithoutRebuilding) {
  const Mesh slave = test::wavy_surface(20, 20, 0.0, 0.05, 0.0);
  Mesh master = test::wavy_surface(15, 15, 0.005, 0.05, 0.002);
  InterfaceSearch search(slave.view(), master.view());
  for (int it = 0; it < 5; ++it) {
    for (std::size_t i = 0; i < master.coords.size(); i += 3) master.coords[i] += 0.002;
    search.update(slave.coords, master.coords);
    auto pairs = search.find_pairs();
    std::sort(pairs.begin(), pairs.end());
    EXPECT_TRUE(pairs == find_pairs_brute_force(search.slave_tree(), search.master_tree()));
  }
  EXPECT_EQ(search.master_tree().n_rebuilds(), 0);
}
