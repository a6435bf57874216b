#include "seam/search/bvh.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace seam::search::detail {

template <int Dim, int NS>
auto Bvh<Dim, NS>::leaf_volume(local_index slot, std::span<const double> coords,
                               std::span<const double> old_coords) const -> Volume {
  KdopBuilder<Dim, NS> b;
  const local_index end = offsets[slot + 1];
  for (local_index k = offsets[slot]; k < end; ++k) {
    const std::size_t i = static_cast<std::size_t>(conn[k]) * Dim;
    b.add_point(coords.data() + i);
    // The volume must hold the facet over the whole step: with the start-of-step position
    // included it covers the motion of each node (the swept hull of a linear motion lies in
    // the hull of both end positions).
    if (!old_coords.empty()) b.add_point(old_coords.data() + i);
  }
  return b.finish(inflation_);
}

template <int Dim, int NS>
void Bvh<Dim, NS>::build(const FacetSurface& surface, std::span<const double> old_coords,
                         double inflation, bool with_normal_cones) {
  n_facets_ = surface.n_facets();
  n_nodes_ = n_facets_ > 0 ? 2 * n_facets_ - 1 : 0;
  n_coords_ = surface.coords.size();
  inflation_ = inflation;
  offsets.assign(surface.offsets.begin(), surface.offsets.end());
  conn.assign(surface.connectivity.begin(), surface.connectivity.end());
  facet_of_slot.resize(n_facets_);
  std::iota(facet_of_slot.begin(), facet_of_slot.end(), 0);

  std::vector<Volume> leaf_volumes(n_facets_);
  std::vector<NormalCone> leaf_cones(with_normal_cones ? n_facets_ : 0);
  for (local_index s = 0; s < n_facets_; ++s) {
    leaf_volumes[s] = leaf_volume(s, surface.coords, old_coords);
    if (with_normal_cones) leaf_cones[s] = facet_normal_cone(Dim, surface.coords, slot_nodes(s));
  }
  cones.assign(with_normal_cones ? n_nodes_ : 0, NormalCone{});
  build_topology(leaf_volumes, leaf_cones);
  merge_upwards();
}

template <int Dim, int NS>
void Bvh<Dim, NS>::refit(std::span<const double> coords, std::span<const double> old_coords) {
  SEAM_ASSERT(coords.size() == n_coords_);
  const bool with_cones = has_normal_cones();
  for (local_index s = 0; s < n_facets_; ++s) {
    const std::int32_t node = node_of_slot[s];
    bounds[node] = leaf_volume(s, coords, old_coords);
    if (with_cones) cones[node] = facet_normal_cone(Dim, coords, slot_nodes(s));
  }
  merge_upwards();
}

template <int Dim, int NS>
void Bvh<Dim, NS>::rebuild_from_leaves() {
  std::vector<Volume> leaf_volumes(n_facets_);
  std::vector<NormalCone> leaf_cones(has_normal_cones() ? n_facets_ : 0);
  for (local_index s = 0; s < n_facets_; ++s) {
    leaf_volumes[s] = bounds[node_of_slot[s]];
    if (has_normal_cones()) leaf_cones[s] = cones[node_of_slot[s]];
  }
  build_topology(leaf_volumes, leaf_cones);
  merge_upwards();
}

template <int Dim, int NS>
void Bvh<Dim, NS>::build_topology(const std::vector<Volume>& leaf_volumes,
                                  const std::vector<NormalCone>& leaf_cones) {
  links.resize(n_nodes_);
  bounds.resize(n_nodes_);
  node_of_slot.resize(n_facets_);
  if (n_facets_ == 0) return;

  // Split positions are the centres of the leaves' axis-aligned extents.
  std::vector<float> centre(static_cast<std::size_t>(n_facets_) * Dim);
  for (local_index s = 0; s < n_facets_; ++s)
    for (int d = 0; d < Dim; ++d)
      centre[s * Dim + d] = 0.5f * leaf_volumes[s].lo[d] + 0.5f * leaf_volumes[s].hi[d];

  // order[new slot] = old slot
  std::vector<local_index> order(n_facets_);
  std::iota(order.begin(), order.end(), 0);

  struct Task {
    std::int32_t node, begin, end;
  };
  std::vector<Task> tasks;
  tasks.reserve(128);
  tasks.push_back({0, 0, n_facets_});
  std::int32_t next_node = 1;
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    if (t.end - t.begin == 1) {
      links[t.node] = {t.begin, 1};
      node_of_slot[t.begin] = t.node;
      continue;
    }
    float lo[Dim], hi[Dim];
    for (int d = 0; d < Dim; ++d) {
      lo[d] = std::numeric_limits<float>::infinity();
      hi[d] = -std::numeric_limits<float>::infinity();
    }
    for (std::int32_t i = t.begin; i < t.end; ++i) {
      const float* c = centre.data() + static_cast<std::size_t>(order[i]) * Dim;
      for (int d = 0; d < Dim; ++d) {
        lo[d] = std::min(lo[d], c[d]);
        hi[d] = std::max(hi[d], c[d]);
      }
    }
    int axis = 0;
    for (int d = 1; d < Dim; ++d)
      if (hi[d] - lo[d] > hi[axis] - lo[axis]) axis = d;
    local_index* first = order.data() + t.begin;
    local_index* last = order.data() + t.end;
    auto key = [&](local_index s) { return centre[static_cast<std::size_t>(s) * Dim + axis]; };
    std::int32_t mid = t.begin + (t.end - t.begin) / 2;
    if (hi[axis] > lo[axis]) {
      // Midpoint split of the longest extent (ALGORITHMS.md Sect. 6); it adapts to the
      // distribution of the facets. A median split takes over when all centres fall on one
      // side, which bounds the depth for clustered input.
      const float split = 0.5f * lo[axis] + 0.5f * hi[axis];
      const std::int32_t m = static_cast<std::int32_t>(
          std::partition(first, last, [&](local_index s) { return key(s) < split; }) -
          order.data());
      if (m > t.begin && m < t.end)
        mid = m;
      else
        std::nth_element(first, order.data() + mid, last,
                         [&](local_index a, local_index b) { return key(a) < key(b); });
    }
    // All centres equal (e.g. every facet in one point): any balanced split will do.
    const std::int32_t left = next_node;
    next_node += 2;
    links[t.node] = {left, t.end - t.begin};
    tasks.push_back({left + 1, mid, t.end});
    tasks.push_back({left, t.begin, mid});
  }
  SEAM_ASSERT(next_node == n_nodes_);

  // Put the facets, their connectivity and leaf data into the new slot order.
  std::vector<local_index> facet(n_facets_), new_offsets(n_facets_ + 1), new_conn(conn.size());
  new_offsets[0] = 0;
  for (local_index s = 0; s < n_facets_; ++s) {
    const local_index old = order[s];
    facet[s] = facet_of_slot[old];
    const local_index n = offsets[old + 1] - offsets[old];
    std::copy_n(conn.data() + offsets[old], n, new_conn.data() + new_offsets[s]);
    new_offsets[s + 1] = new_offsets[s] + n;
    bounds[node_of_slot[s]] = leaf_volumes[old];
    if (!leaf_cones.empty()) cones[node_of_slot[s]] = leaf_cones[old];
  }
  facet_of_slot.swap(facet);
  offsets.swap(new_offsets);
  conn.swap(new_conn);
}

template <int Dim, int NS>
void Bvh<Dim, NS>::merge_upwards() {
  // Children follow their parent, so one backward sweep sees every child before its parent.
  const bool with_cones = has_normal_cones();
  double inner = 0.0, leaves = 0.0;
  for (std::int32_t i = n_nodes_ - 1; i >= 0; --i) {
    const Link l = links[i];
    if (l.count == 1) {
      leaves += margin<Dim>(bounds[i]);
      continue;
    }
    bounds[i] = merge(bounds[l.first], bounds[l.first + 1]);
    inner += margin<Dim>(bounds[i]);
    if (with_cones) cones[i] = merge(cones[l.first], cones[l.first + 1]);
  }
  quality_ = leaves > 0.0 ? inner / leaves : 0.0;
}

template class Bvh<2, 2>;
template class Bvh<2, 4>;
template class Bvh<3, 3>;
template class Bvh<3, 9>;

} // namespace seam::search::detail
