// Polygon clipping and triangulation against analytic overlap areas.
#include <cmath>
#include <initializer_list>
#include <numbers>
#include <random>

#include <gtest/gtest.h>

#include "seam/geometry/polygon.hpp"

using seam::geometry::area;
using seam::geometry::clip_polygons;
using seam::geometry::Point2;
using seam::geometry::Polygon;
using seam::geometry::signed_area;
using seam::geometry::triangulate_fan;

namespace {

Polygon make(std::initializer_list<Point2> points) {
  Polygon p;
  for (const Point2& x : points) p.push_back(x);
  return p;
}

Polygon rectangle(double x0, double y0, double x1, double y1) {
  return make({{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}});
}

// Regular n-gon with circumradius r about c, first vertex at angle phi.
Polygon regular(int n, double r, Point2 c = {0, 0}, double phi = 0.0) {
  Polygon p;
  for (int i = 0; i < n; ++i) {
    const double t = phi + 2.0 * std::numbers::pi * i / n;
    p.push_back(c + r * Point2(std::cos(t), std::sin(t)));
  }
  return p;
}

Polygon transformed(const Polygon& in, double angle, Point2 about, Point2 shift) {
  Eigen::Matrix2d rot;
  rot << std::cos(angle), -std::sin(angle), std::sin(angle), std::cos(angle);
  Polygon out;
  for (const Point2& x : in) out.push_back(about + rot * (x - about) + shift);
  return out;
}

// Signed distance of x to the edges of a counter-clockwise convex polygon (min over edges).
double inside_distance(const Polygon& p, const Point2& x) {
  double d = 1e300;
  for (int i = 0; i < p.size(); ++i) {
    const Point2 e = p[(i + 1) % p.size()] - p[i];
    const Point2 r = x - p[i];
    d = std::min(d, (e.x() * r.y() - e.y() * r.x()) / e.norm());
  }
  return d;
}

void expect_valid_result(const Polygon& result, const Polygon& a, const Polygon& b) {
  ASSERT_GE(result.size(), 3);
  EXPECT_GT(signed_area(result), 0.0);
  Polygon ca = a, cb = b;
  seam::geometry::make_counter_clockwise(ca);
  seam::geometry::make_counter_clockwise(cb);
  const double scale = std::max(seam::geometry::max_edge_length(a), 1e-300);
  for (const Point2& x : result) {
    EXPECT_GE(inside_distance(ca, x), -1e-9 * scale);
    EXPECT_GE(inside_distance(cb, x), -1e-9 * scale);
  }
}

} // namespace

TEST(ClipPolygons, ShiftedSquares) {
  const Polygon a = rectangle(0, 0, 1, 1);
  const Polygon b = rectangle(0.5, 0.25, 1.5, 1.25);
  const Polygon r = clip_polygons(a, b);
  expect_valid_result(r, a, b);
  EXPECT_NEAR(area(r), 0.5 * 0.75, 1e-15);
  EXPECT_EQ(r.size(), 4);
}

TEST(ClipPolygons, CoincidentSquares) {
  const Polygon a = rectangle(0, 0, 1, 1);
  const Polygon r = clip_polygons(a, a);
  expect_valid_result(r, a, a);
  EXPECT_EQ(r.size(), 4);
  EXPECT_NEAR(area(r), 1.0, 1e-15);
}

TEST(ClipPolygons, CoincidentTrianglesAndHexagons) {
  const Polygon t = make({{0.1, 0.2}, {2.0, -0.3}, {0.7, 1.9}});
  EXPECT_EQ(clip_polygons(t, t).size(), 3);
  EXPECT_NEAR(area(clip_polygons(t, t)), area(t), 1e-14);
  const Polygon h = regular(6, 1.3, {0.2, -0.1}, 0.3);
  EXPECT_EQ(clip_polygons(h, h).size(), 6);
  EXPECT_NEAR(area(clip_polygons(h, h)), 1.5 * std::sqrt(3.0) * 1.3 * 1.3, 1e-14);
}

TEST(ClipPolygons, SharedEdgeWithOverlap) {
  // Square inside a rectangle, sharing its bottom edge and two vertices.
  const Polygon a = rectangle(0, 0, 1, 1);
  const Polygon b = rectangle(0, 0, 1, 2);
  const Polygon r = clip_polygons(b, a);
  expect_valid_result(r, a, b);
  EXPECT_EQ(r.size(), 4);
  EXPECT_NEAR(area(r), 1.0, 1e-15);
  // Triangle sharing two vertices and the diagonal direction with the square.
  const Polygon t = make({{0, 0}, {1, 0}, {1, 1}});
  EXPECT_NEAR(area(clip_polygons(a, t)), 0.5, 1e-15);
  EXPECT_NEAR(area(clip_polygons(t, a)), 0.5, 1e-15);
}

TEST(ClipPolygons, TouchingOnlyIsEmpty) {
  const Polygon a = rectangle(0, 0, 1, 1);
  EXPECT_TRUE(clip_polygons(a, rectangle(1, 0, 2, 1)).empty());            // shared edge
  EXPECT_TRUE(clip_polygons(a, rectangle(1, 0.3, 2, 0.6)).empty());        // part of an edge
  EXPECT_TRUE(clip_polygons(a, rectangle(1, 1, 2, 2)).empty());            // shared vertex
  EXPECT_TRUE(clip_polygons(a, make({{1, 0.5}, {2, 0}, {2, 1}})).empty()); // vertex on edge
  EXPECT_TRUE(clip_polygons(a, rectangle(1 + 1e-12, 0, 2, 1)).empty());    // separated by a hair
  EXPECT_TRUE(clip_polygons(a, rectangle(3, 3, 4, 4)).empty());            // far apart
}

TEST(ClipPolygons, VertexOnEdge) {
  // Triangle with two vertices on the square's top and bottom edges; the overlap is the
  // trapezoid x in [0.5, 1] between y = (x - 0.5)/2 and y = 1 - (x - 0.5)/2.
  const Polygon a = rectangle(0, 0, 1, 1);
  const Polygon t = make({{0.5, 0}, {1.5, 0.5}, {0.5, 1}});
  const Polygon r = clip_polygons(a, t);
  expect_valid_result(r, a, t);
  EXPECT_NEAR(area(r), 0.375, 1e-15);
  EXPECT_EQ(r.size(), 4);
  EXPECT_NEAR(area(clip_polygons(t, a)), 0.375, 1e-15);
}

TEST(ClipPolygons, NearlyParallelEdges) {
  const Polygon a = rectangle(0, 0, 1, 1);
  for (const double angle : {1e-14, -1e-14, 1e-12}) {
    for (const Point2& about : {Point2(0.5, 0.5), Point2(0, 0), Point2(1, 0)}) {
      const Polygon b = transformed(a, angle, about, {0, 0});
      const Polygon r = clip_polygons(a, b);
      expect_valid_result(r, a, b);
      EXPECT_NEAR(area(r), 1.0, 1e-11);
      EXPECT_EQ(r.size(), 4);
    }
  }
  // Shift by much less than the tolerance: the edges are treated as coincident.
  const Polygon r = clip_polygons(a, transformed(a, 0, {0, 0}, {1e-14, -1e-14}));
  EXPECT_NEAR(area(r), 1.0, 1e-13);
  EXPECT_EQ(r.size(), 4);
  // Rotations well above the tolerance: the overlap of a square of apothem h with its rotation
  // by t about the centre is a polygon whose eight edges all touch the circle of radius h,
  // so its area is h^2 * sum over vertices of tan(gap/2) = tan(t/2) + tan(pi/4 - t/2).
  for (const double t : {1e-6, 1e-3, 0.3}) {
    const Polygon b = transformed(a, t, {0.5, 0.5}, {0, 0});
    const Polygon rt = clip_polygons(a, b);
    expect_valid_result(rt, a, b);
    EXPECT_EQ(rt.size(), 8);
    EXPECT_NEAR(area(rt), std::tan(t / 2) + std::tan(std::numbers::pi / 4 - t / 2), 1e-14);
  }
}

TEST(ClipPolygons, OneInsideTheOther) {
  const Polygon a = rectangle(0, 0, 4, 3);
  const Polygon t = make({{1, 1}, {2, 1}, {1.5, 2}});
  EXPECT_NEAR(area(clip_polygons(a, t)), 0.5, 1e-15);
  EXPECT_NEAR(area(clip_polygons(t, a)), 0.5, 1e-15);
  const Polygon h = regular(6, 0.5, {2, 1.5});
  EXPECT_NEAR(area(clip_polygons(a, h)), area(h), 1e-15);
  EXPECT_NEAR(area(clip_polygons(h, a)), area(h), 1e-15);
  // Inscribed: the inner polygon's vertices lie on the outer one's edges.
  const Polygon diamond = make({{2, 0}, {4, 1.5}, {2, 3}, {0, 1.5}});
  EXPECT_NEAR(area(clip_polygons(a, diamond)), 6.0, 1e-14);
  EXPECT_EQ(clip_polygons(a, diamond).size(), 4);
}

TEST(ClipPolygons, RotatedSquaresGiveRegularOctagon) {
  // A square and its 45-degree rotation share the apothem 1/2: a regular octagon of
  // area 8 a^2 tan(pi/8).
  const Polygon a = rectangle(-0.5, -0.5, 0.5, 0.5);
  const Polygon b = transformed(a, std::numbers::pi / 4, {0, 0}, {0, 0});
  const Polygon r = clip_polygons(a, b);
  expect_valid_result(r, a, b);
  EXPECT_EQ(r.size(), 8);
  EXPECT_NEAR(area(r), 2.0 * std::tan(std::numbers::pi / 8), 1e-15);
}

TEST(ClipPolygons, HexagonsGiveRegularDodecagon) {
  // Regular hexagon (circumradius 1, apothem sqrt(3)/2) against its 30-degree rotation:
  // a regular dodecagon of area 12 a^2 tan(pi/12) = 9 (2 - sqrt 3).
  const Polygon a = regular(6, 1.0);
  const Polygon b = regular(6, 1.0, {0, 0}, std::numbers::pi / 6);
  const Polygon r = clip_polygons(a, b);
  expect_valid_result(r, a, b);
  EXPECT_EQ(r.size(), 12);
  EXPECT_NEAR(area(r), 9.0 * (2.0 - std::sqrt(3.0)), 1e-14);
}

TEST(ClipPolygons, StarOfDavid) {
  // Two equilateral triangles, one rotated by 180 degrees: the inner hexagon has 2/3 of the
  // triangle's area.
  const Polygon a = regular(3, 1.0, {0, 0}, std::numbers::pi / 2);
  const Polygon b = regular(3, 1.0, {0, 0}, -std::numbers::pi / 2);
  const Polygon r = clip_polygons(a, b);
  expect_valid_result(r, a, b);
  EXPECT_EQ(r.size(), 6);
  EXPECT_NEAR(area(r), std::sqrt(3.0) / 2.0, 1e-15);
}

TEST(ClipPolygons, TrianglesSharingAnEdge) {
  const Polygon a = make({{0, 0}, {1, 0}, {0, 1}});
  const Polygon b = make({{0, 0}, {1, 0}, {1, 1}});
  EXPECT_NEAR(area(clip_polygons(a, b)), 0.25, 1e-15);
}

TEST(ClipPolygons, OrientationAndScaleIndependence) {
  const Polygon a = regular(6, 1.0);
  const Polygon b = regular(6, 1.0, {0, 0}, std::numbers::pi / 6);
  Polygon a_cw;
  for (int i = a.size() - 1; i >= 0; --i) a_cw.push_back(a[i]);
  const double exact = 9.0 * (2.0 - std::sqrt(3.0));
  const Polygon r = clip_polygons(a_cw, b);
  EXPECT_GT(signed_area(r), 0.0);
  EXPECT_NEAR(area(r), exact, 1e-14);
  // Far from the origin and at micrometre scale: tolerances are relative.
  for (const double scale : {1e-6, 1.0, 1e4}) {
    for (const Point2& shift : {Point2(0, 0), Point2(1e6, -3e5)}) {
      Polygon as, bs;
      for (const Point2& x : a) as.push_back(scale * x + shift);
      for (const Point2& x : b) bs.push_back(scale * x + shift);
      const Polygon rs = clip_polygons(as, bs);
      EXPECT_EQ(rs.size(), 12) << scale;
      EXPECT_NEAR(area(rs) / (scale * scale), exact, 1e-9 * (1.0 + shift.norm() / scale));
    }
  }
}

TEST(ClipPolygons, RotatedSquareAgainstItsTranslate) {
  // A unit square with axes e1, e2 against its translate by v overlaps in a rectangle of area
  // (1 - |v.e1|)(1 - |v.e2|).
  std::mt19937 rng(42);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int trial = 0; trial < 200; ++trial) {
    const double angle = std::numbers::pi * u(rng);
    const Point2 v(0.9 * u(rng), 0.9 * u(rng));
    const Point2 e1(std::cos(angle), std::sin(angle)), e2(-e1.y(), e1.x());
    Polygon a;
    for (const Point2& x : {Point2(0, 0), Point2(1, 0), Point2(1, 1), Point2(0, 1)}) {
      a.push_back(x.x() * e1 + x.y() * e2);
    }
    const Polygon b = transformed(a, 0, {0, 0}, v);
    const double exact =
        std::max(0.0, 1 - std::abs(v.dot(e1))) * std::max(0.0, 1 - std::abs(v.dot(e2)));
    const Polygon r = clip_polygons(a, b);
    EXPECT_NEAR(area(r), exact, 1e-14) << trial;
    if (!r.empty()) expect_valid_result(r, a, b);
  }
}

TEST(ClipPolygons, RandomConvexPolygonsAreSymmetric) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  auto random_convex = [&](int n, Point2 c) {
    // Sorted random angles on a perturbed circle give a convex polygon.
    std::vector<double> t(static_cast<std::size_t>(n));
    for (double& x : t) x = 2.0 * std::numbers::pi * u(rng);
    std::sort(t.begin(), t.end());
    const double r = 0.5 + u(rng);
    Polygon p;
    for (double x : t) p.push_back(c + r * Point2(std::cos(x), std::sin(x)));
    return p;
  };
  int n_nonempty = 0;
  for (int trial = 0; trial < 500; ++trial) {
    const Polygon a = random_convex(3 + trial % 7, {0, 0});
    const Polygon b = random_convex(3 + (trial / 7) % 7, {u(rng) - 0.5, u(rng) - 0.5});
    if (area(a) < 1e-3 || area(b) < 1e-3) continue;
    const Polygon ab = clip_polygons(a, b);
    const Polygon ba = clip_polygons(b, a);
    EXPECT_NEAR(area(ab), area(ba), 1e-13);
    EXPECT_LE(area(ab), std::min(area(a), area(b)) + 1e-14);
    if (!ab.empty()) {
      ++n_nonempty;
      expect_valid_result(ab, a, b);
    }
  }
  EXPECT_GT(n_nonempty, 200);
}

TEST(TriangulateFan, CellAreasSumToPolygonArea) {
  const Polygon tri = make({{0, 0}, {2, 0}, {0, 1}});
  ASSERT_EQ(triangulate_fan(tri).size(), 1);
  EXPECT_NEAR(triangulate_fan(tri)[0].area(), 1.0, 1e-15);
  for (int n = 4; n <= 12; ++n) {
    const Polygon p = regular(n, 1.7, {3, -2}, 0.1 * n);
    const auto cells = triangulate_fan(p);
    ASSERT_EQ(cells.size(), n);
    double sum = 0.0;
    for (const auto& c : cells) {
      EXPECT_GT(c.area(), 0.0);
      sum += c.area();
    }
    EXPECT_NEAR(sum, 0.5 * n * 1.7 * 1.7 * std::sin(2 * std::numbers::pi / n), 1e-13);
  }
  // The clip of two hexagons: cells cover the clip polygon.
  const Polygon r = clip_polygons(regular(6, 1.0), regular(6, 1.0, {0.3, 0.2}, 0.4));
  double sum = 0.0;
  for (const auto& c : triangulate_fan(r)) sum += c.area();
  EXPECT_NEAR(sum, area(r), 1e-14);
}

TEST(PolygonHelpers, AreaAndCentroid) {
  const Polygon r = rectangle(1, 2, 4, 3);
  EXPECT_NEAR(signed_area(r), 3.0, 1e-15);
  EXPECT_TRUE(seam::geometry::centroid(r).isApprox(Point2(2.5, 2.5), 1e-15));
  // A triangle's centroid is its vertex mean.
  const Polygon t = make({{0, 0}, {3, 0}, {0, 6}});
  EXPECT_TRUE(seam::geometry::centroid(t).isApprox(Point2(1, 2), 1e-15));
  // Trapezoid (0,0),(4,0),(3,2),(1,2): area 6, centroid y = h(b + 2a)/(3(a + b)) with the
  // bottom b = 4, top a = 2 -> 2 * 8 / 18 = 8/9.
  const Polygon z = make({{0, 0}, {4, 0}, {3, 2}, {1, 2}});
  EXPECT_NEAR(area(z), 6.0, 1e-15);
  EXPECT_NEAR(seam::geometry::centroid(z).x(), 2.0, 1e-15);
  EXPECT_NEAR(seam::geometry::centroid(z).y(), 8.0 / 9.0, 1e-15);
  EXPECT_NEAR(seam::geometry::min_edge_length(z), 2.0, 1e-15);
  EXPECT_NEAR(seam::geometry::max_edge_length(z), 4.0, 1e-15);
}

TEST(ClipPolygons, NearlyDegenerateConfigurationsStayClean) {
  // Coincident polygons perturbed by rotations and shifts around the merge tolerance: the
  // result must keep the exact area to first order, have no near-duplicate vertices and
  // turn strictly left at every vertex (no slivers or spikes from nearly parallel edges).
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::uniform_int_distribution<int> exponent(-16, -7);
  for (int trial = 0; trial < 2000; ++trial) {
    const int n = 3 + trial % 6;
    const Polygon a = regular(n, 1.0, {0.1, -0.2}, u(rng));
    const double angle = std::pow(10.0, exponent(rng)) * u(rng);
    const Point2 shift = std::pow(10.0, exponent(rng)) * Point2(u(rng), u(rng));
    const Polygon b = transformed(a, angle, {u(rng), u(rng)}, shift);
    const Polygon r = clip_polygons(a, b);
    ASSERT_GE(r.size(), 3) << trial;
    EXPECT_LE(r.size(), 2 * n);
    EXPECT_NEAR(area(r), area(a), 1e-6 * area(a)) << trial;
    const double edge = seam::geometry::min_edge_length(a);
    for (int i = 0; i < r.size(); ++i) {
      const Point2 p = r[(i + r.size() - 1) % r.size()], q = r[i], s = r[(i + 1) % r.size()];
      EXPECT_GT((q - p).norm(), 1e-9 * edge) << trial;
      const Point2 e1 = q - p, e2 = s - q;
      // Height of q above the chord p-s: clearly positive for a clean convex polygon.
      const double turn = (e1.x() * e2.y() - e1.y() * e2.x()) / (s - p).norm();
      EXPECT_GT(turn, 1e-9 * edge) << trial << " vertex " << i << " of " << r.size();
    }
  }
}
