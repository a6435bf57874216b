#include "seam/solid/element.hpp"

#include "seam/common/error.hpp"
#include "seam/solid/detail/cell_geometry.hpp"

#include <Eigen/Core>

#include <algorithm>

namespace seam::solid {

namespace {

// In-plane Voigt components used by a D-dimensional kernel (see material.hpp).
template <int D> constexpr std::array<int, D == 3 ? 6 : 3> components() {
  if constexpr (D == 3) {
    return {0, 1, 2, 3, 4, 5};
  } else {
    return {0, 1, 3};
  }
}
constexpr std::array<int, 6> voigt_i = {0, 1, 2, 0, 1, 0};
constexpr std::array<int, 6> voigt_j = {0, 1, 2, 1, 2, 2};

KernelStatus to_kernel_status(PointStatus s) {
  switch (s) {
  case PointStatus::ok:
    return KernelStatus::ok;
  case PointStatus::inverted:
    return KernelStatus::inverted_current;
  case PointStatus::no_plane_stress:
    return KernelStatus::material_failure;
  }
  return KernelStatus::material_failure;
}

int check(const ElementInput& in, const char* where) {
  const int n = detail::checked_n_nodes(in.cell, in.dim, in.X.size(), where);
  SEAM_CHECK(in.u.size() == in.X.size(), InternalError, where, ": expected ", in.X.size(),
             " displacement values, got ", in.u.size());
  SEAM_CHECK((in.dim == 3) == (in.plane == PlaneMode::none), InternalError, where,
             ": 3D needs PlaneMode::none and 2D plane_strain or plane_stress");
  return n;
}

int degree_of(const ElementInput& in) {
  return in.quadrature_degree > 0 ? in.quadrature_degree : fem::default_quadrature_degree(in.cell);
}

// Deformation gradient F = I + grad u as a 3x3 matrix (F33 = 1 in 2D; the material sets it).
template <int D>
Eigen::Matrix3d deformation_gradient(int n, std::span<const double> u,
                                     const detail::NodalGradients<D>& G) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < D; ++i)
      for (int j = 0; j < D; ++j) F(i, j) += u[a * D + i] * G(a, j);
  }
  return F;
}

template <int D>
ElementResult internal_force_impl(const ElementInput& in, int n, std::span<double> r,
                                  std::span<double> K) {
  constexpr auto comp = components<D>();
  constexpr int NV = static_cast<int>(comp.size());
  using BMatrix = Eigen::Matrix<double, NV, D>;

  const int nd = n * D;
  const bool linear = in.material.model == MaterialModel::linear_elastic;
  const bool want_r = !r.empty(), want_K = !K.empty();
  if (want_r) std::fill(r.begin(), r.end(), 0.0);
  if (want_K) std::fill(K.begin(), K.end(), 0.0);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Km(
      K.data(), want_K ? nd : 0, want_K ? nd : 0);

  ElementResult result;
  const fem::QuadratureRule rule = fem::quadrature(in.cell, degree_of(in));
  detail::NodalGradients<D> G;
  std::array<BMatrix, fem::max_cell_nodes> B;
  PointResponse resp;
  for (int q = 0; q < rule.n_points; ++q) {
    const double detJ = detail::reference_gradients<D>(in.cell, n, &rule.points[q * D], in.X, G);
    if (!(detJ > 0.0)) return {KernelStatus::inverted_reference, 0.0};
    const double dV = rule.weights[q] * detJ;

    const Eigen::Matrix3d F = deformation_gradient<D>(n, in.u, G);
    const PointStatus ps = evaluate(in.material, in.plane, F, resp, want_K);
    if (ps != PointStatus::ok) return {to_kernel_status(ps), 0.0};
    result.energy += resp.energy * dV;
    if (!want_r && !want_K) continue;

    // B_a: variation of the Voigt strain (engineering shears) with u_a,
    // dE_IJ = 1/2 (F_iI dN_a/dX_J + F_iJ dN_a/dX_I) du_ai; F = I for the linear model.
    const Eigen::Matrix<double, D, D> Fb =
        linear ? Eigen::Matrix<double, D, D>::Identity().eval() : F.topLeftCorner<D, D>().eval();
    Eigen::Matrix<double, NV, 1> s;
    for (int k = 0; k < NV; ++k) s(k) = resp.stress(voigt_i[comp[k]], voigt_j[comp[k]]);
    for (int a = 0; a < n; ++a) {
      for (int k = 0; k < NV; ++k) {
        const int I = voigt_i[comp[k]], J = voigt_j[comp[k]];
        for (int i = 0; i < D; ++i) {
          B[a](k, i) = I == J ? Fb(i, I) * G(a, I) : Fb(i, I) * G(a, J) + Fb(i, J) * G(a, I);
        }
      }
      if (want_r) {
        const Eigen::Matrix<double, D, 1> ra = B[a].transpose() * s * dV;
        for (int i = 0; i < D; ++i) r[a * D + i] += ra(i);
      }
    }
    if (!want_K) continue;

    Eigen::Matrix<double, NV, NV> C;
    for (int k = 0; k < NV; ++k)
      for (int l = 0; l < NV; ++l) C(k, l) = resp.tangent(comp[k], comp[l]) * dV;
    const Eigen::Matrix<double, D, D> S = resp.stress.topLeftCorner<D, D>() * dV;
    for (int b = 0; b < n; ++b) {
      const BMatrix CB = C * B[b];
      const Eigen::Matrix<double, D, 1> SGb = S * G.row(b).transpose();
      for (int a = 0; a <= b; ++a) {
        Eigen::Matrix<double, D, D> Kab = B[a].transpose() * CB;
        if (!linear) Kab.diagonal().array() += G.row(a).dot(SGb);
        Km.template block<D, D>(a * D, b * D) += Kab;
      }
    }
  }
  // Only the upper block triangle was accumulated; K is symmetric.
  if (want_K) {
    for (int b = 0; b < n; ++b)
      for (int a = 0; a < b; ++a)
        Km.template block<D, D>(b * D, a * D) = Km.template block<D, D>(a * D, b * D).transpose();
  }
  return result;
}

// The 3D kernel in the form of the first elasticity tensor A = dP/dF, P = F S:
//   A_iJkL = F_iI C_IJKL F_kK + delta_ik S_JL,   K_ab,ik = int G_aJ A_iJkL G_bL dV,
// the same tangent as B_a^T C B_b + (G_a . S G_b) I of internal_force_impl, in fewer operations
// (no 6 x 3 B per node and pair). The quadrature points are taken in chunks: for each
// component pair (i, k) the rows of G_q A_ik,q dV_q (n x 3 per point) of a chunk form one
// matrix and its product with the stacked G_q^T (3 x n per point) adds the chunk's share of
// K_ik, so the work is a few dense products of fixed-capacity matrices. K is symmetric:
// the pairs i <= k are computed, K_ki = K_ik^T.
constexpr int chunk_points = 9;
constexpr std::array<std::array<int, 3>, 3> voigt_index = {{{0, 3, 5}, {3, 1, 4}, {5, 4, 2}}};
constexpr std::array<int, 6> pair_i = {0, 1, 2, 0, 1, 0};
constexpr std::array<int, 6> pair_k = {0, 1, 2, 1, 2, 2};

ElementResult internal_force_3d(const ElementInput& in, int n, std::span<double> r,
                                std::span<double> K) {
  constexpr int N = fem::max_cell_nodes;
  constexpr int W = 3 * chunk_points;
  using Stacked = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 6 * N, W>;
  using Gradients = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, W, N>;
  using Result = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::ColMajor, 6 * N, N>;
  using Tensor9 = Eigen::Matrix<double, 9, 9>;

  const int nd = n * 3;
  const bool linear = in.material.model == MaterialModel::linear_elastic;
  const bool want_r = !r.empty(), want_K = !K.empty();
  if (want_r) std::fill(r.begin(), r.end(), 0.0);

  ElementResult result;
  const fem::QuadratureRule rule = fem::quadrature(in.cell, degree_of(in));
  detail::NodalGradients<3> G;
  PointResponse resp;
  Stacked GA;
  Gradients Gt;
  Result R;
  if (want_K) R.setZero(6 * n, n);
  for (int q0 = 0; q0 < rule.n_points; q0 += chunk_points) {
    const int m = std::min(chunk_points, rule.n_points - q0);
    if (want_K) {
      GA.resize(6 * n, 3 * m);
      Gt.resize(3 * m, n);
    }
    for (int c = 0; c < m; ++c) {
      const int q = q0 + c;
      const double detJ = detail::reference_gradients<3>(in.cell, n, &rule.points[q * 3], in.X, G);
      if (!(detJ > 0.0)) return {KernelStatus::inverted_reference, 0.0};
      const double dV = rule.weights[q] * detJ;

      const Eigen::Matrix3d F = deformation_gradient<3>(n, in.u, G);
      const PointStatus ps = evaluate(in.material, in.plane, F, resp, want_K);
      if (ps != PointStatus::ok) return {to_kernel_status(ps), 0.0};
      result.energy += resp.energy * dV;
      if (!want_r && !want_K) continue;

      const Eigen::Matrix3d Fb = linear ? Eigen::Matrix3d::Identity().eval() : F;
      if (want_r) {
        const Eigen::Matrix3d P = Fb * resp.stress * dV;
        for (int a = 0; a < n; ++a)
          for (int i = 0; i < 3; ++i) r[a * 3 + i] += P.row(i).dot(G.row(a));
      }
      if (!want_K) continue;

      // T(IJ, kL) = C_IJKL F_kK, then A(iJ, kL) = F_iI T(IJ, kL), times dV.
      Tensor9 T, A;
      for (int I = 0; I < 3; ++I)
        for (int J = 0; J < 3; ++J)
          for (int k = 0; k < 3; ++k)
            for (int L = 0; L < 3; ++L) {
              double s = 0.0;
              for (int Kc = 0; Kc < 3; ++Kc)
                s += resp.tangent(voigt_index[I][J], voigt_index[Kc][L]) * Fb(k, Kc);
              T(I * 3 + J, k * 3 + L) = s;
            }
      for (int i = 0; i < 3; ++i)
        for (int J = 0; J < 3; ++J)
          for (int kL = 0; kL < 9; ++kL) {
            double s = 0.0;
            for (int I = 0; I < 3; ++I) s += Fb(i, I) * T(I * 3 + J, kL);
            A(i * 3 + J, kL) = s * dV;
          }
      if (!linear) {
        const Eigen::Matrix3d S = resp.stress * dV;
        for (int i = 0; i < 3; ++i) A.block<3, 3>(i * 3, i * 3) += S;
      }
      Gt.block(3 * c, 0, 3, n) = G.transpose();
      for (int p = 0; p < 6; ++p)
        GA.block(p * n, 3 * c, n, 3).noalias() = G * A.block<3, 3>(pair_i[p] * 3, pair_k[p] * 3);
    }
    if (want_K) R.noalias() += GA * Gt;
  }
  if (want_K) {
    Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Km(K.data(),
                                                                                          nd, nd);
    for (int p = 0; p < 6; ++p) {
      const int i = pair_i[p], k = pair_k[p];
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          const double v = R(p * n + a, b);
          Km(a * 3 + i, b * 3 + k) = v;
          if (i != k) Km(b * 3 + k, a * 3 + i) = v;
        }
    }
  }
  return result;
}

template <int D> ElementStress element_stress_impl(const ElementInput& in, int n) {
  ElementStress out;
  const bool linear = in.material.model == MaterialModel::linear_elastic;
  const fem::QuadratureRule rule = fem::quadrature(in.cell, degree_of(in));
  detail::NodalGradients<D> G;
  PointResponse resp;
  Eigen::Matrix3d sum = Eigen::Matrix3d::Zero();
  double volume = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    const double detJ = detail::reference_gradients<D>(in.cell, n, &rule.points[q * D], in.X, G);
    if (!(detJ > 0.0)) {
      out.status = KernelStatus::inverted_reference;
      return out;
    }
    const Eigen::Matrix3d F = deformation_gradient<D>(n, in.u, G);
    const PointStatus ps = evaluate(in.material, in.plane, F, resp, false);
    if (ps != PointStatus::ok) {
      out.status = to_kernel_status(ps);
      return out;
    }
    // dv = J dV; in plane stress J includes the thickness stretch F33.
    double J = 1.0;
    if (!linear) J = F.topLeftCorner<D, D>().determinant() * (D == 2 ? resp.stretch_zz : 1.0);
    const double dv = rule.weights[q] * detJ * J;
    sum += cauchy_stress(in.material, in.plane, F, resp) * dv;
    volume += dv;
  }
  const Eigen::Matrix3d sigma = sum / volume;
  out.cauchy = {sigma(0, 0), sigma(1, 1), sigma(2, 2), sigma(0, 1), sigma(1, 2), sigma(0, 2)};
  out.von_mises = von_mises(sigma);
  return out;
}

} // namespace

std::string_view describe(KernelStatus s) {
  switch (s) {
  case KernelStatus::ok:
    return "ok";
  case KernelStatus::inverted_reference:
    return "non-positive Jacobian determinant in the reference configuration";
  case KernelStatus::inverted_current:
    return "inverted element: non-positive det F in the current configuration";
  case KernelStatus::material_failure:
    return "no plane-stress state found at a quadrature point";
  }
  return "unknown";
}

ElementResult internal_force(const ElementInput& in, std::span<double> r, std::span<double> K) {
  const int n = check(in, "solid::internal_force");
  const std::size_t nd = static_cast<std::size_t>(n * in.dim);
  SEAM_CHECK(r.empty() || r.size() == nd, InternalError,
             "solid::internal_force: residual buffer needs ", nd, " values, got ", r.size());
  SEAM_CHECK(K.empty() || K.size() == nd * nd, InternalError,
             "solid::internal_force: tangent buffer needs ", nd * nd, " values, got ", K.size());
  return in.dim == 3 ? internal_force_3d(in, n, r, K) : internal_force_impl<2>(in, n, r, K);
}

ElementStress element_stress(const ElementInput& in) {
  const int n = check(in, "solid::element_stress");
  return in.dim == 3 ? element_stress_impl<3>(in, n) : element_stress_impl<2>(in, n);
}

} // namespace seam::solid
