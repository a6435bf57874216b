// Newton projections onto analytic curves and surfaces recover the parameters a point was
// built from; ill-posed projections report failure.
#include <cmath>

#include <gtest/gtest.h>

#include "seam/common/error.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/geometry/projection.hpp"

using Eigen::Vector2d;
using Eigen::Vector3d;
using seam::geometry::CurvePoint;
using seam::geometry::SurfacePoint;

namespace {

// A curved, non-uniformly parametrised arc: x = (xi + 0.2 xi^3, 0.3 xi^2 + 0.1 xi).
CurvePoint arc(double xi) {
  return {Vector2d(xi + 0.2 * xi * xi * xi, 0.3 * xi * xi + 0.1 * xi),
          Vector2d(1.0 + 0.6 * xi * xi, 0.6 * xi + 0.1)};
}

// Its (unnormalized) left normal field and derivative.
CurvePoint arc_normal(double xi) {
  const CurvePoint c = arc(xi);
  return {Vector2d(-c.dx.y(), c.dx.x()), Vector2d(-0.6, 1.2 * xi)};
}

// A doubly curved patch.
SurfacePoint patch(const Eigen::Vector2d& xi) {
  const double s = xi.x(), t = xi.y();
  SurfacePoint p;
  p.x = Vector3d(s + 0.1 * t * t, t - 0.05 * s * t, 0.2 * s * t + 0.05 * s * s);
  p.dx.col(0) = Vector3d(1.0, -0.05 * t, 0.2 * t + 0.1 * s);
  p.dx.col(1) = Vector3d(0.2 * t, 1.0 - 0.05 * s, 0.2 * s);
  return p;
}

} // namespace

TEST(ProjectOntoCurve, FixedDirectionRecoversParameter) {
  const Vector2d d = Vector2d(0.2, 1.0).normalized();
  for (const double xi_star : {-0.9, -0.3, 0.0, 0.37, 1.0, 1.04}) {
    for (const double alpha : {-0.4, 0.0, 0.25}) {
      const Vector2d p = arc(xi_star).x + alpha * d;
      const auto r = seam::geometry::project_onto_curve(arc, p, d, 0.0);
      ASSERT_TRUE(r.converged) << xi_star << " " << alpha;
      EXPECT_NEAR(r.xi, xi_star, 1e-12);
      EXPECT_LE(r.iterations, 10);
    }
  }
}

TEST(ProjectOntoCurve, VaryingDirectionRecoversParameter) {
  for (const double xi_star : {-1.0, -0.5, 0.2, 0.8}) {
    for (const double alpha : {-0.3, 0.1, 0.4}) {
      const Vector2d p = arc(xi_star).x + alpha * arc_normal(xi_star).x;
      const auto r = seam::geometry::project_onto_curve_along_field(arc, arc_normal, p, 0.0);
      ASSERT_TRUE(r.converged);
      EXPECT_NEAR(r.xi, xi_star, 1e-12);
    }
  }
}

TEST(ProjectOntoCurve, ReportsFailure) {
  const auto line = [](double xi) { return CurvePoint{Vector2d(xi, 0.0), Vector2d(1.0, 0.0)}; };
  // Direction tangent to the line: no solution.
  const auto tangent = seam::geometry::project_onto_curve(line, {0.3, 1.0}, {1.0, 0.0}, 0.0);
  EXPECT_FALSE(tangent.converged);
  // Iteration cap: a curved problem cannot converge in a single step.
  seam::geometry::NewtonOptions one_step;
  one_step.max_iterations = 1;
  const Vector2d p = arc(0.8).x + 0.3 * Vector2d(0, 1);
  EXPECT_FALSE(seam::geometry::project_onto_curve(arc, p, {0, 1}, -0.9, one_step).converged);
  // A straight line and fixed direction is linear: one step plus the confirming one.
  const auto linear = seam::geometry::project_onto_curve(line, {0.3, 1.0}, {0.0, 1.0}, 0.9);
  EXPECT_TRUE(linear.converged);
  EXPECT_NEAR(linear.xi, 0.3, 1e-15);
  EXPECT_LE(linear.iterations, 2);
}

TEST(ProjectOntoSurface, RecoversParametersAndDistance) {
  const Vector3d d = Vector3d(0.1, -0.2, 1.0).normalized();
  for (const Vector2d& xi_star : {Vector2d(0.3, -0.6), Vector2d(-1, 1), Vector2d(0.9, 0.05)}) {
    for (const double alpha : {-0.5, 0.0, 0.7}) {
      const Vector3d p = patch(xi_star).x + alpha * d;
      const auto r = seam::geometry::project_onto_surface(patch, p, d, Vector2d::Zero());
      ASSERT_TRUE(r.converged);
      EXPECT_NEAR(r.xi.x(), xi_star.x(), 1e-12);
      EXPECT_NEAR(r.xi.y(), xi_star.y(), 1e-12);
      EXPECT_NEAR(r.alpha, alpha, 1e-12);
    }
  }
}

TEST(ProjectOntoSurface, ReportsFailure) {
  const auto flat = [](const Vector2d& xi) {
    SurfacePoint p;
    p.x = Vector3d(xi.x(), xi.y(), 0.0);
    p.dx << 1, 0, 0, 1, 0, 0;
    return p;
  };
  // Direction in the tangent plane: singular Jacobian.
  EXPECT_FALSE(
      seam::geometry::project_onto_surface(flat, {0.2, 0.1, 1.0}, {1, 1, 0}, Vector2d::Zero())
          .converged);
  const auto ok =
      seam::geometry::project_onto_surface(flat, {0.2, 0.1, 1.0}, {0, 0, 1}, Vector2d::Zero());
  EXPECT_TRUE(ok.converged);
  EXPECT_NEAR(ok.alpha, 1.0, 1e-15);
}

TEST(Plane, OrthonormalRightHandedFrame) {
  for (const Vector3d& n : {Vector3d(0, 0, 1), Vector3d(0, 0, -2), Vector3d(1, 0, 0),
                            Vector3d(0.3, -0.4, 0.2), Vector3d(1e-9, 1, 1e-9)}) {
    const auto plane = seam::geometry::make_plane(Vector3d(1, 2, 3), n);
    EXPECT_NEAR(plane.normal.norm(), 1.0, 1e-15);
    EXPECT_TRUE(plane.normal.isApprox(n.normalized(), 1e-15));
    EXPECT_NEAR(plane.t1.norm(), 1.0, 1e-15);
    EXPECT_NEAR(plane.t2.norm(), 1.0, 1e-15);
    EXPECT_NEAR(plane.t1.dot(plane.normal), 0.0, 1e-15);
    EXPECT_TRUE(plane.t1.cross(plane.t2).isApprox(plane.normal, 1e-14));
    const Vector3d x(0.4, -1.3, 2.2);
    const Vector3d projected = x - plane.height(x) * plane.normal;
    EXPECT_TRUE(plane.to_global(plane.to_local(x)).isApprox(projected, 1e-14));
    EXPECT_NEAR(plane.height(plane.origin + 0.7 * plane.normal), 0.7, 1e-15);
  }
  EXPECT_THROW(seam::geometry::make_plane(Vector3d::Zero(), Vector3d::Zero()), seam::InputError);
}
