#pragma once
// Projections of points onto parametrised curves (2D) and surfaces (3D) along a direction,
// by local Newton iteration (ALGORITHMS.md §1 and §2, step 7; Popp et al. 2009, 2010).
// The geometry is passed as a callable so that this module needs no shape functions: the
// mortar module wraps its finite element facets, tests wrap analytic parametrisations.
//
//   curve(xi)   -> CurvePoint   {x, dx/dxi}
//   field(xi)   -> CurvePoint   {d, dd/dxi}   (a direction varying along the curve)
//   surface(xi) -> SurfacePoint {x, [dx/dxi dx/deta]}
#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

namespace seam::geometry {

/// 2D cross product (z component of the 3D one).
inline double cross2(const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  return a.x() * b.y() - a.y() * b.x();
}

struct CurvePoint {
  Eigen::Vector2d x;
  Eigen::Vector2d dx;
};

struct SurfacePoint {
  Eigen::Vector3d x;
  Eigen::Matrix<double, 3, 2> dx;
};

struct NewtonOptions {
  /// Converged when the parameter increment is at most this (parameters are O(1)), or at most
  /// the increment that round-off in the residual alone can cause: x(xi) - p carries an error
  /// of about eps (|x| + |p|) that no iteration removes, and on facets small against their
  /// distance from the origin (|x| / h >~ 1e4) it maps to increments above 1e-12.
  double tolerance = 1e-12;
  int max_iterations = 10;
};

/// 16 unit roundoffs: the round-off floor of a residual is taken as this times its scale.
inline constexpr double residual_roundoff = 16.0 * 2.220446049250313e-16;

struct CurveProjection {
  double xi = 0.0;
  bool converged = false;
  int iterations = 0;
};

struct SurfaceProjection {
  Eigen::Vector2d xi = Eigen::Vector2d::Zero();
  /// Signed distance parameter: x(xi) + alpha * d = p.
  double alpha = 0.0;
  bool converged = false;
  int iterations = 0;
};

/// Find xi with (x(xi) - p) x d(xi) = 0, i.e. p lies on the line through x(xi) along d(xi).
/// Both projections of 2D segmentation are of this form: a slave node along its nodal normal
/// onto the master (d constant), a master node onto the slave along the interpolated slave
/// normal (d = d(xi)); ALGORITHMS.md §1. Reports failure on a singular derivative, a non-finite
/// iterate or when the iteration cap is reached.
template <class Curve, class Field>
CurveProjection project_onto_curve_along_field(const Curve& curve, const Field& field,
                                               const Eigen::Vector2d& p, double xi0,
                                               const NewtonOptions& options = {}) {
  CurveProjection result;
  result.xi = xi0;
  for (int it = 1; it <= options.max_iterations; ++it) {
    result.iterations = it;
    const CurvePoint c = curve(result.xi);
    const CurvePoint d = field(result.xi);
    const Eigen::Vector2d r = c.x - p;
    const double f = cross2(r, d.x);
    const double df = cross2(c.dx, d.x) + cross2(r, d.dx);
    // Scale of df: |dx/dxi| |d|; a vanishing derivative means the direction is tangent to the
    // curve and the projection is ill-posed.
    const double scale = c.dx.norm() * d.x.norm() + r.norm() * d.dx.norm();
    if (!(std::abs(df) > 1e-14 * scale)) return result;
    const double step = -f / df;
    result.xi += step;
    if (!std::isfinite(result.xi)) return result;
    // Round-off floor with 1-norms (bounds of the 2-norms, and free of square roots).
    if (std::abs(step) <= options.tolerance ||
        std::abs(f) <= residual_roundoff * (c.x.lpNorm<1>() + p.lpNorm<1>()) * d.x.lpNorm<1>()) {
      result.converged = true;
      return result;
    }
  }
  return result;
}

/// As above with a fixed direction d.
template <class Curve>
CurveProjection project_onto_curve(const Curve& curve, const Eigen::Vector2d& p,
                                   const Eigen::Vector2d& d, double xi0,
                                   const NewtonOptions& options = {}) {
  const auto constant = [&d](double) { return CurvePoint{d, Eigen::Vector2d::Zero()}; };
  return project_onto_curve_along_field(curve, constant, p, xi0, options);
}

/// Solve x(xi) + alpha d = p for (xi, alpha) by Newton with the 3x3 Jacobian
/// [dx/dxi, dx/deta, d] (back-projection of an integration point from the auxiliary plane,
/// ALGORITHMS.md §2, step 7). Reports failure on a singular Jacobian (d tangent to the
/// surface), a non-finite iterate or when the iteration cap is reached.
template <class Surface>
SurfaceProjection project_onto_surface(const Surface& surface, const Eigen::Vector3d& p,
                                       const Eigen::Vector3d& d, const Eigen::Vector2d& xi0,
                                       const NewtonOptions& options = {}) {
  SurfaceProjection result;
  result.xi = xi0;
  for (int it = 1; it <= options.max_iterations; ++it) {
    result.iterations = it;
    const SurfacePoint s = surface(result.xi);
    Eigen::Matrix3d jacobian;
    jacobian.col(0) = s.dx.col(0);
    jacobian.col(1) = s.dx.col(1);
    jacobian.col(2) = d;
    const double det = jacobian.determinant();
    const double scale = s.dx.col(0).norm() * s.dx.col(1).norm() * d.norm();
    if (!(std::abs(det) > 1e-14 * scale)) return result;
    const double alpha_before = result.alpha;
    const Eigen::Vector3d residual = s.x + result.alpha * d - p;
    const Eigen::Matrix3d inverse = jacobian.inverse();
    const Eigen::Vector3d step = -inverse * residual;
    result.xi += step.head<2>();
    result.alpha += step(2);
    if (!result.xi.allFinite() || !std::isfinite(result.alpha)) return result;
    const double increment = step.head<2>().cwiseAbs().maxCoeff();
    // Round-off floor with 1-norms (bounds of the 2-norms, and free of square roots).
    if (increment <= options.tolerance ||
        increment <=
            residual_roundoff *
                (s.x.lpNorm<1>() + p.lpNorm<1>() + std::abs(alpha_before) * d.lpNorm<1>()) *
                inverse.topRows<2>().cwiseAbs().sum()) {
      result.converged = true;
      return result;
    }
  }
  return result;
}

} // namespace seam::geometry
