#pragma once
// A fluid-structure run (an `fsi` interface between a fluid and a solid body): the monolithic
// Newton method on structure, fluid and fluid mesh (FsiSystem). `integrator: static`: each
// step solves the steady coupled problem at its t, starting from the last converged state;
// `generalized_alpha`: each step is one generalized-alpha step of both fields from rest
// (FsiSystem::History).
// Output: results.pvd (structure and fluid fields, one piece per rank), forces.csv over
// fluid-side groups, steps.csv, interface_<name>.csv with the fluid's traction on the
// structure (docs/fsi.md).
#include "seam/common/mpi.hpp"
#include "seam/io/config.hpp"
#include "seam/problem/restart_from.hpp"

#include <filesystem>

namespace seam::mesh {
struct DistributedMesh;
}

namespace seam::problem {
struct MeshIdentity;
} // namespace seam::problem

namespace seam::fsi {

/// True if the input has an interface of type fsi.
bool has_fsi(const io::Config& config);

struct FsiRunInfo {
  long long n_dofs = 0;
};

/// Checks the input, then runs all steps on `part`, this rank's part of the distributed mesh
/// (its cells and a ghost layer; `identity` the whole mesh's), writing into `dir` (which exists),
/// or continues from the checkpoint of `restart` (the tables and results.pvd continue; the
/// checkpoints of `output.checkpoint_every` hold the nodal state by global node id, written
/// by the owners, so that any number of ranks continues, fsi_solver.cpp). `check_only` stops
/// after the checks. Throws InputError or SolverError.
FsiRunInfo run_fsi(const io::Config& config, mesh::DistributedMesh& part,
                   const problem::MeshIdentity& identity, Comm comm,
                   const std::filesystem::path& dir, bool quiet, bool check_only = false,
                   const problem::RestartFrom& restart = {});

} // namespace seam::fsi
