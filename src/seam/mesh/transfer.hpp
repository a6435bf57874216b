#pragma once
// Transfer of meshes as one packed byte message (sent in chunks that fit MPI's int counts):
// a DistributedMesh from rank to rank, a whole mesh to every rank; and a text broadcast for
// errors found on one rank.
#include "seam/mesh/distribute.hpp"

#include <mpi.h>

#include <string>

namespace seam::mesh {

/// Collective: `text` of rank 0 on every rank.
void broadcast_text(MPI_Comm comm, std::string& text);

/// Sends `part` to rank `dest`, which calls receive_mesh(comm, source).
void send_mesh(MPI_Comm comm, int dest, const DistributedMesh& part);
DistributedMesh receive_mesh(MPI_Comm comm, int source);

/// Collective: rank 0's whole mesh on every rank (runs that keep the mesh replicated).
void broadcast_mesh(MPI_Comm comm, Mesh& mesh);

} // namespace seam::mesh
