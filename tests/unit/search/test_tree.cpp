// The tree reports exactly the pairs whose bounding volumes overlap: compared with the brute-force
// test of all pairs on random, structured, degenerate and moving surfaces.
#include "seam/search/traversal.hpp"
#include "seam/search/tree.hpp"
#include "surfaces.hpp"

#include "seam/common/error.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <numeric>
#include <random>

using namespace seam::search;
using seam::search::test::Mesh;

namespace {

std::vector<CandidatePair> sorted_tree_pairs(const Tree& a, const Tree& b) {
  auto p = find_pairs(a, b);
  std::sort(p.begin(), p.end());
  return p;
}

void expect_tree_equals_brute_force(const Tree& a, const Tree& b, bool expect_some = true) {
  const auto tree = sorted_tree_pairs(a, b);
  const auto brute = find_pairs_brute_force(a, b);
  EXPECT_EQ(tree.size(), brute.size());
  EXPECT_TRUE(tree == brute);
  EXPECT_TRUE(std::adjacent_find(tree.begin(), tree.end()) == tree.end()) << "duplicate pairs";
  if (expect_some) {
    EXPECT_GT(brute.size(), 0u);
  }
}

TreeOptions options(BoundingVolume v, double inflation, int leaf_size = 4) {
  TreeOptions o;
  o.volume = v;
  o.inflation = inflation;
  o.leaf_size = leaf_size;
  return o;
}

const BoundingVolume volumes[] = {BoundingVolume::kdop, BoundingVolume::aabb};

} // namespace

TEST(Tree, RandomFacetsMatchBruteForce) {
  for (int dim : {2, 3})
    for (auto v : volumes)
      for (int leaf : {1, 4, 7}) {
        const Mesh a = test::random_facets(dim, 700, 0.03, 1),
                   b = test::random_facets(dim, 500, 0.03, 2);
        const Tree ta(a.view(), options(v, 0.01, leaf)), tb(b.view(), options(v, 0.01, leaf));
        expect_tree_equals_brute_force(ta, tb);
      }
}

TEST(Tree, StructuredWavySurfacesMatchBruteForce) {
  for (auto v : volumes) {
    for (bool quads : {false, true})
      for (int leaf : {1, 4}) {
        const Mesh a = test::wavy_surface(24, 20, 0.0, 0.1, 0.0, quads);
        const Mesh b = test::wavy_surface(17, 19, 0.01, 0.1, 0.013, quads);
        const Tree ta(a.view(), options(v, 0.015, leaf)), tb(b.view(), options(v, 0.015, 5 - leaf));
        expect_tree_equals_brute_force(ta, tb);
      }
    const Mesh a = test::wavy_polyline(300, 0.0, 0.1, 0.0),
               b = test::wavy_polyline(211, 0.004, 0.1, 0.002);
    const Tree ta(a.view(), options(v, 0.002)), tb(b.view(), options(v, 0.002));
    expect_tree_equals_brute_force(ta, tb);
  }
}

TEST(Tree, CoplanarAndCollapsedFacets) {
  for (auto v : volumes) {
    // All facets in the plane z = 0 (zero extent in z for every volume).
    const Mesh a = test::wavy_surface(15, 15, 0.0, 0.0, 0.0),
               b = test::wavy_surface(11, 13, 0.0, 0.0, 0.01);
    const Tree ta(a.view(), options(v, 0.0)), tb(b.view(), options(v, 0.0));
    expect_tree_equals_brute_force(ta, tb);
    // Every node in one point: all pairs overlap (closed test), depth stays bounded.
    Mesh p = test::random_facets(3, 300, 0.1, 3), q = test::random_facets(3, 200, 0.1, 4);
    std::fill(p.coords.begin(), p.coords.end(), 0.5);
    std::fill(q.coords.begin(), q.coords.end(), 0.5);
    const Tree tp(p.view(), options(v, 0.0)), tq(q.view(), options(v, 0.0));
    EXPECT_EQ(find_pairs(tp, tq).size(), 300u * 200u);
    expect_tree_equals_brute_force(tp, tq);
    // Collinear segments in 2D.
    Mesh s = test::wavy_polyline(200, 0.0, 0.0, 0.0), t = test::wavy_polyline(150, 0.0, 0.0, 0.001);
    const Tree ts(s.view(), options(v, 0.0)), tt(t.view(), options(v, 0.0));
    expect_tree_equals_brute_force(ts, tt);
  }
}

TEST(Tree, EmptyAndSingleFacet) {
  const Mesh one = test::random_facets(3, 1, 0.1, 5);
  Mesh none;
  const Tree t1(one.view(), options(BoundingVolume::kdop, 0.1)),
      t0(none.view(), options(BoundingVolume::kdop, 0.1));
  EXPECT_EQ(find_pairs(t1, t1).size(), 1u);
  EXPECT_TRUE(find_pairs(t0, t1).empty());
  EXPECT_TRUE(find_pairs(t1, t0).empty());
  // A rank without facets may pass no offsets at all.
  const FacetSurface nothing{3, {}, {}, {}};
  const Tree te(nothing, options(BoundingVolume::kdop, 0.1));
  EXPECT_EQ(te.n_facets(), 0);
  EXPECT_TRUE(find_pairs(te, t1).empty());
  EXPECT_TRUE(find_pairs(t1, te).empty());
}

TEST(Tree, MovingSurfacesAfterRefitsAndRebuilds) {
  for (int dim : {2, 3}) {
    Mesh a = dim == 3 ? test::wavy_surface(20, 20, 0.0, 0.05, 0.0)
                      : test::wavy_polyline(400, 0.0, 0.05, 0.0);
    Mesh b = dim == 3 ? test::wavy_surface(16, 18, 0.02, 0.05, 0.01)
                      : test::wavy_polyline(300, 0.003, 0.05, 0.001);
    Tree ta(a.view(), options(BoundingVolume::kdop, 0.01));
    Tree tb(b.view(), options(BoundingVolume::kdop, 0.01));
    std::mt19937 gen(11);
    std::uniform_real_distribution<double> jitter(-0.004, 0.004);
    for (int step = 0; step < 8; ++step) {
      // Smooth sliding of b plus random jitter of every node, with the old positions given.
      const std::vector<double> old = b.coords;
      for (std::size_t i = 0; i < b.coords.size(); ++i) {
        b.coords[i] += jitter(gen);
        if (i % dim == 0) b.coords[i] += 0.03;
      }
      tb.update(b.coords, old);
      expect_tree_equals_brute_force(ta, tb);
      // Pairs found with the old positions included are a superset of those without.
      Tree fresh(b.view(), options(BoundingVolume::kdop, 0.01));
      const auto with_motion = sorted_tree_pairs(ta, tb), without = sorted_tree_pairs(ta, fresh);
      EXPECT_TRUE(
          std::includes(with_motion.begin(), with_motion.end(), without.begin(), without.end()));
    }
  }
}

TEST(Tree, DegradedTreeIsRebuilt) {
  // Unconnected facets swap places: each keeps its size, but the tree's groups now span the
  // whole domain, so the quality degrades, the update rebuilds, and the result stays exact.
  Mesh a = test::random_facets(3, 800, 0.01, 21);
  const Mesh b = test::random_facets(3, 600, 0.01, 22);
  Tree ta(a.view(), options(BoundingVolume::kdop, 0.005));
  const Tree tb(b.view(), options(BoundingVolume::kdop, 0.005));
  // A small motion only refits.
  std::vector<double> moved = a.coords;
  for (double& x : moved) x += 1e-3;
  EXPECT_FALSE(ta.update(moved));
  expect_tree_equals_brute_force(ta, tb);
  std::vector<int> perm(800);
  std::iota(perm.begin(), perm.end(), 0);
  std::shuffle(perm.begin(), perm.end(), std::mt19937(4));
  std::vector<double> swapped(a.coords.size());
  for (int f = 0; f < 800; ++f)
    for (int v = 0; v < 3; ++v)
      for (int d = 0; d < 3; ++d)
        swapped[9 * f + 3 * v + d] =
            a.coords[9 * f + 3 * v + d] - a.coords[9 * f + d] + a.coords[9 * perm[f] + d];
  EXPECT_TRUE(ta.update(swapped));
  EXPECT_EQ(ta.n_rebuilds(), 1);
  expect_tree_equals_brute_force(ta, tb);
}

TEST(Tree, KdopPairsAreASubsetOfAabbPairs) {
  for (int dim : {2, 3}) {
    const Mesh a = dim == 3 ? test::wavy_surface(30, 30, 0.0, 0.1, 0.0)
                            : test::wavy_polyline(600, 0.0, 0.1, 0.0);
    const Mesh b = dim == 3 ? test::wavy_surface(25, 27, 0.01, 0.1, 0.005)
                            : test::wavy_polyline(500, 0.002, 0.1, 0.0007);
    const double infl = dim == 3 ? 0.01 : 0.001;
    const Tree ka(a.view(), options(BoundingVolume::kdop, infl)),
        kb(b.view(), options(BoundingVolume::kdop, infl));
    const Tree xa(a.view(), options(BoundingVolume::aabb, infl)),
        xb(b.view(), options(BoundingVolume::aabb, infl));
    const auto k = sorted_tree_pairs(ka, kb), x = sorted_tree_pairs(xa, xb);
    EXPECT_LE(k.size(), x.size());
    EXPECT_TRUE(std::includes(x.begin(), x.end(), k.begin(), k.end()));
    // On tilted wavy surfaces the diagonal slabs prune a real share of the box pairs.
    EXPECT_LT(double(k.size()), 0.95 * double(x.size())) << dim << "D";
  }
}

TEST(Tree, RejectsBadInput) {
  Mesh m = test::random_facets(3, 4, 0.1, 9);
  EXPECT_THROW(Tree(m.view(), options(BoundingVolume::kdop, -1.0)), seam::InputError);
  Mesh bad = m;
  bad.conn[2] = 1000;
  EXPECT_THROW(Tree(bad.view(), options(BoundingVolume::kdop, 0.1)), seam::InputError);
  bad = m;
  bad.coords[4] = std::nan("");
  EXPECT_THROW(Tree(bad.view(), options(BoundingVolume::kdop, 0.1)), seam::InputError);
  Tree t(m.view(), options(BoundingVolume::kdop, 0.1));
  std::vector<double> short_coords(m.coords.size() - 3, 0.0);
  EXPECT_THROW(t.update(short_coords), seam::InputError);
  const Mesh p = test::wavy_polyline(10, 0.0, 0.0, 0.0);
  const Tree t2(p.view(), options(BoundingVolume::kdop, 0.1));
  EXPECT_THROW(find_pairs(t, t2), seam::InputError);
  EXPECT_THROW(find_self_pairs(t), seam::InputError); // no normal cones
}
