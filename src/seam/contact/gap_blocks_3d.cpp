// The weighted gaps of 3D contact on tri3 and quad4 facets (and, further below, on quadratic
// facets: tri6, quad8, quad9) as functions of the nodal positions, with exact first and second
// derivatives (energy-momentum contact, docs/contact_dynamics.md §5).
//
// The kernel follows integrate_pair of mortar/integration_3d.cpp step by step on a scalar type
// S (double, Dual<36> or Hyper<36>): the auxiliary plane of the slave facet (vertex mean,
// normal from the edge or diagonal cross product), the projection of both facets into it, the
// clip (Sutherland & Hodgman, mortar/linearization_clip.hpp on polygons kept on the heap: a
// Hyper<36> takes 10 kB), the fan triangulation about the area centroid, the cell rule and,
// per point, the back-projection onto both facets, the interpolated nodal normal n and the gap
// (h_m - h_s) n . n_p / |n| from the heights above the plane. Every decision (facing test,
// boxes, clip classification, fan) is taken on values, which freezes the combinatorics at the
// evaluation point. The back-projection's reference coordinates come from the closed-form
// inverse in doubles and are polished by chord Newton steps on S (the Jacobian of the values:
// from the exact value each step makes one more order of derivatives exact; one for Dual, two
// for Hyper). The dual coefficients A = D_e M_e^-1 of the slave facet are recomputed on S from
// its current Jacobian, as dual_basis.cpp does.
//
// The pair kernel's independents are the slave positions, the slave nodal normals and the
// master positions (36 with quad4 on both sides). The averaged unit nodal normal of a slave
// node is a function of the nodes of the facets around it (up to 16 nodes, SymHyper<48>); the
// chain rule H_X = J^T H_y J + sum_i (dg/dy_i) H_X(y_i) takes both to the positions of the
// pair's slots in doubles.
#include "seam/contact/contact_interface.hpp"

#include "seam/common/dual_number.hpp"
#include "seam/common/error.hpp"
#include "seam/common/hyper_dual.hpp"
#include "seam/common/sym_hyper.hpp"
#include "seam/contact/gap_vectors.hpp"
#include "seam/contact/quadratic_pair_kernel.hpp"
#include "seam/geometry/cell_quadrature.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/mortar/dual_basis.hpp"
#include "seam/mortar/facet.hpp"
#include "seam/mortar/linearization_clip.hpp"
#include "seam/mortar/normals.hpp"
#include "seam/mortar/pair_integration_detail.hpp"

#include <algorithm>
#include <cmath>
#include <map>
#include <type_traits>
#include <vector>

namespace seam::contact {

detail::GapHessianTerms detail::gap_hessian_terms = detail::GapHessianTerms::all;

namespace {

constexpr int pair_variables = 36; ///< slave x (12), slave normals (12), master x (12)
constexpr int normal_offset = 12;  ///< first variable of the slave normals
constexpr int master_offset = 24;  ///< first variable of the master positions
constexpr int max_ring_nodes = 16; ///< nodes of the facets around one slave node
constexpr int ring_variables = 3 * max_ring_nodes;

using namespace gap_vectors;

template <class S> constexpr bool is_hyper = false;
template <int N> constexpr bool is_hyper<Hyper<N>> = true;
template <class S> constexpr bool is_sym_hyper = false;
template <int N> constexpr bool is_sym_hyper<SymHyper<N>> = true;

template <class S> S component(const V3<S>& a, int c) {
  return c == 0 ? a.x : c == 1 ? a.y : a.z;
}
template <class S> V3<S> seeded(const Eigen::Vector3d& x, int first) {
  return {independent_variable<S>(x.x(), first), independent_variable<S>(x.y(), first + 1),
          independent_variable<S>(x.z(), first + 2)};
}

/// Shape values and reference gradients of tri3 / quad4 (Gmsh order) at xi of type T.
template <class T>
void shape(int n, const T& s, const T& t, std::array<T, 4>& N, std::array<T, 8>& dN) {
  if (n == 3) {
    N = {1.0 - s - t, s, t, T(0.0)};
    dN = {T(-1.0), T(-1.0), T(1.0), T(0.0), T(0.0), T(1.0), T(0.0), T(0.0)};
    return;
  }
  const T sm = 1.0 - s, sp = 1.0 + s, tm = 1.0 - t, tp = 1.0 + t;
  N = {0.25 * sm * tm, 0.25 * sp * tm, 0.25 * sp * tp, 0.25 * sm * tp};
  dN = {-0.25 * tm, -0.25 * sm, 0.25 * tm, -0.25 * sp, 0.25 * tp, 0.25 * sp, -0.25 * tp, 0.25 * sm};
}

/// The shape values of shape() alone (the kernel's points need no gradients on S; each
/// Hyper<36> temporary is 10 kB).
template <class T> void shape_values(int n, const T& s, const T& t, std::array<T, 4>& N) {
  if (n == 3) {
    N = {1.0 - s - t, s, t, T(0.0)};
    return;
  }
  const T sm = 1.0 - s, sp = 1.0 + s, tm = 1.0 - t, tp = 1.0 + t;
  N = {0.25 * sm * tm, 0.25 * sp * tm, 0.25 * sp * tp, 0.25 * sm * tp};
}

fem::CellType linear_type(int n) {
  return n == 3 ? fem::CellType::tri3 : fem::CellType::quad4;
}

/// The unit normal x_xi x x_eta / |.| of a facet of type `type` (positions x) at its node i,
/// as mortar::averaged_nodal_normals evaluates it.
template <class S> V3<S> facet_unit_normal(const std::vector<V3<S>>& x, fem::CellType type, int i) {
  const double* reference = fem::reference_nodes(type).data();
  mortar::NodalVector N;
  std::array<double, 2 * mortar::max_facet_nodes> dN;
  mortar::detail::shape_functions<true>(
      type, Eigen::Vector2d(reference[2 * i], reference[2 * i + 1]), N, dN);
  V3<S> a, b;
  for (std::size_t k = 0; k < x.size(); ++k) {
    a = a + x[k] * dN[2 * k];
    b = b + x[k] * dN[2 * k + 1];
  }
  const V3<S> c = cross(a, b);
  return c * (1.0 / norm(c));
}

/// The averaged unit normal of one slave node with its first (and second) derivatives with
/// respect to the positions of the ring: the nodes of the facets around it.
struct NormalJet {
  GapOrder order = GapOrder::value; ///< the derivatives it holds
  std::vector<std::int32_t> ring;   ///< mesh nodes
  std::array<double, 3> value{};
  std::vector<double> gradient; ///< 3 x (3 ring)
  std::vector<double> hessian;  ///< 3 x (3 ring)^2
};

/// One pair in the frame of the slave facet's first node.
struct PairInput {
  int ns = 0, nm = 0;
  fem::CellType slave_type = fem::CellType::tri3, master_type = fem::CellType::tri3;
  std::array<Eigen::Vector3d, mortar::max_facet_nodes> xs, xm, normal;
  bool dual = true;
};

/// The polygons of the clip (mortar/linearization_clip.hpp) on the heap.
template <class S> using Polygon = std::vector<V2<S>>;

/// The triangle rule of integration_3d.cpp: barycentric points, weights summing to 1.
struct CellRule {
  std::vector<std::array<double, 4>> points;
  explicit CellRule(int degree) {
    if (degree <= 5) {
      using Rule = geometry::TriangleRule7;
      for (int q = 0; q < Rule::n_points; ++q) {
        const auto& b = Rule::barycentric[static_cast<std::size_t>(q)];
        points.push_back({b[0], b[1], b[2], Rule::weights[static_cast<std::size_t>(q)]});
      }
      return;
    }
    const fem::QuadratureRule rule = fem::quadrature(fem::CellType::tri3, degree);
    for (int q = 0; q < rule.n_points; ++q) {
      const double xi = rule.points[static_cast<std::size_t>(2 * q)];
      const double eta = rule.points[static_cast<std::size_t>(2 * q + 1)];
      points.push_back({1.0 - xi - eta, xi, eta, 2.0 * rule.weights[static_cast<std::size_t>(q)]});
    }
  }
};

/// The cells of a clip polygon, its fan about the area centroid (a triangle stays one cell),
/// and the rule's points in them: f(u, area, weight) with the point u, its cell's area and its
/// weight in the rule.
/// a b_0 + b b_1 + c b_2 on packed Hessians in one pass (defined with the packed path below).
template <int N>
V2<SymHyper<N>> barycentric_packed(const V2<SymHyper<N>>& a, const V2<SymHyper<N>>& b,
                                   const V2<SymHyper<N>>& c, const std::array<double, 4>& point);

template <class S, class F>
void for_each_point(const Polygon<S>& polygon, const CellRule& rule, F&& f) {
  const std::size_t nv = polygon.size();
  const V2<S> c = nv == 3 ? polygon[0] : mortar::ad::centroid_of(polygon);
  for (std::size_t i = 0; i < (nv == 3 ? 1 : nv); ++i) {
    const V2<S> a = nv == 3 ? polygon[0] : c, b = nv == 3 ? polygon[1] : polygon[i],
                cc = nv == 3 ? polygon[2] : polygon[(i + 1) % nv];
    const S area = 0.5 * cross(b - a, cc - a);
    for (const auto& point : rule.points)
      if constexpr (is_sym_hyper<S>)
        f(barycentric_packed(a, b, cc, point), area, point[3]);
      else
        f(V2<S>(a * point[0] + b * point[1] + cc * point[2]), area, point[3]);
  }
}

/// The gap of one point times its weight, w (h_m - h_s) n . n_p / |n| with the interpolated
/// nodal normal n = N_k n_k and the heights h above the plane (slave shape values Ns over ns
/// nodes, master Nm over nm).
template <class S, class Normals, class Heights, class Shapes>
S weighted_point_gap(std::size_t ns, const Normals& nn, const Heights& hs, const Shapes& Ns,
                     std::size_t nm, const Heights& hm, const Shapes& Nm, const V3<S>& np,
                     const S& area, double weight) {
  V3<S> n;
  S h_s = 0.0, h_m = 0.0;
  for (std::size_t k = 0; k < ns; ++k) {
    add_product(n.x, nn[k].x, Ns[k]);
    add_product(n.y, nn[k].y, Ns[k]);
    add_product(n.z, nn[k].z, Ns[k]);
    add_product(h_s, hs[k], Ns[k]);
  }
  for (std::size_t l = 0; l < nm; ++l) add_product(h_m, hm[l], Nm[l]);
  return weight * area * (h_m - h_s) * dot(n, np) / norm(n);
}

/// Reference coordinates (s, t) of the plane point p on the facet with plane images u: the
/// closed-form inverse in doubles, then Newton steps on S with the Jacobian of the values (a
/// chord step: from the exact value, each step makes one more order of derivatives exact, so
/// one step serves the gradient, two the Hessian).
template <class S>
bool locate(int n, const std::array<V2<S>, 4>& u, const mortar::detail::PieceInverse& inverse,
            const V2<S>& p, S& s, S& t) {
  Eigen::Vector2d xi;
  if (!inverse.parent_coordinates(value(p), xi)) return false;
  s = xi.x();
  t = xi.y();
  if constexpr (!std::is_same_v<S, double>) {
    std::array<double, 4> N0;
    std::array<double, 8> dN;
    shape<double>(n, xi.x(), xi.y(), N0, dN);
    Eigen::Vector2d j0 = Eigen::Vector2d::Zero(), j1 = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
      j0 += value(u[k]) * dN[2 * k];
      j1 += value(u[k]) * dN[2 * k + 1];
    }
    const double det = j0.x() * j1.y() - j0.y() * j1.x();
    const int steps = is_dual<S> ? 1 : 2;
    std::array<S, 4> N;
    for (int it = 0; it < steps; ++it) {
      shape_values<S>(n, s, t, N);
      S rx = -p.x, ry = -p.y;
      for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) {
        add_product(rx, u[k].x, N[k]);
        add_product(ry, u[k].y, N[k]);
      }
      // [s, t] -= J^-1 r with J = [j0 j1].
      s = s - (rx * j1.y() - ry * j1.x()) * (1.0 / det);
      t = t - (ry * j0.x() - rx * j0.y()) * (1.0 / det);
    }
  }
  return true;
}

/// The dual coefficients A = D_e M_e^-1 of the slave facet (dual_basis.cpp) on S.
template <class S>
void dual_coefficients(int n, const std::array<V3<S>, 4>& x, std::array<std::array<S, 4>, 4>& A) {
  const fem::QuadratureRule rule = fem::quadrature(linear_type(n), 4);
  std::array<std::array<S, 4>, 4> M;
  std::array<S, 4> D;
  for (int j = 0; j < 4; ++j) {
    D[static_cast<std::size_t>(j)] = 0.0;
    for (int k = 0; k < 4; ++k) M[static_cast<std::size_t>(j)][static_cast<std::size_t>(k)] = 0.0;
  }
  for (int q = 0; q < rule.n_points; ++q) {
    std::array<double, 4> N;
    std::array<double, 8> dN;
    shape<double>(n, rule.points[static_cast<std::size_t>(2 * q)],
                  rule.points[static_cast<std::size_t>(2 * q + 1)], N, dN);
    V3<S> a, b;
    for (int k = 0; k < n; ++k) {
      a = a + x[static_cast<std::size_t>(k)] * dN[static_cast<std::size_t>(2 * k)];
      b = b + x[static_cast<std::size_t>(k)] * dN[static_cast<std::size_t>(2 * k + 1)];
    }
    const S jw = norm(cross(a, b)) * rule.weights[static_cast<std::size_t>(q)];
    for (std::size_t j = 0; j < static_cast<std::size_t>(n); ++j) {
      D[j] += jw * N[j];
      for (std::size_t k = 0; k < static_cast<std::size_t>(n); ++k) M[j][k] += jw * (N[j] * N[k]);
    }
  }
  // M^-1 by Gauss-Jordan (M is symmetric positive definite: no pivoting), then A = D M^-1.
  std::array<std::array<S, 4>, 4> inv;
  for (std::size_t j = 0; j < 4; ++j)
    for (std::size_t k = 0; k < 4; ++k) inv[j][k] = j == k ? 1.0 : 0.0;
  const auto m = static_cast<std::size_t>(n);
  for (std::size_t p = 0; p < m; ++p) {
    const S pivot = 1.0 / M[p][p];
    for (std::size_t k = 0; k < m; ++k) {
      M[p][k] = M[p][k] * pivot;
      inv[p][k] = inv[p][k] * pivot;
    }
    for (std::size_t r = 0; r < m; ++r) {
      if (r == p) continue;
      const S f = M[r][p];
      for (std::size_t k = 0; k < m; ++k) {
        M[r][k] -= f * M[p][k];
        inv[r][k] -= f * inv[p][k];
      }
    }
  }
  for (std::size_t j = 0; j < m; ++j)
    for (std::size_t k = 0; k < m; ++k) A[j][k] = D[j] * inv[j][k];
}

double longest_edge_squared(const std::array<Eigen::Vector3d, mortar::max_facet_nodes>& x, int n) {
  double longest = (x[0] - x[static_cast<std::size_t>(n - 1)]).squaredNorm();
  for (int i = 0; i + 1 < n; ++i)
    longest = std::max(
        longest,
        (x[static_cast<std::size_t>(i + 1)] - x[static_cast<std::size_t>(i)]).squaredNorm());
  return longest;
}

/// The auxiliary plane of a linear piece with vertices x[v[0..nv)] (geometry::make_plane
/// through the vertex mean; the normal from the triangle's edges or the quadrilateral's
/// diagonals) on S, and the projection into it: in-plane coordinates and height.
template <class S> struct AuxPlane {
  V3<S> center, np, t1, t2;

  template <class X> bool set(const X& x, const std::array<int, 4>& v, int nv) {
    const auto at = [&](int k) -> const V3<S>& {
      return x[static_cast<std::size_t>(v[static_cast<std::size_t>(k)])];
    };
    center = V3<S>();
    for (int k = 0; k < nv; ++k) center = center + at(k);
    center = center * (1.0 / nv);
    const V3<S> raw =
        nv == 3 ? cross(at(1) - at(0), at(2) - at(0)) : cross(at(2) - at(0), at(3) - at(1));
    const S raw_length = norm(raw);
    if (!(value_of(raw_length) > 0.0)) return false;
    np = raw * (1.0 / raw_length);
    const Eigen::Vector3d npv = value(np);
    int axis = 0;
    npv.cwiseAbs().minCoeff(&axis);
    V3<S> e = np * (-component(np, axis));
    (axis == 0 ? e.x : axis == 1 ? e.y : e.z) += 1.0;
    t1 = e * (1.0 / norm(e));
    t2 = cross(np, t1);
    return true;
  }
  void into(const V3<S>& x, V2<S>& u, S& h) const {
    const V3<S> r = x - center;
    u = {dot(r, t1), dot(r, t2)};
    h = dot(r, np);
  }
};

template <class S>
void pair_gaps(const PairInput& in, const mortar::PairOptions& options, std::array<S, 4>& g) {
  g = {S(0.0), S(0.0), S(0.0), S(0.0)};
  const int ns = in.ns, nm = in.nm;
  // Centre distance against the reach (integrate_pair's pre-check), on values.
  const double factor = options.max_center_distance_factor;
  const double reach_squared =
      factor * factor * std::max(longest_edge_squared(in.xs, ns), longest_edge_squared(in.xm, nm));
  Eigen::Vector3d cs = Eigen::Vector3d::Zero(), cm = Eigen::Vector3d::Zero();
  for (int k = 0; k < ns; ++k) cs += in.xs[static_cast<std::size_t>(k)] / ns;
  for (int l = 0; l < nm; ++l) cm += in.xm[static_cast<std::size_t>(l)] / nm;
  if ((cs - cm).squaredNorm() > reach_squared) return;

  std::array<V3<S>, 4> xs, nn, xm;
  for (int k = 0; k < ns; ++k) {
    const auto i = static_cast<std::size_t>(k);
    xs[i] = seeded<S>(in.xs[i], 3 * k);
    nn[i] = seeded<S>(in.normal[i], normal_offset + 3 * k);
  }
  for (int l = 0; l < nm; ++l)
    xm[static_cast<std::size_t>(l)] =
        seeded<S>(in.xm[static_cast<std::size_t>(l)], master_offset + 3 * l);

  // The auxiliary plane of the facet.
  AuxPlane<S> plane;
  if (!plane.set(xs, {0, 1, 2, 3}, ns)) return;
  const V3<S>& np = plane.np;
  const Eigen::Vector3d npv = value(np);
  std::array<V2<S>, 4> us, um;
  std::array<S, 4> hs, hm;
  for (std::size_t k = 0; k < static_cast<std::size_t>(ns); ++k) plane.into(xs[k], us[k], hs[k]);
  for (std::size_t l = 0; l < static_cast<std::size_t>(nm); ++l) plane.into(xm[l], um[l], hm[l]);
  // Boxes in the plane and the facing test, on values.
  Eigen::Vector2d slo = value(us[0]), shi = slo, mlo = value(um[0]), mhi = mlo;
  for (int k = 1; k < ns; ++k) {
    slo = slo.cwiseMin(value(us[static_cast<std::size_t>(k)]));
    shi = shi.cwiseMax(value(us[static_cast<std::size_t>(k)]));
  }
  for (int l = 1; l < nm; ++l) {
    mlo = mlo.cwiseMin(value(um[static_cast<std::size_t>(l)]));
    mhi = mhi.cwiseMax(value(um[static_cast<std::size_t>(l)]));
  }
  if ((mlo.array() > shi.array()).any() || (slo.array() > mhi.array()).any()) return;
  {
    const auto& m = in.xm;
    const Eigen::Vector3d n = nm == 3 ? Eigen::Vector3d((m[1] - m[0]).cross(m[2] - m[0]))
                                      : Eigen::Vector3d((m[2] - m[0]).cross(m[3] - m[1]));
    const double length = n.norm();
    if (!(length > 0.0) || !((n / length).dot(npv) < -1e-12)) return;
  }
  Polygon<S> subject(us.begin(), us.begin() + ns), clipper(um.begin(), um.begin() + nm);
  const Polygon<S> polygon =
      mortar::ad::clip_polygons_in<Polygon<S>>(subject, clipper, options.clip);
  if (polygon.empty()) return;
  std::array<Eigen::Vector2d, 4> usv, umv;
  for (std::size_t k = 0; k < 4; ++k) {
    usv[k] = value(us[k]);
    umv[k] = value(um[k]);
  }
  std::array<Eigen::Vector2d, 4> zero;
  zero.fill(Eigen::Vector2d::Zero());
  mortar::detail::PieceInverse slave_inverse, master_inverse;
  const bool slave_valid = slave_inverse.set(ns, usv, zero, true);
  const bool master_valid = master_inverse.set(nm, umv, zero, true);

  std::array<std::array<S, 4>, 4> A;
  if (in.dual) dual_coefficients(ns, xs, A);
  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree : 5;
  const CellRule rule(degree);
  // The fan about the area centroid and its points.
  for_each_point(polygon, rule, [&](const V2<S>& u, const S& area, double weight) {
    S s1 = 0.0, s2 = 0.0, m1 = 0.0, m2 = 0.0;
    if (!slave_valid || !master_valid || !locate(ns, us, slave_inverse, u, s1, s2) ||
        !locate(nm, um, master_inverse, u, m1, m2))
      return;
    std::array<S, 4> Ns, Nm;
    shape_values<S>(ns, s1, s2, Ns);
    shape_values<S>(nm, m1, m2, Nm);
    const S wg = weighted_point_gap(static_cast<std::size_t>(ns), nn, hs, Ns,
                                    static_cast<std::size_t>(nm), hm, Nm, np, area, weight);
    // Phi_j = A_jk N_k with A constant over the pair: sum w g N_k first, apply A once.
    for (std::size_t k = 0; k < static_cast<std::size_t>(ns); ++k) add_product(g[k], wg, Ns[k]);
  });
  if (!in.dual) return;
  const std::array<S, 4> weighted = g;
  for (std::size_t j = 0; j < static_cast<std::size_t>(ns); ++j) {
    g[j] = 0.0;
    for (std::size_t k = 0; k < static_cast<std::size_t>(ns); ++k)
      add_product(g[j], A[j][k], weighted[k]);
  }
}

// ---------------------------------------------------------------------------------------------
// Quadratic facets (tri6, quad8, quad9 on either side; a linear facet against a quadratic one
// too): integrate_pair's path for them, per linear piece of the slave facet an auxiliary plane,
// the clip against each master piece and the back-projection onto the parent facets by Newton
// in the plane. The pair's independents: the slave positions (27), the slave nodal normals (27)
// and the master positions (27). Hessians: on SymHyper<9 n> over the n slots the facets seed
// (pair_gaps_quadratic_packed), each point by the chain rule through its reference
// coordinates (locate_packed and below); the plain forward path on Hyper<81> stays for the
// tests and seam-bench (detail::quadratic_pair_derivatives). Storage of the scalar type on the
// heap (a Hyper<81> takes 53 kB, a SymHyper<81> 27 kB).

constexpr int quadratic_slots = mortar::max_facet_nodes;
constexpr int quadratic_variables = 9 * quadratic_slots;
constexpr int max_ring_nodes_quadratic = 27;
constexpr int quadratic_ring_variables = 3 * max_ring_nodes_quadratic;

/// Shape values of a surface facet at (s, t) on T: mortar::detail::shape_functions' formulas.
template <class T>
void facet_shape_values(fem::CellType type, const T& s, const T& t,
                        std::array<T, mortar::max_facet_nodes>& N) {
  switch (type) {
  case fem::CellType::tri3:
    N[0] = 1.0 - s - t;
    N[1] = s;
    N[2] = t;
    return;
  case fem::CellType::quad4: {
    const T sm = 1.0 - s, sp = 1.0 + s, tm = 1.0 - t, tp = 1.0 + t;
    N[0] = 0.25 * sm * tm;
    N[1] = 0.25 * sp * tm;
    N[2] = 0.25 * sp * tp;
    N[3] = 0.25 * sm * tp;
    return;
  }
  case fem::CellType::tri6: {
    const T l0 = 1.0 - s - t;
    N[0] = l0 * (2.0 * l0 - 1.0);
    N[1] = s * (2.0 * s - 1.0);
    N[2] = t * (2.0 * t - 1.0);
    N[3] = 4.0 * l0 * s;
    N[4] = 4.0 * s * t;
    N[5] = 4.0 * t * l0;
    return;
  }
  case fem::CellType::quad8: {
    constexpr std::array<double, 4> cx{-1.0, 1.0, 1.0, -1.0}, cy{-1.0, -1.0, 1.0, 1.0};
    for (std::size_t v = 0; v < 4; ++v)
      N[v] = 0.25 * (1.0 + cx[v] * s) * (1.0 + cy[v] * t) * (cx[v] * s + cy[v] * t - 1.0);
    const T bx = 1.0 - s * s, by = 1.0 - t * t;
    N[4] = 0.5 * bx * (1.0 - t);
    N[5] = 0.5 * (1.0 + s) * by;
    N[6] = 0.5 * bx * (1.0 + t);
    N[7] = 0.5 * (1.0 - s) * by;
    return;
  }
  default: {
    SEAM_ASSERT(type == fem::CellType::quad9);
    const std::array<T, 3> lx{0.5 * s * (s - 1.0), 0.5 * s * (s + 1.0), 1.0 - s * s};
    const std::array<T, 3> ly{0.5 * t * (t - 1.0), 0.5 * t * (t + 1.0), 1.0 - t * t};
    constexpr std::array<int, 9> ix{0, 1, 1, 0, 2, 1, 2, 0, 2}, iy{0, 0, 1, 1, 0, 2, 1, 2, 2};
    for (std::size_t k = 0; k < 9; ++k)
      N[k] = lx[static_cast<std::size_t>(ix[k])] * ly[static_cast<std::size_t>(iy[k])];
    return;
  }
  }
}

/// The dual coefficients A = D_e M_e^-1 of a slave facet of any type with the basis
/// modification a (dual_basis.cpp: the rule of degree 4 p, the modified shape functions N~),
/// on S; row-major n x n.
template <class S>
void dual_coefficients_of(fem::CellType type, const std::vector<V3<S>>& x, double a,
                          std::vector<S>& A) {
  const auto n = x.size();
  const fem::QuadratureRule rule = fem::quadrature(type, 4 * fem::order(type));
  std::vector<S> M(n * n, S(0.0)), D(n, S(0.0)), inv(n * n, S(0.0));
  for (int q = 0; q < rule.n_points; ++q) {
    mortar::NodalVector N;
    std::array<double, 2 * mortar::max_facet_nodes> dN;
    mortar::detail::shape_functions<true>(
        type,
        Eigen::Vector2d(rule.points[static_cast<std::size_t>(2 * q)],
                        rule.points[static_cast<std::size_t>(2 * q + 1)]),
        N, dN);
    mortar::modify_basis(type, a, N.data());
    V3<S> ta, tb;
    for (std::size_t k = 0; k < n; ++k) {
      ta = ta + x[k] * dN[2 * k];
      tb = tb + x[k] * dN[2 * k + 1];
    }
    const S jw = norm(cross(ta, tb)) * rule.weights[static_cast<std::size_t>(q)];
    for (std::size_t j = 0; j < n; ++j) {
      add_product(D[j], jw, N(static_cast<Eigen::Index>(j)));
      for (std::size_t k = 0; k < n; ++k)
        add_product(M[j * n + k], jw,
                    N(static_cast<Eigen::Index>(j)) * N(static_cast<Eigen::Index>(k)));
    }
  }
  // Gauss-Jordan (M symmetric positive definite: no pivoting), then A = D M^-1.
  for (std::size_t j = 0; j < n; ++j) inv[j * n + j] = 1.0;
  for (std::size_t p = 0; p < n; ++p) {
    const S pivot = 1.0 / M[p * n + p];
    for (std::size_t k = 0; k < n; ++k) {
      M[p * n + k] = M[p * n + k] * pivot;
      inv[p * n + k] = inv[p * n + k] * pivot;
    }
    for (std::size_t r = 0; r < n; ++r) {
      if (r == p) continue;
      const S f = M[r * n + p];
      for (std::size_t k = 0; k < n; ++k) {
        M[r * n + k] -= f * M[p * n + k];
        inv[r * n + k] -= f * inv[p * n + k];
      }
    }
  }
  A.assign(n * n, S(0.0));
  for (std::size_t j = 0; j < n; ++j)
    for (std::size_t k = 0; k < n; ++k) A[j * n + k] = D[j] * inv[j * n + k];
}

/// x(xi_c) at the reference centre of a facet, on values (integrate_pair's pre-check).
Eigen::Vector3d centre_of(fem::CellType type, const std::array<Eigen::Vector3d, 9>& x, int n) {
  const auto c = mortar::reference_center(type);
  mortar::NodalVector N;
  std::array<double, 2 * mortar::max_facet_nodes> dN;
  mortar::detail::shape_functions<false>(type, Eigen::Vector2d(c[0], c[1]), N, dN);
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (int k = 0; k < n; ++k) sum += N(k) * x[static_cast<std::size_t>(k)];
  return sum;
}

/// Reference coordinates (s, t) on a facet of the plane point p: the piece's inverse and Newton
/// in the plane on values (integration_3d.cpp's locate), then chord Newton steps on S with the
/// Jacobian there (locate above).
template <class S>
bool locate_on(const mortar::detail::PlanarFacet& facet, const std::vector<V2<S>>& u,
               const mortar::detail::PieceInverse& inverse, bool linear,
               const geometry::NewtonOptions& newton, const V2<S>& p, S& s, S& t) {
  Eigen::Vector2d xi;
  if (!inverse.parent_coordinates(value(p), xi)) return false;
  if (!linear && !mortar::detail::newton_in_plane(facet, value(p), xi, newton)) return false;
  s = xi.x();
  t = xi.y();
  if constexpr (!std::is_same_v<S, double>) {
    mortar::NodalVector N0;
    std::array<double, 2 * mortar::max_facet_nodes> dN;
    mortar::detail::shape_functions<true>(facet.type, xi, N0, dN);
    Eigen::Vector2d j0 = Eigen::Vector2d::Zero(), j1 = Eigen::Vector2d::Zero();
    for (std::size_t k = 0; k < u.size(); ++k) {
      j0 += value(u[k]) * dN[2 * k];
      j1 += value(u[k]) * dN[2 * k + 1];
    }
    const double det = j0.x() * j1.y() - j0.y() * j1.x();
    const int steps = is_dual<S> ? 1 : 2;
    std::array<S, mortar::max_facet_nodes> N;
    for (int it = 0; it < steps; ++it) {
      S rx = -p.x, ry = -p.y;
      if constexpr (is_dual<S>) {
        // One step from the values: the shape values are numbers (the same sums).
        std::array<double, mortar::max_facet_nodes> Nv;
        facet_shape_values<double>(facet.type, xi.x(), xi.y(), Nv);
        for (std::size_t k = 0; k < u.size(); ++k) {
          add_product(rx, u[k].x, Nv[k]);
          add_product(ry, u[k].y, Nv[k]);
        }
      } else {
        facet_shape_values<S>(facet.type, s, t, N);
        for (std::size_t k = 0; k < u.size(); ++k) {
          add_product(rx, u[k].x, N[k]);
          add_product(ry, u[k].y, N[k]);
        }
      }
      s = s - (rx * j1.y() - ry * j1.x()) * (1.0 / det);
      t = t - (ry * j0.x() - rx * j0.y()) * (1.0 / det);
    }
  }
  return true;
}

// The points of the Hessian path on SymHyper (pair_gaps_quadratic_packed): the chain rule
// through the reference coordinates instead of arithmetic on whole Hessians. At a point the
// back-projection xi of the plane point p solves R(xi) = sum_k N_k(xi) u_k - p = 0; with the
// residual r = R(xi_0) on S at the converged values xi_0 (N_k(xi_0) constant), J = dR/dxi,
// z_a = grad xi_a = -(J^-1 grad r)_a and, from the second derivative of R(xi(X), X) = 0,
//   H(xi_c) = -sum_d J^-1_cd [H(r_d) + sum_a (G_ad z_a^T + z_a G_ad^T)
//                             + sum_ab R_abd z_a z_b^T],
// G_ad = sum_k dN_k/dxi_a grad u_kd, R_abd = sum_k d2N_k/dxi_a dxi_b u_kd: what the chord
// steps of locate_on give (one step per order), in one pass over the Hessian. Interpolated
// nodal quantities Q = sum_k c_k N_k(xi) and the products g N~_k(xi) follow the same way;
// every Hessian is written once, by combine_hessians, row by row.

/// Shape values, first and second reference derivatives of a facet at xi, in doubles (the
/// formulas of facet_shape_values on Hyper<2>), optionally of the modified basis N~.
struct ShapeJet {
  std::array<double, mortar::max_facet_nodes> N{};
  std::array<std::array<double, mortar::max_facet_nodes>, 2> d{};  ///< d/ds, d/dt
  std::array<std::array<double, mortar::max_facet_nodes>, 3> dd{}; ///< ss, st, tt

  ShapeJet(fem::CellType type, const Eigen::Vector2d& xi, double modification) {
    std::array<Hyper<2>, mortar::max_facet_nodes> h;
    facet_shape_values<Hyper<2>>(type, Hyper<2>::variable(xi.x(), 0), Hyper<2>::variable(xi.y(), 1),
                                 h);
    const auto n = static_cast<std::size_t>(fem::n_nodes(type));
    for (std::size_t k = 0; k < n; ++k) {
      N[k] = h[k].value;
      d[0][k] = h[k].gradient[0];
      d[1][k] = h[k].gradient[1];
      dd[0][k] = h[k].second(0, 0);
      dd[1][k] = h[k].second(0, 1);
      dd[2][k] = h[k].second(1, 1);
    }
    if (modification == 0.0) return;
    mortar::modify_basis(type, modification, N.data());
    for (auto& a : d) mortar::modify_basis(type, modification, a.data());
    for (auto& a : dd) mortar::modify_basis(type, modification, a.data());
  }
  /// The second derivative (a, b) of N_k.
  double second(int a, int b, std::size_t k) const {
    return dd[static_cast<std::size_t>(a + b)][k];
  }
};

/// The rows of x's packed Hessian that hold a nonzero: the plane images and heights of the
/// nodes depend on the piece's corners and the node alone (15 of 81 variables for quad9).
template <int N> std::array<bool, N> nonzero_rows(const SymHyper<N>& x) {
  std::array<bool, N> rows{};
  for (int i = 0; i < N; ++i) {
    const double* h = x.hessian.data() + SymHyper<N>::row(i) - i;
    for (int k = i; k < N && !rows[static_cast<std::size_t>(i)]; ++k)
      rows[static_cast<std::size_t>(i)] = h[k] != 0.0;
  }
  return rows;
}

/// The nonzero rows of the Hessians of a node's plane image (x, y) and height.
template <int N> using NodeRows = std::array<std::array<bool, N>, 3>;

/// The shape values N_k(s, t) on Dual by the chain rule: N_k and dN_k/dxi at the values.
template <int N>
void shape_values_chain(fem::CellType type, const Dual<N>& s, const Dual<N>& t,
                        std::array<Dual<N>, mortar::max_facet_nodes>& out) {
  const ShapeJet jet(type, Eigen::Vector2d(s.value, t.value), 0.0);
  for (std::size_t k = 0; k < static_cast<std::size_t>(fem::n_nodes(type)); ++k) {
    out[k].value = jet.N[k];
    for (int i = 0; i < N; ++i)
      out[k].gradient[static_cast<std::size_t>(i)] =
          jet.d[0][k] * s.gradient[static_cast<std::size_t>(i)] +
          jet.d[1][k] * t.gradient[static_cast<std::size_t>(i)];
  }
}

/// out's Hessian = (out's +) sum_j alpha_j H(x_j) + sum_pq C_pq w_p w_q^T for L gradient-sized
/// vectors w (C symmetric), row by row of the packed triangle; rows[j] (if given and not null)
/// the nonzero rows of H(x_j).
template <int N, int L>
void combine_hessians(SymHyper<N>& out, bool accumulate, int n_inputs, const double* alpha,
                      const SymHyper<N>* const* x, const std::array<const double*, L>& w,
                      const std::array<std::array<double, L>, L>& C,
                      const bool* const* rows = nullptr) {
  for (int i = 0; i < N; ++i) {
    const std::ptrdiff_t o = SymHyper<N>::row(i) - i;
    double* r = out.hessian.data() + o;
    if (!accumulate)
      for (int k = i; k < N; ++k) r[k] = 0.0;
    for (int j = 0; j < n_inputs; ++j) {
      const double a = alpha[j];
      if (a == 0.0 || (rows != nullptr && rows[j] != nullptr && !rows[j][i])) continue;
      const double* h = x[j]->hessian.data() + o;
      for (int k = i; k < N; ++k) r[k] += a * h[k];
    }
    for (int q = 0; q < L; ++q) {
      double c = 0.0;
      for (int p = 0; p < L; ++p) c += C[p][q] * w[p][i];
      if (c == 0.0) continue;
      const double* wq = w[q];
      for (int k = i; k < N; ++k) r[k] += c * wq[k];
    }
  }
}

/// The reference coordinates of the plane point p on a facet with plane images u (locate_on's
/// values and derivatives, see above) and the shape jet there; false where locate_on fails.
template <int N>
bool locate_packed(const mortar::detail::PlanarFacet& facet, const std::vector<V2<SymHyper<N>>>& u,
                   const mortar::detail::PieceInverse& inverse, bool linear,
                   const geometry::NewtonOptions& newton, const V2<SymHyper<N>>& p,
                   const std::type_identity_t<std::vector<NodeRows<N>>>& rows,
                   std::array<SymHyper<N>, 2>& xi, Eigen::Vector2d& xi_value) {
  using H = SymHyper<N>;
  Eigen::Vector2d x0;
  if (!inverse.parent_coordinates(value(p), x0)) return false;
  if (!linear && !mortar::detail::newton_in_plane(facet, value(p), x0, newton)) return false;
  const ShapeJet jet(facet.type, x0, 0.0);
  const std::size_t n = u.size();
  // r_d = sum_k N_k u_kd - p_d on S (N_k constant).
  std::array<H, 2> r;
  std::array<double, mortar::max_facet_nodes + 1> alpha{};
  std::array<const H*, mortar::max_facet_nodes + 1> inputs{};
  std::array<const bool*, mortar::max_facet_nodes + 1> input_rows{};
  Eigen::Matrix2d J = Eigen::Matrix2d::Zero();
  std::array<std::array<double, 2>, 3> R{}; // R_ab,d for ab = ss, st, tt
  for (std::size_t k = 0; k < n; ++k) {
    const Eigen::Vector2d uk = value(u[k]);
    for (int a = 0; a < 2; ++a) J.col(a) += jet.d[static_cast<std::size_t>(a)][k] * uk;
    for (std::size_t ab = 0; ab < 3; ++ab) {
      R[ab][0] += jet.dd[ab][k] * uk.x();
      R[ab][1] += jet.dd[ab][k] * uk.y();
    }
  }
  for (int d = 0; d < 2; ++d) {
    H& rd = r[static_cast<std::size_t>(d)];
    const H& pd = d == 0 ? p.x : p.y;
    rd.value = -pd.value;
    for (int i = 0; i < N; ++i) rd.gradient[i] = -pd.gradient[i];
    for (std::size_t k = 0; k < n; ++k) {
      const H& ukd = d == 0 ? u[k].x : u[k].y;
      rd.value += jet.N[k] * ukd.value;
      for (int i = 0; i < N; ++i) rd.gradient[i] += jet.N[k] * ukd.gradient[i];
      alpha[k] = jet.N[k];
      inputs[k] = &ukd;
      input_rows[k] = rows[k][static_cast<std::size_t>(d)].data();
    }
    alpha[n] = -1.0;
    inputs[n] = &pd;
    input_rows[n] = nullptr;
    combine_hessians<N, 0>(rd, false, static_cast<int>(n + 1), alpha.data(), inputs.data(), {}, {},
                           input_rows.data());
  }
  const Eigen::Matrix2d Ji = J.inverse();
  // z_a = grad xi_a; G_ad = sum_k dN_k/dxi_a grad u_kd.
  std::array<std::array<double, N>, 2> z;
  std::array<std::array<std::array<double, N>, 2>, 2> G{};
  for (int i = 0; i < N; ++i) {
    for (int a = 0; a < 2; ++a)
      z[static_cast<std::size_t>(a)][i] =
          -(Ji(a, 0) * r[0].gradient[i] + Ji(a, 1) * r[1].gradient[i]);
    for (std::size_t a = 0; a < 2; ++a)
      for (std::size_t k = 0; k < n; ++k) {
        G[a][0][i] += jet.d[a][k] * u[k].x.gradient[i];
        G[a][1][i] += jet.d[a][k] * u[k].y.gradient[i];
      }
  }
  for (int c = 0; c < 2; ++c) {
    H& x = xi[static_cast<std::size_t>(c)];
    x.value = x0[c] - (Ji(c, 0) * r[0].value + Ji(c, 1) * r[1].value);
    x.gradient = z[static_cast<std::size_t>(c)];
    // P_a = -sum_d J^-1_cd G_ad; w = (z_0, z_1, P_0, P_1).
    std::array<std::array<double, N>, 2> P;
    for (std::size_t a = 0; a < 2; ++a)
      for (int i = 0; i < N; ++i) P[a][i] = -(Ji(c, 0) * G[a][0][i] + Ji(c, 1) * G[a][1][i]);
    std::array<std::array<double, 4>, 4> C{};
    for (int a = 0; a < 2; ++a) {
      for (int b = 0; b < 2; ++b) {
        const auto& Rab = R[static_cast<std::size_t>(a + b)];
        C[static_cast<std::size_t>(a)][static_cast<std::size_t>(b)] =
            -(Ji(c, 0) * Rab[0] + Ji(c, 1) * Rab[1]);
      }
      C[static_cast<std::size_t>(a)][static_cast<std::size_t>(a + 2)] = 1.0;
      C[static_cast<std::size_t>(a + 2)][static_cast<std::size_t>(a)] = 1.0;
    }
    const std::array<double, 2> beta{-Ji(c, 0), -Ji(c, 1)};
    const std::array<const H*, 2> rs{&r[0], &r[1]};
    combine_hessians<N, 4>(x, false, 2, beta.data(), rs.data(),
                           {z[0].data(), z[1].data(), P[0].data(), P[1].data()}, C);
  }
  xi_value = {xi[0].value, xi[1].value};
  return true;
}

/// Q = sum_k c_k N_k(xi) over the n nodes of the jet; the c_k's Hessians have the nonzero rows
/// rows[k][2] or, without rows, are zero (the nodal normals are independents).
template <int N>
SymHyper<N> interpolate_packed(const ShapeJet& jet, std::size_t n,
                               const std::array<const SymHyper<N>*, mortar::max_facet_nodes>& c,
                               const std::type_identity_t<std::vector<NodeRows<N>>>* rows,
                               const std::array<SymHyper<N>, 2>& xi) {
  using H = SymHyper<N>;
  H q(0.0, typename H::Uninitialized{});
  std::array<double, 2> qa{};
  std::array<double, 3> qab{};
  std::array<std::array<double, N>, 2> D{};
  q.gradient.fill(0.0);
  for (std::size_t k = 0; k < n; ++k) {
    const H& ck = *c[k];
    q.value += jet.N[k] * ck.value;
    for (std::size_t a = 0; a < 2; ++a) qa[a] += jet.d[a][k] * ck.value;
    for (std::size_t ab = 0; ab < 3; ++ab) qab[ab] += jet.dd[ab][k] * ck.value;
    for (int i = 0; i < N; ++i) {
      q.gradient[i] += jet.N[k] * ck.gradient[i];
      D[0][i] += jet.d[0][k] * ck.gradient[i];
      D[1][i] += jet.d[1][k] * ck.gradient[i];
    }
  }
  for (int i = 0; i < N; ++i)
    q.gradient[i] += qa[0] * xi[0].gradient[i] + qa[1] * xi[1].gradient[i];
  std::array<double, mortar::max_facet_nodes + 2> alpha{};
  std::array<const H*, mortar::max_facet_nodes + 2> inputs{};
  std::array<const bool*, mortar::max_facet_nodes + 2> input_rows{};
  int m = 0;
  for (std::size_t a = 0; a < 2; ++a) {
    alpha[static_cast<std::size_t>(m)] = qa[a];
    inputs[static_cast<std::size_t>(m++)] = &xi[a];
  }
  if (rows != nullptr)
    for (std::size_t k = 0; k < n; ++k) {
      alpha[static_cast<std::size_t>(m)] = jet.N[k];
      input_rows[static_cast<std::size_t>(m)] = (*rows)[k][2].data();
      inputs[static_cast<std::size_t>(m++)] = c[k];
    }
  std::array<std::array<double, 4>, 4> C{};
  for (std::size_t a = 0; a < 2; ++a) {
    for (std::size_t b = 0; b < 2; ++b) C[a][b] = qab[a + b];
    C[a][a + 2] = C[a + 2][a] = 1.0;
  }
  combine_hessians<N, 4>(q, false, m, alpha.data(), inputs.data(),
                         {xi[0].gradient.data(), xi[1].gradient.data(), D[0].data(), D[1].data()},
                         C, input_rows.data());
  return q;
}

/// weighted_k += g N~_k(xi) for the k < n nodes of the jet (of the modified basis): per node
/// H += N~_k H(g) + g sum_a N~_k,a H(xi_a) + sum_a N~_k,a (grad g z_a^T + z_a grad g^T)
///      + g sum_ab N~_k,ab z_a z_b^T, all nodes in one sweep over the rows of the inputs.
template <int N>
void add_weighted_packed(std::vector<SymHyper<N>>& weighted, const SymHyper<N>& g,
                         const ShapeJet& jet, std::size_t n, const std::array<SymHyper<N>, 2>& xi) {
  const double gv = g.value;
  const double* z0 = xi[0].gradient.data();
  const double* z1 = xi[1].gradient.data();
  const double* gg = g.gradient.data();
  for (std::size_t k = 0; k < n; ++k) {
    SymHyper<N>& out = weighted[k];
    const double Nk = jet.N[k], d0 = jet.d[0][k], d1 = jet.d[1][k];
    out.value += gv * Nk;
    for (int i = 0; i < N; ++i) out.gradient[i] += Nk * gg[i] + gv * (d0 * z0[i] + d1 * z1[i]);
  }
  for (int i = 0; i < N; ++i) {
    const std::ptrdiff_t o = SymHyper<N>::row(i) - i;
    const double* hg = g.hessian.data() + o;
    const double* h0 = xi[0].hessian.data() + o;
    const double* h1 = xi[1].hessian.data() + o;
    for (std::size_t k = 0; k < n; ++k) {
      const double Nk = jet.N[k], d0 = jet.d[0][k], d1 = jet.d[1][k];
      const double a0 = gv * d0, a1 = gv * d1;
      const double s00 = gv * jet.second(0, 0, k), s01 = gv * jet.second(0, 1, k),
                   s11 = gv * jet.second(1, 1, k);
      // Row i of the low-rank terms: c_z0 z0 + c_z1 z1 + c_g grad g.
      const double c0 = s00 * z0[i] + s01 * z1[i] + d0 * gg[i];
      const double c1 = s01 * z0[i] + s11 * z1[i] + d1 * gg[i];
      const double cg = d0 * z0[i] + d1 * z1[i];
      double* r = weighted[k].hessian.data() + o;
      for (int m = i; m < N; ++m)
        r[m] += Nk * hg[m] + a0 * h0[m] + a1 * h1[m] + c0 * z0[m] + c1 * z1[m] + cg * gg[m];
    }
  }
}

template <int N>
V2<SymHyper<N>> barycentric_packed(const V2<SymHyper<N>>& a, const V2<SymHyper<N>>& b,
                                   const V2<SymHyper<N>>& c, const std::array<double, 4>& point) {
  V2<SymHyper<N>> p;
  for (int d = 0; d < 2; ++d) {
    const std::array<const SymHyper<N>*, 3> x{&a(d), &b(d), &c(d)};
    SymHyper<N>& out = d == 0 ? p.x : p.y;
    out.value = point[0] * x[0]->value + point[1] * x[1]->value + point[2] * x[2]->value;
    for (int i = 0; i < N; ++i)
      out.gradient[i] = point[0] * x[0]->gradient[i] + point[1] * x[1]->gradient[i] +
                        point[2] * x[2]->gradient[i];
    combine_hessians<N, 0>(out, false, 3, point.data(), x.data(), {}, {});
  }
  return p;
}

/// f(y_0, ..., y_{M-1}) on SymHyper<N> for M numbers y_j: f's own derivatives on Hyper<M>,
/// then the chain rule, grad f = sum_j f_j grad y_j and
/// H(f) = sum_j f_j H(y_j) + sum_jl f_jl grad y_j grad y_l^T, in one pass.
template <int N, int M, class F>
SymHyper<N> compose(const std::array<const SymHyper<N>*, M>& y, F&& f) {
  std::array<Hyper<M>, M> local;
  for (int j = 0; j < M; ++j)
    local[static_cast<std::size_t>(j)] =
        Hyper<M>::variable(y[static_cast<std::size_t>(j)]->value, j);
  const Hyper<M> r = f(local);
  SymHyper<N> out(r.value, typename SymHyper<N>::Uninitialized{});
  out.gradient.fill(0.0);
  std::array<const double*, M> w;
  std::array<std::array<double, M>, M> C;
  for (std::size_t j = 0; j < M; ++j) {
    const auto& gj = y[j]->gradient;
    for (int i = 0; i < N; ++i) out.gradient[i] += r.gradient[j] * gj[i];
    w[j] = gj.data();
    for (std::size_t l = 0; l < M; ++l) C[j][l] = r.hessian[j * M + l];
  }
  combine_hessians<N, M>(out, false, M, r.gradient.data(), y.data(), w, C);
  return out;
}

template <class S> struct RowsOf { using type = char; };
template <int N> struct RowsOf<SymHyper<N>> { using type = NodeRows<N>; };

/// The corner positions of a piece and its normal on values (make_piece of
/// integration_3d.cpp): the triangle's cross product, the quadrilateral's diagonals'.
Eigen::Vector3d piece_normal(const mortar::SubFacet& piece,
                             const std::array<Eigen::Vector3d, 9>& x) {
  const auto& v = piece.nodes;
  const Eigen::Vector3d n = piece.n_vertices == 3
                                ? Eigen::Vector3d((x[v[1]] - x[v[0]]).cross(x[v[2]] - x[v[0]]))
                                : Eigen::Vector3d((x[v[2]] - x[v[0]]).cross(x[v[3]] - x[v[1]]));
  const double length = n.norm();
  return length > 0.0 ? Eigen::Vector3d(n / length) : Eigen::Vector3d::Zero();
}

/// The kernel on S with the independents laid out in groups of 3 n_slots (slave positions,
/// slave normals, master positions).
template <class S>
void pair_gaps_quadratic_on(const PairInput& in, const mortar::PairOptions& options,
                            std::vector<S>& g, int n_slots) {
  const int ns = in.ns, nm = in.nm;
  const auto ms = static_cast<std::size_t>(ns), mm = static_cast<std::size_t>(nm);
  g.assign(ms, S(0.0));
  // Centre distance against the reach from the corner edges (integrate_pair's pre-check).
  const double factor = options.max_center_distance_factor;
  const double reach_squared =
      factor * factor *
      std::max(longest_edge_squared(in.xs, fem::n_vertices(in.slave_type)),
               longest_edge_squared(in.xm, fem::n_vertices(in.master_type)));
  if ((centre_of(in.slave_type, in.xs, ns) - centre_of(in.master_type, in.xm, nm)).squaredNorm() >
      reach_squared)
    return;
  const bool slave_linear = fem::order(in.slave_type) == 1;
  const bool master_linear = fem::order(in.master_type) == 1;
  std::vector<V3<S>> xs(ms), nn(ms), xm(mm);
  for (std::size_t k = 0; k < ms; ++k) {
    xs[k] = seeded<S>(in.xs[k], 3 * static_cast<int>(k));
    nn[k] = seeded<S>(in.normal[k], 3 * n_slots + 3 * static_cast<int>(k));
  }
  for (std::size_t l = 0; l < mm; ++l)
    xm[l] = seeded<S>(in.xm[l], 6 * n_slots + 3 * static_cast<int>(l));
  const double a = mortar::basis_modification(
      in.slave_type, in.dual ? mortar::Multiplier::dual : mortar::Multiplier::standard);
  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree
                     : slave_linear && master_linear    ? 5
                                                        : 8;
  const CellRule rule(degree);
  const auto master_pieces = mortar::linear_subfacets(in.master_type);
  std::vector<Eigen::Vector3d> master_normals;
  for (const auto& mp : master_pieces) master_normals.push_back(piece_normal(mp, in.xm));
  mortar::Facet<3> slave_facet, master_facet;
  slave_facet.type = in.slave_type;
  slave_facet.n_nodes = ns;
  master_facet.type = in.master_type;
  master_facet.n_nodes = nm;
  for (int k = 0; k < ns; ++k) slave_facet.x.col(k) = in.xs[static_cast<std::size_t>(k)];
  for (int l = 0; l < nm; ++l) master_facet.x.col(l) = in.xm[static_cast<std::size_t>(l)];
  const double* slave_reference = fem::reference_nodes(in.slave_type).data();
  const double* master_reference = fem::reference_nodes(in.master_type).data();
  const auto piece_xi = [](const mortar::SubFacet& piece, const double* reference) {
    std::array<Eigen::Vector2d, 4> xi;
    xi.fill(Eigen::Vector2d::Zero());
    for (int v = 0; v < piece.n_vertices; ++v) {
      const int node = piece.nodes[static_cast<std::size_t>(v)];
      xi[static_cast<std::size_t>(v)] = {reference[2 * node], reference[2 * node + 1]};
    }
    return xi;
  };
  std::vector<S> weighted(ms, S(0.0));
  std::vector<V2<S>> us(ms), um(mm);
  std::vector<S> hs(ms), hm(mm);
  std::array<S, mortar::max_facet_nodes> Ns, Nm;
  // The nonzero rows of the nodes' plane images and heights (the packed path).
  std::vector<typename RowsOf<S>::type> slave_rows(ms), master_rows(mm);
  for (const auto& sp : mortar::linear_subfacets(in.slave_type)) {
    const auto& v = sp.nodes;
    const int nv = sp.n_vertices;
    // The auxiliary plane of the piece (make_piece, geometry::make_plane).
    AuxPlane<S> aux;
    if (!aux.set(xs, v, nv)) continue;
    const V3<S>& np = aux.np;
    const Eigen::Vector3d npv = value(np);
    for (std::size_t k = 0; k < ms; ++k) aux.into(xs[k], us[k], hs[k]);
    for (std::size_t l = 0; l < mm; ++l) aux.into(xm[l], um[l], hm[l]);
    if constexpr (is_sym_hyper<S>) {
      for (std::size_t k = 0; k < ms; ++k)
        slave_rows[k] = {nonzero_rows(us[k].x), nonzero_rows(us[k].y), nonzero_rows(hs[k])};
      for (std::size_t l = 0; l < mm; ++l)
        master_rows[l] = {nonzero_rows(um[l].x), nonzero_rows(um[l].y), nonzero_rows(hm[l])};
    }
    // The same plane and the facets in it on values (for the Newton iterations).
    geometry::Plane plane;
    plane.origin = value(aux.center);
    plane.normal = npv;
    plane.t1 = value(aux.t1);
    plane.t2 = value(aux.t2);
    const mortar::detail::PlanarFacet slave_plane(slave_facet, plane);
    const mortar::detail::PlanarFacet master_plane(master_facet, plane);
    Polygon<S> subject;
    Eigen::Vector2d slo = value(us[v[0]]), shi = slo;
    std::array<Eigen::Vector2d, 4> su;
    for (int k = 0; k < nv; ++k) {
      subject.push_back(us[static_cast<std::size_t>(v[k])]);
      su[static_cast<std::size_t>(k)] = value(us[static_cast<std::size_t>(v[k])]);
      slo = slo.cwiseMin(su[static_cast<std::size_t>(k)]);
      shi = shi.cwiseMax(su[static_cast<std::size_t>(k)]);
    }
    // Every master piece lies in the box of all master nodes.
    Eigen::Vector2d mlo = value(um[0]), mhi = mlo;
    for (std::size_t l = 1; l < mm; ++l) {
      mlo = mlo.cwiseMin(value(um[l]));
      mhi = mhi.cwiseMax(value(um[l]));
    }
    if ((mlo.array() > shi.array()).any() || (slo.array() > mhi.array()).any()) continue;
    mortar::detail::PieceInverse slave_inverse;
    bool slave_inverse_set = false, slave_valid = false;
    for (std::size_t i = 0; i < master_pieces.size(); ++i) {
      const auto& mp = master_pieces[i];
      if (!(master_normals[i].dot(npv) < -1e-12)) continue;
      Polygon<S> clipper;
      std::array<Eigen::Vector2d, 4> mu;
      Eigen::Vector2d plo = value(um[static_cast<std::size_t>(mp.nodes[0])]), phi = plo;
      for (int k = 0; k < mp.n_vertices; ++k) {
        const auto node = static_cast<std::size_t>(mp.nodes[static_cast<std::size_t>(k)]);
        clipper.push_back(um[node]);
        mu[static_cast<std::size_t>(k)] = value(um[node]);
        plo = plo.cwiseMin(mu[static_cast<std::size_t>(k)]);
        phi = phi.cwiseMax(mu[static_cast<std::size_t>(k)]);
      }
      if ((plo.array() > shi.array()).any() || (slo.array() > phi.array()).any()) continue;
      const Polygon<S> polygon =
          mortar::ad::clip_polygons_in<Polygon<S>>(subject, clipper, options.clip);
      if (polygon.empty()) continue;
      if (!slave_inverse_set) {
        slave_valid = slave_inverse.set(nv, su, piece_xi(sp, slave_reference), slave_linear);
        slave_inverse_set = true;
      }
      mortar::detail::PieceInverse master_inverse;
      const bool master_valid =
          master_inverse.set(mp.n_vertices, mu, piece_xi(mp, master_reference), master_linear);
      if constexpr (is_sym_hyper<S>) {
        for_each_point(polygon, rule, [&](const V2<S>& u, const S& area, double weight) {
          std::array<S, 2> xs_ref, xm_ref;
          Eigen::Vector2d slave_xi, master_xi;
          if (!slave_valid || !master_valid ||
              !locate_packed(slave_plane, us, slave_inverse, slave_linear, options.newton, u,
                             slave_rows, xs_ref, slave_xi) ||
              !locate_packed(master_plane, um, master_inverse, master_linear, options.newton, u,
                             master_rows, xm_ref, master_xi))
            return;
          const ShapeJet slave_jet(in.slave_type, slave_xi, 0.0);
          const ShapeJet master_jet(in.master_type, master_xi, 0.0);
          std::array<const S*, mortar::max_facet_nodes> c{};
          V3<S> n;
          for (int axis = 0; axis < 3; ++axis) {
            for (std::size_t k = 0; k < ms; ++k)
              c[k] = axis == 0 ? &nn[k].x : axis == 1 ? &nn[k].y : &nn[k].z;
            (axis == 0   ? n.x
             : axis == 1 ? n.y
                         : n.z) = interpolate_packed(slave_jet, ms, c, nullptr, xs_ref);
          }
          for (std::size_t k = 0; k < ms; ++k) c[k] = &hs[k];
          const S h_s = interpolate_packed(slave_jet, ms, c, &slave_rows, xs_ref);
          for (std::size_t l = 0; l < mm; ++l) c[l] = &hm[l];
          const S h_m = interpolate_packed(master_jet, mm, c, &master_rows, xm_ref);
          // weight area (h_m - h_s) n . n_p / |n| (weighted_point_gap).
          const S wg = compose<S::n_variables, 9>(
              {&area, &h_m, &h_s, &n.x, &n.y, &n.z, &np.x, &np.y, &np.z}, [&](const auto& y) {
                using L = std::decay_t<decltype(y[0])>;
                const V3<L> ny{y[3], y[4], y[5]}, py{y[6], y[7], y[8]};
                return weight * y[0] * (y[1] - y[2]) * dot(ny, py) / norm(ny);
              });
          add_weighted_packed(weighted, wg,
                              a != 0.0 ? ShapeJet(in.slave_type, slave_xi, a) : slave_jet, ms,
                              xs_ref);
        });
        continue;
      }
      for_each_point(polygon, rule, [&](const V2<S>& u, const S& area, double weight) {
        S s1 = 0.0, s2 = 0.0, m1 = 0.0, m2 = 0.0;
        if (!slave_valid || !master_valid ||
            !locate_on(slave_plane, us, slave_inverse, slave_linear, options.newton, u, s1, s2) ||
            !locate_on(master_plane, um, master_inverse, master_linear, options.newton, u, m1, m2))
          return;
        if constexpr (is_dual<S>) {
          shape_values_chain(in.slave_type, s1, s2, Ns);
          shape_values_chain(in.master_type, m1, m2, Nm);
        } else {
          facet_shape_values<S>(in.slave_type, s1, s2, Ns);
          facet_shape_values<S>(in.master_type, m1, m2, Nm);
        }
        const S wg = weighted_point_gap(ms, nn, hs, Ns, mm, hm, Nm, np, area, weight);
        // The modified basis N~ of dual multipliers on tri6/quad8 (modify_basis).
        if (a != 0.0)
          for (const auto& edge : mortar::edge_nodes(in.slave_type)) {
            const S edge_value = Ns[static_cast<std::size_t>(edge.node)];
            add_product(Ns[static_cast<std::size_t>(edge.v0)], edge_value, a);
            add_product(Ns[static_cast<std::size_t>(edge.v1)], edge_value, a);
            Ns[static_cast<std::size_t>(edge.node)] = edge_value * (1.0 - 2.0 * a);
          }
        for (std::size_t k = 0; k < ms; ++k) add_product(weighted[k], wg, Ns[k]);
      });
    }
  }
  if (!in.dual) {
    g = std::move(weighted);
    return;
  }
  // Phi_j = A_jk N~_k with A constant over the pair: sum w g N~_k first, apply A once.
  std::vector<S> A;
  dual_coefficients_of(in.slave_type, xs, a, A);
  for (std::size_t j = 0; j < ms; ++j)
    for (std::size_t k = 0; k < ms; ++k) add_product(g[j], A[j * ms + k], weighted[k]);
}

/// The Hessian path on SymHyper<9 n> (n slots per group: as many as the larger facet has
/// nodes), spread into the 81 variables of the callers.
template <int M>
void pair_gaps_quadratic_packed(const PairInput& in, const mortar::PairOptions& options,
                                std::vector<Hyper<quadratic_variables>>& g) {
  constexpr int n_slots = M / 9;
  std::vector<SymHyper<M>> packed;
  pair_gaps_quadratic_on(in, options, packed, n_slots);
  std::array<int, M> full;
  for (int v = 0; v < M; ++v) full[v] = v / (3 * n_slots) * 3 * quadratic_slots + v % (3 * n_slots);
  g.assign(packed.size(), Hyper<quadratic_variables>(0.0));
  for (std::size_t j = 0; j < packed.size(); ++j) {
    const SymHyper<M>& p = packed[j];
    auto& h = g[j];
    h.value = p.value;
    for (int i = 0; i < M; ++i) {
      h.gradient[full[i]] = p.gradient[i];
      for (int k = i; k < M; ++k)
        h.hessian[full[i] * quadratic_variables + full[k]] =
            h.hessian[full[k] * quadratic_variables + full[i]] = p.hessian[SymHyper<M>::at(i, k)];
    }
  }
}

/// The gaps of one pair of facets of which one at least is quadratic on S: values (double),
/// gradients (Dual<81>) or Hessians (Hyper<81>; computed on packed Hessians over the variables
/// the facets seed).
template <class S>
void pair_gaps_quadratic(const PairInput& in, const mortar::PairOptions& options,
                         std::vector<S>& g) {
  if constexpr (std::is_same_v<S, Hyper<quadratic_variables>>) {
    const int n = std::max(in.ns, in.nm);
    if (n <= 6)
      pair_gaps_quadratic_packed<54>(in, options, g);
    else if (n <= 8)
      pair_gaps_quadratic_packed<72>(in, options, g);
    else
      pair_gaps_quadratic_packed<81>(in, options, g);
  } else {
    pair_gaps_quadratic_on(in, options, g, quadratic_slots);
  }
}

/// The averaged unit normal of slave node `node` (side-local) on S over its ring's positions.
template <class Out>
void normal_of(const mortar::FacetSet& slaves, const mortar::NodeFacets& adjacency,
               local_index node, const std::vector<Eigen::Vector3d>& ring_x,
               const std::vector<local_index>& ring, Out& n) {
  using S = std::decay_t<decltype(n[0])>;
  std::vector<V3<S>> x(ring.size());
  for (std::size_t r = 0; r < ring.size(); ++r)
    x[r] = seeded<S>(ring_x[r], 3 * static_cast<int>(r));
  V3<S> sum;
  for (const auto f : adjacency.of(node)) {
    const auto nodes = slaves.facet_nodes(f);
    std::vector<V3<S>> fx(nodes.size());
    int here = -1;
    for (std::size_t k = 0; k < nodes.size(); ++k) {
      const auto slot = std::find(ring.begin(), ring.end(), nodes[k]) - ring.begin();
      fx[k] = x[static_cast<std::size_t>(slot)];
      if (nodes[k] == node) here = static_cast<int>(k);
    }
    sum = sum + facet_unit_normal(fx, slaves.types[static_cast<std::size_t>(f)], here);
  }
  const S length = norm(sum);
  SEAM_CHECK(value_of(length) > mortar::min_normal_sum, InputError, "slave node ", node,
             ": the normals of its facets cancel (the surface folds back onto itself)");
  n[0] = sum.x / length;
  n[1] = sum.y / length;
  n[2] = sum.z / length;
}

} // namespace

void detail::quadratic_pair_derivatives(const QuadraticPair& pair,
                                        const mortar::PairOptions& options, QuadraticKernel kernel,
                                        std::vector<double>& gap, std::vector<double>& gradient,
                                        std::vector<double>& hessian) {
  PairInput in;
  in.slave_type = pair.slave_type;
  in.master_type = pair.master_type;
  in.ns = static_cast<int>(pair.xs.size());
  in.nm = static_cast<int>(pair.xm.size());
  SEAM_CHECK(in.ns == fem::n_nodes(in.slave_type) && in.nm == fem::n_nodes(in.master_type) &&
                 pair.normals.size() == pair.xs.size(),
             InputError, "quadratic_pair_derivatives: node counts do not match the facet types");
  for (int k = 0; k < in.ns; ++k) {
    in.xs[static_cast<std::size_t>(k)] = pair.xs[static_cast<std::size_t>(k)];
    in.normal[static_cast<std::size_t>(k)] = pair.normals[static_cast<std::size_t>(k)];
  }
  for (int l = 0; l < in.nm; ++l)
    in.xm[static_cast<std::size_t>(l)] = pair.xm[static_cast<std::size_t>(l)];
  in.dual = pair.dual;
  constexpr auto n = static_cast<std::size_t>(quadratic_variables);
  if (kernel == QuadraticKernel::gradient) {
    std::vector<Dual<quadratic_variables>> g;
    pair_gaps_quadratic(in, options, g);
    gap.assign(g.size(), 0.0);
    gradient.assign(g.size() * n, 0.0);
    hessian.clear();
    for (std::size_t j = 0; j < g.size(); ++j) {
      gap[j] = g[j].value;
      std::copy(g[j].gradient.begin(), g[j].gradient.end(),
                gradient.begin() + static_cast<std::ptrdiff_t>(j * n));
    }
    return;
  }
  using H = Hyper<quadratic_variables>;
  std::vector<H> g;
  if (kernel == QuadraticKernel::packed)
    pair_gaps_quadratic(in, options, g);
  else
    pair_gaps_quadratic_on(in, options, g, quadratic_slots);
  gap.assign(g.size(), 0.0);
  gradient.assign(g.size() * n, 0.0);
  hessian.assign(g.size() * n * n, 0.0);
  for (std::size_t j = 0; j < g.size(); ++j) {
    gap[j] = g[j].value;
    std::copy(g[j].gradient.begin(), g[j].gradient.end(),
              gradient.begin() + static_cast<std::ptrdiff_t>(j * n));
    std::copy(g[j].hessian.begin(), g[j].hessian.end(),
              hessian.begin() + static_cast<std::ptrdiff_t>(j * n * n));
  }
}

void ContactInterface::gap_blocks_3d(std::span<const double> u, GapOrder requested,
                                     std::vector<GapBlock>& out,
                                     std::span<const char> hessian_rows) const {
  const auto& X = reference_x();
  const auto position = [&](std::int32_t node) {
    const auto i = static_cast<std::size_t>(node) * 3;
    return Eigen::Vector3d(X[i] + u[i], X[i + 1] + u[i + 1], X[i + 2] + u[i + 2]);
  };
  const mortar::FacetSet slaves = slave_set();
  const mortar::FacetSet masters = integration_master().facet_set();
  const mortar::NodeFacets& adjacency = slave_adjacency();
  const bool dual = options_.multiplier == mortar::Multiplier::dual;
  // The normal jets of the slave nodes met so far (side-local node of the slave set).
  std::map<local_index, NormalJet> jets;
  const auto jet_of = [&](local_index node, GapOrder need) -> const NormalJet& {
    auto it = jets.find(node);
    if (it != jets.end() && it->second.order >= need) return it->second;
    NormalJet jet;
    jet.order = need;
    std::vector<local_index> ring;
    for (const auto f : adjacency.of(node))
      for (const auto k : slaves.facet_nodes(f))
        if (std::find(ring.begin(), ring.end(), k) == ring.end()) ring.push_back(k);
    SEAM_CHECK(static_cast<int>(ring.size()) <= max_ring_nodes_quadratic, InputError, "interface '",
               name_, "': energy-momentum contact: a slave node has more than ",
               max_ring_nodes_quadratic, " nodes on its facets");
    std::vector<Eigen::Vector3d> ring_x;
    for (const auto k : ring) {
      const auto mesh_node = slave_.mesh_nodes[static_cast<std::size_t>(k)];
      jet.ring.push_back(mesh_node);
      ring_x.push_back(position(mesh_node));
    }
    const auto nr = static_cast<std::size_t>(3 * ring.size());
    if (need == GapOrder::value) {
      std::array<double, 3> n;
      normal_of(slaves, adjacency, node, ring_x, ring, n);
      jet.value = n;
    } else {
      // 48 variables for up to 16 ring nodes (linear facets), 81 beyond (quadratic).
      const auto derivatives = [&]<int RV>() {
        const auto take = [&](const auto& n) {
          jet.gradient.resize(3 * nr);
          for (std::size_t a = 0; a < 3; ++a) {
            jet.value[a] = n[a].value;
            for (std::size_t v = 0; v < nr; ++v) jet.gradient[a * nr + v] = n[a].gradient[v];
          }
        };
        if (need == GapOrder::gradient) {
          std::array<Dual<RV>, 3> n;
          normal_of(slaves, adjacency, node, ring_x, ring, n);
          take(n);
          return;
        }
        // Packed Hessians (sym_hyper.hpp): the same numbers for half the memory traffic.
        std::vector<SymHyper<RV>> n(3);
        normal_of(slaves, adjacency, node, ring_x, ring, n);
        take(n);
        jet.hessian.resize(3 * nr * nr);
        for (std::size_t a = 0; a < 3; ++a)
          for (std::size_t v = 0; v < nr; ++v)
            for (std::size_t w = 0; w < nr; ++w)
              jet.hessian[(a * nr + v) * nr + w] =
                  n[a].second(static_cast<int>(v), static_cast<int>(w));
      };
      if (ring.size() <= static_cast<std::size_t>(max_ring_nodes))
        derivatives.template operator()<ring_variables>();
      else
        derivatives.template operator()<quadratic_ring_variables>();
    }
    return jets.insert_or_assign(node, std::move(jet)).first->second;
  };

  for (const auto f : owned_)
    for (const auto& pair : pairs_of(f)) {
      const local_index sf = slave_index(pair.slave), mf = integration_facet(pair.master);
      const auto sn = slaves.facet_nodes(sf);
      const auto mn = masters.facet_nodes(mf);
      GapOrder order = requested;
      if (order == GapOrder::hessian && !hessian_rows.empty() &&
          std::none_of(sn.begin(), sn.end(), [&](local_index k) {
            return hessian_rows[static_cast<std::size_t>(k)] != 0;
          }))
        order = GapOrder::gradient;
      PairInput in;
      in.ns = static_cast<int>(sn.size());
      in.nm = static_cast<int>(mn.size());
      in.slave_type = slaves.types[static_cast<std::size_t>(sf)];
      in.master_type = masters.types[static_cast<std::size_t>(mf)];
      in.dual = dual;
      // Linear facets on both sides: the kernel above on 36 variables; else the quadratic one
      // on 81 (slave positions, slave normals, master positions: 3 x 9 slots each).
      const bool quadratic = fem::order(in.slave_type) > 1 || fem::order(in.master_type) > 1;
      const int n_slots = quadratic ? quadratic_slots : 4;
      const int pv = 9 * n_slots, n_offset = 3 * n_slots, m_offset = 6 * n_slots;
      GapBlock b;
      b.dim = 3;
      // Slots: the slave facet's nodes, the master facet's nodes, then the other ring nodes.
      std::vector<std::int32_t> slots;
      const auto slot_of = [&](std::int32_t mesh_node) {
        const auto it = std::find(slots.begin(), slots.end(), mesh_node);
        if (it != slots.end()) return static_cast<int>(it - slots.begin());
        slots.push_back(mesh_node);
        return static_cast<int>(slots.size()) - 1;
      };
      std::array<int, mortar::max_facet_nodes> slave_slot{}, master_slot{};
      for (std::size_t k = 0; k < sn.size(); ++k) {
        const auto node = slave_.mesh_nodes[static_cast<std::size_t>(sn[k])];
        slave_slot[k] = slot_of(node);
        in.xs[k] = position(node);
        in.normal[k] = Eigen::Vector3d(jet_of(sn[k], order).value.data());
      }
      for (std::size_t l = 0; l < mn.size(); ++l) {
        const auto node = integration_node(mn[l]);
        master_slot[l] = slot_of(node);
        in.xm[l] = position(node);
      }
      // The frame of the slave facet's first node (as integrate_pair's callers).
      const Eigen::Vector3d origin = in.xs[0];
      for (int k = 0; k < in.ns; ++k) in.xs[static_cast<std::size_t>(k)] -= origin;
      for (int l = 0; l < in.nm; ++l) in.xm[static_cast<std::size_t>(l)] -= origin;
      std::array<std::vector<int>, mortar::max_facet_nodes> ring_slots;
      if (order != GapOrder::value)
        for (std::size_t k = 0; k < sn.size(); ++k)
          for (const auto node : jet_of(sn[k], order).ring) ring_slots[k].push_back(slot_of(node));
      const auto nv = static_cast<std::size_t>(3 * slots.size());
      b.slave.assign(sn.begin(), sn.end());
      b.dofs.resize(slots.size());
      for (std::size_t s = 0; s < slots.size(); ++s)
        b.dofs[s] = static_cast<std::int64_t>(slots[s]) * 3;
      b.gap.assign(sn.size(), 0.0);
      // y -> slot variables: J (pv x nv) of positions and normals.
      Eigen::MatrixXd J;
      if (order != GapOrder::value) {
        J = Eigen::MatrixXd::Zero(pv, static_cast<Eigen::Index>(nv));
        for (std::size_t k = 0; k < sn.size(); ++k) {
          const NormalJet& jet = jet_of(sn[k], order);
          const std::size_t nr = 3 * jet.ring.size();
          for (int a = 0; a < 3; ++a) {
            J(3 * static_cast<int>(k) + a, 3 * slave_slot[k] + a) = 1.0;
            for (std::size_t r = 0; r < jet.ring.size(); ++r)
              for (int c = 0; c < 3; ++c)
                J(n_offset + 3 * static_cast<int>(k) + a, 3 * ring_slots[k][r] + c) =
                    jet.gradient[static_cast<std::size_t>(a) * nr + 3 * r +
                                 static_cast<std::size_t>(c)];
          }
        }
        for (std::size_t l = 0; l < mn.size(); ++l)
          for (int a = 0; a < 3; ++a)
            J(m_offset + 3 * static_cast<int>(l) + a, 3 * master_slot[l] + a) = 1.0;
      }
      // The kernel's gaps with their derivatives in the pair variables y: gy (pv per slave
      // node) and Hy (pv x pv, row-major).
      std::vector<double> gy, Hy;
      // The linear kernel's gaps on S (4 slots).
      const auto linear = [&]<class S>() {
        std::array<S, 4> g4;
        pair_gaps(in, options_.pair, g4);
        return std::vector<S>(g4.begin(), g4.begin() + in.ns);
      };
      const auto take = [&]<class S>(const std::vector<S>& g) {
        gy.assign(sn.size() * static_cast<std::size_t>(pv), 0.0);
        if constexpr (is_hyper<S>) Hy.assign(sn.size() * static_cast<std::size_t>(pv * pv), 0.0);
        for (std::size_t j = 0; j < sn.size(); ++j) {
          b.gap[j] = g[j].value;
          std::copy_n(g[j].gradient.begin(), pv,
                      gy.begin() + static_cast<std::ptrdiff_t>(j * static_cast<std::size_t>(pv)));
          if constexpr (is_hyper<S>)
            std::copy_n(g[j].hessian.begin(), pv * pv,
                        Hy.begin() +
                            static_cast<std::ptrdiff_t>(j * static_cast<std::size_t>(pv * pv)));
        }
      };
      bool nonzero = false;
      if (order == GapOrder::value) {
        std::vector<double> g;
        if (quadratic)
          pair_gaps_quadratic(in, options_.pair, g);
        else
          g = linear.template operator()<double>();
        for (std::size_t j = 0; j < sn.size(); ++j) {
          b.gap[j] = g[j];
          nonzero = nonzero || g[j] != 0.0;
        }
      } else if (order == GapOrder::gradient) {
        if (quadratic) {
          std::vector<Dual<quadratic_variables>> g;
          pair_gaps_quadratic(in, options_.pair, g);
          take(g);
        } else {
          take(linear.template operator()<Dual<pair_variables>>());
        }
      } else {
        if (quadratic) {
          std::vector<Hyper<quadratic_variables>> g;
          pair_gaps_quadratic(in, options_.pair, g);
          take(g);
        } else {
          take(linear.template operator()<Hyper<pair_variables>>());
        }
      }
      if (order != GapOrder::value) {
        b.gradient.assign(sn.size() * nv, 0.0);
        if (order == GapOrder::hessian) b.hessian.assign(sn.size() * nv * nv, 0.0);
        for (std::size_t j = 0; j < sn.size(); ++j) {
          const auto gyj =
              Eigen::Map<const Eigen::VectorXd>(gy.data() + j * static_cast<std::size_t>(pv), pv);
          const Eigen::VectorXd gx = J.transpose() * gyj;
          for (std::size_t v = 0; v < nv; ++v) {
            b.gradient[j * nv + v] = gx(static_cast<Eigen::Index>(v));
            nonzero = nonzero || gx(static_cast<Eigen::Index>(v)) != 0.0;
          }
          if (order != GapOrder::hessian) continue;
          const auto Hyj = Eigen::Map<
              const Eigen::Matrix<double, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>>(
              Hy.data() + j * static_cast<std::size_t>(pv * pv), pv, pv);
          Eigen::MatrixXd Hx = J.transpose() * Hyj * J;
          // sum_i dg/dn_i H(n_i): the normals' curvature in the ring positions.
          const bool curvature = detail::gap_hessian_terms == detail::GapHessianTerms::all;
          if (detail::gap_hessian_terms == detail::GapHessianTerms::none) Hx.setZero();
          for (std::size_t k = 0; k < (curvature ? sn.size() : 0); ++k) {
            const NormalJet& jet = jet_of(sn[k], order);
            const std::size_t nr = 3 * jet.ring.size();
            for (std::size_t a = 0; a < 3; ++a) {
              const double weight =
                  gyj(static_cast<Eigen::Index>(static_cast<std::size_t>(n_offset) + 3 * k + a));
              if (weight == 0.0) continue;
              for (std::size_t v = 0; v < nr; ++v)
                for (std::size_t w = 0; w < nr; ++w)
                  Hx(3 * ring_slots[k][v / 3] + static_cast<int>(v % 3),
                     3 * ring_slots[k][w / 3] + static_cast<int>(w % 3)) +=
                      weight * jet.hessian[(a * nr + v) * nr + w];
            }
          }
          for (std::size_t v = 0; v < nv; ++v)
            for (std::size_t w = 0; w < nv; ++w)
              b.hessian[(j * nv + v) * nv + w] =
                  Hx(static_cast<Eigen::Index>(v), static_cast<Eigen::Index>(w));
        }
      }
      if (!nonzero) continue; // no overlap: the pair adds nothing
      out.push_back(std::move(b));
    }
}

} // namespace seam::contact
