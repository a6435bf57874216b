// Bad mesh input ends in an InputError that names the file and says what is wrong; a failed
// read leaves Gmsh usable for the next one.
#include "mesh_test_support.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

namespace seam::mesh {
namespace {

// The InputError message of read_mesh(file, options), or "" if it did not throw.
std::string read_error(const std::filesystem::path& file, const ReadOptions& options = {}) {
  try {
    (void)read_mesh(file, options);
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

#define EXPECT_MESSAGE_HAS(message, text)                                                          \
  EXPECT_NE((message).find(text), std::string::npos) << "message: " << (message)

TEST(ReadErrors, MissingFile) {
  test::ScratchDir dir;
  const auto file = dir / "nowhere.msh";
  const auto message = read_error(file);
  EXPECT_MESSAGE_HAS(message, file.string());
  EXPECT_MESSAGE_HAS(message, "does not exist");
}

TEST(ReadErrors, UnknownExtension) {
  test::ScratchDir dir;
  const auto file = dir.write("mesh.txt", "1 2 3\n");
  EXPECT_MESSAGE_HAS(read_error(file), "unknown extension");
}

TEST(ReadErrors, GarbageFilesThenAGoodOne) {
  test::ScratchDir dir;
  const auto msh = dir.write("garbage.msh", "this is not a mesh\n$MeshFormat\n@@@\n");
  auto message = read_error(msh);
  EXPECT_MESSAGE_HAS(message, msh.string());
  EXPECT_MESSAGE_HAS(message, "garbage.msh");

  const auto geo = dir.write("garbage.geo", "Point(1) = {0, 0, 0;\nfoo bar\n");
  message = read_error(geo);
  EXPECT_MESSAGE_HAS(message, geo.string());
  EXPECT_MESSAGE_HAS(message, "syntax error");

  // Gmsh must still work after its parser failed.
  const auto good = dir.write("good.geo", test::unit_square_geo(2, true));
  const Mesh mesh = read_mesh(good);
  EXPECT_EQ(mesh.n_cells(), 4);
}

TEST(ReadErrors, TruncatedMsh) {
  test::ScratchDir dir;
  const auto good = dir.write("good.geo", test::unit_square_geo(4, true));
  const Mesh mesh = read_mesh(good);
  EXPECT_EQ(mesh.n_cells(), 16);
  // A hand-written msh 4.1 whose element block promises more elements than it has.
  const auto file = dir.write("truncated.msh", R"($MeshFormat
4.1 0 8
$EndMeshFormat
$Nodes
1 4 1 4
2 1 0 4
1
2
3
4
0 0 0
1 0 0
1 1 0
0 1 0
$EndNodes
$Elements
1 2 1 2
2 1 3 2
1 1 2 3 4
)");
  EXPECT_MESSAGE_HAS(read_error(file), "truncated.msh");
}

// One quad4 [0,1]^2 in msh 4.1 with the element line given: for hand-broken variants.
std::string one_quad_msh41(const std::string& element, const std::string& node_3 = "1 1 0") {
  return "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n"
         "0 0 0\n1 0 0\n" +
         node_3 + "\n0 1 0\n$EndNodes\n$Elements\n1 1 1 1\n2 1 3 1\n" + element +
         "\n$EndElements\n";
}

TEST(ReadErrors, NegativeNodeTagInAnElement) {
  test::ScratchDir dir;
  // Gmsh itself accepts the -1 and then crashes on the missing node; seam stops first.
  const auto file = dir.write("negative.msh", one_quad_msh41("1 1 2 -1 4"));
  const auto message = read_error(file);
  EXPECT_MESSAGE_HAS(message, "negative.msh");
  EXPECT_MESSAGE_HAS(message, "line 19");
  EXPECT_MESSAGE_HAS(message, "$Elements: a node tag -1 is out of range [1, 4]");
  // The same quad with its nodes in order reads.
  EXPECT_EQ(read_mesh(dir.write("good.msh", one_quad_msh41("1 1 2 3 4"))).n_cells(), 1);
}

TEST(ReadErrors, Msh41CountsAndNamesThatGmshTrusts) {
  test::ScratchDir dir;
  // Each of these made Gmsh 4.8 crash (heap corruption, segfault) instead of reporting.
  auto text = one_quad_msh41("1 1 2 3 4");
  auto message =
      read_error(dir.write("count.msh", text.replace(text.find("1 4 1 4"), 7, "1 0 1 4")));
  EXPECT_MESSAGE_HAS(message, "count.msh");
  EXPECT_MESSAGE_HAS(message, "line 6: $Nodes: the number of nodes in the block 4 is out of range");
  text = one_quad_msh41("1 1 2 3 4");
  text.insert(text.find("$Nodes"), "$PhysicalNames\n1\n-1\n$EndPhysicalNames\n");
  message = read_error(dir.write("names.msh", text));
  EXPECT_MESSAGE_HAS(message, "line 6: $PhysicalNames: a dimension -1 is out of range [0, 3]");
  text = one_quad_msh41("1 1 2 3 4");
  text.insert(text.find("$Nodes"), "$PhysicalNames\n1\n2 1 \"body\n$EndPhysicalNames\n");
  message = read_error(dir.write("quote.msh", text));
  EXPECT_MESSAGE_HAS(message, "expected DIM TAG \"NAME\"");
  text = one_quad_msh41("1 1 2 3 4");
  message = read_error(dir.write("short.msh", text.replace(text.find("2 1 3 1"), 7, "2 1 3 2")));
  EXPECT_MESSAGE_HAS(message, "$Elements: the number of elements in the block 2 is out of range");
}

TEST(ReadErrors, InvertedDegenerateOrNonFiniteCell) {
  test::ScratchDir dir;
  // Clockwise: det dX/dxi = -1/4 everywhere.
  auto message = read_error(dir.write("clockwise.msh", one_quad_msh41("1 1 4 3 2")));
  EXPECT_MESSAGE_HAS(message, "clockwise.msh");
  EXPECT_MESSAGE_HAS(message, "element 1 (quad4) is inverted or degenerate");
  EXPECT_MESSAGE_HAS(message, "det(dX/dxi) = -0.25");
  // Node 3 moved across the diagonal 2-4: the quad folds over at the quadrature points near 3.
  message = read_error(dir.write("folded.msh", one_quad_msh41("1 1 2 3 4", "0.2 0.2 0")));
  EXPECT_MESSAGE_HAS(message, "is inverted or degenerate");
  // Node 3 on node 1: the quad collapses onto a triangle traversed back and forth.
  message = read_error(dir.write("collapsed.msh", one_quad_msh41("1 1 2 3 4", "0 0 0")));
  EXPECT_MESSAGE_HAS(message, "is inverted or degenerate");
  message = read_error(dir.write("nan.msh", one_quad_msh41("1 1 2 3 4", "nan 1 0")));
  EXPECT_MESSAGE_HAS(message, "nan.msh");
  EXPECT_MESSAGE_HAS(message, "node 3 has a coordinate that is not a finite number");
}

TEST(ReadErrors, UnsupportedElementType) {
  test::ScratchDir dir;
  // Extruding triangles with layers gives prisms (Gmsh type 6), which seam does not support.
  const auto file = dir.write("prisms.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 1};
Curve Loop(1) = {1, 2, 3}; Plane Surface(1) = {1};
Extrude {0, 0, 1} { Surface{1}; Layers{2}; Recombine; }
)");
  const auto message = read_error(file);
  EXPECT_MESSAGE_HAS(message, "prisms.geo");
  EXPECT_MESSAGE_HAS(message, "not supported");
  EXPECT_MESSAGE_HAS(message, "Gmsh element type 6");
}

TEST(ReadErrors, PlanarMeshOffTheXYPlane) {
  test::ScratchDir dir;
  const auto file = dir.write("lifted.geo", R"(
Point(1) = {0, 0, 0.5}; Point(2) = {1, 0, 0.5}; Point(3) = {1, 1, 0.5}; Point(4) = {0, 1, 0.5};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
)");
  EXPECT_MESSAGE_HAS(read_error(file), "z = 0");
}

TEST(ReadErrors, BoundaryElementThatIsNoFacet) {
  test::ScratchDir dir;
  // Curve 5 is meshed but touches no triangle.
  const auto file = dir.write("stray.geo", test::unit_square_geo(2, false) + R"(
Point(11) = {2, 0, 0}; Point(12) = {3, 0, 0}; Line(5) = {11, 12};
Physical Curve("stray") = {5};
)");
  const auto message = read_error(file);
  EXPECT_MESSAGE_HAS(message, "stray.geo");
  EXPECT_MESSAGE_HAS(message, "'stray'");
}

TEST(ReadErrors, NoCellsOfDimensionTwoOrThree) {
  test::ScratchDir dir;
  const auto file = dir.write("curve.geo", "Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0};\n"
                                           "Line(1) = {1, 2};\nPhysical Curve(\"c\") = {1};\n");
  EXPECT_MESSAGE_HAS(read_error(file), "no elements of dimension 2 or 3");
  const auto empty = dir.write("empty.msh", "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n");
  EXPECT_MESSAGE_HAS(read_error(empty), "no elements at all");
}

TEST(ReadErrors, DimensionMismatchAndBadOptions) {
  test::ScratchDir dir;
  const auto file = dir.write("square.geo", test::unit_square_geo(2, true));
  ReadOptions o;
  o.dim = 3;
  EXPECT_MESSAGE_HAS(read_error(file, o), "dimension 2 but dimension 3");
  o = {};
  o.order = 3;
  EXPECT_MESSAGE_HAS(read_error(file, o), "order");
  o = {};
  o.size = -1.0;
  EXPECT_MESSAGE_HAS(read_error(file, o), "size");
}

TEST(ReadErrors, RegionLookupListsTheRegions) {
  test::ScratchDir dir;
  const Mesh mesh = read_mesh(dir.write("square.geo", test::unit_square_geo(2, true)));
  EXPECT_EQ(mesh.find_region("nope"), nullptr);
  EXPECT_EQ(mesh.find_region("left", 2), nullptr);
  ASSERT_NE(mesh.find_region("left", 1), nullptr);
  try {
    (void)mesh.region("nope");
    FAIL() << "no exception";
  } catch (const InputError& e) {
    const std::string message = e.what();
    EXPECT_MESSAGE_HAS(message, "'nope'");
    EXPECT_MESSAGE_HAS(message, "bottom (dim 1)");
  }
}

TEST(ReadErrors, UnnamedGroupsAreNamedByDimensionAndTag) {
  test::ScratchDir dir;
  const auto file = dir.write("unnamed.geo", R"(
Point(1) = {0, 0, 0}; Point(2) = {1, 0, 0}; Point(3) = {1, 1, 0}; Point(4) = {0, 1, 0};
Line(1) = {1, 2}; Line(2) = {2, 3}; Line(3) = {3, 4}; Line(4) = {4, 1};
Curve Loop(1) = {1, 2, 3, 4}; Plane Surface(1) = {1};
Physical Surface(7) = {1};
Physical Curve(12) = {1, 2};
)");
  const Mesh mesh = read_mesh(file);
  const auto* body = mesh.find_region("2:7", 2);
  ASSERT_NE(body, nullptr);
  EXPECT_EQ(body->tag, 7);
  EXPECT_EQ(body->cells.size(), static_cast<std::size_t>(mesh.n_cells()));
  ASSERT_NE(mesh.find_region("1:12", 1), nullptr);
}

} // namespace
} // namespace seam::mesh
