// The nodal frictional condition (contact/friction.hpp) against central differences of its own
// value: every coefficient of d(t . C_t) with respect to the multiplier, the normal, the slip
// increment, D_jj and g~, in 2D and 3D, Coulomb and Tresca, stick and slip; and the stick/slip
// decision against the Coulomb cone.
#include "seam/contact/friction.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

namespace seam::contact {
namespace {

std::array<double, 3> tangent_of(const FrictionNode& node, int which) {
  const auto& n = node.normal;
  if (node.dim == 2) return {-n[1], n[0], 0.0};
  // Two orthonormal tangents: e - (e . n) n normalized, then n x t1.
  std::array<double, 3> e{1.0, 0.0, 0.0};
  if (std::abs(n[0]) > 0.8) e = {0.0, 1.0, 0.0};
  const double en = e[0] * n[0] + e[1] * n[1] + e[2] * n[2];
  std::array<double, 3> t{e[0] - en * n[0], e[1] - en * n[1], e[2] - en * n[2]};
  const double l = std::sqrt(t[0] * t[0] + t[1] * t[1] + t[2] * t[2]);
  for (auto& v : t) v /= l;
  if (which == 0) return t;
  return {n[1] * t[2] - n[2] * t[1], n[2] * t[0] - n[0] * t[2], n[0] * t[1] - n[1] * t[0]};
}

FrictionNode random_node(std::mt19937& rng, int dim, bool sliding) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  FrictionNode node;
  node.dim = dim;
  double l = 0.0;
  for (int c = 0; c < dim; ++c) {
    node.normal[c] = u(rng);
    l += node.normal[c] * node.normal[c];
  }
  for (int c = 0; c < dim; ++c) node.normal[c] /= std::sqrt(l);
  node.D = 0.7 + 0.2 * u(rng);
  node.weighted_gap = -0.01 * (1.5 + u(rng)) * node.D;
  // A compressive multiplier (lambda_n ~ 2) with a tangential part, and a slip of either size.
  for (int c = 0; c < dim; ++c) {
    node.lambda[c] = 2.0 * node.normal[c] + 0.3 * u(rng);
    node.slip[c] = (sliding ? 1.0 : 0.01) * u(rng) * node.D;
  }
  return node;
}

/// max |analytic - central difference| over all inputs, relative to the largest coefficient.
double check_row(const FrictionLaw& law, FrictionNode node, NodeStatus status,
                 const std::array<double, 3>& t) {
  const auto row = friction_row(law, node, status, t);
  const double h = 1e-6;
  double err = 0.0, scale = 1e-300;
  const auto fd = [&](double& x) {
    const double x0 = x;
    x = x0 + h;
    const double p = friction_row(law, node, status, t).value;
    x = x0 - h;
    const double m = friction_row(law, node, status, t).value;
    x = x0;
    return (p - m) / (2 * h);
  };
  const auto compare = [&](double analytic, double numeric) {
    err = std::max(err, std::abs(analytic - numeric));
    scale = std::max(scale, std::abs(analytic));
  };
  for (int c = 0; c < node.dim; ++c) {
    compare(row.alpha[c], fd(node.lambda[c]));
    compare(row.a_n[c], fd(node.normal[c]));
    compare(row.a_u[c], fd(node.slip[c]));
  }
  compare(row.a_D, fd(node.D));
  compare(row.a_g, fd(node.weighted_gap));
  return err / scale;
}

void check_law(FrictionLaw law, int dim) {
  std::mt19937 rng(11 + dim);
  int n_stick = 0, n_slip = 0;
  double worst = 0.0;
  for (int trial = 0; trial < 200; ++trial) {
    const auto node = random_node(rng, dim, trial % 2 == 0);
    const auto status = stick_or_slip(law, node);
    (status == NodeStatus::stick ? n_stick : n_slip)++;
    for (int i = 0; i < dim - 1; ++i)
      worst = std::max(worst, check_row(law, node, status, tangent_of(node, i)));
  }
  std::printf("  dim %d %s: %d stick, %d slip, largest relative derivative error %.2e\n", dim,
              law.model == io::FrictionModel::coulomb ? "Coulomb" : "Tresca", n_stick, n_slip,
              worst);
  EXPECT_GT(n_stick, 10);
  EXPECT_GT(n_slip, 10);
  EXPECT_LT(worst, 1e-7);
}

FrictionLaw coulomb() {
  FrictionLaw law;
  law.model = io::FrictionModel::coulomb;
  law.mu = 0.3;
  law.c_n = 5.0;
  law.c_t = 3.0;
  return law;
}

TEST(FrictionLaw, CoulombDerivatives2D) {
  check_law(coulomb(), 2);
}
TEST(FrictionLaw, CoulombDerivatives3D) {
  check_law(coulomb(), 3);
}
TEST(FrictionLaw, TrescaDerivatives3D) {
  auto law = coulomb();
  law.model = io::FrictionModel::tresca;
  law.bound = 0.6;
  check_law(law, 3);
  check_law(law, 2);
}

TEST(FrictionLaw, SlipResidualVanishesOnTheCone) {
  // A node sliding along t with |lambda_t| = mu lambda_n (gap closed) satisfies C_t = 0; with
  // a tangential traction inside the cone and no slip it sticks, with C_t = 0 as well.
  const auto law = coulomb();
  FrictionNode node;
  node.dim = 3;
  node.normal = {0.0, 0.0, 1.0};
  node.D = 0.5;
  node.weighted_gap = 0.0;
  node.lambda = {0.3 * 2.0, 0.0, 2.0};
  node.slip = {0.01 * node.D, 0.0, 0.0};
  EXPECT_EQ(stick_or_slip(law, node), NodeStatus::slip);
  EXPECT_NEAR(friction_row(law, node, NodeStatus::slip, {1, 0, 0}).value, 0.0, 1e-15);
  EXPECT_NEAR(friction_row(law, node, NodeStatus::slip, {0, 1, 0}).value, 0.0, 1e-15);
  node.lambda = {0.5, 0.0, 2.0};
  node.slip = {0.0, 0.0, 0.0};
  EXPECT_EQ(stick_or_slip(law, node), NodeStatus::stick);
  EXPECT_EQ(friction_row(law, node, NodeStatus::stick, {1, 0, 0}).value, 0.0);
  // A stuck node that slipped has a residual c_t s.
  node.slip = {0.01 * node.D, 0.0, 0.0};
  EXPECT_NEAR(friction_row(law, node, NodeStatus::stick, {1, 0, 0}).value, law.c_t * 0.01, 1e-15);
}

} // namespace
} // namespace seam::contact
