#pragma once
// Kernels of the moving fluid mesh (ALE), without PETSc: the Jacobian-based stiffening of the
// pseudo-elastic mesh, the check that a cell has not inverted, and the mesh position and
// velocity of a generalized-alpha step.
//
// The pseudo-elastic mesh (Stein, Tezduyar & Benney 2003, J. Appl. Mech. 70, 58-63) is linear
// elasticity on the reference mesh, driven by the boundary's displacement, with the Young's
// modulus of cell e scaled by (V_min / V_e)^chi, V_e the reference volume of the cell and
// V_min the smallest of them: small cells (at walls, in boundary layers) are stiffer and keep
// their shape, the large ones far away take up the deformation. chi = 0 is uniform
// elasticity; Stein et al. find chi = 1 .. 2 effective.
#include "seam/fem/cell.hpp"
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::ale {

/// Per listed cell: (V_min / V_e)^power, with V the reference volumes and V_min the smallest
/// over `cells`, or `smallest` if positive (the smallest over the cells of all ranks of a
/// distributed mesh). All 1 for power 0.
std::vector<double> jacobian_stiffening(const mesh::Mesh& mesh, std::span<const std::int32_t> cells,
                                        double power, double smallest = 0.0);

/// Whether a cell with node coordinates x (n_nodes * dim) has det J <= 0 at a point of the
/// fluid kernel's quadrature rule (degree 3 * order) or at a vertex.
bool inverted(fem::CellType type, std::span<const double> x);

/// Generalized-alpha for first-order systems (Jansen, Whiting & Hulbert 2000): second order
/// with gamma = 1/2 + alpha_m - alpha_f.
struct GeneralizedAlpha {
  double alpha_m = 1.0, alpha_f = 1.0, gamma = 1.0;
  static GeneralizedAlpha from_rho_inf(double rho_inf);
};

/// The mesh in a step t_n -> t_n + h of the fluid's generalized-alpha: the rate of the mesh
/// displacement by the integrator's own recursion (JWH eq. 17),
///   d_dot_{n+1} = (d_{n+1} - d_n) / (gamma h) - (1 - gamma) / gamma d_dot_n,
/// the configuration x = X + d_{n+alpha_f} on which the step's integrals are taken and the
/// mesh velocity w = d_dot_{n+alpha_m}: the same intermediate states as the fluid velocity and
/// its rate, so that u - w in the convective term is second order at t_{n+alpha_f}. All
/// arrays node-major, of one size.
void step_mesh(const GeneralizedAlpha& ga, double h, std::span<const double> X,
               std::span<const double> d_old, std::span<const double> d_new,
               std::span<const double> d_dot_old, std::span<double> x, std::span<double> w,
               std::span<double> d_dot_new);

} // namespace seam::ale
