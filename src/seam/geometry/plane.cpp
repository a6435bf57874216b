#include "seam/geometry/plane.hpp"

#include "seam/common/error.hpp"

namespace seam::geometry {

Plane make_plane(const Eigen::Vector3d& origin, const Eigen::Vector3d& normal) {
  const double length = normal.norm();
  SEAM_CHECK(length > 0.0, InputError, "make_plane: zero normal");
  Plane plane;
  plane.origin = origin;
  plane.normal = normal / length;
  int axis = 0;
  plane.normal.cwiseAbs().minCoeff(&axis);
  Eigen::Vector3d e = Eigen::Vector3d::Unit(axis);
  e -= e.dot(plane.normal) * plane.normal;
  plane.t1 = e.normalized();
  plane.t2 = plane.normal.cross(plane.t1);
  return plane;
}

} // namespace seam::geometry
