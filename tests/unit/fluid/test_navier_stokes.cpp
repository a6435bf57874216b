// The Navier-Stokes kernel: the Jacobian against central differences of the residual on
// distorted cells of every type (Taylor-Hood and stabilized linear), on fixed and moving (ALE)
// meshes, the Stokes part symmetric, and
// consistency: a state that interpolates an exact solution of the equations (a uniform flow with a
// constant pressure) leaves no residual in the cell's interior dofs.
#include "seam/fluid/navier_stokes.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

using namespace seam;
using fem::CellType;

namespace {

struct Cell {
  CellType type;
  std::vector<double> x, w; // coordinates; state: velocity then vertex pressure
};

// The reference cell, stretched, sheared and perturbed, with a random smooth state.
Cell make_cell(CellType type, unsigned seed) {
  const int dim = fem::dimension(type);
  const int n = fem::n_nodes(type);
  const auto ref = fem::reference_nodes(type);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.05, 0.05), value(-1.0, 1.0);
  Cell c{type, std::vector<double>(n * dim), {}};
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) {
      double v = ref[a * dim + i] * (1.0 + 0.3 * i);
      if (i == 0) v += 0.2 * ref[a * dim + 1];
      c.x[a * dim + i] = v + jitter(rng);
    }
  c.w.resize(fluid::n_element_dofs(type));
  for (auto& v : c.w) v = value(rng);
  return c;
}

fluid::FluidElementInput input(const Cell& c, const std::vector<double>& w) {
  const int dim = fem::dimension(c.type);
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * dim);
  fluid::FluidElementInput in;
  in.cell = c.type;
  in.dim = dim;
  in.fluid = {2.0, 0.3};
  in.x = c.x;
  in.u = std::span<const double>(w.data(), nu);
  in.p = std::span<const double>(w.data() + nu, w.size() - nu);
  return in;
}

// The largest difference between K and the central differences of `residual` at w, relative
// to the largest entry of K.
template <class Residual>
double jacobian_error(const Residual& residual, const std::vector<double>& w) {
  const auto nd = w.size();
  std::vector<double> r(nd), K(nd * nd), rp(nd), rm(nd), none;
  EXPECT_TRUE(residual(w, r, K));
  const double h = 1e-6;
  double scale = 0.0, worst = 0.0;
  for (double v : K) scale = std::max(scale, std::abs(v));
  for (std::size_t j = 0; j < nd; ++j) {
    auto wp = w, wm = w;
    wp[j] += h;
    wm[j] -= h;
    EXPECT_TRUE(residual(wp, rp, none));
    EXPECT_TRUE(residual(wm, rm, none));
    for (std::size_t i = 0; i < nd; ++i)
      worst = std::max(worst, std::abs((rp[i] - rm[i]) / (2 * h) - K[i * nd + j]));
  }
  return worst / scale;
}

class NavierStokes : public ::testing::TestWithParam<CellType> {};

TEST_P(NavierStokes, JacobianMatchesCentralDifferences) {
  const auto c = make_cell(GetParam(), 7);
  const auto residual = [&](const std::vector<double>& w, std::vector<double>& r,
                            std::vector<double>& K) {
    return fluid::navier_stokes(input(c, w), r, K);
  };
  EXPECT_LT(jacobian_error(residual, c.w), 1e-7) << fem::name(GetParam());
}

// Generalized-alpha: the state (u, p) = af w + (1 - af) w0 and the rate u_dot = m (w - u0) + d0
// depend on the unknown w; the weighted Jacobian must be the derivative by w.
TEST_P(NavierStokes, TimeIntegrationJacobianMatchesCentralDifferences) {
  const auto c = make_cell(GetParam(), 11);
  const auto old = make_cell(GetParam(), 12).w;
  const auto nd = c.w.size();
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * fem::dimension(c.type));
  const double af = 0.6, m = 7.0;
  std::vector<double> state(nd), rate(nu);
  const auto residual = [&](const std::vector<double>& w, std::vector<double>& r,
                            std::vector<double>& K) {
    for (std::size_t k = 0; k < nd; ++k) state[k] = af * w[k] + (1 - af) * old[k];
    for (std::size_t k = 0; k < nu; ++k) rate[k] = m * (w[k] - old[k]) + 0.3;
    auto in = input(c, state);
    in.u_dot = rate;
    in.state_weight = af;
    in.mass_weight = m;
    in.time_step = 0.1;
    return fluid::navier_stokes(in, r, K);
  };
  EXPECT_LT(jacobian_error(residual, c.w), 1e-7) << fem::name(GetParam());
}

// ALE: the convective velocity u - w with a random mesh velocity w, in generalized-alpha; K
// is the derivative by the unknown (u, p) at the given mesh motion.
TEST_P(NavierStokes, AleJacobianMatchesCentralDifferences) {
  const auto c = make_cell(GetParam(), 21);
  const auto old = make_cell(GetParam(), 22).w;
  const auto mesh_velocity = make_cell(GetParam(), 23).w;
  const auto nd = c.w.size();
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * fem::dimension(c.type));
  const double af = 0.7, m = 5.0;
  std::vector<double> state(nd), rate(nu);
  const auto residual = [&](const std::vector<double>& w, std::vector<double>& r,
                            std::vector<double>& K) {
    for (std::size_t k = 0; k < nd; ++k) state[k] = af * w[k] + (1 - af) * old[k];
    for (std::size_t k = 0; k < nu; ++k) rate[k] = m * (w[k] - old[k]) - 0.2;
    auto in = input(c, state);
    in.u_dot = rate;
    in.mesh_velocity = std::span<const double>(mesh_velocity.data(), nu);
    in.state_weight = af;
    in.mass_weight = m;
    in.time_step = 0.05;
    return fluid::navier_stokes(in, r, K);
  };
  EXPECT_LT(jacobian_error(residual, c.w), 1e-7) << fem::name(GetParam());
  // The steady form as well (no rate, dt = 0).
  const auto steady = [&](const std::vector<double>& w, std::vector<double>& r,
                          std::vector<double>& K) {
    auto in = input(c, w);
    in.mesh_velocity = std::span<const double>(mesh_velocity.data(), nu);
    return fluid::navier_stokes(in, r, K);
  };
  EXPECT_LT(jacobian_error(steady, c.w), 1e-7) << fem::name(GetParam());
}

// The shape derivatives (a moving mesh whose motion is an unknown, as in fluid-structure
// interaction): the derivatives of the residual by every node coordinate and every nodal mesh
// velocity against central differences, in generalized-alpha with a position-dependent body
// force, and in the steady form.
TEST_P(NavierStokes, MeshDerivativesMatchCentralDifferences) {
  const auto c = make_cell(GetParam(), 31);
  const auto rates = make_cell(GetParam(), 32).w;
  const auto velocities = make_cell(GetParam(), 33).w;
  const int dim = fem::dimension(c.type);
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * dim);
  const auto nd = c.w.size();
  const fluid::BodyForce force = [dim](const double* x, double* f) {
    for (int i = 0; i < dim; ++i) f[i] = std::sin(1.3 * x[0] + i) * std::cos(0.7 * x[dim - 1]);
  };
  for (const bool steady : {false, true}) {
    std::vector<double> x = c.x, w(velocities.begin(), velocities.begin() + nu);
    const auto make = [&] {
      auto in = input(c, c.w);
      in.x = x;
      in.mesh_velocity = w;
      in.body_force = &force;
      if (!steady) {
        in.u_dot = std::span<const double>(rates.data(), nu);
        in.time_step = 0.05;
      }
      return in;
    };
    std::vector<double> Dx(nd * nu), Dw(nd * nu), rp(nd), rm(nd), none;
    ASSERT_TRUE(fluid::navier_stokes_mesh_derivatives(make(), Dx, Dw));
    for (auto* variable : {&x, &w}) {
      const auto& D = variable == &x ? Dx : Dw;
      double scale = 0.0, worst = 0.0;
      for (double v : D) scale = std::max(scale, std::abs(v));
      const double h = 1e-6;
      for (std::size_t k = 0; k < nu; ++k) {
        const double keep = (*variable)[k];
        (*variable)[k] = keep + h;
        ASSERT_TRUE(fluid::navier_stokes(make(), rp, none));
        (*variable)[k] = keep - h;
        ASSERT_TRUE(fluid::navier_stokes(make(), rm, none));
        (*variable)[k] = keep;
        for (std::size_t i = 0; i < nd; ++i)
          worst = std::max(worst, std::abs((rp[i] - rm[i]) / (2 * h) - D[i * nu + k]));
      }
      EXPECT_GT(scale, 0.0);
      EXPECT_LT(worst / scale, 1e-7) << fem::name(GetParam()) << (steady ? " steady" : " unsteady")
                                     << (variable == &x ? ", by position" : ", by mesh velocity");
    }
  }
}

// The consistent initial state of time integration: the unknowns are the rate u_dot and the
// pressure at a given velocity u (and mesh velocity); K must be the derivative of the residual
// by (u_dot, p). On Taylor-Hood cells the continuity rows are the time derivative of the
// constraint, - int M_k div u_dot: by u_dot the same rows as the steady Jacobian's by u.
TEST_P(NavierStokes, InitialRateJacobianMatchesCentralDifferences) {
  const auto c = make_cell(GetParam(), 51);
  const auto mesh_velocity = make_cell(GetParam(), 52).w;
  const auto nd = c.w.size();
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * fem::dimension(c.type));
  std::vector<double> state = c.w, rate(nu);
  const auto evaluate = [&](const std::vector<double>& y, std::vector<double>& r,
                            std::vector<double>& K) {
    for (std::size_t k = nu; k < nd; ++k) state[k] = y[k];
    for (std::size_t k = 0; k < nu; ++k) rate[k] = y[k];
    auto in = input(c, state);
    in.u_dot = rate;
    in.mesh_velocity = std::span<const double>(mesh_velocity.data(), nu);
    in.state_weight = 0.0;
    in.mass_weight = 1.0;
    in.time_step = 0.05;
    in.initial_rate = true;
    return fluid::navier_stokes(in, r, K);
  };
  const auto y = make_cell(GetParam(), 53).w;
  EXPECT_LT(jacobian_error(evaluate, y), 1e-7) << fem::name(GetParam());
  if (!fluid::is_taylor_hood(c.type)) return;
  std::vector<double> r(nd), K(nd * nd), rs(nd), Ks(nd * nd);
  ASSERT_TRUE(evaluate(y, r, K));
  ASSERT_TRUE(fluid::navier_stokes(input(c, c.w), rs, Ks));
  double scale = 0.0;
  for (double v : K) scale = std::max(scale, std::abs(v));
  for (std::size_t i = nu; i < nd; ++i)
    for (std::size_t j = 0; j < nd; ++j)
      EXPECT_NEAR(K[i * nd + j], j < nu ? Ks[i * nd + j] : 0.0, 1e-14 * scale) << i << ", " << j;
}

// A mesh that moves with the flow (w = u) leaves no convection: the steady residual of the
// Galerkin (Taylor-Hood) cells is that of the Stokes equations, the fluid's density set to 0.
TEST_P(NavierStokes, MeshMovingWithTheFlowRemovesConvection) {
  if (fluid::is_stabilized(GetParam())) GTEST_SKIP() << "tau depends on the density";
  const auto c = make_cell(GetParam(), 31);
  const auto nd = c.w.size();
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * fem::dimension(c.type));
  std::vector<double> r_ale(nd), r_stokes(nd);
  auto in = input(c, c.w);
  in.mesh_velocity = std::span<const double>(c.w.data(), nu);
  ASSERT_TRUE(fluid::navier_stokes(in, r_ale, {}));
  auto creeping = input(c, c.w);
  creeping.fluid.density = 0.0;
  ASSERT_TRUE(fluid::navier_stokes(creeping, r_stokes, {}));
  double scale = 0.0;
  for (double v : r_stokes) scale = std::max(scale, std::abs(v));
  for (std::size_t k = 0; k < nd; ++k) EXPECT_NEAR(r_ale[k], r_stokes[k], 1e-13 * scale) << k;
}

TEST_P(NavierStokes, UniformFlowOnMovingMeshHasNoResidual) {
  // The element level of free-stream preservation: a uniform u, constant p, any mesh velocity.
  auto c = make_cell(GetParam(), 41);
  const auto mesh_velocity = make_cell(GetParam(), 42).w;
  const int dim = fem::dimension(c.type);
  const int n = fem::n_nodes(c.type);
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) c.w[a * dim + i] = 1.0 - 0.7 * i;
  for (std::size_t k = n * dim; k < c.w.size(); ++k) c.w[k] = -2.0;
  std::vector<double> r(c.w.size()), zero_rate(static_cast<std::size_t>(n * dim), 0.0);
  auto in = input(c, c.w);
  in.mesh_velocity =
      std::span<const double>(mesh_velocity.data(), static_cast<std::size_t>(n * dim));
  in.u_dot = zero_rate;
  in.time_step = 0.01;
  ASSERT_TRUE(fluid::navier_stokes(in, r, {}));
  for (std::size_t k = n * dim; k < r.size(); ++k) EXPECT_NEAR(r[k], 0.0, 1e-12);
  for (int i = 0; i < dim; ++i) {
    double sum = 0.0;
    for (int a = 0; a < n; ++a) sum += r[a * dim + i];
    EXPECT_NEAR(sum, 0.0, 1e-12);
  }
}

TEST_P(NavierStokes, StokesPartIsSymmetric) {
  auto c = make_cell(GetParam(), 3);
  const auto nd = c.w.size();
  const auto nu = static_cast<std::size_t>(fem::n_nodes(c.type) * fem::dimension(c.type));
  std::fill(c.w.begin(), c.w.begin() + nu, 0.0); // no flow: no convection
  // Stabilized cells: the derivative of the SUPG test function by u times the residual grad p
  // is not symmetric; at rest with no pressure gradient the Stokes block is.
  if (fluid::is_stabilized(c.type)) std::fill(c.w.begin(), c.w.end(), 0.0);
  std::vector<double> r(nd), K(nd * nd);
  ASSERT_TRUE(fluid::navier_stokes(input(c, c.w), r, K));
  for (std::size_t i = 0; i < nd; ++i)
    for (std::size_t j = 0; j < i; ++j)
      EXPECT_NEAR(K[i * nd + j], K[j * nd + i], 1e-12 * (1 + std::abs(K[i * nd + j])));
}

TEST_P(NavierStokes, UniformFlowHasNoResidual) {
  auto c = make_cell(GetParam(), 5);
  const int dim = fem::dimension(c.type);
  const int n = fem::n_nodes(c.type);
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i) c.w[a * dim + i] = 1.0 + 0.5 * i;
  for (std::size_t k = n * dim; k < c.w.size(); ++k) c.w[k] = 3.0;
  std::vector<double> r(c.w.size());
  ASSERT_TRUE(fluid::navier_stokes(input(c, c.w), r, {}));
  // The pressure rows vanish (div u = 0); the momentum rows hold only the boundary term of the
  // constant pressure, int p dN_a/dx_i, whose sum over the nodes is zero.
  for (std::size_t k = n * dim; k < r.size(); ++k) EXPECT_NEAR(r[k], 0.0, 1e-12);
  for (int i = 0; i < dim; ++i) {
    double sum = 0.0;
    for (int a = 0; a < n; ++a) sum += r[a * dim + i];
    EXPECT_NEAR(sum, 0.0, 1e-12);
  }
}

TEST(NavierStokesCells, PressureCellsAndRejection) {
  EXPECT_EQ(fluid::pressure_cell(CellType::quad9), CellType::quad4);
  EXPECT_EQ(fluid::pressure_cell(CellType::tet10), CellType::tet4);
  EXPECT_FALSE(fluid::is_taylor_hood(CellType::quad8));
  EXPECT_EQ(fluid::pressure_cell(CellType::quad4), CellType::quad4);
  EXPECT_TRUE(fluid::is_stabilized(CellType::tet4));
  EXPECT_THROW(fluid::pressure_cell(CellType::quad8), std::exception);
  EXPECT_EQ(fluid::n_element_dofs(CellType::tri6), 6 * 2 + 3);
}

INSTANTIATE_TEST_SUITE_P(FluidCells, NavierStokes,
                         ::testing::Values(CellType::tri6, CellType::quad9, CellType::tet10,
                                           CellType::hex27, CellType::tri3, CellType::quad4,
                                           CellType::tet4, CellType::hex8),
                         [](const auto& info) { return std::string(fem::name(info.param)); });

} // namespace
