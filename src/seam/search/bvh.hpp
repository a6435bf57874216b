#pragma once
// The bounding volume hierarchy behind seam::search::Tree (internal; use tree.hpp).
//
// Flat arrays, no per-node allocation: node i has a Link and a Kdop (and, for self contact, a
// NormalCone) at index i. The tree is built top-down (ALGORITHMS.md Sect. 6: split the longest
// extent at its midpoint); children are stored as adjacent pairs and always after their parent,
// so a refit is one backward sweep over the arrays, O(n). Leaves hold one facet each and are
// numbered in tree order ("slots"); the connectivity is kept permuted into slot order, so a
// refit reads it sequentially.
#include "seam/common/types.hpp"
#include "seam/search/facets.hpp"
#include "seam/search/kdop.hpp"
#include "seam/search/normal_cone.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::search::detail {

/// Topology of a node: a leaf has count == 1 and first = its slot; an inner node has
/// first = index of its left child (the right child is first + 1) and count = its leaf count.
struct Link {
  std::int32_t first;
  std::int32_t count;
};

template <int Dim, int NS>
class Bvh {
public:
  using Volume = Kdop<NS>;

  /// Copies the connectivity of `surface` and builds the tree on surface.coords (and the
  /// coordinates at the step start, if given). `inflation` widens every leaf volume.
  void build(const FacetSurface& surface, std::span<const double> old_coords, double inflation,
             bool with_normal_cones);

  /// Recomputes the leaf volumes from new coordinates and merges them bottom-up.
  void refit(std::span<const double> coords, std::span<const double> old_coords);

  /// New topology from the current leaf volumes (call after refit).
  void rebuild_from_leaves();

  local_index n_facets() const { return n_facets_; }
  local_index n_nodes() const { return n_nodes_; }
  std::size_t n_coords() const { return n_coords_; }
  double inflation() const { return inflation_; }
  bool has_normal_cones() const { return !cones.empty(); }

  /// Sum of the margins of the inner nodes over that of the leaves: grows when facets move
  /// away from the neighbours they were grouped with; invariant under scaling.
  double quality() const { return quality_; }

  /// Nodes of facet slot s (in the permuted connectivity).
  std::span<const local_index> slot_nodes(local_index s) const {
    return {conn.data() + offsets[s], static_cast<std::size_t>(offsets[s + 1] - offsets[s])};
  }

  std::vector<Link> links;
  std::vector<Volume> bounds;
  std::vector<NormalCone> cones;           ///< per node; empty unless built with normal cones
  std::vector<local_index> facet_of_slot;  ///< original facet number of each leaf slot
  std::vector<std::int32_t> node_of_slot;  ///< node index of each leaf slot
  std::vector<local_index> offsets, conn;  ///< connectivity in slot order

private:
  Volume leaf_volume(local_index slot, std::span<const double> coords,
                     std::span<const double> old_coords) const;
  void build_topology(const std::vector<Volume>& leaf_volumes,
                      const std::vector<NormalCone>& leaf_cones);
  void merge_upwards();

  local_index n_facets_ = 0;
  local_index n_nodes_ = 0; ///< tree nodes, 2 n_facets - 1
  double inflation_ = 0.0;
  double quality_ = 0.0;
  std::size_t n_coords_ = 0; ///< size of the coordinate arrays the connectivity indexes
};

extern template class Bvh<2, 2>;
extern template class Bvh<2, 4>;
extern template class Bvh<3, 3>;
extern template class Bvh<3, 9>;

} // namespace seam::search::detail
