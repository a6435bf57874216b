// la::BlockAdder (element matrices added by 3x3 node blocks straight into an assembled AIJ
// matrix) against Matrix::add_values (MatSetValues) on the same elements, on 1 and 3 ranks:
// elements reaching other ranks' rows and columns, nodes in unsorted order, and dofs outside
// the node-block layout (which take the MatSetValues path).
#include "seam/la/petsc.hpp"

#include <gtest/gtest.h>
#include <mpi.h>

#include <cmath>
#include <vector>

namespace seam::la {
namespace {

constexpr PetscInt bs = 3, nodes_per_rank = 4;

int comm_rank() {
  int r = 0;
  MPI_Comm_rank(PETSC_COMM_WORLD, &r);
  return r;
}
int comm_size() {
  int s = 0;
  MPI_Comm_size(PETSC_COMM_WORLD, &s);
  return s;
}

/// The elements of this rank: three nodes each, the first owned here, the others up to two
/// nodes further (on the next rank at the end of this rank's range), in unsorted order.
std::vector<std::vector<PetscInt>> element_dofs() {
  const PetscInt n_nodes = nodes_per_rank * comm_size();
  std::vector<std::vector<PetscInt>> out;
  for (PetscInt k = 0; k < nodes_per_rank; ++k) {
    const PetscInt a = nodes_per_rank * comm_rank() + k;
    const PetscInt nodes[3] = {(a + 2) % n_nodes, a, (a + 1) % n_nodes};
    std::vector<PetscInt> dofs;
    for (PetscInt n : nodes)
      for (PetscInt i = 0; i < bs; ++i) dofs.push_back(n * bs + i);
    out.push_back(dofs);
  }
  return out;
}

/// A matrix of block size 3 whose pattern is that of the elements (explicit zeros), assembled.
Matrix patterned() {
  const PetscInt n_owned = nodes_per_rank * bs, n = n_owned * comm_size();
  std::vector<PetscInt> d_nnz(n_owned, n_owned), o_nnz(n_owned, n - n_owned);
  Matrix m(PETSC_COMM_WORLD, n_owned, d_nnz, o_nnz, bs);
  for (const auto& dofs : element_dofs()) {
    const std::vector<double> zeros(dofs.size() * dofs.size(), 0.0);
    m.add_values(dofs, dofs, zeros);
  }
  m.assemble();
  return m;
}

/// Distinct values for element e (row-major, dofs.size() squared).
std::vector<double> element_values(std::size_t e, std::size_t nd) {
  std::vector<double> v(nd * nd);
  for (std::size_t k = 0; k < v.size(); ++k)
    v[k] = 1.0 + 0.5 * double(e) + 0.01 * double(k) + 100.0 * comm_rank();
  return v;
}

/// max |A - B| entrywise, and max |A|.
std::pair<double, double> difference(const Matrix& A, const Matrix& B) {
  Matrix D = A.copy();
  D.axpy(-1.0, B);
  PetscReal diff = 0, size = 0;
  MatNorm(D.get(), NORM_MAX, &diff);
  MatNorm(A.get(), NORM_MAX, &size);
  return {diff, size};
}

TEST(BlockAdder, SameMatrixAsMatSetValues) {
  Matrix by_entries = patterned(), by_blocks = patterned();
  const auto elements = element_dofs();
  for (int pass = 0; pass < 2; ++pass) { // twice: the values add up
    BlockAdder adder(by_blocks);
    for (std::size_t e = 0; e < elements.size(); ++e) {
      const auto values = element_values(e, elements[e].size());
      by_entries.add_values(elements[e], elements[e], values);
      adder.add(elements[e], values);
    }
    adder.finish();
    by_entries.assemble();
    by_blocks.assemble();
  }
  const auto [diff, size] = difference(by_entries, by_blocks);
  EXPECT_GT(size, 1.0);
  EXPECT_LE(diff, 1e-14 * size);
}

TEST(BlockAdder, DofsOutsideTheNodeLayoutTakeMatSetValues) {
  // A node's dofs swapped (4, 3, 5): not a block of consecutive dofs from a multiple of 3.
  Matrix by_entries = patterned(), by_blocks = patterned();
  auto dofs = element_dofs()[1];
  std::swap(dofs[0], dofs[1]);
  const auto values = element_values(7, dofs.size());
  {
    BlockAdder adder(by_blocks);
    adder.add(dofs, values);
    adder.finish();
  }
  by_entries.add_values(dofs, dofs, values);
  by_entries.assemble();
  by_blocks.assemble();
  const auto [diff, size] = difference(by_entries, by_blocks);
  EXPECT_GT(size, 1.0);
  EXPECT_LE(diff, 1e-14 * size);
}

TEST(BlockAdder, BeforeTheFirstAssemblyEverythingTakesMatSetValues) {
  const PetscInt n_owned = nodes_per_rank * bs, n = n_owned * comm_size();
  std::vector<PetscInt> d_nnz(n_owned, n_owned), o_nnz(n_owned, n - n_owned);
  Matrix by_entries = patterned(), by_blocks(PETSC_COMM_WORLD, n_owned, d_nnz, o_nnz, bs);
  const auto elements = element_dofs();
  {
    BlockAdder adder(by_blocks);
    for (std::size_t e = 0; e < elements.size(); ++e) {
      const auto values = element_values(e, elements[e].size());
      by_entries.add_values(elements[e], elements[e], values);
      adder.add(elements[e], values);
    }
    adder.finish();
  }
  by_entries.assemble();
  by_blocks.assemble();
  const auto [diff, size] = difference(by_entries, by_blocks);
  EXPECT_GT(size, 1.0);
  EXPECT_LE(diff, 1e-14 * size);
}

} // namespace
} // namespace seam::la
