// Quadratic 3D facets put Hyper<18> and Hyper<27> (6 kB each) into the kernel's 9 x 9 matrices,
// beyond Eigen's default limit of 128 kB for one fixed-size object on the stack; the kernel
// takes about 3 MB of stack there (docs/contact_dynamics.md §5).
#define EIGEN_STACK_ALLOCATION_LIMIT 0
#include "seam/contact/rigid_obstacle_facet.hpp"

#include "seam/common/hyper_dual.hpp"
#include "seam/contact/rigid_obstacle_gaps.hpp"
#include "seam/mortar/linearization_kernels.hpp"

namespace Eigen {

// Hyper<N> in the small Eigen matrices of the kernel (as dual_number.hpp does for Dual<N>).
template <int N>
struct NumTraits<seam::Hyper<N>>
    : AdNumTraits<seam::Hyper<N>, N * N + N + 1, N * N + N + 1, 3 * N * N + 2 * N + 1> {};
template <int N, class BinaryOp> struct ScalarBinaryOpTraits<seam::Hyper<N>, double, BinaryOp> {
  using ReturnType = seam::Hyper<N>;
};
template <int N, class BinaryOp> struct ScalarBinaryOpTraits<double, seam::Hyper<N>, BinaryOp> {
  using ReturnType = seam::Hyper<N>;
};

} // namespace Eigen

namespace seam::contact {

namespace {

namespace ad = mortar::ad;

template <class S, int Dim>
void kernel(const ad::FacetT<S, Dim>& f, const Obstacle& obstacle, mortar::Multiplier multiplier,
            ad::SmallMatrixT<S>& D, ad::NodalVectorT<S>& gap, double& area) {
  const int n = f.n_nodes;
  const double a = mortar::basis_modification(f.type, multiplier);
  const bool dual = multiplier == mortar::Multiplier::dual;
  ad::SmallMatrixT<S> A;
  if (dual) A = ad::dual_coefficients_t(f, a);
  // The rule of the dual coefficients (dual_coefficients_t): Phi_j N~_k J and Phi_j g J are
  // polynomials of no higher degree than the mass matrix integrand N~_j N~_k J.
  const auto rule = fem::quadrature(f.type, 4 * fem::order(f.type));
  D = ad::SmallMatrixT<S>::Zero(n, n);
  gap = ad::NodalVectorT<S>::Zero();
  area = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = rule.points.data() + q * (Dim - 1);
    const S jw = ad::norm(ad::scaled_normal_t<S, Dim>(ad::tangents_t(f, xi))) *
                 rule.weights[static_cast<std::size_t>(q)];
    mortar::NodalVector N, Nt;
    fem::shape_values(f.type, xi, N.data());
    Nt = N;
    if (a != 0.0) mortar::modify_basis(f.type, a, Nt.data());
    const Eigen::Matrix<S, Dim, 1> x = ad::times<S, Dim, 1>(f.x, N, n);
    const S distance = obstacle.distance<S, Dim>(x);
    for (int j = 0; j < n; ++j) {
      S phi = 0.0;
      if (dual) {
        for (int l = 0; l < n; ++l) phi += A(j, l) * Nt(l);
      } else {
        phi = Nt(j);
      }
      const S w = phi * jw;
      for (int k = 0; k < n; ++k) D(j, k) += w * Nt(k);
      gap(j) += w * distance;
    }
    area += value_of(jw);
  }
}

template <int Dim, int K>
void with_derivatives(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                      mortar::Multiplier multiplier, RigidObstacleFacet& out) {
  using S = Dual<K>;
  ad::SmallMatrixT<S> D;
  ad::NodalVectorT<S> gap;
  kernel<S, Dim>(ad::seed<S, Dim>(facet, 0), obstacle, multiplier, D, gap, out.area);
  const int n = facet.n_nodes;
  const int nv = Dim * n;
  out.n_variables = nv;
  out.dD.assign(static_cast<std::size_t>(n * n * nv), 0.0);
  out.dgap.assign(static_cast<std::size_t>(n * nv), 0.0);
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) {
      out.D[static_cast<std::size_t>(j * n + k)] = D(j, k).value;
      std::copy_n(D(j, k).gradient.begin(), nv,
                  out.dD.begin() + static_cast<std::ptrdiff_t>((j * n + k) * nv));
    }
    out.gap[static_cast<std::size_t>(j)] = gap(j).value;
    std::copy_n(gap(j).gradient.begin(), nv,
                out.dgap.begin() + static_cast<std::ptrdiff_t>(j * nv));
  }
}

/// The gaps on Hyper<K> (K >= nv = Dim * nodes; the variables past nv stay unseeded): values,
/// gradients and Hessians.
template <int Dim, int K>
void with_hessians(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                   mortar::Multiplier multiplier, std::vector<double>& gap,
                   std::vector<double>& gradient, std::vector<double>& hessian) {
  using S = Hyper<K>;
  const int n = facet.n_nodes;
  const int nv = Dim * n;
  SEAM_ASSERT(nv <= K);
  ad::FacetT<S, Dim> f;
  f.type = facet.type;
  f.n_nodes = n;
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < Dim; ++a) f.x(a, i) = S::variable(facet.x(a, i), Dim * i + a);
  ad::SmallMatrixT<S> D;
  ad::NodalVectorT<S> g;
  double area = 0.0;
  kernel<S, Dim>(f, obstacle, multiplier, D, g, area);
  gap.resize(static_cast<std::size_t>(n));
  gradient.resize(static_cast<std::size_t>(n * nv));
  hessian.resize(static_cast<std::size_t>(n * nv * nv));
  for (int j = 0; j < n; ++j) {
    gap[static_cast<std::size_t>(j)] = g(j).value;
    std::copy_n(g(j).gradient.begin(), nv, gradient.begin() + static_cast<std::ptrdiff_t>(j * nv));
    for (int v = 0; v < nv; ++v)
      std::copy_n(g(j).hessian.begin() + static_cast<std::ptrdiff_t>(v * K), nv,
                  hessian.begin() + static_cast<std::ptrdiff_t>((j * nv + v) * nv));
  }
}

} // namespace

template <int Dim>
void rigid_obstacle_gap_hessians(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                                 mortar::Multiplier multiplier, std::vector<double>& gap,
                                 std::vector<double>& gradient, std::vector<double>& hessian) {
  const int nv = Dim * facet.n_nodes;
  if constexpr (Dim == 2) {
    SEAM_CHECK(nv == 4 || nv == 6, InputError,
               "energy-momentum contact against a rigid obstacle: line2 and line3 slave facets "
               "only");
    if (nv == 4)
      with_hessians<2, 4>(facet, obstacle, multiplier, gap, gradient, hessian);
    else
      with_hessians<2, 6>(facet, obstacle, multiplier, gap, gradient, hessian);
  } else {
    SEAM_CHECK(nv == 9 || nv == 12 || nv == 18 || nv == 24 || nv == 27, InputError,
               "energy-momentum contact against a rigid obstacle: tri3, quad4, tri6, quad8 and "
               "quad9 slave facets only");
    if (nv == 9)
      with_hessians<3, 9>(facet, obstacle, multiplier, gap, gradient, hessian);
    else if (nv == 12)
      with_hessians<3, 12>(facet, obstacle, multiplier, gap, gradient, hessian);
    else if (nv == 18)
      with_hessians<3, 18>(facet, obstacle, multiplier, gap, gradient, hessian);
    else
      with_hessians<3, 27>(facet, obstacle, multiplier, gap, gradient, hessian); // quad8, quad9
  }
}

template void rigid_obstacle_gap_hessians(const mortar::Facet<2>&, const Obstacle&,
                                          mortar::Multiplier, std::vector<double>&,
                                          std::vector<double>&, std::vector<double>&);
template void rigid_obstacle_gap_hessians(const mortar::Facet<3>&, const Obstacle&,
                                          mortar::Multiplier, std::vector<double>&,
                                          std::vector<double>&, std::vector<double>&);

template <int Dim>
void rigid_obstacle_facet(const mortar::Facet<Dim>& facet, const Obstacle& obstacle,
                          mortar::Multiplier multiplier, bool derivatives,
                          RigidObstacleFacet& out) {
  const int n = facet.n_nodes;
  out.n = n;
  if (!derivatives) {
    out.n_variables = 0;
    ad::SmallMatrixT<double> D;
    ad::NodalVectorT<double> gap;
    kernel<double, Dim>(ad::seed<double, Dim>(facet, 0), obstacle, multiplier, D, gap, out.area);
    for (int j = 0; j < n; ++j) {
      for (int k = 0; k < n; ++k) out.D[static_cast<std::size_t>(j * n + k)] = D(j, k);
      out.gap[static_cast<std::size_t>(j)] = gap(j);
    }
    return;
  }
  ad::with_facet_width(
      Dim * n, [&]<int K>() { with_derivatives<Dim, K>(facet, obstacle, multiplier, out); });
}

template void rigid_obstacle_facet(const mortar::Facet<2>&, const Obstacle&, mortar::Multiplier,
                                   bool, RigidObstacleFacet&);
template void rigid_obstacle_facet(const mortar::Facet<3>&, const Obstacle&, mortar::Multiplier,
                                   bool, RigidObstacleFacet&);

} // namespace seam::contact
