#pragma once
// The distributed mesh (issue 12, item 1). Rank 0 holds the mesh as read, partitions its cells
// (METIS, partition_cells), numbers the nodes per part (number_nodes: a node belongs
// to the smallest part among its cells) and sends every rank a submesh: its own cells, one layer
// of ghost cells (every cell sharing a node with an own cell) and the cells carrying facets of
// the interface regions (mesh tying and contact sides, O(interface) for now), with their nodes.
// Rank 0 then frees the whole mesh: after set-up no rank holds more than that.
//
// Local numbering is monotone in the global one (local cells sorted by global cell id, local
// nodes by global node id), so every sorted structure built from the regions (interface sides,
// node lists) has the same order on every rank, and arrays indexed by a side's local node are
// consistent across ranks. The ghost layer makes every cell around an owned node local, so a
// rank can preallocate and assemble its owned rows without asking anyone.
#include "seam/mesh/mesh.hpp"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace seam::mesh {

/// Why a rank holds a cell: it assembles it, it is in the ghost layer, or it only carries a
/// facet of an interface region.
enum class CellRole : std::int8_t { owned = 0, ghost = 1, interface = 2 };

struct DistributedMesh {
  /// The held cells and nodes in local numbering. Every region of the mesh as read is present
  /// (possibly empty), filtered to the held cells, facets and nodes.
  Mesh mesh;
  std::vector<std::int64_t> node_gid;   ///< local node -> node index in the mesh as read
  std::vector<std::int64_t> cell_gid;   ///< local cell -> cell index in the mesh as read
  std::vector<int> node_owner;          ///< local node -> rank that owns its dofs
  std::vector<std::int64_t> node_index; ///< local node -> global number (dof = dim * it + c)
  std::vector<int> cell_owner;          ///< local cell -> rank that assembles it
  std::vector<CellRole> cell_role;      ///< local cell -> why this rank holds it
  /// n_ranks + 1: rank r owns the global node numbers [node_offsets[r], node_offsets[r+1]).
  std::vector<std::int64_t> node_offsets;
  std::int64_t n_global_nodes = 0;
  std::int64_t n_global_cells = 0;

  std::int32_t n_cells() const { return mesh.n_cells(); }
  std::int32_t n_nodes() const { return mesh.n_nodes(); }
  /// Cells of each role on this rank.
  std::int32_t count(CellRole role) const;
};

/// Collective. `global` is read on rank 0 only (the other ranks pass an empty mesh) and is
/// cleared there once every rank has its part. `interface_regions` (the same on every rank)
/// names facet regions whose cells every rank holds; names that are not facet regions of the
/// mesh are ignored here (the interface set-up reports them). An error on rank 0 (more ranks
/// than cells) is thrown as InputError on every rank.
DistributedMesh distribute_mesh(Mesh& global, MPI_Comm comm,
                                std::span<const std::string> interface_regions = {});

} // namespace seam::mesh
