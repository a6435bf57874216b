// Interface assembly in 3D: non-matching planar grids (linear and quadratic), a curved
// cylindrical interface, weighted gaps and mesh initialization.
#include <numbers>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/mortar/dual_basis.hpp"

using namespace seam::mortar;
using seam::local_index;
using seam::fem::CellType;
using test::Surface;

namespace {

// Rectangle [0, 2] x [0, 1] at height z: slave facets face +z, master facets -z.
Surface plane(int nx, int ny, CellType type, double z, bool slave) {
  return test::grid(
      nx, ny, type, [z](double u, double v) { return Eigen::Vector3d(2 * u, v, z); }, !slave);
}

// Half cylinder of radius r about the y axis (angle 0..pi over x-z), slave outward (body
// inside), master inward.
Surface cylinder(int nx, int ny, CellType type, double r, bool slave) {
  return test::grid(
      nx, ny, type,
      [r](double u, double v) {
        const double t = std::numbers::pi * u;
        return Eigen::Vector3d(r * std::cos(t), 1.5 * v, r * std::sin(t));
      },
      slave);
}

struct Dense {
  Eigen::MatrixXd D, M;
};

Dense dense(const MortarOperators& ops, const Surface& s, const Surface& m) {
  return {test::dense(ops.D, s.n_nodes(), s.n_nodes()),
          test::dense(ops.M, s.n_nodes(), m.n_nodes())};
}

void expect_row_sums(const MortarOperators& ops, const Surface& s, const Surface& m) {
  const Dense o = dense(ops, s, m);
  const double scale = o.D.cwiseAbs().maxCoeff();
  ASSERT_GT(scale, 0.0);
  EXPECT_LE((o.D.rowwise().sum() - o.M.rowwise().sum()).cwiseAbs().maxCoeff(), 1e-12 * scale);
  if (ops.multiplier == Multiplier::dual) {
    EXPECT_EQ((o.D - Eigen::MatrixXd(o.D.diagonal().asDiagonal())).cwiseAbs().maxCoeff(), 0.0);
  }
}

// int N~_j and int N_j N_k over the slave surface, by element quadrature (independent of the
// mortar cells).
Eigen::VectorXd slave_integrals(const Surface& s, Multiplier mult,
                                Eigen::MatrixXd* mass = nullptr) {
  Eigen::VectorXd sum = Eigen::VectorXd::Zero(s.n_nodes());
  if (mass) *mass = Eigen::MatrixXd::Zero(s.n_nodes(), s.n_nodes());
  const FacetSet view = s.view();
  for (local_index f = 0; f < view.n_facets(); ++f) {
    const Facet<3> facet = gather_facet<3>(view, f);
    const auto rule = seam::fem::quadrature(facet.type, 8);
    for (int q = 0; q < rule.n_points; ++q) {
      const auto p = evaluate(facet, rule.points.data() + 2 * q);
      NodalVector N = p.N;
      modify_basis(facet.type, basis_modification(facet.type, mult), N.data());
      const double jw = scaled_normal<3>(p.dx).norm() * rule.weights[static_cast<std::size_t>(q)];
      const auto nodes = view.facet_nodes(f);
      for (int i = 0; i < facet.n_nodes; ++i) {
        sum(nodes[static_cast<std::size_t>(i)]) += jw * N(i);
        for (int k = 0; mass && k < facet.n_nodes; ++k) {
          (*mass)(nodes[static_cast<std::size_t>(i)], nodes[static_cast<std::size_t>(k)]) +=
              jw * p.N(i) * p.N(k);
        }
      }
    }
  }
  return sum;
}

} // namespace

TEST(Interface3D, PlanarNonMatchingQuadAgainstTri) {
  // 3 x 3 quad4 slave against 4 x 5 (x 2) tri3 master, coincident.
  const Surface s = plane(3, 3, CellType::quad4, 0.0, true);
  const Surface m = plane(4, 5, CellType::tri3, 0.0, false);
  const auto pairs = test::all_pairs(s, m);
  for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
    const MortarOperators ops = assemble_mortar_operators(s.view(), m.view(), pairs, {mult, {}});
    expect_row_sums(ops, s, m);
    EXPECT_EQ(ops.n_projection_failures, 0);
    EXPECT_NEAR(ops.integrated_area, 2.0, 1e-13);
    EXPECT_GT(ops.n_integration_cells, 0);
    const Dense o = dense(ops, s, m);
    if (mult == Multiplier::standard) {
      EXPECT_NEAR(o.D.sum(), 2.0, 1e-13); // sum_jk int N_j N_k = area
    }
    // Linear fields: D X_s = M X_m (rigid translation and any affine field).
    for (const auto& f : {std::array<double, 4>{1, 0, 0, 0}, {0.3, 1, 0, 0}, {-1, 0.5, 2, 0.7}}) {
      const Eigen::VectorXd fs =
          (f[1] * s.coordinate(0) + f[2] * s.coordinate(1) + f[3] * s.coordinate(2)).array() + f[0];
      const Eigen::VectorXd fm =
          (f[1] * m.coordinate(0) + f[2] * m.coordinate(1) + f[3] * m.coordinate(2)).array() + f[0];
      EXPECT_LE((o.D * fs - o.M * fm).cwiseAbs().maxCoeff(), 1e-14);
    }
  }
}

TEST(Interface3D, WeightedGapOfParallelPlanes) {
  // g~_j = h int Phi_j = h int N_j; on the 3 x 3 grid of [0,2] x [0,1] (cell area 2/9):
  // corners 1/18, edge nodes 1/9, interior nodes 2/9.
  const double h = 0.04;
  const Surface s = plane(3, 3, CellType::quad4, -h, true);
  const Surface m = plane(4, 5, CellType::tri3, 0.0, false);
  for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
    const MortarOperators ops =
        assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
    for (local_index node : s.nodes) {
      const int I = node % 7, J = node / 7; // lattice indices (2 * 3 + 1 per row)
      const int boundary = (I == 0 || I == 6) + (J == 0 || J == 6);
      const double integral = boundary == 2 ? 1.0 / 18 : boundary == 1 ? 1.0 / 9 : 2.0 / 9;
      EXPECT_NEAR(ops.weighted_gap[static_cast<std::size_t>(node)], h * integral, 1e-15);
    }
  }
}

TEST(Interface3D, QuadraticFacets) {
  struct Combo {
    CellType slave, master;
  };
  const double h = 0.02;
  for (const Combo c :
       {Combo{CellType::tri6, CellType::quad4}, Combo{CellType::quad8, CellType::tri3},
        Combo{CellType::quad9, CellType::tri6}, Combo{CellType::quad8, CellType::quad9}}) {
    const Surface s = plane(3, 2, c.slave, 0.0, true);
    const Surface m = plane(2, 3, c.master, 0.0, false);
    const Surface m_up = plane(2, 3, c.master, h, false);
    for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
      SCOPED_TRACE(std::string(seam::fem::name(c.slave)) + " / " +
                   std::string(seam::fem::name(c.master)) +
                   (mult == Multiplier::dual ? " dual" : " standard"));
      const MortarOperators ops =
          assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
      expect_row_sums(ops, s, m);
      EXPECT_EQ(ops.n_projection_failures, 0);
      EXPECT_NEAR(ops.integrated_area, 2.0, 1e-13);
      const Dense o = dense(ops, s, m);
      if (mult == Multiplier::standard) {
        // Full coverage: D is the slave surface's consistent mass matrix int N_j N_k, which
        // needs the degree-8 cell rule for biquadratic facets.
        Eigen::MatrixXd mass;
        slave_integrals(s, mult, &mass);
        EXPECT_LE((o.D - mass).cwiseAbs().maxCoeff(), 1e-14);
        EXPECT_NEAR(o.D.sum(), 2.0, 1e-13);
      }
      // Modified basis only for dual multipliers on tri6 and quad8.
      EXPECT_EQ(ops.T.empty(), basis_modification(c.slave, mult) == 0.0);
      // Linear fields: on straight-sided facets with mid-side nodes at mid-edges X~ = X, so
      // D X_s = M X_m also holds in the modified basis.
      const Eigen::VectorXd fs = (0.7 * s.coordinate(0) - 1.3 * s.coordinate(1)).array() + 0.4;
      const Eigen::VectorXd fm = (0.7 * m.coordinate(0) - 1.3 * m.coordinate(1)).array() + 0.4;
      EXPECT_LE((o.D * fs - o.M * fm).cwiseAbs().maxCoeff(), 1e-13);
      // Weighted gap of parallel planes: g~_j = h int Phi_j = h int N~_j.
      const MortarOperators up =
          assemble_mortar_operators(s.view(), m_up.view(), test::all_pairs(s, m_up), {mult, {}});
      const Eigen::VectorXd integrals = slave_integrals(s, mult);
      for (local_index node : s.nodes) {
        EXPECT_NEAR(up.weighted_gap[static_cast<std::size_t>(node)], h * integrals(node), 1e-15);
      }
    }
  }
}

TEST(Interface3D, CylindricalInterfaceRowSums) {
  // Two different discretisations of one half cylinder: the facets neither coincide nor match,
  // yet the row-sum identity holds to round-off.
  struct Combo {
    CellType slave, master;
    int sx, sy, mx, my;
  };
  for (const Combo c : {Combo{CellType::quad4, CellType::tri3, 8, 3, 5, 4},
                        Combo{CellType::quad9, CellType::tri6, 4, 2, 3, 3},
                        Combo{CellType::quad8, CellType::quad4, 4, 2, 7, 2}}) {
    const Surface s = cylinder(c.sx, c.sy, c.slave, 1.0, true);
    const Surface m = cylinder(c.mx, c.my, c.master, 1.0, false);
    for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
      SCOPED_TRACE(std::string(seam::fem::name(c.slave)) +
                   (mult == Multiplier::dual ? " dual" : " standard"));
      const MortarOperators ops =
          assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
      expect_row_sums(ops, s, m);
      EXPECT_EQ(ops.n_projection_failures, 0);
      // Covered area close to the half cylinder's pi * r * 1.5 (facets are chords).
      EXPECT_NEAR(ops.integrated_area / (1.5 * std::numbers::pi), 1.0, 0.02);
    }
  }
}

TEST(Interface3D, MeshInitialization) {
  // Coincident planar surfaces already satisfy D X_s = M X_m: nothing moves. A slave offset
  // by h below the master moves onto it, keeping its in-plane coordinates; quad8 with dual
  // multipliers goes through X = T X~.
  for (const CellType type : {CellType::quad4, CellType::quad8, CellType::tri6}) {
    for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
      SCOPED_TRACE(std::string(seam::fem::name(type)) +
                   (mult == Multiplier::dual ? " dual" : " standard"));
      const Surface m = plane(4, 5, CellType::tri3, 0.0, false);
      for (const double h : {0.0, 0.05}) {
        const Surface s = plane(3, 3, type, -h, true);
        const MortarOperators ops =
            assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
        const auto x = initialize_slave_coordinates(ops, s.coordinates, m.coordinates);
        for (local_index node : s.nodes) {
          const auto i = static_cast<std::size_t>(node);
          EXPECT_NEAR(x[3 * i], s.coordinates[3 * i], 1e-13);
          EXPECT_NEAR(x[3 * i + 1], s.coordinates[3 * i + 1], 1e-13);
          EXPECT_NEAR(x[3 * i + 2], 0.0, 1e-13);
        }
      }
    }
  }
}

TEST(Interface3D, PlanarInterfaceInGeneralPosition) {
  // The same non-matching pair of grids rotated and moved far from the origin: nothing may
  // depend on the interface being axis-aligned.
  const Eigen::Matrix3d R = (Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()) *
                             Eigen::AngleAxisd(-1.1, Eigen::Vector3d::UnitX()))
                                .toRotationMatrix();
  const Eigen::Vector3d shift(100.0, -50.0, 20.0);
  const auto placed = [&](double z, bool slave, int nx, int ny, CellType type) {
    return test::grid(
        nx, ny, type,
        [&, z](double u, double v) {
          return Eigen::Vector3d(R * Eigen::Vector3d(2 * u, v, z) + shift);
        },
        !slave);
  };
  const Surface s = placed(0.0, true, 3, 3, CellType::quad4);
  const Surface m = placed(0.0, false, 4, 5, CellType::tri3);
  for (const Multiplier mult : {Multiplier::standard, Multiplier::dual}) {
    const MortarOperators ops =
        assemble_mortar_operators(s.view(), m.view(), test::all_pairs(s, m), {mult, {}});
    expect_row_sums(ops, s, m);
    EXPECT_NEAR(ops.integrated_area, 2.0, 1e-11);
    const Dense o = dense(ops, s, m);
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE((o.D * s.coordinate(a) - o.M * m.coordinate(a)).cwiseAbs().maxCoeff(), 1e-11);
    }
    if (mult == Multiplier::standard) {
      EXPECT_NEAR(o.D.sum(), 2.0, 1e-11);
    }
  }
}
