#pragma once
// A fluid run on a fixed mesh with `integrator: static`: every step solves the steady
// incompressible Navier-Stokes equations at its t by Newton's method on the full Jacobian
// (convection linearized exactly), starting from the last converged flow (continuation in
// the load parameter t), with the step cutting of the solid drivers.
#include "seam/common/mpi.hpp"
#include "seam/io/config.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/problem/restart_from.hpp"

#include <filesystem>
#include <string>

namespace seam::problem {
struct MeshIdentity;
} // namespace seam::problem

namespace seam::flow {

struct FluidRunInfo {
  long long n_dofs = 0;
};

/// Checks the input for the fluid field, then runs all steps, writing into `dir` (which
/// exists), on this rank's part of a distributed mesh (mesh::distribute_mesh): each rank
/// assembles its cells, owns the dofs of its nodes and holds one ghost layer; the moving
/// mesh is solved distributed as well. `identity`: of the whole mesh (checkpoint.hpp).
/// `check_only` (`seam check`) stops after the checks and the set-up of tied interfaces, whose
/// mesh initialization moves slave nodes of `part`. Throws InputError or SolverError.
FluidRunInfo run_fluid(const io::Config& config, mesh::DistributedMesh& part,
                       const problem::MeshIdentity& identity, Comm comm,
                       const std::filesystem::path& dir, bool quiet,
                       const problem::RestartFrom& restart = {}, bool check_only = false);

} // namespace seam::flow
