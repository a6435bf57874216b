#pragma once
// Internals of the element-pair kernels (pair_integration.hpp): per-point helpers written for
// small fixed node counts, and the back-projection into the auxiliary plane.
//
// Back-projection of auxiliary-plane points onto facets (ALGORITHMS.md §2, step 7), done in
// the plane. Projection along the plane normal n is linear, so a facet x(xi) = sum N_k(xi) x_k
// seen in the plane is u(xi) = sum N_k(xi) u_k with u_k the in-plane coordinates of its nodes,
// and solving x(xi) + alpha n = p for a plane point p is the same as solving u(xi) = u(p); the
// height of x(xi) above the plane is sum N_k(xi) h_k. For linear pieces the 2D map is affine
// (triangle) or bilinear (quadrilateral) and inverts in closed form; quadratic facets start a
// 2D Newton iteration from the inverse of the linear piece that contains the point.
#include <array>
#include <cmath>

#include <Eigen/Core>

#include "seam/geometry/plane.hpp"
#include "seam/geometry/projection.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/facet.hpp"

namespace seam::mortar::detail {

using Vector2 = Eigen::Vector2d;

inline double cross(const Vector2& a, const Vector2& b) {
  return a.x() * b.y() - a.y() * b.x();
}

/// A facet seen in an auxiliary plane: in-plane coordinates and heights of its nodes (zero
/// past the node count). Built in place, never copied.
struct PlanarFacet {
  fem::CellType type;
  int n_nodes;
  Eigen::Matrix<double, 2, max_facet_nodes> u = Eigen::Matrix<double, 2, max_facet_nodes>::Zero();
  Eigen::Matrix<double, 1, max_facet_nodes> height =
      Eigen::Matrix<double, 1, max_facet_nodes>::Zero();

  PlanarFacet(const Facet<3>& facet, const geometry::Plane& plane)
      : type(facet.type), n_nodes(facet.n_nodes) {
    for (int k = 0; k < facet.n_nodes; ++k) {
      const Eigen::Vector3d r = facet.x.col(k) - plane.origin;
      u(0, k) = r.dot(plane.t1);
      u(1, k) = r.dot(plane.t2);
      height(k) = r.dot(plane.normal);
    }
  }
  PlanarFacet(const PlanarFacet&) = delete;
  PlanarFacet& operator=(const PlanarFacet&) = delete;
};

/// Shape functions of the surface facets and their gradients dN[2 k + a] = dN_k / dxi_a,
/// written out (Gmsh node order, as seam::fem) because the kernels evaluate them at every
/// Newton iterate and integration point. Entries past the facet's node count are untouched.
///   tri6: N_v = L_v (2 L_v - 1), N_e = 4 L_a L_b with L = (1 - xi - eta, xi, eta);
///   quad8: corners (1 + xi_v xi)(1 + eta_v eta)(xi_v xi + eta_v eta - 1) / 4, mid-sides
///     (1 - xi^2)(1 + eta_e eta) / 2 and (1 + xi_e xi)(1 - eta^2) / 2;
///   quad9: products of the 1D quadratics xi (xi - 1) / 2, xi (xi + 1) / 2, 1 - xi^2.
template <bool Gradients>
inline void shape_functions(fem::CellType type, const Vector2& xi, NodalVector& N,
                            std::array<double, 2 * max_facet_nodes>& dN) {
  const double x = xi.x(), y = xi.y();
  switch (type) {
  case fem::CellType::tri3:
    N(0) = 1.0 - x - y;
    N(1) = x;
    N(2) = y;
    if constexpr (Gradients) {
      dN[0] = -1.0, dN[1] = -1.0, dN[2] = 1.0, dN[3] = 0.0, dN[4] = 0.0, dN[5] = 1.0;
    }
    return;
  case fem::CellType::quad4: {
    const double xm = 1.0 - x, xp = 1.0 + x, ym = 1.0 - y, yp = 1.0 + y;
    N(0) = 0.25 * xm * ym;
    N(1) = 0.25 * xp * ym;
    N(2) = 0.25 * xp * yp;
    N(3) = 0.25 * xm * yp;
    if constexpr (Gradients) {
      dN[0] = -0.25 * ym, dN[1] = -0.25 * xm;
      dN[2] = 0.25 * ym, dN[3] = -0.25 * xp;
      dN[4] = 0.25 * yp, dN[5] = 0.25 * xp;
      dN[6] = -0.25 * yp, dN[7] = 0.25 * xm;
    }
    return;
  }
  case fem::CellType::tri6: {
    const double l0 = 1.0 - x - y;
    N(0) = l0 * (2.0 * l0 - 1.0);
    N(1) = x * (2.0 * x - 1.0);
    N(2) = y * (2.0 * y - 1.0);
    N(3) = 4.0 * l0 * x;
    N(4) = 4.0 * x * y;
    N(5) = 4.0 * y * l0;
    if constexpr (Gradients) {
      const double d0 = 1.0 - 4.0 * l0; // dN0/dxi = dN0/deta
      dN[0] = d0, dN[1] = d0;
      dN[2] = 4.0 * x - 1.0, dN[3] = 0.0;
      dN[4] = 0.0, dN[5] = 4.0 * y - 1.0;
      dN[6] = 4.0 * (l0 - x), dN[7] = -4.0 * x;
      dN[8] = 4.0 * y, dN[9] = 4.0 * x;
      dN[10] = -4.0 * y, dN[11] = 4.0 * (l0 - y);
    }
    return;
  }
  case fem::CellType::quad8: {
    constexpr std::array<double, 4> cx{-1.0, 1.0, 1.0, -1.0}, cy{-1.0, -1.0, 1.0, 1.0};
    for (int v = 0; v < 4; ++v) {
      const auto i = static_cast<std::size_t>(v);
      const double fx = 1.0 + cx[i] * x, fy = 1.0 + cy[i] * y, s = cx[i] * x + cy[i] * y - 1.0;
      N(v) = 0.25 * fx * fy * s;
      if constexpr (Gradients) {
        dN[2 * i] = 0.25 * cx[i] * fy * (s + fx);
        dN[2 * i + 1] = 0.25 * cy[i] * fx * (s + fy);
      }
    }
    const double bx = 1.0 - x * x, by = 1.0 - y * y;
    N(4) = 0.5 * bx * (1.0 - y);
    N(5) = 0.5 * (1.0 + x) * by;
    N(6) = 0.5 * bx * (1.0 + y);
    N(7) = 0.5 * (1.0 - x) * by;
    if constexpr (Gradients) {
      dN[8] = -x * (1.0 - y), dN[9] = -0.5 * bx;
      dN[10] = 0.5 * by, dN[11] = -(1.0 + x) * y;
      dN[12] = -x * (1.0 + y), dN[13] = 0.5 * bx;
      dN[14] = -0.5 * by, dN[15] = -(1.0 - x) * y;
    }
    return;
  }
  case fem::CellType::quad9: {
    // 1D factors at the nodes -1, 1, 0 and their derivatives.
    const std::array<double, 3> lx{0.5 * x * (x - 1.0), 0.5 * x * (x + 1.0), 1.0 - x * x};
    const std::array<double, 3> ly{0.5 * y * (y - 1.0), 0.5 * y * (y + 1.0), 1.0 - y * y};
    const std::array<double, 3> gx{x - 0.5, x + 0.5, -2.0 * x}, gy{y - 0.5, y + 0.5, -2.0 * y};
    // Node k sits at (ix[k], iy[k]) in terms of the 1D factor indices.
    constexpr std::array<int, 9> ix{0, 1, 1, 0, 2, 1, 2, 0, 2}, iy{0, 0, 1, 1, 0, 2, 1, 2, 2};
    for (int k = 0; k < 9; ++k) {
      const auto i = static_cast<std::size_t>(ix[static_cast<std::size_t>(k)]);
      const auto j = static_cast<std::size_t>(iy[static_cast<std::size_t>(k)]);
      N(k) = lx[i] * ly[j];
      if constexpr (Gradients) {
        dN[static_cast<std::size_t>(2 * k)] = gx[i] * ly[j];
        dN[static_cast<std::size_t>(2 * k + 1)] = lx[i] * gy[j];
      }
    }
    return;
  }
  default:
    fem::shape_values(type, xi.data(), N.data());
    if constexpr (Gradients) fem::shape_gradients(type, xi.data(), dN.data());
  }
}

inline void shape_values(fem::CellType type, const Vector2& xi, NodalVector& N) {
  std::array<double, 2 * max_facet_nodes> unused;
  shape_functions<false>(type, xi, N, unused);
}

/// Multiplier values Phi = A N~ (dual) or N~ (standard) and the displacement functions N~ of
/// the slave basis (the loops of slave_functions, dual_basis.hpp, over the node count only).
inline void slave_point_functions(const SlaveBasis& basis, fem::CellType type, int n_nodes,
                                  const NodalVector& N, NodalVector& N_tilde, NodalVector& Phi) {
  for (int k = 0; k < n_nodes; ++k) N_tilde(k) = N(k);
  if (basis.modification != 0.0) modify_basis(type, basis.modification, N_tilde.data());
  if (basis.multiplier == Multiplier::dual) {
    for (int j = 0; j < n_nodes; ++j) {
      double phi = 0.0;
      for (int k = 0; k < n_nodes; ++k) phi += basis.A(j, k) * N_tilde(k);
      Phi(j) = phi;
    }
  } else {
    for (int k = 0; k < n_nodes; ++k) Phi(k) = N_tilde(k);
  }
}

/// Inverse of the plane map of one linear piece: affine for a triangle with vertices at the
/// reference points (0,0), (1,0), (0,1); bilinear u = a + b s + c t + d s t for a
/// quadrilateral with vertices at (-1,-1), (1,-1), (1,1), (-1,1). Each piece vertex also
/// carries its reference coordinates in the parent facet, so that piece coordinates map to
/// parent ones (exactly for linear facets, whose single piece is the facet itself).
class PieceInverse {
public:
  /// u: the piece's vertices in the plane; xi: their parent reference coordinates; `whole`:
  /// the piece is the whole (linear) facet, so piece and parent coordinates coincide. Returns
  /// false for a degenerate piece.
  bool set(int n_vertices, const std::array<Vector2, 4>& u, const std::array<Vector2, 4>& xi,
           bool whole) {
    n_ = n_vertices;
    xi_ = xi;
    whole_ = whole;
    if (n_ == 3) {
      a_ = u[0];
      b_ = u[1] - u[0];
      c_ = u[2] - u[0];
      const double det = cross(b_, c_);
      if (!regular(det, b_, c_)) return false;
      inverse_ << c_.y() / det, -c_.x() / det, -b_.y() / det, b_.x() / det;
      return true;
    }
    a_ = 0.25 * (u[0] + u[1] + u[2] + u[3]);
    b_ = 0.25 * (-u[0] + u[1] + u[2] - u[3]);
    c_ = 0.25 * (-u[0] - u[1] + u[2] + u[3]);
    d_ = 0.25 * (u[0] - u[1] + u[2] - u[3]);
    bc_ = cross(b_, c_);
    bd_ = cross(b_, d_);
    return regular(bc_, b_, c_);
  }

  /// Parent reference coordinates of the plane point p; false if p has no preimage. Runs for
  /// every integration point, hence forced inline: the point loop keeps its values in
  /// registers.
  [[gnu::always_inline]] bool parent_coordinates(const Vector2& p, Vector2& xi) const {
    if (n_ == 3) {
      const Vector2 st = inverse_ * (p - a_);
      xi = whole_ ? st : Vector2(xi_[0] + st.x() * (xi_[1] - xi_[0]) + st.y() * (xi_[2] - xi_[0]));
      return true;
    }
    Vector2 st;
    if (!invert_bilinear(p, st)) return false;
    if (whole_) {
      xi = st;
      return true;
    }
    const double sm = 1.0 - st.x(), sp = 1.0 + st.x(), tm = 1.0 - st.y(), tp = 1.0 + st.y();
    xi = 0.25 * (sm * tm * xi_[0] + sp * tm * xi_[1] + sp * tp * xi_[2] + sm * tp * xi_[3]);
    return true;
  }

  /// |det(a, b)| > 1e-14 |a| |b|: the columns are far from parallel (as in
  /// geometry::project_onto_surface), tested without square roots.
  static bool regular(double det, const Vector2& a, const Vector2& b) {
    return det * det > 1e-28 * a.squaredNorm() * b.squaredNorm();
  }

private:
  // r = p - a = b s + c t + d s t. Crossing with c + d s eliminates t:
  //   (b x d) s^2 + (b x c - r x d) s - r x c = 0,
  // solved with the cancellation-free form of the quadratic formula (its root C / q stays
  // finite as b x d -> 0, the parallelogram case); of the two roots the one in (or nearest
  // to) [-1, 1] is the preimage inside the convex piece. Then t from r - b s = t (c + d s).
  // Both are accurate to round-off while the roots are well apart; when they nearly coincide
  // (a nearly degenerate quadrilateral) one Newton step on the bilinear map restores the
  // precision.
  [[gnu::always_inline]] bool invert_bilinear(const Vector2& p, Vector2& st) const {
    const Vector2 r = p - a_;
    const double A = bd_;
    const double B = bc_ - cross(r, d_);
    const double C = -cross(r, c_);
    double disc = B * B - 4.0 * A * C;
    const bool close_roots = disc < 1e-4 * B * B;
    if (disc < 0.0) {
      if (disc < -1e-12 * B * B) return false;
      disc = 0.0;
    }
    const double q = -0.5 * (B + std::copysign(std::sqrt(disc), B));
    double s = q != 0.0 ? C / q : INFINITY;
    double t;
    if (std::abs(s) <= 1.0) {
      // t for s = C / q with both sides scaled by q: q (r - s b) . q w / |q w|^2, so that its
      // division does not wait for the one of s.
      const Vector2 qw = q * c_ + C * d_;
      const double qwqw = qw.squaredNorm();
      if (!(qwqw > 0.0)) return false;
      t = (q * r - C * b_).dot(qw) / qwqw;
    } else {
      if (A != 0.0) {
        const double other = q / A;
        if (!std::isfinite(s) || std::abs(other) < std::abs(s)) s = other;
      }
      if (!std::isfinite(s)) return false;
      const Vector2 w = c_ + s * d_;
      const double ww = w.squaredNorm();
      if (!(ww > 0.0)) return false;
      t = (r - s * b_).dot(w) / ww;
    }
    if (close_roots) {
      // F = b s + c t + d s t - r, J = [b + d t, c + d s].
      const Vector2 F = s * b_ + t * c_ + (s * t) * d_ - r;
      const Vector2 js = b_ + t * d_, jt = c_ + s * d_;
      const double det = cross(js, jt);
      if (!regular(det, js, jt)) return false;
      const double inv = 1.0 / det;
      s -= cross(F, jt) * inv;
      t -= cross(js, F) * inv;
    }
    st = {s, t};
    return std::isfinite(t);
  }

  // Set by set(); d_ is used by quadrilaterals and inverse_ by triangles only.
  int n_ = 3;
  bool whole_ = false;
  Vector2 a_, b_, c_, d_;
  double bc_, bd_; ///< b x c, b x d
  Eigen::Matrix2d inverse_;
  std::array<Vector2, 4> xi_;
};

/// Solve u(xi) = p on a quadratic planar facet by Newton from xi (ALGORITHMS.md §2, step 7;
/// the 2D form of geometry::project_onto_surface, with the same options and failure rules).
inline bool newton_in_plane(const PlanarFacet& f, const Vector2& p, Vector2& xi,
                            const geometry::NewtonOptions& options) {
  NodalVector N;
  std::array<double, 2 * max_facet_nodes> dN;
  for (int it = 1; it <= options.max_iterations; ++it) {
    shape_functions<true>(f.type, xi, N, dN);
    Vector2 r = -p;
    Vector2 j0 = Vector2::Zero(), j1 = Vector2::Zero();
    for (int k = 0; k < f.n_nodes; ++k) {
      const Vector2 uk = f.u.col(k);
      r += N(k) * uk;
      j0 += dN[static_cast<std::size_t>(2 * k)] * uk;
      j1 += dN[static_cast<std::size_t>(2 * k + 1)] * uk;
    }
    const double det = cross(j0, j1);
    if (!PieceInverse::regular(det, j0, j1)) return false;
    const Vector2 step(-cross(r, j1) / det, -cross(j0, r) / det);
    xi += step;
    if (!xi.allFinite()) return false;
    if (step.cwiseAbs().maxCoeff() <= options.tolerance) return true;
  }
  return false;
}

} // namespace seam::mortar::detail
