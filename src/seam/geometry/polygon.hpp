#pragma once
// Convex polygons in a plane: area, centroid, clipping and triangulation into integration
// cells — steps 4 and 5 of 3D segment-based mortar integration (Puso & Laursen 2004;
// Popp et al. 2010; ALGORITHMS.md §2). Everything lives in fixed-capacity storage.
#include <Eigen/Core>

#include "seam/geometry/static_vector.hpp"

namespace seam::geometry {

using Point2 = Eigen::Vector2d;

/// Largest polygon handled: the clip of two convex polygons of at most
/// max_clip_input_vertices vertices each has at most twice as many vertices.
inline constexpr int max_clip_input_vertices = 9;
inline constexpr int max_polygon_vertices = 2 * max_clip_input_vertices;

using Polygon = StaticVector<Point2, max_polygon_vertices>;

/// Shoelace formula: positive for counter-clockwise vertex order.
double signed_area(const Polygon& polygon);
/// |signed_area|.
double area(const Polygon& polygon);
/// Area centroid; the vertex average when the area vanishes.
Point2 centroid(const Polygon& polygon);
/// Reverse the vertex order if the polygon is clockwise.
void make_counter_clockwise(Polygon& polygon);
/// Shortest / longest edge, including the closing edge; 0 for fewer than two vertices.
double min_edge_length(const Polygon& polygon);
double max_edge_length(const Polygon& polygon);

struct ClipOptions {
  /// Points closer than this (times the shortest edge of either input) are merged, and a point
  /// that close to a clipping line counts as lying on it.
  double merge_tolerance = 1e-8;
  /// A result with area below this (times the subject's area) is reported as empty.
  double min_relative_area = 1e-12;
};

/// Intersection of two convex polygons (either orientation, at most max_clip_input_vertices
/// vertices each), by Sutherland–Hodgman clipping of `subject` against every edge of
/// `clipper` (Sutherland & Hodgman 1974) with tolerance-based classification, so coincident
/// vertices, collinear and nearly parallel edges and touching-only contact give clean results.
/// Returns a counter-clockwise polygon without duplicate or collinear vertices, or an empty
/// polygon when the overlap has fewer than three vertices or negligible area.
Polygon clip_polygons(const Polygon& subject, const Polygon& clipper,
                      const ClipOptions& options = {});

/// A triangle given by three counter-clockwise vertices.
struct Triangle2 {
  Point2 a, b, c;
  double area() const;
};
using TriangleList = StaticVector<Triangle2, max_polygon_vertices>;

/// Split a convex counter-clockwise polygon into integration cells: a triangle stays one cell,
/// otherwise one triangle per edge fanned about the area centroid (ALGORITHMS.md §2, step 5).
/// The cell areas sum to the polygon's area.
TriangleList triangulate_fan(const Polygon& polygon);

} // namespace seam::geometry
