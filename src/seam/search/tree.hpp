#pragma once
// seam::search::Tree: a bounding volume tree over one facet surface, kept between Newton
// iterations (seed paper Sect. 3.2): built once top-down, refitted bottom-up in O(n) on every
// update, rebuilt only when its quality has degraded.
#include "seam/search/bvh.hpp"
#include "seam/search/facets.hpp"
#include "seam/search/kdop.hpp"

#include <span>
#include <variant>
#include <vector>

namespace seam::search {

struct TreeOptions {
  BoundingVolume volume = BoundingVolume::kdop;
  /// Distance by which every facet's bounding volume is widened (absolute length; see
  /// min_edge_length for the usual choice eps * l_min).
  double inflation = 0.0;
  /// Rebuild on update when quality() exceeds this factor times its value after the last
  /// (re)build; must be >= 1.
  double rebuild_factor = 1.5;
  /// Keep normal cones per node; required by find_self_pairs.
  bool normal_cones = false;
  /// Most facets per leaf (1 gives the textbook one-facet leaves). Results do not depend on it.
  int leaf_size = 4;
};

class Tree {
public:
  /// Builds the tree on `surface` (copying its connectivity; coordinates are not kept).
  /// `old_coords` (optional, same layout as surface.coords) are the positions at the start of
  /// the step: every volume then covers the facet's motion over the step.
  Tree(const FacetSurface& surface, const TreeOptions& options,
       std::span<const double> old_coords = {});

  /// New positions of the same nodes (and optionally the step-start positions): refits, and
  /// rebuilds when the quality has degraded. Returns true if it rebuilt.
  bool update(std::span<const double> coords, std::span<const double> old_coords = {});

  /// Refits to `coords` and then always rebuilds the topology.
  void rebuild(std::span<const double> coords, std::span<const double> old_coords = {});

  int dim() const { return dim_; }
  BoundingVolume volume() const { return options_.volume; }
  const TreeOptions& options() const { return options_; }
  local_index n_facets() const;
  double inflation() const { return options_.inflation; }
  /// Node margins over facet margins (see detail::Bvh::quality), and its value after the
  /// last (re)build.
  double quality() const;
  double build_quality() const { return build_quality_; }
  int n_rebuilds() const { return n_rebuilds_; }

  /// The axis-aligned part of each facet's bounding volume, in facet order, dim() values per
  /// facet: for comparing with other searches on identical boxes.
  void facet_boxes(std::vector<float>& lo, std::vector<float>& hi) const;

  using Variant =
      std::variant<detail::Bvh<2, 2>, detail::Bvh<2, 4>, detail::Bvh<3, 3>, detail::Bvh<3, 9>>;
  const Variant& bvh() const { return bvh_; }

private:
  void check_coords(std::span<const double> coords, std::span<const double> old_coords) const;

  int dim_;
  TreeOptions options_;
  Variant bvh_;
  double build_quality_ = 0.0;
  int n_rebuilds_ = 0;
};

} // namespace seam::search
