// 3D segment-based mortar integration (Puso & Laursen 2004; Popp et al. 2010; ALGORITHMS.md §2)
// on a scalar type, following integration_3d.cpp: per linear piece of the slave an auxiliary
// plane, clipping, fan cells and back-projection of every cell point. With dual numbers the
// derivatives pass through the plane (centre and normal of the piece), the projected vertices,
// the clip polygon vertices (frozen combinatorics), the centroid of the fan, the cell areas,
// the back-projected parameters (implicit function theorem), the interpolated normal, the
// dual coefficients and the gap.
#include <algorithm>
#include <array>

#include "seam/geometry/cell_quadrature.hpp"
#include "seam/mortar/linearization_clip.hpp"
#include "seam/mortar/linearization_pair.hpp"

namespace seam::mortar::ad {

namespace {

template <class S> struct PieceT {
  int n_vertices = 0;
  std::array<Vector<S, 3>, 4> x;
  Vector<S, 3> center = Vector<S, 3>::Zero();
  Vector<S, 3> normal = Vector<S, 3>::Zero(); ///< unit; zero if degenerate
  bool degenerate = true;
  Eigen::Vector2d xi_center = Eigen::Vector2d::Zero();
};

// make_piece of integration_3d.cpp: vertex mean and the normal of a triangle or, for a bilinear
// quad, the cross product of the diagonals.
template <class S> PieceT<S> make_piece(const FacetT<S, 3>& facet, const SubFacet& sub) {
  PieceT<S> piece;
  piece.n_vertices = sub.n_vertices;
  const double* reference = fem::reference_nodes(facet.type).data();
  for (int v = 0; v < sub.n_vertices; ++v) {
    const int node = sub.nodes[static_cast<std::size_t>(v)];
    piece.x[static_cast<std::size_t>(v)] = facet.x.col(node);
    piece.center += facet.x.col(node);
    piece.xi_center += Eigen::Vector2d(reference[2 * node], reference[2 * node + 1]);
  }
  piece.center /= static_cast<double>(sub.n_vertices);
  piece.xi_center /= sub.n_vertices;
  const auto& x = piece.x;
  const Vector<S, 3> n = sub.n_vertices == 3 ? cross3<S>(x[1] - x[0], x[2] - x[0])
                                             : cross3<S>(x[2] - x[0], x[3] - x[1]);
  const S length = norm(n);
  if (value_of(length) > 0.0) {
    piece.normal = n / length;
    piece.degenerate = false;
  }
  return piece;
}

double longest_corner_edge(const Facet<3>& facet) {
  const int n = fem::n_vertices(facet.type);
  double longest = 0.0;
  for (int i = 0; i < n; ++i)
    longest = std::max(longest, (facet.x.col((i + 1) % n) - facet.x.col(i)).norm());
  return longest;
}

Eigen::Vector3d center_position(const Facet<3>& facet) {
  const auto xi = reference_center(facet.type);
  return evaluate(facet, xi.data()).x;
}

// for_each_cell_point of integration_3d.cpp.
template <class F> void for_each_cell_point(int degree, F&& f) {
  if (degree <= 5) {
    using Rule = geometry::TriangleRule7;
    for (int q = 0; q < Rule::n_points; ++q) {
      const auto& b = Rule::barycentric[static_cast<std::size_t>(q)];
      f(b[0], b[1], b[2], Rule::weights[static_cast<std::size_t>(q)]);
    }
    return;
  }
  const fem::QuadratureRule rule = fem::quadrature(fem::CellType::tri3, degree);
  for (int q = 0; q < rule.n_points; ++q) {
    const double xi = rule.points[static_cast<std::size_t>(2 * q)];
    const double eta = rule.points[static_cast<std::size_t>(2 * q + 1)];
    f(1.0 - xi - eta, xi, eta, 2.0 * rule.weights[static_cast<std::size_t>(q)]);
  }
}

} // namespace

template <class S>
PairContributionT<S> integrate_pair_t(const SlaveFacetT<S, 3>& slave, const FacetT<S, 3>& master,
                                      const PairOptions& options) {
  const FacetT<S, 3>& s = slave.facet;
  const Facet<3> sv = values(s);
  const Facet<3> mv = values(master);
  PairContributionT<S> c = detail::empty_contribution_t<S>(s.n_nodes, master.n_nodes);

  const double reach = options.max_center_distance_factor *
                       std::max(longest_corner_edge(sv), longest_corner_edge(mv));
  if ((center_position(sv) - center_position(mv)).norm() > reach) return c;

  const auto master_subfacets = linear_subfacets(master.type);
  std::array<PieceT<S>, 5> master_pieces;
  for (std::size_t i = 0; i < master_subfacets.size(); ++i)
    master_pieces[i] = make_piece(master, master_subfacets[i]);

  const int degree = options.cell_quadrature_degree > 0 ? options.cell_quadrature_degree
                     : fem::order(s.type) == 1 && fem::order(master.type) == 1 ? 5
                                                                               : 8;
  NodalVectorT<S> N_tilde;
  NodalVectorT<S> Phi;
  for (const SubFacet& slave_sub : linear_subfacets(s.type)) {
    const PieceT<S> sp = make_piece(s, slave_sub);
    if (sp.degenerate) continue;
    const PlaneT<S> plane = make_plane_t<S>(sp.center, sp.normal);
    PolygonT<S> slave_polygon;
    for (int v = 0; v < sp.n_vertices; ++v)
      slave_polygon.push_back(plane.to_local(sp.x[static_cast<std::size_t>(v)]));
    for (std::size_t i = 0; i < master_subfacets.size(); ++i) {
      const PieceT<S>& mp = master_pieces[i];
      if (!(value_of(dot(mp.normal, plane.normal)) < -1e-12)) continue;
      PolygonT<S> master_polygon;
      for (int v = 0; v < mp.n_vertices; ++v)
        master_polygon.push_back(plane.to_local(mp.x[static_cast<std::size_t>(v)]));
      const PolygonT<S> clip = clip_polygons_t<S>(slave_polygon, master_polygon, options.clip);
      if (clip.empty()) continue;
      const TriangleListT<S> cells = triangulate_fan_t<S>(clip);
      c.n_cells += cells.size();
      c.area += std::abs(value_of(signed_area_t<S>(clip)));
      for (const TriangleT<S>& cell : cells) {
        const S cell_area = cell.area();
        for_each_cell_point(degree, [&](double b0, double b1, double b2, double weight) {
          Vector<S, 2> u = Vector<S, 2>::Zero();
          for (int k = 0; k < 2; ++k) {
            add_product(u(k), cell.a(k), b0);
            add_product(u(k), cell.b(k), b1);
            add_product(u(k), cell.c(k), b2);
          }
          const Vector<S, 3> x_cell = plane.to_global(u);
          const SurfaceProjectionT<S> on_slave =
              project_onto_surface_t<S>(s, x_cell, plane.normal, sp.xi_center, options.newton);
          const SurfaceProjectionT<S> on_master =
              project_onto_surface_t<S>(master, x_cell, plane.normal, mp.xi_center, options.newton);
          if (!on_slave.converged || !on_master.converged) {
            ++c.n_projection_failures;
            return;
          }
          const NodalVectorT<S> N = shape_values_t<S, 3>(s.type, on_slave.xi.data());
          const NodalVectorT<S> Nm = shape_values_t<S, 3>(master.type, on_master.xi.data());
          const Vector<S, 3> x_s = interpolate<S, 3>(s.x, N, s.n_nodes);
          const Vector<S, 3> x_m = interpolate<S, 3>(master.x, Nm, master.n_nodes);
          const Vector<S, 3> n = normalized(interpolate<S, 3>(slave.normals, N, s.n_nodes));
          detail::slave_functions_t(slave, N, N_tilde, Phi);
          detail::accumulate_point_t(c, slave.multiplier, S(weight * cell_area), N_tilde, Phi, Nm,
                                     dot(n, Vector<S, 3>(x_m - x_s)));
        });
      }
    }
  }
  return c;
}

template PairContributionT<double> integrate_pair_t(const SlaveFacetT<double, 3>&,
                                                    const FacetT<double, 3>&, const PairOptions&);
template PairContributionT<Dual<36>>
integrate_pair_t(const SlaveFacetT<Dual<36>, 3>&, const FacetT<Dual<36>, 3>&, const PairOptions&);
template PairContributionT<Dual<81>>
integrate_pair_t(const SlaveFacetT<Dual<81>, 3>&, const FacetT<Dual<81>, 3>&, const PairOptions&);

} // namespace seam::mortar::ad
