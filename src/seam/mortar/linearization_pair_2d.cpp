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

// Shape functions of line2 / line3 (nodes -1, 1, 0) with first and second derivatives.
struct LineShape {
  std::array<double, 3> N{}, dN{}, d2N{};
};

LineShape line_shape(fem::CellType type, double xi) {
  if (type == fem::CellType::line2)
    return {{0.5 * (1.0 - xi), 0.5 * (1.0 + xi), 0.0}, {-0.5, 0.5, 0.0}, {}};
  return {{0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi},
          {xi - 0.5, xi + 0.5, -2.0 * xi},
          {1.0, 1.0, -2.0}};
}

// project_onto_facet along d; a straight master (line2) in closed form: with
// x(eta) = m + eta h, (x(eta) - p) x d = 0 gives eta = (p - m) x d / (h x d).
geometry::CurveProjection project_on_master(const Facet<2>& master, const Eigen::Vector2d& p,
                                            const Eigen::Vector2d& d, double eta0,
                                            const geometry::NewtonOptions& options) {
  if (master.type == fem::CellType::line2) {
    const Eigen::Vector2d m = 0.5 * (master.x.col(0) + master.x.col(1));
    const Eigen::Vector2d h = 0.5 * (master.x.col(1) - master.x.col(0));
    const double slope = geometry::cross2(h, d);
    if (std::abs(slope) > 1e-14 * h.norm() * d.norm()) {
      geometry::CurveProjection r;
      r.xi = geometry::cross2(Eigen::Vector2d(p - m), d) / slope;
      r.converged = std::isfinite(r.xi);
      if (r.converged) return r;
    }
  }
  return project_onto_facet(master, p, d, eta0, options);
}

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
  const int ns = s.n_nodes, nm = master.n_nodes;
  double eta_guess = 0.0;
  NodalVectorT<S> N_tilde;
  NodalVectorT<S> Phi;
  NodalVectorT<S> N = NodalVectorT<S>::Zero();
  NodalVectorT<S> Nm = NodalVectorT<S>::Zero();
  for (int q = 0; q < Rule::n_points; ++q) {
    const double g = Rule::points[static_cast<std::size_t>(q)];
    const S xi = 0.5 * ((1.0 - g) * segment.xa + (1.0 + g) * segment.xb);
    const double xi_value = value_of(xi);
    // To first order N(xi) = N(v) + N'(v) (xi - v) and x'(xi) = x'(v) + x''(v) (xi - v).
    const LineShape shape = line_shape(s.type, xi_value);
    const S dxi = xi - xi_value;
    Vector<S, 2> x_s = Vector<S, 2>::Zero(), normal = Vector<S, 2>::Zero(),
                 tangent = Vector<S, 2>::Zero();
    for (int k = 0; k < ns; ++k) {
      const auto i = static_cast<std::size_t>(k);
      N(k) = shape.N[i];
      add_product(N(k), dxi, shape.dN[i]);
      S dN = shape.dN[i];
      if (shape.d2N[i] != 0.0) add_product(dN, dxi, shape.d2N[i]);
      for (int a = 0; a < 2; ++a) {
        add_product(x_s(a), s.x(a, k), N(k));
        add_product(normal(a), slave.normals(a, k), N(k));
        add_product(tangent(a), s.x(a, k), dN);
      }
    }
    const Vector<S, 2> n = normalized(normal);
    // The Gauss point's image on the master along the interpolated slave normal: Newton on
    // values, then the implicit-function step (linearization_kernels.hpp).
    const geometry::CurveProjection image =
        project_on_master(mv, values(x_s), values(n), eta_guess, options.newton);
    if (!image.converged) {
      ++c.n_projection_failures;
      continue;
    }
    eta_guess = image.xi;
    const LineShape master_shape = line_shape(master.type, image.xi);
    Vector<S, 2> residual = -x_s;
    Eigen::Vector2d dx = Eigen::Vector2d::Zero();
    for (int l = 0; l < nm; ++l) {
      const auto i = static_cast<std::size_t>(l);
      for (int a = 0; a < 2; ++a) add_product(residual(a), master.x(a, l), master_shape.N[i]);
      dx += master_shape.dN[i] * mv.x.col(l);
    }
    const S eta =
        at_root<S>(image.xi, image.xi - cross2<S>(residual, n) / geometry::cross2(dx, values(n)));
    const S deta = eta - image.xi;
    Vector<S, 2> x_m = Vector<S, 2>::Zero();
    for (int l = 0; l < nm; ++l) {
      const auto i = static_cast<std::size_t>(l);
      Nm(l) = master_shape.N[i];
      add_product(Nm(l), deta, master_shape.dN[i]);
      for (int a = 0; a < 2; ++a) add_product(x_m(a), master.x(a, l), Nm(l));
    }
    const S w = Rule::weights[static_cast<std::size_t>(q)] * norm(tangent) * segment_jacobian;
    // Phi = A N~ (N~ = N on lines) over the node count only.
    for (int j = 0; j < ns; ++j) {
      N_tilde(j) = N(j);
      if (slave.multiplier == Multiplier::dual) {
        Phi(j) = slave.A(j, 0) * N(0);
        for (int k = 1; k < ns; ++k) add_product(Phi(j), slave.A(j, k), N(k));
      } else {
        Phi(j) = N(j);
      }
    }
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
