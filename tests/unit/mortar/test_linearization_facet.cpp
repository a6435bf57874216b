// Linearization of whole slave facets with their averaged nodal normals, against the
// interface assembly of seam::mortar: the values summed over all slave facets equal
// assemble_mortar_operators, and the derivatives with respect to every involved coordinate —
// slave facet nodes, the neighbour nodes behind the nodal normals, master nodes — equal
// central differences of assemble_mortar_operators restricted to that slave facet's pairs.
// Curved, perturbed, non-matching (sliding) interfaces in 2D and 3D, dual and standard.
#include <algorithm>
#include <cstdio>
#include <functional>
#include <numbers>
#include <numeric>
#include <random>

#include <gtest/gtest.h>

#include "mortar_test_support.hpp"
#include "seam/mortar/linearization.hpp"

using namespace seam::mortar;
using seam::local_index;
using seam::fem::CellType;
using test::Surface;

namespace {

MortarOptions options_for(Multiplier m) {
  MortarOptions o;
  o.multiplier = m;
  return o;
}

void perturb(Surface& s, std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  for (double& x : s.coordinates) x += u(rng);
}

struct Interface {
  Surface slave;
  Surface master;
};

// Curved 3D interface: slave over [0,1]^2 facing +z, master over a turned, shifted square
// facing -z at a small gap, both on the same wavy surface, nodes perturbed.
Interface interface_3d(CellType slave_type, CellType master_type, int ns, int nm,
                       std::mt19937& rng) {
  const auto height = [](double x, double y) { return 0.15 * std::sin(2.0 * x) * std::cos(y); };
  Interface i;
  i.slave = test::grid(
      ns, ns, slave_type, [&](double u, double v) { return Eigen::Vector3d(u, v, height(u, v)); },
      false);
  const double c = std::cos(0.3), s = std::sin(0.3);
  i.master = test::grid(
      nm, nm, master_type,
      [&](double u, double v) {
        const double x = 1.3 * (c * u - s * v) - 0.05, y = 1.3 * (s * u + c * v) - 0.3;
        return Eigen::Vector3d(x, y, height(x, y) + 0.02);
      },
      true);
  perturb(i.slave, rng, 0.02);
  perturb(i.master, rng, 0.02);
  return i;
}

// Curved 2D interface: arcs, slave facing outward, master inward at a small gap.
Interface interface_2d(CellType type, int ns, int nm, std::mt19937& rng) {
  Interface i;
  i.slave = test::line_mesh(
      ns, type,
      [](double t) {
        const double a = 0.5 * std::numbers::pi * t;
        return Eigen::Vector2d(std::cos(a), std::sin(a));
      },
      true);
  i.master = test::line_mesh(
      nm, type,
      [](double t) {
        const double a = 0.5 * std::numbers::pi * (1.1 * t - 0.05);
        return Eigen::Vector2d(1.01 * std::cos(a), 1.01 * std::sin(a));
      },
      false);
  perturb(i.slave, rng, 0.01);
  perturb(i.master, rng, 0.01);
  return i;
}

std::vector<CandidatePair> candidates_of(local_index slave_facet, local_index n_master) {
  std::vector<CandidatePair> pairs;
  for (local_index m = 0; m < n_master; ++m) pairs.push_back({slave_facet, m});
  return pairs;
}

// Outputs of one slave facet from the interface assembly, in the layout of
// SlaveFacetLinearization (D, M over master_nodes, g~).
Eigen::VectorXd assembled_outputs(const Interface& i, local_index slave_facet,
                                  const SlaveFacetLinearization& lin, Multiplier m) {
  const auto pairs = candidates_of(slave_facet, i.master.view().n_facets());
  const MortarOperators ops =
      assemble_mortar_operators(i.slave.view(), i.master.view(), pairs, options_for(m));
  const Eigen::MatrixXd D = test::dense(ops.D, i.slave.n_nodes(), i.slave.n_nodes());
  const Eigen::MatrixXd M = test::dense(ops.M, i.slave.n_nodes(), i.master.n_nodes());
  const int ns = lin.n_slave, nm = lin.n_master_nodes();
  Eigen::VectorXd out(ns * ns + ns * nm + ns);
  for (int j = 0; j < ns; ++j) {
    const local_index row = lin.slave_nodes[static_cast<std::size_t>(j)];
    for (int k = 0; k < ns; ++k)
      out(j * ns + k) = D(row, lin.slave_nodes[static_cast<std::size_t>(k)]);
    for (int p = 0; p < nm; ++p)
      out(ns * ns + j * nm + p) = M(row, lin.master_nodes[static_cast<std::size_t>(p)]);
    out(ns * ns + ns * nm + j) = ops.weighted_gap[static_cast<std::size_t>(row)];
  }
  return out;
}

struct FacetCheck {
  double max_error = 0.0;
  double max_outside = 0.0; ///< |FD derivative| w.r.t. slave nodes outside the variables
  int n_variables = 0;
};

FacetCheck check_facet(const Interface& iface, local_index slave_facet, Multiplier m) {
  const NodeFacets adjacency = node_facets(iface.slave.view());
  std::vector<local_index> masters(static_cast<std::size_t>(iface.master.view().n_facets()));
  std::iota(masters.begin(), masters.end(), local_index{0});
  SlaveFacetLinearization lin;
  linearize_slave_facet(iface.slave.view(), iface.master.view(), adjacency, slave_facet, masters,
                        options_for(m), lin);
  EXPECT_GT(lin.n_pairs_integrated, 0);
  const int dim = iface.slave.dim, ns = lin.n_slave, nm = lin.n_master_nodes();
  const int nv = lin.n_variables();
  Eigen::MatrixXd ad(ns * ns + ns * nm + ns, nv);
  for (int j = 0; j < ns; ++j) {
    for (int v = 0; v < nv; ++v) {
      for (int k = 0; k < ns; ++k) ad(j * ns + k, v) = lin.dD(j, k)[static_cast<std::size_t>(v)];
      for (int p = 0; p < nm; ++p)
        ad(ns * ns + j * nm + p, v) = lin.dM(j, p)[static_cast<std::size_t>(v)];
      ad(ns * ns + ns * nm + j, v) = lin.dgap(j)[static_cast<std::size_t>(v)];
    }
  }
  // Coordinates behind variable v.
  const int n_slave_variables = dim * static_cast<int>(lin.slave_nodes.size());
  const auto coordinate = [&](Interface& i, int v) -> double& {
    if (v < n_slave_variables) {
      const local_index node = lin.slave_nodes[static_cast<std::size_t>(v / dim)];
      return i.slave.coordinates[static_cast<std::size_t>(node * dim + v % dim)];
    }
    const int w = v - n_slave_variables;
    const local_index node = lin.master_nodes[static_cast<std::size_t>(w / dim)];
    return i.master.coordinates[static_cast<std::size_t>(node * dim + w % dim)];
  };
  constexpr double h = 1e-7;
  Eigen::MatrixXd fd(ad.rows(), nv);
  Interface work = iface;
  for (int v = 0; v < nv; ++v) {
    double& x = coordinate(work, v);
    const double x0 = x;
    x = x0 + h;
    const Eigen::VectorXd plus = assembled_outputs(work, slave_facet, lin, m);
    x = x0 - h;
    const Eigen::VectorXd minus = assembled_outputs(work, slave_facet, lin, m);
    x = x0;
    fd.col(v) = (plus - minus) / (2 * h);
  }
  FacetCheck r;
  r.n_variables = nv;
  const double global = ad.cwiseAbs().maxCoeff();
  for (int i = 0; i < ad.rows(); ++i) {
    const double scale = std::max(ad.row(i).cwiseAbs().maxCoeff(), 1e-3 * global);
    r.max_error = std::max(r.max_error, (ad.row(i) - fd.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  // Slave nodes outside the facet's normal patches must not matter.
  for (local_index node = 0; node < iface.slave.n_nodes(); ++node) {
    if (std::find(lin.slave_nodes.begin(), lin.slave_nodes.end(), node) != lin.slave_nodes.end())
      continue;
    if (adjacency.of(node).empty()) continue;
    for (int a = 0; a < dim; ++a) {
      double& x = work.slave.coordinates[static_cast<std::size_t>(node * dim + a)];
      const double x0 = x;
      x = x0 + 1e-3;
      const Eigen::VectorXd plus = assembled_outputs(work, slave_facet, lin, m);
      x = x0;
      const Eigen::VectorXd base = assembled_outputs(work, slave_facet, lin, m);
      r.max_outside = std::max(r.max_outside, (plus - base).cwiseAbs().maxCoeff());
    }
  }
  return r;
}

// Values of all slave facets summed against the interface assembly.
double value_difference(const Interface& i, Multiplier m) {
  const FacetSet s = i.slave.view(), ms = i.master.view();
  const MortarOperators ops =
      assemble_mortar_operators(s, ms, test::all_pairs(i.slave, i.master), options_for(m));
  Eigen::MatrixXd D = test::dense(ops.D, i.slave.n_nodes(), i.slave.n_nodes());
  Eigen::MatrixXd M = test::dense(ops.M, i.slave.n_nodes(), i.master.n_nodes());
  Eigen::VectorXd g = Eigen::Map<const Eigen::VectorXd>(ops.weighted_gap.data(), i.slave.n_nodes());
  const double scale = D.cwiseAbs().maxCoeff();
  const NodeFacets adjacency = node_facets(s);
  std::vector<local_index> masters(static_cast<std::size_t>(ms.n_facets()));
  std::iota(masters.begin(), masters.end(), local_index{0});
  SlaveFacetLinearization lin;
  for (local_index f = 0; f < s.n_facets(); ++f) {
    linearize_slave_facet(s, ms, adjacency, f, masters, options_for(m), lin);
    for (int j = 0; j < lin.n_slave; ++j) {
      const local_index row = lin.slave_nodes[static_cast<std::size_t>(j)];
      for (int k = 0; k < lin.n_slave; ++k)
        D(row, lin.slave_nodes[static_cast<std::size_t>(k)]) -=
            lin.D[static_cast<std::size_t>(j * lin.n_slave + k)];
      for (int p = 0; p < lin.n_master_nodes(); ++p)
        M(row, lin.master_nodes[static_cast<std::size_t>(p)]) -=
            lin.M[static_cast<std::size_t>(j * lin.n_master_nodes() + p)];
      g(row) -= lin.weighted_gap[static_cast<std::size_t>(j)];
    }
  }
  return std::max({D.cwiseAbs().maxCoeff(), M.cwiseAbs().maxCoeff(), g.cwiseAbs().maxCoeff()}) /
         scale;
}

const char* name(Multiplier m) {
  return m == Multiplier::dual ? "dual" : "standard";
}

} // namespace

TEST(LinearizationFacet, Curved3DInterfaceAgainstAssembly) {
  std::mt19937 rng(23);
  struct Case {
    CellType slave, master;
    int ns, nm;
  };
  double worst = 0.0, worst_value = 0.0;
  for (const Case c :
       {Case{CellType::quad4, CellType::quad4, 3, 4}, Case{CellType::tri3, CellType::quad4, 3, 3},
        Case{CellType::quad4, CellType::tri3, 3, 3}}) {
    const Interface iface = interface_3d(c.slave, c.master, c.ns, c.nm, rng);
    for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
      const double dv = value_difference(iface, m);
      EXPECT_LT(dv, 1e-13);
      worst_value = std::max(worst_value, dv);
      // An interior facet (full normal patches) and a corner facet.
      const local_index interior = c.slave == CellType::quad4 ? 4 : 8;
      for (const local_index f : {interior, local_index{0}}) {
        const FacetCheck r = check_facet(iface, f, m);
        EXPECT_LT(r.max_error, 1e-6) << seam::fem::name(c.slave) << "/" << seam::fem::name(c.master)
                                     << " facet " << f << " " << name(m);
        EXPECT_LT(r.max_outside, 1e-14);
        worst = std::max(worst, r.max_error);
      }
    }
  }
  std::printf("[ 3D slave facets ] worst relative derivative error %.2e, worst value difference "
              "%.2e\n",
              worst, worst_value);
}

TEST(LinearizationFacet, Quadratic3DInterfaceAgainstAssembly) {
  std::mt19937 rng(29);
  double worst = 0.0;
  for (const CellType type : {CellType::quad8, CellType::tri6}) {
    const Interface iface = interface_3d(type, CellType::quad4, 2, 3, rng);
    for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
      EXPECT_LT(value_difference(iface, m), 1e-13);
      const FacetCheck r = check_facet(iface, 0, m);
      EXPECT_LT(r.max_error, 1e-6) << seam::fem::name(type) << " " << name(m);
      worst = std::max(worst, r.max_error);
    }
  }
  std::printf("[ 3D quadratic slave facets ] worst relative derivative error %.2e\n", worst);
}

TEST(LinearizationFacet, Curved2DInterfaceAgainstAssembly) {
  std::mt19937 rng(31);
  double worst = 0.0, worst_value = 0.0;
  for (const CellType type : {CellType::line2, CellType::line3}) {
    const Interface iface = interface_2d(type, 5, 4, rng);
    for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
      const double dv = value_difference(iface, m);
      EXPECT_LT(dv, 1e-13);
      worst_value = std::max(worst_value, dv);
      for (const local_index f : {local_index{2}, local_index{0}}) {
        const FacetCheck r = check_facet(iface, f, m);
        EXPECT_LT(r.max_error, 1e-6) << seam::fem::name(type) << " facet " << f << " " << name(m);
        EXPECT_LT(r.max_outside, 1e-14);
        worst = std::max(worst, r.max_error);
      }
    }
  }
  std::printf("[ 2D slave facets ] worst relative derivative error %.2e, worst value difference "
              "%.2e\n",
              worst, worst_value);
}

TEST(LinearizationFacet, NodeFacetsAndInputErrors) {
  std::mt19937 rng(37);
  const Interface iface = interface_3d(CellType::quad4, CellType::quad4, 2, 2, rng);
  const NodeFacets adjacency = node_facets(iface.slave.view());
  // 2 x 2 quads on a 5 x 5 lattice: the corner nodes of the grid lie on 1 facet, the centre on 4.
  EXPECT_EQ(adjacency.of(0).size(), 1u);
  EXPECT_EQ(adjacency.of(12).size(), 4u);
  EXPECT_TRUE(adjacency.of(1).empty()); // lattice mid-point, used only by quadratic facets
  SlaveFacetLinearization lin;
  const std::vector<local_index> masters = {0, 7};
  EXPECT_THROW(linearize_slave_facet(iface.slave.view(), iface.master.view(), adjacency, 0, masters,
                                     {}, lin),
               seam::InputError);
  EXPECT_THROW(linearize_slave_facet(iface.slave.view(), iface.master.view(), adjacency, 9,
                                     std::vector<local_index>{0}, {}, lin),
               seam::InputError);
}
