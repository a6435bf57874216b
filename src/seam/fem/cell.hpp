#pragma once
// Reference cells: topology, shape functions and quadrature. Node numbering follows Gmsh
// (https://gmsh.info/doc/texinfo/gmsh.html#Node-ordering), so a mesh read from Gmsh needs no
// permutation; VTK output permutes with vtk_node_order().
#include <cstdint>
#include <span>
#include <string_view>

namespace seam::fem {

enum class CellType : std::uint8_t {
  point1,
  line2,
  line3,
  tri3,
  tri6,
  quad4,
  quad8,
  quad9,
  tet4,
  tet10,
  hex8,
  hex20,
  hex27,
};

inline constexpr int max_cell_nodes = 27;
inline constexpr int max_facet_nodes = 9;

/// Parametric dimension (0 for point1, 1 for lines, 2 for tri/quad, 3 for tet/hex).
int dimension(CellType t);
/// Number of nodes.
int n_nodes(CellType t);
/// Polynomial order of the geometry/displacement interpolation (1 or 2; 0 for point1).
int order(CellType t);
/// Number of vertex (corner) nodes; corners come first in the node list.
int n_vertices(CellType t);
/// "hex8", "tri6", ...
std::string_view name(CellType t);

/// Gmsh element type number (1 = line2, 2 = tri3, ...); throws seam::InputError for an
/// element type seam does not support, naming it.
CellType from_gmsh(int gmsh_type);
int to_gmsh(CellType t);
/// VTK cell type id (VTK_HEXAHEDRON = 12, VTK_QUADRATIC_HEXAHEDRON = 25, ...).
int vtk_type(CellType t);
/// vtk_node_order(t)[i] = seam-local node written at VTK position i.
std::span<const int> vtk_node_order(CellType t);

/// Facets (codimension 1): their number, type and local nodes. A facet's node list starts
/// with its corners, cycling around the facet so that the facet's own parametrisation gives
/// the outward normal of the cell:
/// 3D: (dx/dxi x dx/deta) points out of the cell; 2D: for a line facet from node a to node b
/// the outward normal is (t_y, -t_x) with t = dx/dxi (i.e. the cell is on the left of the
/// facet direction, counter-clockwise cells). Mid-edge nodes follow in the facet type's own
/// node order, then the face centre (quad9 facets of hex27). Lines have two point1 facets,
/// xi = -1 (outward -1) and xi = +1; point1 has none. Facet order: tri/quad edges start at
/// node 0, 1, 2(, 3); tet faces (0,2,1), (0,1,3), (0,3,2), (3,1,2) and hex faces z=-1, y=-1,
/// x=-1, x=+1, y=+1, z=+1 as in Gmsh, so hex27 facet f has its centre at node 20 + f.
int n_facets(CellType t);
CellType facet_type(CellType t, int facet);
std::span<const int> facet_nodes(CellType t, int facet);

/// Reference coordinates of the nodes, n_nodes(t) * dimension(t) values, node-major.
/// Reference domains: line [-1,1]; tri {xi,eta >= 0, xi+eta <= 1}; quad [-1,1]^2;
/// tet {xi,eta,zeta >= 0, sum <= 1}; hex [-1,1]^3 (Gmsh conventions).
std::span<const double> reference_nodes(CellType t);

/// Shape function values N[i] at reference point xi (dimension(t) values).
void shape_values(CellType t, const double* xi, double* N);
/// Shape function gradients dN[i*dim + a] = dN_i/dxi_a at xi.
void shape_gradients(CellType t, const double* xi, double* dN);

/// A quadrature rule on a reference cell: n points, points[q*dim + a], weights[q].
/// Weights sum to the reference measure (2, 1/2, 4, 1/6, 8; 1 for point1). All weights are
/// positive and all points interior.
struct QuadratureRule {
  int dim = 0;
  /// polynomials of total degree (simplex) / per-direction degree (tensor) <= degree are
  /// exact; may exceed the degree asked for (Gauss rules are exact to an odd degree).
  int degree = 0;
  int n_points = 0;
  std::span<const double> points;
  std::span<const double> weights;
};

/// The cheapest rule seam has (positive weights, interior points) on the reference domain of t
/// integrating polynomials of the given degree exactly (tensor cells: per direction). Rules
/// are built once and cached (thread-safe). Throws InputError if no rule of that degree is
/// available; every cell has rules for 0 <= degree <= max_quadrature_degree.
QuadratureRule quadrature(CellType t, int degree);
inline constexpr int max_quadrature_degree = 63;

/// Default degree for mass and stiffness integration of a cell of this type: 2 * order on
/// every cell (full Gauss integration on tensor cells; reasons in quadrature.cpp).
int default_quadrature_degree(CellType t);

} // namespace seam::fem
