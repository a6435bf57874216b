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

// A small increment just above the switch to the midpoint rule, from a stretched state of a
// stiff Neo-Hookean material: S_alg : dE must equal the exact energy change, computed here in
// long double, to near machine precision of the change itself. Subtracting the two energies in
// double (W ~ mu, change ~ mu |dE|) loses about eps mu / (mu |dE|) of it, 1e-12 here: the
// floor that kept a Newton residual of an almost rigidly sliding block near 1e-9.
TEST(AlgorithmicStress, SmallIncrementKeepsTheEnergyChangeExact) {
  for (auto mode : {PlaneMode::none, PlaneMode::plane_strain}) {
    const Material m = make_material(MaterialModel::neo_hooke, 0.3);
    Eigen::Matrix3d F0 = Eigen::Matrix3d::Identity();
    F0(0, 0) = 1.3;
    F0(0, 1) = 0.2;
    F0(1, 1) = 0.8;
    Eigen::Matrix3d dF = Eigen::Matrix3d::Zero();
    dF(0, 0) = 1.1e-4;
    dF(1, 0) = -0.7e-4;
    dF(1, 1) = 0.9e-4;
    if (mode == PlaneMode::none) {
      F0(2, 2) = 1.1;
      dF(2, 2) = -0.6e-4;
    }
    const Eigen::Matrix3d F1 = F0 + dF;
    dF = F1 - F0; // exact (Sterbenz): the increment between the two stored states
    AlgorithmicStress a;
    ASSERT_EQ(algorithmic_stress(m, mode, F0, F1, a), PointStatus::ok);
    ASSERT_FALSE(a.midpoint) << mode_name(mode);
    const auto energy = [&](const Eigen::Matrix3d& F) {
      Eigen::Matrix<long double, 3, 3> Fl = F.cast<long double>();
      const Eigen::Matrix<long double, 3, 3> C = Fl.transpose() * Fl;
      const long double J = Fl(0, 0) * (Fl(1, 1) * Fl(2, 2) - Fl(1, 2) * Fl(2, 1)) -
                            Fl(0, 1) * (Fl(1, 0) * Fl(2, 2) - Fl(1, 2) * Fl(2, 0)) +
                            Fl(0, 2) * (Fl(1, 0) * Fl(2, 1) - Fl(1, 1) * Fl(2, 0));
      const long double mu = m.mu(), lambda = m.lambda(), lnJ = std::log(J);
      return 0.5L * mu * (C.trace() - 3.0L) - mu * lnJ + 0.5L * lambda * lnJ * lnJ;
    };
    const long double exact = energy(F1) - energy(F0);
    // dE without subtracting two O(1) strains: (F_mid^T dF + dF^T F_mid) / 2, in long double.
    const Eigen::Matrix<long double, 3, 3> Fm = (0.5L * (F0 + F1).cast<long double>()).eval(),
                                           dFl = dF.cast<long double>();
    const Eigen::Matrix<long double, 3, 3> dE =
        0.5L * (Fm.transpose() * dFl + dFl.transpose() * Fm);
    const int nc = mode == PlaneMode::none ? 3 : 2;
    long double work = 0.0L;
    for (int i = 0; i < nc; ++i)
      for (int j = 0; j < nc; ++j) work += static_cast<long double>(a.stress(i, j)) * dE(i, j);
    EXPECT_LT(std::abs(static_cast<double>((work - exact) / exact)), 1e-13)
        << mode_name(mode) << ": S_alg:dE " << static_cast<double>(work) << ", exact "
        << static_cast<double>(exact);
  }
}
