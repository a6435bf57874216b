#pragma once
// The linearized element-pair mortar kernels (ALGORITHMS.md §5, consistent linearization).
//
// 2D: the segmentation kernel of pair_integration.hpp on a scalar type S. With S = double it
// reproduces integrate_pair; with S = Dual<N> every output — D, M, weighted gaps — carries
// its exact derivative with respect to whatever the caller seeded: slave and master nodal
// coordinates, slave nodal normals. Instantiated for double, Dual<12> and Dual<18>: exactly
// the pair variables Dim * (2 n_slave + n_master) of line2 and line3 pairs.
//
// 3D: linearize_pair_3d differentiates the auxiliary-plane / clipping / cell quadrature in
// mixed mode (dual numbers over a few local variables for the plane and the clip polygon,
// hand-chained partial derivatives per integration point); see linearization_pair_3d.cpp.
//
// Both take the dual coefficients A_e with their derivatives dA_e from
// CoefficientLinearization, so dA_e enters and a slave facet computes it once for all its
// master candidates.
#include "seam/mortar/linearization_kernels.hpp"
#include "seam/mortar/pair_integration.hpp"

namespace seam::mortar {
struct PairLinearization;
}

namespace seam::mortar::ad {

/// The dual coefficients A_e of a slave facet in its current configuration and their
/// derivatives with respect to its nodal coordinates (ALGORITHMS.md §3:
/// dA_e = (dD_e - A_e dM_e) M_e^{-1}); they depend on the slave facet only, so a slave facet
/// computes them once for all its master candidates.
struct CoefficientLinearization {
  int n = 0;           ///< slave nodes
  int n_variables = 0; ///< Dim * n
  SmallMatrix A;
  /// dA_jk / dx_v at (j * n + k) * n_variables + v.
  std::array<double, max_facet_nodes * max_facet_nodes * 3 * max_facet_nodes> gradient{};
};

template <int Dim>
void linearize_coefficients(const Facet<Dim>& facet, double modification,
                            CoefficientLinearization& out);

/// linearize_pair in 3D by mixed-mode differentiation (linearization_pair_3d.cpp).
/// `coefficients` are the slave's (required for dual multipliers, ignored otherwise).
void linearize_pair_3d(const SlaveFacet<3>& slave, const Facet<3>& master,
                       const PairOptions& options, const CoefficientLinearization* coefficients,
                       PairLinearization& out);

/// A slave facet on scalar S: coordinates, unit averaged nodal normals (columns) and the
/// multiplier basis evaluated in the same configuration.
template <class S, int Dim> struct SlaveFacetT {
  FacetT<S, Dim> facet;
  Eigen::Matrix<S, Dim, max_facet_nodes> normals = Eigen::Matrix<S, Dim, max_facet_nodes>::Zero();
  Multiplier multiplier = Multiplier::dual;
  double modification = 0.0; ///< a of dual_basis.hpp
  SmallMatrixT<S> A;         ///< dual coefficients; unused for standard multipliers
};

/// PairContribution on scalar S (the counters stay plain).
template <class S> struct PairContributionT {
  int n_slave = 0;
  int n_master = 0;
  SmallMatrixT<S> D;
  SmallMatrixT<S> M;
  NodalVectorT<S> weighted_gap = NodalVectorT<S>::Zero();
  int n_cells = 0;
  double area = 0.0;
  int n_projection_failures = 0;
};

/// Variables of one pair in the layout of linearization.hpp: slave coordinates, master
/// coordinates, slave nodal normals, Dim per node each.
inline int pair_variable_count(int dim, int n_slave, int n_master) {
  return dim * (2 * n_slave + n_master);
}

/// 2D segment-based integration (segmentation_2d.cpp).
template <class S>
PairContributionT<S> integrate_pair_t(const SlaveFacetT<S, 2>& slave, const FacetT<S, 2>& master,
                                      const PairOptions& options);

namespace detail {

template <class S> PairContributionT<S> empty_contribution_t(int n_slave, int n_master) {
  PairContributionT<S> c;
  c.n_slave = n_slave;
  c.n_master = n_master;
  c.D = SmallMatrixT<S>::Zero(n_slave, n_slave);
  c.M = SmallMatrixT<S>::Zero(n_slave, n_master);
  return c;
}

/// detail::accumulate_point of pair_integration.hpp on S (with the same dual-multiplier row-sum
/// accumulation of D).
template <class S>
void accumulate_point_t(PairContributionT<S>& c, Multiplier multiplier, const S& w,
                        const NodalVectorT<S>& N_tilde, const NodalVectorT<S>& Phi,
                        const NodalVectorT<S>& Nm, const S& gap) {
  // Dual: D_jj gets w Phi_j sum_l Nm_l, the row sum of this point's M entries.
  S master_sum = 0.0;
  if (multiplier == Multiplier::dual)
    for (int l = 0; l < c.n_master; ++l) master_sum += Nm(l);
  for (int j = 0; j < c.n_slave; ++j) {
    const S wphi = w * Phi(j);
    for (int l = 0; l < c.n_master; ++l) add_product(c.M(j, l), wphi, Nm(l));
    if (multiplier == Multiplier::dual) {
      add_product(c.D(j, j), wphi, master_sum);
    } else {
      for (int k = 0; k < c.n_slave; ++k) add_product(c.D(j, k), wphi, N_tilde(k));
    }
    add_product(c.weighted_gap(j), wphi, gap);
  }
}

} // namespace detail

extern template PairContributionT<double>
integrate_pair_t(const SlaveFacetT<double, 2>&, const FacetT<double, 2>&, const PairOptions&);
extern template PairContributionT<Dual<12>>
integrate_pair_t(const SlaveFacetT<Dual<12>, 2>&, const FacetT<Dual<12>, 2>&, const PairOptions&);
extern template PairContributionT<Dual<18>>
integrate_pair_t(const SlaveFacetT<Dual<18>, 2>&, const FacetT<Dual<18>, 2>&, const PairOptions&);

} // namespace seam::mortar::ad
