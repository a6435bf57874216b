#include "seam/solid/algorithmic_stress.hpp"

#include <Eigen/Cholesky>
#include <Eigen/LU>
#include <array>
#include <cmath>

// Derivation of the discrete gradient (Gonzalez 2000, CMAME 190; written in terms of E = (C-I)/2,
// dE = E_{n+1} - E_n, E_mid = (E_n + E_{n+1})/2, ":" the full tensor contraction).
//
// Wanted: a symmetric S_alg(E_n, E_{n+1}) with
//   (i)  directionality  S_alg : dE = W(E_{n+1}) - W(E_n)  for every pair of states,
//   (ii) consistency     S_alg -> S(E_mid) = dW/dE(E_mid) as dE -> 0.
// Take S(E_mid) and add the multiple of dE that removes its defect in (i):
//   S_alg = S(E_mid) + phi dE / (dE:dE),   phi = W(E_{n+1}) - W(E_n) - S(E_mid):dE.
// Proof of (i): S_alg:dE = S(E_mid):dE + phi (dE:dE)/(dE:dE) = W(E_{n+1}) - W(E_n), an
// algebraic identity, so it holds to round-off whatever W is. Proof of (ii): phi is the error
// of the midpoint rule for W(E_{n+1}) - W(E_n) = int_0^1 S(E_n + t dE):dE dt, so
// phi = O(|dE|^3) and the correction is O(|dE|^2). In terms of C (dC = 2 dE, S = 2 dW/dC) this
// is S_alg = 2 dW/dC(C_mid) + 2 [W_{n+1} - W_n - dW/dC(C_mid):dC] dC/(dC:dC), the form in
// ALGORITHMS.md Sec. 7. S_alg is a function of the Green strains only, so it is unchanged by
// superposed rigid rotations (objective), and symmetric (angular momentum).
//
// For a quadratic W (St. Venant–Kirchhoff, and the small-strain model in eps) phi = 0
// identically: W(E_{n+1}) - W(E_n) = (E_{n+1} - E_n):CC:(E_{n+1} + E_n)/2 = dE:S(E_mid). The
// correction is then pure round-off divided by |dE|^2, so those models use S(E_mid)
// = (S_n + S_{n+1})/2 directly (Simo & Tarnow 1992).
//
// Plane stress: the energy returned by evaluate() is W2(C_2D) = W(C_2D, C33*) with C33* the
// solution of S33 = 0; by the envelope theorem dW2/dE_2D = S_2D. The construction above is
// applied to W2 and the in-plane tensors, and S(C_mid) is the plane-stress stress at the
// in-plane C_mid (which need not be the average of the two thickness stretches).
//
// Linearization with respect to E_{n+1} (E_n fixed; dE_mid = dE_{n+1}/2, CC_mid = dS/dE at
// E_mid, S_{n+1} = S(E_{n+1}), q = dE:dE):
//   d phi = (S_{n+1} - S(E_mid) - CC_mid:dE/2) : dE_{n+1},   d q = 2 dE : dE_{n+1},
//   d S_alg = [CC_mid/2 + dE (x) ((S_{n+1} - S(E_mid) - CC_mid:dE/2)/q - 2 phi/q^2 dE)
//             + (phi/q) II] : dE_{n+1}.

namespace seam::solid {

namespace {

// Voigt component k is the tensor pair (vi[k], vj[k]).
constexpr std::array<int, 6> vi = {0, 1, 2, 0, 1, 0};
constexpr std::array<int, 6> vj = {0, 1, 2, 1, 2, 2};

Vector6 stress_voigt(const Eigen::Matrix3d& S) {
  Vector6 s;
  for (int k = 0; k < 6; ++k) s(k) = S(vi[k], vj[k]);
  return s;
}

// The deformation gradient as the mode reads it: in 2D the in-plane block with F33 = 1, so
// that C = F^T F has C33 = 1 and no out-of-plane shear (the material resets F33 itself).
Eigen::Matrix3d in_plane(PlaneMode mode, const Eigen::Matrix3d& F) {
  if (mode == PlaneMode::none) return F;
  Eigen::Matrix3d F2 = Eigen::Matrix3d::Identity();
  F2.topLeftCorner<2, 2>() = F.topLeftCorner<2, 2>();
  return F2;
}

// W(F1) - W(F0) of the Neo-Hookean law (3D or plane strain: F33 = 1 in both) for
// F1 = F0 + dF, written so that no two O(mu) energies are subtracted: tr C changes by
// 2 tr dE, and ln J by log1p(det(I + A) - 1) with A = dF F0^-1, where
// det(I + A) - 1 = tr A + ((tr A)^2 - tr(A^2))/2 + det A exactly (3 x 3). Subtracting the two
// energies instead leaves a round-off error of about eps mu per point, which phi / (dE:dE)
// turns into a stress error of eps mu / |dE|: a floor of the Newton residual near 1e-9 on a
// block sliding almost rigidly.
double neo_hooke_energy_change(const Material& m, const Eigen::Matrix3d& F0,
                               const Eigen::Matrix3d& dF, const Eigen::Matrix3d& dE) {
  const Eigen::Matrix3d A = dF * F0.inverse();
  const double trA = A.trace();
  const double dlnJ = std::log1p(trA + 0.5 * (trA * trA - (A * A).trace()) + A.determinant());
  const double lnJ0 = std::log(F0.determinant());
  return m.mu() * (dE.trace() - dlnJ) + 0.5 * m.lambda() * dlnJ * (2.0 * lnJ0 + dlnJ);
}

} // namespace

PointStatus algorithmic_stress(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F_n,
                               const Eigen::Matrix3d& F_next, AlgorithmicStress& out,
                               bool with_tangent, double threshold) {
  const Eigen::Matrix3d F0 = in_plane(mode, F_n), F1 = in_plane(mode, F_next);
  out.midpoint = false;
  PointResponse r0, r1, rm;

  if (m.model == MaterialModel::linear_elastic) {
    // Midpoint rule: sigma is linear in eps, so sigma(eps_mid) = (sigma_n + sigma_{n+1})/2.
    PointStatus st = evaluate(m, mode, F0, r0, false);
    if (st == PointStatus::ok) st = evaluate(m, mode, F1, r1, false);
    if (st == PointStatus::ok) st = evaluate(m, mode, 0.5 * (F0 + F1), rm, with_tangent);
    if (st != PointStatus::ok) return st;
    out.energy_n = r0.energy;
    out.energy_next = r1.energy;
    out.stress = rm.stress;
    if (with_tangent) out.tangent = 0.5 * rm.tangent;
    return PointStatus::ok;
  }

  PointStatus st = evaluate(m, mode, F0, r0, false);
  // St. Venant–Kirchhoff takes its (constant) tangent from the end point.
  const bool svk = m.model == MaterialModel::saint_venant_kirchhoff;
  if (st == PointStatus::ok) st = evaluate(m, mode, F1, r1, with_tangent && svk);
  if (st != PointStatus::ok) return st;
  out.energy_n = r0.energy;
  out.energy_next = r1.energy;

  if (svk) {
    out.stress = 0.5 * (r0.stress + r1.stress);
    if (with_tangent) out.tangent = 0.5 * r1.tangent; // CC is constant
    return PointStatus::ok;
  }

  // General hyperelastic law: the discrete gradient. The exact identity
  // C_{n+1} - C_n = F_mid^T dF + dF^T F_mid gives the increment without subtracting two
  // O(1) tensors.
  const Eigen::Matrix3d Fm = 0.5 * (F0 + F1), dF = F1 - F0;
  const Eigen::Matrix3d dE = 0.5 * (Fm.transpose() * dF + dF.transpose() * Fm);
  const Eigen::Matrix3d Cm = 0.5 * (F0.transpose() * F0 + F1.transpose() * F1);

  // W and S depend on C only: any F with F^T F = C_mid will do, e.g. the transposed Cholesky
  // factor (upper triangular, det > 0). C_mid is SPD as the mean of two SPD tensors.
  const Eigen::LLT<Eigen::Matrix3d> llt(Cm);
  if (llt.info() != Eigen::Success) return PointStatus::inverted;
  const Eigen::Matrix3d Um = llt.matrixU();
  st = evaluate(m, mode, Um, rm, with_tangent);
  if (st != PointStatus::ok) return st;

  const int nc = mode == PlaneMode::none ? 3 : 2;
  const double dC_norm = 2.0 * dE.topLeftCorner(nc, nc).norm();
  const double Cm_norm = Cm.topLeftCorner(nc, nc).norm();
  if (dC_norm <= threshold * Cm_norm) {
    out.midpoint = true;
    out.stress = rm.stress;
    if (with_tangent) out.tangent = 0.5 * rm.tangent;
    return PointStatus::ok;
  }

  // e: Voigt strain increment (engineering shears); n: the same tensor with stress-like
  // components, so that n.e = dE:dE and s.e = S:dE for any stress s.
  const Vector6 n = stress_voigt(dE);
  Vector6 e = n;
  e.tail<3>() *= 2.0;
  const Vector6 s_mid = stress_voigt(rm.stress);
  const double q = n.dot(e);
  const double dW = m.model == MaterialModel::neo_hooke && mode != PlaneMode::plane_stress
                        ? neo_hooke_energy_change(m, F0, dF, dE)
                        : r1.energy - r0.energy;
  const double phi = dW - s_mid.dot(e);
  out.stress = rm.stress + (phi / q) * dE;
  if (!with_tangent) return PointStatus::ok;

  const Vector6 dphi = stress_voigt(r1.stress) - s_mid - 0.5 * rm.tangent * e;
  out.tangent = 0.5 * rm.tangent + n * (dphi / q - (2.0 * phi / (q * q)) * n).transpose();
  // d n / d e = diag(1, 1, 1, 1/2, 1/2, 1/2): engineering shears to tensor components.
  for (int k = 0; k < 6; ++k) out.tangent(k, k) += (k < 3 ? 1.0 : 0.5) * phi / q;
  return PointStatus::ok;
}

} // namespace seam::solid
