#include "seam/problem/contact_search.hpp"

#include "seam/common/error.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/search/traversal.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <numeric>
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

/// The rank that keeps the self-contact records of facet `id` (its kept roles, the ranks that
/// hold it, the pairs of which it is slave) and decides the roles of a connected group of
/// pairs whose lowest facet is `id`: a hash of the id, so that the records and the decisions
/// spread over the ranks whatever the distribution.
int home_of(std::int64_t id, int size) {
  auto z = static_cast<std::uint64_t>(id) + 0x9e3779b97f4a7c15ull;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
  z ^= z >> 31;
  return static_cast<int>(z % static_cast<std::uint64_t>(size));
}

/// Records sorted by destination rank, sent with one alltoallv; what arrives comes in rank
/// order, each source's records in the order it put them.
template <class T> class Outbox {
public:
  explicit Outbox(MPI_Comm comm) : comm_(comm) {
    int size = 1;
    MPI_Comm_size(comm, &size);
    to_.resize(static_cast<std::size_t>(size));
  }
  int size() const { return static_cast<int>(to_.size()); }
  void put(int rank, const T& record) { to_[static_cast<std::size_t>(rank)].push_back(record); }
  /// Collective. `sources` (optional): the source rank of every record received.
  std::vector<T> exchange(std::vector<int>* sources = nullptr) {
    std::vector<T> flat;
    std::vector<std::int64_t> offsets{0}, recv_offsets;
    for (auto& part : to_) {
      flat.insert(flat.end(), part.begin(), part.end());
      offsets.push_back(static_cast<std::int64_t>(flat.size()));
      part.clear();
    }
    auto received = parallel::alltoallv<T>(comm_, flat, offsets, recv_offsets);
    if (sources) {
      sources->clear();
      for (std::size_t r = 0; r + 1 < recv_offsets.size(); ++r)
        sources->insert(sources->end(),
                        static_cast<std::size_t>(recv_offsets[r + 1] - recv_offsets[r]),
                        static_cast<int>(r));
    }
    return received;
  }

private:
  MPI_Comm comm_;
  std::vector<std::vector<T>> to_;
};

/// The facets of `pairs` by id, sorted, each once.
std::vector<std::int64_t> facets_of(std::span<const GlobalFacingPair> pairs) {
  std::vector<std::int64_t> ids;
  for (const auto& p : pairs) {
    ids.push_back(p.slave);
    ids.push_back(p.master);
  }
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  return ids;
}

struct IdValue {
  std::int64_t id = 0, value = 0;
};

/// The hash of one oriented pair in the fingerprint of a pair set (summed over the pairs).
std::uint64_t mix(std::uint64_t a, std::uint64_t b, std::uint64_t salt) {
  auto z = a * 0x9e3779b97f4a7c15ull ^ (b + salt) * 0xc2b2ae3d27d4eb4full;
  z = (z ^ (z >> 31)) * 0xbf58476d1ce4e5b9ull;
  return z ^ (z >> 29);
}
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
  // The records of this rank (the facets and pairs it keeps): no exchange.
  roles_accepted_.clear();
  for (const auto& [id, bits] : paired_) {
    const auto it = roles_.find(id);
    if (it != roles_.end()) roles_accepted_[id] = it->second;
  }
  pairs_accepted_ = pairs_kept_;
  std::sort(pairs_accepted_.begin(), pairs_accepted_.end(),
            [](const FacetIdPair& a, const FacetIdPair& b) {
              return by_ids(unordered(a), unordered(b));
            });
}

void ContactSearch::accepted_roles(std::vector<std::int64_t>& ids, std::vector<std::int64_t>& roles,
                                   std::vector<std::int64_t>& pairs, bool) const {
  // Each facet's role and each pair are kept on one rank (home_of): the records of this rank.
  ids.clear();
  roles.clear();
  pairs.clear();
  for (const auto& [id, role] : roles_accepted_) {
    ids.push_back(id);
    roles.push_back(static_cast<std::int64_t>(role));
  }
  for (const auto& p : pairs_accepted_) {
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
  // Each record to the rank that keeps it (a checkpoint of any number of ranks).
  Outbox<IdValue> out(comm_);
  for (std::size_t i = 0; i < ids.size(); ++i)
    out.put(home_of(ids[i], out.size()), {ids[i], roles[i]});
  roles_accepted_.clear();
  for (const auto& [id, role] : out.exchange())
    roles_accepted_[id] = role == 0 ? search::Role::slave : search::Role::master;
  Outbox<FacetIdPair> pair_out(comm_);
  for (std::size_t i = 0; i < pairs.size() / 2; ++i)
    pair_out.put(home_of(pairs[2 * i], pair_out.size()), {pairs[2 * i], pairs[2 * i + 1]});
  pairs_accepted_ = pair_out.exchange();
  std::sort(pairs_accepted_.begin(), pairs_accepted_.end(),
            [](const FacetIdPair& a, const FacetIdPair& b) {
              return by_ids(unordered(a), unordered(b));
            });
  pairs_accepted_.erase(std::unique(pairs_accepted_.begin(), pairs_accepted_.end()),
                        pairs_accepted_.end());
  roles_.clear();
}

void ContactSearch::register_holders() {
  // Collective. Whether any rank's side changed since the ranks said which facets they hold.
  int mine = holders_stale_ ? 1 : 0, any = 0;
  MPI_Allreduce(&mine, &any, 1, MPI_INT, MPI_MAX, comm_);
  if (!any) return;
  int rank = 0;
  MPI_Comm_rank(comm_, &rank);
  Outbox<IdValue> out(comm_);
  for (const auto id : slave_ids_.facets) out.put(home_of(id, out.size()), {id, rank});
  holders_.clear();
  for (const auto& [id, holder] : out.exchange()) holders_[id].push_back(holder);
  holders_stale_ = false;
}

void ContactSearch::route_self_pairs() {
  if (!ghosts_) return;
  register_holders();
  // The pairs of the last find() to the ranks that hold their slave facet now.
  Outbox<FacetIdPair> out(comm_);
  for (const auto& p : pairs_kept_) {
    const auto it = holders_.find(p.slave);
    if (it == holders_.end()) continue;
    for (const auto rank : it->second) out.put(static_cast<int>(rank), p);
  }
  pair_ids_ = out.exchange();
  std::sort(pair_ids_.begin(), pair_ids_.end(), by_ids);
  pairs_returned_ = static_cast<std::int64_t>(pair_ids_.size());
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
  // Each pair with its facets' normal axes from the rank that found it (which reads both
  // facets; the others' positions of them may be stale), by facet id.
  std::vector<contact::FacingPair> with;
  contact::with_axes(surface, facing, with);
  std::vector<GlobalFacingPair> found_pairs(with.size());
  for (std::size_t i = 0; i < with.size(); ++i)
    found_pairs[i] = {ghosts.facet_ids[static_cast<std::size_t>(with[i].pair.slave)],
                      ghosts.facet_ids[static_cast<std::size_t>(with[i].pair.master)],
                      with[i].slave_axis, with[i].master_axis};
  decide_roles(found_pairs);
  to_interface(pair_ids_, pairs_);
  itf.set_candidates(pairs_);
}

std::vector<std::int64_t> ContactSearch::group_labels(std::span<const std::int64_t> facets,
                                                      std::vector<local_index>& group,
                                                      std::span<const GlobalFacingPair> pairs) {
  // The roles of a connected group of pairs depend on the whole group, which may span the
  // ranks: each group is named by its lowest facet id. Groups of this rank's pairs first
  // (union-find), then rounds in which each rank says the label of the group of each of its
  // facets to the facet's home rank and takes back the lowest label any rank said for it,
  // until no label falls.
  const auto n = facets.size();
  const auto number = [&](std::int64_t id) { return index_of(facets, id, "paired facet"); };
  std::vector<local_index> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  const auto root = [&](local_index f) {
    while (parent[static_cast<std::size_t>(f)] != f)
      f = parent[static_cast<std::size_t>(f)] =
          parent[static_cast<std::size_t>(parent[static_cast<std::size_t>(f)])];
    return f;
  };
  for (const auto& p : pairs) {
    const auto a = root(number(p.slave)), b = root(number(p.master));
    parent[static_cast<std::size_t>(std::max(a, b))] = std::min(a, b);
  }
  // The facets are sorted by id: a group's root is its lowest facet.
  group.resize(n);
  std::vector<std::int64_t> label;
  std::vector<local_index> group_of_root(n, -1);
  for (std::size_t f = 0; f < n; ++f) {
    const auto r = static_cast<std::size_t>(root(static_cast<local_index>(f)));
    if (group_of_root[r] < 0) {
      group_of_root[r] = static_cast<local_index>(label.size());
      label.push_back(facets[r]);
    }
    group[f] = group_of_root[r];
  }
  label_rounds_ = 0;
  for (;;) {
    ++label_rounds_;
    Outbox<IdValue> out(comm_);
    for (std::size_t f = 0; f < n; ++f)
      out.put(home_of(facets[f], out.size()),
              {facets[f], label[static_cast<std::size_t>(group[f])]});
    std::vector<int> sources;
    const auto said = out.exchange(&sources);
    std::map<std::int64_t, std::int64_t> lowest;
    for (const auto& [id, value] : said) {
      const auto [it, fresh] = lowest.emplace(id, value);
      if (!fresh) it->second = std::min(it->second, value);
    }
    for (std::size_t i = 0; i < said.size(); ++i)
      out.put(sources[i], {said[i].id, lowest[said[i].id]});
    int fell = 0;
    for (const auto& [id, value] : out.exchange()) {
      auto& l = label[static_cast<std::size_t>(group[static_cast<std::size_t>(number(id))])];
      if (value < l) {
        l = value;
        fell = 1;
      }
    }
    int any = 0;
    MPI_Allreduce(&fell, &any, 1, MPI_INT, MPI_MAX, comm_);
    if (!any) break;
  }
  return label;
}

void ContactSearch::decide_roles(std::span<const GlobalFacingPair> found) {
  register_holders();
  // The labels of the groups of this rank's pairs.
  const auto facets = facets_of(found);
  std::vector<local_index> group;
  const auto label = group_labels(facets, group, found);
  const auto label_of = [&](std::int64_t id) {
    return label[static_cast<std::size_t>(
        group[static_cast<std::size_t>(index_of(facets, id, "paired facet"))])];
  };
  const auto decider = [&](std::int64_t id, int size) { return home_of(label_of(id), size); };
  // Each pair to the rank that decides its group (home_of its label); the kept roles and the
  // holders of its facets and whether it is a pair of the last converged step, asked of their
  // home ranks for the deciding rank.
  Outbox<GlobalFacingPair> pair_out(comm_);
  Outbox<IdValue> facet_asks(comm_);
  struct PairAsk {
    FacetIdPair key; // (lower, higher facet)
    std::int64_t to = 0;
  };
  Outbox<PairAsk> pair_asks(comm_);
  const int size = pair_out.size();
  for (auto p : found) {
    p.group = label_of(p.slave);
    pair_out.put(home_of(p.group, size), p);
  }
  for (const auto id : facets) facet_asks.put(home_of(id, size), {id, decider(id, size)});
  for (const auto& p : found) {
    const auto key = unordered({p.slave, p.master});
    const auto d = decider(p.slave, size);
    for (const auto h : {home_of(key.slave, size), home_of(key.master, size)}) {
      pair_asks.put(h, {key, d});
      if (home_of(key.slave, size) == home_of(key.master, size)) break;
    }
  }
  const auto pairs = pair_out.exchange();
  pairs_received_ = static_cast<std::int64_t>(pairs.size());
  {
    std::vector<std::int64_t> groups;
    for (const auto& p : pairs) groups.push_back(p.group);
    std::sort(groups.begin(), groups.end());
    groups_decided_ = std::unique(groups.begin(), groups.end()) - groups.begin();
  }
  const auto asked = facet_asks.exchange();
  const auto asked_pairs = pair_asks.exchange();
  // The answers of the home ranks: per facet its kept role (-1: none) and one record per
  // rank holding it (holder -1: none); per pair of the last converged step its slave.
  struct FacetRecord {
    std::int64_t id = 0, role = -1, holder = -1;
  };
  Outbox<FacetRecord> facet_answers(comm_);
  for (const auto& [id, to] : asked) {
    const auto r = roles_.find(id);
    const std::int64_t role = r == roles_.end() ? -1 : static_cast<std::int64_t>(r->second);
    const auto h = holders_.find(id);
    if (h == holders_.end() || h->second.empty())
      facet_answers.put(static_cast<int>(to), {id, role, -1});
    else
      for (const auto holder : h->second)
        facet_answers.put(static_cast<int>(to), {id, role, holder});
  }
  Outbox<FacetIdPair> pair_answers(comm_);
  for (const auto& [key, to] : asked_pairs) {
    const auto it = std::lower_bound(
        pairs_accepted_.begin(), pairs_accepted_.end(), key,
        [](const FacetIdPair& a, const FacetIdPair& b) { return by_ids(unordered(a), b); });
    if (it != pairs_accepted_.end() && unordered(*it) == key)
      pair_answers.put(static_cast<int>(to), *it);
  }
  const auto facet_records = facet_answers.exchange();
  auto accepted = pair_answers.exchange();
  std::sort(accepted.begin(), accepted.end(), [](const FacetIdPair& a, const FacetIdPair& b) {
    return by_ids(unordered(a), unordered(b));
  });
  const auto accepted_slave = [&](const FacetIdPair& key) -> std::int64_t {
    const auto it = std::lower_bound(
        accepted.begin(), accepted.end(), key,
        [](const FacetIdPair& a, const FacetIdPair& b) { return by_ids(unordered(a), b); });
    return it != accepted.end() && unordered(*it) == key ? it->slave : -1;
  };

  // The decision over the groups this rank decides, as one whole search does it over all
  // groups (contact::orient_pairs: the roles of a group depend on its pairs only): the facets
  // numbered in the order of their ids, so that "the lowest facet" is the one of lowest id, and
  // the pairs in the order of the ranks that found them.
  const auto ids = facets_of(pairs);
  const auto number = [&](std::int64_t id) { return index_of(ids, id, "paired facet"); };
  std::vector<contact::FacingPair> with(pairs.size());
  for (std::size_t i = 0; i < pairs.size(); ++i)
    with[i] = {{number(pairs[i].slave), number(pairs[i].master)},
               pairs[i].slave_axis,
               pairs[i].master_axis};
  std::vector<search::Role> kept(ids.size(), search::Role::none);
  std::vector<std::vector<std::int64_t>> holders(ids.size());
  for (const auto& r : facet_records) {
    const auto f = static_cast<std::size_t>(number(r.id));
    if (r.role >= 0) kept[f] = static_cast<search::Role>(r.role);
    if (r.holder >= 0) holders[f].push_back(r.holder);
  }
  for (auto& h : holders) { // a facet asked for by several ranks is answered to each
    std::sort(h.begin(), h.end());
    h.erase(std::unique(h.begin(), h.end()), h.end());
  }
  // The first search of a step attempt keeps the roles of the last converged step only for
  // the facets of pairs that persist: a facet whose pairs are all new takes a role anew.
  if (first_find_ && keep_across_) {
    std::vector<char> persisting(ids.size(), 0);
    for (const auto& p : pairs)
      if (accepted_slave(unordered({p.slave, p.master})) >= 0)
        persisting[static_cast<std::size_t>(number(p.slave))] =
            persisting[static_cast<std::size_t>(number(p.master))] = 1;
    for (std::size_t f = 0; f < ids.size(); ++f)
      if (!persisting[f]) kept[f] = search::Role::none;
  }
  std::vector<search::Role> roles;
  if (roles_started_) roles = kept;
  std::vector<mortar::CandidatePair> oriented;
  contact::orient_pairs(static_cast<local_index>(ids.size()), with, oriented, roles);

  // Counted here, summed over the ranks below: pairs of facets of the same role; at the first
  // search of a step attempt the pairs of the last converged step found again exchanged; the
  // fingerprint of the pair set.
  std::int64_t counts[5] = {0, 0, static_cast<std::int64_t>(oriented.size()), 0, 0};
  std::uint64_t hashes[2] = {0, 0};
  Outbox<FacetIdPair> pairs_back(comm_), pairs_home(comm_);
  std::vector<std::uint8_t> bits(ids.size(), 0); // bit 0 slave of a pair, bit 1 master
  for (const auto& p : oriented) {
    const auto s = static_cast<std::size_t>(p.slave), m = static_cast<std::size_t>(p.master);
    counts[0] += !roles.empty() && roles[s] == roles[m];
    const FacetIdPair by_id{ids[s], ids[m]};
    if (first_find_) {
      const auto slave = accepted_slave(unordered(by_id));
      counts[1] += slave >= 0 && slave != by_id.slave;
    }
    hashes[0] += mix(static_cast<std::uint64_t>(by_id.slave),
                     static_cast<std::uint64_t>(by_id.master), 0x51ed27u);
    hashes[1] += mix(static_cast<std::uint64_t>(by_id.master),
                     static_cast<std::uint64_t>(by_id.slave), 0x2545f491u);
    for (const auto holder : holders[s]) pairs_back.put(static_cast<int>(holder), by_id);
    pairs_home.put(home_of(by_id.slave, size), by_id);
    bits[s] |= 1;
    bits[m] |= 2;
  }
  // Per facet to its home: its role bits at this search and its role kept (-1: none).
  struct FacetBits {
    std::int64_t id = 0, bits = 0, role = -1;
  };
  Outbox<FacetBits> facet_out(comm_);
  for (std::size_t f = 0; f < ids.size(); ++f)
    facet_out.put(home_of(ids[f], size),
                  {ids[f], bits[f], roles.empty() ? -1 : static_cast<std::int64_t>(roles[f])});
  pair_ids_ = pairs_back.exchange();
  std::sort(pair_ids_.begin(), pair_ids_.end(), by_ids);
  pair_ids_.erase(std::unique(pair_ids_.begin(), pair_ids_.end()), pair_ids_.end());
  pairs_returned_ = static_cast<std::int64_t>(pair_ids_.size());
  pairs_kept_ = pairs_home.exchange();
  // The records of this rank's facets: the roles kept in the step (at the first search of a
  // step attempt those of the facets of persisting pairs and of the new ones only), and the
  // role changes (count_role_changes).
  if (first_find_ && keep_across_) roles_.clear();
  paired_.clear();
  for (const auto& r : facet_out.exchange()) {
    paired_[r.id] = static_cast<std::uint8_t>(r.bits);
    if (r.role >= 0) roles_[r.id] = static_cast<search::Role>(r.role);
  }
  const auto changes = count_role_changes();
  counts[3] = changes.within;
  counts[4] = changes.between;
  first_find_ = false;
  std::int64_t sums[5];
  std::uint64_t hash_sums[2];
  MPI_Allreduce(counts, sums, 5, MPI_INT64_T, MPI_SUM, comm_);
  MPI_Allreduce(hashes, hash_sums, 2, MPI_UINT64_T, MPI_SUM, comm_);
  same_roles_ = sums[0];
  role_changes_.persisting += sums[1];
  pair_set_ = {sums[2], hash_sums[0], hash_sums[1]};
  role_changes_.within += sums[3];
  role_changes_.between += sums[4];
}

ContactSearch::RoleChanges ContactSearch::count_role_changes() {
  // The facets this rank keeps the records of, with their roles at this search: slave (master)
  // if slave (master) of each of its pairs.
  RoleChanges changes;
  for (const auto& [id, bits] : paired_) {
    if (bits != 1 && bits != 2) continue;
    const auto role = bits == 1 ? search::Role::slave : search::Role::master;
    const auto in_step = role_in_step_.find(id);
    if (in_step != role_in_step_.end()) {
      changes.within += in_step->second != role;
    } else {
      const auto before = role_before_.find(id);
      if (before != role_before_.end()) changes.between += before->second != role;
    }
    role_in_step_[id] = role;
  }
  return changes;
}

} // namespace seam::problem
