// The same mesh written by Gmsh as .msh 2.2, 4.1 and binary 4.1 reads back identically, and
// equal to the mesh read from the .geo directly.
#include "mesh_test_support.hpp"

#include "seam/mesh/gmsh_reader.hpp"

#include <gmsh.h>
#include <gtest/gtest.h>

namespace seam::mesh {
namespace {

struct Format {
  std::string file;
  double version;
  bool binary;
};

// Mesh the .geo once with Gmsh and write it in every format (its own Gmsh session, closed
// before read_mesh opens another).
void write_formats(const std::filesystem::path& geo, const ReadOptions& o,
                   const std::vector<std::filesystem::path>& files,
                   const std::vector<Format>& formats) {
  gmsh::initialize(0, nullptr, false);
  gmsh::option::setNumber("General.Terminal", 0);
  gmsh::open(geo.string());
  if (o.size) gmsh::option::setNumber("Mesh.MeshSizeMax", *o.size);
  if (o.order > 0) gmsh::option::setNumber("Mesh.ElementOrder", o.order);
  gmsh::model::mesh::generate(gmsh::model::getDimension());
  for (std::size_t k = 0; k < formats.size(); ++k) {
    gmsh::option::setNumber("Mesh.MshFileVersion", formats[k].version);
    gmsh::option::setNumber("Mesh.Binary", formats[k].binary ? 1 : 0);
    gmsh::write(files[k].string());
  }
  gmsh::finalize();
}

void expect_same(const Mesh& a, const Mesh& b, double x_tol) {
  ASSERT_EQ(a.dim, b.dim);
  ASSERT_EQ(a.n_nodes(), b.n_nodes());
  ASSERT_EQ(a.n_cells(), b.n_cells());
  for (std::size_t i = 0; i < a.x.size(); ++i) ASSERT_NEAR(a.x[i], b.x[i], x_tol) << i;
  EXPECT_EQ(a.cell_type, b.cell_type);
  EXPECT_EQ(a.cell_offsets, b.cell_offsets);
  EXPECT_EQ(a.cell_nodes, b.cell_nodes);
  ASSERT_EQ(a.regions.size(), b.regions.size());
  for (std::size_t r = 0; r < a.regions.size(); ++r) {
    const auto& ra = a.regions[r];
    const auto& rb = b.regions[r];
    EXPECT_EQ(ra.name, rb.name);
    EXPECT_EQ(ra.dim, rb.dim);
    EXPECT_EQ(ra.tag, rb.tag);
    EXPECT_EQ(ra.cells, rb.cells) << ra.name;
    EXPECT_EQ(ra.facet_cell, rb.facet_cell) << ra.name;
    EXPECT_EQ(ra.facet_local, rb.facet_local) << ra.name;
    EXPECT_EQ(ra.nodes, rb.nodes) << ra.name;
  }
}

struct FormatCase {
  std::string label;
  std::string geo;
  ReadOptions options;
  std::size_t n_regions;
};

std::ostream& operator<<(std::ostream& os, const FormatCase& c) {
  return os << c.label;
}

class MshFormats : public ::testing::TestWithParam<FormatCase> {};

TEST_P(MshFormats, ReadBackIdentically) {
  const auto& p = GetParam();
  test::ScratchDir dir;
  const auto geo = dir.write("domain.geo", p.geo);
  const std::vector<Format> formats{
      {"v22.msh", 2.2, false}, {"v41.msh", 4.1, false}, {"v41b.msh", 4.1, true}};
  std::vector<std::filesystem::path> files;
  for (const auto& f : formats) files.push_back(dir / f.file);
  write_formats(geo, p.options, files, formats);

  const Mesh from_geo = read_mesh(geo, p.options);
  ASSERT_EQ(from_geo.regions.size(), p.n_regions);
  std::vector<Mesh> meshes;
  for (const auto& f : files) meshes.push_back(read_mesh(f));
  // ASCII files print 16 significant digits, so coordinates agree to round-off only; binary
  // files and the topology agree exactly.
  expect_same(meshes[0], meshes[1], 0.0);
  expect_same(meshes[2], from_geo, 0.0);
  expect_same(meshes[1], from_geo, 1e-15);
}

ReadOptions with(double size, int order) {
  ReadOptions o;
  if (size > 0) o.size = size;
  o.order = order;
  return o;
}

INSTANTIATE_TEST_SUITE_P(
    Mesh, MshFormats,
    ::testing::Values(FormatCase{"tet10", test::unit_cube_geo(0), with(0.5, 2), 7},
                      FormatCase{"hex8", test::unit_cube_geo(3), with(0, 1), 7},
                      FormatCase{"tri3", test::unit_square_geo(0, false), with(0.25, 1), 6},
                      FormatCase{"quad9", test::unit_square_geo(3, true), with(0, 2), 6}),
    [](const auto& info) { return info.param.label; });

} // namespace
} // namespace seam::mesh
