// la::LinearSolver's choice of MUMPS's ordering (ordering()): a nonzero pattern that stays the
// same is analysed once and keeps the default ordering; one that changes at every
// factorization is analysed every time, and on a matrix of many separate blocks (as the 200
// rings' matrix) QAMD is taken because the default's nested dissection costs far more than the
// factorization; a small one keeps the default (below ordering_trial_seconds). Every solve is
// checked by its true residual, on 1 and 3 ranks.
#include "seam/la/petsc.hpp"

#include "relative_residual.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cstdint>
#include <cstdio>
#include <string>
#include <vector>

namespace seam::la {
namespace {

constexpr PetscInt side = 8; // a block: side x side grid, 5-point stencil
constexpr PetscInt block_rows = side * side;
constexpr PetscInt blocks_per_rank = 600;

/// The blocks' Laplacians shifted to be nonsingular, and `couplings` entries per rank joining
/// the first row of one of its blocks to a row of another block, chosen from `seed` (another
/// seed: another pattern). The diagonal dominates.
Matrix blocks(std::uint32_t seed, int couplings, PetscInt n_blocks = blocks_per_rank) {
  int rank = 0, size = 1;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  MPI_Comm_size(PETSC_COMM_WORLD, &size);
  const PetscInt rows_per_rank = n_blocks * block_rows;
  const PetscInt n = rows_per_rank * size, first = rows_per_rank * rank;
  std::vector<PetscInt> i, j;
  std::vector<double> v;
  const auto add = [&](PetscInt r, PetscInt c, double value) {
    i.push_back(r);
    j.push_back(c);
    v.push_back(value);
  };
  for (PetscInt b = 0; b < n_blocks; ++b)
    for (PetscInt y = 0; y < side; ++y)
      for (PetscInt x = 0; x < side; ++x) {
        const PetscInt r = first + b * block_rows + y * side + x;
        add(r, r, 4.5);
        if (x > 0) add(r, r - 1, -1.0);
        if (x + 1 < side) add(r, r + 1, -1.0);
        if (y > 0) add(r, r - side, -1.0);
        if (y + 1 < side) add(r, r + side, -1.0);
      }
  std::uint32_t state = seed * 2654435761u + 12345u + static_cast<std::uint32_t>(rank) * 97u;
  const auto next = [&state] {
    state = state * 1664525u + 1013904223u;
    return state >> 8;
  };
  for (int k = 0; k < couplings; ++k) {
    const PetscInt r = first + static_cast<PetscInt>(next() % n_blocks) * block_rows;
    const PetscInt c = static_cast<PetscInt>(next() % static_cast<std::uint32_t>(n));
    if (c / block_rows == r / block_rows) continue;
    add(r, c, -0.5);
    add(r, r, 0.5);
  }
  return Matrix::from_triplets(PETSC_COMM_WORLD, rows_per_rank, i, j, v);
}

using testing::relative_residual;

Vector right_hand_side(PetscInt n_blocks = blocks_per_rank) {
  Vector b(PETSC_COMM_WORLD, n_blocks * block_rows);
  Vector::LocalView view(b, true);
  auto values = view.values();
  for (std::size_t k = 0; k < values.size(); ++k) values[k] = 1.0 + 0.3 * double(k % 11);
  return b;
}

TEST(FactorOrdering, APatternThatStaysIsAnalysedOnce) {
  const Vector b = right_hand_side();
  Vector x = b.duplicate();
  LinearSolver solver(PETSC_COMM_WORLD, SolverKind::direct);
  EXPECT_EQ(solver.ordering(), "default");
  const Matrix A = blocks(7, 40);
  for (int k = 0; k < 4; ++k) {
    x.zero();
    ASSERT_TRUE(solver.solve(A, b, x));
    EXPECT_LE(relative_residual(A, x, b), 1e-12);
  }
  EXPECT_EQ(solver.symbolic_analyses(), 1);
  EXPECT_EQ(solver.preconditioner_builds(), 4);
  EXPECT_EQ(solver.ordering(), "default");
  EXPECT_TRUE(solver.take_ordering_note().empty());
}

TEST(FactorOrdering, APatternChangingAtEverySolveOfManyBlocksTakesQamd) {
  const Vector b = right_hand_side();
  Vector x = b.duplicate();
  LinearSolver solver(PETSC_COMM_WORLD, SolverKind::direct);
  std::string note;
  for (std::uint32_t k = 0; k < 6; ++k) {
    const Matrix A = blocks(k + 1, 40);
    x.zero();
    ASSERT_TRUE(solver.solve(A, b, x));
    EXPECT_LE(relative_residual(A, x, b), 1e-12) << "solve " << k << ", " << solver.ordering();
    if (auto n = solver.take_ordering_note(); !n.empty()) note = n;
  }
  int rank = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &rank);
  if (rank == 0) std::printf("%s\n", note.c_str());
  EXPECT_EQ(solver.symbolic_analyses(), 6);
  EXPECT_EQ(solver.ordering(), "qamd") << note;
  EXPECT_NE(note.find("QAMD from here"), std::string::npos) << note;
}

TEST(FactorOrdering, ASmallMatrixKeepsTheDefault) {
  // 20 blocks per rank: a set-up far below ordering_trial_seconds, no trial.
  const Vector b = right_hand_side(20);
  Vector x = b.duplicate();
  LinearSolver solver(PETSC_COMM_WORLD, SolverKind::direct);
  for (std::uint32_t k = 0; k < 6; ++k) {
    const Matrix A = blocks(k + 1, 10, 20);
    ASSERT_TRUE(solver.solve(A, b, x));
    EXPECT_LE(relative_residual(A, x, b), 1e-12);
  }
  EXPECT_EQ(solver.symbolic_analyses(), 6);
  EXPECT_EQ(solver.ordering(), "default");
  EXPECT_TRUE(solver.take_ordering_note().empty());
}

TEST(FactorOrdering, TheCommandLineDecides) {
  PetscOptionsSetValue(nullptr, "-mat_mumps_icntl_7", "7");
  {
    const Vector b = right_hand_side();
    Vector x = b.duplicate();
    LinearSolver solver(PETSC_COMM_WORLD, SolverKind::direct);
    for (std::uint32_t k = 0; k < 4; ++k) {
      const Matrix A = blocks(k + 1, 40);
      ASSERT_TRUE(solver.solve(A, b, x));
      EXPECT_LE(relative_residual(A, x, b), 1e-12);
    }
    EXPECT_EQ(solver.ordering(), "command line");
    EXPECT_TRUE(solver.take_ordering_note().empty());
  }
  PetscOptionsClearValue(nullptr, "-mat_mumps_icntl_7");
}

} // namespace
} // namespace seam::la
