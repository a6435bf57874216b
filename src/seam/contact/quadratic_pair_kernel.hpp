#pragma once
// The weighted gaps of one pair of 3D contact facets of which one at least is quadratic
// (gap_blocks_3d.cpp) with their first and second derivatives, for the unit tests and
// seam-bench: the kernel that gap_blocks_3d runs and the plain forward one on Hyper<81>
// (hyper_dual.hpp) it replaces.
#include "seam/fem/cell.hpp"
#include "seam/mortar/pair_integration.hpp"

#include <Eigen/Core>

#include <cmath>
#include <vector>

namespace seam::contact::detail {

/// One slave/master pair: positions, slave nodal normals (unit), the multiplier basis.
struct QuadraticPair {
  fem::CellType slave_type = fem::CellType::quad9, master_type = fem::CellType::quad9;
  std::vector<Eigen::Vector3d> xs, normals, xm;
  bool dual = true;
};

/// packed: the Hessian path gap_blocks_3d runs; forward: the plain one on Hyper<81>;
/// gradient: the gradient path on Dual<81> (no Hessians).
enum class QuadraticKernel { packed, forward, gradient };

/// The weighted gaps g_j of the slave nodes, their gradients (ns x 81, row-major) and Hessians
/// (ns x 81 x 81) in the variables: 27 slave positions, 27 slave normals, 27 master positions
/// (node k of a side at 3 k of its group; nodes beyond the facet's are unused).
void quadratic_pair_derivatives(const QuadraticPair& pair, const mortar::PairOptions& options,
                                QuadraticKernel kernel, std::vector<double>& gap,
                                std::vector<double>& gradient, std::vector<double>& hessian);

/// A curved pair for tests and seam-bench: both facets on z = 0.1 (x^2 + y^2) about 2 across,
/// the master turned by 0.3, shifted by (0.3, 0.2), 0.03 above and facing the slave, every
/// node and normal perturbed by up to `noise` (numbers from `seed`).
inline QuadraticPair curved_pair(fem::CellType slave_type, fem::CellType master_type, unsigned seed,
                                 double noise = 0.05) {
  unsigned long long state = 2862933555777941757ULL * (seed + 1ULL) + 3037000493ULL;
  const auto random = [&]() { // in [-1, 1)
    state = 6364136223846793005ULL * state + 1442695040888963407ULL;
    return static_cast<double>(state >> 11) * 0x1.0p-52 - 1.0;
  };
  const auto surface = [](double x, double y) { return 0.1 * (x * x + y * y); };
  // Reference nodes centred and scaled to a width of about 2.
  const auto nodes = [&](fem::CellType type, bool mirror) {
    const int n = fem::n_nodes(type);
    const double* r = fem::reference_nodes(type).data();
    const bool triangle = fem::n_vertices(type) == 3;
    std::vector<Eigen::Vector2d> p;
    for (int k = 0; k < n; ++k) {
      Eigen::Vector2d q(r[2 * k], r[2 * k + 1]);
      if (triangle) q = 3.0 * (q - Eigen::Vector2d(1.0 / 3.0, 1.0 / 3.0));
      if (mirror) q = Eigen::Vector2d(q.y(), q.x());
      p.push_back(q);
    }
    return p;
  };
  QuadraticPair pair;
  pair.slave_type = slave_type;
  pair.master_type = master_type;
  for (const auto& q : nodes(slave_type, false)) {
    const Eigen::Vector3d x(q.x() + noise * random(), q.y() + noise * random(),
                            surface(q.x(), q.y()) + noise * random());
    pair.xs.push_back(x);
    const Eigen::Vector3d n(-0.2 * x.x() + noise * random(), -0.2 * x.y() + noise * random(), 1.0);
    pair.normals.push_back(n.normalized());
  }
  const double c = std::cos(0.3), s = std::sin(0.3);
  for (const auto& q : nodes(master_type, true)) {
    const double x = c * q.x() - s * q.y() + 0.3 + noise * random();
    const double y = s * q.x() + c * q.y() + 0.2 + noise * random();
    pair.xm.emplace_back(x, y, surface(x, y) + 0.03 + noise * random());
  }
  return pair;
}

} // namespace seam::contact::detail
