// The main() of the unit tests that run serially and under mpiexec (unit_parallel, unit_problem,
// unit_fsi; tests/CMakeLists.txt: np = 2, 3, 4 and 3). Every test is collective: ranks run the same
// tests in the same order and check what they computed collectively, so that a failure on one rank
// never leaves the others in a collective.
#include "seam/la/petsc.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdio>

namespace {

/// On ranks other than 0: print only failures, tagged with the rank.
class FailurePrinter : public testing::EmptyTestEventListener {
public:
  explicit FailurePrinter(int rank) : rank_(rank) {}
  void OnTestPartResult(const testing::TestPartResult& r) override {
    if (r.failed())
      std::fprintf(stderr, "[rank %d] %s:%d: %s\n", rank_, r.file_name() ? r.file_name() : "?",
                   r.line_number(), r.summary());
  }

private:
  int rank_;
};

} // namespace

int main(int argc, char** argv) {
  // PT-Scotch 7 (the chunked reader's partitioner, through PETSc) runs threads that call MPI.
  int provided = 0;
  MPI_Init_thread(&argc, &argv, MPI_THREAD_MULTIPLE, &provided);
  testing::InitGoogleTest(&argc, argv);
  int failed = 0, any = 0;
  {
    seam::la::Session petsc(argc, argv, {});
    int rank = 0;
    MPI_Comm_rank(MPI_COMM_WORLD, &rank);
    if (rank != 0) {
      auto& listeners = testing::UnitTest::GetInstance()->listeners();
      delete listeners.Release(listeners.default_result_printer());
      listeners.Append(new FailurePrinter(rank));
    }
    failed = RUN_ALL_TESTS();
    MPI_Allreduce(&failed, &any, 1, MPI_INT, MPI_MAX, MPI_COMM_WORLD);
    if (rank == 0 && any && !failed) std::fprintf(stderr, "%s: FAILED on another rank\n", argv[0]);
  }
  MPI_Finalize();
  return any;
}
