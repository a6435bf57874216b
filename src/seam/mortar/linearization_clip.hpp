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
#include <type_traits>
#include <utility>

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

/// The clip, the signed area and the centroid below are written once on the polygon container
/// P: geometry::StaticVector (the mortar linearization) or std::vector (the weighted gaps of
/// contact/gap_blocks_3d.cpp, whose Hyper<36> vertices do not fit fixed storage). A vertex v
/// offers v(0), v(1), v + w, v - w, s * v and v / s: Vector<S, 2> or gap_vectors::V2<S>.
namespace clip_detail {

constexpr int work_capacity = 2 * geometry::max_polygon_vertices + 4;
template <class S> using WorkPolygon = geometry::StaticVector<Vector<S, 2>, work_capacity>;

template <class A> Eigen::Vector2d vertex_value(const A& a) {
  return {value_of(a(0)), value_of(a(1))};
}
template <class A, class B> auto vertex_cross(const A& a, const B& b) {
  return a(0) * b(1) - a(1) * b(0);
}
template <class A> auto vertex_norm(const A& a) {
  using std::sqrt;
  return sqrt(a(0) * a(0) + a(1) * a(1));
}
template <class V> V zero_vertex() {
  if constexpr (requires { V::Zero(); }) {
    return V::Zero();
  } else {
    return V{};
  }
}
template <class P> using VertexOf = std::decay_t<decltype(std::declval<const P&>()[0])>;
template <class P> using ScalarOf = std::decay_t<decltype(std::declval<const VertexOf<P>&>()(0))>;
template <class P> int count(const P& p) {
  return static_cast<int>(p.size());
}

template <class A, class B> double distance(const A& a, const B& b) {
  return (vertex_value(a) - vertex_value(b)).norm();
}

template <class P> ScalarOf<P> signed_area_of(const P& p) {
  using S = ScalarOf<P>;
  S twice = 0.0;
  for (int i = 1; i + 1 < count(p); ++i) twice += vertex_cross(p[i] - p[0], p[i + 1] - p[0]);
  return S(0.5 * twice);
}

template <class P> double min_edge_of(const P& p) {
  const int n = count(p);
  if (n < 2) return 0.0;
  double m = distance(p[0], p[n - 1]);
  for (int i = 0; i + 1 < n; ++i) m = std::min(m, distance(p[i + 1], p[i]));
  return m;
}

template <class P> double max_edge_of(const P& p) {
  const int n = count(p);
  if (n < 2) return 0.0;
  double m = distance(p[0], p[n - 1]);
  for (int i = 0; i + 1 < n; ++i) m = std::max(m, distance(p[i + 1], p[i]));
  return m;
}

template <class P> void reverse_in_place(P& p) {
  for (int i = 0, j = count(p) - 1; i < j; ++i, --j) std::swap(p[i], p[j]);
}

template <class P, class X> void checked_push(P& p, const X& x) {
  if constexpr (requires { p.full(); }) {
    if (p.full()) SEAM_THROW(InternalError, "clip_polygons: working polygon capacity exceeded");
  }
  p.push_back(x);
}

template <class P> void erase_at(P& p, int i) {
  if constexpr (requires { p.erase(i); }) {
    p.erase(i);
  } else {
    p.erase(p.begin() + i);
  }
}

template <class P> void merge_close_vertices(P& p, double tol) {
  P out;
  for (const auto& x : p) {
    if (out.empty() || distance(x, out.back()) > tol) out.push_back(x);
  }
  while (count(out) > 1 && distance(out.back(), out[0]) <= tol) out.pop_back();
  p = std::move(out);
}

template <class P> void remove_collinear_vertices(P& p, double tol) {
  bool changed = true;
  while (changed && count(p) >= 3) {
    changed = false;
    const int n = count(p);
    for (int i = 0; i < n; ++i) {
      const Eigen::Vector2d prev = vertex_value(p[(i + n - 1) % n]);
      const Eigen::Vector2d next = vertex_value(p[(i + 1) % n]);
      const Eigen::Vector2d here = vertex_value(p[i]);
      const Eigen::Vector2d chord = next - prev;
      const double length = chord.norm();
      const double d = length > tol ? std::abs(geometry::cross2(chord, here - prev)) / length
                                    : (here - prev).norm();
      if (d <= tol) {
        erase_at(p, i);
        changed = true;
        break;
      }
    }
  }
}

} // namespace clip_detail

/// Area centroid (geometry::centroid); the vertex average when the area vanishes.
template <class P> clip_detail::VertexOf<P> centroid_of(const P& polygon) {
  using namespace clip_detail;
  using V = VertexOf<P>;
  using S = ScalarOf<P>;
  const int n = count(polygon);
  if (n == 0) return zero_vertex<V>();
  const V origin = polygon[0];
  V vertex_sum = zero_vertex<V>();
  for (const auto& x : polygon) vertex_sum = vertex_sum + (x - origin);
  S twice_area = 0.0;
  V moment = zero_vertex<V>();
  for (int i = 1; i + 1 < n; ++i) {
    const V u = polygon[i] - origin;
    const V v = polygon[i + 1] - origin;
    const S twice = vertex_cross(u, v);
    twice_area += twice;
    moment = moment + twice * (u + v) / 3.0;
  }
  const double scale = std::max(max_edge_of(polygon), 1e-300);
  if (std::abs(value_of(twice_area)) <= 1e-14 * scale * scale)
    return origin + vertex_sum / static_cast<double>(n);
  return origin + moment / twice_area;
}

/// geometry::clip_polygons on the vertices of P (Sutherland & Hodgman 1974 with tolerance
/// classification), working in polygons of type Work (their capacity bounds the intermediate
/// polygons).
template <class Work, class P>
P clip_polygons_in(const P& subject, const P& clipper, const geometry::ClipOptions& options) {
  using namespace clip_detail;
  using V = VertexOf<P>;
  using S = ScalarOf<P>;
  SEAM_CHECK(count(subject) <= geometry::max_clip_input_vertices &&
                 count(clipper) <= geometry::max_clip_input_vertices,
             InputError, "clip_polygons: inputs may have at most ",
             geometry::max_clip_input_vertices, " vertices");
  const double input_tol =
      options.merge_tolerance * std::min(max_edge_of(subject), max_edge_of(clipper));
  Work s;
  for (const auto& x : subject) s.push_back(x);
  merge_close_vertices(s, input_tol);
  Work c;
  for (const auto& x : clipper) c.push_back(x);
  merge_close_vertices(c, input_tol);
  if (count(s) < 3 || count(c) < 3) return {};

  const double subject_area = std::abs(value_of(signed_area_of(s)));
  if (value_of(signed_area_of(s)) < 0.0) reverse_in_place(s);
  if (value_of(signed_area_of(c)) < 0.0) reverse_in_place(c);
  if (subject_area == 0.0 || value_of(signed_area_of(c)) == 0.0) return {};

  const double tol = options.merge_tolerance * std::min(min_edge_of(s), min_edge_of(c));
  for (int k = 0; k < count(c); ++k) {
    const V& a = c[k];
    const V edge = c[(k + 1) % count(c)] - a;
    const S length = vertex_norm(edge);
    // The signed distance of subject vertex i from the clipping line, zero within tol.
    const auto line_distance = [&](int i) {
      const S di = vertex_cross(edge, s[i] - a) / length;
      return std::abs(value_of(di)) <= tol ? S(0.0) : di;
    };
    const int n = count(s);
    const S d_first = line_distance(0);
    S dc = d_first;
    Work out;
    for (int i = 0; i < n; ++i) {
      const int j = (i + 1) % n;
      S dn = j == 0 ? d_first : line_distance(j);
      if (value_of(dc) >= 0.0) checked_push(out, s[i]);
      if ((value_of(dc) > 0.0 && value_of(dn) < 0.0) ||
          (value_of(dc) < 0.0 && value_of(dn) > 0.0)) {
        const S t = dc / (dc - dn);
        checked_push(out, V(s[i] + t * (s[j] - s[i])));
      }
      dc = std::move(dn);
    }
    merge_close_vertices(out, tol);
    s = std::move(out);
    if (count(s) < 3) return {};
  }
  remove_collinear_vertices(s, tol);
  if (count(s) < 3) return {};
  if (value_of(signed_area_of(s)) <= options.min_relative_area * subject_area) return {};
  if (count(s) > geometry::max_polygon_vertices) {
    SEAM_THROW(InternalError, "clip_polygons: result has ", count(s), " vertices");
  }
  if constexpr (std::is_same_v<Work, P>) {
    return s;
  } else {
    P result;
    for (const auto& x : s) result.push_back(x);
    return result;
  }
}

template <class S> S signed_area_t(const PolygonT<S>& p) {
  return clip_detail::signed_area_of(p);
}

template <class S> Vector<S, 2> centroid_t(const PolygonT<S>& polygon) {
  return centroid_of(polygon);
}

/// geometry::clip_polygons on S in fixed-capacity polygons.
template <class S>
PolygonT<S> clip_polygons_t(const PolygonT<S>& subject, const PolygonT<S>& clipper,
                            const geometry::ClipOptions& options) {
  return clip_polygons_in<clip_detail::WorkPolygon<S>>(subject, clipper, options);
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
