// Self and multi-body contact search on random and crumpled surfaces: the pruned self traversal
// finds exactly the pairs that testing all N (N - 1) / 2 facet pairs finds, 2D and 3D; the roles
// of assign_roles alternate across every pair of a bipartite contact graph, the lowest facet of
// each connected group is slave, and the result does not depend on the order of the pairs.
#include "seam/search/interface_search.hpp"
#include "seam/search/traversal.hpp"
#include "surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

using namespace seam::search;
using seam::local_index;
using seam::search::test::Mesh;

namespace {

TreeOptions cone_tree(double inflation) {
  TreeOptions o;
  o.inflation = inflation;
  o.normal_cones = true;
  return o;
}

std::vector<CandidatePair> sorted(std::vector<CandidatePair> p) {
  std::sort(p.begin(), p.end());
  return p;
}

/// A connected surface crumpled at random: a polyline (2D) or a quad grid (3D) whose nodes
/// follow a random walk, so that it folds over itself many times.
Mesh crumpled(int dim, int n, unsigned seed) {
  Mesh m;
  m.dim = dim;
  std::mt19937 gen(seed);
  std::normal_distribution<double> step(0.0, 0.05);
  if (dim == 2) {
    double x = 0.5, y = 0.5;
    for (int i = 0; i <= n; ++i) {
      m.coords.insert(m.coords.end(), {x, y});
      x += std::abs(step(gen)) * 0.3 + step(gen);
      y += step(gen);
      if (i > 0) m.add_facet({i - 1, i});
    }
    return m;
  }
  // 3D: an n x 4 strip whose centre line is a random walk; the cross direction turns slowly.
  double c[3] = {0.5, 0.5, 0.5};
  for (int i = 0; i <= n; ++i) {
    const double angle = 0.3 * i;
    for (int j = 0; j <= 4; ++j)
      m.coords.insert(m.coords.end(),
                      {c[0] + 0.02 * j * std::cos(angle), c[1], c[2] + 0.02 * j * std::sin(angle)});
    for (double& v : c) v += step(gen);
  }
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < 4; ++j) {
      const local_index a = i * 5 + j, b = (i + 1) * 5 + j;
      m.add_facet({a, b, b + 1, a + 1});
    }
  return m;
}

} // namespace

TEST(SelfContactSearch, RandomFacetsEqualBruteForce) {
  for (int dim : {2, 3})
    for (unsigned seed : {11u, 12u}) {
      const Mesh m = test::random_facets(dim, 800, 0.03, seed);
      const Tree t(m.view(), cone_tree(0.01));
      const auto brute = find_self_pairs_brute_force(t);
      EXPECT_FALSE(brute.empty()) << dim;
      EXPECT_EQ(sorted(find_self_pairs(t)), brute) << "dim " << dim << " seed " << seed;
      const SelfContactOptions no_cones{0.0};
      EXPECT_EQ(sorted(find_self_pairs(t, no_cones)), find_self_pairs_brute_force(t, no_cones));
    }
}

TEST(SelfContactSearch, CrumpledSurfacesEqualBruteForce) {
  for (int dim : {2, 3})
    for (unsigned seed : {1u, 2u, 3u}) {
      Mesh m = crumpled(dim, dim == 2 ? 1500 : 400, seed);
      Tree t(m.view(), cone_tree(0.3 * min_edge_length(m.view())));
      const auto brute = find_self_pairs_brute_force(t);
      EXPECT_FALSE(brute.empty()) << dim;
      EXPECT_EQ(sorted(find_self_pairs(t)), brute) << "dim " << dim << " seed " << seed;
      // After a motion (refit, not rebuilt unless degraded) the search still agrees.
      std::mt19937 gen(seed);
      std::normal_distribution<double> move(0.0, 0.02);
      for (auto& x : m.coords) x += move(gen);
      t.update(m.coords);
      EXPECT_EQ(sorted(find_self_pairs(t)), find_self_pairs_brute_force(t));
    }
}

TEST(SelfContactSearch, RolesAlternateAndTheLowestFacetIsSlave) {
  // The folded strip's facing legs: a bipartite contact graph (lower leg against upper leg).
  const Mesh m = test::folded_strip(1.0, 0.05, 0.2, 40, 12, 8);
  const Tree t(m.view(), cone_tree(0.06));
  const auto pairs = find_self_pairs(t);
  ASSERT_FALSE(pairs.empty());
  const auto roles = assign_roles(t, pairs);
  ASSERT_EQ(roles.size(), pairs.size());
  // Per facet: slave (1) or master (2) in its pairs; never both.
  std::map<local_index, int> role;
  for (const auto& p : roles) {
    role[p.slave] |= 1;
    role[p.master] |= 2;
  }
  for (const auto& [f, r] : role) EXPECT_NE(r, 3) << "facet " << f << " is slave and master";
  // The lowest paired facet is slave (one connected group here).
  EXPECT_EQ(role.begin()->second, 1);
  // The same pairs in reverse and shuffled order, and with slave/master swapped, give the same
  // oriented pairs.
  auto shuffled = pairs;
  std::mt19937 gen(5);
  std::shuffle(shuffled.begin(), shuffled.end(), gen);
  for (auto& p : shuffled)
    if (gen() % 2) std::swap(p.slave, p.master);
  const auto again = assign_roles(t, shuffled);
  EXPECT_EQ(sorted(again), sorted(roles));
  // Every oriented pair is one of the pairs found.
  const auto found = sorted(pairs);
  for (const auto& p : roles)
    EXPECT_TRUE(std::binary_search(
        found.begin(), found.end(),
        CandidatePair{std::min(p.slave, p.master), std::max(p.slave, p.master)}));
}

TEST(SelfContactSearch, RolesKeptThroughAStep) {
  // Facets 1, 3, 4 of a strip whose contact graph changes between the searches of one step (as
  // between Newton iterations): first 3 faces 4, then 1 comes in on 3's side, then 4 leaves.
  // Assigned anew at each search, 3 and 4 swap roles (the lowest facet 1 of the group is slave);
  // kept, 3 stays slave, 4 master, and the newcomer 1 is given master once.
  const std::vector<std::array<double, 3>> axis{{0, 1, 0}, {0, -1, 0}, {0, 1, 0},
                                                {0, 1, 0}, {0, -1, 0}, {0, 1, 0}};
  const std::vector<std::vector<CandidatePair>> searches{{{3, 4}}, {{1, 3}, {3, 4}}, {{1, 3}}};
  std::vector<Role> roles(axis.size(), Role::none);
  // Oriented pairs of the step: kept roles, and assigned anew for comparison.
  const std::vector<std::vector<CandidatePair>> kept{{{3, 4}}, {{3, 1}, {3, 4}}, {{3, 1}}};
  const std::vector<std::vector<CandidatePair>> anew{{{3, 4}}, {{1, 3}, {4, 3}}, {{1, 3}}};
  for (std::size_t k = 0; k < searches.size(); ++k) {
    EXPECT_EQ(sorted(assign_roles(axis, searches[k], roles)), sorted(kept[k])) << "search " << k;
    EXPECT_EQ(sorted(assign_roles(axis, searches[k])), sorted(anew[k])) << "search " << k;
  }
  EXPECT_EQ(roles, (std::vector<Role>{Role::none, Role::master, Role::none, Role::slave,
                                      Role::master, Role::none}));
  // Two master facets that meet later in the step: oriented as an odd cycle (lower facet slave),
  // their roles unchanged; a new group not joined to the kept roles is oriented as anew.
  EXPECT_EQ(assign_roles(axis, std::vector<CandidatePair>{{4, 1}}, roles),
            (std::vector<CandidatePair>{{1, 4}}));
  EXPECT_EQ(assign_roles(axis, std::vector<CandidatePair>{{5, 0}}, roles),
            (std::vector<CandidatePair>{{0, 5}}));
  EXPECT_EQ(roles, (std::vector<Role>{Role::slave, Role::master, Role::none, Role::slave,
                                      Role::master, Role::master}));
}

TEST(SelfContactSearch, RolesKeptEqualRolesAnewAtTheFirstSearch) {
  // No role kept yet (a step's first search): the same orientation as assign_roles, on a
  // folded strip and on a crumpled one (odd cycles).
  for (int variant = 0; variant < 2; ++variant) {
    const Mesh m =
        variant == 0 ? test::folded_strip(1.0, 0.05, 0.2, 40, 12, 8) : crumpled(2, 1500, 2);
    const Tree t(m.view(), cone_tree(variant == 0 ? 0.06 : 0.3 * min_edge_length(m.view())));
    const auto pairs = find_self_pairs(t);
    ASSERT_FALSE(pairs.empty());
    std::vector<std::array<double, 3>> axis(static_cast<std::size_t>(t.n_facets()));
    std::visit(
        [&](const auto& b) {
          for (local_index s = 0; s < t.n_facets(); ++s)
            axis[b.facet_of_slot[s]] = b.facet_cones[s].axis;
        },
        t.bvh());
    std::vector<Role> roles(axis.size(), Role::none);
    const auto first = assign_roles(axis, pairs, roles);
    EXPECT_EQ(sorted(first), sorted(assign_roles(t, pairs))) << "variant " << variant;
    // The same pairs again with the roles of the first search: unchanged.
    EXPECT_EQ(sorted(assign_roles(axis, pairs, roles)), sorted(first)) << "variant " << variant;
  }
}
