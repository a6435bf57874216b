#pragma once
// The distributed mesh read in parallel (issue 12, item 1): no rank ever holds the whole mesh.
// Every rank reads its share of a .msh 4.1 file (msh_chunk.hpp); the parts are then built by
// directories (a node's data lives on the rank owning its tag range, a facet's on the rank its
// corner tags hash to), the dual graph is partitioned in parallel by PT-Scotch through PETSc's
// MatPartitioning, and each cell travels to every rank that holds it (owner, ghost layer,
// interface sides). The result has the layout and the global ids of distribute_mesh
// (distribute.hpp): cells and nodes are numbered as read_mesh numbers them, so node ids, regions
// and outputs agree with the rank-0 path; only the partition differs.
#include "seam/mesh/distribute.hpp"

#include <mpi.h>

#include <filesystem>
#include <span>
#include <string>

namespace seam::mesh {

/// Collective; PETSc must be initialized. `dim` (0, 2 or 3) as ReadOptions::dim. Throws
/// MshUnsupported on every rank for files the chunked reader leaves to Gmsh, InputError on
/// every rank for a bad file (naming it) or more ranks than cells.
DistributedMesh distribute_file(const std::filesystem::path& file, MPI_Comm comm,
                                std::span<const std::string> interface_regions = {}, int dim = 0);

} // namespace seam::mesh
