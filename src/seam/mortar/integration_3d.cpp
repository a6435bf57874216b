// 3D segment-based mortar integration of a surface pair (Puso & Laursen 2004; Popp et al.
// 2010; ALGORITHMS.md §2): per linear piece of the slave an auxiliary plane, projection of
// slave and master piece vertices into it, clipping, triangulation into integration cells,
// a 7-point degree-5 rule per cell and back-projection of every point onto both facets.
//
// The back-projection runs in the plane (pair_integration_detail.hpp): closed form for linear
// facets, Newton from the containing piece's inverse for quadratic ones. The gap along the
// interpolated slave normal n follows from the heights above the plane: both projections of a
// plane point differ only along the plane normal n_p, so x_m - x_s = (h_m - h_s) n_p.
#include <algorithm>
#include <array>
#include <cmath>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/mortar/pair_integration.hpp"
#include "seam/mortar/pair_integration_detail.hpp"

namespace seam::mortar {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A linear piece of a facet in space, with the reference coordinates of its vertices in the
// parent facet (to map piece coordinates to parent ones; only needed for quadratic facets).
// Members are set by make_piece; nothing is zero-filled first, as this runs once per pair.
struct Piece {
  int n_vertices;
  std::array<int, 4> nodes;
  std::array<Vector2d, 4> xi;
  Vector3d center;
  Vector3d normal; ///< unit; zero if the piece is degenerate
};

Piece make_piece(const Facet<3>& facet, const SubFacet& sub) {
  Piece piece;
  piece.n_vertices = sub.n_vertices;
  piece.nodes = sub.nodes;
  std::array<Vector3d, 4> x;
  for (int v = 0; v < sub.n_vertices; ++v) {
    x[static_cast<std::size_t>(v)] = facet.x.col(sub.nodes[static_cast<std::size_t>(v)]);
  }
  if (fem::order(facet.type) > 1) {
    const double* reference = fem::reference_nodes(facet.type).data();
    for (int v = 0; v < sub.n_vertices; ++v) {
      const int node = sub.nodes[static_cast<std::size_t>(v)];
      piece.xi[static_cast<std::size_t>(v)] = {reference[2 * node], reference[2 * node + 1]};
    }
  } else {
    piece.xi.fill(Vector2d::Zero());
  }
  // Triangle: the constant normal. Bilinear quad: x_xi x x_eta at its centre is parallel to
  // the cross product of the diagonals, and the centre is the vertex mean (ALGORITHMS.md §2,
  // step 2, for a linear facet: x_c = x(xi_c), n_aux = n(xi_c)).
  Vector3d n;
  if (sub.n_vertices == 3) {
    piece.center = (x[0] + x[1] + x[2]) / 3.0;
    n = (x[1] - x[0]).cross(x[2] - x[0]);
  } else {
    piece.center = 0.25 * (x[0] + x[1] + x[2] + x[3]);
    n = (x[2] - x[0]).cross(x[3] - x[1]);
  }
  const double length = n.norm();
  piece.normal = length > 0.0 ? Vector3d(n / length) : Vector3d::Zero();
  return piece;
}

double longest_corner_edge_squared(const Facet<3>& facet) {
  const int n = fem::n_vertices(facet.type);
  double longest = (facet.x.col(0) - facet.x.col(n - 1)).squaredNorm();
  for (int i = 0; i + 1 < n; ++i) {
    longest = std::max(longest, (facet.x.col(i + 1) - facet.x.col(i)).squaredNorm());
  }
  return longest;
}

// x(xi_c) at the reference centre: the vertex mean for tri3 and quad4.
Vector3d center_position(const Facet<3>& facet) {
  if (fem::order(facet.type) == 1) {
    const int n = facet.n_nodes;
    Vector3d sum = facet.x.col(0);
    for (int k = 1; k < n; ++k) sum += facet.x.col(k);
    return sum / n;
  }
  const auto c = reference_center(facet.type);
  NodalVector N = NodalVector::Zero();
  detail::shape_values(facet.type, Vector2d(c[0], c[1]), N);
  return facet.x * N;
}

// The piece polygon in the plane with its bounding box; its inverse map is set up only once
// a clip turns out non-empty. Built in place and never copied.
struct PlanarPiece {
  const Piece& piece;
  geometry::Polygon polygon;
  Vector2d lo, hi;
  detail::PieceInverse inverse;
  bool has_inverse = false;
  bool valid = false;

  PlanarPiece(const Piece& p, const detail::PlanarFacet& f) : piece(p) {
    for (int v = 0; v < piece.n_vertices; ++v) {
      polygon.push_back(f.u.col(piece.nodes[static_cast<std::size_t>(v)]));
    }
    lo = hi = polygon[0];
    for (int v = 1; v < piece.n_vertices; ++v) {
      lo = lo.cwiseMin(polygon[v]);
      hi = hi.cwiseMax(polygon[v]);
    }
  }
  PlanarPiece(const PlanarPiece&) = delete;
  PlanarPiece& operator=(const PlanarPiece&) = delete;

  void set_inverse(bool linear_facet) {
    if (has_inverse) return;
    std::array<Vector2d, 4> u;
    for (int v = 0; v < polygon.size(); ++v) u[static_cast<std::size_t>(v)] = polygon[v];
    valid = inverse.set(polygon.size(), u, piece.xi, linear_facet);
    has_inverse = true;
  }
};

// Whether the bounding box of all nodes of a facet in the plane meets the piece's box.
bool boxes_overlap(const PlanarPiece& piece, const detail::PlanarFacet& f) {
  Vector2d lo = f.u.col(0), hi = f.u.col(0);
  for (int k = 1; k < f.n_nodes; ++k) {
    lo = lo.cwiseMin(f.u.col(k));
    hi = hi.cwiseMax(f.u.col(k));
  }
  return !((lo.array() > piece.hi.array()).any() || (piece.lo.array() > hi.array()).any());
}

// Reference coordinates on the parent facet of the plane point u inside `piece`.
template <bool Linear>
[[gnu::always_inline]] inline bool locate(const detail::PlanarFacet& f, const PlanarPiece& piece,
                                          const Vector2d& u, const geometry::NewtonOptions& newton,
                                          Vector2d& xi) {
  if (!piece.valid || !piece.inverse.parent_coordinates(u, xi)) return false;
  if constexpr (Linear) {
    return true;
  } else {
    return detail::newton_in_plane(f, u, xi, newton);
  }
}

// A triangle rule in barycentric coordinates with weights summing to 1: the 7-point degree-5
// rule, or seam::fem's reference triangle rule (weights summing to 1/2) of a higher degree.
struct CellRule {
  int n_points = 0;
  const double* points = nullptr; ///< fem rule: (xi, eta) pairs
  const double* weights = nullptr;
  bool fem_rule = false;

  explicit CellRule(int degree) {
    if (degree <= 5) {
      n_points = geometry::TriangleRule7::n_points;
      weights = geometry::TriangleRule7::weights.data();
    } else {
      const fem::QuadratureRule rule = fem::quadrature(fem::CellType::tri3, degree);
      n_points = rule.n_points;
      points = rule.points.data();
      weights = rule.weights.data();
      fem_rule = true;
    }
  }
  // Barycentric coordinates and weight of point q.
  void point(int q, double& b0, double& b1, double& b2, double& w) const {
    const auto i = static_cast<std::size_t>(q);
    if (!fem_rule) {
      const auto& b = geometry::TriangleRule7::barycentric[i];
      b0 = b[0];
      b1 = b[1];
      b2 = b[2];
      w = weights[i];
      return;
    }
    b1 = points[2 * i];
    b2 = points[2 * i + 1];
    b0 = 1.0 - b1 - b2;
    w = 2.0 * weights[i];
  }
};

constexpr fem::CellType linear_type(int n_nodes) {
  return n_nodes == 3 ? fem::CellType::tri3 : fem::CellType::quad4;
}

// What the integration points of one pair need besides the slave facet.
struct PairGeometry {
  const geometry::Plane* plane;
  const detail::PlanarFacet* slave_plane;
  const detail::PlanarFacet* master_plane;
  const PlanarPiece* slave_piece;
  const PlanarPiece* master_piece;
  const CellRule* rule;
  const geometry::NewtonOptions* newton;
};

// The integration points of the cells of one clip polygon, added to c. NS and NM are the node
// counts of slave and master when both facets are linear (3 or 4), so that the per-point
// loops have fixed lengths; 0 means quadratic facets with the counts taken at run time.
template <int NS, int NM>
void integrate_cells(const SlaveFacet<3>& slave, const Facet<3>& master,
                     const geometry::TriangleList& cells, const PairGeometry& g,
                     PairContribution& c) {
  constexpr bool linear = NS > 0;
  constexpr int max_s = linear ? NS : max_facet_nodes;
  constexpr int max_m = linear ? NM : max_facet_nodes;
  const int ns = linear ? NS : slave.facet.n_nodes;
  const int nm = linear ? NM : master.n_nodes;
  const bool dual = slave.basis.multiplier == Multiplier::dual;
  const double a = slave.basis.modification;
  const Vector3d& plane_normal = g.plane->normal;

  // Local sums with compile-time sizes; rows and columns past the node counts stay zero.
  using SlaveVector = Eigen::Matrix<double, max_s, 1>;
  Eigen::Matrix<double, max_s, max_m> M = Eigen::Matrix<double, max_s, max_m>::Zero();
  Eigen::Matrix<double, max_s, max_s> D = Eigen::Matrix<double, max_s, max_s>::Zero();
  SlaveVector gap = SlaveVector::Zero();
  SlaveVector row_sums = SlaveVector::Zero();
  Eigen::Matrix<double, max_s, max_s> A = Eigen::Matrix<double, max_s, max_s>::Zero();
  if (dual) A.topLeftCorner(ns, ns) = slave.basis.A;
  NodalVector Ns = NodalVector::Zero();
  NodalVector Nm = NodalVector::Zero();
  NodalVector N_tilde = NodalVector::Zero();

  // Points go in batches: first all back-projections of a batch, then the evaluation. The
  // back-projections are short independent chains of square roots and divisions, which the
  // processor overlaps when they follow each other.
  constexpr int batch = 8;
  std::array<Vector2d, batch> xi_s, xi_m;
  std::array<double, batch> w;
  std::array<bool, batch> located;
  for (const geometry::Triangle2& cell : cells) {
    const double cell_area = cell.area();
    for (int first = 0; first < g.rule->n_points; first += batch) {
      const int n_batch = std::min(batch, g.rule->n_points - first);
      for (int i = 0; i < n_batch; ++i) {
        const auto b = static_cast<std::size_t>(i);
        double b0, b1, b2, weight;
        g.rule->point(first + i, b0, b1, b2, weight);
        w[b] = weight * cell_area;
        const Vector2d u = b0 * cell.a + b1 * cell.b + b2 * cell.c;
        located[b] = locate<linear>(*g.slave_plane, *g.slave_piece, u, *g.newton, xi_s[b]) &&
                     locate<linear>(*g.master_plane, *g.master_piece, u, *g.newton, xi_m[b]);
      }
      for (int i = 0; i < n_batch; ++i) {
        const auto b = static_cast<std::size_t>(i);
        if (!located[b]) {
          ++c.n_projection_failures;
          continue;
        }
        detail::shape_values(linear ? linear_type(NS) : slave.facet.type, xi_s[b], Ns);
        detail::shape_values(linear ? linear_type(NM) : master.type, xi_m[b], Nm);
        Vector3d n = Vector3d::Zero();
        double h_s = 0.0, h_m = 0.0;
        for (int k = 0; k < ns; ++k) {
          n += Ns(k) * slave.normals.col(k);
          h_s += g.slave_plane->height(k) * Ns(k);
          N_tilde(k) = Ns(k);
        }
        for (int l = 0; l < nm; ++l) h_m += g.master_plane->height(l) * Nm(l);
        if (a != 0.0) modify_basis(slave.facet.type, a, N_tilde.data());
        const auto N_slave = N_tilde.template head<max_s>();
        const SlaveVector Phi = dual ? SlaveVector(A * N_slave) : SlaveVector(N_slave);
        const double point_gap = (h_m - h_s) * n.dot(plane_normal) / n.norm();
        // detail::accumulate_point column by column: M_jl += w Phi_j N_l; with dual
        // multipliers D_jj gets the row sums of the same products, which keeps
        // sum_k D_jk = sum_l M_jl to round-off; standard: D_jk += w Phi_j N~_k.
        const SlaveVector wPhi = w[b] * Phi;
        for (int l = 0; l < nm; ++l) {
          const SlaveVector product = wPhi * Nm(l);
          M.col(l) += product;
          if (dual) row_sums += product;
        }
        if (!dual) {
          for (int k = 0; k < ns; ++k) D.col(k) += wPhi * N_tilde(k);
        }
        gap += wPhi * point_gap;
      }
    }
  }
  if (dual) D.diagonal() += row_sums;
  c.M.topLeftCorner(ns, nm) += M.topLeftCorner(ns, nm);
  c.D.topLeftCorner(ns, ns) += D.topLeftCorner(ns, ns);
  c.weighted_gap.head(ns) += gap.head(ns);
}

using CellIntegrator = void (*)(const SlaveFacet<3>&, const Facet<3>&,
                                const geometry::TriangleList&, const PairGeometry&,
                                PairContribution&);

CellIntegrator cell_integrator(fem::CellType slave, fem::CellType master) {
  using fem::CellType;
  const bool s3 = slave == CellType::tri3, s4 = slave == CellType::quad4;
  const bool m3 = master == CellType::tri3, m4 = master == CellType::quad4;
  if (s3 && m3) return &integrate_cells<3, 3>;
  if (s3 && m4) return &integrate_cells<3, 4>;
  if (s4 && m3) return &integrate_cells<4, 3>;
  if (s4 && m4) return &integrate_cells<4, 4>;
  return &integrate_cells<0, 0>;
}

} // namespace

PairContribution integrate_pair(const SlaveFacet<3>& slave, const Facet<3>& master,
                                const PairOptions& options) {
  const Facet<3>& s = slave.facet;
  PairContribution c = detail::empty_contribution(s.n_nodes, master.n_nodes);

  // Centre distance against the reach, both squared.
  const double factor = options.max_center_distance_factor;
  const double reach_squared =
      factor * factor *
      std::max(longest_corner_edge_squared(s), longest_corner_edge_squared(master));
  if ((center_position(s) - center_position(master)).squaredNorm() > reach_squared) return c;

  const auto master_subfacets = linear_subfacets(master.type);
  std::array<Piece, 5> master_pieces; // made up to master_subfacets.size() once needed
  bool master_pieces_made = false;

  const bool slave_linear = fem::order(s.type) == 1;
  const bool master_linear = fem::order(master.type) == 1;
  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree
                     : slave_linear && master_linear    ? 5
                                                        : 8;
  const CellRule rule(degree);
  const CellIntegrator integrate_cells_of = cell_integrator(s.type, master.type);
  for (const SubFacet& slave_sub : linear_subfacets(s.type)) {
    const Piece sp = make_piece(s, slave_sub);
    if (sp.normal.isZero()) continue;
    const geometry::Plane plane = geometry::make_plane(sp.center, sp.normal);
    const detail::PlanarFacet slave_plane(s, plane);
    PlanarPiece slave_piece(sp, slave_plane);
    const detail::PlanarFacet master_plane(master, plane);
    // Every master piece lies in the bounding box of the master nodes: if that misses the
    // slave piece, so does every clip. Most candidates that do not overlap stop here.
    if (!boxes_overlap(slave_piece, master_plane)) continue;
    if (!master_pieces_made) {
      for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
        master_pieces[i] = make_piece(master, master_subfacets[i]);
      }
      master_pieces_made = true;
    }
    for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
      const Piece& mp = master_pieces[i];
      // The master must face the slave (ALGORITHMS.md §2, step 1).
      if (!(mp.normal.dot(plane.normal) < -1e-12)) continue;
      PlanarPiece master_piece(mp, master_plane);
      // Disjoint bounding boxes: the clip would be empty.
      if ((master_piece.lo.array() > slave_piece.hi.array()).any() ||
          (slave_piece.lo.array() > master_piece.hi.array()).any())
        continue;
      const geometry::Polygon clip =
          geometry::clip_polygons(slave_piece.polygon, master_piece.polygon, options.clip);
      if (clip.empty()) continue;
      const geometry::TriangleList cells = geometry::triangulate_fan(clip);
      c.n_cells += cells.size();
      c.area += geometry::area(clip);
      slave_piece.set_inverse(slave_linear);
      master_piece.set_inverse(master_linear);
      const PairGeometry geometry{&plane,        &slave_plane, &master_plane,  &slave_piece,
                                  &master_piece, &rule,        &options.newton};
      integrate_cells_of(slave, master, cells, geometry, c);
    }
  }
  return c;
}

} // namespace seam::mortar
