#pragma once
// The search of a contact interface distributed over the ranks (seed paper Sect. 3;
// docs/parallel.md, "Contact: master facets ghosted" and "Self contact searched distributed").
//
// Two bodies: each rank sends the master facets of the cells it assembles to the ranks whose
// slave elements their bounding boxes can meet (parallel::ghost_masters), and searches its own
// slave elements against the master facets it received (parallel::DistributedSearch). The
// pairs go to the interface (ContactInterface::set_candidates); together the ranks' pairs are
// those of one whole search.
//
// Self and multi-body contact (`surface:`): each rank searches the surface facets it evaluates
// against the surface facets ghosted to it by bounding boxes, with the self-contact tests of
// one whole search (normal cones, no neighbouring facets, facing); a pair is kept by the rank
// of its lower facet, so that every pair is found once. The roles of a connected group of pairs
// depend on the whole group (contact::orient_pairs), which may span the ranks: the groups are
// named by their lowest facet id (a union-find over each rank's pairs, then rounds of lowest
// labels through the facets' home ranks), each group's pairs go to one deciding rank (a hash of
// the label), which orients them as one whole search does, and the oriented pairs go to the
// ranks whose side holds their slave facet. No rank gathers the pairs of all ranks. The records
// the decisions read and keep (kept roles, pairs of the last converged step, role changes, which
// ranks hold a facet) live on the home rank of the facet (a hash of its id). The roles are kept
// through a step (start_step), so that a facet's role changes
// only between steps, and from step to step (accept_step): a facet paired at the last converged
// step keeps its role in the next, so that a master node never becomes a slave node while its
// contact persists; a facet takes a role anew only when it meets after a step without a pair.
// The surface is held in part (slave_held_in_part):
// the ghosts' nodes are then mesh or outside nodes of the rank (as for a master side held in part).
//
// The ghosting is reused between searches (parallel::VerletGhosts): boxes widened by a skin of
// a fraction of the mean facet size, exchanged anew only when a surface node has moved more
// than half the skin since the last exchange.
//
// What crosses the ranks names facets and nodes by their global ids (SideIds: cell of the mesh
// as read and local facet, node of the mesh as read), not by their index in the side, so that
// the side a rank holds need not be whole.
#include "seam/contact/contact_interface.hpp"
#include "seam/parallel/distributed_search.hpp"
#include "seam/parallel/ghosting.hpp"
#include "seam/search/tree.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <vector>

namespace seam::problem {

/// The global ids of the facets and the nodes of an interface side, in the side's order (both
/// increasing): meshtying::facet_gids and the node ids of the mesh as read.
struct SideIds {
  std::vector<std::int64_t> facets, nodes;
  /// The side-local index of facet (node) id `id`; InternalError if the side has none.
  local_index facet(std::int64_t id) const;
  local_index node(std::int64_t id) const;
};

/// A self-contact pair by the global ids of its facets (meshtying::facet_gids).
struct FacetIdPair {
  std::int64_t slave = 0, master = 0;
  friend bool operator==(const FacetIdPair&, const FacetIdPair&) = default;
};

/// A facing self pair as it crosses the ranks: its facets by global id, with the axes of their
/// normal cones as the rank that found it has them (contact::FacingPair), and the label of
/// its connected group of pairs (the group's lowest facet id; set when the labels are known).
struct GlobalFacingPair {
  std::int64_t slave = 0, master = 0;
  std::array<double, 3> slave_axis, master_axis;
  std::int64_t group = -1;
};

/// Whether the master side of interface `itf` is held in part: each rank holds the master
/// facets of its own and ghost cells (the distributed mesh no longer sends every rank the
/// whole side) and reads every other master facet through the ghosts of the search, whose
/// nodes need not be nodes of its part (ContactConstraint numbers them after the mesh nodes,
/// with their global dofs). Every two-body contact interface: with or without friction, dual
/// or standard multipliers (the saddle point's multiplier rows are numbered by the slave
/// nodes' owners and reached by node id), static, dynamic and energy-momentum contact (its gap
/// blocks read the reference coordinates of mesh and outside nodes). `config` is not read.
bool master_held_in_part(const io::Interface& itf, const io::Config& config);

/// Whether the slave side of interface `itf` is held in part too: the distributed mesh holds
/// the slave facets of a rank's own and ghost cells only (with the bulk distribution those of
/// its own cells are the slave elements it evaluates, the ghost layer gives their nodes'
/// rings for the averaged normals); with the independent distribution, after each
/// distribution, the side holds the rings of the slave nodes the rank owns and of the nodes
/// of the slave facets it evaluates, the facets beyond its mesh sent as facets with their
/// nodes' ids, global dofs and coordinates (ContactConstraint::hold_slave_part; with friction
/// also the rings of the slave nodes of its part of M^n); the nodal arrays are per held slave
/// node. Two-body contact whose master side is held in part, and contact against a rigid
/// plane, sphere or cylinder, with or without friction, with either distribution
/// of the interface (`parallel: interface_distribution`); and the surface of self contact
/// (`surface:`) under the same conditions, the rank's own surface facets handed in to the
/// search and the surface facets it pairs beyond its part read as ghosts. Every other
/// interface keeps its slave side whole.
bool slave_held_in_part(const io::Interface& itf, const io::Config& config);

class ContactSearch {
public:
  /// The skin of the reused ghosting as a fraction of the slave side's mean edge: 0.25, or the
  /// value of SEAM_GHOST_SKIN in the environment (0: a ghost exchange at every search; for
  /// tests). InputError for a value that is not a number >= 0.
  static double skin_factor();
  /// Whether self contact keeps the roles of a step's first search through the step: yes,
  /// unless SEAM_SELF_ROLES_ANEW=1 is in the environment (a diagnostic: the roles are then
  /// assigned anew at every search, as before the roles were kept). InputError for a value
  /// other than 0 or 1.
  static bool roles_kept();
  /// Whether self contact keeps the roles of the facets paired at the last converged step
  /// (accept_step) into the next step: yes, unless SEAM_SELF_ROLES_STEP=1 is in the
  /// environment (a diagnostic: the roles are then assigned anew at each step's first search
  /// and kept within the step only, as before the roles were kept across steps). InputError
  /// for a value other than 0 or 1.
  static bool roles_kept_across_steps();

  /// `held`: the facets (side-local: master facets of two bodies, surface facets of self
  /// contact) this rank hands in to the ghosting, each on one rank (e.g. those of the cells it
  /// assembles). `slave`, `master`: the global ids of the slave and the master side (of the
  /// surface twice on self contact). Switches `itf` to the external search.
  /// `master_in_part`: the master side `itf` holds is a part (master_held_in_part; self
  /// contact: the surface held in part, slave_held_in_part).
  ContactSearch(MPI_Comm comm, contact::ContactInterface& itf, std::vector<local_index> held,
                SideIds slave, SideIds master, bool master_in_part = false);

  /// Collective. The candidate pairs of the owned slave facets of `itf` at its last place().
  /// A master side held in part: `ghost_positions` are the current positions of the nodes of
  /// master_ghosts() as the last find() left them (dim per node; read when the ghosts are
  /// reused), and the ghosts and pairs are handed to `itf` by hand_in_part(), the pairs'
  /// master facets being indices into master_ghosts().
  /// Self contact with the surface held in part: `mesh_nodes` maps the node ids of the ghosts
  /// to the mesh or outside nodes of this part (collective), and the pairs' master facets are
  /// indices into the ghosts.
  using NodeMap = std::function<std::span<const std::int32_t>(std::span<const std::int64_t>)>;
  void find(contact::ContactInterface& itf, std::span<const double> ghost_positions = {},
            const NodeMap& mesh_nodes = {});
  bool master_in_part() const { return in_part_; }
  /// The slave side `itf` holds changed (ContactInterface::hold_slave_facets): its ids.
  void set_slave_ids(SideIds slave) {
    slave_ids_ = std::move(slave);
    holders_stale_ = true;
  }
  /// The master facets ghosted to this rank at the last find() (two bodies).
  const parallel::SurfacePart& master_ghosts() const { return search_->ghosts(); }
  /// A master side held in part: the ghosts and pairs of the last find() to `itf`, with the
  /// mesh node of every ghost node (numbers beyond the mesh's nodes for those outside it).
  void hand_in_part(contact::ContactInterface& itf, std::span<const std::int32_t> mesh_nodes);

  /// Appends the side-local nodes (master side; the surface on self contact) whose positions
  /// the next find() reads on this rank: those of the facets it hands in and of the ghosts of
  /// the last find() (reused ghosts take their nodes' current positions from the side). A
  /// master side held in part: those of the facets it hands in only (the ghosts' nodes are
  /// the caller's, hand_in_part).
  void nodes_read(const contact::ContactInterface& itf, std::vector<local_index>& out) const;

  /// Facets this rank received at the last find() (master facets, or surface facets of self
  /// contact; its own ones included).
  local_index n_received() const;
  /// Ghost exchanges and searches so far (the same on every rank).
  std::int64_t n_exchanges() const;
  std::int64_t n_searches() const;
  /// The absolute skin of the ghosting.
  double skin() const { return skin_; }
  /// Self contact: a new time step (or a new attempt of it). The step starts from the roles
  /// accept_step() kept (none unless roles_kept_across_steps()); the roles the step's finds
  /// assign are kept through its later finds (its Newton iterations): a facet that has been
  /// slave or master in the step keeps that role, one that meets anew takes a role once
  /// (search::assign_roles with roles kept). Without a call the roles are assigned anew at
  /// every find().
  void start_step();
  /// Self contact: the step is converged. The roles of the facets of the last find()'s pairs
  /// are kept for the next steps (a facet's colour in search::assign_roles), those of the other
  /// facets are dropped.
  void accept_step();
  /// Self contact: the roles accept_step() kept, by facet id (sorted), as 0 (slave) and 1
  /// (master), and the pairs they were kept with (slave, master facet id, flat), of the facets
  /// (pairs by their slave facet) whose records this rank keeps: each facet's on one rank (a
  /// hash of its id), whatever the distribution. For checkpoints; `held` is not read.
  void accepted_roles(std::vector<std::int64_t>& ids, std::vector<std::int64_t>& roles,
                      std::vector<std::int64_t>& pairs, bool held) const;
  /// Self contact: the kept roles and pairs of a checkpoint (any part on each rank, of a run on
  /// any number of ranks; collective: each record is sent to the rank that keeps it).
  void restore_roles(std::span<const std::int64_t> ids, std::span<const std::int64_t> roles,
                     std::span<const std::int64_t> pairs);
  /// Self contact: the role changes of the surface's facets so far (the same on every rank).
  /// A facet's role at a search is read from the oriented pairs: slave (master) if it is the
  /// slave (master) of each of its pairs; a facet without a pair, or slave of one pair and
  /// master of another (an odd cycle), has none then. `within`: changes against its role at the
  /// latest earlier search of the same step attempt (between two start_step()); `between`: at
  /// the first search of a step attempt that gives it a role, changes against the role it had
  /// at the last search that gave it one before the attempt. `persisting`: at the first search
  /// of a step attempt, the pairs of the last converged step's last search that it finds again
  /// with the slave and master facets exchanged.
  struct RoleChanges {
    std::int64_t within = 0, between = 0, persisting = 0;
  };
  RoleChanges role_changes() const { return role_changes_; }
  /// Self contact: the oriented pairs found by the last find() whose slave facet this rank's
  /// side holds (those the interface reads), by facet id, sorted by (slave, master).
  std::span<const FacetIdPair> self_pairs() const { return pair_ids_; }
  /// Self contact: the pair set of the last find() over all ranks (the same on every rank):
  /// its number of pairs and two sums of a hash of each oriented pair, so that two searches'
  /// sets are compared without gathering them.
  struct PairSet {
    std::int64_t count = 0;
    std::uint64_t hash = 0, hash2 = 0;
    friend bool operator==(const PairSet&, const PairSet&) = default;
  };
  PairSet pair_set() const { return pair_set_; }
  /// Self contact, collective: the oriented pairs of the last find() to the ranks that hold
  /// their slave facet now (self_pairs() anew, after set_slave_ids()).
  void route_self_pairs();
  /// Self contact, this rank at the last find(): pairs it received to decide their roles (the
  /// pairs of the groups it decides), the groups it decided, pairs it received back
  /// (self_pairs()), and the rounds the labels of the groups took.
  std::int64_t self_pairs_received() const { return pairs_received_; }
  std::int64_t self_groups_decided() const { return groups_decided_; }
  std::int64_t self_pairs_returned() const { return pairs_returned_; }
  int label_rounds() const { return label_rounds_; }
  /// Self contact: `pairs` (e.g. of an earlier find() of the step) in the indices of the
  /// interface: slave facets side-local (pairs of facets the side does not hold left out),
  /// master facets side-local or, the surface held in part, indices into the ghosts of the
  /// last find() (-1 for one not among them: a pair of a slave facet this rank does not
  /// evaluate).
  void to_interface(std::span<const FacetIdPair> pairs, std::vector<mortar::CandidatePair>& out);
  bool self() const { return ghosts_.has_value(); }
  /// Self contact: the pairs of the last find() whose facets have the same role (odd cycles,
  /// or two facets that kept the same role from earlier searches): oriented lower id slave.
  std::int64_t same_role_pairs() const { return same_roles_; }
  /// Periods of the search's pair set that the pair cycling guard recognizes (2 .. 8).
  static constexpr std::size_t max_pair_period = 8;

private:
  void find_self(contact::ContactInterface& itf, std::span<const double> positions,
                 const NodeMap& mesh_nodes);
  /// The positions of the last ghosts' nodes given by the caller (position_ids_ set to their
  /// ids), for ghosts whose nodes need not be held; a placeholder when there are none.
  std::span<const double> reused_positions(const contact::ContactInterface& itf,
                                           const parallel::SurfacePart& ghosts,
                                           std::span<const double> positions);
  /// The roles of the facing pairs `found` by this rank (each pair on one rank), decided by
  /// connected group of pairs over all ranks: sets pair_ids_ and the records of the facets.
  void decide_roles(std::span<const GlobalFacingPair> found);
  /// The label (lowest facet id over all ranks) of each group of `pairs`; `facets`: those of
  /// the pairs (sorted ids), `group`: per facet its group here. Collective.
  std::vector<std::int64_t> group_labels(std::span<const std::int64_t> facets,
                                         std::vector<local_index>& group,
                                         std::span<const GlobalFacingPair> pairs);
  /// The ranks holding which facets to their home ranks, if any side changed. Collective.
  void register_holders();
  /// The role changes of this rank's facets at the last find_self() (within, between).
  RoleChanges count_role_changes();
  /// The ghosts to the interface's integration, in side-local ids.
  void hand_ghosts(contact::ContactInterface& itf, const parallel::SurfacePart& ghosts);

  MPI_Comm comm_;
  double skin_;
  bool in_part_ = false;
  std::vector<std::int64_t> position_ids_; // the ghost nodes of the last find(), scratch
  std::vector<local_index> held_;
  SideIds slave_ids_, master_ids_;
  std::vector<local_index> local_; // side node -> part node, scratch
  // The ghosts in side-local ids for the interface, scratch.
  std::vector<std::int64_t> ghost_facets_, ghost_nodes_;
  parallel::SurfacePart slave_part_, master_part_;
  std::vector<mortar::CandidatePair> pairs_;
  // Two bodies.
  std::optional<parallel::DistributedSearch> search_;
  // Self contact: the ghosts, the tree over them (and the facets it was built on).
  std::optional<parallel::VerletGhosts> ghosts_;
  std::optional<search::Tree> tree_;
  std::vector<global_index> tree_facets_;
  // Self contact: the records of a facet are kept on its home rank (a hash of its id), those of
  // a pair on the home rank of its slave facet.
  /// Self contact: the roles kept in the current step by facet id (those of the facets that
  /// met in the step).
  std::map<std::int64_t, search::Role> roles_;
  bool keep_roles_ = true;     ///< roles_kept()
  bool keep_across_ = true;    ///< roles_kept_across_steps()
  bool roles_started_ = false; ///< start_step() was called
  /// Self contact: the roles of the facets paired at the last converged step (accept_step),
  /// and those pairs (oriented), sorted by (lower, higher) facet id.
  std::map<std::int64_t, search::Role> roles_accepted_;
  std::vector<FacetIdPair> pairs_accepted_;
  bool first_find_ = false;     ///< the next find() is the first of a step attempt
  std::int64_t same_roles_ = 0; ///< same_role_pairs()
  /// Self contact, by facet id: its role at the latest search of the current step attempt
  /// that gave it one, and at the last such search before the attempt (none if none).
  std::map<std::int64_t, search::Role> role_in_step_, role_before_;
  std::vector<FacetIdPair> pair_ids_;           ///< self contact: the oriented pairs by facet id
  std::vector<FacetIdPair> pairs_kept_;         ///< the pairs of the last find() kept here
  std::map<std::int64_t, std::uint8_t> paired_; ///< facets kept here paired then: role bits
  /// Per facet kept here: the ranks whose side holds it (register_holders()).
  std::map<std::int64_t, std::vector<std::int64_t>> holders_;
  bool holders_stale_ = true;
  PairSet pair_set_;
  std::int64_t pairs_received_ = 0, pairs_returned_ = 0, groups_decided_ = 0;
  int label_rounds_ = 0;
  std::vector<std::int64_t> held_ids_; ///< self contact: the facets handed in, by id
  RoleChanges role_changes_;
};

} // namespace seam::problem
