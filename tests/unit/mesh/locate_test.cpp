// Point location on distorted (curved, perturbed) meshes: the found cell and reference point
// reproduce the point to round-off; points outside the mesh are not found.
#include "mesh_test_support.hpp"

#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/gmsh_reader.hpp"
#include "seam/mesh/locate.hpp"

#include <gtest/gtest.h>

#include <random>
#include <set>

namespace seam::mesh {
namespace {

using fem::CellType;

struct LocateCase {
  std::string label;
  int dim;
  int structured_n;
  bool quads;
  double size;
  int order;
  bool serendipity;
};

// Curve the mesh with a smooth map and push every high-order node off its straight position,
// so that cells are genuinely curved and the inverse map is nonlinear.
void distort(Mesh& mesh, std::mt19937& rng) {
  test::transform(mesh, [&](std::array<double, 3> x) {
    return std::array<double, 3>{x[0] + 0.15 * x[1] * x[1] + 0.05 * std::sin(3 * x[2]),
                                 x[1] + 0.1 * std::sin(2 * x[0]) + 0.1 * x[2] * x[2],
                                 x[2] + 0.1 * x[0] * x[1]};
  });
  // High-order nodes move by up to 8 % of the shortest corner-to-corner distance of the cells
  // around them, which keeps every cell valid.
  std::vector<double> scale(static_cast<std::size_t>(mesh.n_nodes()), 1e300);
  std::vector<char> vertex(static_cast<std::size_t>(mesh.n_nodes()), 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto nodes = mesh.cell(c);
    const int n_v = fem::n_vertices(mesh.cell_type[static_cast<std::size_t>(c)]);
    double shortest = 1e300;
    for (int i = 0; i < n_v; ++i)
      for (int j = 0; j < i; ++j) {
        double d2 = 0;
        for (int a = 0; a < mesh.dim; ++a) {
          const double d =
              mesh.node(nodes[static_cast<std::size_t>(i)])[static_cast<std::size_t>(a)] -
              mesh.node(nodes[static_cast<std::size_t>(j)])[static_cast<std::size_t>(a)];
          d2 += d * d;
        }
        shortest = std::min(shortest, std::sqrt(d2));
      }
    for (int i = 0; i < static_cast<int>(nodes.size()); ++i) {
      auto& s = scale[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])];
      s = std::min(s, shortest);
      if (i < n_v) vertex[static_cast<std::size_t>(nodes[static_cast<std::size_t>(i)])] = 1;
    }
  }
  std::uniform_real_distribution<double> shift(-0.08, 0.08);
  for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
    if (!vertex[static_cast<std::size_t>(n)])
      for (int a = 0; a < mesh.dim; ++a)
        mesh.x[static_cast<std::size_t>(n * mesh.dim + a)] +=
            shift(rng) * scale[static_cast<std::size_t>(n)];
}

// A random point well inside the reference domain of t.
std::array<double, 3> random_reference_point(CellType t, std::mt19937& rng) {
  const int d = fem::dimension(t);
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::array<double, 3> xi{};
  const auto centre = reference_centre(t);
  if (t == CellType::tri3 || t == CellType::tri6 || t == CellType::tet4 || t == CellType::tet10) {
    // Uniform on the simplex: the gaps between sorted uniforms, pulled 10 % to the centre.
    std::vector<double> s(static_cast<std::size_t>(d) + 2, 0.0);
    for (int a = 1; a <= d; ++a) s[static_cast<std::size_t>(a)] = u(rng);
    s[static_cast<std::size_t>(d) + 1] = 1;
    std::sort(s.begin() + 1, s.begin() + d + 1);
    for (int a = 0; a < d; ++a) {
      const auto k = static_cast<std::size_t>(a);
      xi[k] = 0.9 * (s[k + 1] - s[k]) + 0.1 * centre[k];
    }
  } else {
    for (int a = 0; a < d; ++a) xi[static_cast<std::size_t>(a)] = 0.9 * (2 * u(rng) - 1);
  }
  return xi;
}

std::ostream& operator<<(std::ostream& os, const LocateCase& c) {
  return os << c.label;
}

class Locate : public ::testing::TestWithParam<LocateCase> {};

TEST_P(Locate, FindsCellAndReferencePointOnDistortedMesh) {
  const auto& p = GetParam();
  test::ScratchDir dir;
  ReadOptions o;
  if (p.size > 0) o.size = p.size;
  o.order = p.order;
  o.serendipity = p.serendipity;
  Mesh mesh =
      read_mesh(dir.write("domain.geo", p.dim == 2 ? test::unit_square_geo(p.structured_n, p.quads)
                                                   : test::unit_cube_geo(p.structured_n)),
                o);
  std::mt19937 rng(42);
  distort(mesh, rng);

  // The distortion must leave every cell valid (positive det J at its quadrature points), and
  // the map must interpolate: x(reference node i) == node i.
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto t = mesh.cell_type[static_cast<std::size_t>(c)];
    const auto rule = fem::quadrature(t, 2);
    std::array<double, 9> J{};
    for (int q = 0; q < rule.n_points; ++q)
      ASSERT_GT(jacobian(mesh, c, &rule.points[static_cast<std::size_t>(q * rule.dim)], J), 0.0)
          << "cell " << c;
    const auto ref = fem::reference_nodes(t);
    const auto nodes = mesh.cell(c);
    for (int i = 0; i < fem::n_nodes(t); ++i) {
      const auto x = map_to_physical(mesh, c, &ref[static_cast<std::size_t>(i * p.dim)]);
      for (int a = 0; a < p.dim; ++a)
        ASSERT_NEAR(x[static_cast<std::size_t>(a)],
                    mesh.node(nodes[static_cast<std::size_t>(i)])[static_cast<std::size_t>(a)],
                    1e-14);
    }
  }

  const PointLocator locator(mesh);
  std::uniform_int_distribution<std::int32_t> pick(0, mesh.n_cells() - 1);
  for (int k = 0; k < 40; ++k) {
    const auto c = pick(rng);
    const auto xi0 = random_reference_point(mesh.cell_type[static_cast<std::size_t>(c)], rng);
    const auto x = map_to_physical(mesh, c, xi0.data());
    const auto found =
        locator.locate(std::span<const double>(x.data(), static_cast<std::size_t>(p.dim)));
    ASSERT_TRUE(found.has_value()) << "cell " << c;
    EXPECT_EQ(found->cell, c);
    const auto y = map_to_physical(mesh, found->cell, found->xi.data());
    for (int a = 0; a < p.dim; ++a) {
      EXPECT_NEAR(y[static_cast<std::size_t>(a)], x[static_cast<std::size_t>(a)], 1e-12);
      EXPECT_NEAR(found->xi[static_cast<std::size_t>(a)], xi0[static_cast<std::size_t>(a)], 1e-10);
    }
  }

  // A mesh vertex belongs to several cells: the lowest-index one is returned.
  for (std::int32_t node : {mesh.cell(0)[0], mesh.cell(mesh.n_cells() / 2)[1]}) {
    std::int32_t lowest = mesh.n_cells();
    for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
      for (auto n : mesh.cell(c))
        if (n == node) lowest = std::min(lowest, c);
    const auto found = locator.locate(mesh.node(node));
    ASSERT_TRUE(found.has_value());
    EXPECT_EQ(found->cell, lowest);
    const auto y = map_to_physical(mesh, found->cell, found->xi.data());
    for (int a = 0; a < p.dim; ++a)
      EXPECT_NEAR(y[static_cast<std::size_t>(a)], mesh.node(node)[static_cast<std::size_t>(a)],
                  1e-12);
  }

  // Outside: beyond the distorted box (x < -0.2 or x > 1.5 everywhere).
  for (double x0 : {-0.3, 1.6}) {
    const std::array<double, 3> q{x0, 0.5, 0.5};
    EXPECT_FALSE(locator.locate(std::span<const double>(q.data(), static_cast<std::size_t>(p.dim)))
                     .has_value());
  }
}

INSTANTIATE_TEST_SUITE_P(Mesh, Locate,
                         ::testing::Values(LocateCase{"tri3", 2, 0, false, 0.25, 1, false},
                                           LocateCase{"tri6", 2, 0, false, 0.25, 2, false},
                                           LocateCase{"quad9", 2, 4, true, 0, 2, false},
                                           LocateCase{"quad8", 2, 4, true, 0, 2, true},
                                           LocateCase{"tet10", 3, 0, false, 0.4, 2, false},
                                           LocateCase{"hex8", 3, 3, false, 0, 1, false},
                                           LocateCase{"hex27", 3, 2, false, 0, 2, false},
                                           LocateCase{"hex20", 3, 2, false, 0, 2, true}),
                         [](const auto& info) { return info.param.label; });

// The tolerance is in reference units: a point just outside the boundary is found only with a
// tolerance larger than its reference distance, and then with xi outside the reference cell.
TEST(Locate, ToleranceOutsideTheBoundary) {
  test::ScratchDir dir;
  const Mesh mesh = read_mesh(dir.write("square.geo", test::unit_square_geo(4, true)));
  // Cells of width 1/4 map [-1, 1] onto 0.25, so 1e-4 outside is 8e-4 in reference units.
  const std::array<double, 2> q{-1e-4, 0.4};
  EXPECT_FALSE(locate_point(mesh, q, 1e-10).has_value());
  EXPECT_FALSE(locate_point(mesh, q, 5e-4).has_value());
  const auto found = locate_point(mesh, q, 1e-3);
  ASSERT_TRUE(found.has_value());
  EXPECT_NEAR(
      reference_distance(mesh.cell_type[static_cast<std::size_t>(found->cell)], found->xi.data()),
      8e-4, 1e-12);
  const auto y = map_to_physical(mesh, found->cell, found->xi.data());
  EXPECT_NEAR(y[0], q[0], 1e-14);
  EXPECT_NEAR(y[1], q[1], 1e-14);
}

} // namespace
} // namespace seam::mesh
