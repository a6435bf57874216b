#include "seam/search/traversal.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <cstdint>
#include <type_traits>
#include <utility>

namespace seam::search {

namespace {

using detail::Bvh;
using detail::Link;
using NodePair = std::pair<std::int32_t, std::int32_t>;

/// Dual-tree traversal (seed paper Sect. 3.2). A node pair is pushed only if its volumes
/// overlap; two leaves are resolved at once by testing their facets against each other. Two
/// inner nodes of similar size are split together (four child tests, one stack entry less per
/// level), otherwise the larger one is split. Children are pushed right before left, so the
/// traversal runs forward through the preorder node arrays and through the facet slots of both
/// trees, the access order the hardware prefetcher follows best. The stack holds a few entries
/// per tree level.
template <int Dim, int NS>
void dual_traversal(const Bvh<Dim, NS>& a, const Bvh<Dim, NS>& b, std::vector<CandidatePair>& out) {
  if (a.n_facets() == 0 || b.n_facets() == 0) return;
  // Raw pointers: out.push_back may alias anything as far as the compiler knows, and would
  // otherwise force a reload of every array's address after each pair.
  const auto* na = a.nodes.data();
  const auto* nb = b.nodes.data();
  const auto* fa = a.facet_bounds.data();
  const auto* fb = b.facet_bounds.data();
  const local_index* ida = a.facet_of_slot.data();
  const local_index* idb = b.facet_of_slot.data();
  auto leaf_pairs = [&](Link li, Link lj) {
    for (std::int32_t s = li.first; s < li.first - li.count; ++s) {
      const auto& vs = fa[s];
      for (std::int32_t t = lj.first; t < lj.first - lj.count; ++t)
        if (overlap(vs, fb[t])) out.push_back({ida[s], idb[t]});
    }
  };
  std::vector<NodePair> stack;
  stack.reserve(256);
  auto visit = [&](std::int32_t i, std::int32_t j) {
    if (!overlap(na[i].bounds, nb[j].bounds)) return;
    const Link li = na[i].link, lj = nb[j].link;
    if (is_leaf(li) && is_leaf(lj)) {
      leaf_pairs(li, lj);
      return;
    }
    // Left children sit next to their parent; start loading the right ones.
    if (!is_leaf(li)) __builtin_prefetch(&na[li.first]);
    if (!is_leaf(lj)) __builtin_prefetch(&nb[lj.first]);
    stack.emplace_back(i, j);
  };
  visit(0, 0);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Link li = na[i].link;
    const Link lj = nb[j].link;
    const bool split_a = !is_leaf(li) && 2 * li.count >= n_facets_below(lj);
    const bool split_b = !is_leaf(lj) && 2 * lj.count >= n_facets_below(li);
    if (split_a && split_b) {
      visit(li.first, lj.first);
      visit(li.first, j + 1);
      visit(i + 1, lj.first);
      visit(i + 1, j + 1);
    } else if (split_a) {
      visit(li.first, j);
      visit(i + 1, j);
    } else {
      visit(i, lj.first);
      visit(i, j + 1);
    }
  }
}

template <int Dim, int NS>
bool share_node(const Bvh<Dim, NS>& t, local_index slot_a, local_index slot_b) {
  const auto na = t.slot_nodes(slot_a);
  const auto nb = t.slot_nodes(slot_b);
  for (local_index x : na)
    for (local_index y : nb)
      if (x == y) return true;
  return false;
}

CandidatePair ordered(local_index f, local_index g) {
  return f < g ? CandidatePair{f, g} : CandidatePair{g, f};
}

/// The self-contact test of two facet slots: volumes overlap, no shared node, and normals that
/// may be at least min_angle apart.
template <int Dim, int NS>
bool self_candidates(const Bvh<Dim, NS>& t, std::int32_t s, std::int32_t r, double min_angle) {
  if (!overlap(t.facet_bounds[s], t.facet_bounds[r]) || share_node(t, s, r)) return false;
  return min_angle <= 0.0 || max_angle_between(t.facet_cones[s], t.facet_cones[r]) >= min_angle;
}

/// Single-tree traversal for self contact: (i, i) stands for "pairs within subtree i", (i, j)
/// with i != j for pairs between two disjoint subtrees.
template <int Dim, int NS>
void self_traversal(const Bvh<Dim, NS>& t, double min_angle, std::vector<CandidatePair>& out) {
  if (t.n_facets() < 2) return;
  const bool use_cones = min_angle > 0.0;
  auto candidates = [&](std::int32_t i, std::int32_t j) {
    return overlap(t.nodes[i].bounds, t.nodes[j].bounds) &&
           (!use_cones || max_angle_between(t.cones[i], t.cones[j]) >= min_angle);
  };
  auto emit = [&](std::int32_t s, std::int32_t r) {
    if (self_candidates(t, s, r, min_angle))
      out.push_back(ordered(t.facet_of_slot[s], t.facet_of_slot[r]));
  };
  std::vector<NodePair> stack;
  stack.reserve(128);
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    const Link li = t.nodes[i].link;
    const Link lj = t.nodes[j].link;
    // A smooth patch: no two of its normals are min_angle apart.
    if (i == j && use_cones && 2.0 * t.cones[i].angle < min_angle) continue;
    if (i == j && is_leaf(li)) {
      for (std::int32_t s = li.first; s < li.first - li.count; ++s)
        for (std::int32_t r = s + 1; r < li.first - li.count; ++r) emit(s, r);
    } else if (i == j) {
      const std::int32_t l = i + 1, r = li.first;
      stack.emplace_back(l, l);
      stack.emplace_back(r, r);
      if (candidates(l, r)) stack.emplace_back(l, r);
    } else if (is_leaf(li) && is_leaf(lj)) {
      for (std::int32_t s = li.first; s < li.first - li.count; ++s)
        for (std::int32_t r = lj.first; r < lj.first - lj.count; ++r) emit(s, r);
    } else if (is_leaf(lj) || (!is_leaf(li) && li.count >= n_facets_below(lj))) {
      if (candidates(li.first, j)) stack.emplace_back(li.first, j);
      if (candidates(i + 1, j)) stack.emplace_back(i + 1, j);
    } else {
      if (candidates(i, lj.first)) stack.emplace_back(i, lj.first);
      if (candidates(i, j + 1)) stack.emplace_back(i, j + 1);
    }
  }
}

void check_compatible(const Tree& a, const Tree& b) {
  SEAM_CHECK(a.dim() == b.dim() && a.volume() == b.volume(), InputError,
             "search: trees of different dimension or bounding volume cannot be paired");
}

void check_self(const Tree& tree, const SelfContactOptions& options) {
  SEAM_CHECK(options.min_normal_angle <= 0.0 || tree.options().normal_cones, InputError,
             "search: self contact with a normal-angle test needs a tree built with "
             "normal_cones = true");
}

} // namespace

void find_pairs(const Tree& slave, const Tree& master, std::vector<CandidatePair>& out) {
  check_compatible(slave, master);
  out.clear();
  std::visit(
      [&](const auto& a) {
        using B = std::decay_t<decltype(a)>;
        dual_traversal(a, std::get<B>(master.bvh()), out);
      },
      slave.bvh());
}

std::vector<CandidatePair> find_pairs(const Tree& slave, const Tree& master) {
  std::vector<CandidatePair> out;
  find_pairs(slave, master, out);
  return out;
}

void find_self_pairs(const Tree& tree, std::vector<CandidatePair>& out,
                     const SelfContactOptions& options) {
  check_self(tree, options);
  out.clear();
  std::visit([&](const auto& t) { self_traversal(t, options.min_normal_angle, out); }, tree.bvh());
}

std::vector<CandidatePair> find_self_pairs(const Tree& tree, const SelfContactOptions& options) {
  std::vector<CandidatePair> out;
  find_self_pairs(tree, out, options);
  return out;
}

std::vector<CandidatePair> find_pairs_brute_force(const Tree& slave, const Tree& master) {
  check_compatible(slave, master);
  std::vector<CandidatePair> out;
  std::visit(
      [&](const auto& a) {
        using B = std::decay_t<decltype(a)>;
        const B& b = std::get<B>(master.bvh());
        for (local_index s = 0; s < a.n_facets(); ++s)
          for (local_index m = 0; m < b.n_facets(); ++m)
            if (overlap(a.facet_bounds[s], b.facet_bounds[m]))
              out.push_back({a.facet_of_slot[s], b.facet_of_slot[m]});
      },
      slave.bvh());
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<CandidatePair> find_self_pairs_brute_force(const Tree& tree,
                                                       const SelfContactOptions& options) {
  check_self(tree, options);
  std::vector<CandidatePair> out;
  std::visit(
      [&](const auto& t) {
        for (local_index s = 0; s < t.n_facets(); ++s)
          for (local_index r = s + 1; r < t.n_facets(); ++r)
            if (self_candidates(t, s, r, options.min_normal_angle))
              out.push_back(ordered(t.facet_of_slot[s], t.facet_of_slot[r]));
      },
      tree.bvh());
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace seam::search
