#pragma once
// The true residual of a linear solve, for the unit tests of la::LinearSolver
// (test_kept_factorization.cpp, test_factor_ordering.cpp).
#include "seam/la/petsc.hpp"

namespace seam::la::testing {

/// |A x - b| / |b|.
inline double relative_residual(const Matrix& A, const Vector& x, const Vector& b) {
  Vector y = b.duplicate();
  A.mult(x, y);
  y.axpy(-1.0, b);
  return y.norm() / b.norm();
}

} // namespace seam::la::testing
