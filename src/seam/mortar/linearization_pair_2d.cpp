// 2D segment-based mortar integration (Popp et al. 2009; ALGORITHMS.md §1) on a scalar type,
// following segmentation_2d.cpp. The overlap case is decided on values; the segment ends xa,
// xb are then either fixed slave ends (+-1, no derivative) or master end nodes projected onto
// the slave along the interpolated normal, whose derivatives follow from the implicit
// function theorem (linearization_kernels.hpp). Each Gauss point xi = ((1-g) xa + (1+g) xb)/2
// moves with the ends, its master image with the slave point and the normal there.
#include <algorithm>
#include <array>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/mortar/linearization_pair.hpp"

namespace seam::mortar::ad {

namespace {

template <class S> struct SegmentT {
  bool overlap = false;
  S xa = 0.0;
  S xb = 0.0;
};

template <class S> S clamp_unit(const S& xi) {
  if (value_of(xi) < -1.0) return S(-1.0);
  if (value_of(xi) > 1.0) return S(1.0);
  return xi;
}

// overlap_segment of segmentation_2d.cpp: the master end nodes projected onto the slave bound
// the segment wherever they land on it; the slave end nodes projected onto the master only
// decide whether the slave lies inside the master.
template <class S>
SegmentT<S> overlap_segment(const Facet<2>& slave, const Facet<2>& master,
                            const std::array<CurveProjectionT<S>, 2>& master_on_slave,
                            const std::array<geometry::CurveProjection, 2>& slave_on_master,
                            double tol) {
  const auto inside_value = [tol](bool converged, double xi) {
    return converged && xi >= -1.0 - tol && xi <= 1.0 + tol;
  };
  const bool m0 = inside_value(master_on_slave[0].converged, value_of(master_on_slave[0].xi));
  const bool m1 = inside_value(master_on_slave[1].converged, value_of(master_on_slave[1].xi));
  SegmentT<S> s;
  if (m0 && m1) {
    const bool first_smaller = value_of(master_on_slave[0].xi) < value_of(master_on_slave[1].xi);
    s.xa = first_smaller ? master_on_slave[0].xi : master_on_slave[1].xi;
    s.xb = first_smaller ? master_on_slave[1].xi : master_on_slave[0].xi;
  } else if (m0 || m1) {
    const int k = m0 ? 0 : 1;
    const S xi_in = clamp_unit(master_on_slave[static_cast<std::size_t>(k)].xi);
    const double xi_value = value_of(xi_in);
    const Eigen::Vector2d towards_other = master.x.col(1 - k) - master.x.col(k);
    if (towards_other.dot(evaluate(slave, &xi_value).dx.col(0)) > 0.0) {
      s.xa = xi_in;
      s.xb = 1.0;
    } else {
      s.xa = -1.0;
      s.xb = xi_in;
    }
  } else if (inside_value(slave_on_master[0].converged, slave_on_master[0].xi) &&
             inside_value(slave_on_master[1].converged, slave_on_master[1].xi)) {
    s.xa = -1.0;
    s.xb = 1.0;
  } else {
    return s;
  }
  s.xa = clamp_unit(s.xa);
  s.xb = clamp_unit(s.xb);
  s.overlap = value_of(s.xb) - value_of(s.xa) > 1e-12;
  return s;
}

} // namespace

template <class S>
PairContributionT<S> integrate_pair_t(const SlaveFacetT<S, 2>& slave, const FacetT<S, 2>& master,
                                      const PairOptions& options) {
  const FacetT<S, 2>& s = slave.facet;
  const Facet<2> sv = values(s);
  const Facet<2> mv = values(master);
  const Eigen::Matrix<double, 2, max_facet_nodes> normals = values(slave.normals);
  PairContributionT<S> c = detail::empty_contribution_t<S>(s.n_nodes, master.n_nodes);

  const double center = 0.0;
  const Eigen::Vector2d n_s = scaled_normal<2>(evaluate(sv, &center).dx).normalized();
  const Eigen::Vector2d n_m = scaled_normal<2>(evaluate(mv, &center).dx).normalized();
  if (!(n_s.dot(n_m) < options.max_normal_alignment_2d)) return c;

  std::array<CurveProjectionT<S>, 2> master_on_slave;
  std::array<geometry::CurveProjection, 2> slave_on_master;
  for (int k = 0; k < 2; ++k) {
    master_on_slave[static_cast<std::size_t>(k)] = project_along_normals_t<S>(
        s, slave.normals, Vector<S, 2>(master.x.col(k)), 0.0, options.newton);
    slave_on_master[static_cast<std::size_t>(k)] =
        project_onto_facet(mv, sv.x.col(k), normals.col(k), 0.0, options.newton);
  }
  const SegmentT<S> segment = overlap_segment<S>(sv, mv, master_on_slave, slave_on_master,
                                                 options.projection_range_tolerance);
  if (!segment.overlap) return c;

  using Rule = geometry::LineRule5;
  const S segment_jacobian = 0.5 * (segment.xb - segment.xa);
  double eta_guess = 0.0;
  NodalVectorT<S> N_tilde;
  NodalVectorT<S> Phi;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double g = Rule::points[static_cast<std::size_t>(q)];
    const S xi = 0.5 * ((1.0 - g) * segment.xa + (1.0 + g) * segment.xb);
    const NodalVectorT<S> N = shape_values_t<S, 2>(s.type, &xi);
    const Vector<S, 2> x_s = interpolate<S, 2>(s.x, N, s.n_nodes);
    const Vector<S, 2> n = normalized(interpolate<S, 2>(slave.normals, N, s.n_nodes));
    // The Gauss point's image on the master along the interpolated slave normal.
    const CurveProjectionT<S> image =
        project_onto_line_t<S>(master, x_s, n, eta_guess, options.newton);
    if (!image.converged) {
      ++c.n_projection_failures;
      continue;
    }
    eta_guess = value_of(image.xi);
    const NodalVectorT<S> Nm = shape_values_t<S, 2>(master.type, &image.xi);
    const Vector<S, 2> x_m = interpolate<S, 2>(master.x, Nm, master.n_nodes);
    const S w = Rule::weights[static_cast<std::size_t>(q)] * norm(line_tangent_t<S>(s, xi)) *
                segment_jacobian;
    detail::slave_functions_t(slave, N, N_tilde, Phi);
    detail::accumulate_point_t(c, slave.multiplier, w, N_tilde, Phi, Nm,
                               dot(n, Vector<S, 2>(x_m - x_s)));
    c.area += value_of(w);
  }
  c.n_cells = 1;
  return c;
}

template PairContributionT<double> integrate_pair_t(const SlaveFacetT<double, 2>&,
                                                    const FacetT<double, 2>&, const PairOptions&);
template PairContributionT<Dual<12>>
integrate_pair_t(const SlaveFacetT<Dual<12>, 2>&, const FacetT<Dual<12>, 2>&, const PairOptions&);
template PairContributionT<Dual<18>>
integrate_pair_t(const SlaveFacetT<Dual<18>, 2>&, const FacetT<Dual<18>, 2>&, const PairOptions&);

} // namespace seam::mortar::ad
