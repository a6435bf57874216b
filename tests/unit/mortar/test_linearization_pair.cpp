// Linearization of single element pairs: the derivatives of D, M and g~ from linearize_pair
// against central differences of the independent double-valued integrate_pair (which
// recomputes the dual coefficients from the perturbed slave), on random perturbed flat,
// tilted, curved and sliding configurations, 2D and 3D, dual and standard multipliers; the
// values against integrate_pair itself.
#include <cstdio>
#include <functional>
#include <random>

#include <gtest/gtest.h>

#include "seam/mortar/linearization.hpp"

using namespace seam::mortar;
using seam::fem::CellType;

namespace {

// Largest |AD - FD| of each output row relative to the row's largest derivative (with a floor
// of 1e-3 of the overall largest, so structurally zero rows compare against the overall scale).
double max_relative_error(const std::function<Eigen::VectorXd(const Eigen::VectorXd&)>& f,
                          const Eigen::VectorXd& q, const Eigen::MatrixXd& ad, double h = 1e-7) {
  Eigen::MatrixXd fd(ad.rows(), ad.cols());
  for (int v = 0; v < q.size(); ++v) {
    Eigen::VectorXd qp = q, qm = q;
    qp(v) += h;
    qm(v) -= h;
    fd.col(v) = (f(qp) - f(qm)) / (2 * h);
  }
  const double global = std::max(ad.cwiseAbs().maxCoeff(), 1e-300);
  double worst = 0.0;
  for (int i = 0; i < ad.rows(); ++i) {
    const double scale = std::max(ad.row(i).cwiseAbs().maxCoeff(), 1e-3 * global);
    worst = std::max(worst, (ad.row(i) - fd.row(i)).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

template <int Dim> struct PairCase {
  Facet<Dim> slave;
  Eigen::Matrix<double, Dim, max_facet_nodes> normals =
      Eigen::Matrix<double, Dim, max_facet_nodes>::Zero();
  Facet<Dim> master;
};

// Pair variables (slave coordinates, master coordinates, slave normals) as one vector.
template <int Dim> Eigen::VectorXd pack(const PairCase<Dim>& c) {
  const int ns = c.slave.n_nodes, nm = c.master.n_nodes;
  Eigen::VectorXd q(Dim * (2 * ns + nm));
  for (int k = 0; k < ns; ++k) q.segment<Dim>(Dim * k) = c.slave.x.col(k);
  for (int l = 0; l < nm; ++l) q.segment<Dim>(Dim * (ns + l)) = c.master.x.col(l);
  for (int k = 0; k < ns; ++k) q.segment<Dim>(Dim * (ns + nm + k)) = c.normals.col(k);
  return q;
}

template <int Dim> PairCase<Dim> unpack(PairCase<Dim> c, const Eigen::VectorXd& q) {
  const int ns = c.slave.n_nodes, nm = c.master.n_nodes;
  for (int k = 0; k < ns; ++k) c.slave.x.col(k) = q.segment<Dim>(Dim * k);
  for (int l = 0; l < nm; ++l) c.master.x.col(l) = q.segment<Dim>(Dim * (ns + l));
  for (int k = 0; k < ns; ++k) c.normals.col(k) = q.segment<Dim>(Dim * (ns + nm + k));
  return c;
}

// D (all n_s^2 entries), M, g~ from the original double kernel.
template <int Dim>
Eigen::VectorXd reference_outputs(const PairCase<Dim>& c, Multiplier multiplier,
                                  const PairOptions& options = {}) {
  SlaveFacet<Dim> s;
  s.facet = c.slave;
  s.normals = c.normals;
  s.basis = make_slave_basis(c.slave, multiplier);
  const PairContribution r = integrate_pair(s, c.master, options);
  const int ns = c.slave.n_nodes, nm = c.master.n_nodes;
  Eigen::VectorXd out(ns * ns + ns * nm + ns);
  for (int j = 0; j < ns; ++j) {
    for (int k = 0; k < ns; ++k) out(j * ns + k) = r.D(j, k);
    for (int l = 0; l < nm; ++l) out(ns * ns + j * nm + l) = r.M(j, l);
    out(ns * ns + ns * nm + j) = r.weighted_gap(j);
  }
  return out;
}

struct Outcome {
  double max_error = 0.0;
  double max_value_difference = 0.0;
  int n_cells = 0;
};

template <int Dim>
Outcome check_pair(const PairCase<Dim>& c, Multiplier multiplier, const PairOptions& options = {}) {
  SlaveFacet<Dim> s;
  s.facet = c.slave;
  s.normals = c.normals;
  s.basis.multiplier = multiplier;
  PairLinearization lin;
  linearize_pair(s, c.master, options, lin);
  const int ns = c.slave.n_nodes, nm = c.master.n_nodes;
  Eigen::MatrixXd ad(ns * ns + ns * nm + ns, lin.n_variables);
  Eigen::VectorXd values(ad.rows());
  const auto put = [&](int row, std::span<const double> g, double value) {
    for (int v = 0; v < lin.n_variables; ++v) ad(row, v) = g[static_cast<std::size_t>(v)];
    values(row) = value;
  };
  for (int j = 0; j < ns; ++j) {
    for (int k = 0; k < ns; ++k) put(j * ns + k, lin.dD(j, k), lin.values.D(j, k));
    for (int l = 0; l < nm; ++l) put(ns * ns + j * nm + l, lin.dM(j, l), lin.values.M(j, l));
    put(ns * ns + ns * nm + j, lin.dgap(j), lin.values.weighted_gap(j));
  }
  const Eigen::VectorXd q = pack(c);
  const auto f = [&](const Eigen::VectorXd& x) {
    return reference_outputs(unpack(c, x), multiplier, options);
  };
  Outcome o;
  o.n_cells = lin.values.n_cells;
  o.max_error = max_relative_error(f, q, ad);
  o.max_value_difference =
      (values - f(q)).cwiseAbs().maxCoeff() / std::max(values.cwiseAbs().maxCoeff(), 1e-300);
  return o;
}

Eigen::Vector3d random_vector(std::mt19937& rng, double amplitude) {
  std::uniform_real_distribution<double> u(-amplitude, amplitude);
  return {u(rng), u(rng), u(rng)};
}

Eigen::Matrix3d rotation(const Eigen::Vector3d& axis_angle) {
  const double angle = axis_angle.norm();
  if (angle == 0.0) return Eigen::Matrix3d::Identity();
  return Eigen::AngleAxisd(angle, axis_angle / angle).toRotationMatrix();
}

enum class Shape { flat, tilted, curved };

// A slave facet about the origin facing +z and a master facing -z at gap h, shifted and turned
// about z so that its edges cut the slave's integration cells; then the whole pair rotated
// (tilted) and/or warped (curved) at random.
PairCase<3> random_pair_3d(CellType slave_type, CellType master_type, Shape shape,
                           std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const double curvature = shape == Shape::curved ? 0.3 : 0.0;
  const double warp = shape == Shape::curved ? 0.03 : 0.0;
  const auto place = [&](CellType type, bool flip, const Eigen::Matrix3d& R,
                         const Eigen::Vector3d& shift, double scale) {
    Facet<3> f;
    f.type = type;
    f.n_nodes = seam::fem::n_nodes(type);
    const double* X = seam::fem::reference_nodes(type).data();
    const bool triangle = type == CellType::tri3 || type == CellType::tri6;
    for (int i = 0; i < f.n_nodes; ++i) {
      double a = X[2 * i], b = X[2 * i + 1];
      if (triangle) a = 2 * a - 0.6, b = 2 * b - 0.6; // about the centroid, quad-like size
      if (flip) b = -b;
      Eigen::Vector3d p(scale * a, scale * b, 0.0);
      p = R * p + shift;
      p.z() += curvature * (p.x() * p.x() + 0.5 * p.y() * p.y());
      f.x.col(i) = p + random_vector(rng, 0.04 * scale) + Eigen::Vector3d(0, 0, warp * u(rng));
    }
    return f;
  };
  PairCase<3> c;
  c.slave = place(slave_type, false, Eigen::Matrix3d::Identity(), Eigen::Vector3d::Zero(), 0.5);
  const Eigen::Matrix3d turn = rotation(Eigen::Vector3d(0, 0, 0.6 * u(rng)));
  const Eigen::Matrix3d tilt = shape == Shape::tilted
                                   ? rotation(Eigen::Vector3d(0.15 * u(rng), 0.15 * u(rng), 0))
                                   : Eigen::Matrix3d::Identity();
  const Eigen::Vector3d shift(0.3 * u(rng), 0.3 * u(rng), 0.02 + 0.02 * u(rng));
  c.master = place(master_type, true, tilt * turn, shift, 0.45 + 0.1 * u(rng));
  // Nodal normals: the facet normal at the node, disturbed as a neighbour patch would.
  const double* X = seam::fem::reference_nodes(slave_type).data();
  for (int k = 0; k < c.slave.n_nodes; ++k) {
    const auto p = evaluate(c.slave, X + 2 * k);
    c.normals.col(k) = (scaled_normal<3>(p.dx).normalized() + random_vector(rng, 0.1)).normalized();
  }
  if (shape != Shape::flat) {
    const Eigen::Matrix3d R = rotation(random_vector(rng, 1.5));
    const Eigen::Vector3d t = random_vector(rng, 2.0);
    for (int k = 0; k < c.slave.n_nodes; ++k) {
      c.slave.x.col(k) = R * c.slave.x.col(k) + t;
      c.normals.col(k) = R * c.normals.col(k);
    }
    for (int l = 0; l < c.master.n_nodes; ++l) c.master.x.col(l) = R * c.master.x.col(l) + t;
  }
  return c;
}

// Slave line from x = 1 to x = 0 (normal +y), master from a to b at height h (normal -y);
// quadratic lines get curved mid nodes; all nodes perturbed; optionally rotated.
PairCase<2> random_pair_2d(CellType type, double a, double b, bool tilted, std::mt19937& rng) {
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  const auto line = [&](Eigen::Vector2d p0, Eigen::Vector2d p1, double bulge) {
    Facet<2> f;
    f.type = type;
    f.n_nodes = seam::fem::n_nodes(type);
    f.x.col(0) = p0 + 0.03 * Eigen::Vector2d(u(rng), u(rng));
    f.x.col(1) = p1 + 0.03 * Eigen::Vector2d(u(rng), u(rng));
    if (type == CellType::line3)
      f.x.col(2) = 0.5 * (p0 + p1) + Eigen::Vector2d(0.05 * u(rng), bulge);
    return f;
  };
  PairCase<2> c;
  c.slave = line({1, 0}, {0, 0}, 0.08);
  c.master = line({a, 0.03}, {b, 0.03}, 0.1);
  for (int k = 0; k < c.slave.n_nodes; ++k)
    c.normals.col(k) = Eigen::Vector2d(0.15 * u(rng), 1.0).normalized();
  if (tilted) {
    const double angle = 3.0 * u(rng);
    const Eigen::Matrix2d R = Eigen::Rotation2Dd(angle).toRotationMatrix();
    const Eigen::Vector2d t(u(rng), u(rng));
    for (int k = 0; k < c.slave.n_nodes; ++k) {
      c.slave.x.col(k) = R * c.slave.x.col(k) + t;
      c.normals.col(k) = R * c.normals.col(k);
    }
    for (int l = 0; l < c.master.n_nodes; ++l) c.master.x.col(l) = R * c.master.x.col(l) + t;
  }
  return c;
}

const char* name(Multiplier m) {
  return m == Multiplier::dual ? "dual" : "standard";
}

} // namespace

TEST(LinearizationPair2D, AllOverlapCasesAgainstFiniteDifferences) {
  std::mt19937 rng(7);
  struct Range {
    double a, b;
  };
  // Partial overlaps at either end, master inside slave, slave inside master.
  const std::array<Range, 4> ranges = {{{0.4, 1.5}, {-0.6, 0.45}, {0.2, 0.75}, {-0.4, 1.4}}};
  double worst = 0.0, worst_value = 0.0;
  for (const CellType type : {CellType::line2, CellType::line3}) {
    for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
      for (const Range r : ranges) {
        for (const bool tilted : {false, true}) {
          for (int trial = 0; trial < 3; ++trial) {
            const PairCase<2> c = random_pair_2d(type, r.a, r.b, tilted, rng);
            const Outcome o = check_pair(c, m);
            ASSERT_EQ(o.n_cells, 1);
            EXPECT_LT(o.max_error, 1e-6) << seam::fem::name(type) << " " << name(m) << " [" << r.a
                                         << ", " << r.b << "] tilted " << tilted;
            EXPECT_LT(o.max_value_difference, 1e-13);
            worst = std::max(worst, o.max_error);
            worst_value = std::max(worst_value, o.max_value_difference);
          }
        }
      }
    }
  }
  std::printf("[ 2D pairs ] worst relative derivative error %.2e, worst value difference %.2e\n",
              worst, worst_value);
}

TEST(LinearizationPair3D, LinearFacetsAgainstFiniteDifferences) {
  std::mt19937 rng(11);
  double worst = 0.0, worst_value = 0.0;
  const std::array<CellType, 2> types = {CellType::quad4, CellType::tri3};
  for (const CellType st : types) {
    for (const CellType mt : types) {
      for (const Shape shape : {Shape::flat, Shape::tilted, Shape::curved}) {
        for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
          for (int trial = 0; trial < 3; ++trial) {
            const PairCase<3> c = random_pair_3d(st, mt, shape, rng);
            const Outcome o = check_pair(c, m);
            ASSERT_GT(o.n_cells, 0);
            EXPECT_LT(o.max_error, 1e-6) << seam::fem::name(st) << "/" << seam::fem::name(mt)
                                         << " shape " << static_cast<int>(shape) << " " << name(m);
            EXPECT_LT(o.max_value_difference, 1e-13);
            worst = std::max(worst, o.max_error);
            worst_value = std::max(worst_value, o.max_value_difference);
          }
        }
      }
    }
  }
  std::printf("[ 3D linear pairs ] worst relative derivative error %.2e, worst value difference "
              "%.2e\n",
              worst, worst_value);
}

TEST(LinearizationPair3D, QuadraticFacetsAgainstFiniteDifferences) {
  std::mt19937 rng(13);
  double worst = 0.0;
  const std::array<std::array<CellType, 2>, 5> combos = {{{CellType::quad8, CellType::quad8},
                                                          {CellType::quad9, CellType::quad4},
                                                          {CellType::tri6, CellType::tri6},
                                                          {CellType::quad4, CellType::quad9},
                                                          {CellType::tri6, CellType::quad8}}};
  for (const auto& combo : combos) {
    for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
      const PairCase<3> c = random_pair_3d(combo[0], combo[1], Shape::curved, rng);
      const Outcome o = check_pair(c, m);
      ASSERT_GT(o.n_cells, 0);
      EXPECT_LT(o.max_error, 1e-6)
          << seam::fem::name(combo[0]) << "/" << seam::fem::name(combo[1]) << " " << name(m);
      EXPECT_LT(o.max_value_difference, 1e-13);
      worst = std::max(worst, o.max_error);
    }
  }
  std::printf("[ 3D quadratic pairs ] worst relative derivative error %.2e\n", worst);
}

// The higher-degree cell rule (seam::fem's triangle rule instead of the 7-point one) on linear
// facets, and a slave facet reused for several masters (the dual coefficients are computed
// per call): derivatives against central differences, values against integrate_pair.
TEST(LinearizationPair3D, HigherCellRuleAndRepeatedCalls) {
  std::mt19937 rng(17);
  PairOptions options;
  options.cell_quadrature_degree = 8;
  double worst = 0.0;
  PairLinearization reused;
  for (const CellType st : {CellType::tri3, CellType::quad4}) {
    for (const CellType mt : {CellType::quad4, CellType::tri3}) {
      for (const Multiplier m : {Multiplier::dual, Multiplier::standard}) {
        const PairCase<3> c = random_pair_3d(st, mt, Shape::curved, rng);
        const Outcome o = check_pair(c, m, options);
        ASSERT_GT(o.n_cells, 0);
        EXPECT_LT(o.max_error, 1e-6) << seam::fem::name(st) << "/" << seam::fem::name(mt);
        EXPECT_LT(o.max_value_difference, 1e-13);
        worst = std::max(worst, o.max_error);
        // The same pair through a PairLinearization that held a larger pair before: the
        // result does not depend on what the reused buffers contained.
        SlaveFacet<3> s;
        s.facet = c.slave;
        s.normals = c.normals;
        s.basis.multiplier = m;
        PairLinearization fresh;
        linearize_pair(s, c.master, options, fresh);
        linearize_pair(s, c.master, options, reused);
        ASSERT_EQ(fresh.M_gradient.size(), reused.M_gradient.size());
        for (std::size_t i = 0; i < fresh.M_gradient.size(); ++i)
          ASSERT_EQ(fresh.M_gradient[i], reused.M_gradient[i]);
        for (std::size_t i = 0; i < fresh.gap_gradient.size(); ++i)
          ASSERT_EQ(fresh.gap_gradient[i], reused.gap_gradient[i]);
      }
    }
  }
  std::printf("[ 3D pairs, degree-8 cells ] worst relative derivative error %.2e\n", worst);
}
