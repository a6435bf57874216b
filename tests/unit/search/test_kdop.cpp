// k-DOP primitives and normal cones against analytic geometry.
#include "seam/search/kdop.hpp"
#include "seam/search/normal_cone.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <random>
#include <vector>

using namespace seam::search;

namespace {

template <int Dim, int NS>
Kdop<NS> volume_of(const std::vector<std::array<double, 3>>& points, double inflation) {
  KdopBuilder<Dim, NS> b;
  for (const auto& p : points) b.add_point(p.data());
  return b.finish(inflation);
}

template <int Dim, int NS> bool contains(const Kdop<NS>& k, const double* x) {
  double p[NS];
  project<Dim, NS>(x, p);
  for (int s = 0; s < NS; ++s)
    if (p[s] < k.lo[s] || p[s] > k.hi[s]) return false;
  return true;
}

} // namespace

TEST(Kdop, OutwardRoundingBracketsTheValue) {
  for (double v : {0.1, -0.1, 1.0 / 3.0, -2.0 / 3.0, 1e-30, 123456.789}) {
    EXPECT_LE(static_cast<double>(round_down(v)), v);
    EXPECT_GE(static_cast<double>(round_up(v)), v);
    // A few float ulps wide at most.
    EXPECT_LE(round_up(v) - round_down(v), 8.0 * std::abs(v) * 1.2e-7 + 0x1p-117);
  }
  EXPECT_LE(round_down(0.0), 0.0f);
  EXPECT_GE(round_up(0.0), 0.0f);
  // Values just off a float: rounding to nearest alone would cross them.
  const double above = 1.0 + 0x1p-30, below = 1.0 - 0x1p-30;
  EXPECT_LE(static_cast<double>(round_down(above)), above);
  EXPECT_GE(static_cast<double>(round_up(below)), below);
  EXPECT_LT(round_down(above), 1.0f);
  EXPECT_GT(round_up(below), 1.0f);
}

TEST(Kdop, DirectionsMatchTheProjection) {
  const double x[3] = {0.3, -1.7, 2.9};
  double p[9];
  project<3, 9>(x, p);
  for (int s = 0; s < 9; ++s) {
    const auto d = slab_direction(3, 9, s);
    EXPECT_DOUBLE_EQ(p[s], d[0] * x[0] + d[1] * x[1] + d[2] * x[2]) << "slab " << s;
    EXPECT_DOUBLE_EQ((slab_norm<3, 9>(s)), std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]));
  }
  double q[4];
  project<2, 4>(x, q);
  for (int s = 0; s < 4; ++s) {
    const auto d = slab_direction(2, 4, s);
    EXPECT_DOUBLE_EQ(q[s], d[0] * x[0] + d[1] * x[1]);
  }
}

TEST(Kdop, DiagonalSlabSeparatesWhatTheBoxCannot) {
  // Segment on x + y = 1 and a short segment beyond it near (0.85, 0.75): the boxes
  // [0,1]^2 and [0.8,0.9]x[0.7,0.8] overlap, but x + y is 1 on one and 1.6 on the other.
  const std::vector<std::array<double, 3>> a{{0.0, 1.0, 0.0}, {1.0, 0.0, 0.0}};
  const std::vector<std::array<double, 3>> b{{0.8, 0.8, 0.0}, {0.9, 0.7, 0.0}};
  EXPECT_TRUE(overlap(volume_of<2, 2>(a, 0.0), volume_of<2, 2>(b, 0.0)));
  EXPECT_FALSE(overlap(volume_of<2, 4>(a, 0.0), volume_of<2, 4>(b, 0.0)));
  // The gap along (1,1)/sqrt2 is 0.6/sqrt2; inflating both by a bit more than half of it closes
  // it, a bit less does not.
  const double gap = 0.6 / std::sqrt(2.0);
  EXPECT_TRUE(overlap(volume_of<2, 4>(a, 0.5 * gap + 1e-6), volume_of<2, 4>(b, 0.5 * gap + 1e-6)));
  EXPECT_FALSE(overlap(volume_of<2, 4>(a, 0.5 * gap - 1e-6), volume_of<2, 4>(b, 0.5 * gap - 1e-6)));
  // 3D: triangles near the plane x + y + z = 1 separated only along (1,1,0).
  const std::vector<std::array<double, 3>> t1{{1, 0, 0}, {0, 1, 0}, {0.5, 0.5, 0.2}};
  const std::vector<std::array<double, 3>> t2{{0.9, 0.8, 0.1}, {0.8, 0.9, 0.1}, {0.9, 0.9, 0.0}};
  EXPECT_TRUE(overlap(volume_of<3, 3>(t1, 0.0), volume_of<3, 3>(t2, 0.0)));
  EXPECT_FALSE(overlap(volume_of<3, 9>(t1, 0.0), volume_of<3, 9>(t2, 0.0)));
}

TEST(Kdop, InflatedVolumeContainsTheDistanceNeighbourhood) {
  // Every point within distance delta of a triangle lies in its inflated 18-DOP (and AABB).
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> u(-1.0, 1.0), w(0.0, 1.0);
  const double delta = 0.05;
  for (int trial = 0; trial < 200; ++trial) {
    std::vector<std::array<double, 3>> tri(3);
    for (auto& p : tri)
      for (double& c : p) c = u(gen);
    const auto k18 = volume_of<3, 9>(tri, delta);
    const auto k6 = volume_of<3, 3>(tri, delta);
    for (int s = 0; s < 50; ++s) {
      double a = w(gen), b = w(gen);
      if (a + b > 1.0) a = 1.0 - a, b = 1.0 - b;
      double dir[3] = {u(gen), u(gen), u(gen)};
      const double l = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
      const double r = delta * w(gen) / l;
      double x[3];
      for (int d = 0; d < 3; ++d)
        x[d] = tri[0][d] + a * (tri[1][d] - tri[0][d]) + b * (tri[2][d] - tri[0][d]) + r * dir[d];
      ASSERT_TRUE((contains<3, 9>(k18, x)));
      ASSERT_TRUE((contains<3, 3>(k6, x)));
    }
  }
}

TEST(Kdop, MergeIsTheSmallestCommonVolume) {
  const std::vector<std::array<double, 3>> a{{0, 0, 0}, {1, 0, 0}};
  const std::vector<std::array<double, 3>> b{{0, 2, 1}, {0, 3, -1}};
  std::vector<std::array<double, 3>> ab = a;
  ab.insert(ab.end(), b.begin(), b.end());
  const auto m = merge(volume_of<3, 9>(a, 0.0), volume_of<3, 9>(b, 0.0));
  const auto direct = volume_of<3, 9>(ab, 0.0);
  EXPECT_EQ(m.lo, direct.lo);
  EXPECT_EQ(m.hi, direct.hi);
  EXPECT_NEAR((margin<3>(m)), 1.0 + 3.0 + 2.0, 1e-5); // up to the outward rounding
}

TEST(NormalCone, FacetNormals) {
  const std::vector<double> c3{0, 0, 0, 2, 0, 0, 0, 3, 0, 2, 3, 0.5};
  const std::vector<seam::local_index> tri{0, 1, 2};
  const auto cone = facet_normal_cone(3, c3, tri);
  EXPECT_NEAR(cone.axis[2], 1.0, 1e-14);
  EXPECT_LT(cone.angle, 1e-8);
  // A warped quad: corner normals are tilted, the cone holds all of them.
  const std::vector<seam::local_index> quad{0, 1, 3, 2};
  const auto qc = facet_normal_cone(3, c3, quad);
  EXPECT_GT(qc.angle, 0.05);
  EXPECT_LT(qc.angle, 0.5 * std::numbers::pi);
  // 2D: segment from (0,0) to (1,0) has right-hand normal (0,-1).
  const std::vector<double> c2{0, 0, 1, 0};
  const std::vector<seam::local_index> seg{0, 1};
  const auto sc = facet_normal_cone(2, c2, seg);
  EXPECT_NEAR(sc.axis[1], -1.0, 1e-14);
  // Degenerate facet: full cone.
  const std::vector<double> c0{1, 1, 1, 1, 1, 1, 1, 1, 1};
  EXPECT_EQ(facet_normal_cone(3, c0, tri).angle, std::numbers::pi);
}

TEST(NormalCone, MergeContainsBothConesAndIsTightForTwoDirections) {
  const double phi = 1.0;
  NormalCone a{{1.0, 0.0, 0.0}, 0.0}, b{{std::cos(phi), std::sin(phi), 0.0}, 0.0};
  const NormalCone m = merge(a, b);
  EXPECT_NEAR(m.angle, 0.5 * phi, 1e-8);
  EXPECT_NEAR(m.axis[0], std::cos(0.5 * phi), 1e-12);
  EXPECT_NEAR(m.axis[1], std::sin(0.5 * phi), 1e-12);
  // Random cones: every direction in a or b is within the merged cone.
  std::mt19937 gen(3);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto unit = [&] {
    std::array<double, 3> v{g(gen), g(gen), g(gen)};
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    for (double& c : v) c /= l;
    return v;
  };
  auto angle = [](const std::array<double, 3>& x, const std::array<double, 3>& y) {
    const double d = x[0] * y[0] + x[1] * y[1] + x[2] * y[2];
    return std::acos(std::clamp(d, -1.0, 1.0));
  };
  for (int trial = 0; trial < 500; ++trial) {
    NormalCone c1{unit(), 0.6 * u(gen)}, c2{unit(), 0.6 * u(gen)};
    const NormalCone mc = merge(c1, c2);
    for (int s = 0; s < 20; ++s) {
      const auto v = unit();
      for (const NormalCone* c : {&c1, &c2}) {
        if (angle(v, c->axis) <= c->angle) {
          ASSERT_LE(angle(v, mc.axis), mc.angle + 1e-12);
        }
      }
    }
    // The bound on the angle between members of two cones.
    EXPECT_GE(max_angle_between(c1, c2) + 1e-12, angle(c1.axis, c2.axis));
  }
  // Opposite normals give a half-space cone.
  const NormalCone opposite = merge(a, NormalCone{{-1.0, 0.0, 0.0}, 0.0});
  EXPECT_NEAR(opposite.angle, 0.5 * std::numbers::pi, 1e-8);
}
