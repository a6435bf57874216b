#include "seam/mesh/parallel_partition.hpp"

#include "seam/common/error.hpp"

#include <petscmat.h>

#include <cstdlib>

#include <cstdio> // scotch.h needs FILE
// Scotch's random generator (libscotch, the library under PETSc's PT-Scotch).
#include <scotch/scotch.h>

namespace seam::mesh {
namespace {

void check(PetscErrorCode code, const char* what) {
  SEAM_CHECK(code == 0, InternalError, "parallel partitioning: ", what, " failed (PETSc error ",
             static_cast<int>(code), ")");
}

/// SCOTCH_PTHREAD_NUMBER=1 while it lives, unless the environment sets a number already
/// (then the user chose threads over reproducibility).
class ScotchThreads {
public:
  ScotchThreads() : set_(std::getenv(kName) == nullptr) {
    if (set_) setenv(kName, "1", 1);
  }
  ~ScotchThreads() {
    if (set_) unsetenv(kName);
  }
  ScotchThreads(const ScotchThreads&) = delete;
  ScotchThreads& operator=(const ScotchThreads&) = delete;

private:
  static constexpr const char* kName = "SCOTCH_PTHREAD_NUMBER";
  bool set_;
};

} // namespace

std::vector<int> partition_dual_graph(MPI_Comm comm, std::int64_t first, std::int64_t n_global,
                                      const std::vector<std::int64_t>& offsets,
                                      const std::vector<std::int64_t>& adjacency,
                                      const std::vector<int>& weights) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  const auto n = static_cast<PetscInt>(offsets.size() - 1);
  std::vector<int> part(static_cast<std::size_t>(n), 0);
  if (size == 1) return part;
  PetscBool initialized = PETSC_FALSE;
  PetscInitialized(&initialized);
  SEAM_CHECK(initialized, InternalError, "parallel partitioning needs PETSc initialized");
  (void)first;
  // MatCreateMPIAdj takes ownership of ia and ja (freed with the matrix).
  PetscInt *ia = nullptr, *ja = nullptr;
  check(PetscMalloc1(n + 1, &ia), "PetscMalloc1");
  check(PetscMalloc1(static_cast<PetscInt>(adjacency.size()) + 1, &ja), "PetscMalloc1");
  for (PetscInt i = 0; i <= n; ++i) ia[i] = static_cast<PetscInt>(offsets[i]);
  for (std::size_t k = 0; k < adjacency.size(); ++k) ja[k] = static_cast<PetscInt>(adjacency[k]);
  Mat graph = nullptr;
  check(MatCreateMPIAdj(comm, n, static_cast<PetscInt>(n_global), ia, ja, nullptr, &graph),
        "MatCreateMPIAdj");
  MatPartitioning mp = nullptr;
  check(MatPartitioningCreate(comm, &mp), "MatPartitioningCreate");
  check(MatPartitioningSetAdjacency(mp, graph), "MatPartitioningSetAdjacency");
  check(MatPartitioningSetNParts(mp, size), "MatPartitioningSetNParts");
  if (!weights.empty()) {
    SEAM_CHECK(weights.size() == static_cast<std::size_t>(n), InternalError,
               "parallel partitioning: ", weights.size(), " weights for ", n, " cells");
    // MatPartitioningSetVertexWeights takes ownership (freed with the partitioning).
    PetscInt* w = nullptr;
    check(PetscMalloc1(n + 1, &w), "PetscMalloc1");
    for (PetscInt i = 0; i < n; ++i) w[i] = static_cast<PetscInt>(weights[i]);
    check(MatPartitioningSetVertexWeights(mp, w), "MatPartitioningSetVertexWeights");
  }
  check(MatPartitioningSetType(mp, MATPARTITIONINGPTSCOTCH), "MatPartitioningSetType(ptscotch)");
  // A reproducible partition (docs/parallel.md "Reproducible runs"): with several threads per
  // rank (Debian's Scotch starts one per core) PT-Scotch's result depends on their timing,
  // and its random generator goes on from the state of an earlier partition in the process.
  // Its default context reads SCOTCH_PTHREAD_NUMBER when a computation starts.
  const ScotchThreads one_thread;
  SCOTCH_randomSeed(1);
  SCOTCH_randomReset();
  IS is = nullptr;
  check(MatPartitioningApply(mp, &is), "MatPartitioningApply");
  const PetscInt* p = nullptr;
  check(ISGetIndices(is, &p), "ISGetIndices");
  for (PetscInt i = 0; i < n; ++i) part[static_cast<std::size_t>(i)] = static_cast<int>(p[i]);
  check(ISRestoreIndices(is, &p), "ISRestoreIndices");
  ISDestroy(&is);
  MatPartitioningDestroy(&mp);
  MatDestroy(&graph);
  return part;
}

} // namespace seam::mesh
