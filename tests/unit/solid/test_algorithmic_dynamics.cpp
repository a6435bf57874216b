// One free element integrated in time with the energy-momentum scheme
//   M (v_{n+1} - v_n)/dt + f_alg(u_n, u_{n+1}) = 0,  (u_{n+1} - u_n)/dt = (v_n + v_{n+1})/2,
// solved by Newton with the kernel's tangent. Large steps of a spinning, vibrating element:
// total energy, linear and angular momentum must be conserved to the Newton tolerance, while
// the implicit midpoint rule (f_int at u_mid) on the same motion visibly does not conserve
// energy.
#include "test_util.hpp"

#include "seam/solid/algorithmic_force.hpp"
#include "seam/solid/element.hpp"
#include "seam/solid/mass.hpp"

#include <Eigen/Dense>
#include <gtest/gtest.h>

using namespace seam;
using namespace seam::solid;
using namespace seam::solid::test;

namespace {

using Vec = Eigen::VectorXd;
using Mat = Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

struct Case {
  fem::CellType cell;
  int dim;
  PlaneMode mode;
  MaterialModel model;
};

struct Invariants {
  double energy;
  Eigen::Vector3d momentum, angular;
};

class FreeElement {
public:
  FreeElement(const Case& c, bool energy_momentum)
      : c_(c), emm_(energy_momentum), X_(cell_coordinates(c.cell, c.dim, 0.08, 9)),
        nd_(static_cast<int>(X_.size())), M_(nd_, nd_) {
    m_ = make_material(c.model, 0.3);
    std::vector<double> M(static_cast<std::size_t>(nd_ * nd_));
    EXPECT_EQ(consistent_mass(c.cell, c.dim, X_, m_.density, M), KernelStatus::ok);
    M_ = Eigen::Map<Mat>(M.data(), nd_, nd_);
  }

  int n_dofs() const { return nd_; }

  // Kinetic + strain energy, linear and angular momentum (about the origin).
  Invariants invariants(const Vec& u, const Vec& v) const {
    const Vec p = M_ * v;
    Invariants inv{0.5 * v.dot(p) + energy(u), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
    for (int a = 0; a < nd_ / c_.dim; ++a) {
      Eigen::Vector3d x = Eigen::Vector3d::Zero(), pa = Eigen::Vector3d::Zero();
      for (int i = 0; i < c_.dim; ++i) {
        x(i) = X_[static_cast<std::size_t>(a * c_.dim + i)] + u(a * c_.dim + i);
        pa(i) = p(a * c_.dim + i);
      }
      inv.momentum += pa;
      inv.angular += x.cross(pa);
    }
    return inv;
  }

  // One step; returns the number of Newton iterations (-1: no convergence).
  int step(double dt, Vec& u, Vec& v) const {
    const Vec u0 = u, v0 = v;
    const Mat M2 = (2.0 / (dt * dt)) * M_;
    Vec f(nd_), du(nd_);
    Mat K(nd_, nd_);
    const double scale = (M2 * (dt * v0)).norm() + 1.0;
    for (int it = 1; it <= 25; ++it) {
      force(u0, u, f, K);
      const Vec R = M2 * (u - u0 - dt * v0) + f;
      if (R.norm() <= 1e-13 * scale) {
        v = 2.0 / dt * (u - u0) - v0;
        return it;
      }
      du = (M2 + K).partialPivLu().solve(-R);
      u += du;
    }
    return -1;
  }

private:
  double energy(const Vec& u) const {
    ElementInput in{c_.cell, c_.dim, c_.mode, m_, X_, std::span<const double>(u.data(), nd_)};
    const ElementResult r = internal_force(in, {}, {});
    EXPECT_EQ(r.status, KernelStatus::ok);
    return r.energy;
  }

  void force(const Vec& u0, const Vec& u1, Vec& f, Mat& K) const {
    std::span<double> fs(f.data(), nd_), Ks(K.data(), nd_ * nd_);
    if (emm_) {
      AlgorithmicInput in;
      in.cell = c_.cell;
      in.dim = c_.dim;
      in.plane = c_.mode;
      in.material = m_;
      in.X = X_;
      in.u_n = std::span<const double>(u0.data(), nd_);
      in.u_next = std::span<const double>(u1.data(), nd_);
      ASSERT_EQ(algorithmic_internal_force(in, fs, Ks).status, KernelStatus::ok);
    } else {
      const Vec um = 0.5 * (u0 + u1);
      ElementInput in{c_.cell, c_.dim, c_.mode, m_, X_, std::span<const double>(um.data(), nd_)};
      ASSERT_EQ(internal_force(in, fs, Ks).status, KernelStatus::ok);
      K *= 0.5; // d u_mid / d u_{n+1} = 1/2
    }
  }

  Case c_;
  bool emm_;
  Material m_;
  std::vector<double> X_;
  int nd_;
  Mat M_;
};

// Initial state: a stretched element spinning about an axis through (0.2, 0.1, 0) with a
// random velocity on top.
void initial_state(const Case& c, int nd, Vec& u, Vec& v) {
  const std::vector<double> X = cell_coordinates(c.cell, c.dim, 0.08, 9);
  const std::vector<double> w = random_vector(static_cast<std::size_t>(nd), 0.08, 31);
  const std::vector<double> r = random_vector(static_cast<std::size_t>(nd), 0.5, 32);
  const Eigen::Vector3d omega =
      c.dim == 3 ? Eigen::Vector3d(0.5, -1.0, 3.0) : Eigen::Vector3d(0, 0, 3.0);
  u.resize(nd);
  v.resize(nd);
  for (int a = 0; a < nd / c.dim; ++a) {
    Eigen::Vector3d x = Eigen::Vector3d::Zero();
    for (int i = 0; i < c.dim; ++i) {
      const int j = a * c.dim + i;
      u(j) = w[static_cast<std::size_t>(j)];
      x(i) = X[static_cast<std::size_t>(j)] + u(j);
    }
    const Eigen::Vector3d vx = omega.cross(x - Eigen::Vector3d(0.2, 0.1, 0.0));
    for (int i = 0; i < c.dim; ++i)
      v(a * c.dim + i) = vx(i) + r[static_cast<std::size_t>(a * c.dim + i)];
  }
}

// Largest relative drift of the invariants over n_steps steps of size dt.
struct Drift {
  double energy = 0.0, momentum = 0.0, angular = 0.0;
  int max_newton = 0;
};

Drift integrate(const Case& c, bool energy_momentum, double dt, int n_steps) {
  const FreeElement e(c, energy_momentum);
  Vec u, v;
  initial_state(c, e.n_dofs(), u, v);
  const Invariants I0 = e.invariants(u, v);
  Drift d;
  for (int n = 0; n < n_steps; ++n) {
    const int its = e.step(dt, u, v);
    EXPECT_GT(its, 0) << "step " << n;
    if (its < 0) return d;
    d.max_newton = std::max(d.max_newton, its);
    const Invariants I = e.invariants(u, v);
    d.energy = std::max(d.energy, std::abs(I.energy - I0.energy) / I0.energy);
    d.momentum = std::max(d.momentum, (I.momentum - I0.momentum).norm() / I0.momentum.norm());
    d.angular = std::max(d.angular, (I.angular - I0.angular).norm() / I0.angular.norm());
  }
  return d;
}

} // namespace

TEST(AlgorithmicDynamics, FreeElementConservesEnergyAndMomenta) {
  const std::vector<Case> cases = {
      {fem::CellType::hex8, 3, PlaneMode::none, MaterialModel::neo_hooke},
      {fem::CellType::hex20, 3, PlaneMode::none, MaterialModel::saint_venant_kirchhoff},
      {fem::CellType::quad4, 2, PlaneMode::plane_strain, MaterialModel::neo_hooke},
      {fem::CellType::tri6, 2, PlaneMode::plane_stress, MaterialModel::neo_hooke},
      {fem::CellType::quad9, 2, PlaneMode::plane_stress, MaterialModel::saint_venant_kirchhoff},
  };
  const double dt = 0.02;
  const int n_steps = 200;
  for (const Case& c : cases) {
    const std::string label = std::string(fem::name(c.cell)) + "/" + std::string(name(c.model));
    const Drift emm = integrate(c, true, dt, n_steps);
    EXPECT_LT(emm.energy, 1e-11) << label;
    EXPECT_LT(emm.momentum, 1e-11) << label;
    EXPECT_LT(emm.angular, 1e-11) << label;
    EXPECT_LE(emm.max_newton, 8) << label; // quadratic convergence with the exact tangent

    const Drift mid = integrate(c, false, dt, n_steps);
    EXPECT_GT(mid.energy, 1e-5) << label; // the test problem is demanding enough
    EXPECT_LT(mid.momentum, 1e-11) << label;
    EXPECT_LT(mid.angular, 1e-11) << label;
  }
}
