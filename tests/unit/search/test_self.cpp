// Self contact: a folded strip and a buckled ring find their touching parts and never pair
// adjacent facets; a smooth closed surface finds nothing; the pruned traversal equals brute force.
#include "seam/search/interface_search.hpp"
#include "seam/search/traversal.hpp"
#include "surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>

using namespace seam::search;
using seam::search::test::Mesh;

namespace {

TreeOptions self_options(double inflation, int leaf_size = 4) {
  TreeOptions o;
  o.inflation = inflation;
  o.normal_cones = true;
  o.leaf_size = leaf_size;
  return o;
}

bool share_node(const Mesh& m, seam::local_index f, seam::local_index g) {
  for (auto i = m.offsets[f]; i < m.offsets[f + 1]; ++i)
    for (auto j = m.offsets[g]; j < m.offsets[g + 1]; ++j)
      if (m.conn[i] == m.conn[j]) return true;
  return false;
}

std::vector<CandidatePair> sorted_self_pairs(const Tree& t, const SelfContactOptions& o = {}) {
  auto p = find_self_pairs(t, o);
  std::sort(p.begin(), p.end());
  return p;
}

// Folded strip geometry shared by the tests below.
constexpr int n_leg = 40, n_bend = 12, n_w = 8;
constexpr double leg = 1.0, radius = 0.05, width = 0.2, inflation = 0.06; // gap 0.1 < 2 * 0.06

enum class Part { lower, bend, upper };
Part part_of(seam::local_index f) {
  const int seg = f / n_w;
  if (seg < n_leg) return Part::lower;
  if (seg < n_leg + n_bend) return Part::bend;
  return Part::upper;
}

} // namespace

TEST(SelfContact, FoldedStripFindsTheFacingLegs) {
  for (int leaf : {1, 4}) {
    const Mesh m = test::folded_strip(leg, radius, width, n_leg, n_bend, n_w);
    const Tree t(m.view(), self_options(inflation, leaf));
    const auto pairs = sorted_self_pairs(t);
    const std::set<CandidatePair> found(pairs.begin(), pairs.end());
    // Lower segment i lies exactly below upper segment 2 n_leg + n_bend - 1 - i, same column:
    // the gap 2 r is below twice the inflation, so every such pair must be found.
    for (int i = 0; i < n_leg; ++i)
      for (int j = 0; j < n_w; ++j) {
        const seam::local_index lower = i * n_w + j, upper = (2 * n_leg + n_bend - 1 - i) * n_w + j;
        EXPECT_TRUE(found.count({lower, upper})) << "segment " << i << " column " << j;
      }
    for (const auto& p : pairs) {
      EXPECT_LT(p.slave, p.master);
      EXPECT_FALSE(share_node(m, p.slave, p.master)) << p.slave << " " << p.master;
      // Facets of one flat leg have parallel normals: never candidates.
      EXPECT_FALSE(part_of(p.slave) == Part::lower && part_of(p.master) == Part::lower);
      EXPECT_FALSE(part_of(p.slave) == Part::upper && part_of(p.master) == Part::upper);
    }
    EXPECT_TRUE(pairs == find_self_pairs_brute_force(t));
    // Without the normal test the legs pair with themselves too, but still never adjacent facets.
    const SelfContactOptions no_cones{0.0};
    const auto all = sorted_self_pairs(t, no_cones);
    EXPECT_GT(all.size(), pairs.size());
    EXPECT_TRUE(std::includes(all.begin(), all.end(), pairs.begin(), pairs.end()));
    for (const auto& p : all) EXPECT_FALSE(share_node(m, p.slave, p.master));
    EXPECT_TRUE(all == find_self_pairs_brute_force(t, no_cones));
  }
}

TEST(SelfContact, FoldedStripOpeningLosesTheContact) {
  // Refit after unfolding the upper leg upwards by 0.2: the legs no longer face within reach.
  Mesh m = test::folded_strip(leg, radius, width, n_leg, n_bend, n_w);
  Tree t(m.view(), self_options(inflation));
  for (std::size_t i = 2; i < m.coords.size(); i += 3)
    if (m.coords[i] > 0.9 * radius) m.coords[i] += 0.2;
  t.update(m.coords);
  for (const auto& p : find_self_pairs(t))
    EXPECT_FALSE(part_of(p.slave) == Part::lower && part_of(p.master) == Part::upper);
  EXPECT_TRUE(sorted_self_pairs(t) == find_self_pairs_brute_force(t));
}

TEST(SelfContact, RolesAlternateAcrossTheFold) {
  const Mesh m = test::folded_strip(leg, radius, width, n_leg, n_bend, n_w);
  const Tree t(m.view(), self_options(inflation));
  const auto oriented = assign_roles(t, find_self_pairs(t));
  // Leg-to-leg pairs: the slave is always on the same leg.
  int lower_slaves = 0, upper_slaves = 0;
  for (const auto& p : oriented) {
    if (part_of(p.slave) == Part::bend || part_of(p.master) == Part::bend) continue;
    ASSERT_NE(part_of(p.slave), part_of(p.master));
    (part_of(p.slave) == Part::lower ? lower_slaves : upper_slaves)++;
  }
  EXPECT_GT(lower_slaves + upper_slaves, n_leg * n_w);
  EXPECT_TRUE(lower_slaves == 0 || upper_slaves == 0) << lower_slaves << " " << upper_slaves;
}

TEST(SelfContact, BuckledRingFindsTheDentTouchingTheBottom) {
  const int n = 600;
  const Mesh m = test::buckled_ring(1.0, 0.02, 0.35, n);
  for (int leaf : {1, 4}) {
    const Tree t(m.view(), self_options(0.015, leaf)); // gap 0.02 < 2 * 0.015
    const auto pairs = sorted_self_pairs(t);
    const std::set<CandidatePair> found(pairs.begin(), pairs.end());
    // Node n/4 is the bottom (0, -1), node 3n/4 the dent's lowest point (0, -0.98).
    for (int a : {n / 4 - 1, n / 4})
      for (int b : {3 * n / 4 - 1, 3 * n / 4}) EXPECT_TRUE(found.count({a, b})) << a << " " << b;
    for (const auto& p : pairs) {
      EXPECT_FALSE(share_node(m, p.slave, p.master));
      // Facets 0 .. n/2 - 1 form the lower half (circle), n/2 .. n - 1 the dented upper half:
      // the only contact is between the two.
      EXPECT_LT(p.slave, n / 2);
      EXPECT_GE(p.master, n / 2);
    }
    EXPECT_TRUE(pairs == find_self_pairs_brute_force(t));
  }
}

TEST(SelfContact, SmoothSphereHasNoSelfContact) {
  const Mesh m = test::sphere(24, 48);
  const Tree t(m.view(), self_options(0.3 * min_edge_length(m.view())));
  EXPECT_TRUE(find_self_pairs(t).empty());
  // Without the normal test, nearby non-adjacent facets would be reported.
  const SelfContactOptions no_cones{0.0};
  const auto all = sorted_self_pairs(t, no_cones);
  EXPECT_FALSE(all.empty());
  EXPECT_TRUE(all == find_self_pairs_brute_force(t, no_cones));
}

TEST(SelfContact, MultiBodyPairsOnlyBetweenNearbyBodies) {
  const Mesh a = test::wavy_surface(12, 12, 0.0, 0.0, 0.0);
  const Mesh b = test::wavy_surface(9, 10, 0.02, 0.0, 0.01);
  const Mesh c = test::wavy_surface(8, 8, 5.0, 0.0, 0.0);
  const Mesh strip = test::folded_strip(leg, radius, width, n_leg, n_bend, n_w);
  std::vector<Tree> bodies;
  for (const Mesh* m : {&a, &b, &c}) bodies.emplace_back(m->view(), self_options(0.015));
  // The strip sits far away at z = 10.
  Mesh lifted = strip;
  for (std::size_t i = 2; i < lifted.coords.size(); i += 3) lifted.coords[i] += 10.0;
  bodies.emplace_back(lifted.view(), self_options(inflation));
  const auto pairs = find_body_pairs(bodies, true);
  std::size_t n01 = 0, n33 = 0;
  for (const auto& p : pairs) {
    const bool ok = (p.body_a == 0 && p.body_b == 1) || (p.body_a == 3 && p.body_b == 3);
    EXPECT_TRUE(ok) << p.body_a << " " << p.body_b;
    n01 += p.body_a == 0 && p.body_b == 1;
    n33 += p.body_a == 3;
  }
  EXPECT_EQ(n01, find_pairs_brute_force(bodies[0], bodies[1]).size());
  EXPECT_EQ(n33, find_self_pairs_brute_force(bodies[3]).size());
  EXPECT_GT(n01, 0u);
  EXPECT_GT(n33, 0u);
  // Without self contact only the body pairs remain.
  EXPECT_EQ(find_body_pairs(bodies, false).size(), n01);
}
