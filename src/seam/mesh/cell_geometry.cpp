#include "seam/mesh/cell_geometry.hpp"

#include "seam/common/error.hpp"

#include <cmath>

namespace seam::mesh {
namespace {

bool is_simplex(fem::CellType t) {
  using fem::CellType;
  return t == CellType::tri3 || t == CellType::tri6 || t == CellType::tet4 || t == CellType::tet10;
}

// Node coordinates of facet `local` of cell c (3 per node); returns the facet node count.
// `at`: node coordinates in mesh.x's layout to use instead of mesh.x (null: mesh.x).
int facet_coordinates(const Mesh& mesh, std::int32_t c, int local,
                      std::array<double, 3 * fem::max_facet_nodes>& xf,
                      const double* at = nullptr) {
  const auto type = mesh.cell_type[c];
  const auto local_nodes = fem::facet_nodes(type, local);
  const auto nodes = mesh.cell(c);
  const int n = static_cast<int>(local_nodes.size());
  for (int i = 0; i < n; ++i) {
    const auto node = nodes[local_nodes[i]];
    const double* x = at ? at + static_cast<std::size_t>(node) * mesh.dim : mesh.node(node).data();
    for (int a = 0; a < 3; ++a) xf[3 * i + a] = a < mesh.dim ? x[a] : 0.0;
  }
  return n;
}

} // namespace

Point reference_centre(fem::CellType t) {
  using fem::CellType;
  switch (t) {
  case CellType::tri3:
  case CellType::tri6:
    return {1.0 / 3.0, 1.0 / 3.0, 0.0};
  case CellType::tet4:
  case CellType::tet10:
    return {0.25, 0.25, 0.25};
  default:
    return {0.0, 0.0, 0.0}; // point, lines, quads, hexes: centred on 0
  }
}

int cell_coordinates(const Mesh& mesh, std::int32_t c,
                     std::array<double, 3 * fem::max_cell_nodes>& xc) {
  const auto nodes = mesh.cell(c);
  const int n = static_cast<int>(nodes.size());
  for (int i = 0; i < n; ++i) {
    const auto x = mesh.node(nodes[i]);
    for (int a = 0; a < 3; ++a) xc[3 * i + a] = a < mesh.dim ? x[a] : 0.0;
  }
  return n;
}

Point map_to_physical(const Mesh& mesh, std::int32_t c, const double* xi) {
  std::array<double, 3 * fem::max_cell_nodes> xc{};
  std::array<double, fem::max_cell_nodes> N{};
  const int n = cell_coordinates(mesh, c, xc);
  fem::shape_values(mesh.cell_type[c], xi, N.data());
  Point x{};
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) x[a] += N[i] * xc[3 * i + a];
  return x;
}

double jacobian(const Mesh& mesh, std::int32_t c, const double* xi, std::array<double, 9>& J) {
  std::array<double, 3 * fem::max_cell_nodes> xc{};
  std::array<double, 3 * fem::max_cell_nodes> dN{};
  const int n = cell_coordinates(mesh, c, xc);
  const int d = mesh.dim;
  fem::shape_gradients(mesh.cell_type[c], xi, dN.data());
  J.fill(0.0);
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < d; ++a)
      for (int b = 0; b < d; ++b) J[a * d + b] += xc[3 * i + a] * dN[i * d + b];
  if (d == 2) return J[0] * J[3] - J[1] * J[2];
  return J[0] * (J[4] * J[8] - J[5] * J[7]) - J[1] * (J[3] * J[8] - J[5] * J[6]) +
         J[2] * (J[3] * J[7] - J[4] * J[6]);
}

int jacobian_degree(fem::CellType t) {
  const int d = fem::dimension(t), p = fem::order(t);
  const int degree = is_simplex(t) ? d * (p - 1) : d * p - 1;
  return degree < 1 ? 1 : degree;
}

double cell_volume(const Mesh& mesh, std::int32_t c) {
  const auto type = mesh.cell_type[c];
  const auto rule = fem::quadrature(type, jacobian_degree(type));
  std::array<double, 9> J{};
  double volume = 0.0;
  for (int q = 0; q < rule.n_points; ++q)
    volume += rule.weights[q] * jacobian(mesh, c, &rule.points[q * rule.dim], J);
  return volume;
}

Point cell_centroid(const Mesh& mesh, std::int32_t c) {
  const auto type = mesh.cell_type[c];
  // x det J has the degree of det J plus the order of the map.
  const auto rule = fem::quadrature(type, jacobian_degree(type) + fem::order(type));
  std::array<double, 9> J{};
  Point moment{};
  double volume = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    const double* xi = &rule.points[q * rule.dim];
    const double w = rule.weights[q] * jacobian(mesh, c, xi, J);
    const auto x = map_to_physical(mesh, c, xi);
    for (int a = 0; a < 3; ++a) moment[a] += w * x[a];
    volume += w;
  }
  for (auto& m : moment) m /= volume;
  return moment;
}

Point facet_point(const Mesh& mesh, std::int32_t c, int local, const double* xi_f) {
  const auto ft = fem::facet_type(mesh.cell_type[c], local);
  std::array<double, 3 * fem::max_facet_nodes> xf{};
  std::array<double, fem::max_facet_nodes> N{};
  const int n = facet_coordinates(mesh, c, local, xf);
  fem::shape_values(ft, xi_f, N.data());
  Point x{};
  for (int i = 0; i < n; ++i)
    for (int a = 0; a < 3; ++a) x[a] += N[i] * xf[3 * i + a];
  return x;
}

Point facet_normal(const Mesh& mesh, std::int32_t c, int local, const double* xi_f,
                   double* area_element, const double* x) {
  const auto ft = fem::facet_type(mesh.cell_type[c], local);
  const int fd = fem::dimension(ft);
  SEAM_ASSERT(fd == mesh.dim - 1);
  std::array<double, 3 * fem::max_facet_nodes> xf{};
  std::array<double, 2 * fem::max_facet_nodes> dN{};
  const int n = facet_coordinates(mesh, c, local, xf, x);
  fem::shape_gradients(ft, xi_f, dN.data());
  std::array<Point, 2> t{}; // tangents dx/dxi_f (and dx/deta_f in 3D)
  for (int i = 0; i < n; ++i)
    for (int k = 0; k < fd; ++k)
      for (int a = 0; a < 3; ++a) t[k][a] += dN[i * fd + k] * xf[3 * i + a];
  Point normal{};
  if (mesh.dim == 2) {
    // Cells lie to the left of their facets' direction, so (t_y, -t_x) points out.
    normal = {t[0][1], -t[0][0], 0.0};
  } else {
    normal = {t[0][1] * t[1][2] - t[0][2] * t[1][1], t[0][2] * t[1][0] - t[0][0] * t[1][2],
              t[0][0] * t[1][1] - t[0][1] * t[1][0]};
  }
  const double length =
      std::sqrt(normal[0] * normal[0] + normal[1] * normal[1] + normal[2] * normal[2]);
  if (area_element != nullptr) *area_element = length;
  if (length > 0.0)
    for (auto& v : normal) v /= length;
  return normal;
}

double facet_area(const Mesh& mesh, std::int32_t c, int local) {
  const auto ft = fem::facet_type(mesh.cell_type[c], local);
  // Exact for flat facets; for curved ones the area element is not polynomial, and one degree
  // above the facet's det J degree keeps the error at the level of the geometry error.
  const auto rule = fem::quadrature(ft, jacobian_degree(ft) + 1);
  double area = 0.0;
  for (int q = 0; q < rule.n_points; ++q) {
    double da = 0.0;
    facet_normal(mesh, c, local, &rule.points[q * rule.dim], &da);
    area += rule.weights[q] * da;
  }
  return area;
}

} // namespace seam::mesh
