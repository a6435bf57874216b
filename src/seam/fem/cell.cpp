// Topology tables of the reference cells: counts, names, Gmsh and VTK numbering, facets and
// reference node coordinates. Node numbering is Gmsh's (gmsh.info/doc/texinfo/gmsh.html,
// section "Node ordering"; checked against gmsh::model::mesh::getElementProperties of Gmsh 4.8).
#include "seam/fem/cell.hpp"

#include "seam/common/error.hpp"

#include <array>

namespace seam::fem {

namespace {

constexpr int n_cell_types = 13;

constexpr int index(CellType t) {
  return static_cast<int>(t);
}

struct CellInfo {
  std::string_view name;
  int dimension;
  int n_nodes;
  int order;
  int n_vertices;
  int gmsh_type;
  int vtk_type;
};

// In CellType order. VTK ids: VTK_VERTEX 1, VTK_LINE 3, VTK_TRIANGLE 5, VTK_QUAD 9, VTK_TETRA 10,
// VTK_HEXAHEDRON 12, VTK_QUADRATIC_EDGE 21, VTK_QUADRATIC_TRIANGLE 22, VTK_QUADRATIC_QUAD 23,
// VTK_QUADRATIC_TETRA 24, VTK_QUADRATIC_HEXAHEDRON 25, VTK_BIQUADRATIC_QUAD 28,
// VTK_TRIQUADRATIC_HEXAHEDRON 29 (vtkCellType.h).
constexpr std::array<CellInfo, n_cell_types> cell_info{{
    {"point1", 0, 1, 0, 1, 15, 1},
    {"line2", 1, 2, 1, 2, 1, 3},
    {"line3", 1, 3, 2, 2, 8, 21},
    {"tri3", 2, 3, 1, 3, 2, 5},
    {"tri6", 2, 6, 2, 3, 9, 22},
    {"quad4", 2, 4, 1, 4, 3, 9},
    {"quad8", 2, 8, 2, 4, 16, 23},
    {"quad9", 2, 9, 2, 4, 10, 28},
    {"tet4", 3, 4, 1, 4, 4, 10},
    {"tet10", 3, 10, 2, 4, 11, 24},
    {"hex8", 3, 8, 1, 8, 5, 12},
    {"hex20", 3, 20, 2, 8, 17, 25},
    {"hex27", 3, 27, 2, 8, 12, 29},
}};

const CellInfo& info(CellType t) {
  const int i = index(t);
  SEAM_CHECK(i >= 0 && i < n_cell_types, InputError, "invalid cell type id ", i);
  return cell_info[static_cast<std::size_t>(i)];
}

// ---- reference node coordinates (Gmsh) ----------------------------------------------------

constexpr std::array<double, 0> nodes_point1{};
constexpr std::array<double, 2> nodes_line2{-1, 1};
constexpr std::array<double, 3> nodes_line3{-1, 1, 0};
constexpr std::array<double, 6> nodes_tri3{0, 0, 1, 0, 0, 1};
constexpr std::array<double, 12> nodes_tri6{0, 0, 1, 0, 0, 1, 0.5, 0, 0.5, 0.5, 0, 0.5};
constexpr std::array<double, 8> nodes_quad4{-1, -1, 1, -1, 1, 1, -1, 1};
// clang-format off
constexpr std::array<double, 18> nodes_quad9{
    -1, -1,   1, -1,   1, 1,   -1, 1,   // corners
     0, -1,   1,  0,   0, 1,   -1, 0,   // edges 0-1, 1-2, 2-3, 3-0
     0,  0};                            // centre
constexpr std::array<double, 12> nodes_tet4{0, 0, 0,   1, 0, 0,   0, 1, 0,   0, 0, 1};
// Gmsh's tet10 edge nodes: 4 (0-1), 5 (1-2), 6 (2-0), 7 (3-0), 8 (3-2), 9 (3-1).
constexpr std::array<double, 30> nodes_tet10{
    0,   0,   0,     1,   0,   0,     0,   1,   0,     0,   0,   1,
    0.5, 0,   0,     0.5, 0.5, 0,     0,   0.5, 0,     0,   0,   0.5,
    0,   0.5, 0.5,   0.5, 0,   0.5};
// Gmsh's hex27: corners; edges 8 (0-1), 9 (0-3), 10 (0-4), 11 (1-2), 12 (1-5), 13 (2-3),
// 14 (2-6), 15 (3-7), 16 (4-5), 17 (4-7), 18 (5-6), 19 (6-7); face centres 20 (z=-1),
// 21 (y=-1), 22 (x=-1), 23 (x=+1), 24 (y=+1), 25 (z=+1); 26 the cell centre. hex8 and hex20
// are its first 8 and 20 nodes.
constexpr std::array<double, 81> nodes_hex27{
    -1, -1, -1,    1, -1, -1,    1,  1, -1,   -1,  1, -1,  // 0-3
    -1, -1,  1,    1, -1,  1,    1,  1,  1,   -1,  1,  1,  // 4-7
     0, -1, -1,   -1,  0, -1,   -1, -1,  0,    1,  0, -1,  // 8-11
     1, -1,  0,    0,  1, -1,    1,  1,  0,   -1,  1,  0,  // 12-15
     0, -1,  1,   -1,  0,  1,    1,  0,  1,    0,  1,  1,  // 16-19
     0,  0, -1,    0, -1,  0,   -1,  0,  0,    1,  0,  0,  // 20-23
     0,  1,  0,    0,  0,  1,    0,  0,  0};               // 24-26
// clang-format on

// ---- VTK node order: vtk_order[i] = seam node written at VTK position i --------------------

constexpr std::array<int, 27> identity_order{0,  1,  2,  3,  4,  5,  6,  7,  8,  9,  10, 11, 12, 13,
                                             14, 15, 16, 17, 18, 19, 20, 21, 22, 23, 24, 25, 26};
// VTK_QUADRATIC_TETRA: edges (0,1),(1,2),(2,0),(0,3),(1,3),(2,3); Gmsh has 2-3 before 1-3.
constexpr std::array<int, 10> vtk_tet10{0, 1, 2, 3, 4, 5, 6, 7, 9, 8};
// VTK_QUADRATIC_HEXAHEDRON: edges (0,1),(1,2),(2,3),(3,0),(4,5),(5,6),(6,7),(7,4),(0,4),(1,5),
// (2,6),(3,7); VTK_TRIQUADRATIC_HEXAHEDRON then adds face centres x=-1, x=+1, y=-1, y=+1, z=-1,
// z=+1 and the cell centre (vtkTriQuadraticHexahedron.cxx, HexFaces).
constexpr std::array<int, 27> vtk_hex27{0,  1,  2,  3,  4,  5,  6,  7,  8,  11, 13, 9,  16, 18,
                                        19, 17, 10, 12, 14, 15, 22, 23, 21, 24, 20, 25, 26};

// ---- facets --------------------------------------------------------------------------------

struct FacetTable {
  CellType type;
  int n_facets;
  int n_facet_nodes;
  const int* nodes; // n_facets * n_facet_nodes
};

// Lines: facet 0 is the point xi = -1 (outward normal -1), facet 1 the point xi = +1.
constexpr std::array<int, 2> facets_line{0, 1};
// 2D: counter-clockwise cells, each edge runs with the cell on its left.
constexpr std::array<int, 6> facets_tri3{0, 1, 1, 2, 2, 0};
constexpr std::array<int, 9> facets_tri6{0, 1, 3, 1, 2, 4, 2, 0, 5};
constexpr std::array<int, 8> facets_quad4{0, 1, 1, 2, 2, 3, 3, 0};
constexpr std::array<int, 12> facets_quad8{0, 1, 4, 1, 2, 5, 2, 3, 6, 3, 0, 7};
// 3D: Gmsh's face order; corner cycles run counter-clockwise seen from outside, so
// dx/dxi x dx/deta of the facet's own (tri3/quad4) parametrisation points out. Mid-edge nodes
// follow as (c0,c1), (c1,c2), (c2,c0|c3), (c3,c0); face centres of hex27 last.
constexpr std::array<int, 12> facets_tet4{0, 2, 1, 0, 1, 3, 0, 3, 2, 3, 1, 2};
constexpr std::array<int, 24> facets_tet10{0, 2, 1, 6, 5, 4, 0, 1, 3, 4, 9, 7,
                                           0, 3, 2, 7, 8, 6, 3, 1, 2, 9, 5, 8};
constexpr std::array<int, 24> facets_hex8{0, 3, 2, 1, 0, 1, 5, 4, 0, 4, 7, 3,
                                          1, 2, 6, 5, 2, 3, 7, 6, 4, 5, 6, 7};
constexpr std::array<int, 54> facets_hex27{
    0, 3, 2, 1, 9,  13, 11, 8,  20, // z = -1
    0, 1, 5, 4, 8,  12, 16, 10, 21, // y = -1
    0, 4, 7, 3, 10, 17, 15, 9,  22, // x = -1
    1, 2, 6, 5, 11, 14, 18, 12, 23, // x = +1
    2, 3, 7, 6, 13, 15, 19, 14, 24, // y = +1
    4, 5, 6, 7, 16, 18, 19, 17, 25, // z = +1
};

// hex20 facets: hex27's without the face centres.
constexpr std::array<int, 48> facets_hex20 = [] {
  std::array<int, 48> f{};
  for (int k = 0; k < 6; ++k)
    for (int j = 0; j < 8; ++j)
      f[static_cast<std::size_t>(8 * k + j)] = facets_hex27[static_cast<std::size_t>(9 * k + j)];
  return f;
}();

FacetTable facet_table(CellType t) {
  switch (t) {
  case CellType::point1:
    return {CellType::point1, 0, 0, nullptr};
  case CellType::line2:
  case CellType::line3:
    return {CellType::point1, 2, 1, facets_line.data()};
  case CellType::tri3:
    return {CellType::line2, 3, 2, facets_tri3.data()};
  case CellType::tri6:
    return {CellType::line3, 3, 3, facets_tri6.data()};
  case CellType::quad4:
    return {CellType::line2, 4, 2, facets_quad4.data()};
  case CellType::quad8:
  case CellType::quad9:
    return {CellType::line3, 4, 3, facets_quad8.data()};
  case CellType::tet4:
    return {CellType::tri3, 4, 3, facets_tet4.data()};
  case CellType::tet10:
    return {CellType::tri6, 4, 6, facets_tet10.data()};
  case CellType::hex8:
    return {CellType::quad4, 6, 4, facets_hex8.data()};
  case CellType::hex20:
    return {CellType::quad8, 6, 8, facets_hex20.data()};
  case CellType::hex27:
    return {CellType::quad9, 6, 9, facets_hex27.data()};
  }
  SEAM_THROW(InputError, "invalid cell type id ", index(t));
}

// Gmsh element types seam does not read, for a clear message (GmshDefines.h).
std::string_view gmsh_type_description(int gmsh_type) {
  switch (gmsh_type) {
  case 6:
    return "6-node prism";
  case 7:
    return "5-node pyramid";
  case 13:
    return "18-node prism";
  case 14:
    return "14-node pyramid";
  case 18:
    return "15-node prism";
  case 19:
    return "13-node pyramid";
  case 20:
    return "9-node incomplete triangle";
  case 21:
    return "10-node triangle";
  case 22:
    return "12-node incomplete triangle";
  case 23:
    return "15-node triangle";
  case 24:
    return "15-node incomplete triangle";
  case 25:
    return "21-node triangle";
  case 26:
    return "4-node line";
  case 27:
    return "5-node line";
  case 28:
    return "6-node line";
  case 29:
    return "20-node tetrahedron";
  case 30:
    return "35-node tetrahedron";
  case 31:
    return "56-node tetrahedron";
  case 36:
    return "16-node quadrangle";
  case 37:
    return "25-node quadrangle";
  case 92:
    return "64-node hexahedron";
  case 93:
    return "125-node hexahedron";
  default:
    return "unknown type";
  }
}

} // namespace

int dimension(CellType t) {
  return info(t).dimension;
}
int n_nodes(CellType t) {
  return info(t).n_nodes;
}
int order(CellType t) {
  return info(t).order;
}
int n_vertices(CellType t) {
  return info(t).n_vertices;
}
std::string_view name(CellType t) {
  return info(t).name;
}

CellType from_gmsh(int gmsh_type) {
  for (int i = 0; i < n_cell_types; ++i)
    if (cell_info[static_cast<std::size_t>(i)].gmsh_type == gmsh_type)
      return static_cast<CellType>(i);
  SEAM_THROW(InputError, "Gmsh element type ", gmsh_type, " (", gmsh_type_description(gmsh_type),
             ") is not supported; seam reads point1, line2, line3, tri3, tri6, quad4, quad8, "
             "quad9, tet4, tet10, hex8, hex20 and hex27 (Gmsh types 15, 1, 8, 2, 9, 3, 16, 10, "
             "4, 11, 5, 17, 12)");
}

int to_gmsh(CellType t) {
  return info(t).gmsh_type;
}
int vtk_type(CellType t) {
  return info(t).vtk_type;
}

std::span<const int> vtk_node_order(CellType t) {
  const auto n = static_cast<std::size_t>(n_nodes(t));
  switch (t) {
  case CellType::tet10:
    return {vtk_tet10.data(), n};
  case CellType::hex20:
  case CellType::hex27:
    return {vtk_hex27.data(), n};
  default:
    return {identity_order.data(), n};
  }
}

int n_facets(CellType t) {
  return facet_table(t).n_facets;
}

CellType facet_type(CellType t, int facet) {
  const FacetTable f = facet_table(t);
  SEAM_CHECK(facet >= 0 && facet < f.n_facets, InputError, "facet ", facet, " of a ", name(t),
             " cell does not exist (it has ", f.n_facets, ")");
  return f.type;
}

std::span<const int> facet_nodes(CellType t, int facet) {
  const FacetTable f = facet_table(t);
  SEAM_CHECK(facet >= 0 && facet < f.n_facets, InputError, "facet ", facet, " of a ", name(t),
             " cell does not exist (it has ", f.n_facets, ")");
  return {f.nodes + facet * f.n_facet_nodes, static_cast<std::size_t>(f.n_facet_nodes)};
}

std::span<const double> reference_nodes(CellType t) {
  switch (t) {
  case CellType::point1:
    return nodes_point1;
  case CellType::line2:
    return nodes_line2;
  case CellType::line3:
    return nodes_line3;
  case CellType::tri3:
    return nodes_tri3;
  case CellType::tri6:
    return nodes_tri6;
  case CellType::quad4:
    return nodes_quad4;
  case CellType::quad8:
    return {nodes_quad9.data(), 16};
  case CellType::quad9:
    return nodes_quad9;
  case CellType::tet4:
    return nodes_tet4;
  case CellType::tet10:
    return nodes_tet10;
  case CellType::hex8:
    return {nodes_hex27.data(), 24};
  case CellType::hex20:
    return {nodes_hex27.data(), 60};
  case CellType::hex27:
    return nodes_hex27;
  }
  SEAM_THROW(InputError, "invalid cell type id ", index(t));
}

} // namespace seam::fem
