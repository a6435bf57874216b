// Dual multiplier bases: closed forms of ALGORITHMS.md §3, biorthogonality checked with an
// independent higher-order rule, and the quadratic basis modification of Popp, Wohlmuth, Gee,
// Wall (2012).
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "seam/common/error.hpp"
#include "seam/mortar/dual_basis.hpp"

using namespace seam::mortar;
using seam::fem::CellType;

namespace {

// Facet whose nodes are the reference nodes mapped by an affine map (2D: xi -> x; 3D:
// (xi, eta) -> x) plus an optional in-plane perturbation.
template <int Dim>
Facet<Dim> mapped_facet(CellType type,
                        const std::function<Eigen::Matrix<double, Dim, 1>(const double*)>& map) {
  Facet<Dim> f;
  f.type = type;
  f.n_nodes = seam::fem::n_nodes(type);
  const double* ref = seam::fem::reference_nodes(type).data();
  for (int i = 0; i < f.n_nodes; ++i) f.x.col(i) = map(ref + i * (Dim - 1));
  return f;
}

Eigen::Vector2d straight_line(const double* xi) {
  return {2.0 + 1.5 * xi[0], -1.0 + 0.5 * xi[0]};
}

Eigen::Vector3d parallelogram(const double* xi) {
  return Eigen::Vector3d(1, 2, 3) + xi[0] * Eigen::Vector3d(1.2, 0.3, -0.1) +
         xi[1] * Eigen::Vector3d(0.5, 0.9, 0.4);
}

// Multiplier values Phi at xi for a facet and modification a.
template <int Dim>
NodalVector phi(const Facet<Dim>& f, const SmallMatrix& A, double a, const double* xi) {
  const auto p = evaluate(f, xi);
  NodalVector N = p.N;
  modify_basis(f.type, a, N.data());
  NodalVector out = NodalVector::Zero();
  out.head(f.n_nodes) = A * N.head(f.n_nodes);
  return out;
}

// int Phi_j N~_k J and int N~_k J with a rule of much higher degree than the one used to build A.
template <int Dim> void expect_biorthogonal(const Facet<Dim>& f, double a, double tol) {
  const SmallMatrix A = dual_coefficients(f, a);
  const int n = f.n_nodes;
  const auto rule = seam::fem::quadrature(f.type, 16);
  Eigen::MatrixXd mixed = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(n);
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = rule.points.data() + q * (Dim - 1);
    const auto p = evaluate(f, xi);
    const double jw = scaled_normal<Dim>(p.dx).norm() * rule.weights[static_cast<std::size_t>(q)];
    NodalVector N = p.N;
    modify_basis(f.type, a, N.data());
    const NodalVector Phi = phi(f, A, a, xi);
    mixed += jw * Phi.head(n) * N.head(n).transpose();
    mass += jw * N.head(n);
  }
  const double scale = mass.cwiseAbs().maxCoeff();
  for (int j = 0; j < n; ++j) {
    for (int k = 0; k < n; ++k) {
      EXPECT_NEAR(mixed(j, k), j == k ? mass(k) : 0.0, tol * scale)
          << seam::fem::name(f.type) << " j=" << j << " k=" << k;
    }
  }
}

} // namespace

TEST(DualBasis, ClosedFormLine2) {
  const auto f = mapped_facet<2>(CellType::line2, straight_line);
  const SmallMatrix A = dual_coefficients(f, 0.0);
  for (const double xi : {-1.0, -0.3, 0.0, 0.6, 1.0}) {
    const NodalVector p = phi(f, A, 0.0, &xi);
    EXPECT_NEAR(p(0), (1 - 3 * xi) / 2, 1e-14);
    EXPECT_NEAR(p(1), (1 + 3 * xi) / 2, 1e-14);
  }
}

TEST(DualBasis, ClosedFormLine3) {
  // Nodes -1, 1, 0 (Gmsh order): Phi = (5xi^2/4 - xi/2 - 1/4, 5xi^2/4 + xi/2 - 1/4, 3/2 - 5xi^2/2).
  const auto f = mapped_facet<2>(CellType::line3, straight_line);
  const SmallMatrix A = dual_coefficients(f, 0.0);
  for (const double xi : {-1.0, -0.3, 0.0, 0.6, 1.0}) {
    const NodalVector p = phi(f, A, 0.0, &xi);
    EXPECT_NEAR(p(0), 1.25 * xi * xi - 0.5 * xi - 0.25, 1e-13);
    EXPECT_NEAR(p(1), 1.25 * xi * xi + 0.5 * xi - 0.25, 1e-13);
    EXPECT_NEAR(p(2), 1.5 - 2.5 * xi * xi, 1e-13);
  }
}

TEST(DualBasis, ClosedFormTri3) {
  const auto f = mapped_facet<3>(CellType::tri3, parallelogram);
  const SmallMatrix A = dual_coefficients(f, 0.0);
  for (const auto& xi : {std::array<double, 2>{0.0, 0.0}, {0.2, 0.3}, {1.0, 0.0}, {0.1, 0.8}}) {
    const NodalVector p = phi(f, A, 0.0, xi.data());
    EXPECT_NEAR(p(0), 3 - 4 * xi[0] - 4 * xi[1], 1e-13);
    EXPECT_NEAR(p(1), 4 * xi[0] - 1, 1e-13);
    EXPECT_NEAR(p(2), 4 * xi[1] - 1, 1e-13);
  }
}

TEST(DualBasis, ClosedFormQuad4Parallelogram) {
  const auto f = mapped_facet<3>(CellType::quad4, parallelogram);
  const SmallMatrix A = dual_coefficients(f, 0.0);
  const double* ref = seam::fem::reference_nodes(CellType::quad4).data();
  for (const auto& xi : {std::array<double, 2>{0.0, 0.0}, {0.2, -0.7}, {1.0, 1.0}, {-0.4, 0.9}}) {
    const NodalVector p = phi(f, A, 0.0, xi.data());
    for (int i = 0; i < 4; ++i) {
      const double expected = (1 + 3 * ref[2 * i] * xi[0]) * (1 + 3 * ref[2 * i + 1] * xi[1]) / 4;
      EXPECT_NEAR(p(i), expected, 1e-13) << i;
    }
  }
}

TEST(DualBasis, Biorthogonality) {
  // Straight line3 with its middle node off-centre: non-constant (linear) Jacobian.
  const auto line3 = mapped_facet<2>(CellType::line3, [](const double* xi) {
    const double t = xi[0] + 0.15 * (1 - xi[0] * xi[0]);
    return Eigen::Vector2d(1.0 + 2.0 * t, 0.5 - t);
  });
  expect_biorthogonal(mapped_facet<2>(CellType::line2, straight_line), 0.0, 1e-13);
  expect_biorthogonal(line3, 0.0, 1e-13);
  expect_biorthogonal(mapped_facet<3>(CellType::tri3, parallelogram), 0.0, 1e-13);
  expect_biorthogonal(mapped_facet<3>(CellType::quad4, parallelogram), 0.0, 1e-13);
  // Flat but distorted (non-affine) facets: the Jacobian varies over the facet.
  const auto distorted = [](const double* xi) {
    const double s = xi[0], t = xi[1];
    return Eigen::Vector3d(s + 0.2 * s * t + 0.1 * t * t, t - 0.15 * s * s + 0.05 * s * t, 0.0);
  };
  expect_biorthogonal(mapped_facet<3>(CellType::quad4, distorted), 0.0, 1e-13);
  expect_biorthogonal(mapped_facet<3>(CellType::tri6, distorted), 0.2, 1e-12);
  expect_biorthogonal(mapped_facet<3>(CellType::quad8, distorted), 0.2, 1e-12);
  expect_biorthogonal(mapped_facet<3>(CellType::quad9, distorted), 0.0, 1e-12);
  expect_biorthogonal(mapped_facet<3>(CellType::tri6, parallelogram), 0.2, 1e-13);
  expect_biorthogonal(mapped_facet<3>(CellType::quad8, parallelogram), 0.2, 1e-13);
}

TEST(DualBasis, ModificationMakesIntegralsPositive) {
  // Reference-facet integrals of the standard basis: 0 at tri6 vertices and -1/3 at quad8
  // corners (so no dual basis of N exists); with a = 1/5: 1/15 and 1/5.
  for (const CellType type : {CellType::tri6, CellType::quad8}) {
    const auto rule = seam::fem::quadrature(type, 6);
    const int n = seam::fem::n_nodes(type);
    NodalVector standard = NodalVector::Zero(), modified = NodalVector::Zero();
    for (int q = 0; q < rule.n_points; ++q) {
      NodalVector N = NodalVector::Zero();
      seam::fem::shape_values(type, rule.points.data() + 2 * q, N.data());
      standard += rule.weights[static_cast<std::size_t>(q)] * N;
      EXPECT_NEAR(N.sum(), 1.0, 1e-14);
      modify_basis(type, basis_modification(type, Multiplier::dual), N.data());
      EXPECT_NEAR(N.sum(), 1.0, 1e-14); // still a partition of unity
      modified += rule.weights[static_cast<std::size_t>(q)] * N;
    }
    const int nv = seam::fem::n_vertices(type);
    for (int i = 0; i < nv; ++i) {
      EXPECT_NEAR(standard(i), type == CellType::tri6 ? 0.0 : -1.0 / 3.0, 1e-14);
      EXPECT_NEAR(modified(i), type == CellType::tri6 ? 1.0 / 15.0 : 0.2, 1e-14);
    }
    for (int i = nv; i < n; ++i) EXPECT_GT(modified(i), 0.0);
  }
  EXPECT_EQ(basis_modification(CellType::quad9, Multiplier::dual), 0.0);
  EXPECT_EQ(basis_modification(CellType::quad8, Multiplier::standard), 0.0);
  EXPECT_EQ(basis_modification(CellType::tri3, Multiplier::dual), 0.0);
}

TEST(DualBasis, TransformationMatchesModifiedInterpolation) {
  // u = sum N_k d_k must equal sum N~_k d~_k when d = T d~, for any d~.
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (const CellType type : {CellType::tri6, CellType::quad8, CellType::quad9}) {
    const int n = seam::fem::n_nodes(type);
    const double a = 0.2;
    const SmallMatrix T = transformation_matrix(type, a);
    Eigen::VectorXd d_tilde(n);
    for (int i = 0; i < n; ++i) d_tilde(i) = u(rng);
    const Eigen::VectorXd d = T * d_tilde;
    for (int trial = 0; trial < 5; ++trial) {
      std::array<double, 2> xi{0.4 * (u(rng) + 1) / 2, 0.4 * (u(rng) + 1) / 2};
      NodalVector N = NodalVector::Zero();
      seam::fem::shape_values(type, xi.data(), N.data());
      const double standard = N.head(n).dot(d);
      modify_basis(type, a, N.data());
      EXPECT_NEAR(standard, N.head(n).dot(d_tilde), 1e-14) << seam::fem::name(type);
    }
  }
  EXPECT_TRUE(transformation_matrix(CellType::quad8, 0.0).isIdentity());
}

TEST(DualBasis, EdgeNodeTableMatchesReferenceCells) {
  for (const CellType type : {CellType::line3, CellType::tri6, CellType::quad8, CellType::quad9}) {
    const int d = seam::fem::dimension(type);
    const double* ref = seam::fem::reference_nodes(type).data();
    for (const EdgeNode& e : edge_nodes(type)) {
      for (int a = 0; a < d; ++a) {
        EXPECT_DOUBLE_EQ(ref[e.node * d + a], 0.5 * (ref[e.v0 * d + a] + ref[e.v1 * d + a]));
      }
    }
  }
}

TEST(DualBasis, DegenerateFacetThrows) {
  Facet<3> f;
  f.type = CellType::tri3;
  f.n_nodes = 3;
  f.x.setZero();
  EXPECT_THROW(dual_coefficients(f, 0.0), seam::InputError);
}
