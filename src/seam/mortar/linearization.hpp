#pragma once
// Consistent linearization of the mortar operators for finite-deformation contact
// (ALGORITHMS.md §5; Popp et al. 2009, 2010): D, M and the weighted gaps g~_j of a slave facet
// in the current configuration together with their exact first derivatives with respect to
// every nodal coordinate they depend on — slave facet nodes, master facet nodes, and the
// nodes of the neighbour facets that enter the averaged nodal normals of the slave nodes.
//
// The pair kernels (linearization_pair.hpp) follow the integrate_pair algorithms: normals and
// their normalization, auxiliary plane, projection into it, clip polygon vertices
// (combinatorics frozen at the evaluation point), fan centroid, cell Jacobians,
// back-projections (implicit function theorem), 2D segment ends, dual coefficients
// A_e = D_e M_e^{-1} and the gap g = n . (x_m - x_s) all carry derivatives. 2D runs the
// kernel with forward-mode dual numbers (seam::Dual) over the pair variables; 3D uses mixed
// mode — small dual numbers for the plane and the clip polygon, hand-chained partial
// derivatives per integration point (linearization_pair_3d.cpp). The dual coefficients and
// their derivatives depend on the slave facet only and are computed once per slave facet in
// linearize_slave_facet. The nodal normals are linearized separately per node,
// n_j = s_j / |s_j| with s_j the sum of the unit facet normals at j,
// dn_j = (I - n_j n_j^T) ds_j / |s_j|, and chained in.
//
// Values agree with integrate_pair / assemble_mortar_operators to round-off (same decisions,
// same formulas), so the derivatives belong to the operators the solver assembles.
#include <array>
#include <span>
#include <vector>

#include "seam/mortar/interface.hpp"
#include "seam/mortar/pair_integration.hpp"

namespace seam::mortar {

/// One pair's D, M and weighted gaps and their gradients. Variables, Dim per node in component
/// order: slave facet node k coordinate a is variable Dim*k + a, master facet node l is
/// Dim*(n_slave + l) + a, and the unit nodal normal of slave node k is
/// Dim*(n_slave + n_master + k) + a (the normals are taken as independent inputs here).
struct PairLinearization {
  int dim = 0;
  int n_slave = 0;
  int n_master = 0;
  int n_variables = 0;
  PairContribution values;
  std::vector<double> D_gradient;   ///< (j * n_slave + k) * n_variables + v
  std::vector<double> M_gradient;   ///< (j * n_master + l) * n_variables + v
  std::vector<double> gap_gradient; ///< j * n_variables + v

  std::span<const double> dD(int j, int k) const { return row(D_gradient, j * n_slave + k); }
  std::span<const double> dM(int j, int l) const { return row(M_gradient, j * n_master + l); }
  std::span<const double> dgap(int j) const { return row(gap_gradient, j); }

private:
  std::span<const double> row(const std::vector<double>& g, int entry) const {
    return std::span<const double>(g).subspan(static_cast<std::size_t>(entry) *
                                                  static_cast<std::size_t>(n_variables),
                                              static_cast<std::size_t>(n_variables));
  }
};

/// Integrate one pair as integrate_pair does and differentiate D, M and g~ with respect to the
/// pair variables. The slave's dual coefficients are recomputed from its coordinates (only
/// slave.basis.multiplier is read). `out` is reused: after the first call of a given size
/// nothing is allocated.
void linearize_pair(const SlaveFacet<2>& slave, const Facet<2>& master, const PairOptions& options,
                    PairLinearization& out);
void linearize_pair(const SlaveFacet<3>& slave, const Facet<3>& master, const PairOptions& options,
                    PairLinearization& out);

/// Facets adjacent to each node of a facet set (CSR: the facets of node i are
/// facets[offsets[i] .. offsets[i+1])).
struct NodeFacets {
  std::vector<local_index> offsets;
  std::vector<local_index> facets;
  std::span<const local_index> of(local_index node) const {
    const auto i = static_cast<std::size_t>(node);
    return std::span<const local_index>(facets).subspan(
        static_cast<std::size_t>(offsets[i]),
        static_cast<std::size_t>(offsets[i + 1] - offsets[i]));
  }
};
NodeFacets node_facets(const FacetSet& facets);

/// The averaged unit normal of one node (normals.hpp) and its Jacobian with respect to the
/// coordinates of the nodes of its adjacent facets.
struct NodalNormalLinearization {
  int dim = 0;
  std::array<double, 3> normal{}; ///< first dim entries
  std::vector<local_index> nodes; ///< nodes of the adjacent facets, ascending
  std::vector<double> jacobian;   ///< dn_a / dx_{nodes[i], b} at a * (dim * n) + dim * i + b
};

/// Linearize the averaged normal of `node` over the facets `adjacent` (all facets of the set
/// that contain the node, e.g. node_facets(facets).of(node)). Throws InputError like
/// averaged_nodal_normals if the facet normals cancel or a facet is degenerate.
void linearize_nodal_normal(const FacetSet& facets, local_index node,
                            std::span<const local_index> adjacent, NodalNormalLinearization& out);

/// D, M and g~ of one slave facet over its contributing master facets, with derivatives with
/// respect to every coordinate involved. Variables, dim per node in component order: first
/// the slave nodes `slave_nodes` (the facet's own nodes in local order, then the other nodes of
/// the facets adjacent to them, ascending), then the master nodes `master_nodes` (the nodes of
/// the listed master facets in order of first appearance): slave_nodes[i] coordinate a is
/// variable dim*i + a, master_nodes[p] is dim*(slave_nodes.size() + p) + a.
/// Rows j are the slave facet's local nodes, D columns too, M columns index master_nodes.
struct SlaveFacetLinearization {
  int dim = 0;
  int n_slave = 0; ///< nodes of the slave facet
  Multiplier multiplier = Multiplier::dual;
  std::vector<local_index> slave_nodes;
  std::vector<local_index> master_nodes;
  std::vector<double> D;            ///< j * n_slave + k
  std::vector<double> M;            ///< j * master_nodes.size() + p
  std::vector<double> weighted_gap; ///< j
  std::vector<double> D_gradient;   ///< entry * n_variables() + v, entries as above
  std::vector<double> M_gradient;
  std::vector<double> gap_gradient;
  int n_pairs_integrated = 0;
  int n_cells = 0;
  int n_projection_failures = 0;
  double area = 0.0;

  int n_master_nodes() const { return static_cast<int>(master_nodes.size()); }
  int n_variables() const {
    return dim * static_cast<int>(slave_nodes.size() + master_nodes.size());
  }
  std::span<const double> dD(int j, int k) const { return row(D_gradient, j * n_slave + k); }
  std::span<const double> dM(int j, int p) const {
    return row(M_gradient, j * n_master_nodes() + p);
  }
  std::span<const double> dgap(int j) const { return row(gap_gradient, j); }

  /// Scratch reused between calls.
  PairLinearization pair;
  std::vector<NodalNormalLinearization> normals;
  std::vector<double> normal_jacobian; ///< (k * dim + a) * n_variables() + v
  std::vector<int> master_position;

private:
  std::span<const double> row(const std::vector<double>& g, int entry) const {
    const auto n = static_cast<std::size_t>(n_variables());
    return std::span<const double>(g).subspan(static_cast<std::size_t>(entry) * n, n);
  }
};

/// Linearize one slave facet against the master facets `master_facets` (its candidates), with
/// the averaged nodal normals built from `slave_facets_of_node` (node_facets(slave) gives the
/// normals averaged_nodal_normals uses). Summed over all slave facets the values are those of
/// assemble_mortar_operators for the same candidates.
void linearize_slave_facet(const FacetSet& slave, const FacetSet& master,
                           const NodeFacets& slave_facets_of_node, local_index slave_facet,
                           std::span<const local_index> master_facets, const MortarOptions& options,
                           SlaveFacetLinearization& out);

} // namespace seam::mortar
