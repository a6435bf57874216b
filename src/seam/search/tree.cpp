#include "seam/search/tree.hpp"

#include "seam/common/error.hpp"

#include <cmath>

namespace seam::search {

namespace {

Tree::Variant make_variant(int dim, BoundingVolume volume) {
  if (dim == 2) {
    if (volume == BoundingVolume::aabb) return detail::Bvh<2, 2>{};
    return detail::Bvh<2, 4>{};
  }
  if (volume == BoundingVolume::aabb) return detail::Bvh<3, 3>{};
  return detail::Bvh<3, 9>{};
}

} // namespace

Tree::Tree(const FacetSurface& surface, const TreeOptions& options,
           std::span<const double> old_coords)
    : dim_(surface.dim), options_(options) {
  check_surface(surface);
  SEAM_CHECK(std::isfinite(options.inflation) && options.inflation >= 0.0, InputError,
             "search: inflation must be a finite distance >= 0, got ", options.inflation);
  SEAM_CHECK(options.rebuild_factor >= 1.0, InputError, "search: rebuild_factor must be >= 1, got ",
             options.rebuild_factor);
  SEAM_CHECK(options.leaf_size >= 1 && options.leaf_size <= 64, InputError,
             "search: leaf_size must be in [1, 64], got ", options.leaf_size);
  check_coords(surface.coords, old_coords);
  bvh_ = make_variant(dim_, options.volume);
  std::visit(
      [&](auto& b) {
        b.build(surface, old_coords, options.inflation, options.leaf_size, options.normal_cones);
        build_quality_ = b.quality();
      },
      bvh_);
}

void Tree::check_coords(std::span<const double> coords, std::span<const double> old_coords) const {
  for (double x : coords)
    SEAM_CHECK(std::isfinite(x), InputError, "search: non-finite node coordinate");
  SEAM_CHECK(old_coords.empty() || old_coords.size() == coords.size(), InputError,
             "search: ", old_coords.size(), " step-start coordinates for ", coords.size(),
             " current ones");
  for (double x : old_coords)
    SEAM_CHECK(std::isfinite(x), InputError, "search: non-finite step-start coordinate");
}

bool Tree::update(std::span<const double> coords, std::span<const double> old_coords) {
  const std::size_t expected = std::visit([](const auto& b) { return b.n_coords(); }, bvh_);
  SEAM_CHECK(coords.size() == expected, InputError, "search: update with ", coords.size(),
             " coordinates, the tree was built on ", expected);
  check_coords(coords, old_coords);
  return std::visit(
      [&](auto& b) {
        b.refit(coords, old_coords);
        if (b.quality() <= options_.rebuild_factor * build_quality_) return false;
        b.rebuild_from_leaves();
        build_quality_ = b.quality();
        ++n_rebuilds_;
        return true;
      },
      bvh_);
}

void Tree::rebuild(std::span<const double> coords, std::span<const double> old_coords) {
  const std::size_t expected = std::visit([](const auto& b) { return b.n_coords(); }, bvh_);
  SEAM_CHECK(coords.size() == expected, InputError, "search: rebuild with ", coords.size(),
             " coordinates, the tree was built on ", expected);
  check_coords(coords, old_coords);
  std::visit(
      [&](auto& b) {
        b.refit(coords, old_coords);
        b.rebuild_from_leaves();
        build_quality_ = b.quality();
      },
      bvh_);
  ++n_rebuilds_;
}

local_index Tree::n_facets() const {
  return std::visit([](const auto& b) { return b.n_facets(); }, bvh_);
}

double Tree::quality() const {
  return std::visit([](const auto& b) { return b.quality(); }, bvh_);
}

void Tree::facet_boxes(std::vector<float>& lo, std::vector<float>& hi) const {
  std::visit(
      [&](const auto& b) {
        lo.resize(static_cast<std::size_t>(b.n_facets()) * dim_);
        hi.resize(lo.size());
        for (local_index s = 0; s < b.n_facets(); ++s) {
          const auto& v = b.facet_bounds[s];
          const std::size_t f = static_cast<std::size_t>(b.facet_of_slot[s]) * dim_;
          for (int d = 0; d < dim_; ++d) {
            lo[f + d] = v.lo[d];
            hi[f + d] = v.hi[d];
          }
        }
      },
      bvh_);
}

} // namespace seam::search
