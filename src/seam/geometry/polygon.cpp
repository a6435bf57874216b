#include "seam/geometry/polygon.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace seam::geometry {

namespace {

double cross(const Point2& a, const Point2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

// Working storage for the clip: Sutherland–Hodgman adds at most one vertex per clipping edge
// to a convex polygon; the margin covers the nearly degenerate cases that tolerance-snapped
// classification can produce before duplicates are merged again.
constexpr int work_capacity = 2 * max_polygon_vertices + 4;
using WorkPolygon = StaticVector<Point2, work_capacity>;

template <class P> double signed_area_of(const P& p) {
  // Shoelace about the first vertex: translation-invariant, so far-from-origin polygons do not
  // lose digits to cancellation.
  double twice = 0.0;
  for (int i = 1; i + 1 < p.size(); ++i) twice += cross(p[i] - p[0], p[i + 1] - p[0]);
  return 0.5 * twice;
}

// Shortest and longest edge (including the closing edge) in one pass over squared lengths.
template <class P> void edge_length_range(const P& p, double& shortest, double& longest) {
  double lo = (p[0] - p[p.size() - 1]).squaredNorm(), hi = lo;
  for (int i = 0; i + 1 < p.size(); ++i) {
    const double l2 = (p[i + 1] - p[i]).squaredNorm();
    lo = std::min(lo, l2);
    hi = std::max(hi, l2);
  }
  shortest = std::sqrt(lo);
  longest = std::sqrt(hi);
}

template <class P> double min_edge_of(const P& p) {
  if (p.size() < 2) return 0.0;
  double m = (p[0] - p[p.size() - 1]).squaredNorm();
  for (int i = 0; i + 1 < p.size(); ++i) m = std::min(m, (p[i + 1] - p[i]).squaredNorm());
  return std::sqrt(m);
}

template <class P> void reverse_in_place(P& p) {
  for (int i = 0, j = p.size() - 1; i < j; ++i, --j) std::swap(p[i], p[j]);
}

template <class P> void checked_push(P& p, const Point2& x) {
  if (p.full()) SEAM_THROW(InternalError, "clip_polygons: working polygon capacity exceeded");
  p.push_back(x);
}

// Drop each vertex that lies within tol of its (cyclic) predecessor; the first of a cluster
// survives. In place: the kept vertices move forward.
template <class P> void merge_close_vertices(P& p, double tol) {
  const double tol2 = tol * tol; // compare squared distances: no square root per vertex
  const int n = p.size();
  int kept = 0;
  for (int i = 0; i < n; ++i) {
    if (kept == 0 || (p[i] - p[kept - 1]).squaredNorm() > tol2) p[kept++] = p[i];
  }
  while (kept > 1 && (p[kept - 1] - p[0]).squaredNorm() <= tol2) --kept;
  while (p.size() > kept) p.pop_back();
}

// Drop vertices within tol of the line through their neighbours: they add no area, and a
// fan about the centroid would otherwise contain slivers.
template <class P> void remove_collinear_vertices(P& p, double tol) {
  bool changed = true;
  while (changed && p.size() >= 3) {
    changed = false;
    const int n = p.size();
    for (int i = 0; i < n; ++i) {
      const Point2& prev = p[i == 0 ? n - 1 : i - 1];
      const Point2& next = p[i + 1 == n ? 0 : i + 1];
      const Point2 chord = next - prev;
      const double length = chord.norm();
      const double distance =
          length > tol ? std::abs(cross(chord, p[i] - prev)) / length : (p[i] - prev).norm();
      if (distance <= tol) {
        p.erase(i);
        changed = true;
        break;
      }
    }
  }
}

template <class P> void copy_into(const Polygon& in, P& out) {
  out.clear();
  for (const Point2& x : in) out.push_back(x);
}

} // namespace

double signed_area(const Polygon& polygon) {
  return signed_area_of(polygon);
}

double area(const Polygon& polygon) {
  return std::abs(signed_area_of(polygon));
}

Point2 centroid(const Polygon& polygon) {
  const int n = polygon.size();
  if (n == 0) return Point2::Zero();
  const Point2 origin = polygon[0];
  Point2 vertex_sum = Point2::Zero();
  for (const Point2& x : polygon) vertex_sum += x - origin;
  // Sum over the fan triangles (origin, p_i, p_{i+1}) of area * triangle centroid.
  double twice_area = 0.0;
  Point2 moment = Point2::Zero();
  for (int i = 1; i + 1 < n; ++i) {
    const Point2 u = polygon[i] - origin;
    const Point2 v = polygon[i + 1] - origin;
    const double twice = cross(u, v);
    twice_area += twice;
    moment += twice * (u + v) / 3.0;
  }
  const double scale = std::max(max_edge_length(polygon), 1e-300);
  if (std::abs(twice_area) <= 1e-14 * scale * scale) return origin + vertex_sum / n;
  return origin + moment / twice_area;
}

void make_counter_clockwise(Polygon& polygon) {
  if (signed_area_of(polygon) < 0.0) reverse_in_place(polygon);
}

double min_edge_length(const Polygon& polygon) {
  return min_edge_of(polygon);
}

double max_edge_length(const Polygon& polygon) {
  const int n = polygon.size();
  if (n < 2) return 0.0;
  double m = (polygon[0] - polygon[n - 1]).squaredNorm();
  for (int i = 0; i + 1 < n; ++i) m = std::max(m, (polygon[i + 1] - polygon[i]).squaredNorm());
  return std::sqrt(m);
}

Polygon clip_polygons(const Polygon& subject, const Polygon& clipper, const ClipOptions& options) {
  SEAM_CHECK(subject.size() <= max_clip_input_vertices && clipper.size() <= max_clip_input_vertices,
             InputError, "clip_polygons: inputs may have at most ", max_clip_input_vertices,
             " vertices (got ", subject.size(), " and ", clipper.size(), ")");
  if (subject.size() < 3 || clipper.size() < 3) return {};
  double subject_min = 0.0, subject_max = 0.0, clipper_min = 0.0, clipper_max = 0.0;
  edge_length_range(subject, subject_min, subject_max);
  edge_length_range(clipper, clipper_min, clipper_max);
  const double input_tol = options.merge_tolerance * std::min(subject_max, clipper_max);

  WorkPolygon s;
  copy_into(subject, s);
  merge_close_vertices(s, input_tol);
  WorkPolygon c;
  copy_into(clipper, c);
  merge_close_vertices(c, input_tol);
  if (s.size() < 3 || c.size() < 3) return {};

  const double subject_signed_area = signed_area_of(s);
  const double clipper_signed_area = signed_area_of(c);
  const double subject_area = std::abs(subject_signed_area);
  if (subject_signed_area < 0.0) reverse_in_place(s);
  if (clipper_signed_area < 0.0) reverse_in_place(c);
  if (subject_area == 0.0 || clipper_signed_area == 0.0) return {};

  // The tolerance is relative to the shortest edge so it scales with the mesh and never
  // swallows a genuine edge (ALGORITHMS.md §2, step 4: tol = 1e-8 * min edge length). Merging
  // rarely removes a vertex; only then are the edges measured again.
  if (s.size() != subject.size()) subject_min = min_edge_of(s);
  if (c.size() != clipper.size()) clipper_min = min_edge_of(c);
  const double tol = options.merge_tolerance * std::min(subject_min, clipper_min);

  std::array<double, work_capacity> distance;
  // Each clipping edge writes the next polygon into the other buffer.
  WorkPolygon buffer;
  WorkPolygon* current = &s;
  WorkPolygon* next = &buffer;
  for (int k = 0; k < c.size(); ++k) {
    const WorkPolygon& p = *current;
    const Point2& a = c[k];
    const Point2 edge = c[k + 1 == c.size() ? 0 : k + 1] - a;
    const double length = edge.norm();
    const int n = p.size();
    // Signed distance to the clipping line, positive on the inner (left) side. Points within
    // tol count as on the line: this is what makes coincident and nearly parallel edges safe,
    // since no intersection of two almost parallel lines is ever computed from them.
    for (int i = 0; i < n; ++i) {
      const double d = cross(edge, p[i] - a) / length;
      distance[static_cast<std::size_t>(i)] = std::abs(d) <= tol ? 0.0 : d;
    }
    WorkPolygon& out = *next;
    out.clear();
    for (int i = 0; i < n; ++i) {
      const int j = i + 1 == n ? 0 : i + 1;
      const double dc = distance[static_cast<std::size_t>(i)];
      const double dn = distance[static_cast<std::size_t>(j)];
      if (dc >= 0.0) checked_push(out, p[i]);
      if ((dc > 0.0 && dn < 0.0) || (dc < 0.0 && dn > 0.0)) {
        checked_push(out, p[i] + (dc / (dc - dn)) * (p[j] - p[i]));
      }
    }
    merge_close_vertices(out, tol);
    std::swap(current, next);
    if (current->size() < 3) return {};
  }
  WorkPolygon& clipped = *current;

  remove_collinear_vertices(clipped, tol);
  if (clipped.size() < 3) return {};
  const double result_area = signed_area_of(clipped);
  if (result_area <= options.min_relative_area * subject_area) return {};
  if (clipped.size() > max_polygon_vertices) {
    SEAM_THROW(InternalError, "clip_polygons: result has ", clipped.size(), " vertices");
  }
  Polygon result;
  for (const Point2& x : clipped) result.push_back(x);
  return result;
}

double Triangle2::area() const {
  return 0.5 * cross(b - a, c - a);
}

TriangleList triangulate_fan(const Polygon& polygon) {
  TriangleList cells;
  const int n = polygon.size();
  if (n < 3) return cells;
  if (n == 3) {
    cells.push_back({polygon[0], polygon[1], polygon[2]});
    return cells;
  }
  const Point2 center = centroid(polygon);
  for (int i = 0; i < n; ++i)
    cells.push_back({center, polygon[i], polygon[i + 1 == n ? 0 : i + 1]});
  return cells;
}

} // namespace seam::geometry
