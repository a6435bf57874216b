// Boundary modification of the multiplier basis for bound slave nodes (prescribed
// displacement, crosspoints): the modified functions vanish at bound nodes, still form a
// partition of unity, stay biorthogonal to the free nodes' displacement functions, and the
// assembled operators keep the consistency identities of mortar coupling. Reference values
// come from independent quadrature of the basis, never from the operators themselves.
#include <functional>
#include <vector>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/interface.hpp"

using namespace seam::mortar;
using namespace seam::mortar::test;
using seam::local_index;
using seam::fem::CellType;

namespace {

// A facet whose nodes are the reference nodes moved by a smooth non-affine map, so that the
// Jacobian varies over the facet.
template <int Dim> Facet<Dim> distorted_facet(CellType type) {
  Facet<Dim> f;
  f.type = type;
  f.n_nodes = seam::fem::n_nodes(type);
  const double* ref = seam::fem::reference_nodes(type).data();
  for (int i = 0; i < f.n_nodes; ++i) {
    const double* xi = ref + i * (Dim - 1);
    if constexpr (Dim == 2) {
      const double t = xi[0] + 0.1 * (1 - xi[0] * xi[0]);
      f.x.col(i) = Eigen::Vector2d(1.0 + 1.5 * t, 0.3 * t);
    } else {
      const double s = xi[0], t = xi[1];
      // Flat, so that the rule of dual_coefficients is exact (see dual_basis.cpp).
      f.x.col(i) =
          Eigen::Vector3d(s + 0.2 * s * t + 0.1 * t * t, t - 0.15 * s * s + 0.05 * s * t, 0.0);
    }
  }
  return f;
}

// Checks the modified basis Phi^ = R A N~ of one facet for one set of bound nodes.
template <int Dim> void expect_modified_basis(CellType type, unsigned mask) {
  const auto f = distorted_facet<Dim>(type);
  const int n = f.n_nodes;
  const double a = basis_modification(type, Multiplier::dual);
  const SmallMatrix A = dual_coefficients(f, a);
  const SmallMatrix R = boundary_transformation(n, mask);
  const auto bound = [mask](int i) { return ((mask >> i) & 1U) != 0; };
  int n_free = 0;
  for (int i = 0; i < n; ++i) n_free += bound(i) ? 0 : 1;

  const auto rule = seam::fem::quadrature(type, 16);
  Eigen::MatrixXd mixed = Eigen::MatrixXd::Zero(n, n);
  Eigen::VectorXd mass = Eigen::VectorXd::Zero(n);
  for (int q = 0; q < rule.n_points; ++q) {
    const auto p = evaluate(f, rule.points.data() + q * (Dim - 1));
    const double jw = scaled_normal<Dim>(p.dx).norm() * rule.weights[static_cast<std::size_t>(q)];
    NodalVector N = p.N;
    modify_basis(type, a, N.data());
    const Eigen::VectorXd phi = R * (A * N.head(n));
    EXPECT_NEAR(phi.sum(), 1.0, 1e-12) << seam::fem::name(type) << " mask " << mask;
    for (int i = 0; i < n; ++i) {
      if (bound(i)) {
        EXPECT_EQ(phi(i), 0.0);
      }
    }
    mixed += jw * phi * N.head(n).transpose();
    mass += jw * N.head(n);
  }
  const double scale = mass.cwiseAbs().maxCoeff();
  for (int j = 0; j < n; ++j) {
    if (bound(j)) continue;
    for (int k = 0; k < n; ++k) {
      // Free columns: biorthogonality; bound columns: the bound node's share D_bb / n_free.
      const double expected = bound(k) ? mass(k) / n_free : (j == k ? mass(k) : 0.0);
      EXPECT_NEAR(mixed(j, k), expected, 1e-12 * scale)
          << seam::fem::name(type) << " mask " << mask << " j=" << j << " k=" << k;
    }
  }
}

TEST(Crosspoint, TransformationRows) {
  const SmallMatrix R = boundary_transformation(4, 0b0011U);
  const Eigen::Matrix4d expected{{0, 0, 0, 0}, {0, 0, 0, 0}, {0.5, 0.5, 1, 0}, {0.5, 0.5, 0, 1}};
  EXPECT_TRUE(R.isApprox(SmallMatrix(expected), 1e-15));
  EXPECT_TRUE(boundary_transformation(3, 0U).isIdentity());
  EXPECT_TRUE(boundary_transformation(3, 0b111U).isZero());
  // line2 with one bound end: the remaining multiplier function is the constant 1 (Wohlmuth).
  const auto f = distorted_facet<2>(CellType::line2);
  const SmallMatrix A = boundary_transformation(2, 0b01U) * dual_coefficients(f, 0.0);
  for (const double xi : {-1.0, 0.3, 1.0}) {
    NodalVector N = evaluate(f, &xi).N;
    EXPECT_NEAR((A * N.head(2))(1), 1.0, 1e-14);
  }
}

TEST(Crosspoint, ModifiedBasisIsBiorthogonalPartitionOfUnity) {
  expect_modified_basis<2>(CellType::line2, 0b01U);
  expect_modified_basis<2>(CellType::line2, 0b10U);
  expect_modified_basis<2>(CellType::line3, 0b001U);
  expect_modified_basis<2>(CellType::line3, 0b011U);
  expect_modified_basis<3>(CellType::tri3, 0b001U);
  expect_modified_basis<3>(CellType::tri3, 0b011U);
  expect_modified_basis<3>(CellType::quad4, 0b0001U);
  expect_modified_basis<3>(CellType::quad4, 0b1001U);
  expect_modified_basis<3>(CellType::quad4, 0b1011U);
  // Quadratic: a bound edge is its two vertices and its edge node.
  expect_modified_basis<3>(CellType::tri6, 0b001U);
  expect_modified_basis<3>(CellType::tri6, 0b001011U);
  expect_modified_basis<3>(CellType::quad8, 0b00010011U);
  expect_modified_basis<3>(CellType::quad8, 0b10011001U);
  expect_modified_basis<3>(CellType::quad9, 0b000010011U);
  expect_modified_basis<3>(CellType::quad9, 0b010011011U);
}

// Consistency of the assembled operators on a flat interface whose slave side has its nodes
// on the edge u = 0 bound:
//  - bound nodes have no row; with dual multipliers D is diagonal on the free columns;
//  - a unit multiplier on every free node gives the consistent nodal loads of a unit traction
//    on both sides: column sums of D = int N~_k (bound nodes included), of M = int N_l;
//  - a linear field on coincident sides satisfies the constraint, D T^{-1} X_S = M X_M.
void expect_consistent_operators(const Surface& slave, const Surface& master, Multiplier multiplier,
                                 const std::vector<char>& bound) {
  MortarOptions options;
  options.multiplier = multiplier;
  const auto ops = assemble_mortar_operators(slave.view(), master.view(), all_pairs(slave, master),
                                             options, bound);
  const int dim = slave.dim;
  const local_index ns = slave.n_nodes(), nm = master.n_nodes();
  const Eigen::MatrixXd D = dense(ops.D, ns, ns), M = dense(ops.M, ns, nm);

  // Independent integrals of the slave (modified) and master displacement functions.
  const auto integrals = [dim](const Surface& s, double a) {
    Eigen::VectorXd out = Eigen::VectorXd::Zero(s.n_nodes());
    const FacetSet set = s.view();
    for (local_index f = 0; f < set.n_facets(); ++f) {
      const CellType type = set.types[static_cast<std::size_t>(f)];
      const auto nodes = set.facet_nodes(f);
      const auto rule = seam::fem::quadrature(type, 12);
      for (int q = 0; q < rule.n_points; ++q) {
        const double* xi = rule.points.data() + q * (dim - 1);
        NodalVector N = NodalVector::Zero();
        double jw = rule.weights[static_cast<std::size_t>(q)];
        if (dim == 2) {
          const auto p = evaluate(gather_facet<2>(set, f), xi);
          N = p.N;
          jw *= scaled_normal<2>(p.dx).norm();
        } else {
          const auto p = evaluate(gather_facet<3>(set, f), xi);
          N = p.N;
          jw *= scaled_normal<3>(p.dx).norm();
        }
        modify_basis(type, a, N.data());
        for (std::size_t i = 0; i < nodes.size(); ++i) out(nodes[i]) += jw * N(static_cast<int>(i));
      }
    }
    return out;
  };
  const double a = basis_modification(slave.types.front(), multiplier);
  const Eigen::VectorXd slave_mass = integrals(slave, a), master_mass = integrals(master, 0.0);
  const double scale = slave_mass.maxCoeff();

  Eigen::VectorXd ones_free = Eigen::VectorXd::Zero(ns);
  for (local_index j = 0; j < ns; ++j) {
    const bool has_row = D.row(j).cwiseAbs().maxCoeff() > 0.0;
    if (bound[static_cast<std::size_t>(j)] != 0) {
      EXPECT_FALSE(has_row) << "bound node " << j << " has a row";
      EXPECT_EQ(M.row(j).cwiseAbs().maxCoeff(), 0.0);
      continue;
    }
    if (!has_row) continue; // a lattice node no facet uses
    ones_free(j) = 1.0;
    for (local_index k = 0; k < ns; ++k) {
      if (multiplier == Multiplier::dual && k != j && bound[static_cast<std::size_t>(k)] == 0) {
        EXPECT_EQ(D(j, k), 0.0) << j << ", " << k;
      }
    }
    EXPECT_NEAR(D.row(j).sum(), M.row(j).sum(), 1e-12 * scale) << "row sum " << j;
  }
  const Eigen::VectorXd d_loads = D.transpose() * ones_free;
  const Eigen::VectorXd m_loads = M.transpose() * ones_free;
  for (local_index k = 0; k < ns; ++k)
    EXPECT_NEAR(d_loads(k), slave_mass(k), 1e-12 * scale) << "slave load " << k;
  for (local_index l = 0; l < nm; ++l)
    EXPECT_NEAR(m_loads(l), master_mass(l), 1e-12 * scale) << "master load " << l;

  const std::vector<Triplet> T_inverse = inverse_transformation(ops.T);
  for (int c = 0; c < dim; ++c) {
    Eigen::VectorXd x_tilde = slave.coordinate(c);
    if (!T_inverse.empty()) x_tilde = dense(T_inverse, ns, ns) * slave.coordinate(c);
    const Eigen::VectorXd residual = D * x_tilde - M * master.coordinate(c);
    EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-12 * scale) << "linear field, component " << c;
  }
}

std::vector<char> bound_where(const Surface& s, const std::function<bool(const double*)>& pred) {
  std::vector<char> bound(static_cast<std::size_t>(s.n_nodes()), 0);
  for (local_index i = 0; i < s.n_nodes(); ++i)
    bound[static_cast<std::size_t>(i)] = pred(s.coordinates.data() + i * s.dim) ? 1 : 0;
  return bound;
}

TEST(Crosspoint, InterfaceOperators3D) {
  const auto plane = [](double u, double v) { return Eigen::Vector3d(u, 0.8 * v, 0.0); };
  const auto on_edge = [](const double* x) { return x[0] < 1e-12; };
  const auto corner = [](const double* x) { return x[0] < 1e-12 && x[1] < 1e-12; };
  for (const CellType type :
       {CellType::tri3, CellType::quad4, CellType::tri6, CellType::quad8, CellType::quad9}) {
    SCOPED_TRACE(seam::fem::name(type));
    const bool quadratic = seam::fem::order(type) == 2;
    const auto slave = grid(3, 2, type, plane, false);
    const auto master = grid(4, 3, quadratic ? CellType::quad9 : CellType::quad4, plane, true);
    expect_consistent_operators(slave, master, Multiplier::dual, bound_where(slave, on_edge));
    expect_consistent_operators(slave, master, Multiplier::dual, bound_where(slave, corner));
    expect_consistent_operators(slave, master, Multiplier::standard, bound_where(slave, on_edge));
  }
}

TEST(Crosspoint, InterfaceOperators2D) {
  const auto line = [](double s) { return Eigen::Vector2d(2.0 * s, 0.0); };
  const auto left = [](const double* x) { return x[0] < 1e-12; };
  const auto both = [](const double* x) { return x[0] < 1e-12 || x[0] > 2.0 - 1e-12; };
  for (const CellType type : {CellType::line2, CellType::line3}) {
    SCOPED_TRACE(seam::fem::name(type));
    // The slave side is the coarse one: its first facet spans several master facets.
    const auto slave = line_mesh(3, type, line, false);
    const auto master = line_mesh(7, type, line, true);
    expect_consistent_operators(slave, master, Multiplier::dual, bound_where(slave, left));
    expect_consistent_operators(slave, master, Multiplier::dual, bound_where(slave, both));
    expect_consistent_operators(slave, master, Multiplier::standard, bound_where(slave, left));
  }
}

TEST(Crosspoint, MeshInitializationKeepsBoundNodes) {
  // A slightly wavy slave surface over a flat master: the initialization moves the free slave
  // nodes so that D X~_S + D_SB X~_B = M X_M, and leaves the bound ones where they are.
  for (const CellType type : {CellType::quad4, CellType::tri6}) {
    SCOPED_TRACE(seam::fem::name(type));
    const auto slave = grid(
        3, 3, type,
        [](double u, double v) { return Eigen::Vector3d(u, v, 0.01 * std::sin(3 * u + 2 * v)); },
        false);
    const auto master = grid(
        4, 4, CellType::quad4, [](double u, double v) { return Eigen::Vector3d(u, v, 0); }, true);
    const auto bound = bound_where(slave, [](const double* x) { return x[1] < 1e-12; });
    const auto ops =
        assemble_mortar_operators(slave.view(), master.view(), all_pairs(slave, master), {}, bound);
    const auto moved = initialize_slave_coordinates(ops, slave.coordinates, master.coordinates);
    const local_index ns = slave.n_nodes();
    const Eigen::MatrixXd D = dense(ops.D, ns, ns), M = dense(ops.M, ns, master.n_nodes());
    Eigen::MatrixXd T_inverse = Eigen::MatrixXd::Identity(ns, ns);
    if (!ops.T.empty()) T_inverse = dense(inverse_transformation(ops.T), ns, ns);
    for (int c = 0; c < 3; ++c) {
      Eigen::VectorXd x(ns);
      for (local_index i = 0; i < ns; ++i) x(i) = moved[static_cast<std::size_t>(i * 3 + c)];
      const Eigen::VectorXd residual = D * (T_inverse * x) - M * master.coordinate(c);
      EXPECT_LT(residual.cwiseAbs().maxCoeff(), 1e-13) << "component " << c;
    }
    for (local_index i = 0; i < ns; ++i) {
      if (bound[static_cast<std::size_t>(i)] == 0) continue;
      for (int c = 0; c < 3; ++c) {
        EXPECT_EQ(moved[static_cast<std::size_t>(i * 3 + c)],
                  slave.coordinates[static_cast<std::size_t>(i * 3 + c)]);
      }
    }
  }
}

} // namespace
