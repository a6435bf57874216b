#pragma once
// Partitioning of the cells over ranks and the matching global node numbering.
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::mesh {

/// Part (in [0, n_parts)) of every cell: METIS_PartMeshDual on the dual graph in which two
/// cells are adjacent when they share a facet (2 corner nodes in 2D, 3 in 3D). Deterministic
/// for the same mesh (fixed seed). n_parts == 1 gives all zeros without METIS. Throws
/// InputError if n_parts < 1 or n_parts > n_cells.
std::vector<int> partition_cells(const Mesh& mesh, int n_parts);

/// Global node numbering for a cell partition: every node belongs to the smallest part among
/// the cells touching it, and each part's nodes are numbered contiguously, ordered by part and
/// then by mesh node index.
struct NodeNumbering {
  std::vector<int> owner;              ///< mesh node -> owning part
  std::vector<std::int64_t> new_index; ///< mesh node -> global index
  std::vector<std::int32_t> old_index; ///< global index -> mesh node (inverse of new_index)
  std::vector<std::int64_t> offsets;   ///< n_parts + 1: part p owns [offsets[p], offsets[p+1])
};

/// Nodes no cell uses (only possible in hand-built meshes) go to part 0. Throws InputError if
/// cell_part has the wrong size or a part outside [0, n_parts).
NodeNumbering number_nodes(const Mesh& mesh, std::span<const int> cell_part, int n_parts);

} // namespace seam::mesh
