// The weighted gaps of 2D line2 and line3 contact as functions of the nodal positions with exact
// first and second derivatives (energy-momentum contact, docs/contact_dynamics.md §4; line3:
// pair_gaps_line3, the same steps on curved facets).
//
// The kernel follows integrate_pair of segmentation_2d.cpp step by step on a scalar type S
// (double, Dual<12> or Hyper<12>): averaged unit nodal normals of the slave facet's nodes, the
// centre-normal pre-check, the end-node projections and the overlap segment (decided on
// values), five Gauss points on the segment, each projected onto the master along the
// interpolated slave normal, the dual (or standard) basis of line2 and the gap
// n . (x_m - x_s). Every formula is written exactly (no first-order expansion), so second
// derivatives come out right: the projection of a master node onto the slave, a root of a
// quadratic, is polished by three Newton steps on S from its converged value (each step
// doubles the order of the derivatives that are exact at the root); the Gauss point's image on
// a straight master is in closed form.
#include "seam/contact/contact_interface.hpp"

#include "seam/common/dual_number.hpp"
#include "seam/common/error.hpp"
#include "seam/common/hyper_dual.hpp"
#include "seam/contact/gap_pair_log.hpp"
#include "seam/contact/gap_vectors.hpp"
#include "seam/contact/rigid_obstacle_gaps.hpp"
#include "seam/geometry/cell_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace seam::contact {

namespace detail {
long gap_rejections[3] = {0, 0, 0};
std::vector<GapPairRecord>* gap_pair_log = nullptr;
} // namespace detail

namespace {

using namespace gap_vectors;

/// Half width of the clamp's rounding (clamp_unit) as a fraction of the projection range
/// tolerance: below 1, so that a projection leaves the range where its clamp is exact.
constexpr double clamp_width = 0.5;

/// max(x, 0) rounded over |x| < w, C2 and exact outside: w q(x / w + 1) with
/// q(u) = u^3 (4 - u) / 16 (q = q' = q'' = 0 at u = 0; w q = x, q' = 1, q'' = 0 at u = 2).
template <class S> S smooth_ramp(const S& x, double w) {
  if (value_of(x) <= -w) return S(0.0);
  if (value_of(x) >= w) return x;
  const S u = x / w + 1.0;
  return w / 16.0 * (u * u * u * (4.0 - u));
}

/// xi clamped to [-1, 1] with C2 corners of half width w: xi - ramp(xi - 1) + ramp(-1 - xi),
/// xi itself for |xi| <= 1 - w and -1 or 1 exactly for |xi| >= 1 + w. A segment end is a
/// master node's projection until it passes the slave's end, and the slave end after: with a
/// sharp clamp g~ has a kink where a master node meets a slave end node (equal meshes, the bar
/// impact), the solution sits on it, and the midpoint gradient (taken at a nonzero gap) jumps
/// between Newton iterations. Two master facets that meet at a master node take the same
/// clamped value of its projection, so they still tile the slave facet; where the paired
/// master region ends at that node (the next master facet is not a pair of this slave facet),
/// g~ of the slave facet's nodes changes slope by the gap there times their dual basis
/// functions at the end (-1 for the other node), and the rounding spreads that change over 2 w
/// with a curvature of at most 3 / (4 w) times it (docs/contact_dynamics.md, "The kink where a
/// master node passes a slave end node"). The rounding moves a segment end by at most 3 w / 16.
template <class S> S clamp_unit(const S& xi, double w) {
  return xi - smooth_ramp(S(xi - 1.0), w) + smooth_ramp(S(-1.0 - xi), w);
}

/// The overlap segment [xa, xb] of the slave parameter from the end-node projections, as
/// overlap_segment of segmentation_2d.cpp decides it on values: the master end nodes that land
/// on the slave bound it (their parameters `on_slave(k)` on the scalar type), else the slave
/// lies inside the master or there is no overlap. `forward(k)`: the master runs from its end k
/// towards +xi. The ends are clamped (rounded); false without overlap.
template <class S, class OnSlave, class Forward>
bool overlap_ends(const std::array<geometry::CurveProjection, 2>& master_on_slave,
                  const std::array<geometry::CurveProjection, 2>& slave_on_master, double tol,
                  const OnSlave& on_slave, const Forward& forward, S& xa, S& xb) {
  const auto inside = [tol](const geometry::CurveProjection& r) {
    return r.converged && r.xi >= -1.0 - tol && r.xi <= 1.0 + tol;
  };
  const bool in0 = inside(master_on_slave[0]), in1 = inside(master_on_slave[1]);
  // Only the ends that are master nodes' projections are clamped: an end that is the slave's
  // end node is -1 or 1 exactly, the value of the clamp of a projection beyond 1 + w, so
  // nothing jumps where the projection leaves the range at xi = 1 + tol (w = tol / 2).
  // Clamping the slave's ends too put them inside, and g~ jumped by the integrand over
  // that distance where a master end node's projection crossed 1 + tol.
  const double w = clamp_width * tol;
  xa = -1.0;
  xb = 1.0;
  if (in0 && in1) {
    const S e0 = on_slave(0), e1 = on_slave(1);
    const bool first = master_on_slave[0].xi < master_on_slave[1].xi;
    xa = clamp_unit(first ? e0 : e1, w);
    xb = clamp_unit(first ? e1 : e0, w);
  } else if (in0 || in1) {
    const std::size_t k = in0 ? 0 : 1;
    const S xi_in = clamp_unit(on_slave(k), w);
    if (forward(k))
      xa = xi_in;
    else
      xb = xi_in;
  } else if (!(inside(slave_on_master[0]) && inside(slave_on_master[1]))) {
    return false;
  }
  return value_of(xb) - value_of(xa) > 1e-12;
}

/// b.gap (and b.gradient, b.hessian as `order` asks) of the R slave rows of a pair from
/// `kernel` (a generic callable filling std::array<S, R>) on double, Dual<N> or Hyper<N>.
template <int N, std::size_t R, class Kernel>
void block_gaps(GapOrder order, GapBlock& b, const Kernel& kernel) {
  b.gap.assign(R, 0.0);
  if (order == GapOrder::value) {
    std::array<double, R> g{};
    kernel(g);
    std::copy(g.begin(), g.end(), b.gap.begin());
    return;
  }
  const auto store = [&b](const auto& g) {
    for (std::size_t j = 0; j < R; ++j) {
      b.gap[j] = g[j].value;
      b.gradient.insert(b.gradient.end(), g[j].gradient.begin(), g[j].gradient.end());
      if constexpr (requires { g[j].hessian; })
        b.hessian.insert(b.hessian.end(), g[j].hessian.begin(), g[j].hessian.end());
    }
  };
  if (order == GapOrder::gradient) {
    std::array<Dual<N>, R> g;
    kernel(g);
    store(g);
  } else {
    std::array<Hyper<N>, R> g;
    kernel(g);
    store(g);
  }
}

/// No overlap: the pair adds nothing.
bool empty_block(const GapBlock& b) {
  const auto zero = [](double v) { return v == 0.0; };
  return std::all_of(b.gap.begin(), b.gap.end(), zero) &&
         std::all_of(b.gradient.begin(), b.gradient.end(), zero);
}

/// One pair of facets with P nodes (line2: 2, line3: 3) in the frame of the slave facet's first
/// node: slots 0 to P - 1 the slave facet's nodes (ends, then line3's mid node), up to 2 (P - 1)
/// more for the other nodes of the facets around them (the nodal normals average those facets'
/// unit normals at the node), then the P master nodes; per slave node the slots of its (at most
/// two) facets in facet order and its local index in each.
template <int P> struct PairInputT {
  static constexpr int slave_slots = 3 * P - 2;
  std::array<Eigen::Vector2d, slave_slots + P> x;
  std::array<int, P> n_adjacent{};
  std::array<std::array<std::array<int, P>, 2>, P> adjacent{};
  std::array<std::array<int, 2>, P> local{};
  bool dual = true;
};
using PairInput = PairInputT<2>;

template <class S>
void pair_gaps(const PairInput& in, const mortar::PairOptions& options, std::array<S, 2>& g) {
  using std::sqrt;
  g = {S(0.0), S(0.0)};
  std::array<V2<S>, 6> X;
  for (int i = 0; i < 6; ++i)
    X[static_cast<std::size_t>(i)] = {
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].x(), 2 * i),
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].y(), 2 * i + 1)};
  // Averaged nodal normals: s_k = sum of the unit facet normals (t_y, -t_x) / |t|, n = s / |s|.
  std::array<V2<S>, 2> nn;
  for (std::size_t k = 0; k < 2; ++k) {
    V2<S> s;
    for (int f = 0; f < in.n_adjacent[k]; ++f) {
      const auto& ab = in.adjacent[k][static_cast<std::size_t>(f)];
      const V2<S> t = X[static_cast<std::size_t>(ab[1])] - X[static_cast<std::size_t>(ab[0])];
      const S l = length(t);
      s = s + V2<S>{t.y / l, -t.x / l};
    }
    const S l = length(s);
    nn[k] = {s.x / l, s.y / l};
  }
  const V2<S>&x0 = X[0], &x1 = X[1], &m0 = X[4], &m1 = X[5];
  const Eigen::Vector2d x0v = value(x0), x1v = value(x1), m0v = value(m0), m1v = value(m1);
  const Eigen::Vector2d n0v = value(nn[0]), n1v = value(nn[1]);
  // Centre normals of the two facets (integrate_pair's pre-check).
  const Eigen::Vector2d ts = 0.5 * (x1v - x0v), tm = 0.5 * (m1v - m0v);
  const Eigen::Vector2d ns = Eigen::Vector2d(ts.y(), -ts.x()).normalized();
  const Eigen::Vector2d nm = Eigen::Vector2d(tm.y(), -tm.x()).normalized();
  if (!(ns.dot(nm) < options.max_normal_alignment_2d)) {
    ++detail::gap_rejections[0];
    return;
  }

  const auto slave_curve = [&](double xi) {
    return geometry::CurvePoint{0.5 * (1.0 - xi) * x0v + 0.5 * (1.0 + xi) * x1v, ts};
  };
  const auto normal_field = [&](double xi) {
    return geometry::CurvePoint{0.5 * (1.0 - xi) * n0v + 0.5 * (1.0 + xi) * n1v, 0.5 * (n1v - n0v)};
  };
  const auto master_curve = [&](double eta) {
    return geometry::CurvePoint{0.5 * (1.0 - eta) * m0v + 0.5 * (1.0 + eta) * m1v, tm};
  };
  std::array<geometry::CurveProjection, 2> master_on_slave, slave_on_master;
  for (std::size_t k = 0; k < 2; ++k) {
    master_on_slave[k] = geometry::project_onto_curve_along_field(
        slave_curve, normal_field, k == 0 ? m0v : m1v, 0.0, options.newton);
    slave_on_master[k] = geometry::project_onto_curve(master_curve, k == 0 ? x0v : x1v,
                                                      k == 0 ? n0v : n1v, 0.0, options.newton);
  }
  // Master node k on the slave along n~(xi) = N_0 n_0 + N_1 n_1: the root of
  // F(xi) = (x_s(xi) - m_k) x n~(xi), polished on S.
  const auto on_slave = [&](std::size_t k) {
    S xi = master_on_slave[k].xi;
    const V2<S>& p = k == 0 ? m0 : m1;
    const V2<S> half_t = (x1 - x0) * 0.5, half_dn = (nn[1] - nn[0]) * 0.5;
    for (int it = 0; it < 3; ++it) {
      const S a0 = 0.5 * (1.0 - xi), a1 = 0.5 * (1.0 + xi);
      const V2<S> r = x0 * a0 + x1 * a1 - p;
      const V2<S> d = nn[0] * a0 + nn[1] * a1;
      xi = xi - cross(r, d) / (cross(half_t, d) + cross(r, half_dn));
    }
    return xi;
  };
  // The master runs from its end k (on the slave) towards its other end: along +xi?
  const auto forward = [&](std::size_t k) {
    const Eigen::Vector2d towards_other = k == 0 ? Eigen::Vector2d(m1v - m0v) : m0v - m1v;
    return towards_other.dot(ts) > 0.0;
  };
  S xa, xb;
  if (!overlap_ends(master_on_slave, slave_on_master, options.projection_range_tolerance, on_slave,
                    forward, xa, xb)) {
    ++detail::gap_rejections[1];
    if (!master_on_slave[0].converged || !master_on_slave[1].converged ||
        !slave_on_master[0].converged || !slave_on_master[1].converged)
      ++detail::gap_rejections[2];
    return;
  }

  using Rule = geometry::LineRule5;
  const S segment_jacobian = (xb - xa) * 0.5;
  const V2<S> half_t = (x1 - x0) * 0.5;
  const S surface_jacobian = length(half_t);
  const V2<S> centre = (m0 + m1) * 0.5, half_m = (m1 - m0) * 0.5;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double gp = Rule::points[static_cast<std::size_t>(q)];
    const S xi = 0.5 * ((1.0 - gp) * xa + (1.0 + gp) * xb);
    const S N0 = 0.5 * (1.0 - xi), N1 = 0.5 * (1.0 + xi);
    const V2<S> xs = x0 * N0 + x1 * N1;
    const V2<S> nt = nn[0] * N0 + nn[1] * N1;
    const S nl = length(nt);
    const V2<S> n = {nt.x / nl, nt.y / nl};
    // The image on the straight master: (m_c + eta h - x_s) x n = 0.
    const S slope = cross(half_m, n);
    if (!(std::abs(value_of(slope)) > 1e-14 * tm.norm())) continue;
    const S eta = cross(xs - centre, n) / slope;
    const V2<S> xm = m0 * (0.5 * (1.0 - eta)) + m1 * (0.5 * (1.0 + eta));
    const S w = Rule::weights[static_cast<std::size_t>(q)] * surface_jacobian * segment_jacobian;
    const S wg = w * dot(n, xm - xs);
    if (in.dual) {
      // Dual basis of a line2 facet: Phi = A N with A = D_e M_e^-1 = [[2, -1], [-1, 2]].
      g[0] += wg * (2.0 * N0 - N1);
      g[1] += wg * (2.0 * N1 - N0);
    } else {
      g[0] += wg * N0;
      g[1] += wg * N1;
    }
  }
}

/// line3 (nodes at xi = -1, 1, 0): N = (xi (xi - 1) / 2, xi (xi + 1) / 2, 1 - xi^2).
template <class S, class T> V2<S> line3_at(const std::array<V2<S>, 3>& p, const T& xi) {
  return p[0] * (0.5 * xi * (xi - 1.0)) + p[1] * (0.5 * xi * (xi + 1.0)) + p[2] * (1.0 - xi * xi);
}
template <class S, class T> V2<S> line3_tangent(const std::array<V2<S>, 3>& p, const T& xi) {
  return p[0] * (xi - 0.5) + p[1] * (xi + 0.5) + p[2] * (-2.0 * xi);
}

using PairInput3 = PairInputT<3>;

/// The weighted gaps of the three slave nodes of a line3 pair, as pair_gaps does for line2 and
/// integrate_pair (segmentation_2d.cpp) for line3: averaged unit nodal normals (the facets'
/// normals at the node), the centre-normal pre-check, the end-node projections decided on
/// values and polished on S, five Gauss points on the segment, the image on the curved master
/// polished on S by Newton steps from its converged value, and the dual basis of the curved
/// facet, A = D_e M_e^-1, on S.
template <class S>
void pair_gaps_line3(const PairInput3& in, const mortar::PairOptions& options,
                     std::array<S, 3>& g) {
  using std::sqrt;
  g = {S(0.0), S(0.0), S(0.0)};
  std::array<V2<S>, 10> X;
  for (int i = 0; i < 10; ++i)
    X[static_cast<std::size_t>(i)] = {
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].x(), 2 * i),
        independent_variable<S>(in.x[static_cast<std::size_t>(i)].y(), 2 * i + 1)};
  constexpr std::array<double, 3> node_xi = {-1.0, 1.0, 0.0};
  std::array<V2<S>, 3> nn;
  for (std::size_t k = 0; k < 3; ++k) {
    V2<S> sum;
    for (int f = 0; f < in.n_adjacent[k]; ++f) {
      const auto& slots = in.adjacent[k][static_cast<std::size_t>(f)];
      const std::array<V2<S>, 3> p = {X[static_cast<std::size_t>(slots[0])],
                                      X[static_cast<std::size_t>(slots[1])],
                                      X[static_cast<std::size_t>(slots[2])]};
      const V2<S> t = line3_tangent(
          p, node_xi[static_cast<std::size_t>(in.local[k][static_cast<std::size_t>(f)])]);
      const S l = length(t);
      sum = sum + V2<S>{t.y / l, -t.x / l};
    }
    const S l = length(sum);
    nn[k] = {sum.x / l, sum.y / l};
  }
  const std::array<V2<S>, 3> xs3 = {X[0], X[1], X[2]}, xm3 = {X[7], X[8], X[9]};
  std::array<Eigen::Vector2d, 3> xv, mv, nv;
  std::array<V2<double>, 3> xd, md, nd;
  for (std::size_t k = 0; k < 3; ++k) {
    xv[k] = value(xs3[k]);
    mv[k] = value(xm3[k]);
    nv[k] = value(nn[k]);
    xd[k] = {xv[k].x(), xv[k].y()};
    md[k] = {mv[k].x(), mv[k].y()};
    nd[k] = {nv[k].x(), nv[k].y()};
  }
  const auto curve = [](const std::array<V2<double>, 3>& p) {
    return [p](double xi) {
      const V2<double> x = line3_at(p, xi), t = line3_tangent(p, xi);
      return geometry::CurvePoint{Eigen::Vector2d(x.x, x.y), Eigen::Vector2d(t.x, t.y)};
    };
  };
  const auto slave_curve = curve(xd), normal_field = curve(nd), master_curve = curve(md);
  const Eigen::Vector2d ts = slave_curve(0.0).dx, tm = master_curve(0.0).dx;
  const Eigen::Vector2d ns = Eigen::Vector2d(ts.y(), -ts.x()).normalized();
  const Eigen::Vector2d nm = Eigen::Vector2d(tm.y(), -tm.x()).normalized();
  if (!(ns.dot(nm) < options.max_normal_alignment_2d)) return;
  std::array<geometry::CurveProjection, 2> master_on_slave, slave_on_master;
  for (std::size_t k = 0; k < 2; ++k) {
    master_on_slave[k] = geometry::project_onto_curve_along_field(slave_curve, normal_field, mv[k],
                                                                  0.0, options.newton);
    slave_on_master[k] =
        geometry::project_onto_curve(master_curve, xv[k], nv[k], 0.0, options.newton);
  }
  // Master end node k on the slave along n~(xi) = sum_i N_i n_i: the root of
  // F(xi) = (x_s(xi) - m_k) x n~(xi), polished on S.
  const auto on_slave = [&](std::size_t k) {
    S xi = master_on_slave[k].xi;
    for (int it = 0; it < 3; ++it) {
      const V2<S> r = line3_at(xs3, xi) - xm3[k];
      const V2<S> d = line3_at(nn, xi);
      xi = xi - cross(r, d) / (cross(line3_tangent(xs3, xi), d) + cross(r, line3_tangent(nn, xi)));
    }
    return xi;
  };
  const auto forward = [&](std::size_t k) {
    const Eigen::Vector2d towards_other = mv[1 - k] - mv[k];
    return towards_other.dot(slave_curve(std::clamp(master_on_slave[k].xi, -1.0, 1.0)).dx) > 0.0;
  };
  S xa, xb;
  if (!overlap_ends(master_on_slave, slave_on_master, options.projection_range_tolerance, on_slave,
                    forward, xa, xb))
    return;

  using Rule = geometry::LineRule5;
  const auto shape = [](const S& xi) {
    return std::array<S, 3>{0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi};
  };
  // The dual coefficients A = D_e M_e^-1 of the curved facet (dual_basis.cpp, exact rule).
  std::array<std::array<S, 3>, 3> A{};
  if (in.dual) {
    std::array<std::array<S, 3>, 3> Me{};
    std::array<S, 3> De{};
    for (int q = 0; q < Rule::n_points; ++q) {
      const double xi = Rule::points[static_cast<std::size_t>(q)];
      const S J = length(line3_tangent(xs3, xi)) * Rule::weights[static_cast<std::size_t>(q)];
      const std::array<double, 3> N = {0.5 * xi * (xi - 1.0), 0.5 * xi * (xi + 1.0), 1.0 - xi * xi};
      for (std::size_t i = 0; i < 3; ++i) {
        De[i] += J * N[i];
        for (std::size_t j = 0; j < 3; ++j) Me[i][j] += J * (N[i] * N[j]);
      }
    }
    // M_e^-1 by cofactors (symmetric).
    const auto& m = Me;
    std::array<std::array<S, 3>, 3> C;
    C[0][0] = m[1][1] * m[2][2] - m[1][2] * m[2][1];
    C[0][1] = m[0][2] * m[2][1] - m[0][1] * m[2][2];
    C[0][2] = m[0][1] * m[1][2] - m[0][2] * m[1][1];
    C[1][0] = m[1][2] * m[2][0] - m[1][0] * m[2][2];
    C[1][1] = m[0][0] * m[2][2] - m[0][2] * m[2][0];
    C[1][2] = m[0][2] * m[1][0] - m[0][0] * m[1][2];
    C[2][0] = m[1][0] * m[2][1] - m[1][1] * m[2][0];
    C[2][1] = m[0][1] * m[2][0] - m[0][0] * m[2][1];
    C[2][2] = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    const S det = m[0][0] * C[0][0] + m[0][1] * C[1][0] + m[0][2] * C[2][0];
    for (std::size_t i = 0; i < 3; ++i)
      for (std::size_t j = 0; j < 3; ++j) A[i][j] = De[i] * C[i][j] / det;
  }
  const S segment_jacobian = (xb - xa) * 0.5;
  double eta_guess = 0.0;
  for (int q = 0; q < Rule::n_points; ++q) {
    const double gp = Rule::points[static_cast<std::size_t>(q)];
    const S xi = 0.5 * ((1.0 - gp) * xa + (1.0 + gp) * xb);
    const std::array<S, 3> N = shape(xi);
    const V2<S> xs = line3_at(xs3, xi);
    const V2<S> nt = line3_at(nn, xi);
    const S nl = length(nt);
    const V2<S> n = {nt.x / nl, nt.y / nl};
    // The image on the curved master: (x_m(eta) - x_s) x n = 0, from its value by Newton on S.
    const geometry::CurveProjection image =
        geometry::project_onto_curve(master_curve, value(xs), value(n), eta_guess, options.newton);
    if (!image.converged) continue;
    eta_guess = image.xi;
    S eta = image.xi;
    for (int it = 0; it < 3; ++it)
      eta = eta - cross(line3_at(xm3, eta) - xs, n) / cross(line3_tangent(xm3, eta), n);
    const V2<S> xm = line3_at(xm3, eta);
    const S w = Rule::weights[static_cast<std::size_t>(q)] * length(line3_tangent(xs3, xi)) *
                segment_jacobian;
    const S wg = w * dot(n, xm - xs);
    for (std::size_t j = 0; j < 3; ++j) {
      S phi = in.dual ? A[j][0] * N[0] + A[j][1] * N[1] + A[j][2] * N[2] : N[j];
      g[j] += wg * phi;
    }
  }
}

} // namespace

bool ContactInterface::has_gap_blocks() const {
  // 2D: line2 or line3 faces, one kind on both sides (the kind of any facet this rank holds: a
  // side held in part may have none here).
  fem::CellType line = fem::CellType::line2;
  if (!slave_.types.empty())
    line = slave_.types.front();
  else if (!rigid_ && !master_.types.empty())
    line = master_.types.front();
  // 3D: linear and quadratic faces, mixed too (gap_blocks_3d.cpp; against a rigid obstacle
  // the slave side's whole-facet kernel, rigid_obstacle_facet.cpp).
  const auto supported = [this, line](fem::CellType t) {
    return dim() == 2 ? t == line && (t == fem::CellType::line2 || t == fem::CellType::line3)
                      : mortar::is_interface_facet(t, 3);
  };
  for (const auto t : slave_.types)
    if (!supported(t)) return false;
  if (rigid_) return true;
  for (const auto t : master_.types)
    if (!supported(t)) return false;
  return true;
}

void ContactInterface::gap_blocks(std::span<const double> u, GapOrder order,
                                  std::vector<GapBlock>& out,
                                  std::span<const char> hessian_rows) const {
  SEAM_ASSERT(has_gap_blocks());
  out.clear();
  // The order of a block with slave nodes `nodes`: gradients instead of Hessians where no
  // node asks for them.
  const auto order_of = [&](const auto& nodes) {
    if (order != GapOrder::hessian || hessian_rows.empty()) return order;
    for (const auto k : nodes)
      if (hessian_rows[static_cast<std::size_t>(k)]) return order;
    return GapOrder::gradient;
  };
  if (rigid_) {
    // One block per owned candidate slave facet: its nodes' weighted gaps as functions of its
    // nodal positions (the obstacle where the last update put it).
    const int dim = this->dim();
    mortar::FacetSet facets = slave_.facet_set();
    std::vector<double> x(slave_.mesh_nodes.size() * static_cast<std::size_t>(dim));
    for (std::size_t k = 0; k < slave_.mesh_nodes.size(); ++k)
      for (int a = 0; a < dim; ++a) {
        const auto i = static_cast<std::size_t>(slave_.mesh_nodes[k]) * dim + a;
        x[k * dim + a] = reference_x()[i] + u[i];
      }
    facets.coordinates = x;
    RigidObstacleFacet rf;
    for (const auto f : owned_) {
      if (n_pairs_of(f) == 0) continue;
      const auto nodes = facets.facet_nodes(f);
      GapBlock b;
      b.dim = dim;
      for (const auto k : nodes) {
        b.slave.push_back(k);
        b.dofs.push_back(static_cast<std::int64_t>(slave_.mesh_nodes[static_cast<std::size_t>(k)]) *
                         dim);
      }
      const GapOrder block_order = order_of(nodes);
      if (block_order == GapOrder::hessian) {
        if (dim == 2)
          rigid_obstacle_gap_hessians<2>(mortar::gather_facet<2>(facets, f), current_,
                                         options_.multiplier, b.gap, b.gradient, b.hessian);
        else
          rigid_obstacle_gap_hessians<3>(mortar::gather_facet<3>(facets, f), current_,
                                         options_.multiplier, b.gap, b.gradient, b.hessian);
      } else {
        const bool derivatives = block_order == GapOrder::gradient;
        if (dim == 2)
          rigid_obstacle_facet<2>(mortar::gather_facet<2>(facets, f), current_, options_.multiplier,
                                  derivatives, rf);
        else
          rigid_obstacle_facet<3>(mortar::gather_facet<3>(facets, f), current_, options_.multiplier,
                                  derivatives, rf);
        b.gap.assign(rf.gap.begin(), rf.gap.begin() + rf.n);
        if (derivatives) b.gradient = rf.dgap;
      }
      out.push_back(std::move(b));
    }
    return;
  }
  if (dim() == 3) {
    gap_blocks_3d(u, order, out, hessian_rows);
    return;
  }
  const auto& X = reference_x();
  const auto position = [&](std::int32_t node) {
    const auto i = static_cast<std::size_t>(node) * 2;
    return Eigen::Vector2d(X[i] + u[i], X[i + 1] + u[i + 1]);
  };
  const mortar::FacetSet slaves = slave_set();
  const mortar::FacetSet masters = integration_master().facet_set();
  const mortar::NodeFacets& adjacency = slave_adjacency();
  // The pair's slots (PairInputT) and their mesh dofs.
  const auto gather = [&]<int P>(auto sn, auto mn, PairInputT<P>& in, GapBlock& b) {
    constexpr int n_slave = PairInputT<P>::slave_slots;
    b.dofs.assign(static_cast<std::size_t>(n_slave + P), -1);
    std::array<local_index, n_slave> slots{};
    int n_slots = 0;
    const auto slot_of = [&](local_index node) {
      for (int t = 0; t < n_slots; ++t)
        if (slots[static_cast<std::size_t>(t)] == node) return t;
      SEAM_ASSERT(n_slots < n_slave);
      slots[static_cast<std::size_t>(n_slots)] = node;
      return n_slots++;
    };
    for (int k = 0; k < P; ++k) slot_of(sn[static_cast<std::size_t>(k)]);
    in.dual = options_.multiplier == mortar::Multiplier::dual;
    for (std::size_t k = 0; k < P; ++k) {
      const auto facets = adjacency.of(sn[k]);
      SEAM_CHECK(facets.size() <= 2, InputError, "interface '", name_, "': slave node ",
                 slave_.mesh_nodes[static_cast<std::size_t>(sn[k])],
                 " lies on more than two facets");
      in.n_adjacent[k] = static_cast<int>(facets.size());
      for (std::size_t e = 0; e < facets.size(); ++e) {
        const auto nodes = slaves.facet_nodes(facets[e]);
        SEAM_ASSERT(nodes.size() == P);
        for (std::size_t c = 0; c < P; ++c) {
          in.adjacent[k][e][c] = slot_of(nodes[c]);
          if (nodes[c] == sn[k]) in.local[k][e] = static_cast<int>(c);
        }
      }
    }
    for (int t = 0; t < n_slots; ++t) {
      const auto node =
          slave_.mesh_nodes[static_cast<std::size_t>(slots[static_cast<std::size_t>(t)])];
      b.dofs[static_cast<std::size_t>(t)] = static_cast<std::int64_t>(node) * 2;
      in.x[static_cast<std::size_t>(t)] = position(node);
    }
    for (std::size_t l = 0; l < P; ++l) {
      const auto node = integration_node(mn[l]);
      b.dofs[n_slave + l] = static_cast<std::int64_t>(node) * 2;
      in.x[n_slave + l] = position(node);
    }
    // The frame of the slave facet's first node (as integrate_pair).
    const Eigen::Vector2d origin = in.x[0];
    for (auto& x : in.x) x -= origin;
    b.slave.assign(sn.begin(), sn.begin() + P);
  };
  for (const auto f : owned_)
    for (const auto& pair : pairs_of(f)) {
      const local_index sf = slave_index(pair.slave), mf = integration_facet(pair.master);
      const auto sn = slaves.facet_nodes(sf);
      const auto mn = masters.facet_nodes(mf);
      const mortar::PairOptions pair_options = options_.pair_options(sf, mf);
      GapBlock b;
      if (sn.size() == 3) {
        PairInput3 in;
        gather.template operator()<3>(sn, mn, in, b);
        block_gaps<20, 3>(order_of(b.slave), b,
                          [&in, &pair_options](auto& g) { pair_gaps_line3(in, pair_options, g); });
      } else {
        PairInput in;
        gather.template operator()<2>(sn, mn, in, b);
        const long r0 = detail::gap_rejections[0], r1 = detail::gap_rejections[1];
        block_gaps<12, 2>(order_of(b.slave), b,
                          [&in, &pair_options](auto& g) { pair_gaps(in, pair_options, g); });
        if (detail::gap_pair_log) {
          GapPairRecord r;
          for (int k = 0; k < 2; ++k) {
            r.slave_nodes[k] = b.dofs[static_cast<std::size_t>(k)] / 2;
            r.master_nodes[k] = b.dofs[static_cast<std::size_t>(PairInput::slave_slots + k)] / 2;
            r.gap[k] = b.gap[static_cast<std::size_t>(k)];
          }
          r.status = detail::gap_rejections[0] != r0 ? 1 : detail::gap_rejections[1] != r1 ? 2 : 0;
          r.kept = !options_.prechecked.empty() &&
                   pair_options.max_normal_alignment_2d != options_.pair.max_normal_alignment_2d;
          const Eigen::Vector2d ts = (in.x[1] - in.x[0]).normalized();
          const Eigen::Vector2d tm =
              (in.x[PairInput::slave_slots + 1] - in.x[PairInput::slave_slots]).normalized();
          r.alignment = ts.dot(tm);
          detail::gap_pair_log->push_back(r);
        }
      }
      if (empty_block(b)) continue;
      out.push_back(std::move(b));
    }
}

} // namespace seam::contact
