#include "seam/problem/contact_search.hpp"

#include "seam/common/error.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/search/traversal.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <string>

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

constexpr double default_skin_factor = 0.25;

void hand_ghosts(contact::ContactInterface& itf, const parallel::SurfacePart& ghosts) {
  itf.set_master_facets(ghosts.facet_ids, ghosts.offsets, ghosts.connectivity, ghosts.node_ids,
                        ghosts.coords);
}

} // namespace

double ContactSearch::skin_factor() {
  const char* text = std::getenv("SEAM_GHOST_SKIN");
  if (text == nullptr || *text == '\0') return default_skin_factor;
  char* end = nullptr;
  const double value = std::strtod(text, &end);
  SEAM_CHECK(end != text && *end == '\0' && value >= 0.0 && std::isfinite(value), InputError,
             "SEAM_GHOST_SKIN='", text,
             "': expected a number >= 0 (the ghosting skin as a "
             "fraction of the mean slave edge)");
  return value;
}

ContactSearch::ContactSearch(MPI_Comm comm, contact::ContactInterface& itf,
                             std::vector<local_index> held)
    : comm_(comm), skin_(skin_factor() * itf.slave_mesh_size()), held_(std::move(held)) {
  std::sort(held_.begin(), held_.end());
  if (itf.self_contact()) {
    ghosts_.emplace(comm, itf.search_inflation(), skin_);
  } else {
    parallel::DistributedSearchOptions options;
    options.skin = skin_;
    search_.emplace(comm, itf.search_inflation(), options);
  }
  itf.use_external_search();
}

local_index ContactSearch::n_received() const {
  return search_ ? search_->stats().n_ghosts : ghosts_->ghosts().n_facets();
}

std::int64_t ContactSearch::n_exchanges() const {
  return search_ ? search_->n_exchanges() : ghosts_->n_exchanges();
}

std::int64_t ContactSearch::n_searches() const {
  return search_ ? search_->n_searches() : ghosts_->n_updates();
}

void ContactSearch::nodes_read(const contact::ContactInterface& itf,
                               std::vector<local_index>& out) const {
  const auto& side = itf.self_contact() ? itf.slave() : itf.master();
  const auto set = side.facet_set();
  for (const auto f : held_)
    for (const auto n : set.facet_nodes(f)) out.push_back(n);
  const auto& ghosts = search_ ? search_->ghosts() : ghosts_->ghosts();
  for (const auto id : ghosts.node_ids) out.push_back(static_cast<local_index>(id));
}

void ContactSearch::find(contact::ContactInterface& itf) {
  if (ghosts_) {
    find_self(itf);
    return;
  }
  side_part(itf.slave(), itf.owned_facets(), local_, slave_part_);
  side_part(itf.master(), held_, local_, master_part_);
  search_->find_pairs(slave_part_, master_part_, itf.master().coordinates);
  pairs_.clear();
  const auto& ghosts = search_->ghosts();
  for (const auto& p : search_->pairs())
    pairs_.push_back({static_cast<local_index>(slave_part_.facet_ids[p.slave]),
                      static_cast<local_index>(ghosts.facet_ids[p.master])});
  // The integration reads the master facets from the ghosts, not from the side held whole.
  hand_ghosts(itf, ghosts);
  itf.set_candidates(pairs_);
}

void ContactSearch::find_self(contact::ContactInterface& itf) {
  const auto& side = itf.slave();
  const auto owned = itf.owned_facets();
  side_part(side, owned, local_, slave_part_);
  side_part(side, held_, local_, master_part_);
  ghosts_->update(slave_part_, master_part_, side.coordinates);
  const auto& ghosts = ghosts_->ghosts();
  // The self pairs among this rank's facets and its ghosts; the tree is kept while the ghosts
  // are the same facets.
  std::vector<search::CandidatePair> found, mine, facing;
  if (!owned.empty() && ghosts.n_facets() >= 2) {
    if (tree_ && ghosts.facet_ids == tree_facets_) {
      tree_->update(ghosts.coords);
    } else {
      tree_.emplace(contact::self_contact_tree(ghosts.view(), itf.search_inflation()));
      tree_facets_ = ghosts.facet_ids;
    }
    search::find_self_pairs(*tree_, found);
  } else {
    tree_.reset();
  }
  // Each pair once: on the rank that evaluates its lower facet (every facet of the surface is
  // evaluated on one rank, and a facet's partners are all ghosted to that rank).
  for (const auto& p : found) {
    const auto a = static_cast<local_index>(ghosts.facet_ids[static_cast<std::size_t>(p.slave)]);
    const auto b = static_cast<local_index>(ghosts.facet_ids[static_cast<std::size_t>(p.master)]);
    const auto lo = std::min(a, b);
    if (std::binary_search(owned.begin(), owned.end(), lo)) mine.push_back({lo, std::max(a, b)});
  }
  contact::keep_facing_pairs(side, itf.search_inflation(), mine, facing);
  // The contact graph of all ranks: the roles of a group of pairs depend on the whole group.
  // Each pair comes with its facets' normal axes from the rank that found it (which reads
  // both facets; the others' positions of them may be stale).
  std::vector<contact::FacingPair> with;
  contact::with_axes(side, facing, with);
  std::vector<std::int64_t> offsets;
  const auto all = parallel::allgatherv<contact::FacingPair>(comm_, with, offsets);
  contact::orient_pairs(side.n_facets(), all, pairs_);
  hand_ghosts(itf, ghosts);
  itf.set_candidates(pairs_);
}

} // namespace seam::problem
