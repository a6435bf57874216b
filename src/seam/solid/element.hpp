#pragma once
// Total-Lagrangian element kernels of the internal forces: residual, consistent tangent,
// strain energy, and element-average Cauchy stress for output.
//
// Layouts: node-major vectors (u[a*dim + i]); element matrices row-major,
// K[(a*dim + i) * n*dim + (b*dim + k)] = d r_{a i} / d u_{b k}.
// Residual convention of seam: r = f_int - f_ext, so this kernel gives +f_int.
// 2D elements have unit thickness.
#include "seam/fem/cell.hpp"
#include "seam/solid/material.hpp"

#include <array>
#include <span>
#include <string_view>

namespace seam::solid {

/// Outcome of a kernel. Anything but `ok` means the outputs are unusable. The kernels never
/// throw for these: the caller reduces the status over ranks (so no rank skips a collective)
/// and then cuts the load step (inverted_current, material_failure) or reports a broken mesh
/// (inverted_reference).
enum class KernelStatus {
  ok,
  inverted_reference, ///< det(dX/dxi) <= 0 at a quadrature point: a tangled or misordered cell
  inverted_current,   ///< det F <= 0 at a quadrature point (hyperelastic models)
  material_failure,   ///< no plane-stress state S33 = 0 could be found
};

/// A short English description of a status, for messages.
std::string_view describe(KernelStatus s);

/// One solid cell. `dim` is the spatial dimension and must equal fem::dimension(cell);
/// `plane` must be none in 3D and plane_strain or plane_stress in 2D. The material is taken
/// as validated (validate() once, when the input is read).
struct ElementInput {
  fem::CellType cell = fem::CellType::hex8;
  int dim = 3;
  PlaneMode plane = PlaneMode::none;
  Material material;
  std::span<const double> X; ///< reference coordinates, n_nodes * dim
  std::span<const double> u; ///< displacements, n_nodes * dim
  int quadrature_degree = 0; ///< <= 0: fem::default_quadrature_degree(cell)
};

struct ElementResult {
  KernelStatus status = KernelStatus::ok;
  double energy = 0.0; ///< strain energy int W dV of the element
};

/// Internal force r_a = int B_a^T S dV (size n*dim) and consistent tangent K = dr/du (size
/// (n*dim)^2, symmetric). Either span may be empty to skip it; both are overwritten.
///
/// Finite-strain models use the total-Lagrangian form (e.g. Bonet & Wood, Nonlinear Continuum
/// Mechanics for FEA, 2008): B_a has rows dE/du_a built with the current F, and
/// K_ab = int B_a^T C B_b dV + int (G_a . S G_b) I dV (material + geometric stiffness),
/// G_a = dN_a/dX.
/// linear_elastic uses F = I in B and no geometric term: the small-strain stiffness.
/// Throws InternalError on inconsistent sizes or modes (a bug of the caller).
ElementResult internal_force(const ElementInput& in, std::span<double> r, std::span<double> K);

/// Element-average Cauchy stress, weighted by current volume (1/v int sigma dv; reference
/// volume for linear_elastic), and the von Mises stress of that average.
struct ElementStress {
  KernelStatus status = KernelStatus::ok;
  std::array<double, 6> cauchy{}; ///< xx, yy, zz, xy, yz, xz (zz is nonzero in plane strain)
  double von_mises = 0.0;
};
ElementStress element_stress(const ElementInput& in);

} // namespace seam::solid
