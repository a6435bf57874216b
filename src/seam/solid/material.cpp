#include "seam/solid/material.hpp"

#include "seam/common/error.hpp"

#include <Eigen/LU>
#include <array>
#include <cmath>

namespace seam::solid {

namespace {

// Voigt component k is the tensor pair (vi[k], vj[k]).
constexpr std::array<int, 6> vi = {0, 1, 2, 0, 1, 0};
constexpr std::array<int, 6> vj = {0, 1, 2, 1, 2, 2};

// Linear elasticity and St. Venant–Kirchhoff share the law S = lambda tr(E) I + 2 mu E; they
// differ only in the strain measure.
void isotropic_linear_law(double lambda, double mu, const Eigen::Matrix3d& E, PointResponse& out,
                          bool with_tangent) {
  const double trE = E.trace();
  out.energy = 0.5 * lambda * trE * trE + mu * E.squaredNorm();
  out.stress = lambda * trE * Eigen::Matrix3d::Identity() + 2.0 * mu * E;
  if (!with_tangent) return;
  out.tangent.setZero();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) out.tangent(a, b) = lambda;
    out.tangent(a, a) = lambda + 2.0 * mu;
    out.tangent(a + 3, a + 3) = mu;
  }
}

// Neo-Hooke, W = mu/2 (tr C - 3) - mu ln J + lambda/2 (ln J)^2:
//   S = mu (I - C^-1) + lambda ln J C^-1,
//   dS/dE = lambda C^-1 (x) C^-1 + (mu - lambda ln J) (C^-1_IK C^-1_JL + C^-1_IL C^-1_JK)
// (Bonet & Wood, Nonlinear Continuum Mechanics for Finite Element Analysis, 2nd ed. 2008,
// Sec. 6.4.3, compressible neo-Hookean material).
PointStatus neo_hooke_law(double lambda, double mu, const Eigen::Matrix3d& F, PointResponse& out,
                          bool with_tangent) {
  const double J = F.determinant();
  if (!(J > 0.0)) return PointStatus::inverted;
  const Eigen::Matrix3d C = F.transpose() * F;
  const Eigen::Matrix3d Ci = C.inverse();
  const double lnJ = std::log(J);
  out.energy = 0.5 * mu * (C.trace() - 3.0) - mu * lnJ + 0.5 * lambda * lnJ * lnJ;
  out.stress = mu * (Eigen::Matrix3d::Identity() - Ci) + lambda * lnJ * Ci;
  if (!with_tangent) return PointStatus::ok;
  const double c = mu - lambda * lnJ;
  for (int a = 0; a < 6; ++a) {
    const int I = vi[a], Jj = vj[a];
    for (int b = 0; b < 6; ++b) {
      const int K = vi[b], L = vj[b];
      out.tangent(a, b) =
          lambda * Ci(I, Jj) * Ci(K, L) + c * (Ci(I, K) * Ci(Jj, L) + Ci(I, L) * Ci(Jj, K));
    }
  }
  return PointStatus::ok;
}

PointStatus evaluate_3d(const Material& m, const Eigen::Matrix3d& F, PointResponse& out,
                        bool with_tangent) {
  const double lambda = m.lambda(), mu = m.mu();
  switch (m.model) {
  case MaterialModel::linear_elastic: {
    const Eigen::Matrix3d H = F - Eigen::Matrix3d::Identity();
    isotropic_linear_law(lambda, mu, 0.5 * (H + H.transpose()), out, with_tangent);
    return PointStatus::ok;
  }
  case MaterialModel::saint_venant_kirchhoff: {
    if (!(F.determinant() > 0.0)) return PointStatus::inverted;
    const Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
    isotropic_linear_law(lambda, mu, E, out, with_tangent);
    return PointStatus::ok;
  }
  case MaterialModel::neo_hooke:
    return neo_hooke_law(lambda, mu, F, out, with_tangent);
  }
  return PointStatus::ok;
}

// Out-of-plane stretch of a neo-Hookean point in plane stress. With F3a = Fa3 = 0, S33 = 0 is
// equivalent to h(s) = mu (exp(2 s) - 1) + lambda (ln J2 + s) = 0, s = ln F33, J2 = det F_2D.
// h is convex (h'' = 4 mu exp(2s) > 0), and h'(0) = 2 mu + lambda > 0 for any admissible
// Poisson ratio, so Newton's method started at s = 0 converges monotonically (after at most
// one overshoot) to the largest root, the one with dS33/dE33 = h'/C33^2 > 0.
bool neo_hooke_plane_stress_stretch(double lambda, double mu, double J2, double& F33) {
  const double lnJ2 = std::log(J2);
  double s = 0.0;
  for (int it = 0; it < 60; ++it) {
    const double e2s = std::exp(2.0 * s);
    const double h = mu * (e2s - 1.0) + lambda * (lnJ2 + s);
    const double dh = 2.0 * mu * e2s + lambda;
    if (!(dh > 0.0)) return false; // left the stable branch: no physical root exists
    const double step = h / dh;
    s -= step;
    if (std::abs(step) <= 1e-15 * (1.0 + std::abs(s))) {
      F33 = std::exp(s);
      return std::isfinite(F33);
    }
  }
  return false;
}

// Static condensation of the 33 component: with S33 = 0 held, dE33 = -C_3b dE_b / C_33.
void condense_plane_stress(Matrix6& C) {
  constexpr std::array<int, 3> in_plane = {0, 1, 3};
  Eigen::Matrix3d reduced;
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) {
      const int p = in_plane[a], q = in_plane[b];
      reduced(a, b) = C(p, q) - C(p, 2) * C(2, q) / C(2, 2);
    }
  }
  C.setZero();
  for (int a = 0; a < 3; ++a) {
    for (int b = 0; b < 3; ++b) C(in_plane[a], in_plane[b]) = reduced(a, b);
  }
}

} // namespace

void validate(const Material& m) {
  SEAM_CHECK(m.young > 0.0, InputError, "material: young must be positive, got ", m.young);
  SEAM_CHECK(m.poisson > -1.0 && m.poisson < 0.5, InputError,
             "material: poisson must lie in (-1, 0.5), got ", m.poisson);
  SEAM_CHECK(m.density >= 0.0, InputError, "material: density must be non-negative, got ",
             m.density);
}

std::string_view name(MaterialModel model) {
  switch (model) {
  case MaterialModel::linear_elastic:
    return "linear_elastic";
  case MaterialModel::saint_venant_kirchhoff:
    return "saint_venant_kirchhoff";
  case MaterialModel::neo_hooke:
    return "neo_hooke";
  }
  return "unknown";
}

std::optional<MaterialModel> parse_material_model(std::string_view s) {
  for (auto m : {MaterialModel::linear_elastic, MaterialModel::saint_venant_kirchhoff,
                 MaterialModel::neo_hooke}) {
    if (name(m) == s) return m;
  }
  return std::nullopt;
}

PointStatus evaluate(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F,
                     PointResponse& out, bool with_tangent) {
  if (mode == PlaneMode::none) {
    out.stretch_zz = F(2, 2);
    return evaluate_3d(m, F, out, with_tangent);
  }
  Eigen::Matrix3d F3 = Eigen::Matrix3d::Zero();
  F3.topLeftCorner<2, 2>() = F.topLeftCorner<2, 2>();
  F3(2, 2) = 1.0;
  if (mode == PlaneMode::plane_strain) {
    out.stretch_zz = 1.0;
    return evaluate_3d(m, F3, out, with_tangent);
  }

  // Plane stress: find F33 with S33 = 0, then condense the tangent.
  const double lambda = m.lambda(), mu = m.mu();
  switch (m.model) {
  case MaterialModel::linear_elastic:
  case MaterialModel::saint_venant_kirchhoff: {
    // S33 = lambda (E11 + E22 + E33) + 2 mu E33 = 0 is linear in E33: the Newton iteration
    // ends after its first step, written out here.
    Eigen::Matrix3d E = Eigen::Matrix3d::Zero();
    const Eigen::Matrix2d F2 = F.topLeftCorner<2, 2>();
    if (m.model == MaterialModel::linear_elastic) {
      const Eigen::Matrix2d H = F2 - Eigen::Matrix2d::Identity();
      E.topLeftCorner<2, 2>() = 0.5 * (H + H.transpose());
    } else {
      if (!(F2.determinant() > 0.0)) return PointStatus::inverted;
      E.topLeftCorner<2, 2>() = 0.5 * (F2.transpose() * F2 - Eigen::Matrix2d::Identity());
    }
    E(2, 2) = -lambda / (lambda + 2.0 * mu) * (E(0, 0) + E(1, 1));
    if (m.model == MaterialModel::linear_elastic) {
      out.stretch_zz = 1.0 + E(2, 2);
    } else {
      const double C33 = 1.0 + 2.0 * E(2, 2);
      if (!(C33 > 0.0)) return PointStatus::no_plane_stress;
      out.stretch_zz = std::sqrt(C33);
    }
    isotropic_linear_law(lambda, mu, E, out, with_tangent);
    out.stress(2, 2) = 0.0; // exactly zero up to round-off; make it exact
    break;
  }
  case MaterialModel::neo_hooke: {
    const double J2 = F3.topLeftCorner<2, 2>().determinant();
    if (!(J2 > 0.0)) return PointStatus::inverted;
    double F33 = 1.0;
    if (!neo_hooke_plane_stress_stretch(lambda, mu, J2, F33)) return PointStatus::no_plane_stress;
    F3(2, 2) = F33;
    out.stretch_zz = F33;
    const PointStatus st = neo_hooke_law(lambda, mu, F3, out, with_tangent);
    if (st != PointStatus::ok) return st;
    out.stress(2, 2) = 0.0;
    break;
  }
  }
  if (with_tangent) condense_plane_stress(out.tangent);
  return PointStatus::ok;
}

Eigen::Matrix3d cauchy_stress(const Material& m, PlaneMode mode, const Eigen::Matrix3d& F,
                              const PointResponse& r) {
  if (m.model == MaterialModel::linear_elastic) return r.stress;
  Eigen::Matrix3d F3 = F;
  if (mode != PlaneMode::none) {
    F3.row(2).setZero();
    F3.col(2).setZero();
    F3(2, 2) = r.stretch_zz;
  }
  return F3 * r.stress * F3.transpose() / F3.determinant();
}

double von_mises(const Eigen::Matrix3d& s) {
  const double d01 = s(0, 0) - s(1, 1), d12 = s(1, 1) - s(2, 2), d20 = s(2, 2) - s(0, 0);
  const double shear = s(0, 1) * s(0, 1) + s(1, 2) * s(1, 2) + s(0, 2) * s(0, 2);
  return std::sqrt(0.5 * (d01 * d01 + d12 * d12 + d20 * d20) + 3.0 * shear);
}

} // namespace seam::solid
