// Topology of the reference cells: counts, Gmsh and VTK numbering. The expected values are
// written out from the Gmsh manual ("Node ordering", element types of the MSH format) and
// VTK's vtkCellType.h / cell class documentation, independently of the tables in cell.cpp.
#include "fem_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

namespace seam::fem {
namespace {

using test::all_cell_types;

struct Expected {
  CellType type;
  const char* name;
  int dim, n_nodes, order, n_vertices, gmsh, vtk;
};

constexpr Expected expected[] = {
    {CellType::point1, "point1", 0, 1, 0, 1, 15, 1},
    {CellType::line2, "line2", 1, 2, 1, 2, 1, 3},
    {CellType::line3, "line3", 1, 3, 2, 2, 8, 21},
    {CellType::tri3, "tri3", 2, 3, 1, 3, 2, 5},
    {CellType::tri6, "tri6", 2, 6, 2, 3, 9, 22},
    {CellType::quad4, "quad4", 2, 4, 1, 4, 3, 9},
    {CellType::quad8, "quad8", 2, 8, 2, 4, 16, 23},
    {CellType::quad9, "quad9", 2, 9, 2, 4, 10, 28},
    {CellType::tet4, "tet4", 3, 4, 1, 4, 4, 10},
    {CellType::tet10, "tet10", 3, 10, 2, 4, 11, 24},
    {CellType::hex8, "hex8", 3, 8, 1, 8, 5, 12},
    {CellType::hex20, "hex20", 3, 20, 2, 8, 17, 25},
    {CellType::hex27, "hex27", 3, 27, 2, 8, 12, 29},
};

TEST(Cell, CountsNamesAndIds) {
  for (const Expected& e : expected) {
    SCOPED_TRACE(e.name);
    EXPECT_EQ(name(e.type), e.name);
    EXPECT_EQ(dimension(e.type), e.dim);
    EXPECT_EQ(n_nodes(e.type), e.n_nodes);
    EXPECT_EQ(order(e.type), e.order);
    EXPECT_EQ(n_vertices(e.type), e.n_vertices);
    EXPECT_EQ(to_gmsh(e.type), e.gmsh);
    EXPECT_EQ(vtk_type(e.type), e.vtk);
    EXPECT_EQ(reference_nodes(e.type).size(), static_cast<std::size_t>(e.n_nodes * e.dim));
  }
}

TEST(Cell, GmshRoundTrip) {
  for (CellType t : all_cell_types) EXPECT_EQ(from_gmsh(to_gmsh(t)), t) << name(t);
}

TEST(Cell, UnsupportedGmshTypesThrowNamingThem) {
  // Gmsh type 5 is the 8-node hexahedron; the unsupported 3D types are prisms and pyramids.
  EXPECT_EQ(from_gmsh(5), CellType::hex8);
  for (int gmsh_type : {6, 7, 13, 14, 18, 19, 21, 0, -3, 1000}) {
    try {
      from_gmsh(gmsh_type);
      ADD_FAILURE() << "Gmsh type " << gmsh_type << " was accepted";
    } catch (const InputError& e) {
      const std::string msg = e.what();
      EXPECT_NE(msg.find("Gmsh element type " + std::to_string(gmsh_type)), std::string::npos)
          << msg;
    }
  }
  try {
    from_gmsh(7);
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("pyramid"), std::string::npos) << e.what();
  }
  EXPECT_THROW(from_gmsh(6), InputError);
}

std::vector<double> node(CellType t, int i) {
  const int dim = dimension(t);
  const auto X = reference_nodes(t);
  return {X.begin() + i * dim, X.begin() + (i + 1) * dim};
}

// Mean of the reference coordinates of the given nodes.
std::vector<double> mean_of(CellType t, const std::vector<int>& nodes) {
  std::vector<double> m(static_cast<std::size_t>(dimension(t)), 0.0);
  for (int i : nodes) {
    const auto x = node(t, i);
    for (std::size_t a = 0; a < m.size(); ++a) m[a] += x[a] / static_cast<double>(nodes.size());
  }
  return m;
}

void expect_node_at(CellType t, int i, const std::vector<double>& x) {
  const auto y = node(t, i);
  ASSERT_EQ(y.size(), x.size());
  for (std::size_t a = 0; a < x.size(); ++a)
    EXPECT_DOUBLE_EQ(y[a], x[a]) << name(t) << " node " << i << " coordinate " << a;
}

TEST(Cell, GmshCornerCoordinates) {
  expect_node_at(CellType::line2, 0, {-1});
  expect_node_at(CellType::line2, 1, {1});
  const std::vector<std::vector<double>> tri{{0, 0}, {1, 0}, {0, 1}};
  const std::vector<std::vector<double>> quad{{-1, -1}, {1, -1}, {1, 1}, {-1, 1}};
  const std::vector<std::vector<double>> tet{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  const std::vector<std::vector<double>> hex{{-1, -1, -1}, {1, -1, -1}, {1, 1, -1}, {-1, 1, -1},
                                             {-1, -1, 1},  {1, -1, 1},  {1, 1, 1},  {-1, 1, 1}};
  for (CellType t : all_cell_types) {
    const std::vector<std::vector<double>>* corners = nullptr;
    if (t == CellType::tri3 || t == CellType::tri6) corners = &tri;
    if (t == CellType::quad4 || t == CellType::quad8 || t == CellType::quad9) corners = &quad;
    if (t == CellType::tet4 || t == CellType::tet10) corners = &tet;
    if (t == CellType::hex8 || t == CellType::hex20 || t == CellType::hex27) corners = &hex;
    if (!corners) continue;
    for (int i = 0; i < n_vertices(t); ++i)
      expect_node_at(t, i, (*corners)[static_cast<std::size_t>(i)]);
  }
}

// Higher-order nodes as the Gmsh manual draws them: each is the mean of the listed corners.
TEST(Cell, GmshHigherOrderNodes) {
  const std::vector<std::vector<int>> tri6{{0, 1}, {1, 2}, {2, 0}};
  const std::vector<std::vector<int>> quad9{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 1, 2, 3}};
  const std::vector<std::vector<int>> tet10{{0, 1}, {1, 2}, {2, 0}, {3, 0}, {3, 2}, {3, 1}};
  const std::vector<std::vector<int>> hex27{{0, 1},
                                            {0, 3},
                                            {0, 4},
                                            {1, 2},
                                            {1, 5},
                                            {2, 3},
                                            {2, 6},
                                            {3, 7},
                                            {4, 5},
                                            {4, 7},
                                            {5, 6},
                                            {6, 7},
                                            {0, 1, 2, 3},
                                            {0, 1, 4, 5},
                                            {0, 3, 4, 7},
                                            {1, 2, 5, 6},
                                            {2, 3, 6, 7},
                                            {4, 5, 6, 7},
                                            {0, 1, 2, 3, 4, 5, 6, 7}};
  const auto check = [](CellType t, const std::vector<std::vector<int>>& parents) {
    for (int i = n_vertices(t); i < n_nodes(t); ++i)
      expect_node_at(t, i, mean_of(t, parents[static_cast<std::size_t>(i - n_vertices(t))]));
  };
  check(CellType::line3, {{0, 1}});
  check(CellType::tri6, tri6);
  check(CellType::quad8, quad9);
  check(CellType::quad9, quad9);
  check(CellType::tet10, tet10);
  check(CellType::hex20, hex27);
  check(CellType::hex27, hex27);
}

TEST(Cell, VtkNodeOrderIsAPermutation) {
  for (CellType t : all_cell_types) {
    const auto order = vtk_node_order(t);
    ASSERT_EQ(order.size(), static_cast<std::size_t>(n_nodes(t))) << name(t);
    std::vector<int> sorted(order.begin(), order.end());
    std::sort(sorted.begin(), sorted.end());
    for (int i = 0; i < n_nodes(t); ++i) EXPECT_EQ(sorted[static_cast<std::size_t>(i)], i);
  }
}

// VTK's own description of its higher-order nodes, in VTK positions: each VTK node is the
// mean of the listed VTK corners (vtkQuadraticTetra, vtkQuadraticHexahedron,
// vtkTriQuadraticHexahedron, vtkBiQuadraticQuad, ... class documentation). VTK's corner order
// equals Gmsh's for all linear cells.
TEST(Cell, VtkNodeOrderMatchesVtkGeometry) {
  const std::vector<std::vector<int>> quad{{0, 1}, {1, 2}, {2, 3}, {3, 0}, {0, 1, 2, 3}};
  const std::vector<std::vector<int>> tet{{0, 1}, {1, 2}, {2, 0}, {0, 3}, {1, 3}, {2, 3}};
  const std::vector<std::vector<int>> hex{{0, 1},
                                          {1, 2},
                                          {2, 3},
                                          {3, 0},
                                          {4, 5},
                                          {5, 6},
                                          {6, 7},
                                          {7, 4},
                                          {0, 4},
                                          {1, 5},
                                          {2, 6},
                                          {3, 7},
                                          {0, 4, 7, 3},
                                          {1, 2, 6, 5},
                                          {0, 1, 5, 4},
                                          {3, 7, 6, 2},
                                          {0, 3, 2, 1},
                                          {4, 5, 6, 7},
                                          {0, 1, 2, 3, 4, 5, 6, 7}};
  const auto check = [](CellType t, const std::vector<std::vector<int>>& parents) {
    const auto order = vtk_node_order(t);
    for (int i = 0; i < n_vertices(t); ++i) EXPECT_EQ(order[static_cast<std::size_t>(i)], i);
    for (int p = n_vertices(t); p < n_nodes(t); ++p) {
      std::vector<int> seam_parents;
      for (int c : parents[static_cast<std::size_t>(p - n_vertices(t))])
        seam_parents.push_back(order[static_cast<std::size_t>(c)]);
      SCOPED_TRACE(testing::Message() << name(t) << " VTK position " << p);
      expect_node_at(t, order[static_cast<std::size_t>(p)], mean_of(t, seam_parents));
    }
  };
  check(CellType::line3, {{0, 1}});
  check(CellType::tri6, {{0, 1}, {1, 2}, {2, 0}});
  check(CellType::quad8, quad);
  check(CellType::quad9, quad);
  check(CellType::tet10, tet);
  check(CellType::hex20, hex);
  check(CellType::hex27, hex);
  for (CellType t : {CellType::point1, CellType::line2, CellType::tri3, CellType::quad4,
                     CellType::tet4, CellType::hex8})
    check(t, {});
}

} // namespace
} // namespace seam::fem
