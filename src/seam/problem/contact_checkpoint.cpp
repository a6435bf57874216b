// The contact and friction state in checkpoints (checkpoint.hpp): what a converged step
// leaves for the next one. Nothing of it is gathered on one rank:
// - per slave node (multipliers, active set, stick/slip status, D^n_jj and the slave positions
//   x^n of friction): each node's owner writes its values into its part file, keyed by the
//   node's id; a restart on any number of ranks routes them to the nodes' new owners
//   (Checkpoints::get_keyed), which publish them as they publish their decisions in every
//   iteration (parallel::publish_from_owners: the nonzero values, in proportion to the contact
//   zone, except x^n);
// - M^n (and D^n_jk, j != k, of standard multipliers), which each rank holds in part (its
//   slave elements): each rank writes its triplets (slave node id, master node id, value; ids
//   of the mesh as read, never an index in the side) into its part file, and a restart gives each
//   part file to the rank that reads it. Only the sum over the ranks enters (the slip increment is
//   summed, the tangent rows are added into the matrix), so any number of ranks can reload them;
// - the cut of the slave elements of the independent distribution: each rank writes the ids of
//   the slave facets it evaluates into its part file; a restart on as many ranks gives every
//   rank its own part's facets back and continues the repartitions from the cut trees, so that
//   it sums in the order of the uninterrupted run (on another number of ranks it cuts anew);
// - state.bin holds only what is O(1) per side: the slave side's size and a hash of its node
//   ids (a checkpoint of another interface is refused), the rigid plane's displacement, the
//   frictional work so far, the ranks of the cut of the independent distribution (its trees,
//   O(ranks), in every part file).
#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"

#include <algorithm>
#include <functional>

namespace seam::problem {

namespace {

/// Values per slave node in record "state": the multiplier (1, or dim with friction), the
/// active flag, and with friction the status, D^n_jj and x^n (dim).
std::size_t state_width(bool friction, int dim) {
  const auto d = static_cast<std::size_t>(dim);
  return friction ? d + 3 + d : 2;
}

/// The slave side's node ids in the mesh as read, hashed: the sum (modulo 2^64) of each node's
/// hashed id over the nodes' owners, so that no rank needs the whole side and the value is the
/// same on any number of ranks. Collective.
std::int64_t node_id_hash(const Discretization& disc, std::span<const std::int32_t> nodes,
                          std::span<const int> owners) {
  std::uint64_t hash = 0;
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    if (owners[j] != disc.comm().rank()) continue;
    const std::int64_t id = disc.node_gid(nodes[j]);
    hash += fnv1a(&id, sizeof id);
  }
  MPI_Allreduce(MPI_IN_PLACE, &hash, 1, MPI_UINT64_T, MPI_SUM, disc.comm().get());
  return static_cast<std::int64_t>(hash);
}

/// The side-local slave node of node id `id` in a checkpoint record, -1 if the side has none.
std::int64_t slave_of_id(const SideIds& ids, std::int64_t id) {
  const auto it = std::lower_bound(ids.nodes.begin(), ids.nodes.end(), id);
  return it != ids.nodes.end() && *it == id ? it - ids.nodes.begin() : -1;
}

/// The number of slave nodes of the side, each counted by its owner (a slave side held in
/// part is not whole on any rank). Collective.
std::int64_t node_count(const Discretization& disc, std::span<const int> owners) {
  const auto mine = std::count(owners.begin(), owners.end(), disc.comm().rank());
  return static_cast<std::int64_t>(disc.comm().sum(static_cast<double>(mine)));
}

/// The cut of the independent distribution: in state.bin its ranks (0: no cut) and the
/// partitions made; in every part file the cut trees (the same on every rank, O(ranks)): per
/// cut of both trees (close, then far) its axis and id cut (integers) and its planes lo, hi
/// (reals).
void put_cut(RecordWriter& out, const std::string& p,
             const parallel::FacetDistribution::State& cut) {
  out.put_integer(p + "cut.ranks", cut.n_parts);
  out.put_integer(p + "cut.partitions", cut.n_partitions);
  std::vector<std::int64_t> axes;
  std::vector<double> planes;
  for (const auto* tree : {&cut.close, &cut.far})
    for (const auto& c : *tree) {
      axes.push_back(c.axis);
      axes.push_back(c.id_cut);
      planes.push_back(c.lo);
      planes.push_back(c.hi);
    }
  out.put_part(p + "cut.axes", axes);
  out.put_part(p + "cut.planes", planes);
}

/// The cut trees put_cut wrote into `part`, of a cut of `n_parts` parts.
void get_cut_trees(const RecordReader& part, const std::string& p,
                   parallel::FacetDistribution::State& cut) {
  const auto n = 2 * static_cast<std::size_t>(cut.n_parts - 1);
  const auto axes = part.integers(p + "cut.axes", 2 * n);
  const auto planes = part.reals(p + "cut.planes", 2 * n);
  cut.close.clear();
  cut.far.clear();
  for (std::size_t i = 0; i < n; ++i) {
    const parallel::RcbCut c{static_cast<int>(axes[2 * i]), planes[2 * i], planes[2 * i + 1],
                             axes[2 * i + 1]};
    (i < n / 2 ? cut.close : cut.far).push_back(c);
  }
}

} // namespace

void ContactConstraint::write_checkpoint(RecordWriter& out) const {
  const int dim = disc_.dim();
  const auto& comm = disc_.comm();
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    const auto& s = sides_[k];
    const std::string p = "contact." + std::to_string(k) + ".";
    const auto& nodes = s.itf.slave().mesh_nodes;
    // The side by its size and node ids.
    out.put_integer(p + "slave_count", node_count(disc_, s.node_owners));
    out.put_integer(p + "slave_hash", node_id_hash(disc_, nodes, s.node_owners));
    out.put_integer(p + "friction", s.friction ? 1 : 0);
    // The slave nodes this rank owns, with their state.
    const std::size_t per_node = s.friction ? static_cast<std::size_t>(dim) : 1;
    std::vector<std::int64_t> ids;
    std::vector<double> state;
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (s.node_owners[j] != comm.rank()) continue;
      ids.push_back(disc_.node_gid(nodes[j]));
      for (std::size_t c = 0; c < per_node; ++c) state.push_back(s.lambda_saved[j * per_node + c]);
      state.push_back(s.active[j] ? 1.0 : 0.0);
      if (!s.friction) continue;
      state.push_back(static_cast<double>(s.status[j]));
      state.push_back(s.D_diag_old[j]);
      for (int c = 0; c < dim; ++c) state.push_back(s.x_old[j * dim + c]);
    }
    out.put_part(p + "nodes", ids);
    out.put_part(p + "state", state);
    // The independent distribution: the slave facets this rank evaluates and the cut trees.
    parallel::FacetDistribution::State cut;
    if (s.distribution && s.distributed) cut = s.distribution->state();
    put_cut(out, p, cut);
    std::vector<std::int64_t> evaluated;
    if (cut.n_parts > 0)
      for (const auto f : s.itf.owned_facets())
        evaluated.push_back(s.slave_ids.facets[static_cast<std::size_t>(f)]);
    std::sort(evaluated.begin(), evaluated.end());
    out.put_part(p + "cut.facets", evaluated);
    // Self contact: the roles kept into the next step, of the facets this rank hands in.
    if (s.search && s.search->self()) {
      std::vector<std::int64_t> facets, roles, pairs;
      s.search->accepted_roles(facets, roles, pairs, true);
      out.put_part(p + "roles.facets", facets);
      out.put_part(p + "roles.values", roles);
      out.put_part(p + "roles.pairs", pairs);
    }
    if (!s.friction) continue;
    out.put(p + "plane_old", std::span<const double>(s.plane_old));
    out.put_real(p + "dissipation", s.dissipation);
    out.put_integer(p + "has_old", s.has_old ? 1 : 0);
    std::vector<std::int64_t> slave, master;
    std::vector<double> value;
    for (const auto& e : s.M_old) {
      slave.push_back(s.slave_ids.nodes[static_cast<std::size_t>(e.slave)]);
      master.push_back(node_id(e.master_node));
      value.push_back(e.value);
    }
    out.put_part(p + "M_old.slave_node", slave);
    out.put_part(p + "M_old.master", master);
    out.put_part(p + "M_old.value", value);
    // Standard multipliers: this rank's entries D_jk (j != k) of the last converged step.
    std::vector<std::int64_t> row, col;
    std::vector<double> coupling;
    for (const auto& e : s.D_coupling_old) {
      row.push_back(s.slave_ids.nodes[static_cast<std::size_t>(e.row)]);
      col.push_back(s.slave_ids.nodes[static_cast<std::size_t>(e.col)]);
      coupling.push_back(e.value);
    }
    out.put_part(p + "D_coupling_old.row_node", row);
    out.put_part(p + "D_coupling_old.col_node", col);
    out.put_part(p + "D_coupling_old.value", coupling);
  }
}

std::optional<std::vector<std::int64_t>>
ContactConstraint::read_cut(const Checkpoints& checkpoints, Side& s, std::size_t k,
                            std::vector<std::string>& notes) {
  if (!s.distribution) return std::nullopt;
  const auto& in = checkpoints.restart();
  const auto& comm = disc_.comm();
  const std::string p = "contact." + std::to_string(k) + ".";
  const std::string which =
      "contact interface " + std::to_string(k + 1) + " '" + s.itf.name() + "'";
  // state.bin: the ranks of the cut (none in a checkpoint written before seam kept it).
  parallel::FacetDistribution::State cut;
  if (in.has(p + "cut.ranks")) {
    cut.n_parts = static_cast<int>(in.integer(p + "cut.ranks"));
    cut.n_partitions = static_cast<int>(in.integer(p + "cut.partitions"));
  }
  if (cut.n_parts != comm.size()) {
    notes.push_back(which + ": the checkpoint was written on " +
                    std::to_string(in.integer("ranks")) + " rank(s)" +
                    (cut.n_parts > 0 ? "" : " without a cut of its slave elements") +
                    "; the slave elements are cut anew on " + std::to_string(comm.size()));
    return std::nullopt;
  }
  // The facets of the whole slave side, by id; a side held in part (its facets beyond the
  // rank's mesh in the facet directory) is asked below.
  auto side = s.slave_ids.facets;
  std::sort(side.begin(), side.end());
  // As many ranks: this rank reads its own part file, which lists the facets it evaluated.
  std::vector<std::int64_t> evaluated;
  std::string part_file;
  checkpoints.read_parts([&](const RecordReader& part) {
    part_file = part.path().string();
    get_cut_trees(part, p, cut);
    try {
      s.distribution->restore(cut);
    } catch (const InputError& e) {
      part.fail("records '" + p + "cut.*': " + e.what());
    }
    evaluated = part.integers(p + "cut.facets");
    bool bad = std::adjacent_find(evaluated.begin(), evaluated.end(), std::greater_equal<>()) !=
               evaluated.end();
    if (!s.slave_region)
      for (const auto id : evaluated)
        bad = bad || !std::binary_search(side.begin(), side.end(), id);
    if (bad)
      part.fail("record '" + p + "cut.facets' names a facet outside the slave side, or twice");
  });
  if (s.slave_region)
    throw_collectively(comm, count_outside_side(s, evaluated) == 0
                                 ? std::string()
                                 : "checkpoint " + part_file + ": record '" + p +
                                       "cut.facets' names a facet outside the slave side");
  // Each facet of the side on one rank: as many as the ranks' own cells have.
  const auto total = comm.sum(static_cast<double>(evaluated.size()));
  const auto expected = comm.sum(static_cast<double>(s.bulk_facets.size()));
  if (total != expected)
    in.fail(which + ": its cut names " + std::to_string(static_cast<std::int64_t>(total)) +
            " slave facets, the side has " + std::to_string(static_cast<std::int64_t>(expected)));
  notes.push_back(which + ": the slave elements keep the checkpoint's cut on " +
                  std::to_string(comm.size()) + " ranks");
  return evaluated;
}

std::vector<std::string> ContactConstraint::read_checkpoint(const Checkpoints& checkpoints) {
  std::vector<std::string> notes;
  const auto& in = checkpoints.restart();
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  // Master nodes by their ids in the mesh as read (node_of_gid): every rank holds the
  // interface cells.
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    auto& s = sides_[k];
    const std::string p = "contact." + std::to_string(k) + ".";
    const std::string which = "contact interface " + std::to_string(k + 1);
    const auto& nodes = s.itf.slave().mesh_nodes;
    const auto n = nodes.size();
    // state.bin, read by every rank: every rank takes the same decision.
    if (in.has(p + "lambda"))
      in.fail("was written by an earlier seam, which stored the contact state in state.bin; "
              "rerun to write a checkpoint of this version");
    // Collective before any failure, so that every rank reaches it.
    const auto hash = node_id_hash(disc_, nodes, s.node_owners);
    const auto count = node_count(disc_, s.node_owners);
    if (in.integer(p + "slave_count") != count || in.integer(p + "slave_hash") != hash)
      in.fail(which + " has other slave nodes than the input's");
    if (s.friction != (in.integer(p + "friction") != 0))
      in.fail(which + " was written " + (s.friction ? "without" : "with") + " friction");
    // The state of the slave nodes this rank owns, from the parts that hold them.
    std::vector<std::int64_t> ids;
    std::vector<std::size_t> mine;
    for (std::size_t j = 0; j < n; ++j)
      if (s.node_owners[j] == comm.rank()) {
        mine.push_back(j);
        ids.push_back(disc_.node_gid(nodes[j]));
      }
    const auto width = state_width(s.friction, dim);
    const auto state = checkpoints.get_keyed(p + "nodes", p + "state", static_cast<int>(width),
                                             disc_.n_global_nodes(), ids);
    const std::size_t per_node = s.friction ? static_cast<std::size_t>(dim) : 1;
    // Filled at the owned nodes, then published by the owners (as in every iteration).
    std::vector<double> lambda(n * per_node, 0.0), flags(n * 3, 0.0), x_old;
    if (s.friction) x_old.assign(n * static_cast<std::size_t>(dim), 0.0);
    for (std::size_t i = 0; i < mine.size(); ++i) {
      const auto j = mine[i];
      const double* v = &state[i * width];
      for (std::size_t c = 0; c < per_node; ++c) lambda[j * per_node + c] = v[c];
      flags[j * 3] = v[per_node];
      if (!s.friction) continue;
      flags[j * 3 + 1] = v[per_node + 1];
      flags[j * 3 + 2] = v[per_node + 2];
      for (int c = 0; c < dim; ++c) x_old[j * dim + c] = v[per_node + 3 + c];
    }
    publish(s, lambda, static_cast<int>(per_node));
    publish(s, flags, 3);
    s.lambda = lambda;
    s.lambda_saved = s.lambda;
    for (std::size_t j = 0; j < n; ++j) s.active[j] = flags[j * 3] != 0.0;
    s.active_previous = s.active;
    s.active_accepted = s.active;
    // The slave elements this rank evaluated, on as many ranks (otherwise the first
    // evaluation cuts anew); with friction and the slave side held in part they are taken
    // below with the slave nodes of M^n.
    const auto cut = read_cut(checkpoints, s, k, notes);
    if (cut && !(s.friction && s.slave_region)) evaluate_facets(s, *cut, {});
    // Self contact: the roles kept into the next step (none in a checkpoint written before
    // seam kept them: the first step assigns them anew). Collective.
    if (s.search && s.search->self()) {
      std::vector<std::int64_t> facets, roles, pairs;
      bool found = false;
      checkpoints.read_parts([&](const RecordReader& part) {
        if (!part.has(p + "roles.facets")) return;
        found = true;
        const auto f = part.integers(p + "roles.facets");
        const auto r = part.integers(p + "roles.values", f.size());
        for (const auto v : r)
          if (v != 0 && v != 1)
            part.fail("record '" + p + "roles.values' holds a value not 0 or 1");
        const auto q = part.integers(p + "roles.pairs");
        if (q.size() % 2 != 0) part.fail("record '" + p + "roles.pairs' has an odd length");
        facets.insert(facets.end(), f.begin(), f.end());
        roles.insert(roles.end(), r.begin(), r.end());
        pairs.insert(pairs.end(), q.begin(), q.end());
      });
      s.search->restore_roles(facets, roles, pairs);
      if (comm.max(found ? 1.0 : 0.0) == 0.0)
        notes.push_back(which + ": the checkpoint has no self-contact roles; the first step "
                                "assigns them anew");
    }
    if (!s.friction) continue;
    for (std::size_t j = 0; j < n; ++j) s.status[j] = static_cast<char>(flags[j * 3 + 1]);
    s.status_previous = s.status;
    s.status_accepted = s.status;
    s.D_diag_old.assign(n, 0.0);
    for (std::size_t j = 0; j < n; ++j) s.D_diag_old[j] = flags[j * 3 + 2];
    // x^n: every rank reads the positions of the nodes it evaluates (all published).
    publish(s, x_old, dim);
    s.x_old = std::move(x_old);
    const auto plane = in.reals(p + "plane_old", 3);
    std::copy(plane.begin(), plane.end(), s.plane_old.begin());
    s.dissipation = in.real(p + "dissipation");
    s.has_old = in.integer(p + "has_old") != 0;
    // The operator pieces of the part files this rank read.
    s.M_old.clear();
    s.D_coupling_old.clear();
    // A master side held in part (or a self-contact surface held in part, its own master
    // side): master nodes outside this rank's part (found below).
    const bool outside_masters = s.master_in_part || (s.itf.self_contact() && s.slave_in_part);
    std::vector<std::int64_t> outside_ids;
    // A slave side held in part with the independent distribution: the slave nodes of the
    // part of M^n read are held with their rings (collective), found in a first pass.
    if (s.slave_region) {
      std::vector<std::int64_t> kept;
      checkpoints.read_parts([&](const RecordReader& part) {
        const auto slave = part.integers(p + "M_old.slave_node");
        kept.insert(kept.end(), slave.begin(), slave.end());
        // Standard multipliers: both nodes of D^n_jk.
        for (const auto* key : {"D_coupling_old.row_node", "D_coupling_old.col_node"}) {
          const auto nodes = part.integers(p + key);
          kept.insert(kept.end(), nodes.begin(), nodes.end());
        }
      });
      if (cut) {
        evaluate_facets(s, *cut, std::move(kept));
      } else {
        hold_slave_part(s, {}, std::move(kept), true);
        s.itf.set_owned_facets(s.bulk_facets);
      }
    }
    checkpoints.read_parts([&](const RecordReader& part) {
      const auto slave = part.integers(p + "M_old.slave_node");
      const auto master = part.integers(p + "M_old.master", slave.size());
      const auto value = part.reals(p + "M_old.value", slave.size());
      for (std::size_t i = 0; i < slave.size(); ++i) {
        const auto j = slave_of_id(s.slave_ids, slave[i]);
        auto master_node = node_of_gid(master[i]);
        if (j < 0 || (master_node < 0 && !outside_masters))
          part.fail("record '" + p + "M_old' names a node outside the interface or the mesh");
        if (master_node < 0) {
          // Numbered after the collective look-up below; -1 - k names outside_ids[k] until then.
          master_node = -1 - static_cast<std::int32_t>(outside_ids.size());
          outside_ids.push_back(master[i]);
        }
        s.M_old.push_back({static_cast<local_index>(j), master_node, value[i]});
      }
      const auto row = part.integers(p + "D_coupling_old.row_node");
      const auto col = part.integers(p + "D_coupling_old.col_node", row.size());
      const auto coupling = part.reals(p + "D_coupling_old.value", row.size());
      for (std::size_t i = 0; i < row.size(); ++i) {
        const auto j = slave_of_id(s.slave_ids, row[i]), k = slave_of_id(s.slave_ids, col[i]);
        if (j < 0 || k < 0)
          part.fail("record '" + p + "D_coupling_old' names a node outside the interface");
        s.D_coupling_old.push_back(
            {static_cast<std::int32_t>(j), static_cast<std::int32_t>(k), coupling[i]});
      }
    });
    if (outside_masters) {
      // Collective (the sides are the same on every rank): the outside nodes of M^n.
      std::vector<std::int32_t> found;
      map_nodes(outside_ids, found);
      for (auto& e : s.M_old)
        if (e.master_node < 0) e.master_node = found[static_cast<std::size_t>(-1 - e.master_node)];
    }
  }
  return notes;
}

} // namespace seam::problem
