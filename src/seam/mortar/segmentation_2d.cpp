// 2D segment-based mortar integration of a line2/line3 slave-master pair (Popp et al. 2009;
// ALGORITHMS.md §1): project the end nodes, decide the overlap segment on the slave, then
// integrate D, M and the weighted gap with 5 Gauss points on that segment.
//
// Both facets are handled in a frame with its origin at the slave's first node: the Newton
// projections converge to a parameter increment of 1e-12, and with global coordinates the
// round-off of x(xi) - p, eps |x|, limits the parameter to about eps |x| / h, more than that on
// small facets far from the origin (|x| / h >~ 1e4). The shape functions of line2 and line3
// are written out, as they are evaluated several times per Newton iteration.
#include <algorithm>
#include <array>

#include "seam/common/error.hpp"
#include "seam/geometry/cell_quadrature.hpp"
#include "seam/mortar/pair_integration.hpp"
#include "seam/mortar/pair_integration_detail.hpp"

namespace seam::mortar {

namespace {

using geometry::CurvePoint;
using geometry::CurveProjection;

struct Segment {
  bool overlap = false;
  double xa = 0.0;
  double xb = 0.0;
};

// Turn the end-node projections into the overlap segment [xa, xb] of the slave parameter.
// The master end nodes, projected along the interpolated slave normal, bound the segment
// wherever they land on the slave; the slave end nodes, projected along their nodal normals,
// only decide the case where no master end lands on the slave (slave inside master or no
// overlap). Only end nodes decide, for line3 too.
template <class SlaveCurve>
Segment overlap_segment(const SlaveCurve& slave_curve, const Facet<2>& master,
                        const std::array<CurveProjection, 2>& master_on_slave,
                        const std::array<CurveProjection, 2>& slave_on_master, double tol) {
  const auto inside = [tol](const CurveProjection& r) {
    return r.converged && r.xi >= -1.0 - tol && r.xi <= 1.0 + tol;
  };
  const bool m0 = inside(master_on_slave[0]);
  const bool m1 = inside(master_on_slave[1]);
  Segment s;
  if (m0 && m1) { // master inside slave (or both cover each other)
    s.xa = std::min(master_on_slave[0].xi, master_on_slave[1].xi);
    s.xb = std::max(master_on_slave[0].xi, master_on_slave[1].xi);
  } else if (m0 || m1) { // partial overlap
    const int k = m0 ? 0 : 1;
    const double xi_in = std::clamp(master_on_slave[static_cast<std::size_t>(k)].xi, -1.0, 1.0);
    // The master runs from its end on the slave towards its other end; the direction of that
    // end along the slave tangent tells which slave end the overlap extends to.
    const Eigen::Vector2d towards_other = master.x.col(1 - k) - master.x.col(k);
    if (towards_other.dot(slave_curve(xi_in).dx) > 0.0) {
      s.xa = xi_in;
      s.xb = 1.0;
    } else {
      s.xa = -1.0;
      s.xb = xi_in;
    }
  } else if (inside(slave_on_master[0]) && inside(slave_on_master[1])) { // slave inside master
    s.xa = -1.0;
    s.xb = 1.0;
  } else {
    return s;
  }
  s.xa = std::clamp(s.xa, -1.0, 1.0);
  s.xb = std::clamp(s.xb, -1.0, 1.0);
  s.overlap = s.xb - s.xa > 1e-12;
  return s;
}

// A line2 or line3 facet in the local frame, its nodes as columns (unused columns zero).
// line2: N = ((1 - xi) / 2, (1 + xi) / 2); line3 (nodes at -1, 1, 0): N = (xi (xi - 1) / 2,
// xi (xi + 1) / 2, 1 - xi^2), as seam::fem.
struct Line {
  int n_nodes = 2;
  Eigen::Matrix<double, 2, 3> x = Eigen::Matrix<double, 2, 3>::Zero();

  void shape(double xi, NodalVector& N, std::array<double, 3>& dN) const {
    if (n_nodes == 2) {
      N(0) = 0.5 * (1.0 - xi);
      N(1) = 0.5 * (1.0 + xi);
      dN = {-0.5, 0.5, 0.0};
    } else {
      N(0) = 0.5 * xi * (xi - 1.0);
      N(1) = 0.5 * xi * (xi + 1.0);
      N(2) = 1.0 - xi * xi;
      dN = {xi - 0.5, xi + 0.5, -2.0 * xi};
    }
  }
  template <class Nodal> CurvePoint combine(const Nodal& X, double xi) const {
    NodalVector N;
    std::array<double, 3> dN;
    shape(xi, N, dN);
    CurvePoint p{N(0) * X.col(0) + N(1) * X.col(1), dN[0] * X.col(0) + dN[1] * X.col(1)};
    if (n_nodes == 3) {
      p.x += N(2) * X.col(2);
      p.dx += dN[2] * X.col(2);
    }
    return p;
  }
  CurvePoint operator()(double xi) const { return combine(x, xi); }
};

Line local_line(const Facet<2>& facet, const Eigen::Vector2d& origin) {
  SEAM_ASSERT(facet.type == fem::CellType::line2 || facet.type == fem::CellType::line3);
  Line line;
  line.n_nodes = facet.n_nodes;
  for (int k = 0; k < facet.n_nodes; ++k) line.x.col(k) = facet.x.col(k) - origin;
  return line;
}

} // namespace

PairContribution integrate_pair(const SlaveFacet<2>& slave, const Facet<2>& master,
                                const PairOptions& options) {
  const Facet<2>& s = slave.facet;
  PairContribution c = detail::empty_contribution(s.n_nodes, master.n_nodes);

  const Eigen::Vector2d origin = s.x.col(0);
  const Line slave_curve = local_line(s, origin);
  const Line master_curve = local_line(master, origin);
  Eigen::Matrix<double, 2, 3> slave_normals = Eigen::Matrix<double, 2, 3>::Zero();
  for (int k = 0; k < s.n_nodes; ++k) slave_normals.col(k) = slave.normals.col(k);
  // Unnormalized interpolated slave normal: scaling does not move the zero of
  // (x_s(xi) - p) x n(xi), and its derivative stays a plain sum.
  const auto slave_normal_field = [&](double xi) { return slave_curve.combine(slave_normals, xi); };

  const Eigen::Vector2d n_s = scaled_normal<2>(slave_curve(0.0).dx).normalized();
  const Eigen::Vector2d n_m = scaled_normal<2>(master_curve(0.0).dx).normalized();
  if (!(n_s.dot(n_m) < options.max_normal_alignment_2d)) return c;

  // End nodes are local nodes 0 (xi = -1) and 1 (xi = +1) of line2 and line3.
  std::array<CurveProjection, 2> master_on_slave;
  std::array<CurveProjection, 2> slave_on_master;
  for (int k = 0; k < 2; ++k) {
    master_on_slave[static_cast<std::size_t>(k)] = geometry::project_onto_curve_along_field(
        slave_curve, slave_normal_field, master_curve.x.col(k), 0.0, options.newton);
    slave_on_master[static_cast<std::size_t>(k)] = geometry::project_onto_curve(
        master_curve, slave_curve.x.col(k), slave.normals.col(k), 0.0, options.newton);
  }
  const Segment segment = overlap_segment(slave_curve, master, master_on_slave, slave_on_master,
                                          options.projection_range_tolerance);
  if (!segment.overlap) return c;

  using Rule = geometry::LineRule5;
  const double segment_jacobian = 0.5 * (segment.xb - segment.xa);
  double eta_guess = 0.0;
  NodalVector Ns = NodalVector::Zero();
  NodalVector Nm = NodalVector::Zero();
  NodalVector N_tilde = NodalVector::Zero();
  NodalVector Phi = NodalVector::Zero();
  std::array<double, 3> dN;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double g = Rule::points[static_cast<std::size_t>(q)];
    const double xi = 0.5 * ((1.0 - g) * segment.xa + (1.0 + g) * segment.xb);
    const CurvePoint sp = slave_curve(xi);
    slave_curve.shape(xi, Ns, dN);
    const Eigen::Vector2d n = slave_curve.combine(slave_normals, xi).x.normalized();
    // The Gauss point's image on the master along the interpolated slave normal.
    const CurveProjection image =
        geometry::project_onto_curve(master_curve, sp.x, n, eta_guess, options.newton);
    if (!image.converged) {
      ++c.n_projection_failures;
      continue;
    }
    eta_guess = image.xi;
    const CurvePoint mp = master_curve(image.xi);
    master_curve.shape(image.xi, Nm, dN);
    const double w = Rule::weights[static_cast<std::size_t>(q)] * sp.dx.norm() * segment_jacobian;
    detail::slave_point_functions(slave.basis, s.type, s.n_nodes, Ns, N_tilde, Phi);
    detail::accumulate_point(c, slave.basis.multiplier, w, N_tilde, Phi, Nm, n.dot(mp.x - sp.x));
    c.area += w;
  }
  c.n_cells = 1;
  return c;
}

} // namespace seam::mortar
