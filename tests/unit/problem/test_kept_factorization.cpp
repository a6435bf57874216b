// la::LinearSolver's kept factorization (allow_factor_reuse): GMRES over the factorization of
// an earlier matrix solves a nearby one to the tolerance set_relative_tolerance gives it (never
// below factor_reuse_rtol), checked by the true residual of each solve, on 1 and 3 ranks.
#include "seam/la/petsc.hpp"

#include "relative_residual.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <vector>

namespace seam::la {
namespace {

constexpr PetscInt rows_per_rank = 200;

/// A nonsymmetric tridiagonal matrix; `shift` scales its diagonal by 1 + shift (1 + r / n).
Matrix tridiagonal(double shift) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const PetscInt n = rows_per_rank * size, first = rows_per_rank * rank;
  std::vector<PetscInt> i, j;
  std::vector<double> v;
  for (PetscInt r = first; r < first + rows_per_rank; ++r)
    for (PetscInt c = r - 1; c <= r + 1; ++c)
      if (c >= 0 && c < n) {
        i.push_back(r);
        j.push_back(c);
        v.push_back(c == r ? 4.0 * (1.0 + shift * (1.0 + double(r) / double(n)))
                           : (c < r ? -1.0 : -1.5));
      }
  return Matrix::from_triplets(PETSC_COMM_WORLD, rows_per_rank, i, j, v);
}

using testing::relative_residual;

TEST(KeptFactorization, SolvesToTheToleranceItIsGiven) {
  const Matrix A = tridiagonal(0.0), A2 = tridiagonal(1e-3);
  Vector b(PETSC_COMM_WORLD, rows_per_rank), x = b.duplicate();
  {
    Vector::LocalView view(b, true);
    auto v = view.values();
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = 1.0 + 0.37 * double(k % 7) + 0.1 * v.size();
  }
  LinearSolver solver(PETSC_COMM_WORLD, SolverKind::direct);
  ASSERT_TRUE(solver.solve(A, b, x));
  EXPECT_TRUE(solver.last_solve_built());

  // The default: as exact as the factorization itself.
  solver.allow_factor_reuse(true);
  ASSERT_TRUE(solver.solve(A2, b, x));
  EXPECT_FALSE(solver.last_solve_built());
  const int exact_iterations = solver.last_iterations();
  EXPECT_LE(relative_residual(A2, x, b), 1e-13);
  ASSERT_LE(exact_iterations, LinearSolver::factor_reuse_refactor_iterations);

  // Solves A2 again over the kept factorization with relative tolerance `rtol`; returns the
  // GMRES iterations and checks the true residual against `bound`.
  const auto resolve = [&](double rtol, double bound) {
    solver.set_relative_tolerance(rtol);
    solver.allow_factor_reuse(true);
    x.zero();
    EXPECT_TRUE(solver.solve(A2, b, x));
    EXPECT_FALSE(solver.last_solve_built());
    EXPECT_LE(relative_residual(A2, x, b), bound);
    return solver.last_iterations();
  };
  // A looser tolerance: fewer GMRES iterations, a residual within it.
  EXPECT_LT(resolve(1e-6, 1e-6), exact_iterations);
  // A tolerance below factor_reuse_rtol is raised to it.
  EXPECT_EQ(resolve(1e-20, 1e-13), exact_iterations);
  EXPECT_EQ(solver.preconditioner_builds(), 1);
}

} // namespace
} // namespace seam::la
