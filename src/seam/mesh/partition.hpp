#pragma once
// Partitioning of the cells over ranks and the matching global node numbering.
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::mesh {

/// The partitioning weight of a cell (issue 12, memory per rank): the sum of its nodes' shares
/// (1 / the number of cells around the node) times its number of nodes, `n_cell_nodes *
/// sum(1 / cells_around)`. Summed over a part it counts the part's nodes, each weighted by the
/// number of nodes of its cells, a measure of the length of its matrix rows (27 neighbour
/// nodes in a hexahedral mesh, about 15 in a tetrahedral one), so that a balanced weight
/// balances the nonzeros of the tangent, its condensed product and the preconditioner built on
/// it. Balancing cell counts instead gives a rank of hexahedra about five times the dofs of a
/// rank of tetrahedra (a tetrahedral mesh has about 5.5 cells per node).
double cell_weight(int n_cell_nodes, double node_share_sum);

/// The integer weights the partitioners take: `weight * scale` rounded, at least 1, with the
/// scale that keeps the sum over all cells (`global_sum` of the real weights) below 2^30.
int integer_weight(double weight, double global_sum);

/// Part (in [0, n_parts)) of every cell: METIS_PartMeshDual on the dual graph in which two
/// cells are adjacent when they share a facet (2 corner nodes in 2D, 3 in 3D), with the cells
/// weighted by cell_weight. Deterministic for the same mesh (fixed seed). n_parts == 1 gives
/// all zeros without METIS. Throws InputError if n_parts < 1 or n_parts > n_cells.
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
