#include "seam/contact/friction.hpp"

#include <cmath>

namespace seam::contact {

namespace {

double dot(int dim, const std::array<double, 3>& a, const std::array<double, 3>& b) {
  double s = 0.0;
  for (int c = 0; c < dim; ++c) s += a[c] * b[c];
  return s;
}

/// The parts of the condition that both status decisions and rows need.
struct Kinematics {
  double lambda_n = 0.0, gap = 0.0, raw_bound = 0.0, bound = 0.0, decision_bound = 0.0;
  double z_norm = 0.0;
  std::array<double, 3> lambda_t{}, s{}, z{};
};

Kinematics kinematics(const FrictionLaw& law, const FrictionNode& node) {
  const int dim = node.dim;
  Kinematics k;
  k.lambda_n = dot(dim, node.normal, node.lambda);
  k.gap = node.weighted_gap / node.D;
  for (int c = 0; c < dim; ++c) k.s[c] = node.slip[c] / node.D;
  const double sn = dot(dim, node.normal, k.s);
  for (int c = 0; c < dim; ++c) {
    k.lambda_t[c] = node.lambda[c] - k.lambda_n * node.normal[c];
    k.z[c] = k.lambda_t[c] + law.c_t * (k.s[c] - sn * node.normal[c]);
  }
  k.z_norm = std::sqrt(dot(dim, k.z, k.z));
  const bool tresca = law.model == io::FrictionModel::tresca;
  k.raw_bound = tresca ? law.bound : law.mu * (k.lambda_n - law.c_n * k.gap);
  k.bound = std::max(k.raw_bound, 0.0);
  k.decision_bound =
      tresca ? law.bound : std::max(law.mu * (k.lambda_n - law.c_n * (k.gap - law.touching)), 0.0);
  return k;
}

} // namespace

double slip_bound(const FrictionLaw& law, const FrictionNode& node) {
  return kinematics(law, node).bound;
}

NodeStatus stick_or_slip(const FrictionLaw& law, const FrictionNode& node) {
  const Kinematics k = kinematics(law, node);
  return k.z_norm < k.decision_bound ? NodeStatus::stick : NodeStatus::slip;
}

bool admissible(const FrictionLaw& law, const FrictionNode& node, NodeStatus status,
                double tolerance) {
  const Kinematics k = kinematics(law, node);
  if (status == NodeStatus::stick) return k.z_norm <= k.decision_bound + tolerance;
  return k.z_norm >= k.decision_bound - tolerance;
}

FrictionRow friction_row(const FrictionLaw& law, const FrictionNode& node, NodeStatus status,
                         const std::array<double, 3>& t) {
  const int dim = node.dim;
  const Kinematics k = kinematics(law, node);
  const auto& n = node.normal;
  const double D = node.D;
  const double sn = dot(dim, n, k.s);
  FrictionRow row;
  if (status == NodeStatus::stick) {
    // C = c_t t . P s (= c_t t . s for t . n = 0).
    const double ts = dot(dim, t, k.s);
    row.value = law.c_t * (ts - sn * dot(dim, t, n));
    for (int c = 0; c < dim; ++c) {
      row.a_u[c] = law.c_t * t[c] / D;
      row.a_n[c] = -law.c_t * sn * t[c];
    }
    row.a_D = -law.c_t * ts / D;
    return row;
  }
  // Slip: C = t . lambda_t - xi t . z^, z^ = z / |z|; with q = t - (t . z^) z^ and
  // kappa = xi / |z|, dC = (t - kappa q) . dlambda_t - (t . z^) dxi - kappa c_t q . d(P s).
  std::array<double, 3> zhat{}, q{}, b{};
  if (k.z_norm > 0.0)
    for (int c = 0; c < dim; ++c) zhat[c] = k.z[c] / k.z_norm;
  const double kappa = k.z_norm > 0.0 ? k.bound / k.z_norm : 0.0;
  const double tz = dot(dim, t, zhat);
  for (int c = 0; c < dim; ++c) {
    q[c] = t[c] - tz * zhat[c];
    b[c] = t[c] - kappa * q[c];
  }
  row.value = dot(dim, t, k.lambda_t) - k.bound * tz;
  const double qs = dot(dim, q, k.s);
  // Coulomb, bound positive: dxi = mu (n . dlambda + lambda . dn - c_n (dg~ - g dD) / D).
  const double mu = law.model == io::FrictionModel::coulomb && k.raw_bound > 0.0 ? law.mu : 0.0;
  for (int c = 0; c < dim; ++c) {
    row.alpha[c] = b[c] - tz * mu * n[c];
    row.a_n[c] = -k.lambda_n * b[c] - tz * mu * node.lambda[c] + kappa * law.c_t * sn * q[c];
    row.a_u[c] = -kappa * law.c_t * q[c] / D;
  }
  row.a_D = kappa * law.c_t * qs / D - tz * mu * law.c_n * k.gap / D;
  row.a_g = tz * mu * law.c_n / D;
  return row;
}

} // namespace seam::contact
