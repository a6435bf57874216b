// Facet topology on small hand-built meshes, where every answer can be counted by hand, and
// the consistency check of hand-built meshes.
#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

namespace seam::mesh {
namespace {

using fem::CellType;

// Two tets sharing the face (1, 2, 3): 0 below it, 4 above.
Mesh two_tets() {
  Mesh m;
  m.dim = 3;
  m.x = {0, 0, 0, 1, 0, 0, 0, 1, 0, 0, 0, 1, 1, 1, 1};
  const std::int32_t a[4] = {0, 1, 2, 3}, b[4] = {1, 2, 3, 4};
  m.add_cell(CellType::tet4, a);
  m.add_cell(CellType::tet4, b);
  return m;
}

TEST(Facets, TwoTetsShareOneFace) {
  const Mesh m = two_tets();
  ASSERT_NO_THROW(m.check());
  const FacetIndex index(m);
  EXPECT_EQ(index.n_facets(), 7u); // 4 + 4 - 1 shared
  const std::int32_t shared[3] = {3, 1, 2};
  const auto* e = index.find(shared);
  ASSERT_NE(e, nullptr);
  EXPECT_EQ(e->n_cells, 2);
  EXPECT_EQ(e->cells[0].cell, 0);
  EXPECT_EQ(e->cells[1].cell, 1);
  const auto other = index.neighbour(m, e->cells[0]);
  ASSERT_TRUE(other.has_value());
  EXPECT_EQ(other->cell, 1);
  EXPECT_EQ(other->local, e->cells[1].local);
  const std::int32_t none[3] = {0, 1, 4};
  EXPECT_EQ(index.find(none), nullptr);

  const auto exterior = exterior_facets(m);
  EXPECT_EQ(exterior.size(), 6);
  EXPECT_TRUE(std::is_sorted(exterior.cell.begin(), exterior.cell.end()));
  // Boundary of the union: three unit right triangles (area 1/2 each) of the first tet and the
  // three faces of the second tet through (1, 1, 1), each with area sqrt(3)/2.
  double area = 0;
  for (std::int32_t k = 0; k < exterior.size(); ++k)
    area += facet_area(m, exterior.cell[static_cast<std::size_t>(k)],
                       exterior.local[static_cast<std::size_t>(k)]);
  EXPECT_NEAR(area, 1.5 + 1.5 * std::sqrt(3.0), 1e-14);
  EXPECT_NEAR(cell_volume(m, 0), 1.0 / 6.0, 1e-15);
  // det[(-1, 1, 0), (-1, 0, 1), (0, 1, 1)] / 6 = 2 / 6.
  EXPECT_NEAR(cell_volume(m, 1), 1.0 / 3.0, 1e-15);
}

// A 2 x 1 strip of quads next to a triangle: 3 cells, 11 cell edges, 2 interior, 7 on the boundary.
TEST(Facets, MixedQuadTriangleStrip) {
  Mesh m;
  m.dim = 2;
  m.x = {0, 0, 1, 0, 2, 0, 0, 1, 1, 1, 2, 1, 3, 0};
  const std::int32_t q0[4] = {0, 1, 4, 3}, q1[4] = {1, 2, 5, 4}, t[3] = {2, 6, 5};
  m.add_cell(CellType::quad4, q0);
  m.add_cell(CellType::quad4, q1);
  m.add_cell(CellType::tri3, t);
  ASSERT_NO_THROW(m.check());
  const auto exterior = exterior_facets(m);
  EXPECT_EQ(exterior.size(), 7);
  double perimeter = 0;
  for (std::int32_t k = 0; k < exterior.size(); ++k)
    perimeter += facet_area(m, exterior.cell[static_cast<std::size_t>(k)],
                            exterior.local[static_cast<std::size_t>(k)]);
  EXPECT_NEAR(perimeter, 3 + 2 + 1 + std::sqrt(2.0), 1e-14); // bottom, top, left, hypotenuse
  double area = 0;
  for (std::int32_t c = 0; c < m.n_cells(); ++c) area += cell_volume(m, c);
  EXPECT_NEAR(area, 2.5, 1e-14);
}

TEST(Facets, CheckRejectsInconsistentMeshes) {
  Mesh m = two_tets();
  m.cell_nodes[3] = 9; // node out of range
  EXPECT_THROW(m.check(), InternalError);
  m = two_tets();
  m.cell_offsets.pop_back();
  EXPECT_THROW(m.check(), InternalError);
  m = two_tets();
  m.regions.push_back({"bad", 2, 1, {}, {0}, {7}, {}});
  EXPECT_THROW(m.check(), InternalError); // a tet has 4 facets
  m = two_tets();
  m.dim = 2;
  EXPECT_THROW(m.check(), InternalError);
}

} // namespace
} // namespace seam::mesh
