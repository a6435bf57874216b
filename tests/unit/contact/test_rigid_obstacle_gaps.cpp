// The weighted gaps of a slave facet against a rigid obstacle with their second derivatives
// (rigid_obstacle_gaps.hpp, energy-momentum contact): the Hessian against central differences
// of the gradient (rigid_obstacle_facet with derivatives), the gradient against central
// differences of the values, on a distorted facet near a plane, a sphere and (3D) a cylinder,
// dual and standard multipliers, line2, tri3 and quad4.
#include "seam/contact/rigid_obstacle_gaps.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

namespace seam::contact {
namespace {

template <int Dim> mortar::Facet<Dim> facet(fem::CellType type) {
  mortar::Facet<Dim> f;
  f.type = type;
  if (Dim == 2) {
    f.n_nodes = type == fem::CellType::line3 ? 3 : 2;
    f.x.col(0) << 0.1, 0.03;
    f.x.col(1) << 0.62, -0.02;
    // line3: the mid node off the chord (a curved facet).
    if (f.n_nodes == 3) f.x.col(2) << 0.37, 0.035;
    return f;
  }
  const double xs[4][3] = {
      {0.0, 0.0, 0.02}, {0.55, 0.05, -0.01}, {0.6, 0.48, 0.04}, {-0.05, 0.5, 0.0}};
  const bool triangle = type == fem::CellType::tri3 || type == fem::CellType::tri6;
  const int corners = triangle ? 3 : 4;
  f.n_nodes = fem::n_nodes(type);
  for (int i = 0; i < corners; ++i)
    for (int a = 0; a < Dim; ++a) f.x(a, i) = xs[i][a];
  if constexpr (Dim == 3) {
    // Quadratic facets: the edge nodes (Gmsh order) off the edges' midpoints and out of the
    // plane, the quad9's centre node off the corners' mean (a curved, distorted facet).
    for (int e = 0; e < corners && f.n_nodes > corners; ++e)
      f.x.col(corners + e) = 0.5 * (f.x.col(e) + f.x.col((e + 1) % corners)) +
                             Eigen::Vector3d(0.01 * (e + 1), -0.015 * e, 0.03 - 0.02 * e);
    if (f.n_nodes == 9)
      f.x.col(8) = 0.25 * (f.x.col(0) + f.x.col(1) + f.x.col(2) + f.x.col(3)) +
                   Eigen::Vector3d(0.02, -0.01, 0.04);
  }
  return f;
}

Obstacle obstacle(int dim, Obstacle::Shape shape) {
  Obstacle o;
  o.shape = shape;
  if (shape == Obstacle::Shape::sphere) {
    o.point =
        dim == 2 ? std::array<double, 3>{0.3, -2.0, 0.0} : std::array<double, 3>{0.3, 0.2, -2.0};
    o.radius = 2.0;
  } else if (shape == Obstacle::Shape::cylinder) {
    // An oblique axis under the facet: the distance depends on all three coordinates.
    o.point = {0.3, 0.2, -2.0};
    o.direction = {0.3, 1.0, 0.1};
    o.radius = 2.0;
  } else {
    o.point = {0.0, 0.0, 0.0};
    o.direction = dim == 2 ? std::array<double, 3>{0.1, 0.995, 0.0}
                           : std::array<double, 3>{0.1, -0.05, 0.9937};
  }
  double l = 0.0;
  for (const double d : o.direction) l += d * d;
  if (l > 0.0)
    for (auto& d : o.direction) d /= std::sqrt(l);
  return o;
}

/// Largest differences of the gradient and of the Hessian from central differences, relative
/// to the largest entry of each.
template <int Dim>
std::pair<double, double> check(fem::CellType type, Obstacle::Shape shape, mortar::Multiplier m) {
  const auto f = facet<Dim>(type);
  const Obstacle o = obstacle(Dim, shape);
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
  for (const auto shape : {Obstacle::Shape::plane, Obstacle::Shape::sphere})
    for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard})
      expect_exact(check<2>(fem::CellType::line2, shape, m));
}

/// The 3D facets of `types` against a plane, a sphere and a cylinder, dual and standard
/// multipliers: gradient and Hessian within the bounds of central differences (relative).
void expect_exact_3d(std::initializer_list<fem::CellType> types, double gradient_bound,
                     double hessian_bound) {
  for (const auto type : types)
    for (const auto shape :
         {Obstacle::Shape::plane, Obstacle::Shape::sphere, Obstacle::Shape::cylinder})
      for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard}) {
        const auto e = check<3>(type, shape, m);
        Obstacle o;
        o.shape = shape;
        std::printf("  %s %s %s: gradient %.2e, Hessian %.2e (relative to central differences)\n",
                    std::string(fem::name(type)).c_str(), o.name(),
                    m == mortar::Multiplier::dual ? "dual" : "standard", e.first, e.second);
        EXPECT_LT(e.first, gradient_bound);
        EXPECT_LT(e.second, hessian_bound);
      }
}

TEST(RigidObstacleGaps, Tri3AndQuad4PlaneSphereAndCylinder) {
  expect_exact_3d({fem::CellType::tri3, fem::CellType::quad4}, 1e-9, 1e-8);
}

/// Quadratic 3D facets (tri6, quad8, quad9; Hyper<18> and Hyper<27>), curved and distorted,
/// with the modified dual basis on tri6 and quad8. The central differences' own error is
/// larger on these curved facets (2e-9 of the gradient, 4e-9 of the Hessian): bound 1e-8.
TEST(RigidObstacleGaps, QuadraticFacetsPlaneSphereAndCylinder) {
  expect_exact_3d({fem::CellType::tri6, fem::CellType::quad8, fem::CellType::quad9}, 1e-8, 1e-8);
}

/// line3 facets (energy-momentum contact against an obstacle takes them too in 2D).
TEST(RigidObstacleGaps, Line3PlaneAndCircle) {
  for (const auto shape : {Obstacle::Shape::plane, Obstacle::Shape::sphere})
    for (const auto m : {mortar::Multiplier::dual, mortar::Multiplier::standard}) {
      const auto e = check<2>(fem::CellType::line3, shape, m);
      std::printf("  line3 %s %s: gradient %.2e, Hessian %.2e\n",
                  shape == Obstacle::Shape::plane ? "plane" : "circle",
                  m == mortar::Multiplier::dual ? "dual" : "standard", e.first, e.second);
      expect_exact(e);
    }
}

/// The cylinder's gaps do not change when the facet slides along the axis or turns about it
/// (the invariance the energy-momentum correction's direction leaves out): the gradient has no
/// resultant along the axis and no moment about it.
TEST(RigidObstacleGaps, CylinderGradientFreeAlongAndAboutTheAxis) {
  const auto f = facet<3>(fem::CellType::quad4);
  const Obstacle o = obstacle(3, Obstacle::Shape::cylinder);
  std::vector<double> gap, gradient, hessian;
  rigid_obstacle_gap_hessians<3>(f, o, mortar::Multiplier::dual, gap, gradient, hessian);
  const int n = f.n_nodes, nv = 3 * n;
  double largest = 0.0;
  for (const double g : gradient) largest = std::max(largest, std::abs(g));
  for (int j = 0; j < n; ++j) {
    double along = 0.0, about = 0.0;
    for (int i = 0; i < n; ++i) {
      const double* g = gradient.data() + j * nv + 3 * i;
      double r[3];
      for (int a = 0; a < 3; ++a) r[a] = f.x(a, i) - o.point[static_cast<std::size_t>(a)];
      const double moment[3] = {r[1] * g[2] - r[2] * g[1], r[2] * g[0] - r[0] * g[2],
                                r[0] * g[1] - r[1] * g[0]};
      for (int a = 0; a < 3; ++a) {
        along += o.direction[static_cast<std::size_t>(a)] * g[a];
        about += o.direction[static_cast<std::size_t>(a)] * moment[a];
      }
    }
    EXPECT_LT(std::abs(along), 1e-14 * largest);
    EXPECT_LT(std::abs(about), 1e-13 * largest);
  }
}

} // namespace
} // namespace seam::contact
