#include "seam/problem/contact_search.hpp"

#include "seam/common/error.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/search/traversal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <string>

namespace seam::problem {

namespace {

constexpr double default_skin_factor = 0.25;

local_index index_of(std::span<const std::int64_t> ids, std::int64_t id, const char* what) {
  const auto it = std::lower_bound(ids.begin(), ids.end(), id);
  SEAM_CHECK(it != ids.end() && *it == id, InternalError, "contact search: ", what, " id ", id,
             " is not on the side");
  return static_cast<local_index>(it - ids.begin());
}

/// A facing pair as it crosses the ranks: its facets by global id.
struct GlobalFacingPair {
  std::int64_t slave = 0, master = 0;
  std::array<double, 3> slave_axis, master_axis;
};

} // namespace

bool master_held_in_part(const io::Interface& itf, const io::Config&) {
  return itf.type == io::InterfaceType::contact && itf.master && itf.surface.empty();
}

bool slave_held_in_part(const io::Interface& itf, const io::Config&) {
  const bool rigid = itf.rigid_plane.has_value() || itf.rigid_obstacle.has_value();
  return itf.type == io::InterfaceType::contact && (itf.master || rigid || !itf.surface.empty());
}

local_index SideIds::facet(std::int64_t id) const {
  return index_of(facets, id, "facet");
}
local_index SideIds::node(std::int64_t id) const {
  return index_of(nodes, id, "node");
}

void ContactSearch::hand_ghosts(contact::ContactInterface& itf,
                                const parallel::SurfacePart& ghosts) {
  // The interface indexes its sides locally: the ghosts' global ids are mapped back.
  const auto& ids = ghosts_ ? slave_ids_ : master_ids_;
  ghost_facets_.resize(ghosts.facet_ids.size());
  for (std::size_t f = 0; f < ghost_facets_.size(); ++f)
    ghost_facets_[f] = ids.facet(ghosts.facet_ids[f]);
  ghost_nodes_.resize(ghosts.node_ids.size());
  for (std::size_t n = 0; n < ghost_nodes_.size(); ++n)
    ghost_nodes_[n] = ids.node(ghosts.node_ids[n]);
  itf.set_master_facets(ghost_facets_, ghosts.offsets, ghosts.connectivity, ghost_nodes_,
                        ghosts.coords);
}

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

bool ContactSearch::roles_kept() {
  const char* text = std::getenv("SEAM_SELF_ROLES_ANEW");
  if (text == nullptr || *text == '\0') return true;
  const std::string value = text;
  SEAM_CHECK(value == "0" || value == "1", InputError, "SEAM_SELF_ROLES_ANEW='", value,
             "': expected 0 or 1 (1: self-contact roles assigned anew at every search)");
  return value == "0";
}

bool ContactSearch::roles_kept_across_steps() {
  const char* text = std::getenv("SEAM_SELF_ROLES_STEP");
  if (text == nullptr || *text == '\0') return true;
  const std::string value = text;
  SEAM_CHECK(value == "0" || value == "1", InputError, "SEAM_SELF_ROLES_STEP='", value,
             "': expected 0 or 1 (1: self-contact roles assigned anew at each step's first "
             "search)");
  return value == "0";
}

ContactSearch::ContactSearch(MPI_Comm comm, contact::ContactInterface& itf,
                             std::vector<local_index> held, SideIds slave, SideIds master,
                             bool master_in_part)
    : comm_(comm), skin_(skin_factor() * itf.slave_mesh_size()), in_part_(master_in_part),
      held_(std::move(held)), slave_ids_(std::move(slave)), master_ids_(std::move(master)) {
  std::sort(held_.begin(), held_.end());
  // The ids increase along the sides (local numbering monotone in the mesh as read), so a
  // side-local index is found by bisection.
  for (const auto* ids : {&slave_ids_, &master_ids_})
    SEAM_CHECK(std::is_sorted(ids->facets.begin(), ids->facets.end()) &&
                   std::is_sorted(ids->nodes.begin(), ids->nodes.end()),
               InternalError, "contact search: side ids not increasing");
  if (itf.self_contact()) {
    ghosts_.emplace(comm, itf.search_inflation(), skin_);
    keep_roles_ = roles_kept();
    keep_across_ = keep_roles_ && roles_kept_across_steps();
    // The facets handed in by id: a surface held in part changes with each distribution.
    for (const auto f : held_) held_ids_.push_back(slave_ids_.facets[static_cast<std::size_t>(f)]);
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
  if (itf.self_contact())
    for (const auto id : held_ids_)
      for (const auto n : set.facet_nodes(slave_ids_.facet(id))) out.push_back(n);
  else
    for (const auto f : held_)
      for (const auto n : set.facet_nodes(f)) out.push_back(n);
  if (in_part_) return;
  const auto& ghosts = search_ ? search_->ghosts() : ghosts_->ghosts();
  const auto& ids = ghosts_ ? slave_ids_ : master_ids_;
  for (const auto id : ghosts.node_ids) out.push_back(ids.node(id));
}

void ContactSearch::find(contact::ContactInterface& itf, std::span<const double> ghost_positions,
                         const NodeMap& mesh_nodes) {
  if (ghosts_) {
    find_self(itf, ghost_positions, mesh_nodes);
    return;
  }
  const auto owned = itf.owned_facets();
  meshtying::side_part(itf.slave(), slave_ids_.facets, slave_ids_.nodes, owned, local_,
                       slave_part_);
  meshtying::side_part(itf.master(), master_ids_.facets, master_ids_.nodes, held_, local_,
                       master_part_);
  if (in_part_) {
    const auto positions = reused_positions(itf, search_->ghosts(), ghost_positions);
    search_->find_pairs(slave_part_, master_part_, positions, position_ids_);
    pairs_.clear();
    for (const auto& p : search_->pairs())
      pairs_.push_back({owned[static_cast<std::size_t>(p.slave)], p.master});
    return;
  }
  search_->find_pairs(slave_part_, master_part_, itf.master().coordinates, master_ids_.nodes);
  pairs_.clear();
  const auto& ghosts = search_->ghosts();
  for (const auto& p : search_->pairs())
    pairs_.push_back({owned[static_cast<std::size_t>(p.slave)],
                      master_ids_.facet(ghosts.facet_ids[static_cast<std::size_t>(p.master)])});
  // The integration reads the master facets from the ghosts, not from the side held whole.
  hand_ghosts(itf, ghosts);
  itf.set_candidates(pairs_);
}

std::span<const double> ContactSearch::reused_positions(const contact::ContactInterface& itf,
                                                        const parallel::SurfacePart& ghosts,
                                                        std::span<const double> positions) {
  // Reused ghosts take their positions from the caller: their nodes need not be held.
  position_ids_ = ghosts.node_ids;
  const auto dim = static_cast<std::size_t>(itf.dim());
  SEAM_CHECK(positions.size() == position_ids_.size() * dim, InternalError,
             "contact search: ", positions.size() / dim, " ghost positions for ",
             position_ids_.size(), " ghost nodes");
  static constexpr double none[3] = {0.0, 0.0, 0.0};
  return positions.empty() ? std::span<const double>(none, dim) : positions;
}

void ContactSearch::hand_in_part(contact::ContactInterface& itf,
                                 std::span<const std::int32_t> mesh_nodes) {
  SEAM_ASSERT(in_part_);
  const auto& ghosts = search_->ghosts();
  // The pairs name the ghosts by their index, which the interface takes as their facet id.
  ghost_facets_.resize(ghosts.facet_ids.size());
  for (std::size_t f = 0; f < ghost_facets_.size(); ++f)
    ghost_facets_[f] = static_cast<std::int64_t>(f);
  itf.set_master_facets(ghost_facets_, ghosts.offsets, ghosts.connectivity, ghosts.node_ids,
                        ghosts.coords, mesh_nodes);
  itf.set_candidates(pairs_);
}

void ContactSearch::start_step() {
  if (!ghosts_) return;
  // A new attempt starts from the roles of the last converged step, as the first did.
  if (keep_across_)
    roles_ = roles_accepted_;
  else
    roles_.clear();
  roles_started_ = keep_roles_;
  first_find_ = true;
  for (const auto& [id, role] : role_in_step_) role_before_[id] = role;
  role_in_step_.clear();
}

namespace {

FacetIdPair unordered(const FacetIdPair& p) {
  return {std::min(p.slave, p.master), std::max(p.slave, p.master)};
}

bool by_ids(const FacetIdPair& a, const FacetIdPair& b) {
  return a.slave != b.slave ? a.slave < b.slave : a.master < b.master;
}

} // namespace

void ContactSearch::accept_step() {
  if (!ghosts_) return;
  roles_accepted_.clear();
  pairs_accepted_.clear();
  for (const auto& p : pair_ids_) {
    for (const auto id : {p.slave, p.master}) {
      const auto it = roles_.find(id);
      if (it != roles_.end()) roles_accepted_[id] = it->second;
    }
    pairs_accepted_.push_back(p);
  }
  std::sort(pairs_accepted_.begin(), pairs_accepted_.end(),
            [](const FacetIdPair& a, const FacetIdPair& b) {
              return by_ids(unordered(a), unordered(b));
            });
}

void ContactSearch::accepted_roles(std::vector<std::int64_t>& ids, std::vector<std::int64_t>& roles,
                                   std::vector<std::int64_t>& pairs, bool held) const {
  const auto mine = [&](std::int64_t id) {
    return !held || std::binary_search(held_ids_.begin(), held_ids_.end(), id);
  };
  ids.clear();
  roles.clear();
  pairs.clear();
  for (const auto& [id, role] : roles_accepted_) {
    if (!mine(id)) continue;
    ids.push_back(id);
    roles.push_back(static_cast<std::int64_t>(role));
  }
  for (const auto& p : pairs_accepted_) {
    if (!mine(std::min(p.slave, p.master))) continue;
    pairs.push_back(p.slave);
    pairs.push_back(p.master);
  }
}

void ContactSearch::restore_roles(std::span<const std::int64_t> ids,
                                  std::span<const std::int64_t> roles,
                                  std::span<const std::int64_t> pairs) {
  SEAM_CHECK(ids.size() == roles.size() && pairs.size() % 2 == 0, InternalError,
             "contact search: ", ids.size(), " facets for ", roles.size(), " roles, ", pairs.size(),
             " pair ids");
  std::vector<FacetIdPair> mine(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) mine[i] = {ids[i], roles[i]};
  std::vector<std::int64_t> offsets;
  const auto all = parallel::allgatherv<FacetIdPair>(comm_, mine, offsets);
  roles_accepted_.clear();
  for (const auto& [id, role] : all)
    roles_accepted_[id] = role == 0 ? search::Role::slave : search::Role::master;
  mine.resize(pairs.size() / 2);
  for (std::size_t i = 0; i < mine.size(); ++i) mine[i] = {pairs[2 * i], pairs[2 * i + 1]};
  pairs_accepted_ = parallel::allgatherv<FacetIdPair>(comm_, mine, offsets);
  std::sort(pairs_accepted_.begin(), pairs_accepted_.end(),
            [](const FacetIdPair& a, const FacetIdPair& b) {
              return by_ids(unordered(a), unordered(b));
            });
  roles_.clear();
}

void ContactSearch::count_role_changes() {
  // At the first search of a step attempt: the pairs of the last converged step that persist
  // with the other facet as slave.
  if (first_find_)
    for (const auto& p : pair_ids_) {
      const auto it = std::lower_bound(pairs_accepted_.begin(), pairs_accepted_.end(), p,
                                       [](const FacetIdPair& a, const FacetIdPair& b) {
                                         return by_ids(unordered(a), unordered(b));
                                       });
      role_changes_.persisting +=
          it != pairs_accepted_.end() && unordered(*it) == unordered(p) && it->slave != p.slave;
    }
  first_find_ = false;
  // Per facet: bit 0 slave of a pair, bit 1 master of a pair.
  std::map<std::int64_t, std::uint8_t> seen;
  for (const auto& p : pair_ids_) {
    seen[p.slave] |= 1;
    seen[p.master] |= 2;
  }
  for (const auto& [id, bits] : seen) {
    if (bits != 1 && bits != 2) continue;
    const auto role = bits == 1 ? search::Role::slave : search::Role::master;
    const auto in_step = role_in_step_.find(id);
    if (in_step != role_in_step_.end()) {
      role_changes_.within += in_step->second != role;
    } else {
      const auto before = role_before_.find(id);
      if (before != role_before_.end()) role_changes_.between += before->second != role;
    }
    role_in_step_[id] = role;
  }
}

void ContactSearch::to_interface(std::span<const FacetIdPair> pairs,
                                 std::vector<mortar::CandidatePair>& out) {
  const auto& facets = slave_ids_.facets;
  const auto& ghosts = ghosts_->ghosts().facet_ids;
  const auto index = [](std::span<const std::int64_t> ids, std::int64_t id) {
    const auto it = std::lower_bound(ids.begin(), ids.end(), id);
    return it != ids.end() && *it == id ? static_cast<local_index>(it - ids.begin())
                                        : local_index{-1};
  };
  out.clear();
  for (const auto& p : pairs) {
    const auto slave = index(facets, p.slave);
    if (slave < 0) continue;
    out.push_back({slave, index(in_part_ ? std::span<const std::int64_t>(ghosts)
                                         : std::span<const std::int64_t>(facets),
                                p.master)});
  }
}

void ContactSearch::find_self(contact::ContactInterface& itf, std::span<const double> positions,
                              const NodeMap& mesh_nodes) {
  const auto& side = itf.slave();
  const auto owned = itf.owned_facets();
  std::vector<local_index> held(held_ids_.size());
  for (std::size_t i = 0; i < held.size(); ++i) held[i] = slave_ids_.facet(held_ids_[i]);
  meshtying::side_part(side, slave_ids_.facets, slave_ids_.nodes, owned, local_, slave_part_);
  meshtying::side_part(side, slave_ids_.facets, slave_ids_.nodes, held, local_, master_part_);
  if (in_part_) {
    const auto reused = reused_positions(itf, ghosts_->ghosts(), positions);
    ghosts_->update(slave_part_, master_part_, reused, position_ids_);
  } else {
    ghosts_->update(slave_part_, master_part_, side.coordinates, slave_ids_.nodes);
  }
  const auto& ghosts = ghosts_->ghosts();
  // The ghosts to the integration (a surface held in part: their nodes as mesh or outside
  // nodes); the facing test and the axes below read the facets as the ghosts have them.
  if (in_part_) {
    ghost_facets_.resize(ghosts.facet_ids.size());
    for (std::size_t f = 0; f < ghost_facets_.size(); ++f)
      ghost_facets_[f] = static_cast<std::int64_t>(f);
    const auto nodes = mesh_nodes(ghosts.node_ids);
    itf.set_master_facets(ghost_facets_, ghosts.offsets, ghosts.connectivity, ghosts.node_ids,
                          ghosts.coords, nodes);
  } else {
    hand_ghosts(itf, ghosts);
  }
  const auto& surface = itf.master_read();
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
  // evaluated on one rank, and a facet's partners are all ghosted to that rank). The pairs in
  // ghost indices, which increase with the facet ids.
  for (const auto& p : found) {
    const auto lo = std::min(p.slave, p.master);
    if (std::binary_search(slave_part_.facet_ids.begin(), slave_part_.facet_ids.end(),
                           ghosts.facet_ids[static_cast<std::size_t>(lo)]))
      mine.push_back({lo, std::max(p.slave, p.master)});
  }
  contact::keep_facing_pairs(surface, itf.search_inflation(), mine, facing);
  // The contact graph of all ranks: the roles of a group of pairs depend on the whole group.
  // Each pair comes with its facets' normal axes from the rank that found it (which reads
  // both facets; the others' positions of them may be stale).
  std::vector<contact::FacingPair> with;
  contact::with_axes(surface, facing, with);
  std::vector<GlobalFacingPair> send(with.size());
  for (std::size_t i = 0; i < with.size(); ++i)
    send[i] = {ghosts.facet_ids[static_cast<std::size_t>(with[i].pair.slave)],
               ghosts.facet_ids[static_cast<std::size_t>(with[i].pair.master)], with[i].slave_axis,
               with[i].master_axis};
  std::vector<std::int64_t> offsets;
  const auto all = parallel::allgatherv<GlobalFacingPair>(comm_, send, offsets);
  // The roles over the facets of the pairs only (O(pairs), not O(surface)), numbered in the
  // order of their ids, so that "the lowest facet" is the one of lowest id.
  std::vector<std::int64_t> ids;
  for (const auto& p : all) {
    ids.push_back(p.slave);
    ids.push_back(p.master);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  const auto number = [&](std::int64_t id) { return index_of(ids, id, "paired facet"); };
  with.resize(all.size());
  for (std::size_t i = 0; i < all.size(); ++i)
    with[i] = {
        {number(all[i].slave), number(all[i].master)}, all[i].slave_axis, all[i].master_axis};
  // The first search of a step attempt keeps the roles of the last converged step only for
  // the facets of pairs that persist: a facet whose pairs are all new takes a role anew.
  if (first_find_ && keep_across_) {
    std::vector<std::int64_t> persisting;
    for (const auto& p : all) {
      const FacetIdPair key = unordered({p.slave, p.master});
      const auto it = std::lower_bound(
          pairs_accepted_.begin(), pairs_accepted_.end(), key,
          [](const FacetIdPair& a, const FacetIdPair& b) { return by_ids(unordered(a), b); });
      if (it != pairs_accepted_.end() && unordered(*it) == key) {
        persisting.push_back(p.slave);
        persisting.push_back(p.master);
      }
    }
    std::sort(persisting.begin(), persisting.end());
    std::erase_if(roles_, [&](const auto& entry) {
      return !std::binary_search(persisting.begin(), persisting.end(), entry.first);
    });
  }
  std::vector<search::Role> roles;
  if (roles_started_) {
    roles.resize(ids.size(), search::Role::none);
    for (std::size_t f = 0; f < ids.size(); ++f) {
      const auto it = roles_.find(ids[f]);
      if (it != roles_.end()) roles[f] = it->second;
    }
  }
  contact::orient_pairs(static_cast<local_index>(ids.size()), with, pairs_, roles);
  same_roles_ = 0;
  for (const auto& p : pairs_)
    same_roles_ += !roles.empty() && roles[static_cast<std::size_t>(p.slave)] ==
                                         roles[static_cast<std::size_t>(p.master)];
  for (std::size_t f = 0; f < roles.size(); ++f)
    if (roles[f] != search::Role::none) roles_[ids[f]] = roles[f];
  pair_ids_.resize(pairs_.size());
  for (std::size_t i = 0; i < pairs_.size(); ++i)
    pair_ids_[i] = {ids[static_cast<std::size_t>(pairs_[i].slave)],
                    ids[static_cast<std::size_t>(pairs_[i].master)]};
  count_role_changes();
  to_interface(pair_ids_, pairs_);
  itf.set_candidates(pairs_);
}

} // namespace seam::problem
