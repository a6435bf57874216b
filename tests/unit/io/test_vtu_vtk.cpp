// Cross-check with the real VTK XML readers (Debian's python3-vtk9), when installed: what VTK
// reads from seam's files must be exactly what was written. Skipped without VTK.
#include "seam/io/vtu.hpp"
#include "test_vtu_mesh.hpp"
#include "test_vtu_xml.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>
#include <map>
#include <sstream>

namespace seam::io {
namespace {

constexpr const char* python = "/usr/bin/python3";

// Prints what VTK reads, one item per line; Python's repr of a float is the shortest text
// that reads back to the same double, so the comparison below is bit-exact.
constexpr const char* reader_script = R"(import sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader, vtkXMLPUnstructuredGridReader
path = sys.argv[1]
r = vtkXMLPUnstructuredGridReader() if path.endswith('.pvtu') else vtkXMLUnstructuredGridReader()
r.SetFileName(path)
r.Update()
g = r.GetOutput()
print('points', g.GetNumberOfPoints())
print('cells', g.GetNumberOfCells())
for i in range(g.GetNumberOfPoints()):
    print('x', *[repr(v) for v in g.GetPoint(i)])
for c in range(g.GetNumberOfCells()):
    ids = g.GetCell(c).GetPointIds()
    print('cell', g.GetCellType(c), *[ids.GetId(k) for k in range(ids.GetNumberOfIds())])
for tag, data in (('point', g.GetPointData()), ('cell', g.GetCellData()), ('field', g.GetFieldData())):
    for a in range(data.GetNumberOfArrays()):
        arr = data.GetAbstractArray(a)
        n, m = arr.GetNumberOfTuples(), arr.GetNumberOfComponents()
        values = [repr(float(arr.GetComponent(t, k))) for t in range(n) for k in range(m)]
        kind = ('f' if arr.GetDataType() in (10, 11) else 'i') + str(arr.GetDataTypeSize())
        print('array', tag, arr.GetName(), kind, m, *values)
)";

bool vtk_available() {
  const std::string command =
      std::string(python) + " -c 'import vtkmodules.vtkIOXML' > /dev/null 2>&1";
  return std::system(command.c_str()) == 0;
}

struct VtkView {
  std::size_t n_points = 0, n_cells = 0;
  std::vector<double> points;
  std::vector<std::vector<long>> cells; // type, then point ids
  struct Array {
    std::string type; // "f8" (Float64), "i4" (Int32), "i8" (Int64)
    int n_components = 0;
    std::vector<double> values;
  };
  std::map<std::string, Array> arrays; // "point:displacement", "field:TimeValue", ...
};

VtkView read_with_vtk(const test::ScratchDir& dir, const std::string& file) {
  const std::string script = dir / "read.py";
  {
    std::ofstream out(script);
    out << reader_script;
  }
  const std::string listing = dir / "listing.txt";
  const std::string errors = dir / "errors.txt";
  const std::string command =
      std::string(python) + " " + script + " " + file + " > " + listing + " 2> " + errors;
  EXPECT_EQ(std::system(command.c_str()), 0) << test::read_text_file(errors);
  // VTK reports problems with a file (bad header, short data) on stderr.
  EXPECT_EQ(test::read_text_file(errors), "");

  VtkView view;
  std::istringstream lines(test::read_text_file(listing));
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream in(line);
    std::string kind;
    in >> kind;
    std::string token;
    if (kind == "points")
      in >> view.n_points;
    else if (kind == "cells")
      in >> view.n_cells;
    else if (kind == "x")
      while (in >> token) view.points.push_back(std::strtod(token.c_str(), nullptr));
    else if (kind == "cell") {
      view.cells.emplace_back();
      long id = 0;
      while (in >> id) view.cells.back().push_back(id);
    } else if (kind == "array") {
      std::string where, name;
      VtkView::Array a;
      in >> where >> name >> a.type >> a.n_components;
      while (in >> token) a.values.push_back(std::strtod(token.c_str(), nullptr));
      view.arrays[where + ":" + name] = a;
    }
  }
  return view;
}

template <class T>
void expect_array(const VtkView& view, const std::string& key, const std::string& type,
                  int n_components, const std::vector<T>& expected, std::size_t n_copies = 1) {
  const auto it = view.arrays.find(key);
  ASSERT_NE(it, view.arrays.end()) << key;
  EXPECT_EQ(it->second.type, type) << key;
  EXPECT_EQ(it->second.n_components, n_components) << key;
  ASSERT_EQ(it->second.values.size(), n_copies * expected.size()) << key;
  for (std::size_t i = 0; i < it->second.values.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(it->second.values[i]),
              std::bit_cast<std::uint64_t>(double(expected[i % expected.size()])))
        << key << "[" << i << "]";
}

void expect_mixed_mesh(const VtkView& view, std::size_t n_copies) {
  const test::MixedMesh mesh;
  EXPECT_EQ(view.n_points, n_copies * 9);
  EXPECT_EQ(view.n_cells, n_copies * 2);
  ASSERT_EQ(view.points.size(), n_copies * mesh.points.size());
  for (std::size_t i = 0; i < view.points.size(); ++i)
    EXPECT_EQ(std::bit_cast<std::uint64_t>(view.points[i]),
              std::bit_cast<std::uint64_t>(mesh.points[i % mesh.points.size()]));
  ASSERT_EQ(view.cells.size(), n_copies * 2);
  for (std::size_t copy = 0; copy < n_copies; ++copy) {
    // The second piece's points follow the first's: its ids are shifted by 9.
    const long shift = long(9 * copy);
    std::vector<long> hex{test::vtk_hexahedron}, tet{test::vtk_tetra};
    for (int k = 0; k < 8; ++k) hex.push_back(mesh.connectivity[k] + shift);
    for (int k = 8; k < 12; ++k) tet.push_back(mesh.connectivity[k] + shift);
    EXPECT_EQ(view.cells[2 * copy], hex);
    EXPECT_EQ(view.cells[2 * copy + 1], tet);
  }
  expect_array(view, "point:displacement", "f8", 3, mesh.displacement, n_copies);
  expect_array(view, "point:status", "i4", 1, mesh.status, n_copies);
  expect_array(view, "cell:von_mises", "f8", 1, mesh.von_mises, n_copies);
  expect_array(view, "cell:stress", "f8", 6, mesh.stress, n_copies);
  expect_array(view, "cell:rank", "i4", 1, mesh.rank, n_copies);
}

TEST(VtuWithVtk, BinaryAndAsciiFilesReadExactly) {
  if (!vtk_available()) GTEST_SKIP() << "python3-vtk9 not installed";
  test::ScratchDir dir("vtk_vtu");
  const test::MixedMesh mesh;
  for (const auto format : {VtkFormat::binary, VtkFormat::ascii}) {
    write_vtu(dir / "mixed.vtu", mesh.piece(), format);
    const VtkView view = read_with_vtk(dir, dir / "mixed.vtu");
    expect_mixed_mesh(view, 1);
    expect_array(view, "field:TimeValue", "f8", 1, std::vector<double>{mesh.time});
    expect_array(view, "field:CYCLE", "i8", 1, std::vector<double>{7.0});
  }
}

TEST(VtuWithVtk, ParallelFileJoinsItsPieces) {
  if (!vtk_available()) GTEST_SKIP() << "python3-vtk9 not installed";
  test::ScratchDir dir("vtk_pvtu");
  const test::MixedMesh mesh;
  const std::vector<std::string> pieces{piece_file_name("results", 1, 0),
                                        piece_file_name("results", 1, 1)};
  for (const auto& piece : pieces) write_vtu(dir / piece, mesh.piece());
  write_pvtu(dir / "results_00001.pvtu", mesh.piece(), pieces);
  expect_mixed_mesh(read_with_vtk(dir, dir / "results_00001.pvtu"), 2);
}

} // namespace
} // namespace seam::io
