#pragma once
// The pressure-space operators of the pressure convection-diffusion (PCD) preconditioner of a
// Taylor-Hood cell (Kay, Loghin & Wathen 2002; Elman, Silvester & Wathen 2014, sec. 9.2): on
// the linear pressure shape functions M_k of the cell's vertices,
//   mass        M_kl = int M_k M_l dx
//   Laplacian   A_kl = int grad M_k . grad M_l dx
//   convection  N_kl = int M_k (c . grad M_l) dx,   c = u - w interpolated from the nodes
// with the geometry of the quadratic cell. On a moving mesh (ALE) `x` is the current configuration
// and c the convective velocity u - w of the momentum equations (w the mesh velocity): a fluid
// moving with its mesh has no convection, as in fluid::navier_stokes. Matrices row-major,
// n_vertices squared. The kernel lives in navier_stokes.cpp, whose quadrature-point geometry it
// shares.
#include "seam/fem/cell.hpp"

#include <span>

namespace seam::fluid {

/// The three operators of one Taylor-Hood cell (tri6, quad9, tet10, hex27) with nodes `x`
/// (n_nodes * dim), nodal fluid velocity `u` and mesh velocity `w` (n_nodes * dim each; `w`
/// empty: a fixed mesh, w = 0), convecting with c = u - w; each output n_vertices^2. Returns
/// false if the cell is inverted.
bool pressure_operators(fem::CellType cell, std::span<const double> x, std::span<const double> u,
                        std::span<const double> w, std::span<double> mass,
                        std::span<double> laplacian, std::span<double> convection);

} // namespace seam::fluid
