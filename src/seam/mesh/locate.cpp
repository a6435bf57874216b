#include "seam/mesh/locate.hpp"

#include "seam/common/error.hpp"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <limits>

namespace seam::mesh {
namespace {

bool is_simplex(fem::CellType t) {
  using fem::CellType;
  return t == CellType::tri3 || t == CellType::tri6 || t == CellType::tet4 || t == CellType::tet10;
}

// Largest extent of the nodes of a cell (its length scale).
double cell_extent(const std::array<double, 3 * fem::max_cell_nodes>& xc, int n) {
  double extent = 0.0;
  for (int a = 0; a < 3; ++a) {
    double lo = xc[a], hi = xc[a];
    for (int i = 1; i < n; ++i) {
      lo = std::min(lo, xc[3 * i + a]);
      hi = std::max(hi, xc[3 * i + a]);
    }
    extent = std::max(extent, hi - lo);
  }
  return extent;
}

} // namespace

double reference_distance(fem::CellType t, const double* xi) {
  const int d = fem::dimension(t);
  double outside = 0.0;
  if (is_simplex(t)) {
    double sum = 0.0;
    for (int a = 0; a < d; ++a) {
      outside = std::max(outside, -xi[a]);
      sum += xi[a];
    }
    outside = std::max(outside, sum - 1.0);
  } else {
    for (int a = 0; a < d; ++a) outside = std::max(outside, std::abs(xi[a]) - 1.0);
  }
  return outside;
}

std::optional<std::array<double, 3>> inverse_map(const Mesh& mesh, std::int32_t c,
                                                 std::span<const double> p) {
  SEAM_ASSERT(static_cast<int>(p.size()) >= mesh.dim);
  const auto type = mesh.cell_type[c];
  const int d = mesh.dim;
  std::array<double, 3 * fem::max_cell_nodes> xc{};
  std::array<double, fem::max_cell_nodes> N{};
  std::array<double, 3 * fem::max_cell_nodes> dN{};
  const int n = cell_coordinates(mesh, c, xc);
  const double h = cell_extent(xc, n);
  if (!(h > 0.0)) return std::nullopt;

  // Newton on r(xi) = x(xi) - p with J = dx/dxi; quadratic convergence near the solution, so a
  // step below 1e-14 (reference units) leaves x(xi) - p at round-off. In 2D the system is
  // padded with an identity row so one 3x3 solve serves both dimensions.
  Point xi = reference_centre(type);
  constexpr int max_iterations = 40;
  for (int it = 0; it < max_iterations; ++it) {
    fem::shape_values(type, xi.data(), N.data());
    fem::shape_gradients(type, xi.data(), dN.data());
    Eigen::Vector3d r = Eigen::Vector3d::Zero();
    Eigen::Matrix3d J = Eigen::Matrix3d::Identity();
    for (int a = 0; a < d; ++a) {
      r(a) = -p[a];
      for (int b = 0; b < d; ++b) J(a, b) = 0.0;
    }
    for (int i = 0; i < n; ++i)
      for (int a = 0; a < d; ++a) {
        r(a) += N[i] * xc[3 * i + a];
        for (int b = 0; b < d; ++b) J(a, b) += xc[3 * i + a] * dN[i * d + b];
      }
    const double det = J.determinant();
    if (!(std::abs(det) > 1e-14 * std::pow(h, d))) return std::nullopt; // degenerate map
    const Eigen::Vector3d step = J.partialPivLu().solve(r);
    double step_norm = 0.0;
    for (int a = 0; a < d; ++a) {
      xi[a] -= step(a);
      step_norm = std::max(step_norm, std::abs(step(a)));
    }
    if (!std::isfinite(step_norm) || std::abs(xi[0]) + std::abs(xi[1]) + std::abs(xi[2]) > 1e3)
      return std::nullopt; // diverging: the point is far from this cell
    if (step_norm <= 1e-14) {
      // Verify rather than trust the step: a stalled iteration must not report a location.
      const auto x = map_to_physical(mesh, c, xi.data());
      double residual = 0.0;
      for (int a = 0; a < d; ++a) residual = std::max(residual, std::abs(x[a] - p[a]));
      if (residual <= 1e-11 * h) return xi;
      return std::nullopt;
    }
  }
  return std::nullopt;
}

PointLocator::PointLocator(const Mesh& mesh)
    : mesh_(&mesh), cells_(static_cast<std::size_t>(mesh.n_cells())) {
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) cells_[c] = c;
  fill_boxes();
}

PointLocator::PointLocator(const Mesh& mesh, std::span<const std::int32_t> cells)
    : mesh_(&mesh), cells_(cells.begin(), cells.end()) {
  SEAM_ASSERT(std::is_sorted(cells_.begin(), cells_.end()));
  fill_boxes();
}

void PointLocator::fill_boxes() {
  const Mesh& mesh = *mesh_;
  boxes_.resize(6 * cells_.size());
  std::array<double, 3 * fem::max_cell_nodes> xc{};
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    const auto c = cells_[k];
    const int n = cell_coordinates(mesh, c, xc);
    const double h = cell_extent(xc, n);
    // A quadratic cell's edges may bulge beyond its nodes' box; a quarter of its size is a
    // generous bound for any cell that is not inverted.
    const double margin = (fem::order(mesh.cell_type[c]) > 1 ? 0.25 : 1e-8) * h;
    double* box = &boxes_[6 * k];
    for (int a = 0; a < 3; ++a) {
      box[a] = std::numeric_limits<double>::max();
      box[3 + a] = std::numeric_limits<double>::lowest();
      for (int i = 0; i < n; ++i) {
        box[a] = std::min(box[a], xc[3 * i + a]);
        box[3 + a] = std::max(box[3 + a], xc[3 * i + a]);
      }
      box[a] -= margin;
      box[3 + a] += margin;
    }
  }
}

std::optional<PointLocation> PointLocator::locate(std::span<const double> point, double tol) const {
  const Mesh& mesh = *mesh_;
  SEAM_CHECK(static_cast<int>(point.size()) == mesh.dim, InputError, "a point in a ", mesh.dim,
             "D mesh needs ", mesh.dim, " coordinates, not ", point.size());
  SEAM_CHECK(tol >= 0.0, InputError, "point location tolerance must be >= 0");
  std::optional<PointLocation> best;
  double best_distance = std::numeric_limits<double>::max();
  for (std::size_t k = 0; k < cells_.size(); ++k) {
    const auto c = cells_[k];
    const double* box = &boxes_[6 * k];
    // The box grows with tol (reference units, at most 2 per cell width) times the cell size.
    double size = 0.0;
    for (int a = 0; a < mesh.dim; ++a) size = std::max(size, box[3 + a] - box[a]);
    const double slack = tol * size;
    bool in_box = true;
    for (int a = 0; a < mesh.dim && in_box; ++a)
      in_box = point[a] >= box[a] - slack && point[a] <= box[3 + a] + slack;
    if (!in_box) continue;
    const auto xi = inverse_map(mesh, c, point);
    if (!xi) continue;
    const double distance = reference_distance(mesh.cell_type[c], xi->data());
    // Inside up to round-off: the lowest-index cell wins, which makes shared facets deterministic.
    if (distance <= 1e-13) return PointLocation{c, *xi};
    if (distance <= tol && distance < best_distance) {
      best_distance = distance;
      best = PointLocation{c, *xi};
    }
  }
  return best;
}

std::optional<PointLocation> locate_point(const Mesh& mesh, std::span<const double> point,
                                          double tol) {
  return PointLocator(mesh).locate(point, tol);
}

} // namespace seam::mesh
