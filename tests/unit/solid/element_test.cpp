// Element kernel tests: residual = d(energy)/du and tangent = d(residual)/du by central
// differences on distorted cells of every type, rigid motions, exact homogeneous states.
#include "test_util.hpp"

#include "seam/common/error.hpp"
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

ElementInput make_input(const Setup& s, const Material& m, const std::vector<double>& X,
                        const std::vector<double>& u) {
  ElementInput in;
  in.cell = s.cell;
  in.dim = s.dim;
  in.plane = s.mode;
  in.material = m;
  in.X = X;
  in.u = u;
  return in;
}

} // namespace

TEST(Element, ResidualIsEnergyGradientAndTangentIsResidualDerivative) {
  const double h = 1e-6;
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 3);
    const std::size_t nd = X.size();
    for (auto model : all_models) {
      const Material m = make_material(model, 0.3);
      std::vector<double> u = random_vector(nd, 0.12, 11);
      std::vector<double> r(nd), K(nd * nd), rp(nd), rm(nd);
      const ElementResult res = internal_force(make_input(s, m, X, u), r, K);
      ASSERT_EQ(res.status, KernelStatus::ok) << label(s, m.model);
      const double r_scale = max_abs(r), K_scale = max_abs(K);
      ASSERT_GT(r_scale, 1.0) << label(s, m.model); // the state is really loaded
      double worst_r = 0.0, worst_K = 0.0, worst_sym = 0.0;
      for (std::size_t j = 0; j < nd; ++j) {
        std::vector<double> up = u, um = u;
        up[j] += h;
        um[j] -= h;
        const ElementResult ep = internal_force(make_input(s, m, X, up), rp, {});
        const ElementResult em = internal_force(make_input(s, m, X, um), rm, {});
        ASSERT_EQ(ep.status, KernelStatus::ok);
        ASSERT_EQ(em.status, KernelStatus::ok);
        worst_r = std::max(worst_r, std::abs((ep.energy - em.energy) / (2 * h) - r[j]));
        for (std::size_t i = 0; i < nd; ++i) {
          worst_K = std::max(worst_K, std::abs((rp[i] - rm[i]) / (2 * h) - K[i * nd + j]));
          worst_sym = std::max(worst_sym, std::abs(K[i * nd + j] - K[j * nd + i]));
        }
      }
      EXPECT_LT(worst_r, 1e-6 * r_scale) << label(s, m.model);
      EXPECT_LT(worst_K, 1e-6 * K_scale) << label(s, m.model);
      EXPECT_LT(worst_sym, 1e-12 * K_scale) << label(s, m.model);
    }
  }
}

TEST(Element, RigidRotationGivesNoInternalForce) {
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.08, 5);
    const Eigen::Matrix3d Q =
        s.dim == 3 ? rotation({0.2, 1.0, -0.4}, 0.9) : rotation({0, 0, 1}, 0.9);
    std::vector<double> u(X.size());
    for (std::size_t a = 0; a < X.size() / s.dim; ++a) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero();
      for (int i = 0; i < s.dim; ++i) x(i) = X[a * s.dim + i];
      const Eigen::Vector3d d = Q * x - x;
      for (int i = 0; i < s.dim; ++i) u[a * s.dim + i] = d(i);
    }
    for (auto model : {MaterialModel::saint_venant_kirchhoff, MaterialModel::neo_hooke}) {
      const Material m = make_material(model);
      std::vector<double> r(X.size());
      const ElementResult res = internal_force(make_input(s, m, X, u), r, {});
      ASSERT_EQ(res.status, KernelStatus::ok);
      EXPECT_LT(max_abs(r), 1e-12 * m.young) << label(s, model);
      EXPECT_LT(std::abs(res.energy), 1e-12 * m.young) << label(s, model);
    }
  }
}

TEST(Element, HomogeneousStateGivesExactStressResultant) {
  // For u = (F - I) X (reproduced exactly by every isoparametric cell), the first Piola stress
  // P is uniform and sum_a r_a (x) X_a = int P grad(X) dV = P V. On an affine cell V is
  // exact: V = det(A) |reference cell|.
  const double stretch = 1.7;
  for (const auto& s : all_setups()) {
    const std::vector<double> X = cell_coordinates(s.cell, s.dim, 0.0);
    const int n = fem::n_nodes(s.cell);
    Eigen::Matrix3d A;
    A << 1.1, 0.2, -0.1, -0.15, 0.9, 0.2, 0.1, -0.05, 1.2; // as in cell_coordinates
    const bool simplex = s.cell == fem::CellType::tri3 || s.cell == fem::CellType::tri6 ||
                         s.cell == fem::CellType::tet4 || s.cell == fem::CellType::tet10;
    const double ref_measure = s.dim == 2 ? (simplex ? 0.5 : 4.0) : (simplex ? 1.0 / 6 : 8.0);
    const double V =
        ref_measure * (s.dim == 2 ? A.topLeftCorner<2, 2>().determinant() : A.determinant());

    auto resultant = [&](const Material& m, const Eigen::Matrix3d& F, double& energy) {
      std::vector<double> u(X.size()), r(X.size());
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < s.dim; ++i) {
          double d = 0;
          for (int j = 0; j < s.dim; ++j) d += (F(i, j) - (i == j)) * X[a * s.dim + j];
          u[a * s.dim + i] = d;
        }
      const ElementResult res = internal_force(make_input(s, m, X, u), r, {});
      EXPECT_EQ(res.status, KernelStatus::ok);
      energy = res.energy;
      Eigen::Matrix3d T = Eigen::Matrix3d::Zero();
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < s.dim; ++i)
          for (int j = 0; j < s.dim; ++j) T(i, j) += r[a * s.dim + i] * X[a * s.dim + j];
      return T;
    };

    // Neo-Hooke, nu = 0, uniaxial stretch: P11 = mu (l - 1/l), W = mu/2 (l^2 - 1) - mu ln l.
    const Material nh = make_material(MaterialModel::neo_hooke, 0.0);
    const Eigen::Matrix3d F = Eigen::Vector3d(stretch, 1, 1).asDiagonal();
    double W = 0;
    Eigen::Matrix3d P = resultant(nh, F, W) / V;
    const double mu = nh.mu();
    EXPECT_NEAR(P(0, 0), mu * (stretch - 1 / stretch), 1e-11 * mu) << fem::name(s.cell);
    EXPECT_NEAR(P(1, 1), 0.0, 1e-11 * mu);
    EXPECT_NEAR(P(0, 1), 0.0, 1e-11 * mu);
    EXPECT_NEAR(W / V, 0.5 * mu * (stretch * stretch - 1) - mu * std::log(stretch), 1e-11 * mu);

    ElementInput in = make_input(s, nh, X, {});
    std::vector<double> u(X.size());
    for (int a = 0; a < n; ++a) u[a * s.dim] = (stretch - 1) * X[a * s.dim];
    in.u = u;
    const ElementStress st = element_stress(in);
    ASSERT_EQ(st.status, KernelStatus::ok);
    // sigma = F S F^T / J with J = stretch: sigma11 = mu (l - 1/l) as well.
    EXPECT_NEAR(st.cauchy[0], mu * (stretch - 1 / stretch), 1e-11 * mu);
    EXPECT_NEAR(st.cauchy[1], 0.0, 1e-11 * mu);
    EXPECT_NEAR(st.cauchy[2], 0.0, 1e-11 * mu);
    EXPECT_NEAR(st.von_mises, mu * (stretch - 1 / stretch), 1e-11 * mu);

    // Linear elasticity, pure shear strain eps12 = g/2 plus dilatation e: sigma analytic.
    const Material le = make_material(MaterialModel::linear_elastic, 0.3);
    const double e = 1e-3, g = 2e-3;
    Eigen::Matrix3d H = Eigen::Matrix3d::Zero();
    H(0, 0) = e;
    H(0, 1) = g;
    double W_lin = 0;
    const Eigen::Matrix3d sig = resultant(le, Eigen::Matrix3d::Identity() + H, W_lin) / V;
    const double lambda = le.lambda(), mul = le.mu();
    const double lam_eff =
        s.mode == PlaneMode::plane_stress ? 2 * mul * lambda / (lambda + 2 * mul) : lambda;
    EXPECT_NEAR(sig(0, 0), (lam_eff + 2 * mul) * e, 1e-12 * le.young) << fem::name(s.cell);
    EXPECT_NEAR(sig(1, 1), lam_eff * e, 1e-12 * le.young);
    EXPECT_NEAR(sig(0, 1), mul * g, 1e-12 * le.young);
    EXPECT_NEAR(sig(1, 0), mul * g, 1e-12 * le.young);
    if (s.mode == PlaneMode::plane_strain) {
      in.material = le;
      std::vector<double> ul(X.size());
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < 2; ++i) ul[a * 2 + i] = H(i, 0) * X[a * 2] + H(i, 1) * X[a * 2 + 1];
      in.u = ul;
      const ElementStress sl = element_stress(in);
      EXPECT_NEAR(sl.cauchy[2], lambda * e, 1e-12 * le.young); // sigma_zz = lambda tr(eps)
    }
  }
}

TEST(Element, FailureStatuses) {
  // Reversed node order in 2D mirrors the cell: negative reference Jacobian.
  const Material nh = make_material(MaterialModel::neo_hooke);
  std::vector<double> X = {0, 0, 0, 1, 1, 1, 1, 0}; // quad4 numbered clockwise
  std::vector<double> u(8, 0.0), r(8), K(64);
  ElementInput in = make_input({fem::CellType::quad4, 2, PlaneMode::plane_strain}, nh, X, u);
  EXPECT_EQ(internal_force(in, r, K).status, KernelStatus::inverted_reference);
  EXPECT_EQ(element_stress(in).status, KernelStatus::inverted_reference);

  // Pushing node 2 of a unit triangle through the opposite edge inverts it.
  X = {0, 0, 1, 0, 0, 1};
  u = {0, 0, 0, 0, 0, -1.5};
  r.resize(6);
  K.resize(36);
  in = make_input({fem::CellType::tri3, 2, PlaneMode::plane_strain}, nh, X, u);
  EXPECT_EQ(internal_force(in, r, K).status, KernelStatus::inverted_current);
  // The linear model has no notion of inversion.
  in.material = make_material(MaterialModel::linear_elastic);
  EXPECT_EQ(internal_force(in, r, K).status, KernelStatus::ok);
  // Plane-stress St. Venant–Kirchhoff under a large biaxial stretch has no S33 = 0 state.
  in.material = make_material(MaterialModel::saint_venant_kirchhoff);
  in.plane = PlaneMode::plane_stress;
  u = {0, 0, 0.6, 0, 0, 0.6};
  EXPECT_EQ(internal_force(in, r, K).status, KernelStatus::material_failure);
  EXPECT_FALSE(describe(KernelStatus::material_failure).empty());

  // Misuse is an InternalError, never memory corruption.
  in.plane = PlaneMode::none;
  EXPECT_THROW((void)internal_force(in, r, K), InternalError);
  in.plane = PlaneMode::plane_strain;
  r.resize(5);
  EXPECT_THROW((void)internal_force(in, r, K), InternalError);
}
