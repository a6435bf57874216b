// 3D segment-based mortar integration of a surface pair (Puso & Laursen 2004; Popp et al.
// 2010; ALGORITHMS.md §2): per linear piece of the slave an auxiliary plane, projection of
// slave and master piece vertices into it, clipping, triangulation into integration cells,
// a 7-point degree-5 rule per cell and back-projection of every point onto both facets.
#include <algorithm>
#include <array>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/geometry/plane.hpp"
#include "seam/mortar/normals.hpp"
#include "seam/mortar/pair_integration.hpp"

namespace seam::mortar {

namespace {

using Eigen::Vector2d;
using Eigen::Vector3d;

// A linear piece of a facet in space, with the reference coordinates of its centre in the
// parent facet (the Newton start of back-projections onto the parent).
struct Piece {
  int n_vertices = 0;
  std::array<Vector3d, 4> x;
  Vector3d center = Vector3d::Zero();
  Vector3d normal = Vector3d::Zero(); ///< unit; zero if the piece is degenerate
  Vector2d xi_center = Vector2d::Zero();
};

Piece make_piece(const Facet<3>& facet, const SubFacet& sub) {
  Piece piece;
  piece.n_vertices = sub.n_vertices;
  const double* reference = fem::reference_nodes(facet.type).data();
  for (int v = 0; v < sub.n_vertices; ++v) {
    const int node = sub.nodes[static_cast<std::size_t>(v)];
    piece.x[static_cast<std::size_t>(v)] = facet.x.col(node);
    piece.center += facet.x.col(node);
    piece.xi_center += Vector2d(reference[2 * node], reference[2 * node + 1]);
  }
  piece.center /= sub.n_vertices;
  piece.xi_center /= sub.n_vertices;
  // Triangle: the constant normal. Bilinear quad: x_xi x x_eta at its centre is parallel to
  // the cross product of the diagonals, and the centre is the vertex mean (ALGORITHMS.md §2,
  // step 2, for a linear facet: x_c = x(xi_c), n_aux = n(xi_c)).
  const auto& x = piece.x;
  const Vector3d n = sub.n_vertices == 3 ? Vector3d((x[1] - x[0]).cross(x[2] - x[0]))
                                         : Vector3d((x[2] - x[0]).cross(x[3] - x[1]));
  const double length = n.norm();
  if (length > 0.0) piece.normal = n / length;
  return piece;
}

double longest_corner_edge(const Facet<3>& facet) {
  const int n = fem::n_vertices(facet.type);
  double longest = 0.0;
  for (int i = 0; i < n; ++i) {
    longest = std::max(longest, (facet.x.col((i + 1) % n) - facet.x.col(i)).norm());
  }
  return longest;
}

Vector3d center_position(const Facet<3>& facet) {
  const auto xi = reference_center(facet.type);
  return evaluate(facet, xi.data()).x;
}

// Call f(b0, b1, b2, w) for each point of a triangle rule of the given degree, in barycentric
// coordinates with weights summing to 1.
template <class F> void for_each_cell_point(int degree, F&& f) {
  if (degree <= 5) {
    using Rule = geometry::TriangleRule7;
    for (int q = 0; q < Rule::n_points; ++q) {
      const auto& b = Rule::barycentric[static_cast<std::size_t>(q)];
      f(b[0], b[1], b[2], Rule::weights[static_cast<std::size_t>(q)]);
    }
    return;
  }
  // Reference triangle rule of seam::fem: points (xi, eta), weights summing to 1/2.
  const fem::QuadratureRule rule = fem::quadrature(fem::CellType::tri3, degree);
  for (int q = 0; q < rule.n_points; ++q) {
    const double xi = rule.points[static_cast<std::size_t>(2 * q)];
    const double eta = rule.points[static_cast<std::size_t>(2 * q + 1)];
    f(1.0 - xi - eta, xi, eta, 2.0 * rule.weights[static_cast<std::size_t>(q)]);
  }
}

} // namespace

PairContribution integrate_pair(const SlaveFacet<3>& slave, const Facet<3>& master,
                                const PairOptions& options) {
  const Facet<3>& s = slave.facet;
  PairContribution c = detail::empty_contribution(s.n_nodes, master.n_nodes);

  const double reach = options.max_center_distance_factor *
                       std::max(longest_corner_edge(s), longest_corner_edge(master));
  if ((center_position(s) - center_position(master)).norm() > reach) return c;

  const auto master_subfacets = linear_subfacets(master.type);
  std::array<Piece, 5> master_pieces;
  for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
    master_pieces[i] = make_piece(master, master_subfacets[i]);
  }

  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree
                     : fem::order(s.type) == 1 && fem::order(master.type) == 1 ? 5
                                                                               : 8;
  NodalVector N_tilde;
  NodalVector Phi;
  for (const SubFacet& slave_sub : linear_subfacets(s.type)) {
    const Piece sp = make_piece(s, slave_sub);
    if (sp.normal.isZero()) continue;
    const geometry::Plane plane = geometry::make_plane(sp.center, sp.normal);
    geometry::Polygon slave_polygon;
    for (int v = 0; v < sp.n_vertices; ++v) {
      slave_polygon.push_back(plane.to_local(sp.x[static_cast<std::size_t>(v)]));
    }
    for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
      const Piece& mp = master_pieces[i];
      // The master must face the slave (ALGORITHMS.md §2, step 1).
      if (!(mp.normal.dot(plane.normal) < -1e-12)) continue;
      geometry::Polygon master_polygon;
      for (int v = 0; v < mp.n_vertices; ++v) {
        master_polygon.push_back(plane.to_local(mp.x[static_cast<std::size_t>(v)]));
      }
      const geometry::Polygon clip =
          geometry::clip_polygons(slave_polygon, master_polygon, options.clip);
      if (clip.empty()) continue;
      const geometry::TriangleList cells = geometry::triangulate_fan(clip);
      c.n_cells += cells.size();
      c.area += geometry::area(clip);
      for (const geometry::Triangle2& cell : cells) {
        const double cell_area = cell.area();
        for_each_cell_point(degree, [&](double b0, double b1, double b2, double weight) {
          const Vector3d x_cell = plane.to_global(b0 * cell.a + b1 * cell.b + b2 * cell.c);
          // Back-projection along the plane normal onto the full (possibly quadratic) facets.
          const auto on_slave =
              project_onto_facet(s, x_cell, plane.normal, sp.xi_center, options.newton);
          const auto on_master =
              project_onto_facet(master, x_cell, plane.normal, mp.xi_center, options.newton);
          if (!on_slave.converged || !on_master.converged) {
            ++c.n_projection_failures;
            return;
          }
          const auto ps = evaluate(s, on_slave.xi.data());
          const auto pm = evaluate(master, on_master.xi.data());
          const Vector3d n = interpolated_normal<3>(slave.normals, ps.N);
          slave_functions(slave.basis, s.type, s.n_nodes, ps.N, N_tilde, Phi);
          detail::accumulate_point(c, slave.basis.multiplier, weight * cell_area, N_tilde, Phi,
                                   pm.N, n.dot(pm.x - ps.x));
        });
      }
    }
  }
  return c;
}

} // namespace seam::mortar
