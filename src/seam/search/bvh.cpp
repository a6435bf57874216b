#include "seam/search/bvh.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <limits>
#include <numeric>

namespace seam::search::detail {

template <int Dim, int NS>
auto Bvh<Dim, NS>::facet_volume(local_index slot, std::span<const double> coords,
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
                         double inflation, int leaf_size, bool with_normal_cones) {
  SEAM_ASSERT(leaf_size >= 1);
  n_facets_ = surface.n_facets();
  leaf_size_ = leaf_size;
  n_coords_ = surface.coords.size();
  inflation_ = inflation;
  offsets.assign(surface.offsets.begin(), surface.offsets.end());
  conn.assign(surface.connectivity.begin(), surface.connectivity.end());
  facet_of_slot.resize(n_facets_);
  std::iota(facet_of_slot.begin(), facet_of_slot.end(), 0);
  facet_bounds.resize(n_facets_);
  facet_cones.resize(with_normal_cones ? n_facets_ : 0);
  for (local_index s = 0; s < n_facets_; ++s) {
    facet_bounds[s] = facet_volume(s, surface.coords, old_coords);
    if (with_normal_cones) facet_cones[s] = facet_normal_cone(Dim, surface.coords, slot_nodes(s));
  }
  build_topology();
  merge_upwards();
}

template <int Dim, int NS>
void Bvh<Dim, NS>::refit(std::span<const double> coords, std::span<const double> old_coords) {
  SEAM_ASSERT(coords.size() == n_coords_);
  SEAM_ASSERT(old_coords.empty() || old_coords.size() == n_coords_);
  merge_upwards(coords, old_coords, true);
}

template <int Dim, int NS> void Bvh<Dim, NS>::rebuild_from_leaves() {
  build_topology();
  merge_upwards();
}

template <int Dim, int NS> void Bvh<Dim, NS>::build_topology() {
  nodes.clear();
  if (n_facets_ == 0) {
    cones.clear();
    return;
  }
  nodes.reserve(4 * static_cast<std::size_t>(n_facets_) / leaf_size_ + 1);

  // Split positions are the centres of the facets' axis-aligned extents.
  std::vector<float> centre(static_cast<std::size_t>(n_facets_) * Dim);
  for (local_index s = 0; s < n_facets_; ++s)
    for (int d = 0; d < Dim; ++d)
      centre[s * Dim + d] = 0.5f * facet_bounds[s].lo[d] + 0.5f * facet_bounds[s].hi[d];

  // order[new slot] = old slot
  std::vector<local_index> order(n_facets_);
  std::iota(order.begin(), order.end(), 0);

  // Depth first, left before right, so that nodes are appended in preorder. A right subtree is
  // appended after the whole left one; `parent` is the node whose link must point at it.
  struct Task {
    std::int32_t begin, end, parent;
  };
  std::vector<Task> tasks;
  tasks.reserve(128);
  tasks.push_back({0, n_facets_, -1});
  while (!tasks.empty()) {
    const Task t = tasks.back();
    tasks.pop_back();
    const std::int32_t me = static_cast<std::int32_t>(nodes.size());
    nodes.emplace_back();
    if (t.parent >= 0) nodes[t.parent].link.first = me;
    if (t.end - t.begin <= leaf_size_) {
      nodes[me].link = {t.begin, -(t.end - t.begin)};
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
    nodes[me].link = {-1, t.end - t.begin}; // first is set when the right child is appended
    tasks.push_back({mid, t.end, me});
    tasks.push_back({t.begin, mid, -1});
  }
  cones.resize(facet_cones.empty() ? 0 : nodes.size());

  // Put the facets, their connectivity, volumes and cones into the new slot order.
  Array<local_index> facet(n_facets_), new_offsets(n_facets_ + 1), new_conn(conn.size());
  Array<Volume> volumes(n_facets_);
  Array<NormalCone> facet_normals(facet_cones.size());
  new_offsets[0] = 0;
  for (local_index s = 0; s < n_facets_; ++s) {
    const local_index old = order[s];
    facet[s] = facet_of_slot[old];
    const local_index n = offsets[old + 1] - offsets[old];
    std::copy_n(conn.data() + offsets[old], n, new_conn.data() + new_offsets[s]);
    new_offsets[s + 1] = new_offsets[s] + n;
    volumes[s] = facet_bounds[old];
    if (!facet_cones.empty()) facet_normals[s] = facet_cones[old];
  }
  facet_of_slot.swap(facet);
  offsets.swap(new_offsets);
  conn.swap(new_conn);
  facet_bounds.swap(volumes);
  facet_cones.swap(facet_normals);
}

template <int Dim, int NS>
void Bvh<Dim, NS>::merge_upwards(std::span<const double> coords, std::span<const double> old_coords,
                                 bool refit_facets) {
  // Children follow their parent, so one backward sweep sees every child before its parent. A
  // refit recomputes each leaf's facet volumes right where the leaf is merged: the volumes are
  // still in cache when they are merged, instead of being written in one pass over all facets
  // and read back in a second.
  const bool with_cones = has_normal_cones();
  double node_margins = 0.0, facet_margins = 0.0;
  for (std::int32_t i = n_tree_nodes() - 1; i >= 0; --i) {
    Node<NS>& node = nodes[i];
    const Link l = node.link;
    if (is_leaf(l)) {
      const std::int32_t end = l.first - l.count;
      if (refit_facets)
        for (std::int32_t s = l.first; s < end; ++s) {
          facet_bounds[s] = facet_volume(s, coords, old_coords);
          if (with_cones) facet_cones[s] = facet_normal_cone(Dim, coords, slot_nodes(s));
        }
      Volume v = facet_bounds[l.first];
      facet_margins += margin<Dim>(v);
      for (std::int32_t s = l.first + 1; s < end; ++s) {
        v = merge(v, facet_bounds[s]);
        facet_margins += margin<Dim>(facet_bounds[s]);
      }
      node.bounds = v;
      if (with_cones) {
        NormalCone c = facet_cones[l.first];
        for (std::int32_t s = l.first + 1; s < end; ++s) c = merge(c, facet_cones[s]);
        cones[i] = c;
      }
    } else {
      node.bounds = merge(nodes[i + 1].bounds, nodes[l.first].bounds);
      if (with_cones) cones[i] = merge(cones[i + 1], cones[l.first]);
    }
    node_margins += margin<Dim>(node.bounds);
  }
  quality_ = facet_margins > 0.0 ? node_margins / facet_margins : 0.0;
}

template class Bvh<2, 2>;
template class Bvh<2, 4>;
template class Bvh<3, 3>;
template class Bvh<3, 9>;

} // namespace seam::search::detail
