#pragma once
// Mesh tying interfaces (seed paper Sect. 2): the mortar operators D and M of each
// `type: mesh_tying` interface, computed once in the reference configuration, after the
// mesh initialization that makes D X_S = M X_M hold exactly (ALGORITHMS.md §4, §7).
#include "seam/common/timer.hpp"
#include "seam/io/config.hpp"
#include "seam/meshtying/interface_side.hpp"
#include "seam/mortar/interface.hpp"

#include <mpi.h>

#include <array>
#include <cstdint>
#include <functional>
#include <span>
#include <string>
#include <vector>

namespace seam::mesh {
struct DistributedMesh;
}

namespace seam::meshtying {

struct TiedInterface {
  std::string name;
  io::Multiplier multiplier = io::Multiplier::dual;
  io::Strategy strategy = io::Strategy::condensed;
  InterfaceSide slave, master;
  /// D (slave x slave) and M (slave x master) over side-local node numbers.
  mortar::MortarOperators operators;
  /// Largest distance a slave node was moved by the mesh initialization (over all ranks).
  double max_relocation = 0.0;
  /// Facets of the whole sides (the same on every rank).
  std::int64_t n_slave_facets = 0, n_master_facets = 0;

  /// Distributed (docs/parallel.md, "Mesh tying distributed"): `slave` is the part of the
  /// slave side this rank holds (its facets on owned and ghost cells), `master` holds no
  /// facets but the master nodes the rows of M refer to (coordinates, `master_index`), and D
  /// and M carry the complete rows (summed over the ranks) of every slave node of the rank's
  /// own cells and of their neighbours in T. Replicated: both sides whole on every rank.
  bool distributed = false;
  std::vector<std::int64_t> slave_index;  ///< distributed: slave node -> global node number
  std::vector<std::int64_t> master_index; ///< distributed: master node -> global node number
  /// Distributed fsi: P = D^-1 M (T D^-1 M with a modified quadratic basis) of every held slave
  /// node, (slave node, master node, weight), computed by the node's owner and sent to the
  /// ranks that hold it (the master nodes its columns reach are in `master`, `master_index`).
  std::vector<mortar::Triplet> projection;
  /// This rank's share (distributed; the whole interface when replicated): slave facets it
  /// integrated, master facets ghosted to it, candidate pairs, integration cells.
  std::int64_t local_slave_facets = 0, local_master_ghosts = 0, local_pairs = 0,
               local_integration_cells = 0;
};

/// The boundary region (dimension mesh.dim - 1) an interface side names; a located InputError
/// if the mesh has none.
const mesh::Region& side_region(const mesh::Mesh& mesh, const io::RegionRef& ref);

/// The nodes a slave and a master side share, each counted by its owner (who holds every facet
/// around it, so that a node in one rank's part only is found).
struct SharedNodes {
  std::int64_t count = 0;    ///< over all ranks
  std::int64_t first = -1;   ///< the lowest id of a shared node (node id of the output)
  std::array<double, 3> x{}; ///< its coordinates
  /// "share N node(s) (the first: node I at (x, y[, z]))", the same on every rank.
  std::string describe(int dim) const;
};

/// Collective over `comm` (MPI_COMM_SELF for sides held whole). `slave` and `master`: the
/// sides' mesh nodes (sorted); `owned(n)`: this rank owns mesh node n; `id(n)`: its id in the
/// mesh as read.
SharedNodes shared_nodes(MPI_Comm comm, const mesh::Mesh& mesh, std::span<const std::int32_t> slave,
                         std::span<const std::int32_t> master,
                         const std::function<bool(std::int32_t)>& owned,
                         const std::function<std::int64_t(std::int32_t)>& id);

/// Sets up every mesh-tying interface of the input: extracts both sides, searches candidate
/// pairs (k-DOP trees), integrates D and M, relocates the slave nodes of the mesh so that the
/// constraint holds exactly for the reference geometry. Throws InputError (located at the
/// interface in the YAML) for sides that share nodes or do not face each other.
/// `type` fsi: the same for the `fsi` interfaces (fluid side = slave, structure = master),
/// where the coupling wins over velocity conditions (no bound slave nodes). `node_gid`: the
/// ids of `mesh`'s nodes in the mesh as read when it is a rank's part (the messages name them).
std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::Mesh& mesh,
                                            PhaseTimers& timers,
                                            io::InterfaceType type = io::InterfaceType::mesh_tying,
                                            std::span<const std::int64_t> node_gid = {});

/// P = D^-1 M of a dual basis over the rows [0, n_rows) of `ops` (with a modified quadratic
/// basis, d_S = T d~_S: T D^-1 M), rows with D_jj = 0 left empty: (row, master column, weight),
/// each row's columns ascending.
std::vector<mortar::Triplet> projection(const mortar::MortarOperators& ops, local_index n_rows);

/// True for the interfaces set up distributed on a distributed mesh (mesh tying, condensed and
/// saddle point, and the `fsi` couplings): their sides need not be held whole on every rank.
bool distributed_tying(const io::Interface& interface);

/// Collective. The mesh-tying interfaces on a distributed mesh: the distributed_tying ones
/// integrated, each slave facet by its rank of an RCB cut over all ranks
/// (`parallel.interface_distribution: independent`) or by the owner of its cell (`bulk`, or one
/// rank), against the master facets ghosted to it by bounding boxes, the rows of D and M summed on
/// the slave nodes' owners and sent to the ranks that hold the nodes. Relocates the slave nodes of
/// `part` like the replicated set-up; with standard multipliers (D not diagonal) by one distributed
/// solve of D on the slave nodes' owners. `type` fsi: the `fsi` interfaces (no bound slave nodes),
/// each with its `projection`.
std::vector<TiedInterface> setup_mesh_tying(const io::Config& config, mesh::DistributedMesh& part,
                                            MPI_Comm comm, PhaseTimers& timers,
                                            io::InterfaceType type = io::InterfaceType::mesh_tying);

} // namespace seam::meshtying
