// The distributed search finds exactly the pairs of a brute-force search on the whole
// surfaces, each on the rank holding its slave facet, on random and moving surfaces.
#include "parallel_test_support.hpp"
#include "seam/parallel/distributed_search.hpp"
#include "seam/parallel/rcb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace seam::parallel::test {
namespace {

struct Case {
  const char* name;
  Mesh slave, master;
};

std::vector<Case> cases() {
  std::vector<Case> c;
  c.push_back({"random 2D", search::test::random_facets(2, 400, 0.03, 7u),
               search::test::random_facets(2, 500, 0.03, 8u)});
  c.push_back({"random 3D", search::test::random_facets(3, 500, 0.04, 9u),
               search::test::random_facets(3, 600, 0.04, 10u)});
  c.push_back({"wavy 2D", search::test::wavy_polyline(300, 0.0, 0.05, 0.0),
               search::test::wavy_polyline(230, 0.01, -0.05, 0.013)});
  c.push_back({"wavy 3D", search::test::wavy_surface(24, 20, 0.0, 0.05, 0.0),
               search::test::wavy_surface(17, 19, 0.01, -0.05, 0.021, true)});
  return c;
}

/// Slave x += 0.04 sin(2 pi y) (deformed), master translated by (0.05, 0.02, -0.01).
void move(Mesh& slave, Mesh& master) {
  for (std::size_t n = 0; n < slave.coords.size(); n += slave.dim)
    slave.coords[n] += 0.04 * std::sin(2 * std::numbers::pi * slave.coords[n + 1]);
  const double shift[3] = {0.05, 0.02, -0.01};
  for (std::size_t n = 0; n < master.coords.size(); ++n) master.coords[n] += shift[n % master.dim];
}

void expect_exact(const DistributedSearch& search, const SurfacePart& slave, const Mesh& slave_mesh,
                  const Mesh& master_mesh, const char* name) {
  // Local pairs: slave facets are this rank's.
  const auto local = search.global_pairs();
  for (const auto& p : local)
    EXPECT_TRUE(std::binary_search(slave.facet_ids.begin(), slave.facet_ids.end(), p.slave));
  std::vector<GlobalPair> all = gather_pairs(world(), local);
  const std::size_t n_found = all.size();
  std::sort(all.begin(), all.end());
  // Each pair found once: no duplicates in the union.
  EXPECT_EQ(std::adjacent_find(all.begin(), all.end()), all.end()) << name;
  const auto expected = brute_force_pairs(slave_mesh, master_mesh, search.inflation());
  EXPECT_EQ(n_found, expected.size()) << name;
  EXPECT_EQ(all, expected) << name;
  EXPECT_FALSE(expected.empty()) << name;
}

TEST(DistributedSearch, FindsExactlyTheBruteForcePairsOnRandomAndMovingSurfaces) {
  for (Case& c : cases()) {
    // Slave: RCB of a round-robin input; master: contiguous blocks of ids (as from a bulk
    // partition), not moved: the ghosting finds the masters wherever they are.
    const SurfacePart input = round_robin_part(c.slave);
    Points pts(input);
    Rcb rcb(c.slave.dim);
    rcb.partition(world(), pts.x, {}, input.facet_ids, pts.parts);
    SurfacePart slave = migrate(world(), input, pts.parts);
    SurfacePart master = block_part(c.master);

    const double inflation = global_inflation(world(), slave, master, 0.3);
    DistributedSearch search(world(), inflation);
    search.find_pairs(slave, master);
    EXPECT_TRUE(search.stats().rebuilt || search.stats().n_pairs == 0);
    expect_exact(search, slave, c.slave, c.master, c.name);

    // Same facets, moved: trees refitted where the ghost set stayed, pairs exact again.
    move(c.slave, c.master);
    refresh_coords(slave, c.slave);
    refresh_coords(master, c.master);
    search.find_pairs(slave, master);
    expect_exact(search, slave, c.slave, c.master, c.name);

    // Unchanged coordinates: the same ghosts, so the trees are refitted, not rebuilt.
    search.find_pairs(slave, master);
    EXPECT_FALSE(search.stats().rebuilt) << c.name;
    expect_exact(search, slave, c.slave, c.master, c.name);
  }
}

TEST(DistributedSearch, GlobalInflationIsThatOfTheWholeSurfaces) {
  const Mesh s = search::test::wavy_surface(13, 11, 0.0, 0.05, 0.0);
  const Mesh m = search::test::wavy_surface(9, 7, 0.01, 0.05, 0.0);
  const double whole =
      0.3 * std::min(search::min_edge_length(s.view()), search::min_edge_length(m.view()));
  EXPECT_DOUBLE_EQ(global_inflation(world(), round_robin_part(s), block_part(m), 0.3), whole);
}

} // namespace
} // namespace seam::parallel::test
