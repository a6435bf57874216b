// Load kernel tests: follower-pressure tangent by central differences, closed surfaces
// (zero net force, divergence theorem for the enclosed volume), dead traction and body force
// resultants.
#include "test_util.hpp"

#include "seam/solid/loads.hpp"

#include <gtest/gtest.h>

using namespace seam;
using namespace seam::solid;
using namespace seam::solid::test;

namespace {

const std::vector<std::pair<fem::CellType, int>> facet_types = {
    {fem::CellType::line2, 2}, {fem::CellType::line3, 2}, {fem::CellType::tri3, 3},
    {fem::CellType::tri6, 3},  {fem::CellType::quad4, 3}, {fem::CellType::quad8, 3},
    {fem::CellType::quad9, 3}};

// Measure of the current configuration x = X + u of a cell: int det(dx/dxi) dxi with a rule
// exact for the polynomial integrand.
double current_volume(fem::CellType cell, int dim, const std::vector<double>& x) {
  const auto rule = fem::quadrature(cell, 8);
  const int n = fem::n_nodes(cell);
  double dN[fem::max_cell_nodes * 3], v = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    fem::shape_gradients(cell, &rule.points[q * dim], dN);
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    J.topLeftCorner(dim, dim).setZero();
    for (int a = 0; a < n; ++a)
      for (int i = 0; i < dim; ++i)
        for (int k = 0; k < dim; ++k) J(i, k) += x[a * dim + i] * dN[a * dim + k];
    v += rule.weights[q] * J.determinant();
  }
  return v;
}

} // namespace

TEST(Loads, FollowerPressureTangentMatchesFiniteDifferences) {
  const double h = 1e-6;
  // A pressure varying with the reference position: the tangent must not differentiate it.
  const ScalarField p = [](const double* X) { return 3.0 + X[0] - 0.5 * X[1]; };
  for (auto [facet, dim] : facet_types) {
    const std::vector<double> X = cell_coordinates(facet, dim, 0.1, 21);
    const std::vector<double> u = random_vector(X.size(), 0.2, 22);
    const std::size_t nd = X.size();
    FacetInput in{facet, dim, X, u, 0};
    std::vector<double> r(nd), K(nd * nd), rp(nd), rm(nd);
    follower_pressure(in, p, r, K);
    const double scale = max_abs(K);
    ASSERT_GT(scale, 0.1);
    double worst = 0.0, asym = 0.0;
    for (std::size_t j = 0; j < nd; ++j) {
      std::vector<double> up = u, um = u;
      up[j] += h;
      um[j] -= h;
      follower_pressure(FacetInput{facet, dim, X, up, 0}, p, rp, {});
      follower_pressure(FacetInput{facet, dim, X, um, 0}, p, rm, {});
      for (std::size_t i = 0; i < nd; ++i) {
        worst = std::max(worst, std::abs((rp[i] - rm[i]) / (2 * h) - K[i * nd + j]));
        asym = std::max(asym, std::abs(K[i * nd + j] - K[j * nd + i]));
      }
    }
    EXPECT_LT(worst, 1e-7 * scale) << fem::name(facet);
    if (dim == 3) {
      EXPECT_GT(asym, 1e-3 * scale) << fem::name(facet); // nonsymmetric indeed
    }
  }
}

TEST(Loads, PressureOnClosedDeformedSurface) {
  // Over the closed boundary of a deformed cell: int p n da = 0 and, by the divergence
  // theorem, sum_a r_a . x_a = p int x . n da = p dim v (v the current volume).
  const double p = 2.5;
  std::vector<std::pair<fem::CellType, int>> cells;
  for (auto c : cells_2d) cells.emplace_back(c, 2);
  for (auto c : cells_3d) cells.emplace_back(c, 3);
  for (auto [cell, dim] : cells) {
    const std::vector<double> X = cell_coordinates(cell, dim, 0.08, 31);
    const std::vector<double> u = random_vector(X.size(), 0.15, 32);
    std::vector<double> x(X.size()), total(X.size(), 0.0);
    for (std::size_t i = 0; i < X.size(); ++i) x[i] = X[i] + u[i];
    for (int f = 0; f < fem::n_facets(cell); ++f) {
      const auto nodes = fem::facet_nodes(cell, f);
      const fem::CellType ft = fem::facet_type(cell, f);
      std::vector<double> Xf, uf;
      for (int a : nodes)
        for (int i = 0; i < dim; ++i) {
          Xf.push_back(X[a * dim + i]);
          uf.push_back(u[a * dim + i]);
        }
      std::vector<double> rf(Xf.size());
      follower_pressure(FacetInput{ft, dim, Xf, uf, 8}, p, rf, {});
      for (std::size_t k = 0; k < nodes.size(); ++k)
        for (int i = 0; i < dim; ++i) total[nodes[k] * dim + i] += rf[k * dim + i];
    }
    Eigen::Vector3d net = Eigen::Vector3d::Zero();
    double virial = 0.0;
    for (int a = 0; a < fem::n_nodes(cell); ++a)
      for (int i = 0; i < dim; ++i) {
        net(i) += total[a * dim + i];
        virial += total[a * dim + i] * x[a * dim + i];
      }
    const double v = current_volume(cell, dim, x);
    EXPECT_LT(net.norm(), 1e-13 * p) << fem::name(cell);
    EXPECT_NEAR(virial, p * dim * v, 1e-12 * p * v) << fem::name(cell);
    EXPECT_GT(v, 0.1); // a sane, non-degenerate cell
  }
}

TEST(Loads, PressurePushesIntoTheBody) {
  // Top face z = 1 of the unit cube [0,1]^3 as a hex8 facet, p = 2: the external force
  // -p n A = (0, 0, -2) pushes down, so the residual contribution sums to (0, 0, +2).
  std::vector<double> X = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0, 0, 0, 1, 1, 0, 1, 1, 1, 1, 0, 1, 1};
  for (int f = 0; f < 6; ++f) {
    std::vector<double> Xf, uf;
    for (int a : fem::facet_nodes(fem::CellType::hex8, f))
      for (int i = 0; i < 3; ++i) {
        // Map reference [-1,1]^3 node positions (Gmsh order) to [0,1]^3.
        Xf.push_back(0.5 * (fem::reference_nodes(fem::CellType::hex8)[a * 3 + i] + 1));
        uf.push_back(0.0);
      }
    bool top = true;
    for (std::size_t k = 2; k < Xf.size(); k += 3) top = top && Xf[k] == 1.0;
    if (!top) continue;
    std::vector<double> r(12);
    follower_pressure(FacetInput{fem::CellType::quad4, 3, Xf, uf, 0}, 2.0, r, {});
    double fz = 0, fx = 0;
    for (int a = 0; a < 4; ++a) {
      fx += r[a * 3];
      fz += r[a * 3 + 2];
      EXPECT_NEAR(r[a * 3 + 2], 0.5, 1e-14); // p A / 4 per corner
    }
    EXPECT_NEAR(fz, 2.0, 1e-14);
    EXPECT_NEAR(fx, 0.0, 1e-14);
  }
  (void)X;
}

TEST(Loads, DeadTractionResultant) {
  // On a flat affine facet, a traction linear in X integrates to -(t(X_c)) A with X_c the
  // centroid and A the area, both exact: A = |A e1 x A e2| |ref| (3D), |A e1| |ref| (2D).
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, -0.15, 0.9, 0.2, 0.1, -0.05, 1.2;
  const Eigen::Vector3d c(0.3, -0.2, 0.5);
  // The kernel provides room for three components in either dimension.
  const VectorField t = [](const double* X, double* v) {
    v[0] = 1.0 + 2.0 * X[0];
    v[1] = -0.5 + X[1];
    v[2] = 0.25 - X[0];
  };
  for (auto [facet, dim] : facet_types) {
    const std::vector<double> X = cell_coordinates(facet, dim, 0.0);
    const bool tri = facet == fem::CellType::tri3 || facet == fem::CellType::tri6;
    double area = 0.0;
    Eigen::Vector3d xi_c = Eigen::Vector3d::Zero();
    if (dim == 2) {
      area = 2.0 * A.col(0).head<2>().norm();
    } else {
      area = (tri ? 0.5 : 4.0) * A.col(0).cross(A.col(1)).norm();
      if (tri) xi_c << 1.0 / 3, 1.0 / 3, 0;
    }
    const Eigen::Vector3d Xc = c + A * xi_c;
    double tc[3] = {0, 0, 0};
    t(Xc.data(), tc);
    std::vector<double> r(X.size());
    dead_traction(FacetInput{facet, dim, X, {}, 0}, t, r);
    for (int i = 0; i < dim; ++i) {
      double sum = 0;
      for (int a = 0; a < fem::n_nodes(facet); ++a) sum += r[a * dim + i];
      EXPECT_NEAR(sum, -tc[i] * area, 1e-13) << fem::name(facet) << " component " << i;
    }
  }
}

TEST(Loads, BodyForceResultant) {
  Eigen::Matrix3d A;
  A << 1.1, 0.2, -0.1, -0.15, 0.9, 0.2, 0.1, -0.05, 1.2;
  const Eigen::Vector3d c(0.3, -0.2, 0.5);
  const VectorField b = [](const double* X, double* v) {
    v[0] = 2.0 - X[1];
    v[1] = 0.5 * X[0];
    v[2] = -9.81; // only read in 3D
  };
  std::vector<std::pair<fem::CellType, int>> cells;
  for (auto cell : cells_2d) cells.emplace_back(cell, 2);
  for (auto cell : cells_3d) cells.emplace_back(cell, 3);
  for (auto [cell, dim] : cells) {
    const bool simplex = fem::n_vertices(cell) == dim + 1;
    const double ref = dim == 2 ? (simplex ? 0.5 : 4.0) : (simplex ? 1.0 / 6 : 8.0);
    const double V = ref * (dim == 2 ? A.topLeftCorner<2, 2>().determinant() : A.determinant());
    Eigen::Vector3d xi_c = Eigen::Vector3d::Zero();
    if (simplex) xi_c.head(dim).setConstant(1.0 / (dim + 1));
    if (dim == 2) xi_c(2) = 0;
    const Eigen::Vector3d Xc = c + A * xi_c;
    double bc[3];
    b(Xc.data(), bc);
    const std::vector<double> X = cell_coordinates(cell, dim, 0.0);
    ElementInput in;
    in.cell = cell;
    in.dim = dim;
    in.plane = dim == 2 ? PlaneMode::plane_strain : PlaneMode::none;
    in.X = X;
    std::vector<double> r(X.size());
    ASSERT_EQ(body_force(in, b, r), KernelStatus::ok);
    for (int i = 0; i < dim; ++i) {
      double sum = 0;
      for (int a = 0; a < fem::n_nodes(cell); ++a) sum += r[a * dim + i];
      EXPECT_NEAR(sum, -bc[i] * V, 1e-12) << fem::name(cell) << " component " << i;
    }
  }
}
