#pragma once
// The bounding volume hierarchy behind seam::search::Tree (internal; use tree.hpp).
//
// Flat arrays, no per-node allocation. The tree is built top-down (ALGORITHMS.md Sect. 6: split
// the longest extent at its midpoint) and stored in depth-first preorder: the left child of node
// i is node i + 1, so every subtree is one contiguous run of the node array, and a node's
// volume and topology sit together in one record. A traversal that descends the tree therefore
// walks forward through memory, and a refit is one backward sweep, O(n), that sees every child
// before its parent. Facets are renumbered in tree order ("slots"): a leaf holds a contiguous
// run of slots, and facet volumes, cones and connectivity are stored in slot order, so leaves
// that are neighbours in the tree are neighbours in memory. Leaves of a few facets (leaf_size,
// default 4) make the tree about four times smaller, which matters once the trees no longer
// fit in cache.
#include "seam/common/types.hpp"
#include "seam/search/facets.hpp"
#include "seam/search/huge_page_allocator.hpp"
#include "seam/search/kdop.hpp"
#include "seam/search/normal_cone.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::search::detail {

/// Topology of a node. An inner node i has its left child at i + 1, first = index of its right
/// child and count = the number of facets below it (>= 2). A leaf holds the facet slots
/// first .. first + n - 1 and stores count = -n.
struct Link {
  std::int32_t first;
  std::int32_t count;
};

/// One tree node: its volume and its topology, read together by every node visit.
template <int NS> struct Node {
  Kdop<NS> bounds;
  Link link;
};

inline bool is_leaf(Link l) {
  return l.count < 0;
}
inline std::int32_t n_facets_below(Link l) {
  return l.count < 0 ? -l.count : l.count;
}

/// Flat array of the tree (see huge_page_allocator.hpp).
template <class T> using Array = std::vector<T, HugePageAllocator<T>>;

template <int Dim, int NS> class Bvh {
public:
  using Volume = Kdop<NS>;

  /// Copies the connectivity of `surface` and builds the tree on surface.coords (and the
  /// coordinates at the step start, if given). `inflation` widens every facet volume; a leaf
  /// holds at most `leaf_size` facets.
  void build(const FacetSurface& surface, std::span<const double> old_coords, double inflation,
             int leaf_size, bool with_normal_cones);

  /// Recomputes the facet volumes from new coordinates and merges them bottom-up.
  void refit(std::span<const double> coords, std::span<const double> old_coords);

  /// New topology from the current facet volumes (call after refit).
  void rebuild_from_leaves();

  local_index n_facets() const { return n_facets_; }
  std::int32_t n_tree_nodes() const { return static_cast<std::int32_t>(nodes.size()); }
  std::size_t n_coords() const { return n_coords_; }
  double inflation() const { return inflation_; }
  bool has_normal_cones() const { return !cones.empty(); }

  /// Sum of the margins of all tree nodes over that of the facets: grows when facets move away
  /// from the neighbours they were grouped with; invariant under scaling.
  double quality() const { return quality_; }

  /// Nodes of facet slot s (in the permuted connectivity).
  std::span<const local_index> slot_nodes(local_index s) const {
    return {conn.data() + offsets[s], static_cast<std::size_t>(offsets[s + 1] - offsets[s])};
  }

  Array<Node<NS>> nodes;            ///< the tree in depth-first preorder; node 0 is the root
  Array<NormalCone> cones;          ///< per tree node; empty unless built with cones
  Array<Volume> facet_bounds;       ///< per facet slot (tree order)
  Array<NormalCone> facet_cones;    ///< per facet slot; empty unless built with cones
  Array<local_index> facet_of_slot; ///< original facet number of each slot
  Array<local_index> offsets, conn; ///< connectivity in slot order

private:
  Volume facet_volume(local_index slot, std::span<const double> coords,
                      std::span<const double> old_coords) const;
  void build_topology();
  /// Recomputes the node volumes (and cones) bottom-up; with refit_facets it first recomputes
  /// the facet volumes of each leaf from `coords` (and `old_coords`), in the same sweep.
  void merge_upwards(std::span<const double> coords = {}, std::span<const double> old_coords = {},
                     bool refit_facets = false);

  local_index n_facets_ = 0;
  int leaf_size_ = 1;
  double inflation_ = 0.0;
  double quality_ = 0.0;
  std::size_t n_coords_ = 0; ///< size of the coordinate arrays the connectivity indexes
};

extern template class Bvh<2, 2>;
extern template class Bvh<2, 4>;
extern template class Bvh<3, 3>;
extern template class Bvh<3, 9>;

} // namespace seam::search::detail
