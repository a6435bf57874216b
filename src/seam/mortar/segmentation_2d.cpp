// 2D segment-based mortar integration of a line2/line3 slave-master pair (Popp et al. 2009;
// ALGORITHMS.md §1): project the end nodes, decide the overlap segment on the slave, then
// integrate D, M and the weighted gap with 5 Gauss points on that segment.
#include <algorithm>
#include <array>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/mortar/normals.hpp"
#include "seam/mortar/pair_integration.hpp"

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

} // namespace

PairContribution integrate_pair(const SlaveFacet<2>& slave, const Facet<2>& master,
                                const PairOptions& options) {
  const Facet<2>& s = slave.facet;
  PairContribution c = detail::empty_contribution(s.n_nodes, master.n_nodes);

  const auto slave_curve = [&s](double xi) {
    const auto p = evaluate(s, &xi);
    return CurvePoint{p.x, p.dx.col(0)};
  };
  // Unnormalized interpolated slave normal: scaling does not move the zero of
  // (x_s(xi) - p) x n(xi), and its derivative stays a plain sum.
  const auto slave_normal_field = [&slave](double xi) {
    const auto p = evaluate(slave.facet, &xi);
    return CurvePoint{slave.normals * p.N, slave.normals * p.dN.col(0)};
  };

  const double center = 0.0;
  const Eigen::Vector2d n_s = scaled_normal<2>(evaluate(s, &center).dx).normalized();
  const Eigen::Vector2d n_m = scaled_normal<2>(evaluate(master, &center).dx).normalized();
  if (!(n_s.dot(n_m) < options.max_normal_alignment_2d)) return c;

  // End nodes are local nodes 0 (xi = -1) and 1 (xi = +1) of line2 and line3.
  std::array<CurveProjection, 2> master_on_slave;
  std::array<CurveProjection, 2> slave_on_master;
  for (int k = 0; k < 2; ++k) {
    master_on_slave[static_cast<std::size_t>(k)] = geometry::project_onto_curve_along_field(
        slave_curve, slave_normal_field, master.x.col(k), 0.0, options.newton);
    slave_on_master[static_cast<std::size_t>(k)] =
        project_onto_facet(master, s.x.col(k), slave.normals.col(k), 0.0, options.newton);
  }
  const Segment segment = overlap_segment(slave_curve, master, master_on_slave, slave_on_master,
                                          options.projection_range_tolerance);
  if (!segment.overlap) return c;

  using Rule = geometry::LineRule5;
  const double segment_jacobian = 0.5 * (segment.xb - segment.xa);
  double eta_guess = 0.0;
  NodalVector N_tilde;
  NodalVector Phi;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double g = Rule::points[static_cast<std::size_t>(q)];
    const double xi = 0.5 * ((1.0 - g) * segment.xa + (1.0 + g) * segment.xb);
    const auto sp = evaluate(s, &xi);
    const Eigen::Vector2d n = interpolated_normal<2>(slave.normals, sp.N);
    // The Gauss point's image on the master along the interpolated slave normal.
    const CurveProjection image = project_onto_facet(master, sp.x, n, eta_guess, options.newton);
    if (!image.converged) {
      ++c.n_projection_failures;
      continue;
    }
    eta_guess = image.xi;
    const auto mp = evaluate(master, &image.xi);
    const double w =
        Rule::weights[static_cast<std::size_t>(q)] * sp.dx.col(0).norm() * segment_jacobian;
    slave_functions(slave.basis, s.type, s.n_nodes, sp.N, N_tilde, Phi);
    detail::accumulate_point(c, slave.basis.multiplier, w, N_tilde, Phi, mp.N, n.dot(mp.x - sp.x));
    c.area += w;
  }
  c.n_cells = 1;
  return c;
}

} // namespace seam::mortar
