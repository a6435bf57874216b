#pragma once
// The auxiliary plane of 3D mortar integration (Puso & Laursen 2004; ALGORITHMS.md §2,
// steps 2-3): slave and master nodes are projected along its normal into it, and points in
// it are addressed by two in-plane coordinates so that clipping runs in 2D.
#include <Eigen/Core>
#include <Eigen/Geometry>

namespace seam::geometry {

struct Plane {
  Eigen::Vector3d origin;
  Eigen::Vector3d normal; ///< unit normal
  Eigen::Vector3d t1;     ///< unit in-plane axes with t1 x t2 = normal, so a polygon that
  Eigen::Vector3d t2;     ///< turns counter-clockwise about the normal stays counter-clockwise

  /// In-plane coordinates of the projection of x along the normal.
  Eigen::Vector2d to_local(const Eigen::Vector3d& x) const {
    const Eigen::Vector3d r = x - origin;
    return {r.dot(t1), r.dot(t2)};
  }
  /// The point of the plane with in-plane coordinates u.
  Eigen::Vector3d to_global(const Eigen::Vector2d& u) const {
    return origin + u.x() * t1 + u.y() * t2;
  }
  /// Signed distance of x from the plane along the normal.
  double height(const Eigen::Vector3d& x) const { return (x - origin).dot(normal); }
};

/// Plane through origin with the given normal (normalized here; must be nonzero). The first
/// axis is built from the coordinate axis least aligned with the normal, which keeps it
/// well-conditioned for every normal.
Plane make_plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal);

} // namespace seam::geometry
