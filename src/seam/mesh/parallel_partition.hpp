#pragma once
// Parallel partitioning of a distributed dual graph (the cells of a chunked read): PT-Scotch
// through PETSc's MatPartitioning (Debian's PETSc has PT-Scotch, not ParMETIS). partition.hpp
// keeps METIS for meshes held whole on one rank.
#include <mpi.h>

#include <cstdint>
#include <vector>

namespace seam::mesh {

/// Collective; PETSc must be initialized. This rank's rows are the cells [first, first + n),
/// n = offsets.size() - 1, of n_global; the neighbours of row i are adjacency[offsets[i] ..
/// offsets[i+1]) (global cell ids, no self loops); `weights` (empty: all 1) the vertex weight
/// of each row (partition.hpp, integer_weight). Returns the part (= rank) of each row; one
/// rank gives all zeros.
std::vector<int> partition_dual_graph(MPI_Comm comm, std::int64_t first, std::int64_t n_global,
                                      const std::vector<std::int64_t>& offsets,
                                      const std::vector<std::int64_t>& adjacency,
                                      const std::vector<int>& weights = {});

} // namespace seam::mesh
