// Each read runs in a clean Gmsh session: options set by one .geo do not reach the next read,
// caller options override the file's, and the process environment and locale are left alone.
#include "mesh_test_support.hpp"

#include "seam/mesh/gmsh_reader.hpp"

#include <gtest/gtest.h>

#include <clocale>
#include <cstdlib>

namespace seam::mesh {
namespace {

using fem::CellType;

TEST(GmshSession, FileOptionsDoNotLeakIntoTheNextRead) {
  test::ScratchDir dir;
  const auto quadratic =
      dir.write("quadratic.geo", "Mesh.ElementOrder = 2;\nMesh.RecombineAll = 1;\n" +
                                     test::unit_square_geo(2, false));
  const auto plain = dir.write("plain.geo", test::unit_square_geo(2, false));
  const Mesh a = read_mesh(quadratic);
  for (auto t : a.cell_type) EXPECT_EQ(t, CellType::quad9);
  const Mesh b = read_mesh(plain);
  for (auto t : b.cell_type) EXPECT_EQ(t, CellType::tri3);

  // The caller's order wins over the file's.
  ReadOptions o;
  o.order = 1;
  const Mesh c = read_mesh(quadratic, o);
  for (auto t : c.cell_type) EXPECT_EQ(t, CellType::quad4);
}

TEST(GmshSession, SizeOptionRefines) {
  test::ScratchDir dir;
  const auto file = dir.write("square.geo", test::unit_square_geo(0, false));
  ReadOptions coarse, fine;
  coarse.size = 0.1;
  fine.size = 0.05;
  const auto n_coarse = read_mesh(file, coarse).n_cells();
  const auto n_fine = read_mesh(file, fine).n_cells();
  // Near-equilateral triangles of side h: about 1 / (sqrt(3) / 4 h^2) = 924 of them for
  // h = 0.05, and four times fewer for 2 h.
  EXPECT_GT(n_fine, 3 * n_coarse);
  EXPECT_GT(n_fine, 600);
  EXPECT_LT(n_fine, 1400);
}

TEST(GmshSession, EnvironmentAndLocaleUntouched) {
  const auto env = [](const char* name) {
    const char* v = std::getenv(name);
    return std::string(v != nullptr ? v : "<unset>");
  };
  const std::string path = env("PATH"), python_path = env("PYTHONPATH");
  const std::string locale = std::setlocale(LC_ALL, nullptr);
  test::ScratchDir dir;
  const auto file = dir.write("square.geo", test::unit_square_geo(2, true));
  for (int i = 0; i < 2; ++i) (void)read_mesh(file);
  EXPECT_EQ(env("PATH"), path);
  EXPECT_EQ(env("PYTHONPATH"), python_path);
  EXPECT_EQ(std::string(std::setlocale(LC_ALL, nullptr)), locale);
}

} // namespace
} // namespace seam::mesh
