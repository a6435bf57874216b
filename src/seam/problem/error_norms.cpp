#include "seam/problem/error_norms.hpp"

#include "seam/fem/cell.hpp"

#include <Eigen/Dense>

#include <array>
#include <cmath>

namespace seam::problem {

ErrorNorms error_norms(const Discretization& disc, const la::Vector& u, double t,
                       const std::vector<io::Expression>& exact) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  la::Vector::LocalView view(u, false);
  const auto ul = view.values();
  std::array<double, fem::max_cell_nodes> N{};
  std::array<double, fem::max_cell_nodes * 3> dN{};
  double e_l2 = 0.0, e_h1 = 0.0, u_l2 = 0.0;
  auto eval = [&](int i, const double* p) {
    return exact[i](t, p[0], p[1], dim == 3 ? p[2] : 0.0);
  };
  for (auto c : disc.local_cells()) {
    const auto type = mesh.cell_type[c];
    const auto nodes = mesh.cell(c);
    const int n = static_cast<int>(nodes.size());
    const auto rule = fem::quadrature(type, fem::default_quadrature_degree(type) + 2);
    // A finite-difference step relative to the cell size.
    double size = 0.0;
    for (int a = 1; a < n; ++a)
      for (int i = 0; i < dim; ++i)
        size = std::max(size, std::abs(mesh.x[nodes[a] * dim + i] - mesh.x[nodes[0] * dim + i]));
    const double h = 1e-6 * std::max(size, 1e-300);
    for (int q = 0; q < rule.n_points; ++q) {
      const double* xi = &rule.points[static_cast<std::size_t>(q) * dim];
      fem::shape_values(type, xi, N.data());
      fem::shape_gradients(type, xi, dN.data());
      Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
      double X[3] = {0, 0, 0};
      for (int i = 0; i < dim; ++i)
        for (int a_ = 0; a_ < dim; ++a_) J(i, a_) = 0.0;
      for (int a = 0; a < n; ++a)
        for (int i = 0; i < dim; ++i) {
          const double xa = mesh.x[static_cast<std::size_t>(nodes[a]) * dim + i];
          X[i] += N[a] * xa;
          for (int k = 0; k < dim; ++k) J(i, k) += xa * dN[a * dim + k];
        }
      const Eigen::Matrix3d Jinv = J.inverse();
      const double w = rule.weights[q] * std::abs(J.determinant());
      for (int i = 0; i < dim; ++i) {
        double uh = 0.0;
        double grad_h[3] = {0, 0, 0};
        for (int a = 0; a < n; ++a) {
          const double ua = ul[disc.local_dof(nodes[a], i)];
          uh += N[a] * ua;
          for (int k = 0; k < dim; ++k)
            for (int m = 0; m < dim; ++m) grad_h[k] += ua * dN[a * dim + m] * Jinv(m, k);
        }
        const double ue = eval(i, X);
        e_l2 += w * (uh - ue) * (uh - ue);
        u_l2 += w * ue * ue;
        for (int k = 0; k < dim; ++k) {
          double Xp[3] = {X[0], X[1], X[2]}, Xm[3] = {X[0], X[1], X[2]};
          Xp[k] += h;
          Xm[k] -= h;
          const double g = (eval(i, Xp) - eval(i, Xm)) / (2 * h);
          e_h1 += w * (grad_h[k] - g) * (grad_h[k] - g);
        }
      }
    }
  }
  const auto& comm = disc.comm();
  return {std::sqrt(comm.sum(e_l2)), std::sqrt(comm.sum(e_h1)), std::sqrt(comm.sum(u_l2))};
}

} // namespace seam::problem
