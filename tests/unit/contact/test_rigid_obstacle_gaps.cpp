// The weighted gaps of a slave facet against a rigid obstacle with their second derivatives
// (rigid_obstacle_gaps.hpp, energy-momentum contact): the Hessian against central differences
// of the gradient (rigid_obstacle_facet with derivatives), the gradient against central
// differences of the values, on a distorted facet near a plane and a sphere, dual and
// standard multipliers, line2, tri3 and quad4.
#include "seam/contact/rigid_obstacle_gaps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <vector>

namespace seam::contact {
namespace {

template <int Dim> mortar::Facet<Dim> facet(fem::CellType type) {
  mortar::Facet<Dim> f;
  f.type = type;
  if (Dim == 2) {
    f.n_nodes = 2;
    f.x.col(0) << 0.1, 0.03;
    f.x.col(1) << 0.62, -0.02;
  } else {
    const double xs[4][3] = {
        {0.0, 0.0, 0.02}, {0.55, 0.05, -0.01}, {0.6, 0.48, 0.04}, {-0.05, 0.5, 0.0}};
    f.n_nodes = type == fem::CellType::tri3 ? 3 : 4;
    for (int i = 0; i < f.n_nodes; ++i)
      for (int a = 0; a < Dim; ++a) f.x(a, i) = xs[i][a];
  }
  return f;
}

Obstacle obstacle(int dim, bool sphere) {
  Obstacle o;
  if (sphere) {
    o.shape = Obstacle::Shape::sphere;
    o.point =
        dim == 2 ? std::array<double, 3>{0.3, -2.0, 0.0} : std::array<double, 3>{0.3, 0.2, -2.0};
    o.radius = 2.0;
  } else {
    o.point = {0.0, 0.0, 0.0};
    o.direction = dim == 2 ? std::array<double, 3>{0.1, 0.995, 0.0}
                           : std::array<double, 3>{0.1, -0.05, 0.9937};
    double l = 0.0;
    for (const double d : o.direction) l += d * d;
    for (auto& d : o.direction) d /= std::sqrt(l);
  }
  return o;
}

/// Largest differences of the gradient and of the Hessian from central differences, relative
/// to the largest entry of each.
template <int Dim>
std::pair<double, double> check(fem::CellType type, bool sphere, mortar::Multiplier m) {
  const auto f = facet<Dim>(type);
  const Obstacle o = obstacle(Dim, sphere);
  std::vector<double> gap, gradient, hessian;
  rigid_obstacle_gap_hessians<Dim>(f, o, m, gap, gradient, hessian);
  const int n = f.n_nodes, nv = Dim * n;
  RigidObstacleFacet plain;
  rigid_obstacle_facet<Dim>(f, o, m, true, plain);
  double gmax = 0.0, hmax = 0.0, gerr = 0.0, herr = 0.0;
  for (int j = 0; j < n; ++j) {
    EXPECT_NEAR(gap[static_cast<std::size_t>(j)], plain.gap[static_cast<std::size_t>(j)], 1e-15);
    for (int v = 0; v < nv; ++v)
      EXPECT_NEAR(gradient[static_cast<std::size_t>(j * nv + v)],
                  plain.dgap[static_cast<std::size_t>(j * nv + v)], 1e-15);
  }
  const double h = 1e-5;
  for (int v = 0; v < nv; ++v) {
    RigidObstacleFacet plus, minus;
    auto fp = f, fm = f;
    fp.x(v % Dim, v / Dim) += h;
    fm.x(v % Dim, v / Dim) -= h;
    rigid_obstacle_facet<Dim>(fp, o, m, true, plus);
    rigid_obstacle_facet<Dim>(fm, o, m, true, minus);
    for (int j = 0; j < n; ++j) {
      const auto J = static_cast<std::size_t>(j);
      const double dg = (plus.gap[J] - minus.gap[J]) / (2 * h);
      gmax = std::max(gmax, std::abs(gradient[J * nv + v]));
      gerr = std::max(gerr, std::abs(dg - gradient[J * nv + v]));
      for (int w = 0; w < nv; ++w) {
        const auto W = static_cast<std::size_t>(w);
        const double dh = (plus.dgap[J * nv + W] - minus.dgap[J * nv + W]) / (2 * h);
        const double exact = hessian[(J * nv + v) * nv + W];
        hmax = std::max(hmax, std::abs(exact));
        herr = std::max(herr, std::abs(dh - exact));
      }
    }
  }
  return {gerr / gmax, herr / hmax};
}

void expect_exact(std::pair<double, double> e) {
  EXPECT_LT(e.first, 1e-9);
  EXPECT_LT(e.second, 1e-8);
}

TEST(RigidObstacleGaps, Line2PlaneAndCircle) {
  for (const bool sphere : {false, true})
    for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard})
      expect_exact(check<2>(fem::CellType::line2, sphere, m));
}

TEST(RigidObstacleGaps, Tri3AndQuad4PlaneAndSphere) {
  for (const auto type : {fem::CellType::tri3, fem::CellType::quad4})
    for (const bool sphere : {false, true})
      for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard}) {
        const auto e = check<3>(type, sphere, m);
        std::printf("  %s %s %s: gradient %.2e, Hessian %.2e (relative to central differences)\n",
                    std::string(fem::name(type)).c_str(), sphere ? "sphere" : "plane",
                    m == mortar::Multiplier::dual ? "dual" : "standard", e.first, e.second);
        expect_exact(e);
      }
}

} // namespace
} // namespace seam::contact
