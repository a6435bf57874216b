// The tree's memory layout and its float volumes. The traversal relies on the depth-first
// preorder (left child next to its parent, subtrees contiguous, leaves in slot order) and on
// float volumes that contain the exact ones; both are checked here against independent
// double-precision computations, not against the tree's own output.
#include "seam/search/traversal.hpp"
#include "seam/search/tree.hpp"
#include "surfaces.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <variant>
#include <vector>

using namespace seam::search;
using seam::local_index;
using seam::search::test::Mesh;

namespace {

/// Exact (double) k-DOP of a facet: projections onto slab_direction() by plain dot products,
/// widened by inflation * |d_s|.
struct DoubleKdop {
  std::array<double, 9> lo, hi;
};

DoubleKdop double_kdop(const Mesh& m, local_index f, int ns, double inflation) {
  DoubleKdop k;
  k.lo.fill(std::numeric_limits<double>::infinity());
  k.hi.fill(-std::numeric_limits<double>::infinity());
  for (local_index c = m.offsets[f]; c < m.offsets[f + 1]; ++c) {
    const double* x = m.coords.data() + static_cast<std::size_t>(m.conn[c]) * m.dim;
    for (int s = 0; s < ns; ++s) {
      const auto d = slab_direction(m.dim, ns, s);
      double p = 0.0;
      for (int i = 0; i < m.dim; ++i) p += d[i] * x[i];
      k.lo[s] = std::min(k.lo[s], p);
      k.hi[s] = std::max(k.hi[s], p);
    }
  }
  for (int s = 0; s < ns; ++s) {
    const auto d = slab_direction(m.dim, ns, s);
    const double w = inflation * std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    k.lo[s] -= w;
    k.hi[s] += w;
  }
  return k;
}

template <int NS> bool contains(const Kdop<NS>& outer, const Kdop<NS>& inner) {
  for (int s = 0; s < NS; ++s)
    if (outer.lo[s] > inner.lo[s] || outer.hi[s] < inner.hi[s]) return false;
  return true;
}

/// Walks the preorder array recursively and checks every structural invariant; returns the
/// number of nodes of the subtree at i. `next_slot` is the slot the next leaf must start at.
template <class B> std::int32_t check_subtree(const B& b, std::int32_t i, std::int32_t& next_slot) {
  const auto link = b.nodes[i].link;
  if (detail::is_leaf(link)) {
    EXPECT_EQ(link.first, next_slot) << "leaves must hold the slots in preorder";
    const std::int32_t n = -link.count;
    for (std::int32_t s = link.first; s < link.first + n; ++s)
      EXPECT_TRUE(contains(b.nodes[i].bounds, b.facet_bounds[s])) << "leaf " << i << " slot " << s;
    next_slot += n;
    return 1;
  }
  const std::int32_t left = i + 1, right = link.first;
  EXPECT_TRUE(contains(b.nodes[i].bounds, b.nodes[left].bounds));
  EXPECT_TRUE(contains(b.nodes[i].bounds, b.nodes[right].bounds));
  const std::int32_t n_left = check_subtree(b, left, next_slot);
  EXPECT_EQ(right, left + n_left) << "the left subtree must fill the nodes up to the right child";
  const std::int32_t n_right = check_subtree(b, right, next_slot);
  EXPECT_EQ(link.count, detail::n_facets_below(b.nodes[left].link) +
                            detail::n_facets_below(b.nodes[right].link));
  return 1 + n_left + n_right;
}

void check_layout(const Tree& tree) {
  std::visit(
      [&](const auto& b) {
        if (b.n_facets() == 0) return;
        std::int32_t next_slot = 0;
        EXPECT_EQ(check_subtree(b, 0, next_slot), b.n_tree_nodes());
        EXPECT_EQ(next_slot, b.n_facets());
        // facet_of_slot is a permutation.
        std::vector<local_index> f(b.facet_of_slot.begin(), b.facet_of_slot.end());
        std::sort(f.begin(), f.end());
        for (local_index k = 0; k < b.n_facets(); ++k) EXPECT_EQ(f[k], k);
      },
      tree.bvh());
}

TreeOptions options(BoundingVolume v, double inflation, int leaf_size) {
  TreeOptions o;
  o.volume = v;
  o.inflation = inflation;
  o.leaf_size = leaf_size;
  return o;
}

} // namespace

TEST(Layout, PreorderSubtreesAreContiguousAndNested) {
  for (int dim : {2, 3})
    for (auto v : {BoundingVolume::kdop, BoundingVolume::aabb})
      for (int leaf : {1, 3, 4, 7}) {
        Mesh m = test::random_facets(dim, 500, 0.03, 5);
        Tree t(m.view(), options(v, 0.01, leaf));
        check_layout(t);
        // After a refit and after a rebuild the layout still holds.
        for (double& x : m.coords) x *= 1.01;
        t.update(m.coords);
        check_layout(t);
        t.rebuild(m.coords);
        check_layout(t);
      }
}

TEST(Layout, FloatVolumesContainTheExactOnes) {
  // Coordinates like 0.1 have no exact float; the stored volumes must still contain the
  // double-precision k-DOPs of every facet.
  for (int dim : {2, 3})
    for (auto v : {BoundingVolume::kdop, BoundingVolume::aabb}) {
      const Mesh m = dim == 3 ? test::wavy_surface(13, 11, 0.1, 0.07, 0.1)
                              : test::wavy_polyline(97, 0.1, 0.07, 0.1);
      const double inflation = 0.003;
      const Tree t(m.view(), options(v, inflation, 4));
      const int ns = n_slabs(dim, v);
      std::visit(
          [&](const auto& b) {
            for (local_index s = 0; s < b.n_facets(); ++s) {
              const DoubleKdop exact = double_kdop(m, b.facet_of_slot[s], ns, inflation);
              for (int k = 0; k < ns; ++k) {
                EXPECT_LE(double(b.facet_bounds[s].lo[k]), exact.lo[k]);
                EXPECT_GE(double(b.facet_bounds[s].hi[k]), exact.hi[k]);
              }
            }
          },
          t.bvh());
    }
}

TEST(Layout, FloatTreeFindsEveryPairOfTheExactTest) {
  // Two triangulations of the same nodes (the master splits each cell along the other
  // diagonal) without inflation: facets that share only an edge or a node have exactly
  // touching double volumes, the tightest case for the float volumes, the merges and the
  // traversal together. Every pair the double-precision test reports must be among the tree's.
  for (int dim : {2, 3})
    for (auto v : {BoundingVolume::kdop, BoundingVolume::aabb}) {
      const Mesh a = dim == 3 ? test::wavy_surface(17, 15, 0.1, 0.05, 0.1)
                              : test::wavy_polyline(203, 0.1, 0.05, 0.1);
      Mesh b = a;
      if (dim == 3)
        for (std::size_t f = 0; f + 1 < b.offsets.size(); f += 2) {
          // wavy_surface stores each cell as triangles (p, q, r), (p, r, s); use (p, q, s),
          // (q, r, s) instead.
          const local_index* c = a.conn.data() + a.offsets[f];
          const local_index p = c[0], q = c[1], r = c[2], s = c[5];
          local_index* d = b.conn.data() + b.offsets[f];
          const local_index flipped[6] = {p, q, s, q, r, s};
          std::copy_n(flipped, 6, d);
        }
      const Tree ta(a.view(), options(v, 0.0, 4)), tb(b.view(), options(v, 0.0, 3));
      auto tree = find_pairs(ta, tb);
      std::sort(tree.begin(), tree.end());
      const int ns = n_slabs(dim, v);
      std::vector<DoubleKdop> ka, kb;
      for (local_index f = 0; f < a.view().n_facets(); ++f) ka.push_back(double_kdop(a, f, ns, 0));
      for (local_index f = 0; f < b.view().n_facets(); ++f) kb.push_back(double_kdop(b, f, ns, 0));
      std::size_t n_exact = 0, n_missed = 0;
      for (local_index f = 0; f < local_index(ka.size()); ++f)
        for (local_index g = 0; g < local_index(kb.size()); ++g) {
          bool overlap = true;
          for (int s = 0; s < ns; ++s)
            overlap = overlap && ka[f].lo[s] <= kb[g].hi[s] && kb[g].lo[s] <= ka[f].hi[s];
          if (!overlap) continue;
          ++n_exact;
          n_missed += !std::binary_search(tree.begin(), tree.end(), CandidatePair{f, g});
        }
      EXPECT_GT(n_exact, 0u);
      EXPECT_EQ(n_missed, 0u) << dim << "D";
    }
}
