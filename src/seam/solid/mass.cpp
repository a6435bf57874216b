#include "seam/solid/mass.hpp"

#include "seam/common/error.hpp"
#include "seam/solid/detail/cell_geometry.hpp"

#include <Eigen/Core>
#include <algorithm>

namespace seam::solid {

namespace {

bool is_simplex(fem::CellType t) {
  using fem::CellType;
  return t == CellType::tri3 || t == CellType::tri6 || t == CellType::tet4 || t == CellType::tet10;
}

// Scalar mass matrix m_ab = density int N_a N_b dV into `m` (n x n, row-major).
template <int D>
KernelStatus scalar_mass(fem::CellType cell, int n, std::span<const double> X, double density,
                         int degree, double* m) {
  std::fill(m, m + n * n, 0.0);
  const fem::QuadratureRule rule = fem::quadrature(cell, degree);
  double N[fem::max_cell_nodes];
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = &rule.points[q * D];
    const double detJ = detail::reference_jacobian_det<D>(cell, n, xi, X);
    if (!(detJ > 0.0)) return KernelStatus::inverted_reference;
    fem::shape_values(cell, xi, N);
    const double w = density * rule.weights[q] * detJ;
    for (int a = 0; a < n; ++a)
      for (int b = a; b < n; ++b) m[a * n + b] += w * N[a] * N[b];
  }
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < a; ++b) m[a * n + b] = m[b * n + a]; // exactly symmetric
  return KernelStatus::ok;
}

KernelStatus scalar_mass(fem::CellType cell, int dim, std::span<const double> X, double density,
                         int degree, double* m, int& n) {
  n = detail::checked_n_nodes(cell, dim, X.size(), "solid::mass");
  if (degree <= 0) degree = mass_quadrature_degree(cell);
  return dim == 3 ? scalar_mass<3>(cell, n, X, density, degree, m)
                  : scalar_mass<2>(cell, n, X, density, degree, m);
}

} // namespace

int mass_quadrature_degree(fem::CellType cell) {
  // Simplices: affine map, constant Jacobian. Tensor cells: det(dX/dxi) of a multilinear map
  // has degree dim - 1 per direction (x order of the geometry).
  const int p = fem::order(cell);
  if (is_simplex(cell)) return 2 * p;
  return 2 * p + p * (fem::dimension(cell) - 1);
}

KernelStatus consistent_mass(fem::CellType cell, int dim, std::span<const double> X, double density,
                             std::span<double> M, int quadrature_degree) {
  double m[fem::max_cell_nodes * fem::max_cell_nodes];
  int n = 0;
  const KernelStatus st = scalar_mass(cell, dim, X, density, quadrature_degree, m, n);
  const std::size_t nd = static_cast<std::size_t>(n * dim);
  SEAM_CHECK(M.size() == nd * nd, InternalError, "solid::consistent_mass: buffer needs ", nd * nd,
             " values, got ", M.size());
  if (st != KernelStatus::ok) return st;
  std::fill(M.begin(), M.end(), 0.0);
  for (int a = 0; a < n; ++a)
    for (int b = 0; b < n; ++b)
      for (int i = 0; i < dim; ++i) M[(a * dim + i) * nd + b * dim + i] = m[a * n + b];
  return KernelStatus::ok;
}

KernelStatus lumped_mass(fem::CellType cell, int dim, std::span<const double> X, double density,
                         std::span<double> lumped, Lumping scheme, int quadrature_degree) {
  double m[fem::max_cell_nodes * fem::max_cell_nodes];
  int n = 0;
  const KernelStatus st = scalar_mass(cell, dim, X, density, quadrature_degree, m, n);
  SEAM_CHECK(lumped.size() == static_cast<std::size_t>(n * dim), InternalError,
             "solid::lumped_mass: buffer needs ", n * dim, " values, got ", lumped.size());
  if (st != KernelStatus::ok) return st;
  double total = 0.0, diagonal = 0.0;
  for (int a = 0; a < n; ++a) {
    for (int b = 0; b < n; ++b) total += m[a * n + b];
    diagonal += m[a * n + a];
  }
  for (int a = 0; a < n; ++a) {
    double value = 0.0;
    if (scheme == Lumping::row_sum) {
      for (int b = 0; b < n; ++b) value += m[a * n + b];
    } else {
      value = diagonal > 0.0 ? m[a * n + a] * total / diagonal : 0.0;
    }
    for (int i = 0; i < dim; ++i) lumped[a * dim + i] = value;
  }
  return KernelStatus::ok;
}

} // namespace seam::solid
