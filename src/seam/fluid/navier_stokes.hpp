#pragma once
// Element kernel of the steady incompressible Navier-Stokes equations for a Newtonian fluid on
// a fixed mesh, in the Taylor-Hood discretization: the velocity on all nodes of a quadratic
// cell (tri6, quad9, tet10, hex27), the pressure on its vertices, interpolated linearly
// (P2/P1, Q2/Q1; inf-sup stable, Brezzi & Fortin 1991, sec. VI.6).
//
// Weak form (gradient, or "Laplace", form of the viscous term, which for constant viscosity
// and div u = 0 equals the symmetric one in the interior and makes the boundary without a
// condition a "do nothing" outflow, (mu grad u - p I) n = 0, Heywood, Rannacher & Turek 1996):
//   r_{a i} = int rho N_a (u . grad) u_i + mu grad N_a . grad u_i - p dN_a/dx_i - N_a f_i dx
//   r_k     = - int M_k div u dx
// with N_a the velocity and M_k the pressure shape functions. The Stokes part of the
// Jacobian is symmetric; the convective part is linearized in full (Newton).
//
// Linear cells (tri3, quad4, tet4, hex8) use equal-order velocity and pressure with the
// residual-based PSPG/SUPG/LSIC stabilization of navier_stokes.cpp.
//
// Layout of the element vector: the velocity node-major (a * dim + i) for all n nodes, then
// the pressure of the n_p vertices; matrices row-major, K[row * n_dofs + col].
// On a moving mesh (ALE, arbitrary Lagrangian-Eulerian; Donea, Huerta, Ponthot &
// Rodriguez-Ferran 2004, Encyclopedia of Computational Mechanics ch. 14; the convective form) `x`
// is the current configuration, the time derivative is the one at a fixed mesh point and the
// convective velocity is c = u - w with w the mesh velocity: (u . grad) u becomes (c . grad) u, in
// the Galerkin term and in the stabilization (SUPG direction, tau). K is exact in (u, p) at the
// given mesh motion; the derivatives by the mesh position and velocity (shape derivatives) come
// from navier_stokes_mesh_derivatives. Residual convention of seam: r = f_int - f_ext. With time
// integration the residual gains int rho N_a du_i/dt (Jansen, Whiting & Hulbert 2000: velocity and
// pressure at n + alpha_f, the velocity's rate at n + alpha_m; the weights of the Jacobian come in
// with the input).
#include "seam/fem/cell.hpp"

#include <array>
#include <functional>
#include <span>

namespace seam::fluid {

struct Fluid {
  double density = 1.0;   ///< rho > 0
  double viscosity = 1.0; ///< dynamic viscosity mu > 0
};

/// The cell of the pressure: the linear cell of a Taylor-Hood cell (tri6 -> tri3, quad9 ->
/// quad4, tet10 -> tet4, hex27 -> hex8), a linear cell itself (equal order). Throws InputError
/// for any other cell type, naming it.
fem::CellType pressure_cell(fem::CellType velocity_cell);
/// Whether `cell` is a Taylor-Hood velocity cell (tri6, quad9, tet10, hex27).
bool is_taylor_hood(fem::CellType cell);
/// Whether `cell` is a linear cell with equal-order velocity and pressure and residual-based
/// stabilization (tri3, quad4, tet4, hex8).
bool is_stabilized(fem::CellType cell);

/// Body force per unit volume at the physical point x (dim values written to `value`).
using BodyForce = std::function<void(const double* x, double* value)>;

struct FluidElementInput {
  fem::CellType cell = fem::CellType::quad9;
  int dim = 2; ///< fem::dimension(cell)
  Fluid fluid;
  std::span<const double> x;             ///< node coordinates, n_nodes * dim
  std::span<const double> u;             ///< nodal velocity, n_nodes * dim
  std::span<const double> p;             ///< vertex pressure, n_vertices
  const BodyForce* body_force = nullptr; ///< optional
  /// Unsteady flow (time integration): the nodal time derivative of the velocity, n_nodes *
  /// dim, adding int rho N_a du_i/dt to r_{a i}; empty for steady flow.
  std::span<const double> u_dot;
  /// ALE: the nodal mesh velocity w, n_nodes * dim; empty for a fixed mesh (w = 0).
  std::span<const double> mesh_velocity;
  /// The derivative of the state (u, p) and of u_dot by the unknowns: K is
  /// d r/d(u, p) * state_weight, plus M * mass_weight in the velocity block with M_ab =
  /// int rho N_a N_b (generalized-alpha: alpha_f and alpha_m / (gamma dt)).
  double state_weight = 1.0;
  double mass_weight = 0.0;
  /// The time step, for the stabilization of linear cells (0: steady flow).
  double time_step = 0.0;
  /// The consistent initial state of time integration: K is the derivative by (u_dot, p) at
  /// the given u (state_weight 0: mass_weight * M in the velocity block, the pressure columns
  /// with weight 1). On Taylor-Hood cells the continuity rows become the time derivative of
  /// the constraint, - int M_k div u_dot = 0 (residual and K by u_dot). On stabilized cells
  /// they are the PSPG-stabilized continuity equation itself, which holds u_dot and p.
  bool initial_rate = false;
};

/// Number of element dofs: n_nodes * dim + n_vertices.
int n_element_dofs(fem::CellType cell);

/// Residual (size n_element_dofs) and Jacobian (its square, or empty to skip). Returns false
/// if the cell is inverted (det J <= 0 at a quadrature point); the outputs are then unusable.
bool navier_stokes(const FluidElementInput& in, std::span<double> r, std::span<double> K);

/// The shape derivatives of a moving mesh: the derivatives of the residual by the node
/// coordinates x (`by_position`) and by the mesh velocity w (`by_velocity`), at fixed (u, p,
/// u_dot); each row-major n_element_dofs x (n_nodes * dim), or empty to skip. Exact (forward-mode
/// automatic differentiation of the residual), except that a position-dependent body force
/// enters by central differences of its expression. An empty `mesh_velocity` is w = 0. Returns
/// false if the cell is inverted.
bool navier_stokes_mesh_derivatives(const FluidElementInput& in, std::span<double> by_position,
                                    std::span<double> by_velocity);

/// Integrals over one cell for an energy budget of the flow (docs/fsi.md, "Energy budget"),
/// with the residual's quadrature, at in.x, in.u and in.mesh_velocity w (empty: w = 0):
/// the kinetic energy 1/2 int rho |u|^2, the dissipation rate int mu grad u : grad u (of the
/// gradient form of the viscous term), the convective power int rho ((u - w) . grad u) . u and
/// the mesh's transport 1/2 int rho |u|^2 div w. With u as test function the Taylor-Hood
/// residual gives: the power of the reactions = int rho du/dt . u + convection + dissipation.
struct EnergyIntegrals {
  double kinetic = 0.0, dissipation = 0.0, convection = 0.0, mesh_transport = 0.0;
};
EnergyIntegrals energy_integrals(const FluidElementInput& in);

/// Integrals over one cell for the L2 errors against exact fields, with a rule two degrees
/// above the residual's: {int |u_h - u|^2, int (p_h - p)^2, int (p_h - p), |cell|}. The last
/// two let a caller remove the constant by which an enclosed flow's pressure is undetermined:
/// ||e - mean e||^2 = int e^2 - (int e)^2 / |domain|.
using ExactVelocity = std::function<void(const double* x, double* value)>;
using ExactPressure = std::function<double(const double* x)>;
std::array<double, 4> error_integrals(const FluidElementInput& in, const ExactVelocity& u,
                                      const ExactPressure& p);

} // namespace seam::fluid
