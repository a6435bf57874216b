#include "seam/solid/loads.hpp"

#include "seam/common/error.hpp"
#include "seam/solid/detail/cell_geometry.hpp"

#include <Eigen/Geometry>
#include <algorithm>

namespace seam::solid {

namespace {

int check_facet(const FacetInput& in, bool needs_u, const char* where) {
  SEAM_CHECK(in.dim == 2 || in.dim == 3, InternalError, where, ": dimension must be 2 or 3");
  SEAM_CHECK(fem::dimension(in.facet) == in.dim - 1, InternalError, where, ": a ",
             fem::name(in.facet), " is not a facet of a ", in.dim, "D body");
  const int n = fem::n_nodes(in.facet);
  SEAM_CHECK(in.X.size() == static_cast<std::size_t>(n * in.dim), InternalError, where,
             ": expected ", n * in.dim, " coordinates, got ", in.X.size());
  SEAM_CHECK(in.u.size() == in.X.size() || (!needs_u && in.u.empty()), InternalError, where,
             ": expected ", n * in.dim, " displacement values, got ", in.u.size());
  return n;
}

int facet_degree(const FacetInput& in) {
  return in.quadrature_degree > 0 ? in.quadrature_degree : fem::default_quadrature_degree(in.facet);
}

// Skew matrix [v]x with [v]x w = v x w.
Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

// Shape values, parametric derivatives, and the position/tangents of a facet at one point.
template <int D> struct FacetPoint {
  double N[fem::max_facet_nodes];
  double dN[fem::max_facet_nodes * (D - 1)];
  Eigen::Matrix<double, D, 1> X0 = Eigen::Matrix<double, D, 1>::Zero(); ///< reference position
  Eigen::Matrix<double, D, D - 1> T = Eigen::Matrix<double, D, D - 1>::Zero(); ///< dx/dxi

  // x = X + u (u may be empty: reference configuration).
  FacetPoint(const FacetInput& in, int n, const double* xi, bool current) {
    fem::shape_values(in.facet, xi, N);
    fem::shape_gradients(in.facet, xi, dN);
    for (int a = 0; a < n; ++a) {
      for (int i = 0; i < D; ++i) {
        const double X = in.X[a * D + i];
        const double x = current && !in.u.empty() ? X + in.u[a * D + i] : X;
        X0(i) += N[a] * X;
        for (int k = 0; k < D - 1; ++k) T(i, k) += dN[a * (D - 1) + k] * x;
      }
    }
  }

  // Area-weighted normal n da / dxi: outward per the facet orientation of fem::cell.hpp.
  Eigen::Matrix<double, D, 1> weighted_normal() const {
    if constexpr (D == 3) {
      return T.col(0).cross(T.col(1));
    } else {
      return Eigen::Vector2d(T(1, 0), -T(0, 0));
    }
  }
};

template <int D>
void follower_pressure_impl(const FacetInput& in, int n, const ScalarField& p, std::span<double> r,
                            std::span<double> K) {
  const int nd = n * D;
  std::fill(r.begin(), r.end(), 0.0);
  std::fill(K.begin(), K.end(), 0.0);
  const fem::QuadratureRule rule = fem::quadrature(in.facet, facet_degree(in));
  for (int q = 0; q < rule.n_points; ++q) {
    const FacetPoint<D> pt(in, n, &rule.points[q * (D - 1)], true);
    const double wp = rule.weights[q] * p(pt.X0.data());
    const Eigen::Matrix<double, D, 1> nda = pt.weighted_normal();
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < D; ++i) r[a * D + i] += wp * pt.N[a] * nda(i);
    if (K.empty()) continue;
    // d(n da)/dx_b: 3D d(t1 x t2) = dt1 x t2 + t1 x dt2 with dt_k = dN_b,k dx_b;
    // 2D d(t_y, -t_x) = R dt, R = [[0, 1], [-1, 0]].
    for (int b = 0; b < n; ++b) {
      Eigen::Matrix<double, D, D> dn;
      if constexpr (D == 3) {
        dn = -pt.dN[b * 2] * skew(pt.T.col(1)) + pt.dN[b * 2 + 1] * skew(pt.T.col(0));
      } else {
        dn << 0.0, pt.dN[b], -pt.dN[b], 0.0;
      }
      for (int a = 0; a < n; ++a) {
        const double c = wp * pt.N[a];
        for (int i = 0; i < D; ++i)
          for (int k = 0; k < D; ++k) K[(a * D + i) * nd + b * D + k] += c * dn(i, k);
      }
    }
  }
}

template <int D>
void dead_traction_impl(const FacetInput& in, int n, const VectorField& t, std::span<double> r) {
  std::fill(r.begin(), r.end(), 0.0);
  const fem::QuadratureRule rule = fem::quadrature(in.facet, facet_degree(in));
  for (int q = 0; q < rule.n_points; ++q) {
    const FacetPoint<D> pt(in, n, &rule.points[q * (D - 1)], false);
    const double dA = rule.weights[q] * pt.weighted_normal().norm();
    double tq[3] = {0.0, 0.0, 0.0};
    t(pt.X0.data(), tq);
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < D; ++i) r[a * D + i] -= dA * pt.N[a] * tq[i];
  }
}

template <int D>
KernelStatus body_force_impl(const ElementInput& in, int n, const VectorField& b,
                             std::span<double> r) {
  std::fill(r.begin(), r.end(), 0.0);
  const int degree =
      in.quadrature_degree > 0 ? in.quadrature_degree : fem::default_quadrature_degree(in.cell);
  const fem::QuadratureRule rule = fem::quadrature(in.cell, degree);
  double N[fem::max_cell_nodes];
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = &rule.points[q * D];
    const double detJ = detail::reference_jacobian_det<D>(in.cell, n, xi, in.X);
    if (!(detJ > 0.0)) return KernelStatus::inverted_reference;
    fem::shape_values(in.cell, xi, N);
    double X0[3] = {0.0, 0.0, 0.0};
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < D; ++i) X0[i] += N[a] * in.X[a * D + i];
    double bq[3] = {0.0, 0.0, 0.0};
    b(X0, bq);
    const double dV = rule.weights[q] * detJ;
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < D; ++i) r[a * D + i] -= dV * N[a] * bq[i];
  }
  return KernelStatus::ok;
}

} // namespace

void follower_pressure(const FacetInput& in, const ScalarField& p, std::span<double> r,
                       std::span<double> K) {
  const int n = check_facet(in, true, "solid::follower_pressure");
  const std::size_t nd = static_cast<std::size_t>(n * in.dim);
  SEAM_CHECK(r.size() == nd && (K.empty() || K.size() == nd * nd), InternalError,
             "solid::follower_pressure: buffers need ", nd, " and ", nd * nd, " values");
  if (in.dim == 3) {
    follower_pressure_impl<3>(in, n, p, r, K);
  } else {
    follower_pressure_impl<2>(in, n, p, r, K);
  }
}

void follower_pressure(const FacetInput& in, double p, std::span<double> r, std::span<double> K) {
  follower_pressure(
      in, [p](const double*) { return p; }, r, K);
}

void dead_traction(const FacetInput& in, const VectorField& t, std::span<double> r) {
  const int n = check_facet(in, false, "solid::dead_traction");
  SEAM_CHECK(r.size() == static_cast<std::size_t>(n * in.dim), InternalError,
             "solid::dead_traction: buffer needs ", n * in.dim, " values, got ", r.size());
  if (in.dim == 3) {
    dead_traction_impl<3>(in, n, t, r);
  } else {
    dead_traction_impl<2>(in, n, t, r);
  }
}

KernelStatus body_force(const ElementInput& in, const VectorField& b, std::span<double> r) {
  const int n = detail::checked_n_nodes(in.cell, in.dim, in.X.size(), "solid::body_force");
  SEAM_CHECK(r.size() == static_cast<std::size_t>(n * in.dim), InternalError,
             "solid::body_force: buffer needs ", n * in.dim, " values, got ", r.size());
  return in.dim == 3 ? body_force_impl<3>(in, n, b, r) : body_force_impl<2>(in, n, b, r);
}

} // namespace seam::solid
