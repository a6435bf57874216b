#pragma once
// Element mass matrices.
#include "seam/fem/cell.hpp"
#include "seam/solid/element.hpp"

#include <span>

namespace seam::solid {

/// Quadrature degree used for mass matrices when none is given: N_a N_b (degree 2 * order)
/// times det(dX/dxi) of an affine simplex or of a multilinear tensor cell, so that the mass
/// of straight-sided cells is integrated exactly.
int mass_quadrature_degree(fem::CellType cell);

/// Consistent mass M_(ai)(bk) = delta_ik density int N_a N_b dV, (n*dim)^2 values, row-major
/// (overwritten). X: reference coordinates, n_nodes * dim.
KernelStatus consistent_mass(fem::CellType cell, int dim, std::span<const double> X, double density,
                             std::span<double> M, int quadrature_degree = 0);

enum class Lumping {
  row_sum, ///< m_a = sum_b M_ab; zero or negative corner masses for tri6, tet10, quad8, hex20
  diagonal_scaling, ///< Hinton, Rock & Zienkiewicz (1976): M_aa scaled to the total mass; positive
};

/// Lumped (diagonal) mass, n*dim values (overwritten), the same for each component of a node.
KernelStatus lumped_mass(fem::CellType cell, int dim, std::span<const double> X, double density,
                         std::span<double> m, Lumping scheme = Lumping::row_sum,
                         int quadrature_degree = 0);

} // namespace seam::solid
