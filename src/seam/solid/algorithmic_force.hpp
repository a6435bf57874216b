#pragma once
// Element kernel of the energy-momentum method (Simo & Tarnow 1992; Gonzalez 2000): the
// algorithmic internal force of one time step t_n -> t_{n+1} and its derivative with respect to
// u_{n+1}, the unknown of the step's Newton iteration.
//
//   f_alg,a = int B_mid,a^T S_alg dV,   B_mid built with F_mid = (F_n + F_{n+1})/2,
//
// with S_alg from algorithmic_stress() (algorithmic_stress.hpp). Properties, each to round-off
// and independent of the quadrature rule:
//   * energy:           (u_{n+1} - u_n) . f_alg = Pi(u_{n+1}) - Pi(u_n), Pi = int W dV with
//                       the same quadrature as internal_force();
//   * linear momentum:  sum_a f_alg,a = 0;
//   * angular momentum: sum_a x_mid,a x f_alg,a = 0, x_mid = X + (u_n + u_{n+1})/2
//                       (hyperelastic models; linear_elastic is not objective);
//   * consistency:      f_alg(u, u) = internal_force(u), and its tangent is half the
//                       internal_force() tangent there.
// A step of the scheme solves M (v_{n+1} - v_n)/dt + f_alg = f_ext,mid with
// (u_{n+1} - u_n)/dt = (v_n + v_{n+1})/2; the kinetic energy change then cancels the work of
// f_alg exactly.
//
// Layouts as in element.hpp: node-major vectors; K row-major with
// K[(a*dim + i) * n*dim + (b*dim + k)] = d f_alg,ai / d u_{n+1},bk (not symmetric).
#include "seam/fem/cell.hpp"
#include "seam/solid/algorithmic_stress.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/material.hpp"

#include <span>

namespace seam::solid {

/// One solid cell over one time step. Same rules as ElementInput (dim = fem::dimension(cell),
/// plane none in 3D and plane_strain/plane_stress in 2D, material validated).
struct AlgorithmicInput {
  fem::CellType cell = fem::CellType::hex8;
  int dim = 3;
  PlaneMode plane = PlaneMode::none;
  Material material;
  std::span<const double> X;      ///< reference coordinates, n_nodes * dim
  std::span<const double> u_n;    ///< displacements at t_n, n_nodes * dim
  std::span<const double> u_next; ///< displacements at t_{n+1}, n_nodes * dim
  int quadrature_degree = 0;      ///< <= 0: fem::default_quadrature_degree(cell)
  /// Switch of the discrete gradient to S(C_mid); see algorithmic_stress.hpp.
  double threshold = default_discrete_gradient_threshold;
};

struct AlgorithmicResult {
  KernelStatus status = KernelStatus::ok;
  double energy_n = 0.0;    ///< int W(C_n) dV
  double energy_next = 0.0; ///< int W(C_{n+1}) dV
  /// Quadrature points where the strain increment was below the threshold and S(C_mid) was
  /// used instead of the discrete gradient (neo_hooke only).
  int n_midpoint_points = 0;
};

/// Algorithmic internal force f_alg (size n*dim) and its tangent K = d f_alg / d u_{n+1}
/// (size (n*dim)^2):
///   K_ab = int B_mid,a^T A B_{n+1},b dV + 1/2 int (G_a . S_alg G_b) I dV,
/// with A = dS_alg/dE_{n+1}, B_{n+1} built with F_{n+1}, G_a = dN_a/dX; linear_elastic uses
/// B_mid = B_{n+1} = the small-strain B and no geometric term.
/// Either span may be empty to skip it; both are overwritten. Status handling as for
/// internal_force(): a status other than ok leaves the outputs unusable. Throws
/// InternalError on inconsistent sizes or modes (a bug of the caller).
AlgorithmicResult algorithmic_internal_force(const AlgorithmicInput& in, std::span<double> f,
                                             std::span<double> K);

} // namespace seam::solid
