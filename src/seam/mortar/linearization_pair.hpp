#pragma once
// The element-pair mortar kernels of pair_integration.hpp (2D segmentation, 3D auxiliary
// plane + clipping) on a scalar type S. With S = double they reproduce integrate_pair; with
// S = Dual<N> every output — D, M, weighted gaps — carries its exact derivative with respect
// to whatever the caller seeded: slave and master nodal coordinates, slave nodal normals
// (ALGORITHMS.md §5, consistent linearization). The dual coefficients A_e are recomputed from
// the slave facet's current coordinates, so dA_e enters too.
//
// Instantiated for S = double, Dual<12>, Dual<18> (2D) and double, Dual<36>, Dual<81> (3D):
// enough for every pair's variables Dim * (2 n_slave + n_master), see pair_variable_count.
#include "seam/mortar/linearization_kernels.hpp"
#include "seam/mortar/pair_integration.hpp"

namespace seam::mortar::ad {

/// A slave facet on scalar S: coordinates, unit averaged nodal normals (columns) and the
/// multiplier basis evaluated in the same configuration.
template <class S, int Dim> struct SlaveFacetT {
  FacetT<S, Dim> facet;
  Eigen::Matrix<S, Dim, max_facet_nodes> normals = Eigen::Matrix<S, Dim, max_facet_nodes>::Zero();
  Multiplier multiplier = Multiplier::dual;
  double modification = 0.0; ///< a of dual_basis.hpp
  SmallMatrixT<S> A;         ///< dual coefficients; unused for standard multipliers
};

template <class S, int Dim>
SlaveFacetT<S, Dim> make_slave_facet_t(const FacetT<S, Dim>& facet,
                                       const Eigen::Matrix<S, Dim, max_facet_nodes>& normals,
                                       Multiplier multiplier) {
  SlaveFacetT<S, Dim> s;
  s.facet = facet;
  s.normals = normals;
  s.multiplier = multiplier;
  s.modification = basis_modification(facet.type, multiplier);
  if (multiplier == Multiplier::dual) s.A = dual_coefficients_t(facet, s.modification);
  return s;
}

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

/// 3D integration via auxiliary planes and clipping (integration_3d.cpp).
template <class S>
PairContributionT<S> integrate_pair_t(const SlaveFacetT<S, 3>& slave, const FacetT<S, 3>& master,
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

/// N~ and Phi = A N~ (or N~) from the standard shape values N (slave_functions).
template <class S, int Dim>
void slave_functions_t(const SlaveFacetT<S, Dim>& slave, const NodalVectorT<S>& N,
                       NodalVectorT<S>& N_tilde, NodalVectorT<S>& Phi) {
  N_tilde = N;
  modify_basis_t(slave.facet.type, slave.modification, N_tilde);
  if (slave.multiplier == Multiplier::dual) {
    const int n = slave.facet.n_nodes;
    Phi.setZero();
    for (int j = 0; j < n; ++j)
      for (int k = 0; k < n; ++k) add_product(Phi(j), slave.A(j, k), N_tilde(k));
  } else {
    Phi = N_tilde;
  }
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
extern template PairContributionT<double>
integrate_pair_t(const SlaveFacetT<double, 3>&, const FacetT<double, 3>&, const PairOptions&);
extern template PairContributionT<Dual<36>>
integrate_pair_t(const SlaveFacetT<Dual<36>, 3>&, const FacetT<Dual<36>, 3>&, const PairOptions&);
extern template PairContributionT<Dual<81>>
integrate_pair_t(const SlaveFacetT<Dual<81>, 3>&, const FacetT<Dual<81>, 3>&, const PairOptions&);

} // namespace seam::mortar::ad
