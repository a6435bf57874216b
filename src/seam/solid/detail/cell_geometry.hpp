#pragma once
// Geometry of a cell at one quadrature point, shared by the kernels of seam::solid.
// Fixed-capacity storage (fem::max_cell_nodes): nothing is allocated per point.
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"

#include <Eigen/Core>
#include <Eigen/LU>
#include <span>

namespace seam::solid::detail {

/// Shape gradients with respect to reference (material) coordinates, one row per node.
template <int D>
using NodalGradients =
    Eigen::Matrix<double, Eigen::Dynamic, D, Eigen::RowMajor, fem::max_cell_nodes, D>;

/// Computes G(a, j) = dN_a/dX_j at reference point xi of a cell of parametric dimension D in
/// D-dimensional space with node coordinates X (node-major). Returns det(dX/dxi); G is left
/// unset when the determinant is not positive.
template <int D>
double reference_gradients(fem::CellType cell, int n, const double* xi, std::span<const double> X,
                           NodalGradients<D>& G) {
  double dN[fem::max_cell_nodes * 3];
  fem::shape_gradients(cell, xi, dN);
  Eigen::Matrix<double, D, D> jac = Eigen::Matrix<double, D, D>::Zero();
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < D; ++k) jac(i, k) += X[a * D + i] * dN[a * D + k];
  }
  const double det = jac.determinant();
  if (!(det > 0.0)) return det;
  const Eigen::Matrix<double, D, D> inv = jac.inverse();
  G.resize(n, D);
  for (int a = 0; a < n; ++a) {
    for (int j = 0; j < D; ++j) {
      double s = 0.0;
      for (int k = 0; k < D; ++k) s += dN[a * D + k] * inv(k, j);
      G(a, j) = s;
    }
  }
  return det;
}

/// det(dX/dxi) only.
template <int D>
double reference_jacobian_det(fem::CellType cell, int n, const double* xi,
                              std::span<const double> X) {
  double dN[fem::max_cell_nodes * 3];
  fem::shape_gradients(cell, xi, dN);
  Eigen::Matrix<double, D, D> jac = Eigen::Matrix<double, D, D>::Zero();
  for (int a = 0; a < n; ++a) {
    for (int i = 0; i < D; ++i)
      for (int k = 0; k < D; ++k) jac(i, k) += X[a * D + i] * dN[a * D + k];
  }
  return jac.determinant();
}

/// Validates the sizes of a cell's coordinate, displacement and output buffers against its
/// type; misuse is a programming error of the caller, reported as InternalError.
inline int checked_n_nodes(fem::CellType cell, int dim, std::size_t n_coords, const char* where) {
  SEAM_CHECK(dim == 2 || dim == 3, InternalError, where, ": dimension must be 2 or 3, got ", dim);
  SEAM_CHECK(fem::dimension(cell) == dim, InternalError, where, ": a ", fem::name(cell),
             " cell is not a ", dim, "D solid cell");
  const int n = fem::n_nodes(cell);
  SEAM_CHECK(n_coords == static_cast<std::size_t>(n * dim), InternalError, where, ": expected ",
             n * dim, " coordinates for a ", fem::name(cell), ", got ", n_coords);
  return n;
}

} // namespace seam::solid::detail
