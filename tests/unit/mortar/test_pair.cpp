// Single element pairs against integrals computed directly from the analytic shape functions
// on the known overlap, independent of segmentation, clipping and projection.
#include <functional>

#include <gtest/gtest.h>

#include "seam/mortar/pair_integration.hpp"

using namespace seam::mortar;
using seam::fem::CellType;

namespace {

// Composite 3-point Gauss–Legendre: exact for polynomials of degree <= 5 on each piece.
double integrate(const std::function<double(double)>& f, double a, double b, int pieces = 16) {
  const double g = std::sqrt(0.6);
  const std::array<double, 3> x = {-g, 0.0, g}, w = {5.0 / 9, 8.0 / 9, 5.0 / 9};
  double sum = 0.0;
  const double h = (b - a) / pieces;
  for (int p = 0; p < pieces; ++p) {
    for (int q = 0; q < 3; ++q) sum += 0.5 * h * w[q] * f(a + h * (p + 0.5 + 0.5 * x[q]));
  }
  return sum;
}

double integrate2(const std::function<double(double, double)>& f, double x0, double x1, double y0,
                  double y1) {
  return integrate(
      [&](double x) { return integrate([&](double y) { return f(x, y); }, y0, y1, 4); }, x0, x1, 4);
}

// Slave line2 on y = 0 from x = 1 (node 0) to x = 0 (node 1): body below, normal +y.
SlaveFacet<2> slave_line(Multiplier m) {
  SlaveFacet<2> s;
  s.facet.type = CellType::line2;
  s.facet.n_nodes = 2;
  s.facet.x.col(0) = Eigen::Vector2d(1, 0);
  s.facet.x.col(1) = Eigen::Vector2d(0, 0);
  s.normals.col(0) = Eigen::Vector2d(0, 1);
  s.normals.col(1) = Eigen::Vector2d(0, 1);
  s.basis = make_slave_basis(s.facet, m);
  return s;
}

// Master line2 at height h from x = a (node 0) to x = b (node 1): body above, normal -y.
Facet<2> master_line(double a, double b, double h = 0.0) {
  Facet<2> m;
  m.type = CellType::line2;
  m.n_nodes = 2;
  m.x.col(0) = Eigen::Vector2d(a, h);
  m.x.col(1) = Eigen::Vector2d(b, h);
  return m;
}

} // namespace

TEST(Pair2D, SegmentationCases) {
  const SlaveFacet<2> s = slave_line(Multiplier::standard);
  struct Case {
    double a, b, length;
  };
  for (const Case c : {Case{0.25, 0.75, 0.5}, Case{-0.5, 1.5, 1.0}, Case{0.5, 1.5, 0.5},
                       Case{-0.5, 0.3, 0.3}, Case{0.0, 1.0, 1.0}, Case{1.5, 2.5, 0.0},
                       Case{1.0, 2.0, 0.0}, Case{-1.0, 0.0, 0.0}, Case{-3.0, -2.0, 0.0}}) {
    const PairContribution r = integrate_pair(s, master_line(c.a, c.b));
    EXPECT_NEAR(r.area, c.length, 1e-14) << c.a << " " << c.b;
    EXPECT_EQ(r.n_cells, c.length > 0 ? 1 : 0);
    EXPECT_EQ(r.n_projection_failures, 0);
    EXPECT_NEAR(r.D.sum(), c.length, 1e-14); // sum_jk int N_j N_k = overlap length
  }
  // A master facing the same way as the slave is no contact partner.
  EXPECT_EQ(integrate_pair(s, master_line(1.0, 0.0)).n_cells, 0);
}

TEST(Pair2D, StandardAndDualMatricesOnPartialOverlap) {
  // Overlap x in [0.5, 1]. Slave: N0 = x, N1 = 1 - x; dual Phi0 = 3x - 1, Phi1 = 2 - 3x.
  // Master from 0.5 to 1.5: Nm0 = 1.5 - x, Nm1 = x - 0.5.
  const std::array<std::function<double(double)>, 2> N = {[](double x) { return x; },
                                                          [](double x) { return 1 - x; }};
  const std::array<std::function<double(double)>, 2> dual = {[](double x) { return 3 * x - 1; },
                                                             [](double x) { return 2 - 3 * x; }};
  const std::array<std::function<double(double)>, 2> Nm = {[](double x) { return 1.5 - x; },
                                                           [](double x) { return x - 0.5; }};
  const double h = 0.125;
  for (const Multiplier m : {Multiplier::standard, Multiplier::dual}) {
    const auto& Phi = m == Multiplier::dual ? dual : N;
    const PairContribution r = integrate_pair(slave_line(m), master_line(0.5, 1.5, h));
    for (int j = 0; j < 2; ++j) {
      for (int l = 0; l < 2; ++l) {
        EXPECT_NEAR(r.M(j, l), integrate([&](double x) { return Phi[j](x) * Nm[l](x); }, 0.5, 1),
                    1e-15);
      }
      for (int k = 0; k < 2; ++k) {
        const double exact =
            m == Multiplier::dual
                ? (j == k ? integrate([&](double x) { return Phi[j](x); }, 0.5, 1) : 0.0)
                : integrate([&](double x) { return Phi[j](x) * N[k](x); }, 0.5, 1);
        EXPECT_NEAR(r.D(j, k), exact, 1e-15);
      }
      EXPECT_NEAR(r.weighted_gap(j), h * integrate([&](double x) { return Phi[j](x); }, 0.5, 1),
                  1e-15);
    }
  }
}

TEST(Pair2D, Line3MasterInsideCurvedSlave) {
  // Slave line3 on the parabola y = 0.1 (1 - x^2) (x from 1 to -1), master a straight line3
  // facing it; only the row-sum identity and D's symmetry can be stated exactly here.
  SlaveFacet<2> s;
  s.facet.type = CellType::line3;
  s.facet.n_nodes = 3;
  s.facet.x.col(0) = Eigen::Vector2d(1, 0);
  s.facet.x.col(1) = Eigen::Vector2d(-1, 0);
  s.facet.x.col(2) = Eigen::Vector2d(0, 0.1);
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector2d x = s.facet.x.col(i);
    s.normals.col(i) = Eigen::Vector2d(0.2 * x.x(), 1.0).normalized();
  }
  for (const Multiplier m : {Multiplier::standard, Multiplier::dual}) {
    s.basis = make_slave_basis(s.facet, m);
    Facet<2> master;
    master.type = CellType::line3;
    master.n_nodes = 3;
    master.x.col(0) = Eigen::Vector2d(-0.6, 0.2);
    master.x.col(1) = Eigen::Vector2d(0.4, 0.2);
    master.x.col(2) = Eigen::Vector2d(-0.1, 0.2);
    const PairContribution r = integrate_pair(s, master);
    ASSERT_EQ(r.n_cells, 1);
    EXPECT_EQ(r.n_projection_failures, 0);
    for (int j = 0; j < 3; ++j) EXPECT_NEAR(r.D.row(j).sum(), r.M.row(j).sum(), 1e-15);
    if (m == Multiplier::standard) {
      EXPECT_NEAR((r.D - r.D.transpose()).norm(), 0.0, 1e-15);
    } else {
      EXPECT_EQ((r.D - Eigen::MatrixXd(r.D.diagonal().asDiagonal())).norm(), 0.0);
    }
  }
}

namespace {

// Unit-square quad4 at height z, nodes counter-clockwise seen from +z unless flipped.
Facet<3> square(double x0, double y0, double size, double z, bool flip) {
  Facet<3> f;
  f.type = CellType::quad4;
  f.n_nodes = 4;
  const std::array<Eigen::Vector3d, 4> c = {
      Eigen::Vector3d(x0, y0, z), Eigen::Vector3d(x0 + size, y0, z),
      Eigen::Vector3d(x0 + size, y0 + size, z), Eigen::Vector3d(x0, y0 + size, z)};
  for (int i = 0; i < 4; ++i) f.x.col(i) = c[static_cast<std::size_t>(flip ? (4 - i) % 4 : i)];
  return f;
}

// Bilinear function of node i of the axis-aligned square [x0, x0+s] x [y0, y0+s].
double bilinear(const Facet<3>& f, int i, double x, double y) {
  const double x0 = f.x.row(0).head(4).minCoeff(), x1 = f.x.row(0).head(4).maxCoeff();
  const double y0 = f.x.row(1).head(4).minCoeff(), y1 = f.x.row(1).head(4).maxCoeff();
  const double sx = (x - x0) / (x1 - x0), sy = (y - y0) / (y1 - y0);
  const double fx = f.x(0, i) == x0 ? 1 - sx : sx;
  const double fy = f.x(1, i) == y0 ? 1 - sy : sy;
  return fx * fy;
}

} // namespace

TEST(Pair3D, Quad4OverlapMatchesAnalyticIntegrals) {
  SlaveFacet<3> s;
  s.facet = square(0, 0, 1, 0, false);
  for (int i = 0; i < 4; ++i) s.normals.col(i) = Eigen::Vector3d(0, 0, 1);
  const double h = 0.3;
  const Facet<3> master = square(0.5, 0.25, 1, h, true);
  // Dual functions of the unit square: Phi_i = (1 + 3 xi_i xi)(1 + 3 eta_i eta)/4 in [-1,1]^2,
  // i.e. in x in [0, 1] a factor 3x - 1 for a node at x = 1 and 2 - 3x for one at x = 0.
  const auto dual = [&](int i, double x, double y) {
    const double fx = s.facet.x(0, i) == 0 ? 2 - 3 * x : 3 * x - 1;
    const double fy = s.facet.x(1, i) == 0 ? 2 - 3 * y : 3 * y - 1;
    return fx * fy;
  };
  for (const Multiplier m : {Multiplier::standard, Multiplier::dual}) {
    s.basis = make_slave_basis(s.facet, m);
    const PairContribution r = integrate_pair(s, master);
    EXPECT_EQ(r.n_cells, 4); // rectangle fanned about its centroid
    EXPECT_NEAR(r.area, 0.375, 1e-15);
    EXPECT_EQ(r.n_projection_failures, 0);
    const auto phi = [&](int j, double x, double y) {
      return m == Multiplier::dual ? dual(j, x, y) : bilinear(s.facet, j, x, y);
    };
    for (int j = 0; j < 4; ++j) {
      for (int l = 0; l < 4; ++l) {
        const double exact =
            integrate2([&](double x, double y) { return phi(j, x, y) * bilinear(master, l, x, y); },
                       0.5, 1, 0.25, 1);
        EXPECT_NEAR(r.M(j, l), exact, 1e-15) << j << " " << l;
      }
      for (int k = 0; k < 4; ++k) {
        const double exact =
            m == Multiplier::dual
                ? (j == k ? integrate2([&](double x, double y) { return phi(j, x, y); }, 0.5, 1,
                                       0.25, 1)
                          : 0.0)
                : integrate2(
                      [&](double x, double y) { return phi(j, x, y) * bilinear(s.facet, k, x, y); },
                      0.5, 1, 0.25, 1);
        EXPECT_NEAR(r.D(j, k), exact, 1e-15);
      }
      const double gap =
          h * integrate2([&](double x, double y) { return phi(j, x, y); }, 0.5, 1, 0.25, 1);
      EXPECT_NEAR(r.weighted_gap(j), gap, 1e-15);
    }
  }
}

TEST(Pair3D, RejectedPairs) {
  SlaveFacet<3> s;
  s.facet = square(0, 0, 1, 0, false);
  for (int i = 0; i < 4; ++i) s.normals.col(i) = Eigen::Vector3d(0, 0, 1);
  s.basis = make_slave_basis(s.facet, Multiplier::dual);
  EXPECT_EQ(integrate_pair(s, square(0.2, 0.2, 1, 0, false)).n_cells, 0); // same orientation
  EXPECT_EQ(integrate_pair(s, square(5.0, 0.0, 1, 0, true)).n_cells, 0);  // far away
  EXPECT_EQ(integrate_pair(s, square(1.0, 0.0, 1, 0, true)).n_cells, 0);  // shares an edge only
  EXPECT_EQ(integrate_pair(s, square(1.0, 1.0, 1, 0, true)).n_cells, 0);  // shares a corner only
}

TEST(Pair3D, TiltedMasterGap) {
  // Master plane z = h + t x above the unit slave square, covering it: along the slave normal
  // the gap is g(x) = h + t x; with standard multipliers g~_j = int N_j (h + t x).
  SlaveFacet<3> s;
  s.facet = square(0, 0, 1, 0, false);
  for (int i = 0; i < 4; ++i) s.normals.col(i) = Eigen::Vector3d(0, 0, 1);
  s.basis = make_slave_basis(s.facet, Multiplier::standard);
  Facet<3> master = square(-0.5, -0.5, 2, 0, true);
  const double h = 0.2, t = 0.1;
  for (int i = 0; i < 4; ++i) master.x(2, i) = h + t * master.x(0, i);
  const PairContribution r = integrate_pair(s, master);
  EXPECT_NEAR(r.area, 1.0, 1e-15);
  for (int j = 0; j < 4; ++j) {
    EXPECT_NEAR(
        r.weighted_gap(j),
        integrate2([&](double x, double y) { return bilinear(s.facet, j, x, y) * (h + t * x); }, 0,
                   1, 0, 1),
        1e-15);
  }
}
