// Algorithmic stress at a material point: directionality S_alg : dE = W_{n+1} - W_n,
// consistency with S(C_mid), invariance under rotations of either state, and the tangent
// dS_alg/dE_{n+1} against central differences on both sides of the small-increment switch.
#include "test_util.hpp"

#include "seam/solid/algorithmic_stress.hpp"

#include <gtest/gtest.h>

using namespace seam::solid;
using namespace seam::solid::test;

namespace {

const char* mode_name(PlaneMode m) {
  return m == PlaneMode::none ? "3d" : (m == PlaneMode::plane_strain ? "plane_strain" : "stress");
}

// A large strain state with every free component nonzero (stretches roughly 0.7..1.5).
Eigen::Matrix3d sample_strain(PlaneMode mode, unsigned seed, double amplitude = 0.25) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-amplitude, amplitude);
  Vector6 e = Vector6::Zero();
  for (int k : free_components(mode)) e(k) = d(gen);
  return strain_from_voigt(e);
}

// Green strain of F over the components the mode reads (in-plane block in 2D).
Eigen::Matrix3d green_strain(PlaneMode mode, const Eigen::Matrix3d& F) {
  Eigen::Matrix3d E = 0.5 * (F.transpose() * F - Eigen::Matrix3d::Identity());
  if (mode != PlaneMode::none) {
    E.row(2).setZero();
    E.col(2).setZero();
  }
  return E;
}

double contract(const Eigen::Matrix3d& A, const Eigen::Matrix3d& B, PlaneMode mode) {
  const int nc = mode == PlaneMode::none ? 3 : 2;
  return A.topLeftCorner(nc, nc).cwiseProduct(B.topLeftCorner(nc, nc)).sum();
}

} // namespace

TEST(AlgorithmicStress, DirectionalityHoldsToRoundOff) {
  for (auto model : all_models) {
    for (auto mode : all_modes) {
      const Material m = make_material(model, 0.3);
      for (unsigned seed = 1; seed <= 20; ++seed) {
        // Different rotations at the two states: the step contains a large rigid rotation.
        const Eigen::Matrix3d Q0 =
            hyperelastic(model) ? rotation({0, 0, 1}, 0.4) : Eigen::Matrix3d::Identity();
        const Eigen::Matrix3d Q1 =
            hyperelastic(model) ? rotation({0, 0, 1}, -1.1) : Eigen::Matrix3d::Identity();
        const Eigen::Matrix3d F0 = Q0 * F_of_strain(model, sample_strain(mode, seed));
        const Eigen::Matrix3d F1 = Q1 * F_of_strain(model, sample_strain(mode, 100 + seed));
        AlgorithmicStress a;
        ASSERT_EQ(algorithmic_stress(m, mode, F0, F1, a), PointStatus::ok);
        ASSERT_FALSE(a.midpoint);
        const Eigen::Matrix3d dE =
            model == MaterialModel::linear_elastic
                ? Eigen::Matrix3d(0.5 * (F1 - F0 + (F1 - F0).transpose()))
                : Eigen::Matrix3d(green_strain(mode, F1) - green_strain(mode, F0));
        const double work = contract(a.stress, dE, mode);
        const double dW = a.energy_next - a.energy_n;
        const double scale = std::abs(a.energy_n) + std::abs(a.energy_next);
        EXPECT_LT(std::abs(work - dW), 1e-13 * scale)
            << name(model) << " " << mode_name(mode) << " seed " << seed;
        EXPECT_LT((a.stress - a.stress.transpose()).norm(), 1e-14 * a.stress.norm());

        // The plain midpoint stress S(C_mid) is not enough for neo-Hooke: the discrete-gradient
        // correction is what the check above measures.
        if (model == MaterialModel::neo_hooke) {
          PointResponse mid;
          const Eigen::Matrix3d Cm = 0.5 * (F0.transpose() * F0 + F1.transpose() * F1);
          ASSERT_EQ(evaluate(m, mode, spd_sqrt(Cm), mid, false), PointStatus::ok);
          EXPECT_GT(std::abs(contract(mid.stress, dE, mode) - dW), 1e-6 * scale);
        }
      }
    }
  }
}

TEST(AlgorithmicStress, QuadraticModelsUseTheMidpointStress) {
  // Simo & Tarnow: for St. Venant–Kirchhoff (S(E_n) + S(E_{n+1}))/2 = S(E_mid).
  for (auto mode : all_modes) {
    const Material m = make_material(MaterialModel::saint_venant_kirchhoff);
    const Eigen::Matrix3d E0 = sample_strain(mode, 3), E1 = sample_strain(mode, 4);
    const Eigen::Matrix3d F0 = F_of_strain(m.model, E0), F1 = F_of_strain(m.model, E1);
    AlgorithmicStress a;
    ASSERT_EQ(algorithmic_stress(m, mode, F0, F1, a), PointStatus::ok);
    PointResponse mid;
    ASSERT_EQ(evaluate(m, mode, F_of_strain(m.model, 0.5 * (E0 + E1)), mid), PointStatus::ok);
    const int nc = mode == PlaneMode::none ? 3 : 2;
    EXPECT_LT((a.stress - mid.stress).topLeftCorner(nc, nc).norm(), 1e-12 * mid.stress.norm());
  }
}

TEST(AlgorithmicStress, ConvergesToMidpointStressForSmallIncrements) {
  // The correction is O(|dE|^2): halving the increment divides the gap to S(C_mid) by 4.
  const Material m = make_material(MaterialModel::neo_hooke);
  for (auto mode : all_modes) {
    const Eigen::Matrix3d E0 = sample_strain(mode, 7), D = sample_strain(mode, 8);
    double previous = 0.0;
    for (int k = 0; k < 4; ++k) {
      const double t = 0.02 / (1 << k);
      const Eigen::Matrix3d F0 = F_of_strain(m.model, E0), F1 = F_of_strain(m.model, E0 + t * D);
      AlgorithmicStress a;
      ASSERT_EQ(algorithmic_stress(m, mode, F0, F1, a, false), PointStatus::ok);
      ASSERT_FALSE(a.midpoint);
      PointResponse mid;
      ASSERT_EQ(evaluate(m, mode, F_of_strain(m.model, E0 + 0.5 * t * D), mid, false),
                PointStatus::ok);
      const double gap = (a.stress - mid.stress).norm();
      if (k > 0) {
        EXPECT_NEAR(previous / gap, 4.0, 0.25) << mode_name(mode) << " t " << t;
      }
      previous = gap;
    }
  }
}

TEST(AlgorithmicStress, InvariantUnderRotationsOfEitherState) {
  for (auto model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hooke}) {
    const Material m = make_material(model);
    const Eigen::Matrix3d F0 = F_of_strain(model, sample_strain(PlaneMode::none, 11));
    const Eigen::Matrix3d F1 = F_of_strain(model, sample_strain(PlaneMode::none, 12));
    AlgorithmicStress a, b;
    ASSERT_EQ(algorithmic_stress(m, PlaneMode::none, F0, F1, a), PointStatus::ok);
    ASSERT_EQ(algorithmic_stress(m, PlaneMode::none, rotation({1, 2, 3}, 0.8) * F0,
                                 rotation({-2, 0.5, 1}, 2.1) * F1, b),
              PointStatus::ok);
    EXPECT_LT((a.stress - b.stress).norm(), 1e-12 * a.stress.norm()) << name(model);
    EXPECT_LT((a.tangent - b.tangent).norm(), 1e-12 * a.tangent.norm()) << name(model);
  }
}

TEST(AlgorithmicStress, TangentMatchesCentralDifferences) {
  // dS_alg/dE_{n+1} column l from S_alg at F_{n+1} = sqrt(I + 2 (E1 +- h e_l)). The increments
  // cover large steps and both sides of the switch, |dC|/|C_mid| = 3 and 1/3 times the
  // threshold. Above it h is ~1e-2 |dE|: large enough that the round-off of the correction
  // (~ eps_mach |CC| / |dE|, amplified by 1/h in the difference) stays below the derivative.
  const double tau = default_discrete_gradient_threshold;
  for (auto model : all_models) {
    for (auto mode : all_modes) {
      const Material m = make_material(model, 0.3);
      const Eigen::Matrix3d E0 = sample_strain(mode, 21), D = sample_strain(mode, 22);
      for (double size : {1.0, 3.0 * tau, tau / 3.0}) {
        // Scale D so that |dC| / |C_mid| ~ size (|dC| = 2 |dE| and |C_mid| ~ |I|).
        const double nI = std::sqrt(mode == PlaneMode::none ? 3.0 : 2.0);
        const Eigen::Matrix3d E1 = E0 + (size < 1.0 ? size * nI / (2.0 * D.norm()) : 1.0) * D;
        const Eigen::Matrix3d F0 = F_of_strain(model, E0);
        AlgorithmicStress a;
        ASSERT_EQ(algorithmic_stress(m, mode, F0, F_of_strain(model, E1), a), PointStatus::ok);
        if (model == MaterialModel::neo_hooke) {
          EXPECT_EQ(a.midpoint, size < tau);
        }
        const double h = size < tau ? 1e-7 : (size < 1.0 ? 3e-6 : 1e-6);
        double worst = 0.0;
        for (int l : free_components(mode)) {
          Vector6 dl = Vector6::Zero();
          dl(l) = h;
          AlgorithmicStress p, q;
          ASSERT_EQ(algorithmic_stress(m, mode, F0, F_of_strain(model, E1 + strain_from_voigt(dl)),
                                       p, false),
                    PointStatus::ok);
          ASSERT_EQ(algorithmic_stress(m, mode, F0, F_of_strain(model, E1 - strain_from_voigt(dl)),
                                       q, false),
                    PointStatus::ok);
          ASSERT_EQ(p.midpoint, a.midpoint); // the difference does not straddle the switch
          const Vector6 fd = stress_to_voigt(p.stress - q.stress) / (2 * h);
          for (int k : free_components(mode))
            worst = std::max(worst, std::abs(fd(k) - a.tangent(k, l)));
        }
        EXPECT_LT(worst, 1e-6 * a.tangent.cwiseAbs().maxCoeff())
            << name(model) << " " << mode_name(mode) << " size " << size;
      }
    }
  }
}
