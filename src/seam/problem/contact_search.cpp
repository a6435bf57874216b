#include "seam/problem/contact_search.hpp"

#include <algorithm>

namespace seam::problem {

namespace {

/// Facets `facets` of `side` at its current positions, as a surface part: facet ids and node
/// ids are the side-local ones (the same on every rank, which holds the side whole).
void side_part(const meshtying::InterfaceSide& side, std::span<const local_index> facets,
               std::vector<local_index>& local, parallel::SurfacePart& out) {
  const int dim = side.dim;
  out.dim = dim;
  out.facet_ids.clear();
  out.offsets.assign(1, 0);
  out.connectivity.clear();
  out.node_ids.clear();
  out.coords.clear();
  local.assign(side.mesh_nodes.size(), -1);
  const auto set = side.facet_set();
  for (const auto f : facets) {
    out.facet_ids.push_back(f);
    for (const auto n : set.facet_nodes(f)) {
      const auto i = static_cast<std::size_t>(n);
      if (local[i] < 0) {
        local[i] = out.n_nodes();
        out.node_ids.push_back(n);
        for (int c = 0; c < dim; ++c) out.coords.push_back(side.coordinates[i * dim + c]);
      }
      out.connectivity.push_back(local[i]);
    }
    out.offsets.push_back(static_cast<local_index>(out.connectivity.size()));
  }
}

} // namespace

ContactSearch::ContactSearch(MPI_Comm comm, contact::ContactInterface& itf,
                             std::vector<local_index> held_masters)
    : held_masters_(std::move(held_masters)), search_(comm, itf.search_inflation()) {
  std::sort(held_masters_.begin(), held_masters_.end());
  itf.use_external_search();
}

void ContactSearch::find(contact::ContactInterface& itf) {
  std::vector<local_index> local;
  side_part(itf.slave(), itf.owned_facets(), local, slave_part_);
  side_part(itf.master(), held_masters_, local, master_part_);
  search_.find_pairs(slave_part_, master_part_);
  pairs_.clear();
  const auto& ghosts = search_.ghosts();
  for (const auto& p : search_.pairs())
    pairs_.push_back({static_cast<local_index>(slave_part_.facet_ids[p.slave]),
                      static_cast<local_index>(ghosts.facet_ids[p.master])});
  itf.set_candidates(pairs_);
}

} // namespace seam::problem
