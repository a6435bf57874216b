#pragma once
// The pressure-space operators of the pressure convection-diffusion (PCD) preconditioner of a
// Taylor-Hood cell (Kay, Loghin & Wathen 2002; Elman, Silvester & Wathen 2014, sec. 9.2): on
// the linear pressure shape functions M_k of the cell's vertices,
//   mass        M_kl = int M_k M_l dx
//   Laplacian   A_kl = int grad M_k . grad M_l dx
//   convection  N_kl = int M_k (c . grad M_l) dx,   c the velocity interpolated from the nodes
// with the geometry of the quadratic cell. Matrices row-major, n_vertices squared. The kernel
// lives in navier_stokes.cpp, whose quadrature-point geometry it shares.
#include "seam/fem/cell.hpp"

#include <span>

namespace seam::fluid {

/// The three operators of one Taylor-Hood cell (tri6, quad9, tet10, hex27) with nodes `x`
/// (n_nodes * dim) and nodal convective velocity `c` (n_nodes * dim); each output
/// n_vertices^2. Returns false if the cell is inverted.
bool pressure_operators(fem::CellType cell, std::span<const double> x, std::span<const double> c,
                        std::span<double> mass, std::span<double> laplacian,
                        std::span<double> convection);

} // namespace seam::fluid
