// Material point tests: stress = dW/dE and tangent = dS/dE by central differences, stress-free
// reference state, objectivity, analytic uniaxial states.
#include "test_util.hpp"

#include "seam/common/error.hpp"

#include <gtest/gtest.h>

using namespace seam::solid;
using namespace seam::solid::test;

namespace {

struct Case {
  MaterialModel model;
  PlaneMode mode;
  double nu;
};

std::vector<Case> all_cases() {
  std::vector<Case> cases;
  for (auto model : all_models) {
    for (auto mode : all_modes) {
      cases.push_back({model, mode, 0.3});
      // A negative Poisson ratio makes lambda < 0: the plane-stress Newton for neo-Hooke must
      // still pick the stable root.
      cases.push_back({model, mode, -0.2});
    }
  }
  return cases;
}

// A moderately large strain state (stretches 0.8..1.3) with all free components nonzero.
Vector6 sample_strain(PlaneMode mode, int seed) {
  std::mt19937 gen(seed);
  std::uniform_real_distribution<double> d(-0.12, 0.15);
  Vector6 e = Vector6::Zero();
  for (int k : free_components(mode)) e(k) = d(gen);
  return e;
}

PointResponse eval_strain(const Material& m, PlaneMode mode, const Vector6& e) {
  PointResponse r;
  EXPECT_EQ(evaluate(m, mode, F_of_strain(m.model, strain_from_voigt(e)), r), PointStatus::ok);
  return r;
}

std::string label(const Case& c) {
  const char* modes[] = {"3d", "plane_strain", "plane_stress"};
  return std::string(name(c.model)) + "/" + modes[static_cast<int>(c.mode)] +
         "/nu=" + std::to_string(c.nu);
}

} // namespace

TEST(Material, StressIsEnergyDerivative) {
  const double h = 1e-6;
  for (const auto& c : all_cases()) {
    const Material m = make_material(c.model, c.nu);
    for (int seed = 1; seed <= 3; ++seed) {
      const Vector6 e = sample_strain(c.mode, seed);
      const PointResponse r = eval_strain(m, c.mode, e);
      const Vector6 s = stress_to_voigt(r.stress);
      for (int k : free_components(c.mode)) {
        Vector6 ep = e, em = e;
        ep(k) += h;
        em(k) -= h;
        const double fd =
            (eval_strain(m, c.mode, ep).energy - eval_strain(m, c.mode, em).energy) / (2 * h);
        EXPECT_NEAR(s(k), fd, 1e-6 * s.norm()) << label(c) << " component " << k;
      }
      if (c.mode == PlaneMode::plane_stress) {
        EXPECT_NEAR(r.stress(2, 2), 0.0, 1e-12 * s.norm()) << label(c);
      }
    }
  }
}

TEST(Material, TangentIsStressDerivative) {
  const double h = 1e-6;
  for (const auto& c : all_cases()) {
    const Material m = make_material(c.model, c.nu);
    for (int seed = 1; seed <= 3; ++seed) {
      const Vector6 e = sample_strain(c.mode, seed);
      const PointResponse r = eval_strain(m, c.mode, e);
      const auto free = free_components(c.mode);
      for (int k : free) {
        Vector6 ep = e, em = e;
        ep(k) += h;
        em(k) -= h;
        const Vector6 fd = (stress_to_voigt(eval_strain(m, c.mode, ep).stress) -
                            stress_to_voigt(eval_strain(m, c.mode, em).stress)) /
                           (2 * h);
        for (int a : free) {
          EXPECT_NEAR(r.tangent(a, k), fd(a), 1e-6 * r.tangent.norm())
              << label(c) << " entry " << a << "," << k;
        }
      }
      EXPECT_LT((r.tangent - r.tangent.transpose()).norm(), 1e-12 * r.tangent.norm());
      if (c.mode == PlaneMode::plane_stress) {
        EXPECT_EQ(r.tangent.row(2).norm(), 0.0);
        EXPECT_EQ(r.tangent.col(2).norm(), 0.0);
      }
    }
  }
}

TEST(Material, StressFreeReferenceState) {
  for (auto model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hooke}) {
    for (auto mode : all_modes) {
      const Material m = make_material(model);
      PointResponse r;
      ASSERT_EQ(evaluate(m, mode, Eigen::Matrix3d::Identity(), r), PointStatus::ok);
      EXPECT_LT(r.stress.norm(), 1e-14 * m.young);
      EXPECT_NEAR(r.energy, 0.0, 1e-14 * m.young);
      EXPECT_NEAR(r.stretch_zz, 1.0, 1e-14);
      // At F = I every model reduces to linear elasticity.
      const double lambda = m.lambda(), mu = m.mu();
      if (mode != PlaneMode::plane_stress) {
        EXPECT_NEAR(r.tangent(0, 0), lambda + 2 * mu, 1e-12 * m.young);
        EXPECT_NEAR(r.tangent(0, 1), lambda, 1e-12 * m.young);
      } else {
        const double lambda_ps = 2 * mu * lambda / (lambda + 2 * mu);
        EXPECT_NEAR(r.tangent(0, 0), lambda_ps + 2 * mu, 1e-12 * m.young);
        EXPECT_NEAR(r.tangent(0, 1), lambda_ps, 1e-12 * m.young);
      }
      EXPECT_NEAR(r.tangent(3, 3), mu, 1e-12 * m.young);
    }
  }
}

TEST(Material, Objectivity) {
  std::mt19937 gen(7);
  std::uniform_real_distribution<double> d(-0.2, 0.2);
  for (auto model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hooke}) {
    const Material m = make_material(model);
    for (auto mode : all_modes) {
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) F(i, j) += d(gen);
      Eigen::Matrix3d Q = rotation({0.3, -0.5, 0.8}, 1.1);
      if (mode != PlaneMode::none) {
        F.row(2) << 0, 0, 1;
        F.col(2) << 0, 0, 1;
        Q = rotation({0, 0, 1}, 2.2);
      }
      PointResponse r0, r1;
      ASSERT_EQ(evaluate(m, mode, F, r0), PointStatus::ok);
      ASSERT_EQ(evaluate(m, mode, Q * F, r1), PointStatus::ok);
      EXPECT_NEAR(r1.energy, r0.energy, 1e-12 * std::abs(r0.energy));
      EXPECT_LT((r1.stress - r0.stress).norm(), 1e-12 * r0.stress.norm());
      EXPECT_GT(r0.energy, 1e-3 * m.young * 1e-3); // the state is really strained
      // Cauchy stress rotates with the body.
      const Eigen::Matrix3d s0 = cauchy_stress(m, mode, F, r0);
      const Eigen::Matrix3d s1 = cauchy_stress(m, mode, Q * F, r1);
      EXPECT_LT((s1 - Q * s0 * Q.transpose()).norm(), 1e-12 * s0.norm());
    }
  }
}

TEST(Material, LinearElasticUniaxial) {
  const Material m = make_material(MaterialModel::linear_elastic, 0.3);
  const double E = m.young, nu = m.poisson, e = 1e-3;
  PointResponse r;
  // 3D uniaxial stress: eps = diag(e, -nu e, -nu e).
  Eigen::Matrix3d F = Eigen::Vector3d(1 + e, 1 - nu * e, 1 - nu * e).asDiagonal();
  ASSERT_EQ(evaluate(m, PlaneMode::none, F, r), PointStatus::ok);
  EXPECT_NEAR(r.stress(0, 0), E * e, 1e-12 * E);
  EXPECT_NEAR(r.stress(1, 1), 0.0, 1e-12 * E);
  EXPECT_NEAR(r.stress(2, 2), 0.0, 1e-12 * E);
  EXPECT_NEAR(r.energy, 0.5 * E * e * e, 1e-12 * E * e * e);
  EXPECT_NEAR(von_mises(r.stress), E * e, 1e-12 * E);
  // Plane stress: the same in-plane strain gives the same stress; eps33 = -nu e.
  ASSERT_EQ(evaluate(m, PlaneMode::plane_stress, F, r), PointStatus::ok);
  EXPECT_NEAR(r.stress(0, 0), E * e, 1e-12 * E);
  EXPECT_NEAR(r.stress(1, 1), 0.0, 1e-12 * E);
  EXPECT_NEAR(r.stretch_zz, 1 - nu * e, 1e-14);
  // Plane strain with eps = diag(e, 0): sigma11 = E(1-nu)/((1+nu)(1-2nu)) e, sigma22 = sigma33
  // = E nu/((1+nu)(1-2nu)) e.
  F = Eigen::Vector3d(1 + e, 1, 1).asDiagonal();
  ASSERT_EQ(evaluate(m, PlaneMode::plane_strain, F, r), PointStatus::ok);
  const double k = E / ((1 + nu) * (1 - 2 * nu));
  EXPECT_NEAR(r.stress(0, 0), k * (1 - nu) * e, 1e-12 * E);
  EXPECT_NEAR(r.stress(1, 1), k * nu * e, 1e-12 * E);
  EXPECT_NEAR(r.stress(2, 2), k * nu * e, 1e-12 * E);
  // Simple shear: sigma12 = mu gamma, von Mises sqrt(3) mu gamma.
  F = Eigen::Matrix3d::Identity();
  F(0, 1) = e;
  ASSERT_EQ(evaluate(m, PlaneMode::none, F, r), PointStatus::ok);
  EXPECT_NEAR(r.stress(0, 1), m.mu() * e, 1e-12 * E);
  EXPECT_NEAR(von_mises(r.stress), std::sqrt(3.0) * m.mu() * e, 1e-12 * E);
}

TEST(Material, NeoHookeUniaxialStretchNuZero) {
  // nu = 0 gives lambda = 0 and uncoupled directions: F = diag(s, 1, 1) is a homogeneous
  // uniaxial-stress state with P11 = mu (s - 1/s), in 3D and both plane modes.
  const Material m = make_material(MaterialModel::neo_hooke, 0.0);
  for (auto mode : all_modes) {
    for (double s : {0.5, 0.9, 1.5, 3.0}) {
      const Eigen::Matrix3d F = Eigen::Vector3d(s, 1, 1).asDiagonal();
      PointResponse r;
      ASSERT_EQ(evaluate(m, mode, F, r), PointStatus::ok);
      const Eigen::Matrix3d P = F * r.stress;
      EXPECT_NEAR(P(0, 0), m.mu() * (s - 1 / s), 1e-12 * m.young);
      EXPECT_NEAR(P(1, 1), 0.0, 1e-12 * m.young);
      EXPECT_NEAR(P(2, 2), 0.0, 1e-12 * m.young);
      EXPECT_NEAR(r.energy, 0.5 * m.mu() * (s * s - 1) - m.mu() * std::log(s), 1e-12 * m.young);
    }
  }
}

TEST(Material, PlaneStressAgreesWith3d) {
  // The plane-stress state evaluated with the full 3D law at the solved F33 has S33 = 0 and
  // the same in-plane stress and energy.
  for (auto model : all_models) {
    for (double nu : {0.3, 0.45, -0.3}) {
      const Material m = make_material(model, nu);
      Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
      F.topLeftCorner<2, 2>() << 1.35, 0.2, -0.1, 0.85;
      PointResponse ps, r3;
      ASSERT_EQ(evaluate(m, PlaneMode::plane_stress, F, ps), PointStatus::ok);
      F(2, 2) = ps.stretch_zz;
      ASSERT_EQ(evaluate(m, PlaneMode::none, F, r3), PointStatus::ok);
      EXPECT_NEAR(r3.stress(2, 2), 0.0, 1e-12 * m.young) << name(model) << " nu " << nu;
      EXPECT_LT((r3.stress - ps.stress).norm(), 1e-12 * m.young);
      EXPECT_NEAR(r3.energy, ps.energy, 1e-12 * m.young);
    }
  }
}

TEST(Material, FailureStatuses) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(0, 0) = -0.5;
  PointResponse r;
  for (auto mode : all_modes) {
    EXPECT_EQ(evaluate(make_material(MaterialModel::neo_hooke), mode, F, r), PointStatus::inverted);
    EXPECT_EQ(evaluate(make_material(MaterialModel::saint_venant_kirchhoff), mode, F, r),
              PointStatus::inverted);
    EXPECT_EQ(evaluate(make_material(MaterialModel::linear_elastic), mode, F, r), PointStatus::ok);
  }
  // St. Venant–Kirchhoff under a large equibiaxial stretch needs C33 = 1 + 2 E33 < 0 for
  // S33 = 0: no plane-stress state exists.
  F = Eigen::Vector3d(1.6, 1.6, 1).asDiagonal();
  EXPECT_EQ(
      evaluate(make_material(MaterialModel::saint_venant_kirchhoff), PlaneMode::plane_stress, F, r),
      PointStatus::no_plane_stress);
}

TEST(Material, ValidateAndNames) {
  Material m = make_material(MaterialModel::neo_hooke);
  EXPECT_NO_THROW(validate(m));
  m.poisson = 0.5;
  EXPECT_THROW(validate(m), seam::InputError);
  m = make_material(MaterialModel::neo_hooke);
  m.young = 0;
  EXPECT_THROW(validate(m), seam::InputError);
  for (auto model : all_models) EXPECT_EQ(parse_material_model(name(model)), model);
  EXPECT_FALSE(parse_material_model("mooney_rivlin").has_value());
  m.young = 2.6;
  m.poisson = 0.3;
  EXPECT_NEAR(m.mu(), 1.0, 1e-15);
  EXPECT_NEAR(m.lambda(), 1.5, 1e-15);
}
