#pragma once
// The auxiliary plane, convex polygon clipping and fan triangulation of 3D mortar integration
// (Puso & Laursen 2004; Popp et al. 2010; ALGORITHMS.md §2 steps 2-5) on a scalar type S,
// following geometry/plane.cpp and geometry/polygon.cpp decision for decision. Every
// classification (inside/outside a clipping line, merging, collinearity, orientation) looks
// at values, so the combinatorics are frozen at the evaluation point; the vertices that come
// out — input vertices or intersections s_i + d_i / (d_i - d_j) (s_j - s_i) of an edge with a
// clipping line — carry the derivatives of the smooth branch taken.
#include <algorithm>
#include <array>
#include <cmath>

#include "seam/common/error.hpp"
#include "seam/geometry/polygon.hpp"
#include "seam/geometry/static_vector.hpp"
#include "seam/mortar/linearization_kernels.hpp"

namespace seam::mortar::ad {

template <class S> struct PlaneT {
  Vector<S, 3> origin;
  Vector<S, 3> normal; ///< unit
  Vector<S, 3> t1;
  Vector<S, 3> t2;

  Vector<S, 2> to_local(const Vector<S, 3>& x) const {
    const Vector<S, 3> r = x - origin;
    return {dot(r, t1), dot(r, t2)};
  }
  Vector<S, 3> to_global(const Vector<S, 2>& u) const {
    Vector<S, 3> x = origin;
    for (int a = 0; a < 3; ++a) {
      add_product(x(a), u(0), t1(a));
      add_product(x(a), u(1), t2(a));
    }
    return x;
  }
};

/// geometry::make_plane on S: the first axis comes from the coordinate axis least aligned with
/// the normal (chosen on values), made orthogonal to the normal.
template <class S> PlaneT<S> make_plane_t(const Vector<S, 3>& origin, const Vector<S, 3>& normal) {
  PlaneT<S> plane;
  plane.origin = origin;
  plane.normal = normalized(normal);
  int axis = 0;
  values(plane.normal).cwiseAbs().minCoeff(&axis);
  Vector<S, 3> e = Vector<S, 3>::Zero();
  e(axis) = 1.0;
  e -= plane.normal(axis) * plane.normal;
  plane.t1 = normalized(e);
  plane.t2 = cross3<S>(plane.normal, plane.t1);
  return plane;
}

template <class S>
using PolygonT = geometry::StaticVector<Vector<S, 2>, geometry::max_polygon_vertices>;

namespace clip_detail {

constexpr int work_capacity = 2 * geometry::max_polygon_vertices + 4;
template <class S> using WorkPolygon = geometry::StaticVector<Vector<S, 2>, work_capacity>;

template <class S> double distance(const Vector<S, 2>& a, const Vector<S, 2>& b) {
  return (values(a) - values(b)).norm();
}

template <class P> auto signed_area_of(const P& p) {
  using S = std::decay_t<decltype(p[0](0))>;
  S twice = 0.0;
  for (int i = 1; i + 1 < p.size(); ++i) twice += cross2<S>(p[i] - p[0], p[i + 1] - p[0]);
  return S(0.5 * twice);
}

template <class P> double min_edge_of(const P& p) {
  if (p.size() < 2) return 0.0;
  double m = distance(p[0], p[p.size() - 1]);
  for (int i = 0; i + 1 < p.size(); ++i) m = std::min(m, distance(p[i + 1], p[i]));
  return m;
}

template <class P> double max_edge_of(const P& p) {
  if (p.size() < 2) return 0.0;
  double m = distance(p[0], p[p.size() - 1]);
  for (int i = 0; i + 1 < p.size(); ++i) m = std::max(m, distance(p[i + 1], p[i]));
  return m;
}

template <class P> void reverse_in_place(P& p) {
  for (int i = 0, j = p.size() - 1; i < j; ++i, --j) std::swap(p[i], p[j]);
}

template <class P, class X> void checked_push(P& p, const X& x) {
  if (p.full()) SEAM_THROW(InternalError, "clip_polygons: working polygon capacity exceeded");
  p.push_back(x);
}

template <class P> void merge_close_vertices(P& p, double tol) {
  P out;
  for (const auto& x : p) {
    if (out.empty() || distance(x, out.back()) > tol) out.push_back(x);
  }
  while (out.size() > 1 && distance(out.back(), out[0]) <= tol) out.pop_back();
  p = out;
}

template <class P> void remove_collinear_vertices(P& p, double tol) {
  bool changed = true;
  while (changed && p.size() >= 3) {
    changed = false;
    const int n = p.size();
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d prev = values(p[(i + n - 1) % n]);
      const Eigen::Vector2d next = values(p[(i + 1) % n]);
      const Eigen::Vector2d here = values(p[i]);
      const Eigen::Vector2d chord = next - prev;
      const double length = chord.norm();
      const double d = length > tol ? std::abs(geometry::cross2(chord, here - prev)) / length
                                    : (here - prev).norm();
      if (d <= tol) {
        p.erase(i);
        changed = true;
        break;
      }
    }
  }
}

} // namespace clip_detail

template <class S> S signed_area_t(const PolygonT<S>& p) {
  return clip_detail::signed_area_of(p);
}

/// Area centroid (geometry::centroid); the vertex average when the area vanishes.
template <class S> Vector<S, 2> centroid_t(const PolygonT<S>& polygon) {
  const int n = polygon.size();
  if (n == 0) return Vector<S, 2>::Zero();
  const Vector<S, 2> origin = polygon[0];
  Vector<S, 2> vertex_sum = Vector<S, 2>::Zero();
  for (const auto& x : polygon) vertex_sum += x - origin;
  S twice_area = 0.0;
  Vector<S, 2> moment = Vector<S, 2>::Zero();
  for (int i = 1; i + 1 < n; ++i) {
    const Vector<S, 2> u = polygon[i] - origin;
    const Vector<S, 2> v = polygon[i + 1] - origin;
    const S twice = cross2<S>(u, v);
    twice_area += twice;
    moment += twice * (u + v) / 3.0;
  }
  const double scale = std::max(clip_detail::max_edge_of(polygon), 1e-300);
  if (std::abs(value_of(twice_area)) <= 1e-14 * scale * scale)
    return origin + vertex_sum / static_cast<double>(n);
  return origin + moment / twice_area;
}

/// geometry::clip_polygons on S (Sutherland & Hodgman 1974 with tolerance classification).
template <class S>
PolygonT<S> clip_polygons_t(const PolygonT<S>& subject, const PolygonT<S>& clipper,
                            const geometry::ClipOptions& options) {
  using namespace clip_detail;
  SEAM_CHECK(subject.size() <= geometry::max_clip_input_vertices &&
                 clipper.size() <= geometry::max_clip_input_vertices,
             InputError, "clip_polygons: inputs may have at most ",
             geometry::max_clip_input_vertices, " vertices");
  const double input_tol =
      options.merge_tolerance * std::min(max_edge_of(subject), max_edge_of(clipper));
  WorkPolygon<S> s;
  for (const auto& x : subject) s.push_back(x);
  merge_close_vertices(s, input_tol);
  WorkPolygon<S> c;
  for (const auto& x : clipper) c.push_back(x);
  merge_close_vertices(c, input_tol);
  if (s.size() < 3 || c.size() < 3) return {};

  const double subject_area = std::abs(value_of(signed_area_of(s)));
  if (value_of(signed_area_of(s)) < 0.0) reverse_in_place(s);
  if (value_of(signed_area_of(c)) < 0.0) reverse_in_place(c);
  if (subject_area == 0.0 || value_of(signed_area_of(c)) == 0.0) return {};

  const double tol = options.merge_tolerance * std::min(min_edge_of(s), min_edge_of(c));
  std::array<S, work_capacity> d{};
  for (int k = 0; k < c.size(); ++k) {
    const Vector<S, 2>& a = c[k];
    const Vector<S, 2> edge = c[(k + 1) % c.size()] - a;
    const S length = norm(edge);
    const int n = s.size();
    for (int i = 0; i < n; ++i) {
      const S di = cross2<S>(edge, s[i] - a) / length;
      d[static_cast<std::size_t>(i)] = std::abs(value_of(di)) <= tol ? S(0.0) : di;
    }
    WorkPolygon<S> out;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      const S& dc = d[static_cast<std::size_t>(i)];
      const S& dn = d[static_cast<std::size_t>(j)];
      if (value_of(dc) >= 0.0) checked_push(out, s[i]);
      if ((value_of(dc) > 0.0 && value_of(dn) < 0.0) ||
          (value_of(dc) < 0.0 && value_of(dn) > 0.0)) {
        const S t = dc / (dc - dn);
        checked_push(out, Vector<S, 2>(s[i] + t * (s[j] - s[i])));
      }
    }
    merge_close_vertices(out, tol);
    s = out;
    if (s.size() < 3) return {};
  }
  remove_collinear_vertices(s, tol);
  if (s.size() < 3) return {};
  if (value_of(signed_area_of(s)) <= options.min_relative_area * subject_area) return {};
  if (s.size() > geometry::max_polygon_vertices) {
    SEAM_THROW(InternalError, "clip_polygons: result has ", s.size(), " vertices");
  }
  PolygonT<S> result;
  for (const auto& x : s) result.push_back(x);
  return result;
}

template <class S> struct TriangleT {
  Vector<S, 2> a, b, c;
  S area() const { return 0.5 * cross2<S>(b - a, c - a); }
};
template <class S>
using TriangleListT = geometry::StaticVector<TriangleT<S>, geometry::max_polygon_vertices>;

/// geometry::triangulate_fan on S: a triangle stays one cell, otherwise a fan about the
/// area centroid.
template <class S> TriangleListT<S> triangulate_fan_t(const PolygonT<S>& polygon) {
  TriangleListT<S> cells;
  const int n = polygon.size();
  if (n < 3) return cells;
  if (n == 3) {
    cells.push_back({polygon[0], polygon[1], polygon[2]});
    return cells;
  }
  const Vector<S, 2> center = centroid_t(polygon);
  for (int i = 0; i < n; ++i) cells.push_back({center, polygon[i], polygon[(i + 1) % n]});
  return cells;
}

} // namespace seam::mortar::ad
