#include "seam/ale/mesh_motion.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace seam::ale {

std::vector<double> jacobian_stiffening(const mesh::Mesh& mesh, std::span<const std::int32_t> cells,
                                        double power, double smallest) {
  std::vector<double> factor(cells.size(), 1.0);
  if (cells.empty() || power == 0.0) return factor;
  const bool given = smallest > 0.0;
  for (std::size_t k = 0; k < cells.size(); ++k) {
    factor[k] = mesh::cell_volume(mesh, cells[k]);
    if (!given) smallest = k == 0 ? factor[k] : std::min(smallest, factor[k]);
  }
  for (auto& f : factor) f = std::pow(smallest / f, power);
  return factor;
}

namespace {

double det_at(fem::CellType type, std::span<const double> x, const double* xi) {
  const int dim = fem::dimension(type);
  const int n = fem::n_nodes(type);
  std::array<double, fem::max_cell_nodes * 3> dN{};
  fem::shape_gradients(type, xi, dN.data());
  std::array<double, 9> J{};
  for (int a = 0; a < n; ++a)
    for (int i = 0; i < dim; ++i)
      for (int b = 0; b < dim; ++b) J[i * dim + b] += x[a * dim + i] * dN[a * dim + b];
  if (dim == 2) return J[0] * J[3] - J[1] * J[2];
  return J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
         J[2] * (J[3] * J[7] - J[4] * J[6]);
}

} // namespace

bool inverted(fem::CellType type, std::span<const double> x) {
  const int dim = fem::dimension(type);
  SEAM_ASSERT(static_cast<int>(x.size()) == fem::n_nodes(type) * dim);
  const auto rule = fem::quadrature(type, 3 * fem::order(type));
  for (int q = 0; q < rule.n_points; ++q)
    if (!(det_at(type, x, &rule.points[q * dim]) > 0.0)) return true;
  // The vertices: a cell can fold at a corner between the quadrature points.
  const auto ref = fem::reference_nodes(type);
  for (int v = 0; v < fem::n_vertices(type); ++v)
    if (!(det_at(type, x, &ref[v * dim]) > 0.0)) return true;
  return false;
}

GeneralizedAlpha GeneralizedAlpha::from_rho_inf(double rho_inf) {
  GeneralizedAlpha ga;
  ga.alpha_m = 0.5 * (3.0 - rho_inf) / (1.0 + rho_inf);
  ga.alpha_f = 1.0 / (1.0 + rho_inf);
  ga.gamma = 0.5 + ga.alpha_m - ga.alpha_f;
  return ga;
}

void step_mesh(const GeneralizedAlpha& ga, double h, std::span<const double> X,
               std::span<const double> d_old, std::span<const double> d_new,
               std::span<const double> d_dot_old, std::span<double> x, std::span<double> w,
               std::span<double> d_dot_new) {
  const std::size_t n = X.size();
  SEAM_ASSERT(d_old.size() == n && d_new.size() == n && d_dot_old.size() == n && x.size() == n &&
              w.size() == n && d_dot_new.size() == n && h > 0.0);
  for (std::size_t k = 0; k < n; ++k) {
    d_dot_new[k] =
        (d_new[k] - d_old[k]) / (ga.gamma * h) - (1.0 - ga.gamma) / ga.gamma * d_dot_old[k];
    x[k] = X[k] + (1.0 - ga.alpha_f) * d_old[k] + ga.alpha_f * d_new[k];
    w[k] = (1.0 - ga.alpha_m) * d_dot_old[k] + ga.alpha_m * d_dot_new[k];
  }
}

} // namespace seam::ale
