#include "seam/solid/algorithmic_force.hpp"

#include "seam/common/error.hpp"
#include "seam/solid/detail/cell_geometry.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>

namespace seam::solid {

namespace {

// Voigt components used by a D-dimensional kernel (see material.hpp).
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

// I + grad u as a 3x3 matrix (identity out of plane in 2D; the material sets F33).
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

// Rows of B_a: variation of the Voigt strain (engineering shears) with u_a for the
// configuration with deformation gradient F, dE_IJ = 1/2 (F_iI G_aJ + F_iJ G_aI) du_ai.
template <int D, int NV>
void strain_variation(const Eigen::Matrix<double, D, D>& F, const detail::NodalGradients<D>& G,
                      int a, Eigen::Matrix<double, NV, D>& B) {
  constexpr auto comp = components<D>();
  for (int k = 0; k < NV; ++k) {
    const int I = voigt_i[comp[k]], J = voigt_j[comp[k]];
    for (int i = 0; i < D; ++i)
      B(k, i) = I == J ? F(i, I) * G(a, I) : F(i, I) * G(a, J) + F(i, J) * G(a, I);
  }
}

template <int D>
AlgorithmicResult algorithmic_force_impl(const AlgorithmicInput& in, int n, std::span<double> f,
                                         std::span<double> K) {
  constexpr auto comp = components<D>();
  constexpr int NV = static_cast<int>(comp.size());
  using BMatrix = Eigen::Matrix<double, NV, D>;
  using DMatrix = Eigen::Matrix<double, D, D>;

  const int nd = n * D;
  const bool linear = in.material.model == MaterialModel::linear_elastic;
  const bool want_f = !f.empty(), want_K = !K.empty();
  if (want_f) std::fill(f.begin(), f.end(), 0.0);
  if (want_K) std::fill(K.begin(), K.end(), 0.0);
  Eigen::Map<Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>> Km(
      K.data(), want_K ? nd : 0, want_K ? nd : 0);

  AlgorithmicResult result;
  const int degree =
      in.quadrature_degree > 0 ? in.quadrature_degree : fem::default_quadrature_degree(in.cell);
  const fem::QuadratureRule rule = fem::quadrature(in.cell, degree);
  detail::NodalGradients<D> G;
  std::array<BMatrix, fem::max_cell_nodes> B_mid, B_next;
  AlgorithmicStress point;
  for (int q = 0; q < rule.n_points; ++q) {
    const double detJ = detail::reference_gradients<D>(in.cell, n, &rule.points[q * D], in.X, G);
    if (!(detJ > 0.0)) return {KernelStatus::inverted_reference, 0.0, 0.0, 0};
    const double dV = rule.weights[q] * detJ;

    const Eigen::Matrix3d F0 = deformation_gradient<D>(n, in.u_n, G);
    const Eigen::Matrix3d F1 = deformation_gradient<D>(n, in.u_next, G);
    const PointStatus ps =
        algorithmic_stress(in.material, in.plane, F0, F1, point, want_K, in.threshold);
    if (ps != PointStatus::ok) return {to_kernel_status(ps), 0.0, 0.0, 0};
    result.energy_n += point.energy_n * dV;
    result.energy_next += point.energy_next * dV;
    if (point.midpoint) ++result.n_midpoint_points;
    if (!want_f && !want_K) continue;

    // The small-strain model varies eps = sym(grad u): B with F = I.
    const DMatrix Fm =
        linear ? DMatrix::Identity().eval() : (0.5 * (F0 + F1)).topLeftCorner<D, D>().eval();
    const DMatrix F1b = linear ? DMatrix::Identity().eval() : F1.topLeftCorner<D, D>().eval();
    Eigen::Matrix<double, NV, 1> s;
    for (int k = 0; k < NV; ++k) s(k) = point.stress(voigt_i[comp[k]], voigt_j[comp[k]]);
    for (int a = 0; a < n; ++a) {
      strain_variation<D, NV>(Fm, G, a, B_mid[a]);
      if (want_K) strain_variation<D, NV>(F1b, G, a, B_next[a]);
      if (want_f) {
        const Eigen::Matrix<double, D, 1> fa = B_mid[a].transpose() * s * dV;
        for (int i = 0; i < D; ++i) f[a * D + i] += fa(i);
      }
    }
    if (!want_K) continue;

    Eigen::Matrix<double, NV, NV> A;
    for (int k = 0; k < NV; ++k)
      for (int l = 0; l < NV; ++l) A(k, l) = point.tangent(comp[k], comp[l]) * dV;
    // F_mid moves with u_{n+1}/2: the geometric term carries a factor 1/2.
    const DMatrix S_half = 0.5 * dV * point.stress.topLeftCorner<D, D>();
    for (int b = 0; b < n; ++b) {
      const BMatrix AB = A * B_next[b];
      const Eigen::Matrix<double, D, 1> SGb = S_half * G.row(b).transpose();
      for (int a = 0; a < n; ++a) {
        DMatrix Kab = B_mid[a].transpose() * AB;
        if (!linear) Kab.diagonal().array() += G.row(a).dot(SGb);
        Km.template block<D, D>(a * D, b * D) += Kab;
      }
    }
  }
  return result;
}

} // namespace

AlgorithmicResult algorithmic_internal_force(const AlgorithmicInput& in, std::span<double> f,
                                             std::span<double> K) {
  constexpr const char* where = "solid::algorithmic_internal_force";
  const int n = detail::checked_n_nodes(in.cell, in.dim, in.X.size(), where);
  SEAM_CHECK(in.u_n.size() == in.X.size() && in.u_next.size() == in.X.size(), InternalError, where,
             ": expected ", in.X.size(), " displacement values per state, got ", in.u_n.size(),
             " and ", in.u_next.size());
  SEAM_CHECK((in.dim == 3) == (in.plane == PlaneMode::none), InternalError, where,
             ": 3D needs PlaneMode::none and 2D plane_strain or plane_stress");
  SEAM_CHECK(in.threshold >= 0.0, InternalError, where, ": threshold must be >= 0, got ",
             in.threshold);
  const std::size_t nd = static_cast<std::size_t>(n * in.dim);
  SEAM_CHECK(f.empty() || f.size() == nd, InternalError, where, ": force buffer needs ", nd,
             " values, got ", f.size());
  SEAM_CHECK(K.empty() || K.size() == nd * nd, InternalError, where, ": tangent buffer needs ",
             nd * nd, " values, got ", K.size());
  return in.dim == 3 ? algorithmic_force_impl<3>(in, n, f, K)
                     : algorithmic_force_impl<2>(in, n, f, K);
}

} // namespace seam::solid
