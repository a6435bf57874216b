#include "seam/problem/contact_constraint.hpp"

#include "seam/common/error.hpp"
#include "seam/contact/self_contact.hpp"
#include "seam/fem/cell.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <string>
#include <string_view>

namespace seam::problem {

namespace {

/// A node whose prescribed components leave less than this share of its normal free cannot
/// move towards the other side: it is kept out of the active set.
constexpr double min_free_normal = 0.1;

/// The largest Young's modulus of the cells that touch one of `nodes` (mesh nodes, sorted):
/// the stiffness of the body a contact side belongs to. Collective: each rank looks at the
/// cells it assembles (a rank may not hold every cell touching a side node).
double side_young(const Discretization& disc, const Model& model,
                  std::span<const std::int32_t> nodes) {
  const auto& mesh = disc.mesh();
  std::vector<char> on_side(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (const auto n : nodes) on_side[static_cast<std::size_t>(n)] = 1;
  double young = 0.0;
  for (const auto c : disc.local_cells()) {
    const int m = model.cell_material[static_cast<std::size_t>(c)];
    if (m < 0) continue;
    for (const auto n : mesh.cell(c))
      if (on_side[static_cast<std::size_t>(n)]) {
        young = std::max(young, model.materials[static_cast<std::size_t>(m)].young);
        break;
      }
  }
  return disc.comm().max(young);
}

/// The global ids of the side extracted from `region` (whose nodes are `mesh_nodes`).
SideIds side_ids(const Discretization& disc, const mesh::Region& region,
                 std::span<const std::int32_t> mesh_nodes) {
  SideIds ids;
  ids.facets = meshtying::facet_gids(region, [&](std::int32_t c) { return disc.cell_gid(c); });
  ids.nodes.reserve(mesh_nodes.size());
  for (const auto n : mesh_nodes) ids.nodes.push_back(disc.node_gid(n));
  return ids;
}

/// `records` sent to the home rank of their keys (key % size), sorted by (home, key): what
/// this rank received, and in `from` where each source's records start.
template <class T, class Key>
std::vector<T> to_homes(MPI_Comm comm, std::vector<T>& records, Key key,
                        std::vector<std::int64_t>& from) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const auto home = [&](const T& r) { return static_cast<int>(key(r) % size); };
  std::sort(records.begin(), records.end(), [&](const T& a, const T& b) {
    return home(a) != home(b) ? home(a) < home(b) : key(a) < key(b);
  });
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  for (const auto& r : records) ++offsets[static_cast<std::size_t>(home(r)) + 1];
  for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
  return parallel::alltoallv<T>(comm, records, offsets, from);
}

/// Collective. The records filed under `keys` in a directory whose part on this rank is
/// `directory` (sorted by key; the rank key % size keeps a key's records): every record of
/// every key asked, in the order of (home, key).
template <class T, class Key>
std::vector<T> ask_homes(MPI_Comm comm, std::span<const T> directory,
                         std::vector<std::int64_t> keys, Key key) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::sort(keys.begin(), keys.end());
  keys.erase(std::unique(keys.begin(), keys.end()), keys.end());
  std::vector<std::int64_t> from;
  const auto asked = to_homes(
      comm, keys, [](std::int64_t k) { return k; }, from);
  std::vector<T> answers;
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  for (int r = 0; r < size; ++r) {
    for (auto i = from[r]; i < from[r + 1]; ++i) {
      const auto id = asked[static_cast<std::size_t>(i)];
      auto it = std::lower_bound(directory.begin(), directory.end(), id,
                                 [&](const T& d, std::int64_t k) { return key(d) < k; });
      for (; it != directory.end() && key(*it) == id; ++it) answers.push_back(*it);
    }
    offsets[r + 1] = static_cast<std::int64_t>(answers.size());
  }
  std::vector<std::int64_t> received;
  return parallel::alltoallv<T>(comm, answers, offsets, received);
}

/// The facets f of `full` for which keep(f) holds, in its order: a part of the side.
template <class Keep> mesh::Region region_part(const mesh::Region& full, Keep keep) {
  mesh::Region part;
  part.name = full.name;
  part.dim = full.dim;
  part.tag = full.tag;
  for (std::int32_t f = 0; f < full.n_facets(); ++f)
    if (keep(f)) {
      part.facet_cell.push_back(full.facet_cell[static_cast<std::size_t>(f)]);
      part.facet_local.push_back(full.facet_local[static_cast<std::size_t>(f)]);
    }
  return part;
}

} // namespace

ContactConstraint::ContactConstraint(const io::Config& config, const Discretization& disc,
                                     const Model& model)
    : disc_(disc), parallel_(config.parallel),
      energy_momentum_(config.time.integrator == io::Integrator::energy_momentum) {
  const int dim = disc.dim();
  double young = 0.0;
  for (const auto& m : model.materials) young = std::max(young, m.young);
  reference_x_ = disc.mesh().x;
  for (const auto& itf : config.interfaces) {
    if (itf.type != io::InterfaceType::contact) continue;
    const bool slave_part = slave_held_in_part(itf, config) && disc.comm().size() > 1;
    Side s(contact::ContactInterface(itf, disc.mesh(), slave_part));
    s.itf.set_reference_coordinates(&reference_x_);
    s.slave_in_part = slave_part;
    if (!s.itf.rigid() && !s.itf.self_contact()) check_shared_nodes(s, itf);
    // The slave facets the side holds. In part with the independent distribution: those of
    // the rank's own and ghost cells until the first distribution (its mesh holds only those;
    // hold_slave_part takes the facets it is sent from there and from the directories).
    mesh::Region region;
    const bool self = !itf.surface.empty();
    if (slave_part && self) {
      // A surface held in part: the facets of the rank's own and ghost cells; every group
      // must have facets on some rank. Its facets are filed in the directories (the ghosts'
      // nodes are found there) with either distribution.
      for (const auto& group : itf.surface) {
        const auto& facets = meshtying::side_region(disc.mesh(), group);
        double own = 0.0;
        for (const auto c : facets.facet_cell) own += disc.is_local_cell(c) ? 1.0 : 0.0;
        if (!(disc.comm().sum(own) > 0.0))
          io::fail_at(group.mark, "the surface group '" + group.name + "' has no facets");
      }
      s.surface_region = std::make_shared<const mesh::Region>(
          contact::surface_region(disc.mesh(), itf.surface, true));
      s.slave_region = s.surface_region.get();
    }
    if (slave_part &&
        config.parallel.interface_distribution == io::InterfaceDistribution::independent) {
      if (!self) s.slave_region = &meshtying::side_region(disc.mesh(), itf.slave);
      region = region_part(*s.slave_region, [&](std::int32_t f) {
        return !disc.interface_only_cell(s.slave_region->facet_cell[static_cast<std::size_t>(f)]);
      });
      s.itf.hold_slave_facets(region);
    } else {
      region = !self ? meshtying::side_region(disc.mesh(), itf.slave)
                     : contact::surface_region(disc.mesh(), itf.surface, slave_part);
    }
    if (slave_part) {
      // Every part agrees on the slave side's mean edge (c_n, the skin of the ghosting): the
      // sums over the slave facets of each part's own cells, each facet counted once.
      std::vector<local_index> own;
      for (std::int32_t f = 0; f < region.n_facets(); ++f)
        if (disc.is_local_cell(region.facet_cell[static_cast<std::size_t>(f)])) own.push_back(f);
      const auto [sum, count] = s.itf.slave_edge_sum(own);
      const double total = disc.comm().sum(count);
      if (!(total > 0.0))
        io::fail_at(itf.slave.mark, "the slave region '" + itf.slave.name + "' has no facets");
      s.itf.set_slave_mesh_size(disc.comm().sum(sum) / total);
      if (s.itf.rigid()) agree_on_obstacle_search(s);
    }
    if (s.itf.standard()) {
      saddle_point_ = true;
      // Standard multipliers weight the gaps with N_j, whose integral vanishes (tri6) or is
      // negative (quad8) at the vertices: no sign condition can be put on such weighted gaps.
      for (const auto type : s.itf.slave().types)
        if (type == fem::CellType::tri6 || type == fem::CellType::quad8)
          io::fail_at(itf.mark, "interface '" + itf.name +
                                    "': standard multipliers on tri6/quad8 faces give weighted "
                                    "gaps of no fixed sign at the vertices, with or without "
                                    "friction; use multiplier: dual");
    }
    // Energy-momentum contact: the discrete gradient force where the weighted gaps have exact
    // second derivatives (contact/gap_blocks.cpp); with friction its normal part.
    const bool em_gaps =
        config.time.integrator == io::Integrator::energy_momentum && s.itf.has_gap_blocks();
    // The discrete gradient is the gradient of the weighted gaps in the nodal positions, of the
    // modified dual basis on tri6/quad8 faces as they are weighted: its force needs no
    // transformation of the slave displacements (the frictional slip takes T^-1 itself,
    // contact_energy_momentum_friction.cpp).
    if (!em_gaps) s.T_inverse = mortar::inverse_transformation(s.itf.transformation());
    s.compact =
        slave_part && s.itf.rigid() && disc.comm().max(s.T_inverse.empty() ? 0.0 : 1.0) == 0.0;
    // c_n ~ E / h makes c_n g and lambda_n the same size for a gap of one element's strain;
    // E of the softer body in contact, whose strain sets the pressure a penetration stands
    // for (a stiff die on a soft slab with the die's E makes every set decision a gap test,
    // and the sets then jump as the die slides).
    double e = side_young(disc, model, s.itf.slave().mesh_nodes);
    if (!s.itf.rigid()) e = std::min(e, side_young(disc, model, s.itf.master_nodes()));
    if (!(e > 0.0)) e = young;
    s.c_n = itf.c_n ? *itf.c_n : e / s.itf.slave_mesh_size();
    const auto n = static_cast<std::size_t>(s.itf.n_slave_nodes());
    s.lambda.assign(n, 0.0);
    s.lambda_saved = s.lambda;
    s.active.assign(n, 0);
    s.active_previous = s.active;
    s.active_accepted = s.active;
    const auto& nodes = s.itf.slave().mesh_nodes;
    auto facet_ids =
        meshtying::facet_gids(region, [&](std::int32_t c) { return disc.cell_gid(c); });
    for (std::int32_t f = 0; f < region.n_facets(); ++f)
      if (disc.is_local_cell(region.facet_cell[static_cast<std::size_t>(f)]))
        s.own_facet_ids.push_back(facet_ids[static_cast<std::size_t>(f)]);
    index_slave_side(s, std::move(facet_ids));
    // Prescribed components of the slave nodes: known on the owning rank only (the model
    // holds the owned rows), published by the owners (in proportion to the prescribed nodes).
    std::vector<double> fixed(n * dim, 0.0);
    for (const auto& d : model.dirichlet) {
      const auto it = std::lower_bound(nodes.begin(), nodes.end(), d.node);
      if (it == nodes.end() || *it != d.node) continue;
      const auto j = static_cast<std::size_t>(it - nodes.begin());
      for (int c = 0; c < dim; ++c)
        if (disc.global_dof(d.node, c) == d.dof) fixed[j * dim + c] = 1.0;
    }
    publish(s, fixed, dim);
    s.dirichlet.assign(n * dim, 0);
    for (std::size_t i = 0; i < fixed.size(); ++i) s.dirichlet[i] = fixed[i] > 0.0;
    if (itf.friction.model != io::FrictionModel::frictionless) init_friction(s, itf, s.c_n);
    // Its multipliers are saddle-point unknowns; with friction the normal part
    // (contact_energy_momentum_friction.cpp).
    s.discrete_gradient = em_gaps;
    saddle_point_ = saddle_point_ || s.discrete_gradient;
    if (parallel_.interface_distribution == io::InterfaceDistribution::independent &&
        disc.comm().size() > 1)
      s.distribution = std::make_unique<parallel::FacetDistribution>(disc.comm().get(), dim);
    if (s.itf.self_contact()) {
      // Self contact: each rank searches the surface facets it evaluates against the surface
      // facets ghosted to it; it hands in those of its own cells. A surface held in part: the
      // parts agree on the search inflation (the shortest edge of all parts, as the whole
      // surface's) and on the quadrature.
      s.slave_facets = static_cast<int>(disc.comm().sum(static_cast<double>(s.bulk_facets.size())));
      if (slave_part) {
        const double huge = std::numeric_limits<double>::max();
        const double part = search::min_edge_length(s.itf.slave().surface());
        const double edge = disc.comm().min(part > 0.0 ? part : huge);
        s.itf.set_search_edge(edge < huge ? edge : 0.0);
        s.itf.set_cell_quadrature_degree(
            static_cast<int>(disc.comm().max(static_cast<double>(s.itf.cell_quadrature_degree()))));
      }
      s.search = std::make_unique<ContactSearch>(disc.comm().get(), s.itf, s.bulk_facets,
                                                 s.slave_ids, s.slave_ids, slave_part);
      s.itf.set_owned_facets(s.bulk_facets);
    } else if (!s.itf.rigid()) {
      // Two bodies: each rank searches the slave facets it evaluates against the master
      // facets ghosted to it; it hands in those of its own cells.
      const mesh::Region master = meshtying::side_region(disc.mesh(), *itf.master);
      std::vector<local_index> held;
      for (std::int32_t f = 0; f < master.n_facets(); ++f)
        if (disc.is_local_cell(master.facet_cell[static_cast<std::size_t>(f)])) held.push_back(f);
      s.master_in_part = master_held_in_part(itf, config);
      s.master_facets = static_cast<int>(disc.comm().sum(static_cast<double>(held.size())));
      s.slave_facets = static_cast<int>(disc.comm().sum(static_cast<double>(s.bulk_facets.size())));
      if (s.master_facets == 0)
        io::fail_at(itf.master->mark, "the master region '" + itf.master->name + "' has no facets");
      if (s.master_in_part) {
        // The parts agree on the search inflation (from the shortest edge of both sides, as
        // search::InterfaceSearch takes it) and on the quadrature (a part may hold no curved
        // master facet).
        const double huge = std::numeric_limits<double>::max();
        const double part = search::min_edge_length(s.itf.master().surface());
        double lm = disc.comm().min(part > 0.0 ? part : huge);
        lm = lm < huge ? lm : 0.0;
        double ls = search::min_edge_length(s.itf.slave().surface());
        if (s.slave_in_part) {
          ls = disc.comm().min(ls > 0.0 ? ls : huge);
          ls = ls < huge ? ls : 0.0;
        }
        s.itf.set_search_edge(ls > 0.0 && lm > 0.0 ? std::min(ls, lm) : std::max(ls, lm));
      }
      if (s.master_in_part)
        s.itf.set_cell_quadrature_degree(
            static_cast<int>(disc.comm().max(static_cast<double>(s.itf.cell_quadrature_degree()))));
      s.search = std::make_unique<ContactSearch>(
          disc.comm().get(), s.itf, std::move(held), s.slave_ids,
          side_ids(disc, master, s.itf.master_nodes()), s.master_in_part);
      s.itf.set_owned_facets(s.bulk_facets);
    } else {
      s.slave_facets = static_cast<int>(disc.comm().sum(static_cast<double>(s.bulk_facets.size())));
    }
    sides_.push_back(std::move(s));
  }
  if (saddle_point_)
    for (std::size_t k = 0; k < sides_.size(); ++k)
      if (disc.comm().max(sides_[k].T_inverse.empty() ? 0.0 : 1.0) > 0.0)
        io::fail_at(config.interfaces[k].mark,
                    "interface '" + sides_[k].itf.name() +
                        "': quadratic faces with dual multipliers cannot share a run with "
                        "standard multipliers or energy-momentum contact (saddle point)");
  collect_interface_nodes();
  // The interface nodes of all ranks, each counted by its owner (a master side held in part
  // is not whole on any rank).
  interface_total_ = static_cast<std::int64_t>(disc.comm().sum(
      static_cast<double>(std::count_if(interface_nodes_.begin(), interface_nodes_.end(),
                                        [&](std::int32_t node) { return disc.owns_node(node); }))));
  if (!saddle_point_) return;
  // One multiplier per slave node (dim with friction), owned with the node; numbered rank by
  // rank, on a rank side by side (a side held in part holds every slave node its rank owns).
  const auto& comm = disc.comm();
  std::vector<PetscInt> side_lm(sides_.size(), 0);
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    const auto& s = sides_[k];
    for (const auto node : s.itf.slave().mesh_nodes)
      side_lm[k] += owns(node) ? (s.friction ? dim : 1) : 0;
    n_lm_ += side_lm[k];
  }
  PetscInt mine = n_lm_;
  MPI_Exscan(&mine, &first_lm_, 1, MPIU_INT, MPI_SUM, comm.get());
  if (comm.rank() == 0) first_lm_ = 0;
  PetscInt next = first_lm_;
  for (std::size_t k = 0; k < sides_.size(); ++k) {
    sides_[k].lm_first = next;
    next += side_lm[k];
    number_multipliers(sides_[k]);
  }
  lm_numbered_ = true;
}

void ContactConstraint::number_multipliers(Side& s) const {
  const auto& nodes = s.itf.slave().mesh_nodes;
  const PetscInt per_node = s.friction ? disc_.dim() : 1;
  // Row + 1 (the publication sends nonzero records), 0 for the nodes of other owners.
  std::vector<double> row(nodes.size(), 0.0);
  PetscInt next = s.lm_first;
  for (std::size_t j = 0; j < nodes.size(); ++j)
    if (owns(nodes[j])) {
      row[j] = static_cast<double>(next + 1);
      next += per_node;
    }
  publish(s, row, 1);
  s.lm_index.resize(nodes.size());
  for (std::size_t j = 0; j < nodes.size(); ++j) {
    SEAM_CHECK(row[j] > 0.0, InternalError, "contact saddle point: slave node ", s.node_keys[j],
               " has no multiplier row");
    s.lm_index[j] = static_cast<PetscInt>(row[j]) - 1;
  }
}

void ContactConstraint::check_shared_nodes(const Side& s, const io::Interface& itf) const {
  // Each shared node is counted by its owner, which holds every facet around it (the ghost
  // layer), whether the sides are held whole or in part.
  const auto shared = meshtying::shared_nodes(
      disc_.comm().get(), disc_.mesh(), s.itf.slave().mesh_nodes, s.itf.master_nodes(),
      [&](std::int32_t n) { return disc_.owns_node(n); },
      [&](std::int32_t n) { return disc_.node_gid(n); });
  if (shared.count > 0)
    io::fail_at(itf.mark, "the slave side '" + itf.slave.name + "' and the master side '" +
                              itf.master->name + "' " + shared.describe(disc_.dim()) +
                              "; self contact is not available in this version (use 'surface')");
}

void ContactConstraint::agree_on_obstacle_search(Side& s) const {
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  if (s.itf.obstacle().shape != contact::Obstacle::Shape::plane) return; // round: mesh size
  // The plane's facet spans the whole slave side's box (the parts' boxes together) and the
  // search inflation is the whole side's: 0.75 x the shortest edge of all parts and the plane.
  const auto& slave = s.itf.slave();
  std::array<double, 3> lo{}, hi{};
  for (int c = 0; c < dim; ++c) {
    double a = std::numeric_limits<double>::max(), b = -a;
    for (std::size_t j = 0; j < slave.mesh_nodes.size(); ++j) {
      a = std::min(a, slave.coordinates[j * dim + c]);
      b = std::max(b, slave.coordinates[j * dim + c]);
    }
    lo[static_cast<std::size_t>(c)] = comm.min(a);
    hi[static_cast<std::size_t>(c)] = comm.max(b);
  }
  s.itf.span_plane(lo, hi);
  const double huge = std::numeric_limits<double>::max();
  const double part = search::min_edge_length(slave.surface());
  const double ls = comm.min(part > 0.0 ? part : huge);
  const double lm = search::min_edge_length(s.itf.master().surface());
  s.itf.set_search_edge(std::min(ls, lm));
}

void ContactConstraint::collect_interface_nodes() {
  interface_nodes_.clear();
  const auto n_mesh = disc_.mesh().n_nodes();
  for (const auto& s : sides_) {
    // The mesh nodes only (a slave side held in part may hold outside nodes).
    for (const auto node : s.itf.slave().mesh_nodes)
      if (node < n_mesh) interface_nodes_.push_back(node);
    for (const auto node : s.itf.master_nodes())
      if (node < n_mesh) interface_nodes_.push_back(node);
  }
  std::sort(interface_nodes_.begin(), interface_nodes_.end());
  interface_nodes_.erase(std::unique(interface_nodes_.begin(), interface_nodes_.end()),
                         interface_nodes_.end());
  interface_numbers_.clear(); // made anew at the next node_of_gid
}

void ContactConstraint::index_slave_side(Side& s, std::vector<std::int64_t> facet_ids) {
  const auto& nodes = s.itf.slave().mesh_nodes;
  const auto n = nodes.size();
  s.node_keys.resize(n);
  s.node_owners.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    s.node_keys[j] = node_id(nodes[j]); // the same id on every rank
    s.node_owners[j] = owner_of(nodes[j]);
  }
  if (s.slave_in_part)
    s.holders =
        std::make_shared<parallel::HolderPublisher>(disc_.comm().get(), s.node_keys, s.node_owners);
  // The slave facets start with the bulk partition (the facets of this rank's cells).
  s.bulk_facets.clear();
  for (std::size_t f = 0; f < facet_ids.size(); ++f)
    if (std::binary_search(s.own_facet_ids.begin(), s.own_facet_ids.end(), facet_ids[f]))
      s.bulk_facets.push_back(static_cast<local_index>(f));
  s.slave_ids.facets = std::move(facet_ids);
  s.slave_ids.nodes = s.node_keys;
  if (s.search) s.search->set_slave_ids(s.slave_ids);
}

std::int32_t ContactConstraint::mesh_node_of(std::int64_t id) const {
  // The local numbering is monotone in the ids (mesh/distribute.hpp): bisection.
  const auto n = disc_.mesh().n_nodes();
  std::int32_t lo = 0, hi = n;
  while (lo < hi) {
    const std::int32_t mid = lo + (hi - lo) / 2;
    if (disc_.node_gid(mid) < id)
      lo = mid + 1;
    else
      hi = mid;
  }
  return lo < n && disc_.node_gid(lo) == id ? lo : -1;
}

int ContactConstraint::owner_of(std::int32_t node) const {
  const auto n = disc_.mesh().n_nodes();
  return node < n ? disc_.node_owner(node) : outside_[static_cast<std::size_t>(node - n)].owner;
}

std::int32_t ContactConstraint::node_of_gid(std::int64_t number) const {
  if (interface_numbers_.empty()) {
    // Made at the first use: `seam check` builds the constraint without the dof numbering.
    for (const auto node : interface_nodes_)
      interface_numbers_.emplace_back(disc_.node_gid(node), node);
    std::sort(interface_numbers_.begin(), interface_numbers_.end());
  }
  const auto it = std::lower_bound(interface_numbers_.begin(), interface_numbers_.end(),
                                   std::pair<std::int64_t, std::int32_t>{number, -1});
  return it != interface_numbers_.end() && it->first == number ? it->second : -1;
}

std::vector<std::int32_t> ContactConstraint::nodes_read() {
  const int rank = disc_.comm().rank();
  std::vector<std::int32_t> out;
  std::vector<local_index> mine, more;
  for (auto& s : sides_) {
    const auto& slave = s.itf.slave();
    const auto set = slave.facet_set();
    mine.clear();
    for (const auto f : s.itf.owned_facets())
      for (const auto j : set.facet_nodes(f)) mine.push_back(j);
    for (std::size_t j = 0; j < s.node_owners.size(); ++j)
      if (s.node_owners[j] == rank) mine.push_back(static_cast<local_index>(j));
    // Energy-momentum friction: the slave rows of this rank's part of the last converged
    // step's operators (its mean operators), whose rings and normals it reads.
    if (s.discrete_gradient && s.friction) {
      for (const auto& e : s.M_old) mine.push_back(static_cast<local_index>(e.slave));
      for (const auto& e : s.D_coupling_old) mine.push_back(static_cast<local_index>(e.row));
    }
    std::sort(mine.begin(), mine.end());
    mine.erase(std::unique(mine.begin(), mine.end()), mine.end());
    for (const auto j : s.itf.normal_ring(mine)) out.push_back(slave.mesh_nodes[j]);
    // Standard multipliers with friction: the slave positions this rank's D^n reaches.
    for (const auto& e : s.D_coupling_old) {
      out.push_back(slave.mesh_nodes[static_cast<std::size_t>(e.row)]);
      out.push_back(slave.mesh_nodes[static_cast<std::size_t>(e.col)]);
    }
    s.itf.set_normal_nodes(std::move(mine));
    mine = {};
    if (s.search) {
      more.clear();
      s.search->nodes_read(s.itf, more);
      const auto masters = s.itf.master_nodes();
      for (const auto p : more) out.push_back(masters[static_cast<std::size_t>(p)]);
      out.insert(out.end(), s.ghost_nodes.begin(), s.ghost_nodes.end());
    }
    for (const auto& e : s.M_old) out.push_back(e.master_node);
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

void ContactConstraint::refresh_displacement(const la::Vector& u) {
  const int dim = disc_.dim();
  auto nodes = nodes_read();
  const bool changed = disc_.comm().max(!gather_made_ || nodes != gathered_ ? 1.0 : 0.0) > 0.0;
  if (changed) {
    gathered_ = std::move(nodes);
    std::vector<PetscInt> dofs;
    dofs.reserve(gathered_.size() * static_cast<std::size_t>(dim));
    for (const auto node : gathered_)
      for (int c = 0; c < dim; ++c) dofs.push_back(dof_of(node, c));
    gather_ = la::Gather(u, dofs);
    gather_made_ = true;
    start_read_ = false;
  }
  // Over the mesh and outside nodes (a slave side held in part may have found new ones).
  u_mesh_.resize((static_cast<std::size_t>(disc_.mesh().n_nodes()) + outside_.size()) * dim, 0.0);
  const auto read = [&](const la::Vector& v, std::vector<double>& out) {
    std::vector<double> values;
    gather_(v, values);
    for (std::size_t k = 0; k < gathered_.size(); ++k)
      for (int c = 0; c < dim; ++c)
        out[static_cast<std::size_t>(gathered_[k]) * dim + c] = values[k * dim + c];
  };
  read(u, u_mesh_);
  // The start of an energy-momentum step at the same nodes, by the same scatter (again after
  // a new scatter: new ghosts, a redistribution). The same decision on every rank.
  if (has_start_) u_mesh_start_.resize(u_mesh_.size(), 0.0); // outside nodes found since
  if (has_start_ && !start_read_) {
    read(u_start_, u_mesh_start_);
    start_read_ = true;
  }
}

ContactConstraint::NodeFrame ContactConstraint::frame(const Side& s, std::size_t j) const {
  if (held_ && !s.held_frames.empty()) return s.held_frames[j];
  const int dim = disc_.dim();
  NodeFrame f;
  const double* n = &s.itf.normals()[j * dim];
  double w2 = 0.0;
  for (int c = 0; c < dim; ++c) {
    f.w[c] = s.dirichlet[j * dim + c] ? 0.0 : n[c];
    f.wn += f.w[c] * n[c];
    w2 += f.w[c] * f.w[c];
  }
  f.gap_component = 0;
  for (int c = 1; c < dim; ++c)
    if (std::abs(f.w[c]) > std::abs(f.w[f.gap_component])) f.gap_component = c;
  // Orthonormal basis of the free directions orthogonal to w (Gram-Schmidt on the unit
  // vectors of the other free components).
  const double wl = std::sqrt(w2);
  for (int c = 0; c < dim; ++c) {
    if (c == f.gap_component || s.dirichlet[j * dim + c]) continue;
    double t[3] = {0, 0, 0};
    t[c] = 1.0;
    if (wl > 0.0)
      for (int b = 0; b < dim; ++b) t[b] -= f.w[c] / wl * f.w[b] / wl;
    for (int i = 0; i < f.n_tangents; ++i) {
      double d = 0.0;
      for (int b = 0; b < dim; ++b) d += f.tangent[i][b] * t[b];
      for (int b = 0; b < dim; ++b) t[b] -= d * f.tangent[i][b];
    }
    double l = 0.0;
    for (int b = 0; b < dim; ++b) l += t[b] * t[b];
    l = std::sqrt(l);
    for (int b = 0; b < dim; ++b) f.tangent[f.n_tangents][b] = t[b] / l;
    f.tangent_component[f.n_tangents++] = c;
  }
  return f;
}

namespace {

/// Whether a pair's 2D pre-check is decided once per step attempt
/// (ContactInterface::keep_prechecked_pairs): yes unless SEAM_PRECHECK_ANEW=1 is in the
/// environment (a diagnostic: decided at every evaluation, as before; docs/input.md §6.6).
bool prechecks_kept() {
  static const bool kept = [] {
    const char* text = std::getenv("SEAM_PRECHECK_ANEW");
    if (text == nullptr || *text == '\0') return true;
    const std::string value = text;
    SEAM_CHECK(value == "0" || value == "1", InputError, "SEAM_PRECHECK_ANEW='", value,
               "': expected 0 or 1 (1: the contact pairs' pre-check decided at every evaluation)");
    return value == "0";
  }();
  return kept;
}

} // namespace

int ContactConstraint::evaluate(const la::Vector& u, double t, bool first, PhaseTimers& timers,
                                bool retrial) {
  const auto& comm = disc_.comm();
  released_ = 0;
  // Only the nodes this rank reads (nodes_read()), not the whole interface; the scatter is
  // made anew when they change (a redistribution, a new ghost set).
  refresh_displacement(u);
  // Taken anew after each refresh: outside nodes found by a search extend u_mesh_.
  std::span<const double> u_mesh = u_mesh_;
  // A slave surface folded back onto itself has no normal at the fold: the iterate is unusable
  // (no mortar quantity is computed there), and on the mesh as read the input is wrong. Agreed
  // over the ranks before anything collective (the largest id of the nodes found).
  folded_node_ = -1;
  for (const auto& s : sides_) {
    const std::int32_t node = s.itf.folded_slave_node(u_mesh);
    const std::int64_t id =
        node >= 0 && node < disc_.mesh().n_nodes() ? disc_.node_gid(node) : std::int64_t{-1};
    folded_node_ = std::max(folded_node_, id);
  }
  const std::int64_t folded = comm.max(folded_node_);
  if (folded >= 0) {
    SEAM_CHECK(evaluated_, InputError, "contact: slave node ", folded,
               ": the normals of its facets cancel (the surface folds back onto itself in the "
               "mesh as read)");
    folded_node_ = folded;
    return 0;
  }
  evaluated_ = true;
  int changes = 0;
  for (auto& s : sides_) {
    if (retrial) s.cycles.retract();
    if (first) {
      s.pair_history.clear();
      s.pairs_held = false;
      // Self contact: the roles of the last converged step's pairs and of this search are kept
      // through the step's iterations.
      if (s.search) s.search->start_step();
      s.itf.forget_prechecked_pairs();
    } else if (retrial && !s.pairs_held && !s.pair_history.empty()) {
      s.pair_history.pop_back(); // the shortened correction's search stands for the iteration
    }
    // The ghost exchanges so far (the same count on every rank): the nodes read change within
    // this evaluation only with an exchange or the first distribution.
    const std::int64_t exchanges = s.search ? s.search->n_exchanges() : 0;
    {
      ScopedTimer timer(timers, "search");
      search(s, u_mesh, t);
      if (prechecks_kept()) s.itf.keep_prechecked_pairs();
    }
    if (!s.distributed) {
      // The first distribution needs the candidate pairs of the slave elements each rank
      // holds at the start; the search then runs on its new slave elements, whose nodes are
      // read anew.
      distribute(s);
      refresh_displacement(u);
      u_mesh = u_mesh_;
      ScopedTimer timer(timers, "search");
      search(s, u_mesh, t);
      if (prechecks_kept()) s.itf.keep_prechecked_pairs();
    }
    // New ghosts (an exchange) come with their positions; their nodes' displacements are read
    // from here on (friction reads the master nodes of M).
    if (s.search && s.search->n_exchanges() != exchanges) {
      refresh_displacement(u);
      u_mesh = u_mesh_;
    }
    ScopedTimer timer(timers, "mortar");
    const double cpu = cpu_seconds();
    s.itf.evaluate(s.part);
    s.work_seconds += cpu_seconds() - cpu;
    sum_nodal_values(s);
    s.area = comm.sum(s.part.area);
    // Replaces g~ by the gaps of the discrete-gradient blocks (replicated).
    if (s.discrete_gradient) {
      evaluate_discrete_gradient(s, u_mesh, false);
      s.em_displacement.assign(u_mesh.begin(), u_mesh.end());
      s.em_tangent_current = false;
    }
    if (s.friction) {
      changes += evaluate_friction(s, u_mesh, first);
      continue;
    }
    if (first) {
      s.frozen = false;
      s.cycles.start(s.active);
    }
    s.active_previous = s.active;
    // The owner of each slave node decides its status from its sums; frozen or held sets
    // keep theirs, except at nodes that have no pair at this iterate (paired(): D_jj = 0 where
    // self contact made their facets master only or they left every pair, or no gap row of the
    // discrete gradient). Such a node has no constraint row, so kept active it would make the
    // saddle point singular (examples/rings, 200 rings at t = 0.66: active nodes of the frozen
    // union whose roles flipped); it is released (inactive, lambda_j = 0) and counted as a
    // change.
    const double d_max = max_weight(s);
    const double touching = 1e-9 * s.itf.slave_mesh_size();
    const bool decide = !s.frozen && !held_;
    std::vector<char> next(s.active.size(), 0);
    for (std::size_t j = 0; j < next.size(); ++j) {
      if (s.node_owners[j] != comm.rank()) continue;
      if (!paired(s, j, d_max)) continue;
      if (!decide) {
        next[j] = s.active[j];
        continue;
      }
      const NodeFrame f = frame(s, j);
      if (f.wn < min_free_normal) continue;
      // Touching (zero gap, zero pressure) counts as active: bodies held only by contact
      // then start with a nonsingular system.
      next[j] = s.lambda[j] - s.c_n * (s.gap[j] / s.D[j] - touching) > 0.0;
    }
    publish_nodal_values(s, next);
    // The counts are the same on every rank: on a slave side held in part each rank counts
    // the nodes it owns and the counts are summed (every node is held by its owner).
    const auto counted = [&](std::size_t j) {
      return !s.slave_in_part || s.node_owners[j] == comm.rank();
    };
    const auto agreed = [&](int n) {
      return s.slave_in_part ? static_cast<int>(comm.sum(static_cast<double>(n))) : n;
    };
    if (!decide) {
      int released = 0;
      for (std::size_t j = 0; j < next.size(); ++j)
        released += counted(j) && s.active[j] && !next[j];
      released = agreed(released);
      s.active = std::move(next);
      released_ += released;
      changes += released;
      continue;
    }
    // Cycling guard (contact/active_set_cycles.hpp): a set that returns to the one of k <= 12
    // iterations ago is replaced by the union of the sets of the cycle and kept for the rest
    // of the step. The same published set on every rank gives the same decision; on a slave
    // side held in part each rank compares the nodes it holds and the ranks agree (two sets
    // are equal where they are equal on every rank).
    std::vector<char> alternating;
    const auto all_ranks = [&](bool equal) { return comm.min(equal ? 1.0 : 0.0) > 0.0; };
    if (s.cycles.guard(next, alternating,
                       s.slave_in_part ? contact::ActiveSetCycles::Agree(all_ranks)
                                       : contact::ActiveSetCycles::Agree()) > 0) {
      s.frozen = true;
      // The union of the cycle's sets can hold nodes that have no pair at this iterate.
      int released = 0;
      for (std::size_t j = 0; j < next.size(); ++j)
        if (next[j] && !paired(s, j, d_max)) {
          next[j] = 0;
          released += counted(j);
        }
      released_ += agreed(released);
    }
    s.active = std::move(next);
    int changed = 0;
    for (std::size_t j = 0; j < s.active.size(); ++j)
      changed += counted(j) && s.active[j] != s.active_previous[j];
    changes += agreed(changed);
  }
  return changes;
}

void ContactConstraint::search(Side& s, std::span<const double> u, double t) {
  if (!s.search) {
    s.itf.update(u, t);
    return;
  }
  s.itf.place(u, t);
  const bool self_in_part = s.slave_in_part && s.itf.self_contact();
  std::vector<double> positions;
  if (s.pairs_held) {
    // No search: the ghosts' positions are not handed.
    if (self_in_part) {
      node_positions(s.ghost_nodes, positions);
      s.itf.set_master_coordinates(positions);
    } else {
      s.itf.refresh_master_coordinates();
    }
    s.itf.set_candidates(s.held_pairs);
    return;
  }
  if (self_in_part) {
    // As a master side held in part: the ghosts' nodes are mesh or outside nodes.
    node_positions(s.ghost_nodes, positions);
    s.search->find(s.itf, positions, [&](std::span<const std::int64_t> ids) {
      map_nodes(ids, s.ghost_nodes);
      return std::span<const std::int32_t>(s.ghost_nodes);
    });
  } else if (s.master_in_part) {
    // The ghosts' nodes need not be nodes of this part: their positions (for reused ghosts)
    // are their reference coordinates plus the displacement read, and the mortar entries
    // name them by mesh node or outside node.
    node_positions(s.ghost_nodes, positions);
    s.search->find(s.itf, positions);
    map_nodes(s.search->master_ghosts().node_ids, s.ghost_nodes);
    s.search->hand_in_part(s.itf, s.ghost_nodes);
    return;
  } else {
    s.search->find(s.itf);
  }
  if (!s.search->self()) return;
  // Pair cycling guard (self contact). Whether two facets are a candidate pair is decided on
  // the facets' normals and positions with hard thresholds (normal cones, facing test), so the
  // pair set, and with it the weighted gaps, jump where a pair enters or leaves. Newton's
  // iterates can then alternate between two configurations, each of which drops the pairs that
  // the other one needs (examples/tori_impact at t = 22: four pairs at the rim of the contact
  // zone, gap of the central node +0.026 without them and -0.032 with them, 30 iterations).
  // When the pairs of this search equal those of k = 2 .. 8 searches ago and differ from the
  // last ones, the largest set of the cycle is held for the rest of the step (the same on every
  // rank: the sets are compared by their number of pairs and hashes over all ranks, and each
  // rank holds its pairs of the set).
  const auto current = s.search->self_pairs();
  const auto set = s.search->pair_set();
  auto& history = s.pair_history;
  // For tests (docs/contact_dynamics.md, "Pair cycling"): SEAM_HOLD_SELF_PAIRS=1 holds the
  // pairs of each step's second search, so that the held path runs on small cases.
  static const bool hold_for_tests = [] {
    const char* v = std::getenv("SEAM_HOLD_SELF_PAIRS");
    return v != nullptr && std::string_view(v) == "1";
  }();
  if (hold_for_tests && !history.empty()) {
    s.search->to_interface(current, s.held_pairs);
    s.pairs_held = true;
    return;
  }
  const std::size_t n = history.size();
  for (std::size_t k = 2; k <= std::min(ContactSearch::max_pair_period, n); ++k) {
    if (!(history[n - k].set == set) || history[n - 1].set == set) continue;
    std::size_t largest = n; // the current set
    for (std::size_t i = n - k + 1; i < n; ++i)
      if (history[i].set.count > (largest == n ? set.count : history[largest].set.count))
        largest = i;
    // In the interface's indices (the ghosts are those of this search until the step ends).
    s.search->to_interface(largest == n ? current
                                        : std::span<const FacetIdPair>(history[largest].pairs),
                           s.held_pairs);
    s.pairs_held = true;
    if (largest != n) s.itf.set_candidates(s.held_pairs);
    return;
  }
  history.push_back({set, {current.begin(), current.end()}});
  if (history.size() > ContactSearch::max_pair_period + 1) history.pop_front();
}

void ContactConstraint::sum_nodal_values(Side& s) const {
  const auto n = static_cast<std::size_t>(s.itf.n_slave_nodes());
  const int width = s.friction ? 3 : 2;
  std::vector<double> v(n * width, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    v[j * width] = s.part.D[j];
    v[j * width + 1] = s.part.gap[j];
    if (s.friction) v[j * width + 2] = s.part.D[j];
  }
  // Standard multipliers: the nodal weight sum_k D_jk takes the place of D_jj.
  for (const auto& e : s.part.D_coupling) v[static_cast<std::size_t>(e.row) * width] += e.value;
  s.nodal.sent = static_cast<std::int64_t>(
      parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, v, width));
  s.D.resize(n);
  s.gap.resize(n);
  if (s.friction) s.D_diag.resize(n);
  for (std::size_t j = 0; j < n; ++j) {
    s.D[j] = v[j * width];
    s.gap[j] = v[j * width + 1];
    if (s.friction) s.D_diag[j] = v[j * width + 2];
  }
}

void ContactConstraint::publish_nodal_values(Side& s, std::vector<char>& next) const {
  const auto n = static_cast<std::size_t>(s.itf.n_slave_nodes());
  const int width = s.friction ? 4 : 3;
  std::vector<double> v(n * width, 0.0);
  for (std::size_t j = 0; j < n; ++j) {
    v[j * width] = s.D[j];
    v[j * width + 1] = s.gap[j];
    v[j * width + width - 1] = static_cast<double>(next[j]);
    if (s.friction) v[j * width + 2] = s.D_diag[j];
  }
  // The owned nodes with nonzero records (publish() counts the records sent, one per holder
  // on a side held in part).
  s.nodal.decided = 0;
  for (std::size_t j = 0; j < n; ++j)
    if (s.node_owners[j] == disc_.comm().rank())
      s.nodal.decided +=
          std::any_of(&v[j * width], &v[j * width] + width, [](double x) { return x != 0.0; });
  publish(s, v, width);
  for (std::size_t j = 0; j < n; ++j) {
    s.D[j] = v[j * width];
    s.gap[j] = v[j * width + 1];
    next[j] = static_cast<char>(v[j * width + width - 1]);
    if (s.friction) s.D_diag[j] = v[j * width + 2];
  }
}

std::size_t ContactConstraint::publish(const Side& s, std::span<double> values, int width) const {
  if (s.holders) return s.holders->publish(values, width);
  return parallel::publish_from_owners(disc_.comm().get(), s.node_keys, s.node_owners, values,
                                       width);
}

double ContactConstraint::max_weight(const Side& s) const {
  double d_max = 0.0;
  for (const double d : s.D) d_max = std::max(d_max, d);
  return disc_.comm().max(d_max);
}

void ContactConstraint::add_force(la::Vector& r, bool between_bodies_only) const {
  const int dim = disc_.dim();
  std::vector<PetscInt> rows;
  std::vector<double> values;
  for (const auto& s : sides_) {
    if (between_bodies_only && s.itf.rigid()) continue;
    if (s.discrete_gradient) {
      // -sum_j lambda_n,j grad_d g~_j (the nodes this rank owns); with friction the mortar
      // force of the tangential parts follows.
      const auto lambda_n = normal_multipliers(s);
      for (const auto& e : s.em_gradient) {
        rows.push_back(global_dof(e.dof));
        values.push_back(lambda_n[e.j] * e.value);
      }
      if (!s.friction) continue;
    }
    std::vector<double> f(
        (static_cast<std::size_t>(disc_.mesh().n_nodes()) + outside_.size()) * dim, 0.0);
    if (s.discrete_gradient)
      add_energy_momentum_friction_force(s, f);
    else
      s.itf.add_force(s.part, s.lambda, f);
    if (!s.T_inverse.empty()) {
      // Slave forces of the modified basis: f_S = T^-T (D lambda n).
      const auto& nodes = s.itf.slave().mesh_nodes;
      std::vector<double> y(nodes.size() * dim), fs(nodes.size() * dim, 0.0);
      for (std::size_t j = 0; j < nodes.size(); ++j)
        for (int c = 0; c < dim; ++c)
          y[j * dim + c] = f[static_cast<std::size_t>(nodes[j]) * dim + c];
      std::vector<char> has_row(nodes.size(), 0);
      for (const auto& e : s.T_inverse) has_row[static_cast<std::size_t>(e.row)] = 1;
      for (std::size_t j = 0; j < nodes.size(); ++j)
        if (!has_row[j])
          for (int c = 0; c < dim; ++c) fs[j * dim + c] = y[j * dim + c];
      for (const auto& e : s.T_inverse)
        for (int c = 0; c < dim; ++c)
          fs[static_cast<std::size_t>(e.col) * dim + c] +=
              e.value * y[static_cast<std::size_t>(e.row) * dim + c];
      for (std::size_t j = 0; j < nodes.size(); ++j)
        for (int c = 0; c < dim; ++c)
          f[static_cast<std::size_t>(nodes[j]) * dim + c] = fs[j * dim + c];
    }
    for (std::size_t i = 0; i < f.size(); ++i) {
      if (f[i] == 0.0) continue;
      rows.push_back(dof_of(static_cast<std::int32_t>(i / dim), static_cast<int>(i % dim)));
      values.push_back(f[i]);
    }
  }
  r.add_values(rows, values);
  r.assemble();
}

double ContactConstraint::complementarity_norm() const {
  double sum = 0.0, own = 0.0;
  for (const auto& s : sides_) {
    if (s.friction) {
      sum += s.ncp_norm2;
      continue;
    }
    // Each node once, by its owner (a slave side held in part is not whole on any rank).
    const int rank = disc_.comm().rank();
    for (std::size_t j = 0; j < s.active.size(); ++j) {
      if (s.node_owners[j] != rank) continue;
      const double c = s.active[j] ? s.c_n * s.gap[j] : s.D[j] * s.lambda[j];
      own += c * c;
    }
  }
  return std::sqrt(sum + disc_.comm().sum(own));
}

void ContactConstraint::condense(const la::Matrix& K, const la::Vector& r, la::Matrix& Ksys,
                                 la::Vector& rsys, PhaseTimers& timers) {
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  const PetscInt first = disc_.first_owned_dof();
  const PetscInt n_owned = disc_.n_owned_dofs();
  std::vector<PetscInt> ki, kj, li, lj, gi, gj;
  std::vector<double> kv, lv, gv;
  std::vector<char> replaced(static_cast<std::size_t>(n_owned), 0);
  std::vector<PetscInt> gap_rows, friction_rows;
  std::vector<double> gap_values, friction_values;
  for (auto& s : sides_) {
    ScopedTimer timer(timers, "mortar");
    linearize(s, ki, kj, kv);
    const auto& nodes = s.itf.slave().mesh_nodes;
    std::vector<NodeFrame> frames(nodes.size());
    for (std::size_t j = 0; j < nodes.size(); ++j)
      if (s.active[j]) frames[j] = frame(s, j);
    for (const auto& e : s.lin.gap_gradient) {
      const auto j = static_cast<std::size_t>(e.row);
      gi.push_back(dof_of(nodes[j], frames[j].gap_component));
      gj.push_back(global_dof(e.col));
      gv.push_back(s.c_n * e.value);
    }
    if (s.friction) {
      condense_friction(s, replaced, li, lj, lv, gi, gj, gv, gap_rows, gap_values, friction_rows,
                        friction_values);
      continue;
    }
    // Master rows: (M_jl / (D_jj w.n_j)) n_j w^T applied to the rows of slave node j.
    const double* normals = s.itf.normals().data();
    for (const auto& e : s.part.M) {
      const auto j = static_cast<std::size_t>(e.slave);
      if (!s.active[j]) continue;
      const NodeFrame& f = frames[j];
      const double scale = e.value / (s.D[j] * f.wn);
      for (int a = 0; a < dim; ++a)
        for (int b = 0; b < dim; ++b) {
          const double v = scale * normals[j * dim + a] * f.w[b];
          if (v == 0.0) continue;
          li.push_back(dof_of(e.master_node, a));
          lj.push_back(dof_of(nodes[j], b));
          lv.push_back(v);
        }
    }
    // Free rows of the active slave nodes this rank owns: the gap row and the tangent rows.
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (!s.active[j] || !owns(nodes[j])) continue;
      const NodeFrame& f = frames[j];
      const PetscInt gap_row = dof_of(nodes[j], f.gap_component);
      replaced[static_cast<std::size_t>(gap_row - first)] = 1;
      gap_rows.push_back(gap_row);
      gap_values.push_back(s.c_n * s.gap[j]);
      for (int i = 0; i < f.n_tangents; ++i) {
        const PetscInt row = dof_of(nodes[j], f.tangent_component[i]);
        replaced[static_cast<std::size_t>(row - first)] = 1;
        for (int b = 0; b < dim; ++b)
          if (f.tangent[i][b] != 0.0) {
            li.push_back(row);
            lj.push_back(dof_of(nodes[j], b));
            lv.push_back(f.tangent[i][b]);
          }
      }
    }
  }
  ScopedTimer timer(timers, "condensation");
  // L = I + dL: only the rows of the active slave nodes and of their master nodes differ from
  // the identity, so the products below touch those rows of K alone.
  for (PetscInt i = 0; i < n_owned; ++i)
    if (replaced[static_cast<std::size_t>(i)]) {
      li.push_back(first + i);
      lj.push_back(first + i);
      lv.push_back(-1.0);
    }
  const MPI_Comm mpi = comm.get();
  Kc_ = la::Matrix::from_triplets(mpi, n_owned, ki, kj, kv);
  const auto dL = la::Matrix::from_triplets(mpi, n_owned, li, lj, lv);
  // Ksys = L P K + L Kc + G = K + dLP K + Kc + dL Kc + G with L P = I + dLP,
  // dLP = dL + dP + dL dP (P = I + dP, dP = 0 without a modified slave basis).
  la::Matrix dLP = dL.copy();
  if (transformed()) {
    dP_ = transformation_delta();
    dLP.axpy_any_pattern(1.0, dP_);
    dLP.axpy_any_pattern(1.0, la::Matrix::multiply(dL, dP_));
  }
  // S = dLP K + dL Kc + Kc + G from one set of triplets (products: this rank's rows of them,
  // each entry once; Kc and G: the triplets as given, on any rank). Each entry of S sums its
  // parts in that order.
  std::vector<PetscInt> si, sj;
  std::vector<double> sv;
  la::Matrix::append_product(dLP, K, si, sj, sv);
  la::Matrix::append_product(dL, Kc_, si, sj, sv);
  si.insert(si.end(), ki.begin(), ki.end());
  sj.insert(sj.end(), kj.begin(), kj.end());
  sv.insert(sv.end(), kv.begin(), kv.end());
  si.insert(si.end(), gi.begin(), gi.end());
  sj.insert(sj.end(), gj.begin(), gj.end());
  sv.insert(sv.end(), gv.begin(), gv.end());
  const auto S = la::Matrix::from_triplets(mpi, n_owned, si, sj, sv);
  // In place while the pattern holds (the matrix object and a kept preconditioner stay).
  Ksys.assign_sum(K, S);
  dLP.mult(r, rsys);
  rsys.axpy(1.0, r);
  rsys.set_values(gap_rows, gap_values);
  rsys.assemble();
  if (comm.any(!friction_rows.empty())) {
    rsys.add_values(friction_rows, friction_values);
    rsys.assemble();
  }
}

void ContactConstraint::recover(const la::Matrix& K, const la::Vector& r, const la::Vector& dd) {
  const int dim = disc_.dim();
  // The slave rows (combined by T^T with a modified basis) at the new state: K~ dd + r.
  la::Vector y = disc_.make_vector(), yc = disc_.make_vector();
  K.mult(dd, y);
  y.axpy(1.0, r);
  if (transformed()) {
    dP_.mult(y, yc); // y = P y = y + dP y
    y.axpy(1.0, yc);
  }
  Kc_.mult(dd, yc);
  y.axpy(1.0, yc);
  la::Vector::LocalView view(y, false);
  const auto values = view.values();
  const PetscInt first = disc_.first_owned_dof();
  for (auto& s : sides_) {
    const auto& nodes = s.itf.slave().mesh_nodes;
    if (s.friction) {
      // lambda_j = -P_V y_j / D_jj: the Cartesian multiplier in the free directions.
      std::vector<double> lambda(nodes.size() * dim, 0.0);
      for (std::size_t j = 0; j < nodes.size(); ++j) {
        if (!s.active[j] || !owns(nodes[j])) continue;
        for (int b = 0; b < dim; ++b)
          if (!s.dirichlet[j * dim + b])
            lambda[j * dim + b] =
                -values[static_cast<std::size_t>(dof_of(nodes[j], b) - first)] / s.D[j];
      }
      publish(s, lambda, dim);
      s.lambda = std::move(lambda);
      continue;
    }
    std::vector<double> lambda(nodes.size(), 0.0);
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (!s.active[j] || !owns(nodes[j])) continue;
      const NodeFrame f = frame(s, j);
      double wy = 0.0;
      for (int b = 0; b < dim; ++b)
        wy += f.w[b] * values[static_cast<std::size_t>(dof_of(nodes[j], b) - first)];
      lambda[j] = -wy / (s.D[j] * f.wn);
    }
    // The owners' multipliers (nonzero at active nodes only) to every rank.
    publish(s, lambda, 1);
    s.lambda = std::move(lambda);
  }
}

void ContactConstraint::linearize(Side& s, std::vector<PetscInt>& rows, std::vector<PetscInt>& cols,
                                  std::vector<double>& values) {
  const double cpu = cpu_seconds();
  // Energy-momentum contact: the gap rows and the tangent of the discrete-gradient force come
  // from the last evaluate().
  if (!s.discrete_gradient) s.itf.linearize(s.lambda, s.active, s.lin);
  if (s.discrete_gradient && !s.em_tangent_current) {
    evaluate_discrete_gradient(s, s.em_displacement, true);
    if (s.friction) energy_momentum_friction_tangent(s);
    s.em_tangent_current = true;
  }
  s.work_seconds += cpu_seconds() - cpu;
  for (const auto& e : s.discrete_gradient ? s.em_tangent : s.lin.force_tangent) {
    rows.push_back(global_dof(e.row));
    cols.push_back(global_dof(e.col));
    values.push_back(e.value);
  }
}

PetscInt ContactConstraint::global_dof(std::int64_t mesh_dof) const {
  const int dim = disc_.dim();
  return dof_of(static_cast<std::int32_t>(mesh_dof / dim), static_cast<int>(mesh_dof % dim));
}

PetscInt ContactConstraint::dof_of(std::int32_t node, int c) const {
  const auto n = disc_.mesh().n_nodes();
  if (node < n) return disc_.global_dof(node, c);
  return static_cast<PetscInt>(outside_[static_cast<std::size_t>(node - n)].dofs[c]);
}

double ContactConstraint::reference(std::int32_t node, int c) const {
  const auto n = disc_.mesh().n_nodes();
  if (node < n) return disc_.mesh().x[static_cast<std::size_t>(node) * disc_.dim() + c];
  return outside_[static_cast<std::size_t>(node - n)].x[c];
}

std::int64_t ContactConstraint::node_id(std::int32_t node) const {
  const auto n = disc_.mesh().n_nodes();
  return node < n ? disc_.node_gid(node) : outside_[static_cast<std::size_t>(node - n)].id;
}

void ContactConstraint::node_positions(std::span<const std::int32_t> nodes,
                                       std::vector<double>& out) const {
  const int dim = disc_.dim();
  out.resize(nodes.size() * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    const auto node = static_cast<std::size_t>(nodes[i]);
    for (int c = 0; c < dim; ++c)
      out[i * dim + c] = reference(nodes[i], c) + u_mesh_[node * dim + c];
  }
}

void ContactConstraint::make_directories() {
  if (directory_made_) return;
  const auto& comm = disc_.comm();
  const auto& mesh = disc_.mesh();
  const int dim = disc_.dim();
  // Every master node of the facets the ranks hand in and every slave node of the slave
  // facets of their own cells, at its home rank (made at the first search or distribution:
  // `seam check` builds the constraint without the dof numbering).
  std::vector<OutsideNode> mine;
  const auto record = [&](std::int32_t node) {
    OutsideNode r;
    r.id = disc_.node_gid(node);
    r.owner = disc_.node_owner(node);
    for (int c = 0; c < dim; ++c) {
      r.dofs[c] = disc_.global_dof(node, c);
      r.x[c] = mesh.x[static_cast<std::size_t>(node) * dim + c];
    }
    mine.push_back(r);
  };
  const auto key = [](const SlaveFacet& f) { return f.key; };
  const auto by_key = [](const SlaveFacet& a, const SlaveFacet& b) {
    return a.key != b.key ? a.key < b.key : a.id < b.id;
  };
  std::vector<std::int64_t> from;
  for (auto& s : sides_) {
    if (s.master_in_part) {
      std::vector<local_index> nodes;
      s.search->nodes_read(s.itf, nodes);
      const auto masters = s.itf.master_nodes();
      for (const auto p : nodes) record(masters[static_cast<std::size_t>(p)]);
    }
    if (!s.slave_region) continue;
    // The slave facets of this rank's own cells (each on one rank) at the homes of their ids
    // and of their nodes' ids (the rings).
    std::vector<SlaveFacet> facets, rings;
    const auto& region = *s.slave_region;
    for (std::int32_t f = 0; f < region.n_facets(); ++f) {
      const auto c = region.facet_cell[static_cast<std::size_t>(f)];
      if (!disc_.is_local_cell(c)) continue;
      const auto cell = mesh.cell(c);
      const auto local = region.facet_local[static_cast<std::size_t>(f)];
      SlaveFacet r;
      r.id = disc_.cell_gid(c) * 8 + local;
      r.key = r.id;
      r.type = static_cast<std::int32_t>(
          fem::facet_type(mesh.cell_type[static_cast<std::size_t>(c)], local));
      for (const int k : fem::facet_nodes(mesh.cell_type[static_cast<std::size_t>(c)], local)) {
        const auto node = cell[static_cast<std::size_t>(k)];
        r.nodes[r.n_nodes++] = disc_.node_gid(node);
        record(node);
      }
      facets.push_back(r);
      for (std::int32_t k = 0; k < r.n_nodes; ++k) {
        rings.push_back(r);
        rings.back().key = r.nodes[k];
      }
    }
    s.facet_directory = to_homes(comm.get(), facets, key, from);
    s.ring_directory = to_homes(comm.get(), rings, key, from);
    std::sort(s.facet_directory.begin(), s.facet_directory.end(), by_key);
    std::sort(s.ring_directory.begin(), s.ring_directory.end(), by_key);
  }
  directory_ = to_homes(
      comm.get(), mine, [](const OutsideNode& r) { return r.id; }, from);
  const auto by_id = [](const OutsideNode& a, const OutsideNode& b) { return a.id < b.id; };
  std::sort(directory_.begin(), directory_.end(), by_id);
  directory_.erase(
      std::unique(directory_.begin(), directory_.end(),
                  [](const OutsideNode& a, const OutsideNode& b) { return a.id == b.id; }),
      directory_.end());
  directory_made_ = true;
}

void ContactConstraint::map_nodes(std::span<const std::int64_t> ids,
                                  std::vector<std::int32_t>& out) {
  make_directories();
  const auto outside_node = [&](std::int64_t id) {
    const auto it = std::lower_bound(outside_index_.begin(), outside_index_.end(),
                                     std::pair<std::int64_t, std::int32_t>{id, -1});
    return it != outside_index_.end() && it->first == id ? it->second : -1;
  };
  // Ids neither interface nodes of this part nor known outside nodes: asked at their homes.
  std::vector<std::int64_t> asked;
  for (const auto id : ids)
    if (node_of_gid(id) < 0 && outside_node(id) < 0) asked.push_back(id);
  const auto found = ask_homes<OutsideNode>(disc_.comm().get(), directory_, std::move(asked),
                                            [](const OutsideNode& r) { return r.id; });
  for (const auto& r : found) {
    if (outside_node(r.id) >= 0) continue;
    const auto node = static_cast<std::int32_t>(disc_.mesh().n_nodes() + outside_.size());
    outside_.push_back(r);
    reference_x_.insert(reference_x_.end(), r.x, r.x + disc_.dim());
    outside_index_.insert(std::lower_bound(outside_index_.begin(), outside_index_.end(),
                                           std::pair<std::int64_t, std::int32_t>{r.id, -1}),
                          {r.id, node});
  }
  out.resize(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) {
    const auto node = node_of_gid(ids[i]);
    out[i] = node >= 0 ? node : outside_node(ids[i]);
    SEAM_CHECK(out[i] >= 0, InternalError, "contact: node ", ids[i],
               " is in no rank's interface facets");
  }
}

meshtying::InterfaceSide ContactConstraint::slave_side_of(std::span<const SlaveFacet> facets) {
  const int dim = disc_.dim();
  // The nodes in increasing id (the side's order on every part): mesh nodes of this part, or
  // outside nodes from the directory.
  std::vector<std::int64_t> ids;
  for (const auto& f : facets) ids.insert(ids.end(), f.nodes, f.nodes + f.n_nodes);
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  std::vector<std::int32_t> nodes(ids.size()), mapped;
  std::vector<std::int64_t> outside;
  for (std::size_t i = 0; i < ids.size(); ++i) {
    nodes[i] = mesh_node_of(ids[i]);
    if (nodes[i] < 0) outside.push_back(ids[i]);
  }
  map_nodes(outside, mapped);
  std::size_t k = 0;
  for (auto& node : nodes)
    if (node < 0) node = mapped[k++];
  meshtying::InterfaceSide side;
  side.dim = dim;
  side.mesh_nodes = std::move(nodes);
  side.coordinates.resize(ids.size() * static_cast<std::size_t>(dim));
  for (std::size_t i = 0; i < ids.size(); ++i)
    for (int c = 0; c < dim; ++c) side.coordinates[i * dim + c] = reference(side.mesh_nodes[i], c);
  for (const auto& f : facets) {
    side.types.push_back(static_cast<fem::CellType>(f.type));
    for (std::int32_t a = 0; a < f.n_nodes; ++a)
      side.nodes.push_back(static_cast<local_index>(
          std::lower_bound(ids.begin(), ids.end(), f.nodes[a]) - ids.begin()));
    side.offsets.push_back(static_cast<local_index>(side.nodes.size()));
  }
  return side;
}

bool ContactConstraint::solve_saddle_point(const la::Matrix& K, const la::Vector& minus_r,
                                           std::span<const PetscInt> dirichlet, const la::Vector* g,
                                           la::LinearSolver& solver, la::Vector& dd,
                                           PhaseTimers& timers) {
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  const PetscInt n_disp = disc_.n_owned_dofs();
  std::vector<PetscInt> ki, kj, bi, bj, ci, cj, ei, ej;
  std::vector<double> kv, bv, cv, ev, lm_rhs;
  for (auto& s : sides_) {
    {
      ScopedTimer timer(timers, "mortar");
      linearize(s, ki, kj, kv);
    }
    // B^T, this rank's part: column of multiplier j, rows D_jk n_j (slave k), -M_jl n_j; with
    // friction columns (j, c), rows D_jk e_c and -M_jl e_c.
    const auto& nodes = s.itf.slave().mesh_nodes;
    const double* normals = s.itf.normals().data();
    const auto add_column = [&](std::int32_t mesh_node, std::size_t j, double value) {
      for (int a = 0; a < dim; ++a) {
        const double v =
            s.friction ? value : value * normals[j * dim + static_cast<std::size_t>(a)];
        if (v == 0.0) continue;
        bi.push_back(dof_of(mesh_node, a));
        bj.push_back(s.lm_index[j] + (s.friction ? a : 0));
        bv.push_back(v);
      }
    };
    if (s.discrete_gradient && s.friction) {
      energy_momentum_friction_columns(s, bi, bj, bv);
    } else if (s.discrete_gradient) {
      // B^T: column j is -grad_d g~_j.
      for (const auto& e : s.em_gradient) {
        bi.push_back(global_dof(e.dof));
        bj.push_back(s.lm_index[e.j]);
        bv.push_back(e.value);
      }
    } else {
      for (std::size_t j = 0; j < nodes.size(); ++j)
        if (s.part.D[j] != 0.0) add_column(nodes[j], j, s.part.D[j]);
      for (const auto& e : s.part.D_coupling)
        add_column(nodes[static_cast<std::size_t>(e.col)], static_cast<std::size_t>(e.row),
                   e.value);
      for (const auto& e : s.part.M)
        add_column(e.master_node, static_cast<std::size_t>(e.slave), -e.value);
    }
    if (s.friction) {
      saddle_friction(s, ci, cj, cv, ei, ej, ev, lm_rhs);
      continue;
    }
    // Active rows: c_n dg~_j dd = -c_n g~_j; inactive rows: D_j lambda_j = 0.
    for (const auto& e : s.lin.gap_gradient) {
      if (!s.active[static_cast<std::size_t>(e.row)]) continue;
      ci.push_back(s.lm_index[static_cast<std::size_t>(e.row)]);
      cj.push_back(global_dof(e.col));
      cv.push_back(s.c_n * e.value);
    }
    // Inactive nodes outside the contact zone (D_j = 0) get the mean nodal weight.
    const double weight = mean_weight(s);
    for (std::size_t j = 0; j < nodes.size(); ++j) {
      if (!owns(nodes[j])) continue;
      ei.push_back(s.lm_index[j]);
      ej.push_back(s.lm_index[j]);
      ev.push_back(s.active[j] ? 0.0 : (s.D[j] > 0.0 ? s.D[j] : weight));
      lm_rhs.push_back(s.active[j] ? -s.c_n * s.gap[j] : 0.0);
    }
  }
  auto assembly = std::make_unique<ScopedTimer>(timers, "condensation");
  const MPI_Comm mpi = comm.get();
  la::Matrix A11 = K.copy();
  A11.axpy_any_pattern(1.0, la::Matrix::from_triplets(mpi, n_disp, ki, kj, kv));
  const auto BT = la::Matrix::from_triplets(mpi, n_disp, bi, bj, bv, n_lm_);
  const auto C = la::Matrix::from_triplets(mpi, n_lm_, ci, cj, cv, n_disp);
  const auto E = la::Matrix::from_triplets(mpi, n_lm_, ei, ej, ev);
  // [K~ B^T; C E] as AIJ, rows per rank: displacement dofs, then multipliers.
  Mat blocks[4] = {A11.get(), BT.get(), C.get(), E.get()};
  Mat nest = nullptr, aug = nullptr;
  la::check(MatCreateNest(mpi, 2, nullptr, 2, nullptr, blocks, &nest), "MatCreateNest");
  la::check(MatConvert(nest, MATAIJ, MAT_INITIAL_MATRIX, &aug), "MatConvert");
  MatDestroy(&nest);
  la::Matrix A = la::Matrix::adopt(aug);
  la::Vector b(mpi, n_disp + n_lm_), x(mpi, n_disp + n_lm_), gx(mpi, n_disp + n_lm_);
  {
    la::Vector::LocalView bw(b, true), rv(minus_r, false);
    auto bl = bw.values();
    const auto rl = rv.values();
    for (PetscInt i = 0; i < n_disp; ++i) bl[i] = rl[i];
    for (PetscInt i = 0; i < n_lm_; ++i) bl[n_disp + i] = lm_rhs[static_cast<std::size_t>(i)];
  }
  // Augmented index of an owned displacement dof: shifted by the multipliers of lower ranks.
  std::vector<PetscInt> rows(dirichlet.begin(), dirichlet.end());
  for (auto& r : rows) r += first_lm_;
  if (g) {
    la::Vector::LocalView xw(gx, true), gv(*g, false);
    auto xl = xw.values();
    const auto gl = gv.values();
    for (PetscInt i = 0; i < n_disp; ++i) xl[i] = gl[i];
  }
  A.zero_rows_columns(rows, g ? &gx : nullptr, g ? &b : nullptr);
  // The unknowns are the new multipliers, whose rows of b hold the whole interface force: a
  // Krylov solve solves for their change from the present ones instead, so that its relative
  // tolerance applies to the Newton residual (the inexact-Newton forcing), not to b.
  const bool incremental = solver.kind() == la::SolverKind::iterative;
  la::Vector x0(mpi, n_disp + n_lm_);
  if (incremental) {
    {
      la::Vector::LocalView x0w(x0, true);
      auto x0l = x0w.values();
      PetscInt at = n_disp;
      for (const auto& s : sides_) {
        const auto& nodes = s.itf.slave().mesh_nodes;
        const std::size_t per_node = s.friction ? static_cast<std::size_t>(dim) : 1;
        const bool known = s.lambda.size() == nodes.size() * per_node;
        for (std::size_t j = 0; j < nodes.size(); ++j)
          if (owns(nodes[j]))
            for (std::size_t c = 0; c < per_node; ++c)
              x0l[at++] = known ? s.lambda[j * per_node + c] : 0.0;
      }
    }
    la::Vector Ax0(mpi, n_disp + n_lm_);
    A.mult(x0, Ax0);
    b.axpy(-1.0, Ax0);
  }
  assembly.reset();
  {
    ScopedTimer solve_timer(timers, "linear_solve");
    solver.set_saddle_point_fields(n_disp, n_lm_, K);
    if (!solver.solve(A, b, x)) return false;
  }
  static const bool measure = std::getenv("SEAM_NEWTON_CHECK") != nullptr;
  if (measure) {
    la::Vector Ax(mpi, n_disp + n_lm_);
    A.mult(x, Ax);
    Ax.axpy(-1.0, b);
    last_solve_residual_ = Ax.norm() / b.norm();
  }
  if (incremental) x.axpy(1.0, x0);
  la::Vector::LocalView xv(x, false), dw(dd, true);
  const auto xl = xv.values();
  auto dl = dw.values();
  for (PetscInt i = 0; i < n_disp; ++i) dl[i] = xl[i];
  PetscInt next = n_disp;
  for (auto& s : sides_) {
    const auto& nodes = s.itf.slave().mesh_nodes;
    const std::size_t per_node = s.friction ? static_cast<std::size_t>(dim) : 1;
    std::vector<double> lambda(nodes.size() * per_node, 0.0);
    for (std::size_t j = 0; j < nodes.size(); ++j)
      if (owns(nodes[j]))
        for (std::size_t c = 0; c < per_node; ++c) lambda[j * per_node + c] = xl[next++];
    publish(s, lambda, static_cast<int>(per_node));
    s.lambda = std::move(lambda);
  }
  return true;
}

double ContactConstraint::mean_weight(const Side& s) const {
  // Each node by its owner: the same mean on every rank, whatever part of the side it holds.
  double sums[2] = {0.0, 0.0};
  for (std::size_t j = 0; j < s.D.size(); ++j) {
    if (!(s.D[j] > 0.0) || s.node_owners[j] != disc_.comm().rank()) continue;
    sums[0] += s.D[j];
    sums[1] += 1.0;
  }
  disc_.comm().sum_in_place(std::span<double>(sums, 2));
  return sums[1] > 0.0 ? sums[0] / sums[1] : 1.0;
}

void ContactConstraint::hold_sets(bool hold) {
  held_ = false;
  for (auto& s : sides_) {
    s.held_frames.clear();
    if (!hold) continue;
    for (std::size_t j = 0; j < s.active.size(); ++j) s.held_frames.push_back(frame(s, j));
  }
  held_ = hold;
}

std::vector<double> ContactConstraint::multipliers() const {
  std::vector<double> out;
  for (const auto& s : sides_) out.insert(out.end(), s.lambda.begin(), s.lambda.end());
  return out;
}

void ContactConstraint::set_multipliers(std::span<const double> lambda) {
  std::size_t k = 0;
  for (auto& s : sides_)
    for (auto& l : s.lambda) l = lambda[k++];
}

std::vector<double> ContactConstraint::constraint_values() const {
  const int dim = disc_.dim();
  std::vector<double> out;
  for (const auto& s : sides_) {
    const auto n = s.active.size();
    if (!s.friction) {
      for (std::size_t j = 0; j < n; ++j) out.push_back(s.active[j] ? s.gap[j] : s.lambda[j]);
      continue;
    }
    const FrictionRows fr = friction_rows(s);
    for (std::size_t j = 0; j < n; ++j) {
      const auto offset = out.size();
      out.insert(out.end(), &s.lambda[j * dim], &s.lambda[j * dim] + dim);
      if (!s.active[j]) continue;
      const NodeFrame& f = fr.frames[j];
      out[offset + static_cast<std::size_t>(f.gap_component)] = s.gap[j];
      for (int i = 0; i < f.n_tangents; ++i)
        out[offset + static_cast<std::size_t>(f.tangent_component[i])] =
            fr.rows[j][static_cast<std::size_t>(i)].value;
    }
  }
  return out;
}

bool ContactConstraint::transformed() const {
  for (const auto& s : sides_)
    if (!s.T_inverse.empty()) return true;
  return false;
}

la::Matrix ContactConstraint::transformation_delta() const {
  // Row (j, c) of P: sum_k T_kj (row (k, c)), for the slave nodes this rank owns; prescribed
  // rows are left out (their equations hold reactions, and they are replaced anyway). dP = P - I.
  // Only the rows that carry multipliers need combining: those of the nodes of every facet with
  // an active node or a nonzero multiplier (the slave force T^-T D lambda n reaches no further);
  // P stays the identity elsewhere, which keeps the products with K to the contact zone.
  const int dim = disc_.dim();
  const PetscInt first = disc_.first_owned_dof();
  const PetscInt n_owned = disc_.n_owned_dofs();
  std::vector<char> has_row(static_cast<std::size_t>(n_owned), 0);
  std::vector<PetscInt> pi, pj;
  std::vector<double> pv;
  for (const auto& s : sides_) {
    if (s.T_inverse.empty()) continue; // untransformed (energy-momentum contact)
    const auto& nodes = s.itf.slave().mesh_nodes;
    const auto& facets = s.itf.slave().facet_set();
    std::vector<char> zone(nodes.size(), 0);
    for (local_index f = 0; f < facets.n_facets(); ++f) {
      const auto fn = facets.facet_nodes(f);
      bool carries = false;
      const int per_node = s.friction ? dim : 1; // Cartesian multipliers with friction
      for (const auto j : fn) {
        carries = carries || s.active[j];
        for (int c = 0; c < per_node; ++c)
          carries = carries || s.lambda[static_cast<std::size_t>(j) * per_node + c] != 0.0;
      }
      if (carries)
        for (const auto j : fn) zone[static_cast<std::size_t>(j)] = 1;
    }
    for (const auto& e : s.itf.transformation()) {
      const auto j = static_cast<std::size_t>(e.col), k = static_cast<std::size_t>(e.row);
      if (!zone[j] || !owns(nodes[j])) continue;
      for (int c = 0; c < dim; ++c) {
        if (k != j && s.dirichlet[k * dim + c]) continue;
        const PetscInt row = dof_of(nodes[j], c);
        has_row[static_cast<std::size_t>(row - first)] = 1;
        pi.push_back(row);
        pj.push_back(dof_of(nodes[k], c));
        pv.push_back(e.value);
      }
    }
  }
  for (PetscInt i = 0; i < n_owned; ++i)
    if (has_row[static_cast<std::size_t>(i)]) {
      pi.push_back(first + i);
      pj.push_back(first + i);
      pv.push_back(-1.0);
    }
  return la::Matrix::from_triplets(disc_.comm().get(), n_owned, pi, pj, pv);
}

void ContactConstraint::distribute(Side& s) {
  if (!s.distribution) {
    // One rank, or `interface_distribution: bulk`: the facets stay with their cells.
    if (!s.distributed) s.itf.set_owned_facets(s.bulk_facets);
    s.distributed = true;
    return;
  }
  const int dim = disc_.dim();
  const auto owned = s.itf.owned_facets();
  const std::vector<local_index> held =
      s.distributed ? std::vector<local_index>(owned.begin(), owned.end()) : s.bulk_facets;
  // The facets this rank holds, by global id, with their centroids and work.
  const auto n = held.size();
  std::vector<std::int64_t> ids(n);
  std::vector<double> centroids(n * static_cast<std::size_t>(dim)), work(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto f = held[i];
    ids[i] = s.slave_ids.facets[static_cast<std::size_t>(f)];
    const auto c = s.itf.slave_centroid(f);
    for (int a = 0; a < dim; ++a) centroids[i * dim + a] = c[static_cast<std::size_t>(a)];
    // The work of a facet: its candidate pairs (each one a projection and a clip) and its
    // integration cells at the last evaluation (known once it has been evaluated).
    work[i] = static_cast<double>(s.itf.n_pairs_of(f));
    if (s.distributed)
      work[i] += static_cast<double>(s.part.facet_cells[static_cast<std::size_t>(f)]);
  }
  evaluate_facets(s, s.distribution->distribute(ids, centroids, work), {});
}

void ContactConstraint::evaluate_facets(Side& s, std::vector<std::int64_t> ids,
                                        std::vector<std::int64_t> kept) {
  // The slave side follows the facets this rank evaluates now (the independent distribution
  // with the slave side held in part).
  if (s.slave_region) hold_slave_part(s, ids, std::move(kept), false);
  std::vector<local_index> facets(ids.size());
  for (std::size_t i = 0; i < ids.size(); ++i) facets[i] = s.slave_ids.facet(ids[i]);
  s.itf.set_owned_facets(std::move(facets));
  if (s.slave_region && s.itf.self_contact()) {
    // The slave patch of the last search's pairs over the new part: the output rows of the
    // step read its normals before the next search.
    std::vector<mortar::CandidatePair> pairs;
    s.search->route_self_pairs();
    s.search->to_interface(s.search->self_pairs(), pairs);
    // set_candidates averages the normals anew over the side as made (reference coordinates):
    // the normals kept through the cut are read until the next placement (the frictional work
    // of the step, summed by the owners).
    const std::vector<double> normals(s.itf.normals().begin(), s.itf.normals().end());
    s.itf.set_candidates(pairs);
    s.itf.set_normals(normals);
  }
  s.distributed = true;
}

std::size_t ContactConstraint::count_outside_side(Side& s, std::vector<std::int64_t> ids) {
  make_directories();
  const auto n = ids.size();
  const auto found = ask_homes<SlaveFacet>(disc_.comm().get(), s.facet_directory, std::move(ids),
                                           [](const SlaveFacet& f) { return f.key; });
  return n - std::min(n, found.size());
}

void ContactConstraint::hold_slave_part(Side& s, std::vector<std::int64_t> evaluated,
                                        std::vector<std::int64_t> kept, bool own_cells) {
  make_directories();
  const auto& comm = disc_.comm();
  const auto& mesh = disc_.mesh();
  const auto& region = *s.slave_region; // the facets of its own and ghost cells
  const auto key = [](const SlaveFacet& f) { return f.key; };
  // The facets of its mesh, by id (increasing along the region).
  std::vector<SlaveFacet> local(static_cast<std::size_t>(region.n_facets()));
  for (std::size_t f = 0; f < local.size(); ++f) {
    const auto c = region.facet_cell[f];
    const auto cell = mesh.cell(c);
    auto& r = local[f];
    r.id = disc_.cell_gid(c) * 8 + region.facet_local[f];
    r.key = r.id;
    r.type = static_cast<std::int32_t>(
        fem::facet_type(mesh.cell_type[static_cast<std::size_t>(c)], region.facet_local[f]));
    for (const int k :
         fem::facet_nodes(mesh.cell_type[static_cast<std::size_t>(c)], region.facet_local[f]))
      r.nodes[r.n_nodes++] = disc_.node_gid(cell[static_cast<std::size_t>(k)]);
  }
  const auto owned = [&](std::int64_t id) {
    const auto node = mesh_node_of(id);
    return node >= 0 && owns(node);
  };
  std::sort(evaluated.begin(), evaluated.end());
  // With friction this rank's part of M^n (summed by slave node into the slip increments)
  // keeps its slave nodes held until it is replaced.
  if (s.friction) {
    for (const auto* m : {&s.M_old, &s.part.M})
      for (const auto& e : *m) kept.push_back(s.node_keys[static_cast<std::size_t>(e.slave)]);
    // Standard multipliers: its part of D^n_jk and D_jk (j != k) too, both nodes.
    for (const auto* d : {&s.D_coupling_old, &s.part.D_coupling})
      for (const auto& e : *d)
        for (const auto j : {e.row, e.col})
          kept.push_back(s.node_keys[static_cast<std::size_t>(j)]);
  }
  // The facets it evaluates: from its mesh, or sent from the facet directory.
  std::vector<SlaveFacet> held;
  std::vector<std::int64_t> asked;
  for (const auto id : evaluated) {
    const auto it = std::lower_bound(local.begin(), local.end(), id,
                                     [](const SlaveFacet& f, std::int64_t i) { return f.id < i; });
    if (it != local.end() && it->id == id)
      held.push_back(*it);
    else
      asked.push_back(id);
  }
  const auto sent = ask_homes<SlaveFacet>(comm.get(), s.facet_directory, std::move(asked), key);
  held.insert(held.end(), sent.begin(), sent.end());
  // The nodes whose rings it holds: those of the facets it evaluates (unless s.compact: against
  // a rigid obstacle no ring is read) and `kept`; after the first distribution also the nodes
  // it owns (it decides their status from their normals), whose rings its mesh holds.
  std::vector<std::int64_t> ring = std::move(kept);
  if (!s.compact)
    for (const auto& f : held) ring.insert(ring.end(), f.nodes, f.nodes + f.n_nodes);
  std::sort(ring.begin(), ring.end());
  ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
  // Before the first distribution the facets of its own and ghost cells (the bulk share it
  // starts from); on a self-contact surface always those of its own cells (it hands them in
  // to the search).
  if (own_cells) held.insert(held.end(), local.begin(), local.end());
  if (s.itf.self_contact() && !own_cells)
    for (std::size_t f = 0; f < local.size(); ++f)
      if (disc_.is_local_cell(region.facet_cell[f])) held.push_back(local[f]);
  // Against a rigid obstacle, for each node it owns that none of the evaluated facets has, one
  // facet of its mesh that has it: first the facets all of whose nodes it owns and needs (few
  // facets cover many nodes), then one for each node still without.
  if (s.compact && !own_cells) {
    std::vector<std::int64_t> covered;
    for (const auto& f : held) covered.insert(covered.end(), f.nodes, f.nodes + f.n_nodes);
    std::sort(covered.begin(), covered.end());
    for (const bool all : {true, false})
      for (const auto& f : local) {
        int wanted = 0;
        for (std::int32_t a = 0; a < f.n_nodes; ++a)
          wanted +=
              owned(f.nodes[a]) && !std::binary_search(covered.begin(), covered.end(), f.nodes[a]);
        if (wanted == 0 || (all && wanted < f.n_nodes)) continue;
        held.push_back(f);
        for (std::int32_t a = 0; a < f.n_nodes; ++a)
          covered.insert(std::lower_bound(covered.begin(), covered.end(), f.nodes[a]), f.nodes[a]);
      }
  }
  // The rings: of the nodes it owns from its mesh (which holds every cell around them), of the
  // others from the ring directory.
  std::vector<std::int64_t> ring_asked;
  for (const auto id : ring)
    if (!owned(id)) ring_asked.push_back(id);
  for (const auto& f : local) {
    bool in_ring = false;
    for (std::int32_t a = 0; a < f.n_nodes && !in_ring; ++a)
      in_ring = (!s.compact && !own_cells && owned(f.nodes[a])) ||
                std::binary_search(ring.begin(), ring.end(), f.nodes[a]);
    if (in_ring) held.push_back(f);
  }
  const auto around =
      ask_homes<SlaveFacet>(comm.get(), s.ring_directory, std::move(ring_asked), key);
  held.insert(held.end(), around.begin(), around.end());
  std::sort(held.begin(), held.end(),
            [](const SlaveFacet& a, const SlaveFacet& b) { return a.id < b.id; });
  held.erase(std::unique(held.begin(), held.end(),
                         [](const SlaveFacet& a, const SlaveFacet& b) { return a.id == b.id; }),
             held.end());
  std::vector<std::int64_t> facet_ids(held.size());
  for (std::size_t f = 0; f < held.size(); ++f) facet_ids[f] = held[f].id;
  // The nodal state by node id: kept where this rank held the node, zero elsewhere, then the
  // owners' values published to every holder (an owner holds its nodes before and after).
  const std::vector<std::int64_t> before = s.node_keys;
  s.itf.hold_slave_facets(slave_side_of(held));
  index_slave_side(s, std::move(facet_ids));
  if (!s.discrete_gradient) s.T_inverse = mortar::inverse_transformation(s.itf.transformation());
  const auto& after = s.node_keys;
  const auto moved = [&](auto& values, std::size_t width) {
    values.resize(before.size() * width, {}); // D and g~ are sized at the first sums
    std::remove_reference_t<decltype(values)> out(after.size() * width, {});
    for (std::size_t j = 0; j < after.size(); ++j) {
      const auto it = std::lower_bound(before.begin(), before.end(), after[j]);
      if (it == before.end() || *it != after[j]) continue;
      const auto i = static_cast<std::size_t>(it - before.begin());
      std::copy_n(values.begin() + static_cast<std::ptrdiff_t>(i * width), width,
                  out.begin() + static_cast<std::ptrdiff_t>(j * width));
    }
    values = std::move(out);
  };
  const auto dim = static_cast<std::size_t>(disc_.dim());
  // Moved, then the owners' values published (every array is the owners' on every holder).
  std::vector<double> buffer;
  const auto follow = [&](auto& values, std::size_t width) {
    moved(values, width);
    buffer.assign(values.begin(), values.end());
    publish(s, buffer, static_cast<int>(width));
    for (std::size_t i = 0; i < buffer.size(); ++i)
      values[i] = static_cast<std::remove_reference_t<decltype(values[i])>>(buffer[i]);
  };
  const std::size_t per_node = s.friction ? dim : 1;
  for (auto* v : {&s.lambda, &s.lambda_saved}) follow(*v, per_node);
  for (auto* v : {&s.D, &s.gap}) follow(*v, 1);
  for (auto* v : {&s.active, &s.active_previous, &s.active_accepted}) follow(*v, 1);
  moved(s.dirichlet, dim);
  buffer.assign(s.dirichlet.begin(), s.dirichlet.end());
  publish(s, buffer, static_cast<int>(dim));
  for (std::size_t i = 0; i < buffer.size(); ++i) s.dirichlet[i] = buffer[i] > 0.0;
  if (s.friction) {
    for (auto* v : {&s.status, &s.status_previous, &s.status_accepted, &s.frozen_nodes})
      follow(*v, 1);
    for (auto* v : {&s.slip, &s.x, &s.x_old}) follow(*v, dim);
    for (auto* v : {&s.D_diag, &s.D_diag_old}) follow(*v, 1);
  }
  // This rank's parts of M^n and of M (M^n at the next save()) by their slave nodes' new
  // indices (held with friction: `kept`; without, M is read no more before the next
  // evaluation, and its rows of nodes no longer held are dropped); its nodal sums of the last
  // evaluation by node.
  for (auto* m : {&s.M_old, &s.part.M}) {
    std::size_t k = 0;
    for (auto e : *m) {
      const auto id = before[static_cast<std::size_t>(e.slave)];
      const auto it = std::lower_bound(after.begin(), after.end(), id);
      const bool held = it != after.end() && *it == id;
      SEAM_CHECK(held || !s.friction, InternalError, "contact: slave node ", id,
                 " of M is not held after the distribution");
      if (!held) continue;
      e.slave = static_cast<local_index>(it - after.begin());
      (*m)[k++] = e;
    }
    m->resize(k);
  }
  // Standard multipliers: its parts of D^n_jk and D_jk by their nodes' new indices (held with
  // friction; without, D_jk is read no more before the next evaluation).
  const auto index_after = [&](std::int32_t j) -> std::int32_t {
    const auto id = before[static_cast<std::size_t>(j)];
    const auto it = std::lower_bound(after.begin(), after.end(), id);
    return it != after.end() && *it == id ? static_cast<std::int32_t>(it - after.begin()) : -1;
  };
  for (auto* d : {&s.D_coupling_old, &s.part.D_coupling}) {
    std::size_t k = 0;
    for (auto e : *d) {
      e.row = index_after(e.row);
      e.col = index_after(e.col);
      SEAM_CHECK((e.row >= 0 && e.col >= 0) || !s.friction, InternalError, "contact: a slave node ",
                 "of D_jk is not held after the distribution");
      if (e.row >= 0 && e.col >= 0) (*d)[k++] = e;
    }
    d->resize(k);
  }
  for (auto* v : {&s.part.D, &s.part.gap}) moved(*v, 1);
  if (s.discrete_gradient) {
    // The gap rows and the discrete gradients of the last evaluation (the owner's nodes, which
    // it holds before and after: read by the reports of the step).
    moved(s.em_row, 1);
    if (s.friction) moved(s.em_gap_mid, dim);
    for (auto& e : s.em_gradient) {
      const auto j = index_after(static_cast<std::int32_t>(e.j));
      SEAM_CHECK(j >= 0, InternalError, "contact: an owned slave node is not held after the ",
                 "distribution");
      e.j = static_cast<std::size_t>(j);
    }
  }
  if (lm_numbered_) number_multipliers(s);
  s.cycles = {};
  s.held_frames.clear();
  collect_interface_nodes();
}

void ContactConstraint::balance() {
  const auto& comm = disc_.comm();
  // Timing differences below this are noise, not imbalance.
  constexpr double noise_seconds = 1e-3;
  for (auto& s : sides_) {
    parallel::RankWork mine;
    mine.pairs = s.part.n_pairs;
    mine.integration_cells = s.part.n_cells;
    mine.seconds = parallel_.work == io::WorkMeasure::time ? s.work_seconds
                                                           : static_cast<double>(s.part.n_cells);
    s.balance = parallel::LoadMonitor(parallel_.rebalance_tolerance).evaluate(comm.get(), mine);
    // This rank's share in the step, before a redistribution changes it.
    s.share.slave_elements = static_cast<int>(s.itf.owned_facets().size());
    std::vector<local_index> masters;
    for (const auto f : s.itf.owned_facets())
      for (const auto& p : s.itf.pairs_of(f)) masters.push_back(p.master);
    std::sort(masters.begin(), masters.end());
    s.share.master_ghosts =
        static_cast<int>(std::unique(masters.begin(), masters.end()) - masters.begin());
    s.share.candidates =
        static_cast<std::int64_t>(comm.sum(static_cast<double>(s.itf.n_candidates())));
    // Without the distributed search a rank searches against the whole master surface.
    s.share.master_received = s.itf.self_contact() ? 0
                              : s.search           ? s.search->n_received()
                                                   : s.itf.n_master_facets();
    s.share.surface_received = s.itf.self_contact() ? s.search->n_received() : 0;
    if (s.itf.self_contact()) {
      s.share.self_pairs_received = s.search->self_pairs_received();
      s.share.self_pairs_returned = s.search->self_pairs_returned();
      s.share.self_groups = s.search->self_groups_decided();
      s.share.label_rounds = s.search->label_rounds();
    }
    if (s.search) {
      s.share.ghost_exchanges = s.search->n_exchanges();
      s.share.searches = s.search->n_searches();
    }
    s.work_seconds = 0.0;
    s.redistributed = false;
    if (!s.distribution || !s.balance.rebalance) continue;
    if (parallel_.work == io::WorkMeasure::time &&
        s.balance.time.max - s.balance.time.min < noise_seconds)
      continue;
    distribute(s);
    s.redistributed = true;
  }
}

void ContactConstraint::save() {
  for (auto& s : sides_) {
    // Self contact: the roles of this step's pairs carry into the next step.
    if (s.search) s.search->accept_step();
    s.lambda_saved = s.lambda;
    s.active_accepted = s.active;
    if (s.friction) {
      s.status_accepted = s.status;
      save_friction(s);
    }
  }
}

bool ContactConstraint::set_changed() const {
  bool changed = false;
  for (const auto& s : sides_) changed = changed || s.active != s.active_accepted;
  return disc_.comm().max(changed ? 1.0 : 0.0) > 0.0;
}

void ContactConstraint::restore() {
  // A new attempt starts from the statuses of the last converged step, as the first attempt
  // did: a node on its friction cone keeps the status it has (contact_friction.cpp), which
  // must not be the one a failed attempt left.
  for (auto& s : sides_) {
    s.lambda = s.lambda_saved;
    s.active = s.active_accepted;
    if (s.friction) s.status = s.status_accepted;
  }
}

int ContactConstraint::n_active() const {
  // Each node counted by its owner.
  const int rank = disc_.comm().rank();
  double n = 0.0;
  for (const auto& s : sides_)
    for (std::size_t j = 0; j < s.active.size(); ++j)
      n += s.node_owners[j] == rank && s.active[j] == 1;
  return static_cast<int>(disc_.comm().sum(n));
}

std::vector<std::string> ContactConstraint::describe() const {
  std::vector<std::string> out;
  for (const auto& s : sides_) {
    char line[256];
    const int n_facets =
        s.slave_in_part ? s.slave_facets : static_cast<int>(s.itf.slave().n_facets());
    const char* multipliers =
        s.itf.standard() ? "standard multipliers (saddle point)" : "dual multipliers (condensed)";
    if (s.itf.self_contact())
      std::snprintf(line, sizeof line,
                    "interface %s: self and multi-body contact over %d surface facets (slave and "
                    "master roles assigned at every search), %s, c_n = %.4g",
                    s.itf.name().c_str(), n_facets, multipliers, s.c_n);
    else
      std::snprintf(line, sizeof line,
                    "interface %s: contact, %d slave facets against %s, %s, c_n = %.4g",
                    s.itf.name().c_str(), n_facets,
                    s.itf.rigid() ? s.itf.obstacle().name()
                                  : (std::to_string(s.master_facets) + " master facets").c_str(),
                    multipliers, s.c_n);
    std::string text = line;
    if (s.discrete_gradient)
      text += s.friction
                  ? (s.itf.rigid() ? ", energy-momentum contact force (discrete gradient of the "
                                     "weighted gaps; friction: slip over the step's mean D)"
                                   : ", energy-momentum contact force (discrete gradient of the "
                                     "weighted gaps; friction: frame-indifferent slip over the "
                                     "step's mean D and M)")
                  : ", energy-momentum contact force (discrete gradient of the weighted gaps)";
    else if (energy_momentum_)
      text += ", contact force of the end of the step (energy-momentum contact needs one kind "
              "of faces in 2D, line2 or line3)";
    if (s.friction) {
      std::snprintf(line, sizeof line, ", %s friction %s = %.4g, c_t = %.4g",
                    s.law.model == io::FrictionModel::coulomb ? "Coulomb" : "Tresca",
                    s.law.model == io::FrictionModel::coulomb ? "mu" : "bound",
                    s.law.model == io::FrictionModel::coulomb ? s.law.mu : s.law.bound, s.law.c_t);
      text += line;
    }
    out.push_back(std::move(text));
  }
  return out;
}

std::vector<std::string> ContactConstraint::held_whole() const {
  std::vector<std::string> out;
  for (const auto& s : sides_) {
    const auto n_slave = std::to_string(s.itf.slave().n_facets());
    std::string text = "interface " + s.itf.name() + ": held whole on every rank: ";
    const std::string arrays =
        std::string("the nodal arrays per slave node (D, g~, multipliers, active set") +
        (s.friction ? ", friction history" : "") + ")";
    // Saddle point: the multiplier rows of the nodes it holds (numbered by their owners).
    const std::string rows = saddle_point_ ? ", multiplier rows" : "";
    const std::string read =
        std::string("; read per rank: the displacement of the nodes of its slave elements, of "
                    "their neighbours and of its master facets and ghosts (energy-momentum "
                    "contact: at the start of the step too), the normals of its slave nodes; "
                    "per rank: the output rows of the slave nodes around its slave elements, the "
                    "checkpointed state of the slave nodes it owns");
    char skin[64];
    if (s.search) std::snprintf(skin, sizeof skin, "%.3g", s.search->skin());
    const std::string reused =
        s.search ? std::string(", the ghosts reused while no node moved half the skin ") + skin
                 : std::string();
    if (s.itf.self_contact() && s.slave_in_part)
      text = "interface " + s.itf.name() +
             ": held in part: the surface (the facets of its own and ghost cells" +
             (s.distribution ? " at set-up; then those of its own cells and the rings of the "
                               "nodes it owns and of the nodes of the facets it evaluates, taken "
                               "anew at each distribution, those beyond its mesh sent as facets"
                             : "") +
             ": " + n_slave + " of " + std::to_string(s.slave_facets) +
             " surface facets, the others it pairs read as ghosts), the facing pairs of each "
             "search by facet id (gathered for the roles, O(pairs)), the nodal arrays per held "
             "surface node (D, g~, multipliers, active set" +
             (s.friction ? ", friction history" : "") + rows + "; the owners' values published)" +
             read +
             "; distributed: the search (own surface facets against the surface facets "
             "ghosted by bounding boxes" +
             reused + ") and the mortar integration of the own slave elements";
    else if (s.itf.self_contact())
      text += "the surface (" + n_slave +
              " facets, nodes, positions), the facing pairs of each search (gathered "
              "for the roles and the slave patch), " +
              arrays + read +
              "; distributed: the search (own surface facets against the surface facets "
              "ghosted by bounding boxes" +
              reused +
              ") and the mortar integration of the own slave elements (against the "
              "ghosted surface facets)";
    else if (s.search && s.slave_in_part)
      text = "interface " + s.itf.name() +
             ": held in part: both sides (the facets of its own and ghost cells" +
             (s.slave_region ? " at set-up; then the rings of the slave nodes it owns and of "
                               "the nodes of the slave facets it evaluates, taken anew at each "
                               "distribution, those beyond its mesh sent as facets"
                             : "") +
             ": " + n_slave + " of " + std::to_string(s.slave_facets) + " slave and " +
             std::to_string(s.itf.n_master_facets()) + " of " + std::to_string(s.master_facets) +
             " master facets, the other master facets read as ghosts), the nodal arrays per "
             "held slave node (D, g~, multipliers, active set" +
             (s.friction ? ", friction history" : "") + rows + "; the owners' values published)" +
             read +
             "; distributed: the search (own slave elements against the master facets "
             "ghosted by bounding boxes" +
             reused + ") and the mortar integration of the own slave elements";
    else if (s.search && s.master_in_part)
      text += "the slave side (" + n_slave +
              " facets, nodes, positions; held in part at np > 1), " + arrays + read +
              "; in part: the master side (the facets of its own and ghost cells, " +
              std::to_string(s.itf.n_master_facets()) + " of " + std::to_string(s.master_facets) +
              ", the others read as ghosts)" +
              "; distributed: the search (own slave elements against the master facets "
              "ghosted by bounding boxes" +
              reused +
              ") and the mortar integration of the own slave "
              "elements (against the ghosted master facets)";
    else if (s.search)
      text += "both sides (" + n_slave + " slave and " + std::to_string(s.master_facets) +
              " master facets, their nodes and positions; held in part at np > 1), " + arrays +
              read +
              "; distributed: the search (own slave elements against the master facets "
              "ghosted by bounding boxes" +
              reused +
              ") and the mortar integration of the own slave "
              "elements (against the ghosted master facets)";
    else if (s.slave_in_part)
      text = "interface " + s.itf.name() + ": held in part: the slave side (the facets of its " +
             "own and ghost cells" +
             (s.slave_region ? " at set-up; then the rings of the slave nodes it owns and of "
                               "the nodes of the slave facets it evaluates, taken anew at each "
                               "distribution, those beyond its mesh sent as facets"
                             : "") +
             ": " + n_slave + " of " + std::to_string(s.slave_facets) +
             " slave facets), the nodal arrays per held slave node (D, g~, multipliers, active "
             "set" +
             (s.friction ? ", friction history" : "") + rows + "; the owners' values published)" +
             "; on every rank: " + s.itf.obstacle().name() + read +
             "; distributed: the search and the integration of the own slave elements";
    else
      text += "the slave side (" + n_slave + " facets, nodes, positions; held in part at " +
              "np > 1), " + s.itf.obstacle().name() + ", " + arrays + read +
              "; distributed: the search and the integration of the slave elements";
    out.push_back(std::move(text));
  }
  return out;
}

std::vector<ContactReport> ContactConstraint::reports(const la::Vector& u) {
  // balance() may have given this rank other slave elements since the last evaluation: the
  // scatter then brings the nodes around the new ones (the rows below read them).
  refresh_displacement(u);
  const int dim = disc_.dim();
  const auto& comm = disc_.comm();
  // Each slave node's row is computed by one rank (against a rigid obstacle held in part, whose
  // normals are the obstacle's at the node, s.compact: the node's owner): the rank that
  // evaluates the first slave facet around it (the lowest index; each facet is evaluated by one
  // rank), so the rows follow the distribution of the slave elements, not the bulk partition (which
  // may give one rank every slave node). That rank reads the node's displacement and those of the
  // facets around it (its normal) through its own scatter (nodes_read() holds them), and the node's
  // multipliers, gap and status are published to every rank: no scatter of the whole
  // interface, no exchange. The owners compute the multiplier vectors of their nodes (VTU).
  SEAM_ASSERT(gather_made_);
  std::vector<double> u_mesh(u_mesh_.size(), 0.0), values;
  gather_(u, values);
  for (std::size_t k = 0; k < gathered_.size(); ++k)
    for (int c = 0; c < dim; ++c)
      u_mesh[static_cast<std::size_t>(gathered_[k]) * dim + c] = values[k * dim + c];
  std::vector<ContactReport> out;
  for (const auto& s : sides_) {
    ContactReport rep;
    rep.name = s.itf.name();
    rep.slave_nodes = s.itf.slave().mesh_nodes;
    const auto n = rep.slave_nodes.size();
    rep.owned.assign(n, 0);
    // The first facet of every slave node: a pass over the side every rank holds (local work).
    std::vector<local_index> first(n, -1), mine, rows;
    const auto set = s.itf.slave().facet_set();
    for (local_index f = 0; f < set.n_facets(); ++f)
      for (const auto j : set.facet_nodes(f))
        if (first[static_cast<std::size_t>(j)] < 0) first[static_cast<std::size_t>(j)] = f;
    const auto own = s.itf.owned_facets();
    for (std::size_t j = 0; j < n; ++j) {
      rep.owned[j] = s.node_owners[j] == comm.rank();
      const bool row =
          s.compact ? rep.owned[j] != 0 : std::binary_search(own.begin(), own.end(), first[j]);
      rep.local_owned_nodes += rep.owned[j];
      if (rep.owned[j] || row) mine.push_back(static_cast<local_index>(j));
      if (row) rows.push_back(static_cast<local_index>(j));
    }
    const auto normal = s.itf.normals_at(u_mesh, mine);
    // The multiplier vector: lambda_n n without friction, the Cartesian one with it.
    rep.lambda.assign(n * dim, 0.0);
    rep.status.assign(n, 0);
    // Totals over this rank's rows (each node in one rank's rows), then summed: normal force,
    // tangential force (dim).
    double totals[4] = {0.0, 0.0, 0.0, 0.0};
    for (std::size_t j = 0; j < n; ++j)
      // Without friction every active node slides freely: status slip.
      rep.status[j] = s.friction ? s.status[j] : (s.active[j] ? 2 : 0);
    const auto lambda_of = [&](std::size_t j, double* lj) {
      for (int c = 0; c < dim; ++c)
        lj[c] = s.friction ? s.lambda[j * dim + c] : s.lambda[j] * normal[j * dim + c];
    };
    for (std::size_t j = 0; j < n; ++j)
      if (rep.owned[j]) lambda_of(j, &rep.lambda[j * dim]);
    for (const auto jl : rows) {
      const auto j = static_cast<std::size_t>(jl);
      const double* nj = &normal[j * dim];
      double lj[3] = {0.0, 0.0, 0.0};
      lambda_of(j, lj);
      InterfaceNodeRow row;
      const auto node = rep.slave_nodes[j];
      row.node = node_id(node);
      row.order = row.node; // the side's order (ids increase along it), on every part
      for (int c = 0; c < dim; ++c) {
        row.normal += lj[c] * nj[c];
        row.x[c] = reference(node, c);
        row.u[c] = u_mesh[static_cast<std::size_t>(node) * dim + c];
      }
      double lt2 = 0.0;
      for (int c = 0; c < dim; ++c) {
        const double lt = lj[c] - row.normal * nj[c];
        lt2 += lt * lt;
        totals[1 + c] += s.D[j] * lt;
      }
      totals[0] += s.D[j] * row.normal;
      row.tangential = std::sqrt(lt2);
      if (s.D[j] > 0.0) row.gap = s.gap[j] / s.D[j];
      row.status = rep.status[j];
      rep.rows.push_back(row);
    }
    comm.sum_in_place(totals);
    rep.normal_force = totals[0];
    rep.tangential_force =
        std::sqrt(totals[1] * totals[1] + totals[2] * totals[2] + totals[3] * totals[3]);
    rep.weighted_gap = s.gap;
    rep.active = s.active;
    // Each node counted by its owner.
    double counts[3] = {0.0, 0.0, 0.0}; // area, active nodes, slip nodes
    for (std::size_t j = 0; j < n; ++j) {
      if (!rep.owned[j]) continue;
      if (s.active[j]) {
        counts[0] += s.D[j];
        ++counts[1];
      }
      counts[2] += rep.status[j] == 2;
    }
    comm.sum_in_place(counts);
    rep.contact_area = counts[0];
    rep.active_nodes = static_cast<int>(counts[1]);
    rep.slip_nodes = static_cast<int>(counts[2]);
    // Energy-momentum contact against a rigid plane: its reaction is the resultant of the
    // discrete-gradient force along the normal (the nodal weights of the midpoint gradient and
    // the correction, not D_j of the end of the step); the momentum balance needs that one.
    if (s.discrete_gradient && s.itf.rigid() &&
        s.itf.obstacle().shape == contact::Obstacle::Shape::plane) {
      const auto& normal = s.itf.obstacle().direction;
      const auto lambda_n = normal_multipliers(s); // with friction the normal parts
      double f = 0.0;
      for (const auto& e : s.em_gradient)
        f -= lambda_n[e.j] * e.value * normal[static_cast<std::size_t>(e.dof % dim)];
      rep.normal_force = disc_.comm().sum(f);
    }
    // The frictional work including this step (save() adds it once the step is accepted).
    rep.frictional_dissipation = s.friction ? s.dissipation + dissipation_increment(s) : 0.0;
    rep.slave_elements = s.slave_in_part ? s.slave_facets : s.itf.slave().n_facets();
    rep.master_elements = s.itf.rigid() ? s.itf.n_master_facets() : s.master_facets;
    rep.candidate_pairs = static_cast<int>(s.share.candidates);
    rep.work_min = s.balance.time.min;
    rep.work_mean = s.balance.time.mean;
    rep.work_max = s.balance.time.max;
    rep.redistributed = s.redistributed;
    rep.local_slave_elements = s.share.slave_elements;
    rep.local_master_ghosts = s.share.master_ghosts;
    rep.local_master_received = s.share.master_received;
    rep.local_surface_received = s.share.surface_received;
    rep.local_self_pairs_received = s.share.self_pairs_received;
    rep.local_self_pairs_returned = s.share.self_pairs_returned;
    rep.local_self_groups = s.share.self_groups;
    rep.self_label_rounds = s.share.label_rounds;
    rep.surface_facets = !s.itf.self_contact() ? 0
                         : s.slave_in_part     ? s.slave_facets
                                               : static_cast<int>(s.itf.slave().n_facets());
    rep.local_ghost_exchanges = s.share.ghost_exchanges;
    rep.local_searches = s.share.searches;
    if (s.search && s.search->self()) {
      rep.role_changes_within_step = s.search->role_changes().within;
      rep.role_changes_between_steps = s.search->role_changes().between;
      rep.role_changes_persisting = s.search->role_changes().persisting;
    }
    rep.local_pairs = s.part.n_pairs;
    rep.local_integration_cells = s.part.n_cells;
    rep.local_contact_nodes = s.nodal.decided;
    rep.local_nodal_records = s.nodal.sent;
    if (out.empty()) {
      rep.local_nodes_gathered = static_cast<std::int64_t>(gathered_.size());
      rep.interface_nodes = interface_total_;
    }
    rep.local_master_facets_read = s.itf.rigid() ? 0 : s.itf.n_master_facets_read();
    rep.local_normals = s.itf.n_normals_computed();
    // The sides' facets held, and those whose nodes the scatter all brought.
    const auto all_read = [&](const meshtying::InterfaceSide& side) {
      std::int64_t n = 0;
      for (local_index f = 0; f < side.n_facets(); ++f) {
        bool read = true;
        for (auto k = side.offsets[f]; read && k < side.offsets[f + 1]; ++k)
          read = std::binary_search(
              gathered_.begin(), gathered_.end(),
              side.mesh_nodes[static_cast<std::size_t>(side.nodes[static_cast<std::size_t>(k)])]);
        n += read;
      }
      return n;
    };
    const bool two_bodies = !s.itf.rigid() && !s.itf.self_contact();
    rep.local_side_facets_held =
        s.itf.slave().n_facets() + (two_bodies ? s.itf.n_master_facets() : 0);
    rep.local_slave_facets_held = s.itf.slave().n_facets();
    rep.local_em_entries_sent = s.em_entries_sent;
    rep.local_em_entries_received = s.em_entries_received;
    rep.local_side_facets_read =
        all_read(s.itf.slave()) + (two_bodies ? all_read(s.itf.master()) : 0);
    out.push_back(std::move(rep));
  }
  return out;
}

int ContactConstraint::n_slip() const {
  // Each node counted by its owner.
  const int rank = disc_.comm().rank();
  double n = 0.0;
  for (const auto& s : sides_)
    for (std::size_t j = 0; j < s.active.size(); ++j)
      if (s.node_owners[j] == rank) n += s.friction ? s.status[j] == 2 : s.active[j] != 0;
  return static_cast<int>(disc_.comm().sum(n));
}

} // namespace seam::problem
