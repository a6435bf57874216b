#pragma once
// Averaged nodal normals of a slave surface (ALGORITHMS.md §1; Popp et al. 2009, 2010):
// n_j = normalized sum of the unit normals of the facets adjacent to node j, each evaluated
// at the node. They define the projection directions of 2D segmentation and the normal of
// the weighted gap; interpolated along a facet, n(xi) = sum N_k(xi) n_k / |.|.
#include <vector>

#include "seam/mortar/facet.hpp"

namespace seam::mortar {

/// Below this length the sum of the unit facet normals at a node has no direction: the normals
/// cancel.
inline constexpr double min_normal_sum = 1e-8;

/// dim values per node of the set's coordinate array; zero vectors for nodes on no facet.
/// Throws InputError if the normals at a node cancel (a surface folded onto itself).
std::vector<double> averaged_nodal_normals(const FacetSet& facets);
/// The averaged unit normals of the nodes `nodes` only, from the facets `adjacent` (sorted
/// facet indices holding every facet around those nodes, e.g. the union of their adjacent
/// facets): bit for bit the values of the whole computation at those nodes (the facets are
/// summed in the same order); zero at every other node.
std::vector<double> averaged_nodal_normals(const FacetSet& facets,
                                           std::span<const local_index> adjacent,
                                           std::span<const local_index> nodes);

/// The first node of the set at which the normals of its facets cancel (their sum is shorter
/// than min_normal_sum: the surface folds back onto itself there), -1 if there is none. Throws
/// only on a degenerate facet, as averaged_nodal_normals.
local_index folded_node(const FacetSet& facets);

/// Unit normal interpolated from nodal normals (columns) with shape values N.
template <int Dim>
Eigen::Matrix<double, Dim, 1>
interpolated_normal(const Eigen::Matrix<double, Dim, max_facet_nodes>& nodal_normals,
                    const NodalVector& N) {
  return (nodal_normals * N).normalized();
}

} // namespace seam::mortar
