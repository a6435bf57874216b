#pragma once
// Building blocks of the mortar element-pair kernel written once on a scalar type S: double
// gives the values, seam::Dual<N> their exact derivatives by forward-mode automatic
// differentiation (ALGORITHMS.md §5, consistent linearization). Each block follows the
// double-valued original of seam::mortar / seam::geometry decision for decision, so the two
// agree to round-off and the derivative is that of the branch the original takes.
//
// Local Newton solves (projections) run on values with the original double code; the
// derivative of the converged parameter then comes from one Newton step in dual numbers taken
// at the solution with the value Jacobian — the implicit function theorem
// d(xi) = -(dF/dxi)^{-1} (dF/dq) dq for F(xi, q) = 0, with the value part kept at the
// converged root so values match the originals exactly.
#include <array>
#include <cmath>

#include <Eigen/Core>
#include <Eigen/LU>

#include "seam/common/dual_number.hpp"
#include "seam/common/error.hpp"
#include "seam/geometry/projection.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/facet.hpp"

namespace seam::mortar::ad {

template <class S, int Dim> using Vector = Eigen::Matrix<S, Dim, 1>;
template <class S> using NodalVectorT = Eigen::Matrix<S, max_facet_nodes, 1>;
template <class S>
using SmallMatrixT = Eigen::Matrix<S, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor,
                                   max_facet_nodes, max_facet_nodes>;

/// A facet whose nodal coordinates (columns) are of scalar type S.
template <class S, int Dim> struct FacetT {
  fem::CellType type = Dim == 2 ? fem::CellType::line2 : fem::CellType::tri3;
  int n_nodes = 0;
  Eigen::Matrix<S, Dim, max_facet_nodes> x = Eigen::Matrix<S, Dim, max_facet_nodes>::Zero();
};

template <class S, int Dim, int Cols>
Eigen::Matrix<double, Dim, Cols> values(const Eigen::Matrix<S, Dim, Cols>& m) {
  Eigen::Matrix<double, Dim, Cols> v;
  for (int j = 0; j < Cols; ++j)
    for (int i = 0; i < Dim; ++i) v(i, j) = value_of(m(i, j));
  return v;
}

template <class S, int Dim> Facet<Dim> values(const FacetT<S, Dim>& f) {
  Facet<Dim> v;
  v.type = f.type;
  v.n_nodes = f.n_nodes;
  v.x = values(f.x);
  return v;
}

/// Coordinates as dual variables: node i, component a is variable first + Dim * i + a.
template <class S, int Dim> FacetT<S, Dim> seed(const Facet<Dim>& f, int first) {
  FacetT<S, Dim> r;
  r.type = f.type;
  r.n_nodes = f.n_nodes;
  for (int i = 0; i < f.n_nodes; ++i) {
    for (int a = 0; a < Dim; ++a) {
      if constexpr (is_dual<S>) {
        r.x(a, i) = S::variable(f.x(a, i), first + Dim * i + a);
      } else {
        r.x(a, i) = f.x(a, i);
      }
    }
  }
  return r;
}

/// X * B over the first n columns of X (the facet's nodes), B of plain values.
template <class S, int Dim, int Cols>
Eigen::Matrix<S, Dim, Cols> times(const Eigen::Matrix<S, Dim, max_facet_nodes>& X,
                                  const Eigen::Matrix<double, max_facet_nodes, Cols>& B, int n) {
  Eigen::Matrix<S, Dim, Cols> r = Eigen::Matrix<S, Dim, Cols>::Zero();
  for (int i = 0; i < n; ++i)
    for (int c = 0; c < Cols; ++c)
      for (int a = 0; a < Dim; ++a) add_product(r(a, c), X(a, i), B(i, c));
  return r;
}

/// X * N over the first n columns, N of scalar type S.
template <class S, int Dim>
Vector<S, Dim> interpolate(const Eigen::Matrix<S, Dim, max_facet_nodes>& X,
                           const NodalVectorT<S>& N, int n) {
  Vector<S, Dim> r = Vector<S, Dim>::Zero();
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < Dim; ++a) add_product(r(a), X(a, i), N(i));
  return r;
}

template <class S, int Dim> S dot(const Vector<S, Dim>& a, const Vector<S, Dim>& b) {
  S r = a(0) * b(0);
  for (int i = 1; i < Dim; ++i) r += a(i) * b(i);
  return r;
}

template <class S, int Dim> S norm(const Vector<S, Dim>& a) {
  using std::sqrt;
  return sqrt(dot(a, a));
}

template <class S, int Dim> Vector<S, Dim> normalized(const Vector<S, Dim>& a) {
  return a / norm(a);
}

template <class S> S cross2(const Vector<S, 2>& a, const Vector<S, 2>& b) {
  return a(0) * b(1) - a(1) * b(0);
}

template <class S> Vector<S, 3> cross3(const Vector<S, 3>& a, const Vector<S, 3>& b) {
  return {a(1) * b(2) - a(2) * b(1), a(2) * b(0) - a(0) * b(2), a(0) * b(1) - a(1) * b(0)};
}

/// Normal whose length is the surface Jacobian (scaled_normal of facet.hpp on scalar S).
template <class S, int Dim>
Vector<S, Dim> scaled_normal_t(const Eigen::Matrix<S, Dim, Dim - 1>& t) {
  if constexpr (Dim == 2) {
    return {t(1, 0), -t(0, 0)};
  } else {
    return cross3<S>(t.col(0), t.col(1));
  }
}

/// Calls f.template operator()<K>() with the smallest K of 4, 6, 9, 12 that holds n_variables
/// (else 3 * max_facet_nodes): a dual number just wide enough for one facet's coordinates
/// (linear facets are the common case).
template <class F> void with_facet_width(int n_variables, F&& f) {
  if (n_variables <= 4) {
    f.template operator()<4>();
  } else if (n_variables <= 6) {
    f.template operator()<6>();
  } else if (n_variables <= 9) {
    f.template operator()<9>();
  } else if (n_variables <= 12) {
    f.template operator()<12>();
  } else {
    f.template operator()<3 * max_facet_nodes>();
  }
}

/// Shape values and gradients at a plain reference point.
struct ShapeAt {
  NodalVector N = NodalVector::Zero();
  Eigen::Matrix<double, max_facet_nodes, 2> dN = Eigen::Matrix<double, max_facet_nodes, 2>::Zero();
};

inline ShapeAt shape_at(fem::CellType type, const double* xi, int p) {
  ShapeAt s;
  std::array<double, max_facet_nodes * 2> g{};
  fem::shape_values(type, xi, s.N.data());
  fem::shape_gradients(type, xi, g.data());
  const int n = fem::n_nodes(type);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < p; ++a) s.dN(i, a) = g[static_cast<std::size_t>(i * p + a)];
  return s;
}

/// Tangents dx/dxi (and dx/deta) at a plain reference point.
template <class S, int Dim>
Eigen::Matrix<S, Dim, Dim - 1> tangents_t(const FacetT<S, Dim>& f, const double* xi) {
  const ShapeAt s = shape_at(f.type, xi, Dim - 1);
  const Eigen::Matrix<double, max_facet_nodes, Dim - 1> dN = s.dN.leftCols(Dim - 1);
  return times<S, Dim, Dim - 1>(f.x, dN, f.n_nodes);
}

/// Unit normal of a facet evaluated at its local node i (the summands of the averaged nodal
/// normals, normals.cpp).
template <class S, int Dim> Vector<S, Dim> unit_normal_at_node(const FacetT<S, Dim>& f, int i) {
  const double* reference = fem::reference_nodes(f.type).data();
  const Vector<S, Dim> n = scaled_normal_t<S, Dim>(tangents_t(f, reference + i * (Dim - 1)));
  SEAM_CHECK(value_of(norm(n)) > 0.0, InputError,
             "slave facet is degenerate (zero Jacobian at its node ", i, ")");
  return normalized(n);
}

/// Solve A X = B for small square A by Gaussian elimination with partial pivoting on values.
/// Returns false if a pivot is below tiny (relative scale set by the caller).
template <class S> bool solve_small(SmallMatrixT<S> A, SmallMatrixT<S>& B, double tiny) {
  const int n = static_cast<int>(A.rows());
  for (int k = 0; k < n; ++k) {
    int pivot = k;
    for (int i = k + 1; i < n; ++i)
      if (std::abs(value_of(A(i, k))) > std::abs(value_of(A(pivot, k)))) pivot = i;
    if (!(std::abs(value_of(A(pivot, k))) > tiny)) return false;
    if (pivot != k) {
      A.row(k).swap(A.row(pivot));
      B.row(k).swap(B.row(pivot));
    }
    for (int i = k + 1; i < n; ++i) {
      const S factor = A(i, k) / A(k, k);
      for (int j = k + 1; j < n; ++j) A(i, j) -= factor * A(k, j);
      for (int j = 0; j < B.cols(); ++j) B(i, j) -= factor * B(k, j);
    }
  }
  for (int k = n - 1; k >= 0; --k) {
    for (int j = 0; j < B.cols(); ++j) {
      S sum = B(k, j);
      for (int i = k + 1; i < n; ++i) sum -= A(k, i) * B(i, j);
      B(k, j) = sum / A(k, k);
    }
  }
  return true;
}

/// Dual coefficients A_e = D_e M_e^{-1} in the facet's current configuration (dual_basis.cpp;
/// ALGORITHMS.md §3): with S dual this is dA_e = (dD_e - A_e dM_e) M_e^{-1}.
template <class S, int Dim> SmallMatrixT<S> dual_coefficients_t(const FacetT<S, Dim>& f, double a) {
  const int n = f.n_nodes;
  const auto rule = fem::quadrature(f.type, 4 * fem::order(f.type));
  SmallMatrixT<S> M = SmallMatrixT<S>::Zero(n, n);
  SmallMatrixT<S> D = SmallMatrixT<S>::Zero(n, n);
  double measure = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = rule.points.data() + q * (Dim - 1);
    const S jw = norm(scaled_normal_t<S, Dim>(tangents_t(f, xi))) *
                 rule.weights[static_cast<std::size_t>(q)];
    NodalVector N;
    fem::shape_values(f.type, xi, N.data());
    modify_basis(f.type, a, N.data());
    for (int j = 0; j < n; ++j) {
      const S jwN = jw * N(j);
      D(j, j) += jwN;
      for (int k = 0; k < n; ++k) M(j, k) += jwN * N(k);
    }
    measure += value_of(jw);
  }
  // M symmetric: A = D M^{-1} = (M^{-1} D)^T.
  SmallMatrixT<S> X = D;
  const bool ok = measure > 0.0 && solve_small<S>(M, X, 1e-14 * measure);
  SEAM_CHECK(ok, InputError, "dual Lagrange multipliers: the ", fem::name(f.type),
             " slave facet is degenerate (its mass matrix is singular)");
  return X.transpose();
}

/// Converged projection parameter(s) with derivatives.
template <class S> struct CurveProjectionT {
  S xi = 0.0;
  bool converged = false;
};

template <class S> struct SurfaceProjectionT {
  Vector<S, 2> xi = Vector<S, 2>::Zero();
  S alpha = 0.0;
  bool converged = false;
};

/// Keep the value v, take the gradient of the dual correction step (see the file comment).
template <class S> S at_root(double v, const S& step) {
  S r = step;
  if constexpr (is_dual<S>) {
    r.value = v;
  } else {
    r = v;
  }
  return r;
}

/// Project p along a fixed direction d onto a line facet: (x(xi) - p) x d = 0, Newton from xi0
/// (project_onto_facet of facet.hpp).
template <class S>
CurveProjectionT<S> project_onto_line_t(const FacetT<S, 2>& f, const Vector<S, 2>& p,
                                        const Vector<S, 2>& d, double xi0,
                                        const geometry::NewtonOptions& options) {
  const geometry::CurveProjection r =
      project_onto_facet(values(f), values(p), values(d), xi0, options);
  CurveProjectionT<S> out;
  out.converged = r.converged;
  if (!r.converged) return out;
  const ShapeAt s = shape_at(f.type, &r.xi, 1);
  const Vector<S, 2> x = times<S, 2, 1>(f.x, s.N, f.n_nodes);
  const Eigen::Vector2d dx = values(f.x) * s.dN.col(0);
  const double slope = geometry::cross2(dx, values(d));
  out.xi = at_root<S>(r.xi, r.xi - cross2<S>(x - p, d) / slope);
  return out;
}

/// Project p onto a line facet along the interpolated unnormalized nodal normal field
/// n~(xi) = sum N_k(xi) n_k: (x(xi) - p) x n~(xi) = 0 (segmentation_2d.cpp, ALGORITHMS.md §1).
template <class S>
CurveProjectionT<S>
project_along_normals_t(const FacetT<S, 2>& f, const Eigen::Matrix<S, 2, max_facet_nodes>& normals,
                        const Vector<S, 2>& p, double xi0, const geometry::NewtonOptions& options) {
  const Facet<2> fv = values(f);
  const Eigen::Matrix<double, 2, max_facet_nodes> nv = values(normals);
  const auto curve = [&fv](double xi) {
    const auto q = evaluate(fv, &xi);
    return geometry::CurvePoint{q.x, q.dx.col(0)};
  };
  const auto field = [&fv, &nv](double xi) {
    const auto q = evaluate(fv, &xi);
    return geometry::CurvePoint{nv * q.N, nv * q.dN.col(0)};
  };
  const geometry::CurveProjection r =
      geometry::project_onto_curve_along_field(curve, field, values(p), xi0, options);
  CurveProjectionT<S> out;
  out.converged = r.converged;
  if (!r.converged) return out;
  const ShapeAt s = shape_at(f.type, &r.xi, 1);
  const Vector<S, 2> residual = times<S, 2, 1>(f.x, s.N, f.n_nodes) - p;
  const Vector<S, 2> direction = times<S, 2, 1>(normals, s.N, f.n_nodes);
  const Eigen::Vector2d dx = fv.x * s.dN.col(0);
  const Eigen::Vector2d dn = nv * s.dN.col(0);
  const double slope = geometry::cross2(dx, nv * s.N) + geometry::cross2(values(residual), dn);
  out.xi = at_root<S>(r.xi, r.xi - cross2<S>(residual, direction) / slope);
  return out;
}

/// Solve x(xi) + alpha d = p on a surface facet (back-projection, ALGORITHMS.md §2 step 7).
template <class S>
SurfaceProjectionT<S> project_onto_surface_t(const FacetT<S, 3>& f, const Vector<S, 3>& p,
                                             const Vector<S, 3>& d, const Eigen::Vector2d& xi0,
                                             const geometry::NewtonOptions& options) {
  const Facet<3> fv = values(f);
  const geometry::SurfaceProjection r = project_onto_facet(fv, values(p), values(d), xi0, options);
  SurfaceProjectionT<S> out;
  out.converged = r.converged;
  if (!r.converged) return out;
  const ShapeAt s = shape_at(f.type, r.xi.data(), 2);
  Vector<S, 3> residual = times<S, 3, 1>(f.x, s.N, f.n_nodes);
  for (int a = 0; a < 3; ++a) {
    add_product(residual(a), d(a), r.alpha);
    residual(a) -= p(a);
  }
  Eigen::Matrix3d jacobian;
  jacobian.leftCols<2>() = fv.x * s.dN;
  jacobian.col(2) = values(d);
  const Eigen::Matrix3d inverse = jacobian.inverse();
  std::array<S, 3> step{};
  for (int i = 0; i < 3; ++i) {
    for (int k = 0; k < 3; ++k)
      add_product(step[static_cast<std::size_t>(i)], residual(k), -inverse(i, k));
  }
  out.xi(0) = at_root<S>(r.xi(0), r.xi(0) + step[0]);
  out.xi(1) = at_root<S>(r.xi(1), r.xi(1) + step[1]);
  out.alpha = at_root<S>(r.alpha, r.alpha + step[2]);
  return out;
}

} // namespace seam::mortar::ad
