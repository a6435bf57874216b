// Mesh tying on a distributed mesh (issue 12, item 3; docs/parallel.md, "Mesh tying
// distributed"): the slave facets of each interface are cut by a weighted RCB over all ranks
// (`parallel.interface_distribution: independent`, the default) or stay on the owners of their
// cells (`bulk`); every rank integrates its slave facets against the master facets ghosted to it
// by bounding boxes; the rows of D and M are summed on the owners of their slave nodes, and
// every rank then receives the complete rows of the slave nodes it holds.
#include "seam/common/error.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/meshtying/tied_interface_detail.hpp"
#include "seam/parallel/distributed_search.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/parallel/ghosting.hpp"
#include "seam/parallel/load_balance.hpp"
#include "seam/search/interface_search.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace seam::meshtying {

bool distributed_tying(const io::Interface& itf) {
  return itf.type == io::InterfaceType::mesh_tying || itf.type == io::InterfaceType::fsi;
}

namespace {

/// One entry of a row of D (kind 0) or of M (kind 1) in global node numbers; x holds the
/// coordinates of an M entry's master node.
struct RowEntry {
  std::int64_t row = 0;
  std::int64_t col = 0;
  double value = 0.0;
  double x[3] = {0.0, 0.0, 0.0};
  std::int32_t kind = 0;
  std::int32_t pad = 0;
};

bool entry_less(const RowEntry& a, const RowEntry& b) {
  if (a.row != b.row) return a.row < b.row;
  if (a.kind != b.kind) return a.kind < b.kind;
  return a.col < b.col;
}

fem::CellType facet_type_of(int dim, std::size_t n_nodes) {
  using fem::CellType;
  if (dim == 2) return n_nodes == 3 ? CellType::line3 : CellType::line2;
  switch (n_nodes) {
  case 3:
    return CellType::tri3;
  case 4:
    return CellType::quad4;
  case 6:
    return CellType::tri6;
  case 8:
    return CellType::quad8;
  default:
    return CellType::quad9;
  }
}

/// The facets f of `side` (extracted from `region`) with take[f], as a surface part in global
/// node numbers; facet ids from the cell ids of the mesh as read.
parallel::SurfacePart side_part(const InterfaceSide& side, const mesh::DistributedMesh& part,
                                const mesh::Region& region, const std::vector<char>& take) {
  std::vector<local_index> facets;
  for (local_index f = 0; f < side.n_facets(); ++f)
    if (take[static_cast<std::size_t>(f)]) facets.push_back(f);
  std::vector<std::int64_t> node_ids(side.mesh_nodes.size());
  for (std::size_t n = 0; n < node_ids.size(); ++n)
    node_ids[n] = part.node_index[static_cast<std::size_t>(side.mesh_nodes[n])];
  std::vector<local_index> scratch;
  parallel::SurfacePart p;
  const auto facet_ids = facet_gids(
      region, [&](std::int32_t c) { return part.cell_gid[static_cast<std::size_t>(c)]; });
  meshtying::side_part(side, facet_ids, node_ids, facets, scratch, p);
  return p;
}

/// Facets of a held side on the cells this rank owns.
std::vector<char> owned_facets(const mesh::DistributedMesh& part, const mesh::Region& region,
                               int rank) {
  std::vector<char> owned(static_cast<std::size_t>(region.n_facets()), 0);
  for (std::int32_t f = 0; f < region.n_facets(); ++f)
    owned[static_cast<std::size_t>(f)] =
        part.cell_owner[static_cast<std::size_t>(region.facet_cell[f])] == rank;
  return owned;
}

/// Records grouped by destination rank -> (records in rank order, offsets).
template <class T>
std::vector<T> by_rank(int size, const std::vector<std::pair<int, T>>& items,
                       std::vector<std::int64_t>& offsets) {
  offsets.assign(static_cast<std::size_t>(size) + 1, 0);
  for (const auto& [r, x] : items) ++offsets[static_cast<std::size_t>(r) + 1];
  for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
  std::vector<T> out(items.size());
  std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
  for (const auto& [r, x] : items) out[static_cast<std::size_t>(next[r]++)] = x;
  return out;
}

/// A surface part as an interface side over its own node table (no mesh nodes), the facet
/// types from their node counts.
InterfaceSide side_of(parallel::SurfacePart&& p) {
  InterfaceSide side;
  side.dim = p.dim;
  side.coordinates = std::move(p.coords);
  side.offsets = std::move(p.offsets);
  side.nodes = std::move(p.connectivity);
  for (std::size_t f = 0; f + 1 < side.offsets.size(); ++f)
    side.types.push_back(
        facet_type_of(side.dim, static_cast<std::size_t>(side.offsets[f + 1] - side.offsets[f])));
  return side;
}

/// The slave facets a rank integrates with the independent distribution, and what
/// integrating them needs.
struct SlaveShare {
  parallel::SurfacePart assigned; ///< the facets this rank integrates (sorted by id)
  parallel::SurfacePart facets;   ///< those and the facets around their nodes (unique ids)
  std::vector<char> integrate;    ///< per facet of `facets`: one of `assigned`
  std::vector<char> bound;        ///< per node of `facets` (empty: none bound)
};

/// Collective. Cuts the slave facets of the cells the ranks own (`owned`: this rank's, facets
/// of the held side `held` as `held_part`, facet for facet) by weighted RCB over all ranks (unit
/// weights: every facet of a tied interface is integrated) and sends each facet to its rank
/// with the facets around its nodes, which the averaged nodal normals and the modified basis of
/// its nodes read, and the bound flags `bound` (per held node) of its nodes. The owner of a
/// facet's cell holds every slave facet around the facet's nodes (the ghost layer) and has
/// their flags complete, so what it sends is what the whole side gives.
SlaveShare share_slave_facets(MPI_Comm comm, const InterfaceSide& held,
                              const parallel::SurfacePart& held_part,
                              const parallel::SurfacePart& owned_part,
                              std::span<const local_index> owned, const std::vector<char>& bound) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int dim = held.dim;
  SlaveShare share;
  std::vector<double> centroids;
  parallel::facet_centroids(owned_part, centroids);
  const std::vector<double> work(owned.size(), 1.0);
  std::vector<int> parts(owned.size(), 0);
  parallel::ProximityPartition(dim).partition(comm, centroids, work, owned_part.facet_ids, parts);
  share.assigned = parallel::migrate(comm, owned_part, parts);

  // Each owned facet and the held facets around its nodes, to its rank.
  const auto n_nodes = held.mesh_nodes.size();
  std::vector<std::int64_t> around_offsets(n_nodes + 1, 0);
  for (auto n : held.nodes) ++around_offsets[static_cast<std::size_t>(n) + 1];
  for (std::size_t n = 0; n < n_nodes; ++n) around_offsets[n + 1] += around_offsets[n];
  std::vector<local_index> around(held.nodes.size());
  {
    std::vector<std::int64_t> next(around_offsets.begin(), around_offsets.end() - 1);
    for (local_index f = 0; f < held.n_facets(); ++f)
      for (auto k = held.offsets[static_cast<std::size_t>(f)];
           k < held.offsets[static_cast<std::size_t>(f) + 1]; ++k)
        around[static_cast<std::size_t>(next[static_cast<std::size_t>(held.nodes[k])]++)] = f;
  }
  std::vector<std::pair<int, local_index>> send;
  std::vector<std::pair<int, std::int64_t>> bound_ids;
  for (std::size_t i = 0; i < owned.size(); ++i) {
    const auto f = static_cast<std::size_t>(owned[i]);
    for (auto k = held.offsets[f]; k < held.offsets[f + 1]; ++k) {
      const auto n = static_cast<std::size_t>(held.nodes[static_cast<std::size_t>(k)]);
      for (auto a = around_offsets[n]; a < around_offsets[n + 1]; ++a)
        send.emplace_back(parts[i], around[static_cast<std::size_t>(a)]);
      if (!bound.empty() && bound[n])
        bound_ids.emplace_back(parts[i], held_part.node_ids[static_cast<std::size_t>(
                                             held_part.connectivity[static_cast<std::size_t>(k)])]);
    }
  }
  std::sort(send.begin(), send.end());
  send.erase(std::unique(send.begin(), send.end()), send.end());
  std::vector<std::int64_t> offsets, recv_offsets;
  const auto facets = by_rank(size, send, offsets);
  auto received = parallel::send_facets(comm, held_part, offsets, facets);
  // A facet around the nodes of facets from several ranks comes from each of them: kept once.
  auto& out = share.facets;
  out.dim = dim;
  out.node_ids = std::move(received.node_ids);
  out.coords = std::move(received.coords);
  for (local_index f = 0; f < received.n_facets(); ++f) {
    const auto id = received.facet_ids[static_cast<std::size_t>(f)];
    if (!out.facet_ids.empty() && out.facet_ids.back() == id) continue;
    out.facet_ids.push_back(id);
    for (auto k = received.offsets[static_cast<std::size_t>(f)];
         k < received.offsets[static_cast<std::size_t>(f) + 1]; ++k)
      out.connectivity.push_back(received.connectivity[static_cast<std::size_t>(k)]);
    out.offsets.push_back(static_cast<local_index>(out.connectivity.size()));
  }
  share.integrate.assign(out.facet_ids.size(), 0);
  for (const auto id : share.assigned.facet_ids) {
    const auto it = std::lower_bound(out.facet_ids.begin(), out.facet_ids.end(), id);
    SEAM_ASSERT(it != out.facet_ids.end() && *it == id);
    share.integrate[static_cast<std::size_t>(it - out.facet_ids.begin())] = 1;
  }
  // The bound flags of the nodes of the facets sent (a node of several facets more than once).
  std::sort(bound_ids.begin(), bound_ids.end());
  bound_ids.erase(std::unique(bound_ids.begin(), bound_ids.end()), bound_ids.end());
  const auto bound_send = by_rank(size, bound_ids, offsets);
  const auto bound_recv =
      parallel::alltoallv<std::int64_t>(comm, bound_send, offsets, recv_offsets);
  if (!bound_recv.empty()) {
    share.bound.assign(out.node_ids.size(), 0);
    for (const auto id : bound_recv) {
      const auto it = std::lower_bound(out.node_ids.begin(), out.node_ids.end(), id);
      SEAM_ASSERT(it != out.node_ids.end() && *it == id);
      share.bound[static_cast<std::size_t>(it - out.node_ids.begin())] = 1;
    }
  }
  return share;
}

/// The entry of a slave x master triplet `e` (slave row into `rows`, column into
/// `columns`) in global node numbers, with the master node's coordinates from `coordinates`.
RowEntry master_entry(int dim, std::span<const std::int64_t> rows,
                      std::span<const std::int64_t> columns, const mortar::Triplet& e,
                      const std::vector<double>& coordinates) {
  RowEntry r;
  r.row = rows[static_cast<std::size_t>(e.row)];
  r.col = columns[static_cast<std::size_t>(e.col)];
  r.value = e.value;
  r.kind = 1;
  for (int c = 0; c < dim; ++c) r.x[c] = coordinates[static_cast<std::size_t>(e.col) * dim + c];
  return r;
}

/// The entries of the rows `ids` (with their owners `owners`) from the owners' `rows` (this
/// rank's owned rows, sorted by row): one request and one reply exchange.
std::vector<RowEntry> rows_from_owners(MPI_Comm comm, std::span<const std::int64_t> ids,
                                       std::span<const int> owners,
                                       const std::vector<RowEntry>& rows) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  std::vector<std::pair<int, std::int64_t>> requests;
  for (std::size_t i = 0; i < ids.size(); ++i) requests.emplace_back(owners[i], ids[i]);
  std::vector<std::int64_t> offsets, recv_offsets;
  const auto send = by_rank(size, requests, offsets);
  const auto asked = parallel::alltoallv<std::int64_t>(comm, send, offsets, recv_offsets);
  std::vector<std::pair<int, RowEntry>> replies;
  for (int r = 0; r < size; ++r)
    for (auto k = recv_offsets[r]; k < recv_offsets[r + 1]; ++k) {
      const auto row = asked[static_cast<std::size_t>(k)];
      const auto first =
          std::lower_bound(rows.begin(), rows.end(), row,
                           [](const RowEntry& e, std::int64_t key) { return e.row < key; });
      for (auto it = first; it != rows.end() && it->row == row; ++it) replies.emplace_back(r, *it);
    }
  const auto reply = by_rank(size, replies, offsets);
  return parallel::alltoallv<RowEntry>(comm, reply, offsets, recv_offsets);
}

/// Mesh initialization with a non-diagonal D (standard multipliers): D_SS X_S = M X_M - D_SB X_B
/// over the whole side as one distributed linear system, its rows the slave nodes with a row of
/// D on their owners (`rows`: the complete rows of the nodes this rank owns, sorted), solved by
/// a parallel LU (MUMPS). Returns X_S - X of the nodes this rank owns (dim values per held
/// slave node, zero elsewhere and for nodes not moved). Bound columns (no row of their own)
/// keep their place; their coordinates are those held here (a column of an owned row is a
/// neighbour on a facet around an owned node, held by the ghost layer).
std::vector<double>
standard_initialization(MPI_Comm comm, const TiedInterface& t, const std::vector<RowEntry>& rows,
                        const std::unordered_map<std::int64_t, local_index>& slave_local,
                        const std::vector<int>& owners) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const int dim = t.slave.dim;
  // This rank's unknowns: its owned nodes with a row of D, in the order of their numbers.
  std::vector<std::int64_t> mine;
  for (const auto& e : rows)
    if (e.kind == 0 && (mine.empty() || mine.back() != e.row)) mine.push_back(e.row);
  PetscInt n_local = static_cast<PetscInt>(mine.size()), first = 0;
  MPI_Exscan(&n_local, &first, 1, MPIU_INT, MPI_SUM, comm);
  if (rank == 0) first = 0;
  const auto number_of_mine = [&](std::int64_t node) -> PetscInt {
    const auto it = std::lower_bound(mine.begin(), mine.end(), node);
    return it != mine.end() && *it == node ? first + static_cast<PetscInt>(it - mine.begin()) : -1;
  };
  // The numbers of the columns of D from their owners (-1: a bound node without a row).
  std::vector<std::int64_t> columns;
  for (const auto& e : rows)
    if (e.kind == 0) columns.push_back(e.col);
  std::sort(columns.begin(), columns.end());
  columns.erase(std::unique(columns.begin(), columns.end()), columns.end());
  std::vector<std::pair<int, std::int64_t>> requests;
  for (auto c : columns)
    requests.emplace_back(owners[static_cast<std::size_t>(slave_local.at(c))], c);
  std::vector<std::int64_t> offsets, recv_offsets;
  const auto send = by_rank(size, requests, offsets);
  const auto asked = parallel::alltoallv<std::int64_t>(comm, send, offsets, recv_offsets);
  std::vector<std::int64_t> answers(asked.size());
  for (std::size_t k = 0; k < asked.size(); ++k) answers[k] = number_of_mine(asked[k]);
  const auto replies = parallel::alltoallv<std::int64_t>(comm, answers, recv_offsets, offsets);
  std::unordered_map<std::int64_t, PetscInt> number;
  for (std::size_t k = 0; k < send.size(); ++k)
    number.emplace(send[k], static_cast<PetscInt>(replies[k]));

  // D_SS and the right-hand sides M X_M - D_SB X_B, one column per coordinate.
  std::vector<PetscInt> d_nnz(static_cast<std::size_t>(n_local), 0),
      o_nnz(static_cast<std::size_t>(n_local), 0);
  std::vector<double> rhs(static_cast<std::size_t>(n_local) * dim, 0.0);
  for (const auto& e : rows) {
    const auto i = static_cast<std::size_t>(number_of_mine(e.row) - first);
    if (e.kind == 1) {
      for (int c = 0; c < dim; ++c) rhs[i * dim + c] += e.value * e.x[c];
      continue;
    }
    const PetscInt col = number.at(e.col);
    if (col < 0) {
      const auto b = static_cast<std::size_t>(slave_local.at(e.col));
      for (int c = 0; c < dim; ++c) rhs[i * dim + c] -= e.value * t.slave.coordinates[b * dim + c];
      continue;
    }
    ++(col >= first && col < first + n_local ? d_nnz[i] : o_nnz[i]);
  }
  Mat D = nullptr;
  la::check(MatCreateAIJ(comm, n_local, n_local, PETSC_DETERMINE, PETSC_DETERMINE, 0, d_nnz.data(),
                         0, o_nnz.data(), &D),
            "MatCreateAIJ");
  for (const auto& e : rows) {
    if (e.kind != 0 || number.at(e.col) < 0) continue;
    const PetscInt row = number_of_mine(e.row), col = number.at(e.col);
    la::check(MatSetValue(D, row, col, e.value, ADD_VALUES), "MatSetValue");
  }
  la::check(MatAssemblyBegin(D, MAT_FINAL_ASSEMBLY), "MatAssemblyBegin");
  la::check(MatAssemblyEnd(D, MAT_FINAL_ASSEMBLY), "MatAssemblyEnd");
  KSP ksp = nullptr;
  PC pc = nullptr;
  la::check(KSPCreate(comm, &ksp), "KSPCreate");
  la::check(KSPSetOperators(ksp, D, D), "KSPSetOperators");
  la::check(KSPSetType(ksp, KSPPREONLY), "KSPSetType");
  la::check(KSPGetPC(ksp, &pc), "KSPGetPC");
  la::check(PCSetType(pc, PCLU), "PCSetType");
  la::check(PCFactorSetMatSolverType(pc, MATSOLVERMUMPS), "PCFactorSetMatSolverType");
  la::check(KSPSetOptionsPrefix(ksp, "mesh_initialization_"), "KSPSetOptionsPrefix");
  la::check(KSPSetFromOptions(ksp), "KSPSetFromOptions");
  PetscErrorCode setup = KSPSetUp(ksp);
  KSPConvergedReason reason = KSP_CONVERGED_ITERATING;
  std::vector<double> delta(t.slave.mesh_nodes.size() * dim, 0.0);
  Vec b = nullptr, x = nullptr;
  la::check(MatCreateVecs(D, &x, &b), "MatCreateVecs");
  bool singular = setup != 0;
  for (int c = 0; c < dim && !singular; ++c) {
    PetscScalar* bv = nullptr;
    la::check(VecGetArray(b, &bv), "VecGetArray");
    for (PetscInt i = 0; i < n_local; ++i) bv[i] = rhs[static_cast<std::size_t>(i) * dim + c];
    la::check(VecRestoreArray(b, &bv), "VecRestoreArray");
    singular = KSPSolve(ksp, b, x) != 0;
    if (!singular) {
      la::check(KSPGetConvergedReason(ksp, &reason), "KSPGetConvergedReason");
      singular = reason < 0;
    }
    if (singular) break;
    const PetscScalar* xv = nullptr;
    la::check(VecGetArrayRead(x, &xv), "VecGetArrayRead");
    for (PetscInt i = 0; i < n_local; ++i) {
      const auto j = static_cast<std::size_t>(slave_local.at(mine[static_cast<std::size_t>(i)]));
      delta[j * dim + c] = xv[i] - t.slave.coordinates[j * dim + c];
    }
    la::check(VecRestoreArrayRead(x, &xv), "VecRestoreArrayRead");
  }
  VecDestroy(&b);
  VecDestroy(&x);
  KSPDestroy(&ksp);
  MatDestroy(&D);
  int bad = singular ? 1 : 0;
  MPI_Allreduce(MPI_IN_PLACE, &bad, 1, MPI_INT, MPI_MAX, comm);
  SEAM_CHECK(bad == 0, InputError, "interface '", t.name,
             "': mesh initialization: the mortar matrix D is singular");
  return delta;
}

/// fsi: P = D^-1 M (with a modified quadratic basis T D^-1 M) of the slave nodes this rank
/// owns, whose rows are complete here, with D_jj, sent to every rank that holds the node (by
/// node id): t.projection over the held slave nodes, the master nodes its columns reach added
/// to t.master and t.master_index.
void publish_projection(MPI_Comm comm, TiedInterface& t, const std::vector<int>& owners) {
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  const int dim = t.slave.dim;
  const auto n_slave = t.slave.mesh_nodes.size();
  const auto P = projection(t.operators, static_cast<local_index>(n_slave));
  std::vector<RowEntry> rows;
  for (const auto& e : t.operators.D)
    if (owners[static_cast<std::size_t>(e.row)] == rank) {
      RowEntry r;
      r.row = r.col = t.slave_index[static_cast<std::size_t>(e.row)];
      r.value = e.value;
      rows.push_back(r);
    }
  for (const auto& e : P)
    if (owners[static_cast<std::size_t>(e.row)] == rank)
      rows.push_back(master_entry(dim, t.slave_index, t.master_index, e, t.master.coordinates));
  std::sort(rows.begin(), rows.end(), entry_less);
  const auto complete = rows_from_owners(comm, t.slave_index, owners, rows);
  std::unordered_map<std::int64_t, local_index> slave_local, master_local;
  for (std::size_t i = 0; i < n_slave; ++i)
    slave_local.emplace(t.slave_index[i], static_cast<local_index>(i));
  for (std::size_t i = 0; i < t.master_index.size(); ++i)
    master_local.emplace(t.master_index[i], static_cast<local_index>(i));
  t.projection.clear();
  for (const auto& e : complete) {
    if (e.kind == 0) continue;
    const auto [it, added] =
        master_local.emplace(e.col, static_cast<local_index>(t.master_index.size()));
    if (added) {
      t.master_index.push_back(e.col);
      for (int c = 0; c < dim; ++c) t.master.coordinates.push_back(e.x[c]);
    }
    t.projection.push_back({slave_local.at(e.row), it->second, e.value});
  }
}

struct SetupResult {
  TiedInterface t;
  std::vector<std::int32_t> owned_master_nodes; ///< master side nodes this rank owns
};

SetupResult setup_distributed(const io::Config& config, const io::Interface& itf,
                              mesh::DistributedMesh& part, MPI_Comm comm, PhaseTimers& timers,
                              io::InterfaceType type) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  auto& mesh = part.mesh;
  const int dim = mesh.dim;
  SetupResult result;
  TiedInterface& t = result.t;
  t.name = itf.name;
  t.multiplier = itf.multiplier;
  t.strategy = itf.strategy;
  t.distributed = true;
  // The sides as held: facets on owned and ghost cells. Every slave facet around a node of an
  // owned cell is held (the ghost layer holds every cell around such a node), so the averaged
  // nodal normals and the nodal transformation of those nodes are complete.
  const auto& slave_region = side_region(mesh, itf.slave);
  const auto& master_region = side_region(mesh, *itf.master);
  t.slave = extract_side(mesh, slave_region);
  const auto master_held = extract_side(mesh, master_region);
  const auto slave_owned = owned_facets(part, slave_region, rank);
  const auto master_owned = owned_facets(part, master_region, rank);

  // Shared nodes, each counted by its owner (who holds every facet around it).
  const auto shared = shared_nodes(
      comm, mesh, t.slave.mesh_nodes, master_held.mesh_nodes,
      [&](std::int32_t n) { return part.node_owner[static_cast<std::size_t>(n)] == rank; },
      [&](std::int32_t n) { return part.node_gid[static_cast<std::size_t>(n)]; });
  if (shared.count > 0) detail::fail_shared_nodes(itf, shared, dim);
  for (auto n : master_held.mesh_nodes)
    if (part.node_owner[static_cast<std::size_t>(n)] == rank)
      result.owned_master_nodes.push_back(n);

  // Global node numbers of the held slave nodes.
  const auto n_slave = t.slave.mesh_nodes.size();
  t.slave_index.resize(n_slave);
  std::unordered_map<std::int64_t, local_index> slave_local;
  for (std::size_t i = 0; i < n_slave; ++i) {
    t.slave_index[i] = part.node_index[static_cast<std::size_t>(t.slave.mesh_nodes[i])];
    slave_local.emplace(t.slave_index[i], static_cast<local_index>(i));
  }
  const auto owner = [&](std::size_t i) {
    return part.node_owner[static_cast<std::size_t>(t.slave.mesh_nodes[i])];
  };
  // The owner of a global node number (ranks own consecutive numbers).
  const auto owner_of = [&](std::int64_t node) {
    const auto it = std::upper_bound(part.node_offsets.begin(), part.node_offsets.end(), node);
    return static_cast<int>(it - part.node_offsets.begin()) - 1;
  };
  // An fsi coupling wins over velocity conditions: no bound slave nodes (as when whole).
  const auto multiplier = itf.multiplier == io::Multiplier::dual ? mortar::Multiplier::dual
                                                                 : mortar::Multiplier::standard;
  const auto bound = type == io::InterfaceType::fsi
                         ? std::vector<char>{}
                         : detail::bound_slave_nodes(config, mesh, t.slave, multiplier);

  // The slave facets of this rank's cells and the master facets it holds; with the independent
  // distribution the slave facets it integrates are cut anew over all ranks and arrive with the
  // facets around their nodes (`integrated`: those, over their own node table `integrated_ids`).
  // With `bulk` (or on one rank) a rank integrates the slave facets of the cells it owns.
  const auto slave_part = side_part(t.slave, part, slave_region, slave_owned);
  const auto master_part = side_part(master_held, part, master_region, master_owned);
  const bool independent =
      size > 1 && config.parallel.interface_distribution == io::InterfaceDistribution::independent;
  SlaveShare share;
  InterfaceSide shared_side;
  if (independent) {
    ScopedTimer timer(timers, "search");
    std::vector<local_index> owned_list;
    for (local_index f = 0; f < t.slave.n_facets(); ++f)
      if (slave_owned[static_cast<std::size_t>(f)]) owned_list.push_back(f);
    const auto held_part =
        side_part(t.slave, part, slave_region,
                  std::vector<char>(static_cast<std::size_t>(t.slave.n_facets()), 1));
    share = share_slave_facets(comm, t.slave, held_part, slave_part, owned_list, bound);
    shared_side = side_of(parallel::SurfacePart(share.facets));
  }
  const InterfaceSide& integrated = independent ? shared_side : t.slave;
  const std::vector<std::int64_t>& integrated_ids =
      independent ? share.facets.node_ids : t.slave_index;
  const std::vector<char>& integrate = independent ? share.integrate : slave_owned;
  const parallel::SurfacePart& integrated_part = independent ? share.assigned : slave_part;

  std::vector<mortar::CandidatePair> candidates;
  InterfaceSide ghosts;
  {
    ScopedTimer timer(timers, "search");
    // The inflation of the whole interface (0.3 of the shortest edge of both sides), as the
    // replicated search takes it, so that the ranks' pairs together are the serial ones.
    const double eps = parallel::global_inflation(comm, slave_part, master_part, 0.3);
    auto g = parallel::ghost_masters(comm, integrated_part, master_part, eps);
    t.master_index = g.node_ids;
    ghosts = side_of(std::move(g));
    if (integrated_part.n_facets() > 0 && ghosts.n_facets() > 0) {
      search::SearchOptions options;
      options.inflation = eps;
      search::InterfaceSearch finder(integrated.surface(), ghosts.surface(), options);
      for (const auto& p : finder.find_pairs())
        if (integrate[static_cast<std::size_t>(p.slave)]) candidates.push_back({p.slave, p.master});
    }
  }

  ScopedTimer timer(timers, "mortar");
  auto options = detail::mortar_options(itf, integrated, ghosts);
  // Curved facets anywhere on the interface raise the quadrature everywhere, as when whole.
  MPI_Allreduce(MPI_IN_PLACE, &options.pair.cell_quadrature_degree, 1, MPI_INT, MPI_MAX, comm);
  auto ops =
      mortar::assemble_mortar_operators(integrated.facet_set(), ghosts.facet_set(), candidates,
                                        options, independent ? share.bound : bound);
  t.local_slave_facets = integrated_part.n_facets();
  t.local_master_ghosts = ghosts.n_facets();
  t.local_pairs = static_cast<std::int64_t>(candidates.size());
  t.local_integration_cells = ops.n_integration_cells;

  // 1. This rank's contributions to the rows of D and M, to the owners of the rows' nodes.
  std::vector<RowEntry> rows; // complete rows of the owned slave nodes, sorted
  {
    std::vector<std::pair<int, RowEntry>> items;
    items.reserve(ops.D.size() + ops.M.size());
    for (const auto& e : ops.D) {
      RowEntry r;
      r.row = integrated_ids[static_cast<std::size_t>(e.row)];
      r.col = integrated_ids[static_cast<std::size_t>(e.col)];
      r.value = e.value;
      items.emplace_back(owner_of(r.row), r);
    }
    for (const auto& e : ops.M) {
      auto r = master_entry(dim, integrated_ids, t.master_index, e, ghosts.coordinates);
      items.emplace_back(owner_of(r.row), r);
    }
    std::vector<std::int64_t> offsets, recv_offsets;
    const auto send = by_rank(size, items, offsets);
    auto received = parallel::alltoallv<RowEntry>(comm, send, offsets, recv_offsets);
    // Summed in the order received (by source rank), the same on every call.
    std::stable_sort(received.begin(), received.end(), entry_less);
    for (const auto& r : received) {
      if (!rows.empty() && rows.back().row == r.row && rows.back().kind == r.kind &&
          rows.back().col == r.col) {
        rows.back().value += r.value;
      } else {
        rows.push_back(r);
      }
    }
  }

  if (independent) {
    // The averaged nodal normals, the nodal transformation T and the bound flags over the held
    // side (as with `bulk`); D and M come from the rows below, the counts from the integration.
    auto held = mortar::assemble_mortar_operators(t.slave.facet_set(), ghosts.facet_set(), {},
                                                  options, bound);
    held.n_candidates = ops.n_candidates;
    held.n_pairs_integrated = ops.n_pairs_integrated;
    held.n_integration_cells = ops.n_integration_cells;
    held.n_projection_failures = ops.n_projection_failures;
    held.integrated_area = ops.integrated_area;
    ops = std::move(held);
  }

  // 2. The complete rows of every held slave node, from their owners.
  std::vector<int> owners(n_slave);
  for (std::size_t i = 0; i < n_slave; ++i) owners[i] = owner(i);
  const auto complete = rows_from_owners(comm, t.slave_index, owners, rows);

  // 3. The operators over the held slave nodes and the master nodes their rows reach. A row
  // with a column outside the held side (a bound neighbour beyond the ghost layer) is dropped;
  // it must not be one that this rank's own cells need.
  std::vector<char> dropped(n_slave, 0);
  for (const auto& e : complete)
    if (e.kind == 0 && slave_local.count(e.col) == 0)
      dropped[static_cast<std::size_t>(slave_local.at(e.row))] = 1;
  InterfaceSide master;
  master.dim = dim;
  std::vector<std::int64_t> master_index;
  std::unordered_map<std::int64_t, local_index> master_local;
  std::vector<mortar::Triplet> D, M;
  for (const auto& e : complete) {
    const auto row = slave_local.at(e.row);
    if (dropped[static_cast<std::size_t>(row)]) continue;
    if (e.kind == 0) {
      D.push_back({row, slave_local.at(e.col), e.value});
      continue;
    }
    const auto [it, added] =
        master_local.emplace(e.col, static_cast<local_index>(master_index.size()));
    if (added) {
      master_index.push_back(e.col);
      for (int c = 0; c < dim; ++c) master.coordinates.push_back(e.x[c]);
    }
    M.push_back({row, it->second, e.value});
  }
  // The nodes of this rank's cells and their neighbours in T need complete rows.
  std::vector<char> in_owned_cell(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (part.cell_role[static_cast<std::size_t>(c)] == mesh::CellRole::owned)
      for (auto n : mesh.cell(c)) in_owned_cell[static_cast<std::size_t>(n)] = 1;
  std::vector<char> needed(n_slave, 0);
  for (std::size_t i = 0; i < n_slave; ++i)
    needed[i] = in_owned_cell[static_cast<std::size_t>(t.slave.mesh_nodes[i])];
  for (const auto& e : ops.T)
    if (in_owned_cell[static_cast<std::size_t>(
            t.slave.mesh_nodes[static_cast<std::size_t>(e.row)])])
      needed[static_cast<std::size_t>(e.col)] = 1;
  bool bad = false;
  for (std::size_t i = 0; i < n_slave; ++i) bad = bad || (needed[i] && dropped[i]);
  parallel::check_collectively(comm, bad,
                               "mesh tying: a bound slave node beyond the ghost layer is needed "
                               "by the distributed interface set-up; run on fewer ranks");

  ops.D = std::move(D);
  ops.M = std::move(M);
  mortar::compress(ops.D, static_cast<local_index>(n_slave));
  mortar::compress(ops.M, static_cast<local_index>(n_slave));
  // Counts of the whole interface.
  {
    std::int64_t counts[6] = {ops.n_candidates,        ops.n_pairs_integrated,
                              ops.n_integration_cells, ops.n_projection_failures,
                              slave_part.n_facets(),   master_part.n_facets()};
    MPI_Allreduce(MPI_IN_PLACE, counts, 6, MPI_INT64_T, MPI_SUM, comm);
    double area = ops.integrated_area;
    MPI_Allreduce(MPI_IN_PLACE, &area, 1, MPI_DOUBLE, MPI_SUM, comm);
    ops.n_candidates = static_cast<local_index>(counts[0]);
    ops.n_pairs_integrated = static_cast<local_index>(counts[1]);
    ops.n_integration_cells = static_cast<local_index>(counts[2]);
    ops.n_projection_failures = static_cast<local_index>(counts[3]);
    t.n_slave_facets = counts[4];
    t.n_master_facets = counts[5];
    ops.integrated_area = area;
  }
  if (ops.n_pairs_integrated == 0) detail::fail_no_overlap(itf);
  t.operators = std::move(ops);
  t.master = std::move(master);
  t.master_index = std::move(master_index);
  if (type == io::InterfaceType::fsi) publish_projection(comm, t, owners);

  // Mesh initialization (D X_S = M X_M). Dual multipliers (D diagonal): from the complete
  // rows, for the nodes of the rank's cells; every rank that holds such a node computes the
  // same position from the same rows. Standard multipliers: one distributed solve over the
  // side, each node's move published by its owner to every rank that holds the node.
  std::vector<double> moved;
  std::vector<char> update(n_slave, 0);
  if (t.operators.multiplier == mortar::Multiplier::standard) {
    auto delta = standard_initialization(comm, t, rows, slave_local, owners);
    parallel::HolderPublisher(comm, t.slave_index, owners).publish(delta, dim);
    moved = t.slave.coordinates;
    for (std::size_t k = 0; k < moved.size(); ++k) moved[k] += delta[k];
    std::fill(update.begin(), update.end(), 1);
  } else {
    moved = mortar::initialize_slave_coordinates(t.operators, t.slave.coordinates,
                                                 t.master.coordinates);
    for (std::size_t i = 0; i < n_slave; ++i)
      update[i] = in_owned_cell[static_cast<std::size_t>(t.slave.mesh_nodes[i])];
  }
  double max_relocation = 0.0;
  for (std::size_t i = 0; i < n_slave; ++i) {
    const auto node = static_cast<std::size_t>(t.slave.mesh_nodes[i]);
    if (!update[i]) continue;
    double d2 = 0.0;
    for (int c = 0; c < dim; ++c) {
      const double delta = moved[i * dim + c] - t.slave.coordinates[i * dim + c];
      d2 += delta * delta;
      mesh.x[node * dim + c] = moved[i * dim + c];
    }
    if (part.node_owner[node] == rank) max_relocation = std::max(max_relocation, std::sqrt(d2));
  }
  MPI_Allreduce(&max_relocation, &t.max_relocation, 1, MPI_DOUBLE, MPI_MAX, comm);
  t.slave.update_coordinates(mesh);
  return result;
}

} // namespace

std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::DistributedMesh& part,
                                            MPI_Comm comm, PhaseTimers& timers,
                                            io::InterfaceType type) {
  std::vector<TiedInterface> out;
  std::vector<std::vector<std::int32_t>> owned_master_nodes;
  for (const auto& itf : config.interfaces) {
    if (itf.type != type) continue;
    if (!distributed_tying(itf)) {
      out.push_back(detail::setup_whole(config, itf, part.mesh, timers, itf.type, part.node_gid));
      owned_master_nodes.emplace_back();
      continue;
    }
    auto r = setup_distributed(config, itf, part, comm, timers, type);
    out.push_back(std::move(r.t));
    owned_master_nodes.push_back(std::move(r.owned_master_nodes));
  }
  // Chained tying: a master node (checked by its owner, who holds every facet around it) that
  // is a slave node of another interface.
  int chained = static_cast<int>(out.size());
  for (std::size_t a = 0; a < out.size() && chained == static_cast<int>(out.size()); ++a)
    for (std::size_t b = 0; b < out.size(); ++b) {
      if (a == b || !out[a].distributed) continue;
      const auto& slaves = out[b].slave.mesh_nodes;
      for (auto n : owned_master_nodes[a])
        if (std::binary_search(slaves.begin(), slaves.end(), n)) chained = static_cast<int>(a);
    }
  MPI_Allreduce(MPI_IN_PLACE, &chained, 1, MPI_INT, MPI_MIN, comm);
  if (chained < static_cast<int>(out.size()))
    for (const auto& itf : config.interfaces)
      if (itf.name == out[static_cast<std::size_t>(chained)].name)
        io::fail_at(itf.mark, "interface '" + itf.name +
                                  "': a master node is a slave node of another interface; "
                                  "chained tying is not supported");
  return out;
}

} // namespace seam::meshtying
