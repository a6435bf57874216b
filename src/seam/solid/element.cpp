#include "seam/solid/element.hpp"

#include "seam/common/error.hpp"
#include "seam/solid/detail/cell_geometry.hpp"

#include <Eigen/Core>

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
  return in.dim == 3 ? internal_force_impl<3>(in, n, r, K) : internal_force_impl<2>(in, n, r, K);
}

ElementStress element_stress(const ElementInput& in) {
  const int n = check(in, "solid::element_stress");
  return in.dim == 3 ? element_stress_impl<3>(in, n) : element_stress_impl<2>(in, n);
}

} // namespace seam::solid
