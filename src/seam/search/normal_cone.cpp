#include "seam/search/normal_cone.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

namespace seam::search {

namespace {

using Vec = std::array<double, 3>;

Vec sub(const Vec& a, const Vec& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
double dot(const Vec& a, const Vec& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}
Vec cross(const Vec& a, const Vec& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Vec& a) {
  return std::sqrt(dot(a, a));
}

/// Angle between unit vectors, robust near 0 and pi (atan2 of |a x b| and a . b).
double angle_between(const Vec& a, const Vec& b) {
  return std::atan2(norm(cross(a, b)), dot(a, b));
}

// Cones are grown by this much so that rounding never makes them too narrow.
constexpr double angle_slack = 1e-9;

NormalCone full_cone() {
  return {{0.0, 0.0, 1.0}, std::numbers::pi};
}

} // namespace

NormalCone facet_normal_cone(int dim, std::span<const double> coords,
                             std::span<const local_index> nodes) {
  auto point = [&](int i) {
    Vec p{0.0, 0.0, 0.0};
    for (int d = 0; d < dim; ++d) p[d] = coords[static_cast<std::size_t>(nodes[i]) * dim + d];
    return p;
  };
  if (dim == 2) {
    if (nodes.size() != 2) return full_cone();
    const Vec t = sub(point(1), point(0));
    const Vec n{t[1], -t[0], 0.0}; // outward for counter-clockwise boundaries
    const double l = norm(n);
    if (l == 0.0) return full_cone();
    return {{n[0] / l, n[1] / l, 0.0}, angle_slack};
  }
  const int n_nodes = static_cast<int>(nodes.size());
  if (n_nodes != 3 && n_nodes != 4) return full_cone();
  // Corner normals (x_{i+1} - x_i) x (x_{i-1} - x_i); for a triangle all three coincide, for
  // a bilinear quad the normal field is a convex-weighted blend of them up to scaling, so the
  // cone of the corner normals contains every normal of the facet.
  std::array<Vec, 4> corner;
  Vec mean{0.0, 0.0, 0.0};
  for (int i = 0; i < n_nodes; ++i) {
    const Vec x = point(i);
    corner[i] = cross(sub(point((i + 1) % n_nodes), x), sub(point((i + n_nodes - 1) % n_nodes), x));
    const double l = norm(corner[i]);
    if (l == 0.0) return full_cone();
    for (int d = 0; d < 3; ++d) corner[i][d] /= l;
    for (int d = 0; d < 3; ++d) mean[d] += corner[i][d];
  }
  const double l = norm(mean);
  if (l == 0.0) return full_cone();
  for (int d = 0; d < 3; ++d) mean[d] /= l;
  double angle = 0.0;
  for (int i = 0; i < n_nodes; ++i) angle = std::max(angle, angle_between(mean, corner[i]));
  // Only a cone narrower than 90 degrees is convex, which the blending argument needs.
  if (angle >= 0.5 * std::numbers::pi) return full_cone();
  return {mean, std::min(angle + angle_slack, std::numbers::pi)};
}

NormalCone merge(const NormalCone& a, const NormalCone& b) {
  if (a.angle >= std::numbers::pi || b.angle >= std::numbers::pi) return full_cone();
  const double phi = angle_between(a.axis, b.axis);
  if (phi + b.angle <= a.angle) return a;
  if (phi + a.angle <= b.angle) return b;
  const double angle = 0.5 * (phi + a.angle + b.angle);
  if (angle >= std::numbers::pi) return full_cone();
  // Rotate a's axis towards b's by (angle - a.angle) along the great circle through both; if
  // the axes are (anti)parallel any perpendicular direction serves.
  Vec p = sub(b.axis, Vec{dot(a.axis, b.axis) * a.axis[0], dot(a.axis, b.axis) * a.axis[1],
                          dot(a.axis, b.axis) * a.axis[2]});
  double lp = norm(p);
  if (lp < 1e-12) {
    const Vec trial = std::abs(a.axis[0]) < 0.9 ? Vec{1.0, 0.0, 0.0} : Vec{0.0, 1.0, 0.0};
    p = cross(cross(a.axis, trial), a.axis);
    // Stay in the plane for 2D cones (z = 0).
    if (a.axis[2] == 0.0 && b.axis[2] == 0.0) p = Vec{-a.axis[1], a.axis[0], 0.0};
    lp = norm(p);
  }
  const double rot = angle - a.angle;
  NormalCone m;
  for (int d = 0; d < 3; ++d) m.axis[d] = std::cos(rot) * a.axis[d] + std::sin(rot) * p[d] / lp;
  const double l = norm(m.axis);
  for (int d = 0; d < 3; ++d) m.axis[d] /= l;
  m.angle = std::min(angle + angle_slack, std::numbers::pi);
  return m;
}

double max_angle_between(const NormalCone& a, const NormalCone& b) {
  return std::min(angle_between(a.axis, b.axis) + a.angle + b.angle, std::numbers::pi);
}

} // namespace seam::search
