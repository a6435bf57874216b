#pragma once
// Interface-level assembly of the mortar operators (ALGORITHMS.md §1-§4): loop over
// candidate (slave facet, master facet) pairs, integrate each pair, scatter the local blocks
// into node-indexed triplets. No PETSc: the strategy layer (mesh tying, contact) moves the
// triplets into distributed matrices, expanding each scalar entry by the ndim identity block
// of the seed paper, eqs. (15)-(16).
#include <algorithm>
#include <limits>
#include <span>
#include <utility>
#include <vector>

#include "seam/mortar/pair_integration.hpp"

namespace seam::mortar {

struct Triplet {
  local_index row = 0;
  local_index col = 0;
  double value = 0.0;
};

/// Indices of a slave facet and a master facet that may overlap (from a search).
struct CandidatePair {
  local_index slave = 0;
  local_index master = 0;
};

struct MortarOptions {
  Multiplier multiplier = Multiplier::dual;
  PairOptions pair;
  /// 2D: the pairs (slave facet, master facet of the facet sets integrated; sorted) that are
  /// integrated without the centre-normal pre-check (PairOptions::max_normal_alignment_2d):
  /// contact keeps a pair that passed it once in a step attempt (contact::ContactInterface::
  /// keep_prechecked_pairs), so that the pair does not leave and enter from one Newton
  /// iterate to the next.
  std::vector<std::pair<local_index, local_index>> prechecked = {};
  /// The options of pair (slave, master): `pair`, without the 2D pre-check for a pair of
  /// `prechecked`.
  PairOptions pair_options(local_index slave, local_index master) const {
    if (prechecked.empty() ||
        !std::binary_search(prechecked.begin(), prechecked.end(), std::pair(slave, master)))
      return pair;
    PairOptions o = pair;
    o.max_normal_alignment_2d = std::numeric_limits<double>::infinity();
    return o;
  }
};

struct MortarOperators {
  int dim = 0;
  Multiplier multiplier = Multiplier::dual;
  /// D (slave node, slave node) and M (slave node, master node) as triplets sorted by
  /// (row, col) without duplicates. Node indices are those of the slave / master FacetSet.
  /// Bound slave nodes have no row; their columns of D couple the known displacements of
  /// the bound nodes into the constraint. With dual multipliers D is diagonal apart from
  /// the bound columns.
  std::vector<Triplet> D;
  std::vector<Triplet> M;
  /// Weighted gap g~_j per slave node (zero off the interface).
  std::vector<double> weighted_gap;
  /// Averaged unit nodal normals of the slave surface, dim values per slave node.
  std::vector<double> nodal_normals;
  /// Nodal transformation d = T d~ of the slave nodes when their displacement basis is
  /// modified (dual multipliers on tri6/quad8; ALGORITHMS.md §3): D, M and the weighted gap
  /// then refer to the modified basis, i.e. the constraint reads D d~_S = M d_M. One row per
  /// slave facet node; empty when no facet is modified (T = I).
  std::vector<Triplet> T;
  /// Per slave node: nonzero if bound (a copy of the bound_slave_nodes argument); empty if
  /// no node is bound.
  std::vector<char> bound;

  /// Integration cells per slave facet (the work each facet took; zero without candidates).
  std::vector<local_index> slave_facet_cells;
  local_index n_candidates = 0;
  local_index n_pairs_integrated = 0; ///< candidate pairs with a non-empty overlap
  local_index n_integration_cells = 0;
  local_index n_projection_failures = 0;
  double integrated_area = 0.0; ///< sum of segment lengths (2D) / cell areas (3D)
};

/// Assemble D, M and the weighted gap of one interface in the configuration given by the
/// coordinates of the two facet sets. `bound_slave_nodes` (per slave node, or empty) marks
/// "bound" nodes: their displacement is known (all components prescribed), so they carry no
/// multiplier and the facets around them use the boundary-modified basis (see
/// boundary_transformation in dual_basis.hpp). Throws InputError for inconsistent input (see
/// validate), mismatched dimensions or candidate indices out of range.
MortarOperators assemble_mortar_operators(const FacetSet& slave, const FacetSet& master,
                                          std::span<const CandidatePair> candidates,
                                          const MortarOptions& options = {},
                                          std::span<const char> bound_slave_nodes = {});

/// Sort triplets by (row, col) and sum duplicates.
void compress(std::vector<Triplet>& triplets);
/// The same for rows known to lie in [0, n_rows): bucketed by row in O(n).
void compress(std::vector<Triplet>& triplets, local_index n_rows);

/// T^{-1} for the nodal transformation T of a modified slave basis (same sparsity). Vertex
/// rows of T are unit rows, so an edge row d_e = T_ee d~_e + sum_v T_ev d~_v inverts to
/// d~_e = (d_e - sum_v T_ev d_v) / T_ee. Empty for an empty T (identity).
std::vector<Triplet> inverse_transformation(std::span<const Triplet> T);

/// Mesh initialization for exact angular momentum (ALGORITHMS.md §4; Puso 2004): the slave
/// coordinates with every interface slave node moved so that D X_S = M X_M holds — dual:
/// X~_S = D^{-1} M X_M directly; standard: a sparse LU solve; then X_S = T X~_S when the slave
/// basis is modified. Slave nodes without a row of D keep their coordinates. Returns the new
/// slave coordinate array (same layout as the slave FacetSet's).
std::vector<double> initialize_slave_coordinates(const MortarOperators& operators,
                                                 std::span<const double> slave_coordinates,
                                                 std::span<const double> master_coordinates);

} // namespace seam::mortar
