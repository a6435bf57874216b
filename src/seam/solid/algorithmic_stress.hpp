#pragma once
// Algorithmic (discrete-gradient) stress of a time step t_n -> t_{n+1}, the material-point part
// of the energy-momentum method for nonlinear elastodynamics.
//
// The time-stepping scheme (J.C. Simo & N. Tarnow, The discrete energy-momentum method, ZAMP
// 43 (1992) 757-792; O. Gonzalez, Exact energy and momentum conserving algorithms for general
// models in nonlinear elasticity, CMAME 190 (2000) 1763-1783) evaluates the internal force
// at the midpoint configuration with an algorithmic stress S_alg in place of S:
//   f_alg = int B_mid^T S_alg dV,  B_mid built with F_mid = (F_n + F_{n+1}) / 2.
// Because C_{n+1} - C_n = F_mid^T dF + dF^T F_mid exactly (dF = F_{n+1} - F_n), the strain
// increment dE = (C_{n+1} - C_n)/2 is B_mid (u_{n+1} - u_n), and
//   (u_{n+1} - u_n) . f_alg = int S_alg : dE dV.
// A stress with the directionality property S_alg : dE = W(C_{n+1}) - W(C_n) at every
// quadrature point therefore makes the element work over the step equal to the change of the
// strain energy, which is what conserves the total energy of the integrator. S_alg is
// symmetric, so F_mid S_alg F_mid^T is symmetric and the scheme also conserves angular
// momentum (about x_mid = X + (u_n + u_{n+1})/2).
//
// The stresses used per model (derivation in algorithmic_stress.cpp):
//   linear_elastic          sigma(eps_mid): the midpoint rule, exact for a quadratic energy.
//   saint_venant_kirchhoff  (S(E_n) + S(E_{n+1}))/2 (Simo & Tarnow 1992): S is linear in E,
//                           so this equals S(E_mid) and has the directionality property.
//   neo_hooke               Gonzalez's discrete gradient (usable for any W(C)):
//                             S_alg = S(C_mid) + [W_{n+1} - W_n - S(C_mid):dE] dE / (dE:dE),
//                           C_mid = (C_n + C_{n+1})/2; S(C_mid) alone when
//                           |dC| <= threshold |C_mid| (the correction is O(|dC|^2) there).
//
// Conventions as in material.hpp: Voigt order (11, 22, 33, 12, 23, 13), engineering shears in
// strains; in 2D only the in-plane components are meaningful, and in plane stress W is the
// energy with S33 = 0 enforced, a function of the in-plane C alone.
#include "seam/solid/material.hpp"

#include <Eigen/Core>

namespace seam::solid {

/// Relative increment |C_{n+1} - C_n|_F / |C_mid|_F at or below which the discrete gradient
/// is replaced by S(C_mid). The correction is computed from W_{n+1} - W_n, whose round-off
/// (~ eps_mach |CC|) does not shrink with the increment: just above the switch it perturbs the
/// stress by ~ eps_mach |CC| / |dE| (~1e-12 |CC|) and the tangent by ~ eps_mach |CC| / |dE|^2
/// (~1e-8 |CC|). Just below, the omitted correction is O(|CC| |dE|^2) (~1e-8 |CC|) and the
/// directionality defect O(|CC| |dE|^3), ~1e-8 of the step's energy change.
inline constexpr double default_discrete_gradient_threshold = 1e-4;

/// The algorithmic stress of a material point over one time step.
struct AlgorithmicStress {
  /// S_alg (2nd Piola–Kirchhoff; sigma for linear_elastic). Symmetric. In 2D only the
  /// in-plane block is meaningful.
  Eigen::Matrix3d stress;
  /// dS_alg/dE_{n+1} in Voigt form (rows: stress components, columns: strain components with
  /// engineering shears), E_n held fixed. Not symmetric in general. In 2D only the in-plane
  /// rows and columns {0, 1, 3} are meaningful; in plane stress it is the condensed tangent.
  Matrix6 tangent;
  double energy_n = 0.0;    ///< W(C_n)
  double energy_next = 0.0; ///< W(C_{n+1})
  /// true when the increment was at or below the threshold and S_alg = S(C_mid) was used
  /// (neo_hooke only).
  bool midpoint = false;
};

/// Evaluates the algorithmic stress between deformation gradients F_n and F_next (= F_{n+1};
/// for linear_elastic the "F" is I + grad u, as in evaluate()). In 2D modes only the in-plane
/// blocks are read. `tangent` is computed only when `with_tangent` is true. Returns the first
/// status other than ok met while evaluating the material at F_n, F_{n+1} or C_mid.
PointStatus algorithmic_stress(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F_n,
                               const Eigen::Matrix3d& F_next, AlgorithmicStress& out,
                               bool with_tangent = true,
                               double threshold = default_discrete_gradient_threshold);

} // namespace seam::solid
