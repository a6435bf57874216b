// The distributed self-contact search decides the roles of each connected group of pairs on one
// rank (problem/contact_search.hpp): contact::orient_pairs over some of the groups only, the
// facets renumbered in the order of their ids, the pairs in their order among all pairs, must
// give every group the roles and orientation that orient_pairs over all groups gives it. Checked
// on random graphs (odd cycles, roles kept from earlier searches, axes of one facet differing
// between its pairs) against the whole graph.
#include "seam/contact/self_contact.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <numeric>
#include <random>
#include <set>

using namespace seam;
using contact::FacingPair;
using search::Role;

namespace {

struct Graph {
  local_index n = 0;
  std::vector<FacingPair> pairs;
  std::vector<Role> roles; // kept from earlier searches (none: not yet)
};

Graph random_graph(std::mt19937& gen) {
  Graph g;
  g.n = std::uniform_int_distribution<local_index>(2, 40)(gen);
  const auto n_pairs = std::uniform_int_distribution<int>(1, g.n + g.n / 2)(gen);
  std::uniform_int_distribution<local_index> facet(0, g.n - 1);
  std::normal_distribution<double> normal(0.0, 1.0);
  std::set<std::pair<local_index, local_index>> seen;
  const auto axis = [&] { return std::array<double, 3>{normal(gen), normal(gen), normal(gen)}; };
  for (int k = 0; k < n_pairs; ++k) {
    const auto a = facet(gen), b = facet(gen);
    if (a == b || !seen.insert({std::min(a, b), std::max(a, b)}).second) continue;
    g.pairs.push_back({{a, b}, axis(), axis()});
  }
  g.roles.assign(static_cast<std::size_t>(g.n), Role::none);
  std::uniform_int_distribution<int> pick(0, 3);
  for (auto& r : g.roles) r = pick(gen) == 0 ? Role::slave : pick(gen) == 0 ? Role::master : r;
  return g;
}

/// Per facet its group (the lowest facet of its connected group of pairs), by brute force.
std::vector<local_index> groups(const Graph& g) {
  std::vector<local_index> label(static_cast<std::size_t>(g.n));
  std::iota(label.begin(), label.end(), 0);
  for (bool changed = true; changed;) {
    changed = false;
    for (const auto& p : g.pairs) {
      auto& a = label[static_cast<std::size_t>(p.pair.slave)];
      auto& b = label[static_cast<std::size_t>(p.pair.master)];
      if (a != b) {
        a = b = std::min(a, b);
        changed = true;
      }
    }
  }
  return label;
}

std::set<std::pair<local_index, local_index>> as_set(const std::vector<mortar::CandidatePair>& v) {
  std::set<std::pair<local_index, local_index>> s;
  for (const auto& p : v) s.insert({p.slave, p.master});
  return s;
}

} // namespace

TEST(OrientGroups, SomeGroupsAloneAsInTheWholeGraph) {
  std::mt19937 gen(2026);
  int checked = 0, several = 0;
  for (int trial = 0; trial < 400; ++trial) {
    const auto g = random_graph(gen);
    const bool keep = trial % 2 == 0; // with roles kept, or the first search of a step
    std::vector<mortar::CandidatePair> whole;
    auto whole_roles = keep ? g.roles : std::vector<Role>{};
    contact::orient_pairs(g.n, g.pairs, whole, whole_roles);
    const auto label = groups(g);
    std::set<local_index> all(label.begin(), label.end());
    // The groups dealt to 3 deciding ranks at random.
    std::map<local_index, int> rank_of;
    std::uniform_int_distribution<int> rank(0, 2);
    for (const auto l : all) rank_of[l] = rank(gen);
    std::set<std::pair<local_index, local_index>> merged;
    int deciding = 0;
    for (int r = 0; r < 3; ++r) {
      // This rank's facets in the order of their numbers, its pairs in their order.
      std::vector<local_index> ids;
      std::vector<FacingPair> mine;
      for (const auto& p : g.pairs)
        if (rank_of[label[static_cast<std::size_t>(p.pair.slave)]] == r) {
          mine.push_back(p);
          ids.push_back(p.pair.slave);
          ids.push_back(p.pair.master);
        }
      if (mine.empty()) continue;
      ++deciding;
      std::sort(ids.begin(), ids.end());
      ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
      const auto number = [&](local_index f) {
        return static_cast<local_index>(std::lower_bound(ids.begin(), ids.end(), f) - ids.begin());
      };
      for (auto& p : mine) p.pair = {number(p.pair.slave), number(p.pair.master)};
      std::vector<Role> roles;
      if (keep)
        for (const auto f : ids) roles.push_back(g.roles[static_cast<std::size_t>(f)]);
      std::vector<mortar::CandidatePair> out;
      contact::orient_pairs(static_cast<local_index>(ids.size()), mine, out, roles);
      for (const auto& p : out)
        merged.insert(
            {ids[static_cast<std::size_t>(p.slave)], ids[static_cast<std::size_t>(p.master)]});
      for (std::size_t f = 0; keep && f < ids.size(); ++f)
        EXPECT_EQ(roles[f], whole_roles[static_cast<std::size_t>(ids[f])])
            << "trial " << trial << " facet " << ids[f];
    }
    EXPECT_EQ(merged, as_set(whole)) << "trial " << trial;
    ++checked;
    several += deciding > 1;
  }
  EXPECT_EQ(checked, 400);
  EXPECT_GT(several, 150); // most trials split over several deciding ranks
}
