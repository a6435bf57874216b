// la::Matrix::assign_sum (this = A + B in place while the pattern holds), as the condensed
// contact system uses it: against A x + B x computed separately, on 1 and 3 ranks; and
// la::Matrix::multiply_sparse_left (A B fetching only the rows of B that A's columns name), as
// the condensation forms dLP K: against MatMatMult (Matrix::multiply), the same pattern and
// values, with A's columns on other ranks and a rank whose rows of A are all empty.
#include "seam/la/petsc.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace seam::la {
namespace {

constexpr PetscInt rows_per_rank = 6;

struct Triplets {
  std::vector<PetscInt> i, j;
  std::vector<double> v;
  void add(PetscInt r, PetscInt c, double value) {
    i.push_back(r);
    j.push_back(c);
    v.push_back(value);
  }
  Matrix matrix() const { return Matrix::from_triplets(PETSC_COMM_WORLD, rows_per_rank, i, j, v); }
};

int rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int size() {
  int s = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

/// A tridiagonal matrix (the "bulk" pattern) on this rank's rows.
Matrix tridiagonal() {
  const PetscInt n = rows_per_rank * size(), first = rows_per_rank * rank();
  Triplets t;
  for (PetscInt r = first; r < first + rows_per_rank; ++r)
    for (PetscInt c = r - 1; c <= r + 1; ++c)
      if (c >= 0 && c < n) t.add(r, c, c == r ? 4.0 + r : -1.0 - 0.1 * c);
  return t.matrix();
}

/// Entries at (row, col) with `value` on the rank that owns row.
Matrix sparse(const std::vector<std::pair<PetscInt, PetscInt>>& at, double value) {
  const PetscInt first = rows_per_rank * rank();
  Triplets t;
  for (const auto& [r, c] : at)
    if (r >= first && r < first + rows_per_rank) t.add(r, c, value + 0.01 * r + 0.001 * c);
  return t.matrix();
}

/// max |S x - (A x + B x)| over a fixed x.
double sum_error(const Matrix& S, const Matrix& A, const Matrix& B) {
  Vector x(PETSC_COMM_WORLD, rows_per_rank), y(PETSC_COMM_WORLD, rows_per_rank),
      z(PETSC_COMM_WORLD, rows_per_rank), w(PETSC_COMM_WORLD, rows_per_rank);
  {
    Vector::LocalView view(x, true);
    auto v = view.values();
    for (std::size_t k = 0; k < v.size(); ++k) v[k] = 1.0 + 0.37 * k + rank();
  }
  S.mult(x, y);
  A.mult(x, z);
  B.mult(x, w);
  z.axpy(1.0, w);
  y.axpy(-1.0, z);
  return y.norm();
}

TEST(MatrixAssignSum, InPlaceWhileThePatternHolds) {
  const PetscInt n = rows_per_rank * size();
  const Matrix A = tridiagonal();
  Matrix S;
  // First sum: a new matrix; B's entry (0, 2) lies outside A's pattern.
  const Matrix B1 = sparse({{0, 2}, {1, 1}, {n - 1, n - 2}}, 2.0);
  EXPECT_FALSE(S.assign_sum(A, B1));
  EXPECT_LT(sum_error(S, A, B1), 1e-12);
  const Mat object = S.get();
  // A subset of the pattern with other values: in place, and B1's values are gone.
  const Matrix B2 = sparse({{1, 1}, {n - 1, n - 2}}, -3.0);
  EXPECT_TRUE(S.assign_sum(A, B2));
  EXPECT_EQ(S.get(), object);
  EXPECT_LT(sum_error(S, A, B2), 1e-12);
  // Fixed rows and columns zeroed on the sum (as the Newton system does) keep the pattern.
  const std::vector<PetscInt> fixed =
      rank() == 0 ? std::vector<PetscInt>{0} : std::vector<PetscInt>{};
  S.zero_rows_columns(fixed);
  EXPECT_TRUE(S.assign_sum(A, B1));
  EXPECT_LT(sum_error(S, A, B1), 1e-12);
  // A new coupling (0, n - 1), off the pattern (another rank's column on 3 ranks): rebuilt.
  const Matrix B3 = sparse({{0, n - 1}}, 5.0);
  EXPECT_FALSE(S.assign_sum(A, B3));
  EXPECT_LT(sum_error(S, A, B3), 1e-12);
  // Another A (a new object with the same pattern): rebuilt, as its pattern is not known.
  const Matrix A2 = tridiagonal();
  EXPECT_FALSE(S.assign_sum(A2, B2));
  EXPECT_LT(sum_error(S, A2, B2), 1e-12);
}

/// A banded "stiffness" on this rank's rows (bandwidth 2, plus a coupling to the last row),
/// with values that round differently in another order of summation.
Matrix banded() {
  const PetscInt n = rows_per_rank * size(), first = rows_per_rank * rank();
  Triplets t;
  for (PetscInt r = first; r < first + rows_per_rank; ++r) {
    for (PetscInt c = r - 2; c <= r + 2; ++c)
      if (c >= 0 && c < n) t.add(r, c, c == r ? 4.0 + 0.3 * r : -1.0 / (3.0 + r + 0.7 * c));
    if (r != n - 1) t.add(r, n - 1, 0.1 / (1.0 + r));
  }
  return t.matrix();
}

/// Entries of A at (row, col) on the rank owning the row: a few rows, columns anywhere, one
/// explicit zero (its products are kept in the pattern, as MatMatMult keeps them).
Matrix few_rows() {
  const PetscInt n = rows_per_rank * size(), first = rows_per_rank * rank();
  const std::vector<std::pair<PetscInt, PetscInt>> at = {
      {0, 0}, {0, n - 1}, {0, n / 2}, {1, 3}, {n / 2, 1}, {n / 2, n / 2 + 1}, {n - 2, n - 2}};
  Triplets t;
  for (std::size_t k = 0; k < at.size(); ++k) {
    const auto [r, c] = at[k];
    // Rank 1 of 3 owns rows 6..11: only n / 2 = 9 has entries there; none on the last rows
    // but n - 2. An explicit zero at (1, 3).
    if (r >= first && r < first + rows_per_rank) t.add(r, c, k == 3 ? 0.0 : 1.0 / (1.0 + k));
  }
  return t.matrix();
}

TEST(MatrixSparseLeft, EqualsMatMatMult) {
  const Matrix A = few_rows(), B = banded();
  const Matrix C = Matrix::multiply_sparse_left(A, B), R = Matrix::multiply(A, B);
  PetscInt lo = 0, hi = 0;
  ASSERT_EQ(MatGetOwnershipRange(R.get(), &lo, &hi), 0);
  int rows_with_entries = 0;
  for (PetscInt i = lo; i < hi; ++i) {
    PetscInt nc = 0, nr = 0;
    const PetscInt *cc = nullptr, *cr = nullptr;
    const PetscScalar *vc = nullptr, *vr = nullptr;
    ASSERT_EQ(MatGetRow(C.get(), i, &nc, &cc, &vc), 0);
    ASSERT_EQ(MatGetRow(R.get(), i, &nr, &cr, &vr), 0);
    EXPECT_EQ(nc, nr) << "row " << i;
    for (PetscInt k = 0; k < std::min(nc, nr); ++k) {
      EXPECT_EQ(cc[k], cr[k]) << "row " << i;
      EXPECT_LE(std::abs(vc[k] - vr[k]), 1e-15 * std::max(1.0, std::abs(vr[k])))
          << "row " << i << " column " << cr[k];
    }
    rows_with_entries += nr > 0;
    MatRestoreRow(C.get(), i, &nc, &cc, &vc);
    MatRestoreRow(R.get(), i, &nr, &cr, &vr);
  }
  // The case covers rows with products (the explicit zero's row included) on some ranks and
  // none on others.
  int total = 0;
  MPI_Allreduce(&rows_with_entries, &total, 1, MPI_INT, MPI_SUM, PETSC_COMM_WORLD);
  EXPECT_EQ(total, 4);
}

TEST(MatrixSparseLeft, EmptyLeftFactor) {
  const Matrix A = Triplets{}.matrix(), B = banded();
  const Matrix C = Matrix::multiply_sparse_left(A, B);
  MatInfo info;
  ASSERT_EQ(MatGetInfo(C.get(), MAT_GLOBAL_SUM, &info), 0);
  EXPECT_EQ(info.nz_used, 0.0);
}

} // namespace
} // namespace seam::la
