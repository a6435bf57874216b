#pragma once
// Geometry of one mesh cell or facet through its isoparametric map x(xi) = sum_i N_i(xi) x_i.
// For setup, checks and post-processing; nothing here allocates.
#include "seam/mesh/mesh.hpp"

#include <array>
#include <cstdint>

namespace seam::mesh {

using Point = std::array<double, 3>; ///< unused trailing components are 0

/// Centre of the reference domain of t (line 0, tri (1/3, 1/3), quad 0, tet 1/4, hex 0).
Point reference_centre(fem::CellType t);

/// Node coordinates of cell c into xc (n_nodes * 3 values, z = 0 in 2D); returns n_nodes.
int cell_coordinates(const Mesh& mesh, std::int32_t c,
                     std::array<double, 3 * fem::max_cell_nodes>& xc);

/// x(xi) in cell c; xi has fem::dimension(type) values.
Point map_to_physical(const Mesh& mesh, std::int32_t c, const double* xi);

/// Jacobian J[a * dim + b] = dx_a / dxi_b of cell c at xi (dim = mesh.dim); returns det J.
double jacobian(const Mesh& mesh, std::int32_t c, const double* xi, std::array<double, 9>& J);

/// Quadrature degree that integrates det J exactly: dim * (order - 1) for simplices (total
/// degree), dim * order - 1 per direction for tensor cells.
int jacobian_degree(fem::CellType t);

/// Volume (area in 2D) of cell c, int det J dxi, exact for polynomial maps.
double cell_volume(const Mesh& mesh, std::int32_t c);
/// Centroid int x dV / V of cell c.
Point cell_centroid(const Mesh& mesh, std::int32_t c);

/// x(xi_f) on facet `local` of cell c; xi_f are the facet's reference coordinates.
Point facet_point(const Mesh& mesh, std::int32_t c, int local, const double* xi_f);
/// Outward unit normal of facet `local` of cell c at xi_f (fem::facet_nodes orientation); the
/// area element |dx/dxi_f x dx/deta_f| (3D) or |dx/dxi_f| (2D) goes to *area_element if given.
/// `x`: node coordinates in the layout of mesh.x to take instead of mesh.x (a moved mesh).
Point facet_normal(const Mesh& mesh, std::int32_t c, int local, const double* xi_f,
                   double* area_element = nullptr, const double* x = nullptr);
/// Area (length in 2D) of facet `local` of cell c by quadrature of the area element.
double facet_area(const Mesh& mesh, std::int32_t c, int local);

} // namespace seam::mesh
