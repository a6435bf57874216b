// la::Matrix::share_near_null_space: a product P^T K T with P of block size 1 (the mesh-tying
// condensation) has block size 1 and no near-null space; sharing gives it the block size
// and the rigid-body modes of K, and leaves a matrix with its own near-null space alone.
#include "seam/la/petsc.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <vector>

namespace seam::la {
namespace {

constexpr PetscInt dim = 3, nodes_per_rank = 4, n_owned = dim * nodes_per_rank;

PetscInt first_row() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return n_owned * r;
}

/// A diagonal matrix of block size `bs` (the identity times `scale`), assembled.
Matrix diagonal(PetscInt bs, double scale) {
  const std::vector<PetscInt> d_nnz(n_owned, 1), o_nnz(n_owned, 0);
  Matrix m(PETSC_COMM_WORLD, n_owned, d_nnz, o_nnz, bs);
  for (PetscInt i = first_row(); i < first_row() + n_owned; ++i) {
    const double v = scale;
    m.add_values({&i, 1}, {&i, 1}, {&v, 1});
  }
  m.assemble();
  return m;
}

/// Node coordinates (x, y, z of each owned node), distinct and not on one line.
Vector coordinates() {
  Vector x(PETSC_COMM_WORLD, n_owned);
  std::vector<PetscInt> rows;
  std::vector<double> values;
  for (PetscInt i = 0; i < n_owned; ++i) {
    const PetscInt row = first_row() + i, node = row / dim;
    rows.push_back(row);
    values.push_back(row % dim == 0 ? double(node) : row % dim == 1 ? double(node * node) : 1.0);
  }
  x.set_values(rows, values);
  x.assemble();
  return x;
}

PetscInt block_size(const Matrix& m) {
  PetscInt bs = 0;
  check(MatGetBlockSize(m.get(), &bs), "MatGetBlockSize");
  return bs;
}

PetscInt modes(const Matrix& m) {
  MatNullSpace nsp = nullptr;
  check(MatGetNearNullSpace(m.get(), &nsp), "MatGetNearNullSpace");
  if (!nsp) return 0;
  PetscBool constant = PETSC_FALSE;
  PetscInt n = 0;
  const Vec* vecs = nullptr;
  check(MatNullSpaceGetVecs(nsp, &constant, &n, &vecs), "MatNullSpaceGetVecs");
  return n + (constant ? 1 : 0);
}

TEST(NearNullSpace, CondensedProductGetsBlockSizeAndRigidBodyModes) {
  Matrix K = diagonal(dim, 2.0);
  const Vector X = coordinates();
  K.set_near_null_space(X);
  ASSERT_EQ(block_size(K), dim);
  ASSERT_EQ(modes(K), 6);
  const Matrix P = diagonal(1, 1.0);
  Matrix C = Matrix::ptap(K, P);
  EXPECT_EQ(block_size(C), 1);
  EXPECT_EQ(modes(C), 0);
  C.share_near_null_space(K);
  EXPECT_EQ(block_size(C), dim);
  EXPECT_EQ(modes(C), 6);
  // Once more (the next Newton iteration): unchanged.
  C.share_near_null_space(K);
  EXPECT_EQ(modes(C), 6);
}

TEST(NearNullSpace, OwnNearNullSpaceKept) {
  Matrix K = diagonal(dim, 2.0);
  const Vector X = coordinates();
  K.set_near_null_space(X);
  Matrix C = diagonal(1, 1.0);
  C.set_near_null_space(X); // block size 1: the constant vector alone
  ASSERT_EQ(modes(C), 1);
  C.share_near_null_space(K);
  EXPECT_EQ(block_size(C), 1);
  EXPECT_EQ(modes(C), 1);
}

TEST(NearNullSpace, NothingToShare) {
  const Matrix K = diagonal(dim, 2.0);
  Matrix C = diagonal(1, 1.0);
  C.share_near_null_space(K);
  EXPECT_EQ(block_size(C), 1);
  EXPECT_EQ(modes(C), 0);
}

} // namespace
} // namespace seam::la
