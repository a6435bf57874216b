// Energy-momentum element kernel: the discrete energy balance (u_{n+1} - u_n) . f_alg =
// Pi(u_{n+1}) - Pi(u_n), linear and angular momentum, the tangent against central differences
// (also next to the small-increment switch), and the limit u_{n+1} -> u_n.
#include "test_util.hpp"

#include "seam/solid/algorithmic_force.hpp"
#include "seam/solid/element.hpp"

#include <gtest/gtest.h>

using namespace seam;
using namespace seam::solid;
using namespace seam::solid::test;

namespace {

struct Setup {
  fem::CellType cell;
  int dim;
  PlaneMode mode;
};

std::vector<Setup> all_setups() {
  std::vector<Setup> s;
  for (auto c : cells_2d) {
    s.push_back({c, 2, PlaneMode::plane_strain});
    s.push_back({c, 2, PlaneMode::plane_stress});
  }
  for (auto c : cells_3d) s.push_back({c, 3, PlaneMode::none});
  return s;
}

std::string label(const Setup& s, MaterialModel m) {
  const char* modes[] = {"3d", "plane_strain", "plane_stress"};
  return std::string(fem::name(s.cell)) + "/" + modes[static_cast<int>(s.mode)] + "/" +
         std::string(name(m));
}

AlgorithmicInput make_input(const Setup& s, const Material& m, const std::vector<double>& X,
                            const std::vector<double>& u_n, const std::vector<double>& u_next) {
  AlgorithmicInput in;
  in.cell = s.cell;
  in.dim = s.dim;
  in.plane = s.mode;
  in.material = m;
  in.X = X;
  in.u_n = u_n;
  in.u_next = u_next;
  return in;
}

ElementResult standard_force(const Setup& s, const Material& m, const std::vector<double>& X,
                             const std::vector<double>& u, std::span<double> r,
                             std::span<double> K = {}) {
  ElementInput in;
  in.cell = s.cell;
  in.dim = s.dim;
  in.plane = s.mode;
  in.material = m;
  in.X = X;
  in.u = u;
  return internal_force(in, r, K);
}

// Displacement of the motion x = Q (X + w) (+ a shift) with Q a rotation about `axis`.
std::vector<double> rotated(const Setup& s, const std::vector<double>& X,
                            const std::vector<double>& w, double angle) {
  const Eigen::Matrix3d Q =
      s.dim == 3 ? rotation({0.3, -1.0, 0.6}, angle) : rotation({0, 0, 1}, angle);
  std::vector<double> u(X.size());
  for (std::size_t a = 0; a < X.size() / s.dim; ++a) {
    Eigen::Vector3d y = Eigen::Vector3d::Zero();
    for (int i = 0; i < s.dim; ++i) y(i) = X[a * s.dim + i] + w[a * s.dim + i];
    const Eigen::Vector3d x = Q * y + Eigen::Vector3d(0.2, -0.1, 0.05);
    for (int i = 0; i < s.dim; ++i) u[a * s.dim + i] = x(i) - X[a * s.dim + i];
  }
  return u;
}

// A large step: distorted states with a rigid rotation of 1.2 rad between them (none for the
// small-strain model, which is not objective and would see the rotation as strain).
void large_step(const Setup& s, MaterialModel model, const std::vector<double>& X, unsigned seed,
                std::vector<double>& u_n, std::vector<double>& u_next) {
  const std::vector<double> w0 = random_vector(X.size(), 0.12, seed);
  const std::vector<double> w1 = random_vector(X.size(), 0.12, seed + 1000);
  const double turn = hyperelastic(model) ? 1.2 : 0.0;
  u_n = rotated(s, X, w0, 0.3);
  u_next = rotated(s, X, w1, 0.3 + turn);
  if (!hyperelastic(model)) u_n = w0, u_next = w1;
}

} // namespace

TEST(AlgorithmicForce, WorkOverTheStepEqualsTheEnergyChange) {
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 3);
    const std::size_t nd = X.size();
    for (auto model : all_models) {
      const Material m = make_material(model, 0.3);
      for (unsigned seed = 1; seed <= 3; ++seed) {
        std::vector<double> u_n, u_next, f(nd), r(nd);
        large_step(s, model, X, seed, u_n, u_next);
        const AlgorithmicResult res =
            algorithmic_internal_force(make_input(s, m, X, u_n, u_next), f, {});
        ASSERT_EQ(res.status, KernelStatus::ok) << label(s, model);
        ASSERT_EQ(res.n_midpoint_points, 0);
        const ElementResult e0 = standard_force(s, m, X, u_n, r);
        const ElementResult e1 = standard_force(s, m, X, u_next, r);
        ASSERT_EQ(e0.status, KernelStatus::ok);
        ASSERT_EQ(e1.status, KernelStatus::ok);
        const double scale = std::abs(e0.energy) + std::abs(e1.energy);
        EXPECT_LT(std::abs(res.energy_n - e0.energy), 1e-14 * scale);
        EXPECT_LT(std::abs(res.energy_next - e1.energy), 1e-14 * scale);

        double work = 0.0;
        for (std::size_t j = 0; j < nd; ++j) work += (u_next[j] - u_n[j]) * f[j];
        EXPECT_LT(std::abs(work - (e1.energy - e0.energy)), 1e-12 * scale)
            << label(s, model) << " seed " << seed;

        // The standard force at the midpoint displacement misses the balance by far: the
        // check above is a real one.
        if (model == MaterialModel::neo_hooke) {
          std::vector<double> u_mid(nd);
          for (std::size_t j = 0; j < nd; ++j) u_mid[j] = 0.5 * (u_n[j] + u_next[j]);
          ASSERT_EQ(standard_force(s, m, X, u_mid, r).status, KernelStatus::ok);
          double plain = 0.0;
          for (std::size_t j = 0; j < nd; ++j) plain += (u_next[j] - u_n[j]) * r[j];
          EXPECT_GT(std::abs(plain - (e1.energy - e0.energy)), 1e-6 * scale) << label(s, model);
        }
      }
    }
  }
}

TEST(AlgorithmicForce, ConservesLinearAndAngularMomentum) {
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 5);
    const std::size_t nd = X.size();
    const int n = fem::n_nodes(s.cell);
    for (auto model : all_models) {
      const Material m = make_material(model, 0.3);
      std::vector<double> u_n, u_next, f(nd);
      large_step(s, model, X, 7, u_n, u_next);
      ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u_n, u_next), f, {}).status,
                KernelStatus::ok);
      Eigen::Vector3d force = Eigen::Vector3d::Zero(), moment_mid = Eigen::Vector3d::Zero(),
                      moment_end = Eigen::Vector3d::Zero();
      double f_scale = 0.0, m_scale = 0.0;
      for (int a = 0; a < n; ++a) {
        Eigen::Vector3d fa = Eigen::Vector3d::Zero(), xm = Eigen::Vector3d::Zero(),
                        x1 = Eigen::Vector3d::Zero();
        for (int i = 0; i < s.dim; ++i) {
          const std::size_t j = static_cast<std::size_t>(a * s.dim + i);
          fa(i) = f[j];
          xm(i) = X[j] + 0.5 * (u_n[j] + u_next[j]);
          x1(i) = X[j] + u_next[j];
        }
        force += fa;
        moment_mid += xm.cross(fa);
        moment_end += x1.cross(fa);
        f_scale += fa.norm();
        m_scale += xm.norm() * fa.norm();
      }
      EXPECT_LT(force.norm(), 1e-13 * f_scale) << label(s, model);
      if (!hyperelastic(model)) continue;
      EXPECT_LT(moment_mid.norm(), 1e-13 * m_scale) << label(s, model);
      // About the end configuration the moment does not vanish.
      EXPECT_GT(moment_end.norm(), 1e-3 * m_scale) << label(s, model);
    }
  }
}

TEST(AlgorithmicForce, TangentMatchesCentralDifferences) {
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 3);
    const std::size_t nd = X.size();
    for (auto model : all_models) {
      const Material m = make_material(model, 0.3);
      std::vector<double> u_n, u_next;
      large_step(s, model, X, 11, u_n, u_next);
      std::vector<double> f(nd), K(nd * nd), fp(nd), fm(nd);
      ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u_n, u_next), f, K).status,
                KernelStatus::ok);
      const double h = 1e-6, K_scale = max_abs(K);
      double worst = 0.0;
      for (std::size_t j = 0; j < nd; ++j) {
        std::vector<double> up = u_next, um = u_next;
        up[j] += h;
        um[j] -= h;
        ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u_n, up), fp, {}).status,
                  KernelStatus::ok);
        ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u_n, um), fm, {}).status,
                  KernelStatus::ok);
        for (std::size_t i = 0; i < nd; ++i)
          worst = std::max(worst, std::abs((fp[i] - fm[i]) / (2 * h) - K[i * nd + j]));
      }
      EXPECT_LT(worst, 1e-6 * K_scale) << label(s, model);
    }
  }
}

TEST(AlgorithmicForce, TangentMatchesCentralDifferencesNextToTheSwitch) {
  // Neo-Hooke with a homogeneous increment u_{n+1} - u_n = t H X sized so that
  // |dC| / |C_mid| is about 4 (discrete gradient at every point) or 1/4 (S(C_mid) at every
  // point) times the threshold.
  const Material m = make_material(MaterialModel::neo_hooke, 0.3);
  const double tau = default_discrete_gradient_threshold;
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 3);
    const std::size_t nd = X.size();
    const int n_points = fem::quadrature(s.cell, fem::default_quadrature_degree(s.cell)).n_points;
    const std::vector<double> u_n = random_vector(nd, 0.02, 4);
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    H.topLeftCorner(s.dim, s.dim) =
        Eigen::Map<const Eigen::MatrixXd>(random_vector(9, 1.0, 6).data(), 3, 3)
            .topLeftCorner(s.dim, s.dim);
    const Eigen::Matrix3d symH = 0.5 * (H + H.transpose());
    for (double ratio : {4.0, 0.25}) {
      // |dC| ~ 2 |sym H| t, |C_mid| ~ sqrt(dim).
      const double t = ratio * tau * std::sqrt(double(s.dim)) / (2.0 * symH.norm());
      std::vector<double> u_next = u_n;
      for (std::size_t a = 0; a < nd / s.dim; ++a)
        for (int i = 0; i < s.dim; ++i)
          for (int k = 0; k < s.dim; ++k) u_next[a * s.dim + i] += t * H(i, k) * X[a * s.dim + k];
      std::vector<double> f(nd), K(nd * nd), fp(nd), fm(nd);
      const AlgorithmicResult res =
          algorithmic_internal_force(make_input(s, m, X, u_n, u_next), f, K);
      ASSERT_EQ(res.status, KernelStatus::ok);
      ASSERT_EQ(res.n_midpoint_points, ratio < 1.0 ? n_points : 0) << label(s, m.model);
      // h changes |dC| by < 10% (ratio 1/4) and < 1% (ratio 4), never across the switch; a
      // much smaller h would resolve the round-off of the discrete-gradient correction
      // (~ eps_mach |CC| / |dE|) instead of the derivative.
      const double h = 1e-6, K_scale = max_abs(K);
      double worst = 0.0;
      for (std::size_t j = 0; j < nd; ++j) {
        std::vector<double> up = u_next, um = u_next;
        up[j] += h;
        um[j] -= h;
        const AlgorithmicResult rp =
            algorithmic_internal_force(make_input(s, m, X, u_n, up), fp, {});
        const AlgorithmicResult rm =
            algorithmic_internal_force(make_input(s, m, X, u_n, um), fm, {});
        ASSERT_EQ(rp.n_midpoint_points, res.n_midpoint_points);
        ASSERT_EQ(rm.n_midpoint_points, res.n_midpoint_points);
        for (std::size_t i = 0; i < nd; ++i)
          worst = std::max(worst, std::abs((fp[i] - fm[i]) / (2 * h) - K[i * nd + j]));
      }
      EXPECT_LT(worst, 1e-6 * K_scale) << label(s, m.model) << " ratio " << ratio;
    }
  }
}

TEST(AlgorithmicForce, ReducesToTheStandardForceForAZeroStep) {
  // f_alg(u, u) = internal_force(u) and d f_alg / d u_{n+1} = K(u) / 2 there; for a step
  // t d the gap to internal_force(u + t d / 2) closes like t^2.
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 3);
    const std::size_t nd = X.size();
    for (auto model : all_models) {
      const Material m = make_material(model, 0.3);
      const std::vector<double> u = random_vector(nd, 0.12, 21);
      std::vector<double> f(nd), K(nd * nd), r(nd), Kr(nd * nd);
      ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u, u), f, K).status,
                KernelStatus::ok);
      ASSERT_EQ(standard_force(s, m, X, u, r, Kr).status, KernelStatus::ok);
      double worst_f = 0.0, worst_K = 0.0;
      for (std::size_t j = 0; j < nd; ++j) worst_f = std::max(worst_f, std::abs(f[j] - r[j]));
      for (std::size_t j = 0; j < nd * nd; ++j)
        worst_K = std::max(worst_K, std::abs(K[j] - 0.5 * Kr[j]));
      EXPECT_LT(worst_f, 1e-13 * max_abs(r)) << label(s, model);
      EXPECT_LT(worst_K, 1e-13 * max_abs(Kr)) << label(s, model);

      if (!hyperelastic(model)) continue; // linear_elastic: f_alg = f(u_mid) exactly
      const std::vector<double> d = random_vector(nd, 0.1, 22);
      double previous = 0.0;
      for (int k = 0; k < 4; ++k) {
        const double t = 0.02 / (1 << k);
        std::vector<double> u1(nd), um(nd);
        for (std::size_t j = 0; j < nd; ++j) u1[j] = u[j] + t * d[j], um[j] = u[j] + 0.5 * t * d[j];
        ASSERT_EQ(algorithmic_internal_force(make_input(s, m, X, u, u1), f, {}).status,
                  KernelStatus::ok);
        ASSERT_EQ(standard_force(s, m, X, um, r).status, KernelStatus::ok);
        double gap = 0.0;
        for (std::size_t j = 0; j < nd; ++j) gap = std::max(gap, std::abs(f[j] - r[j]));
        if (k > 0) {
          EXPECT_NEAR(previous / gap, 4.0, 0.3) << label(s, model) << " t " << t;
        }
        previous = gap;
      }
    }
  }
}
