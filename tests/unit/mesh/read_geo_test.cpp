// Meshing the unit square and cube from .geo files: cell types, exact volumes and boundary
// areas, outward facet normals, region contents and node counts of structured meshes.
#include "mesh_test_support.hpp"

#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <set>

namespace seam::mesh {
namespace {

using fem::CellType;

struct GeoCase {
  std::string label;
  int dim;
  int structured_n; // > 0: transfinite grid
  bool quads;       // 2D only: recombine
  ReadOptions options;
  CellType expected;
};

std::ostream& operator<<(std::ostream& os, const GeoCase& c) {
  return os << c.label;
}

std::string boundary_name(int dim, int axis, int side) {
  if (dim == 2) {
    static const char* names[2][2] = {{"left", "right"}, {"bottom", "top"}};
    return names[axis][side];
  }
  return std::string(1, "xyz"[axis]) + std::to_string(side);
}

// Number of nodes of a structured n^d grid of cells of the given type.
std::int64_t structured_node_count(CellType t, int n) {
  const std::int64_t m = n + 1, k = 2 * n + 1;
  switch (t) {
  case CellType::quad4:
    return m * m;
  case CellType::quad9:
    return k * k;
  case CellType::quad8:
    return m * m + 2 * n * m; // corners + one node per edge
  case CellType::hex8:
    return m * m * m;
  case CellType::hex27:
    return k * k * k;
  case CellType::hex20:
    return m * m * m + 3 * n * m * m;
  default:
    return -1;
  }
}

class ReadGeo : public ::testing::TestWithParam<GeoCase> {};

TEST_P(ReadGeo, GeometryTopologyAndRegions) {
  const auto& p = GetParam();
  test::ScratchDir dir;
  const auto file =
      dir.write("domain.geo", p.dim == 2 ? test::unit_square_geo(p.structured_n, p.quads)
                                         : test::unit_cube_geo(p.structured_n));
  auto options = p.options;
  options.dim = p.dim;
  const Mesh mesh = read_mesh(file, options);
  ASSERT_NO_THROW(mesh.check());
  ASSERT_EQ(mesh.dim, p.dim);
  ASSERT_GT(mesh.n_cells(), 0);
  for (auto t : mesh.cell_type) ASSERT_EQ(t, p.expected) << fem::name(t);

  // Nodes are exactly those used by cells.
  std::vector<char> used(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (auto n : mesh.cell_nodes) used[static_cast<std::size_t>(n)] = 1;
  EXPECT_EQ(std::count(used.begin(), used.end(), 1), mesh.n_nodes());

  double volume = 0;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const double v = cell_volume(mesh, c);
    EXPECT_GT(v, 0.0) << "cell " << c << " inverted";
    volume += v;
  }
  EXPECT_NEAR(volume, 1.0, 1e-12);

  const auto& body = mesh.region(p.dim == 2 ? "square" : "cube", p.dim);
  EXPECT_EQ(body.cells.size(), static_cast<std::size_t>(mesh.n_cells()));
  EXPECT_EQ(body.nodes.size(), static_cast<std::size_t>(mesh.n_nodes()));

  // Every face of the box: area 1, normal -e_a / +e_a, nodes on the plane x_a = side.
  std::int32_t n_boundary_facets = 0;
  for (int axis = 0; axis < p.dim; ++axis)
    for (int side = 0; side < 2; ++side) {
      const auto& r = mesh.region(boundary_name(p.dim, axis, side), p.dim - 1);
      ASSERT_GT(r.n_facets(), 0);
      n_boundary_facets += r.n_facets();
      double area = 0;
      for (std::int32_t k = 0; k < r.n_facets(); ++k) {
        const auto c = r.facet_cell[static_cast<std::size_t>(k)];
        const int f = r.facet_local[static_cast<std::size_t>(k)];
        area += facet_area(mesh, c, f);
        const auto centre =
            reference_centre(fem::facet_type(mesh.cell_type[static_cast<std::size_t>(c)], f));
        const auto n = facet_normal(mesh, c, f, centre.data());
        for (int a = 0; a < 3; ++a)
          EXPECT_NEAR(n[a], a == axis ? (side == 0 ? -1.0 : 1.0) : 0.0, 1e-12);
      }
      EXPECT_NEAR(area, 1.0, 1e-12) << r.name;
      for (auto node : r.nodes) EXPECT_NEAR(mesh.node(node)[axis], side, 1e-12);
    }

  // The exterior facets are exactly the union of the six (four) faces; their normals point
  // away from their cell.
  const auto exterior = exterior_facets(mesh);
  EXPECT_EQ(exterior.size(), n_boundary_facets);
  double boundary_area = 0;
  for (std::int32_t k = 0; k < exterior.size(); ++k) {
    const auto c = exterior.cell[static_cast<std::size_t>(k)];
    const int f = exterior.local[static_cast<std::size_t>(k)];
    boundary_area += facet_area(mesh, c, f);
    const auto centre =
        reference_centre(fem::facet_type(mesh.cell_type[static_cast<std::size_t>(c)], f));
    const auto x_f = facet_point(mesh, c, f, centre.data());
    const auto n = facet_normal(mesh, c, f, centre.data());
    const auto x_c = cell_centroid(mesh, c);
    double dot = 0;
    for (int a = 0; a < 3; ++a) dot += (x_f[a] - x_c[a]) * n[a];
    EXPECT_GT(dot, 0.0) << "cell " << c << " facet " << f;
  }
  EXPECT_NEAR(boundary_area, 2.0 * p.dim, 1e-11);

  // Every facet of every cell is either exterior or shared by exactly two cells.
  const FacetIndex index(mesh);
  std::array<std::int32_t, 4> corners{};
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (int f = 0; f < fem::n_facets(mesh.cell_type[static_cast<std::size_t>(c)]); ++f) {
      const int n = facet_corners(mesh, c, f, corners);
      const auto* e =
          index.find(std::span<const std::int32_t>(corners.data(), static_cast<std::size_t>(n)));
      ASSERT_NE(e, nullptr);
      EXPECT_TRUE(e->n_cells == 1 || e->n_cells == 2);
    }

  if (p.dim == 2) {
    const auto& origin = mesh.region("origin", 0);
    ASSERT_EQ(origin.nodes.size(), 1u);
    EXPECT_EQ(mesh.node(origin.nodes[0])[0], 0.0);
    EXPECT_EQ(mesh.node(origin.nodes[0])[1], 0.0);
  }

  if (p.structured_n > 0) {
    const int n = p.structured_n;
    EXPECT_EQ(mesh.n_cells(), p.dim == 2 ? n * n : n * n * n);
    EXPECT_EQ(mesh.n_nodes(), structured_node_count(p.expected, n));
    // A face of the structured mesh is a structured grid one dimension lower.
    const auto face_type = fem::facet_type(p.expected, 0);
    const auto& face = mesh.region(boundary_name(p.dim, 0, 0), p.dim - 1);
    const std::int64_t face_nodes = p.dim == 3 ? structured_node_count(face_type, n)
                                               : (fem::order(face_type) == 2 ? 2 * n + 1 : n + 1);
    EXPECT_EQ(static_cast<std::int64_t>(face.nodes.size()), face_nodes);
  }
}

// x -> x + (a y^2 + d x^2, b x^2) (2D) or (a y^2 + d x^2, b z^2, c x^2) (3D) is quadratic, so
// every quadratic element reproduces it exactly and the mapped mesh's volume is the exact
// int det(grad phi) dX: 1 + d - a b in 2D, 1 + d + a b c in 3D.
TEST_P(ReadGeo, CurvedVolume) {
  const auto& p = GetParam();
  test::ScratchDir dir;
  const auto file =
      dir.write("domain.geo", p.dim == 2 ? test::unit_square_geo(p.structured_n, p.quads)
                                         : test::unit_cube_geo(p.structured_n));
  Mesh mesh = read_mesh(file, p.options);
  const double a = 0.2, b = 0.3, c = 0.25, d = 0.1;
  test::transform(mesh, [&](std::array<double, 3> x) {
    return std::array<double, 3>{x[0] + a * x[1] * x[1] + d * x[0] * x[0],
                                 x[1] + b * (p.dim == 2 ? x[0] * x[0] : x[2] * x[2]),
                                 x[2] + c * x[0] * x[0]};
  });
  double volume = 0;
  for (std::int32_t e = 0; e < mesh.n_cells(); ++e) volume += cell_volume(mesh, e);
  const double exact = p.dim == 2 ? 1.0 + d - a * b : 1.0 + d + a * b * c;
  // Linear cells interpolate the curved map with an O(h^2) volume error.
  EXPECT_NEAR(volume, exact, fem::order(p.expected) == 2 ? 1e-12 : 5e-3);
}

ReadOptions opts(double size, int order, bool serendipity = false) {
  ReadOptions o;
  if (size > 0) o.size = size;
  o.order = order;
  o.serendipity = serendipity;
  return o;
}

INSTANTIATE_TEST_SUITE_P(
    Mesh, ReadGeo,
    ::testing::Values(GeoCase{"tri3", 2, 0, false, opts(0.2, 1), CellType::tri3},
                      GeoCase{"tri6", 2, 0, false, opts(0.3, 2), CellType::tri6},
                      GeoCase{"quad4", 2, 5, true, opts(0, 1), CellType::quad4},
                      GeoCase{"quad9", 2, 4, true, opts(0, 2), CellType::quad9},
                      GeoCase{"quad8", 2, 4, true, opts(0, 2, true), CellType::quad8},
                      GeoCase{"tet4", 3, 0, false, opts(0.4, 1), CellType::tet4},
                      GeoCase{"tet10", 3, 0, false, opts(0.5, 2), CellType::tet10},
                      GeoCase{"hex8", 3, 3, false, opts(0, 1), CellType::hex8},
                      GeoCase{"hex27", 3, 2, false, opts(0, 2), CellType::hex27},
                      GeoCase{"hex20", 3, 2, false, opts(0, 2, true), CellType::hex20}),
    [](const auto& info) { return info.param.label; });

// A square of quads next to a square of triangles, with the shared curve as a region: mixed
// cell types, and an interior facet region mapped to one (the lower-index) cell.
TEST(ReadGeo, MixedTriQuadWithInteriorInterface) {
  test::ScratchDir dir;
  const auto file = dir.write("mixed.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Point(5) = {2, 0, 0}; Point(6) = {2, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Line(5) = {2, 5}; Line(6) = {5, 6}; Line(7) = {6, 3};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Curve Loop(2) = {5, 6, 7, -2}; Plane Surface(2) = {2};
Transfinite Curve{1, 2, 3, 4, 5, 6, 7} = 5;
Transfinite Surface{1}; Recombine Surface{1};
Physical Surface("quads") = {1};
Physical Surface("triangles") = {2};
Physical Curve("interface") = {2};
Physical Curve("outer") = {1, 3, 4, 5, 6, 7};
)");
  for (int order : {1, 2}) {
    ReadOptions o;
    o.order = order;
    const Mesh mesh = read_mesh(file, o);
    ASSERT_NO_THROW(mesh.check());
    std::set<CellType> types(mesh.cell_type.begin(), mesh.cell_type.end());
    EXPECT_EQ(types, (order == 1 ? std::set<CellType>{CellType::tri3, CellType::quad4}
                                 : std::set<CellType>{CellType::tri6, CellType::quad9}));
    const auto& quads = mesh.region("quads");
    const auto& tris = mesh.region("triangles");
    EXPECT_EQ(quads.cells.size(), 16u);
    EXPECT_EQ(quads.cells.size() + tris.cells.size(), static_cast<std::size_t>(mesh.n_cells()));
    double area_q = 0, area_t = 0;
    for (auto c : quads.cells) area_q += cell_volume(mesh, c);
    for (auto c : tris.cells) area_t += cell_volume(mesh, c);
    EXPECT_NEAR(area_q, 1.0, 1e-12);
    EXPECT_NEAR(area_t, 1.0, 1e-12);

    // The interface: 4 segments on x = 1, each seen from the lower-index of its two cells.
    const auto& interface = mesh.region("interface", 1);
    ASSERT_EQ(interface.n_facets(), 4);
    const FacetIndex index(mesh);
    double length = 0;
    for (std::int32_t k = 0; k < interface.n_facets(); ++k) {
      const FacetRef f{interface.facet_cell[static_cast<std::size_t>(k)],
                       interface.facet_local[static_cast<std::size_t>(k)]};
      const auto other = index.neighbour(mesh, f);
      ASSERT_TRUE(other.has_value());
      EXPECT_LT(f.cell, other->cell);
      length += facet_area(mesh, f.cell, f.local);
      const double xi0 = 0;
      EXPECT_NEAR(facet_point(mesh, f.cell, f.local, &xi0)[0], 1.0, 1e-12);
    }
    EXPECT_NEAR(length, 1.0, 1e-12);
    EXPECT_EQ(interface.nodes.size(), order == 1 ? 5u : 9u);
    // Interior facets are not exterior.
    EXPECT_EQ(exterior_facets(mesh).size(), mesh.region("outer", 1).n_facets());
  }
}

// An affine map x -> A x + b scales volumes by det A and face areas by |det A| |A^-T n|.
TEST(ReadGeo, AffineMapScalesVolumeAndAreas) {
  test::ScratchDir dir;
  const auto file = dir.write("cube.geo", test::unit_cube_geo(2));
  Mesh mesh = read_mesh(file, opts(0, 2));
  // A = [[2, 0.5, 0], [0, 1, 0.3], [0, 0, 1.5]]: upper triangular, det = 3; the face x = 0
  // spans A e_y and A e_z, area |A e_y x A e_z|.
  test::transform(mesh, [](std::array<double, 3> x) {
    return std::array<double, 3>{2 * x[0] + 0.5 * x[1] + 1, x[1] + 0.3 * x[2], 1.5 * x[2] - 2};
  });
  double volume = 0;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) volume += cell_volume(mesh, c);
  EXPECT_NEAR(volume, 3.0, 1e-12);
  const std::array<double, 3> ay{0.5, 1, 0}, az{0, 0.3, 1.5};
  const std::array<double, 3> cross{ay[1] * az[2] - ay[2] * az[1], ay[2] * az[0] - ay[0] * az[2],
                                    ay[0] * az[1] - ay[1] * az[0]};
  const double expected =
      std::sqrt(cross[0] * cross[0] + cross[1] * cross[1] + cross[2] * cross[2]);
  const auto& face = mesh.region("x0");
  double area = 0;
  for (std::int32_t k = 0; k < face.n_facets(); ++k)
    area += facet_area(mesh, face.facet_cell[static_cast<std::size_t>(k)],
                       face.facet_local[static_cast<std::size_t>(k)]);
  EXPECT_NEAR(area, expected, 1e-12);
}

} // namespace
} // namespace seam::mesh
