#pragma once
// Pieces of the mixed-mode linearized 3D pair kernel (linearization_pair_3d.cpp): the slave
// piece with its auxiliary plane in dual numbers, master pieces, the pre-checks of
// integration_3d.cpp, the cell rule, and the per-output adjoint scratch.
#include <algorithm>
#include <array>
#include <cmath>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/mortar/linearization.hpp"
#include "seam/mortar/linearization_clip.hpp"
#include "seam/mortar/linearization_pair.hpp"
#include "seam/mortar/pair_integration_detail.hpp"

namespace seam::mortar::ad::pair3d {

using Eigen::Vector2d;
using Eigen::Vector3d;
using PlaneDual = Dual<12>; ///< over the coordinates of a slave piece's (<= 4) vertices
using ClipDual = Dual<16>;  ///< over the in-plane coordinates of slave then master piece vertices
inline constexpr int clip_master_offset = 8;
inline constexpr int max_nodes = max_facet_nodes;
inline constexpr int max_outputs = 2 * max_nodes * max_nodes + max_nodes;
inline constexpr int max_parameters = 9 * max_nodes; ///< 6 n_s + 3 n_m
inline constexpr int cell_parameters = 7;            ///< cell vertices a, b, c in the plane, area

struct SlavePiece {
  SubFacet sub;
  std::array<Vector2d, 4> xi;
  std::array<Vector<PlaneDual, 3>, 3> e; ///< t1, t2, n_aux
  Vector<PlaneDual, 3> origin;
  geometry::Plane plane;
  bool degenerate = true;
};

inline std::array<Vector2d, 4> reference_of(fem::CellType type, const SubFacet& sub) {
  std::array<Vector2d, 4> xi;
  xi.fill(Vector2d::Zero());
  if (fem::order(type) > 1) {
    const double* reference = fem::reference_nodes(type).data();
    for (int v = 0; v < sub.n_vertices; ++v) {
      const int node = sub.nodes[static_cast<std::size_t>(v)];
      xi[static_cast<std::size_t>(v)] = {reference[2 * node], reference[2 * node + 1]};
    }
  }
  return xi;
}

// Piece centre (vertex mean) and unit normal (triangle: edge cross product; bilinear quad:
// cross product of the diagonals), then the plane of geometry::make_plane, all in dual
// numbers over the piece vertices.
inline SlavePiece make_slave_piece(const Facet<3>& facet, const SubFacet& sub) {
  SlavePiece p;
  p.sub = sub;
  p.xi = reference_of(facet.type, sub);
  std::array<Vector<PlaneDual, 3>, 4> x;
  Vector<PlaneDual, 3> center = Vector<PlaneDual, 3>::Zero();
  for (int v = 0; v < sub.n_vertices; ++v) {
    const int node = sub.nodes[static_cast<std::size_t>(v)];
    for (int a = 0; a < 3; ++a)
      x[static_cast<std::size_t>(v)](a) = PlaneDual::variable(facet.x(a, node), 3 * v + a);
    center += x[static_cast<std::size_t>(v)];
  }
  center /= static_cast<double>(sub.n_vertices);
  const Vector<PlaneDual, 3> n = sub.n_vertices == 3 ? cross3<PlaneDual>(x[1] - x[0], x[2] - x[0])
                                                     : cross3<PlaneDual>(x[2] - x[0], x[3] - x[1]);
  const PlaneDual length = norm(n);
  if (!(length.value > 0.0)) return p;
  p.degenerate = false;
  const PlaneT<PlaneDual> plane = make_plane_t<PlaneDual>(center, Vector<PlaneDual, 3>(n / length));
  p.e = {plane.t1, plane.t2, plane.normal};
  p.origin = plane.origin;
  p.plane.origin = values(p.origin);
  p.plane.t1 = values(plane.t1);
  p.plane.t2 = values(plane.t2);
  p.plane.normal = values(plane.normal);
  return p;
}

struct MasterPiece {
  SubFacet sub;
  std::array<Vector2d, 4> xi;
  Vector3d normal = Vector3d::Zero(); ///< unit; zero if degenerate
};

inline MasterPiece make_master_piece(const Facet<3>& facet, const SubFacet& sub) {
  MasterPiece p;
  p.sub = sub;
  p.xi = reference_of(facet.type, sub);
  const auto x = [&](int v) { return facet.x.col(sub.nodes[static_cast<std::size_t>(v)]); };
  const Vector3d n = sub.n_vertices == 3 ? Vector3d((x(1) - x(0)).cross(x(2) - x(0)))
                                         : Vector3d((x(2) - x(0)).cross(x(3) - x(1)));
  const double length = n.norm();
  if (length > 0.0) p.normal = n / length;
  return p;
}

inline double longest_corner_edge_squared(const Facet<3>& facet) {
  const int n = fem::n_vertices(facet.type);
  double longest = (facet.x.col(0) - facet.x.col(n - 1)).squaredNorm();
  for (int i = 0; i + 1 < n; ++i)
    longest = std::max(longest, (facet.x.col(i + 1) - facet.x.col(i)).squaredNorm());
  return longest;
}

inline Vector3d center_position(const Facet<3>& facet) {
  const auto c = reference_center(facet.type);
  NodalVector N = NodalVector::Zero();
  mortar::detail::shape_values(facet.type, Vector2d(c[0], c[1]), N);
  return facet.x.leftCols(facet.n_nodes) * N.head(facet.n_nodes);
}

struct Box {
  Vector2d lo, hi;
  bool misses(const Box& o) const {
    return (lo.array() > o.hi.array()).any() || (o.lo.array() > hi.array()).any();
  }
};

template <class P> Box box_of(const P& points, int n) {
  Box b{points(0), points(0)};
  for (int i = 1; i < n; ++i) {
    b.lo = b.lo.cwiseMin(points(i));
    b.hi = b.hi.cwiseMax(points(i));
  }
  return b;
}

// The per-output adjoint accumulators (thread-local scratch, so no heap traffic per pair).
struct Adjoints {
  int n_outputs = 0;
  int width = 0; ///< parameters per output: U_s (2 n_s), U_m (2 n_m), H_s, H_m, n~ (3 n_s)
  std::array<double, max_outputs * max_parameters> parameters;
  std::array<double, max_outputs * max_nodes> coefficients; ///< d o / dA_{j(o) k}
  std::array<double, max_outputs * 16> clip;
  std::array<double, max_outputs * cell_parameters> cell;
};

// Cell rule: barycentric points with weights summing to 1 (for_each_cell_point of the
// integration).
struct CellRule {
  int n_points = 0;
  std::array<std::array<double, 4>, 64> points; ///< b0, b1, b2, weight
  explicit CellRule(int degree) {
    if (degree <= 5) {
      using Rule = geometry::TriangleRule7;
      n_points = Rule::n_points;
      for (int q = 0; q < n_points; ++q) {
        const auto& b = Rule::barycentric[static_cast<std::size_t>(q)];
        points[static_cast<std::size_t>(q)] = {b[0], b[1], b[2],
                                               Rule::weights[static_cast<std::size_t>(q)]};
      }
      return;
    }
    const fem::QuadratureRule rule = fem::quadrature(fem::CellType::tri3, degree);
    SEAM_CHECK(rule.n_points <= 64, InputError, "cell quadrature degree ", degree,
               " has too many points for the linearized kernel");
    n_points = rule.n_points;
    for (int q = 0; q < n_points; ++q) {
      const double xi = rule.points[static_cast<std::size_t>(2 * q)];
      const double eta = rule.points[static_cast<std::size_t>(2 * q + 1)];
      points[static_cast<std::size_t>(q)] = {1.0 - xi - eta, xi, eta,
                                             2.0 * rule.weights[static_cast<std::size_t>(q)]};
    }
  }
};

// Everything the point loop of one pair needs.
struct PairState {
  const SlaveFacet<3>* slave;
  const Facet<3>* master;
  const CoefficientLinearization* coefficients;
  bool dual;
  double modification;
  PairLinearization* out;
  PairContribution* values; ///< summed over the pair
  Adjoints* adj;
};

// Gradient row of output o: M_jl (o = j n_m + l), g~_j (o = n_s n_m + j), standard D_jk
// (o = n_s n_m + n_s + j n_s + k).
inline double* output_row(PairLinearization& out, int o) {
  const int ns = out.n_slave, nm = out.n_master;
  const auto nv = static_cast<std::size_t>(out.n_variables);
  if (o < ns * nm) return out.M_gradient.data() + static_cast<std::size_t>(o) * nv;
  if (o < ns * nm + ns) return out.gap_gradient.data() + static_cast<std::size_t>(o - ns * nm) * nv;
  return out.D_gradient.data() + static_cast<std::size_t>(o - ns * nm - ns) * nv;
}

inline void prepare_output(PairLinearization& out, int dim, int ns, int nm) {
  out.dim = dim;
  out.n_slave = ns;
  out.n_master = nm;
  out.n_variables = pair_variable_count(dim, ns, nm);
  out.values = mortar::detail::empty_contribution(ns, nm);
  const auto nv = static_cast<std::size_t>(out.n_variables);
  out.D_gradient.assign(static_cast<std::size_t>(ns * ns) * nv, 0.0);
  out.M_gradient.assign(static_cast<std::size_t>(ns * nm) * nv, 0.0);
  out.gap_gradient.assign(static_cast<std::size_t>(ns) * nv, 0.0);
}

} // namespace seam::mortar::ad::pair3d
