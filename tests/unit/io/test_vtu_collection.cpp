// The .pvtu parallel header and the .pvd time collection: well-formed XML that lists the
// right pieces, fields, files and times.
#include "seam/common/error.hpp"
#include "seam/io/vtu.hpp"
#include "test_vtu_mesh.hpp"
#include "test_vtu_xml.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cstdlib>

namespace seam::io {
namespace {

using test::XmlElement;

TEST(Pvd, EmptyCollectionIsWrittenAtOnce) {
  test::ScratchDir dir("pvd_empty");
  const PvdCollection pvd(dir / "results.pvd");
  const XmlElement root = test::parse_xml_file(dir / "results.pvd");
  EXPECT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attr("type"), "Collection");
  EXPECT_TRUE(root.child("Collection").children.empty());
}

TEST(Pvd, CollectionIsValidAfterEveryStep) {
  test::ScratchDir dir("pvd_steps");
  const std::string file = dir / "results.pvd";
  PvdCollection pvd(file);
  const std::vector<double> times{0.0, 0.1, 0.1 + 0.2, 1.0 / 3.0, 12.5};
  for (std::size_t step = 0; step < times.size(); ++step) {
    pvd.add(times[step], step_file_name("results", std::int64_t(step), ".vtu"));
    // A run that stopped here would leave exactly this file behind.
    const XmlElement root = test::parse_xml_file(file);
    const auto data_sets = root.child("Collection").all("DataSet");
    ASSERT_EQ(data_sets.size(), step + 1);
    for (std::size_t k = 0; k <= step; ++k) {
      const double t = std::strtod(data_sets[k]->attr("timestep").c_str(), nullptr);
      EXPECT_EQ(std::bit_cast<std::uint64_t>(t), std::bit_cast<std::uint64_t>(times[k]));
      EXPECT_EQ(data_sets[k]->attr("file"), step_file_name("results", std::int64_t(k), ".vtu"));
      EXPECT_EQ(data_sets[k]->attr("part"), "0");
    }
  }
  EXPECT_EQ(pvd.entries().size(), times.size());
  EXPECT_FALSE(std::filesystem::exists(file + ".tmp"));
}

TEST(Pvd, FreshCollectionReplacesAnOldOne) {
  test::ScratchDir dir("pvd_fresh");
  {
    PvdCollection old(dir / "results.pvd");
    old.add(1.0, "old_00001.vtu");
  }
  const PvdCollection fresh(dir / "results.pvd");
  EXPECT_TRUE(test::parse_xml_file(dir / "results.pvd").child("Collection").children.empty());
}

TEST(Pvtu, ListsPiecesAndTheFieldsOfThePieces) {
  test::ScratchDir dir("pvtu");
  const test::MixedMesh mesh;
  const std::vector<std::string> pieces{piece_file_name("results", 3, 0),
                                        piece_file_name("results", 3, 1)};
  for (const auto& piece : pieces) write_vtu(dir / piece, mesh.piece());
  const std::string pvtu = dir / step_file_name("results", 3, ".pvtu");
  write_pvtu(pvtu, mesh.piece(), pieces);

  const XmlElement root = test::parse_xml_file(pvtu);
  EXPECT_EQ(root.attr("type"), "PUnstructuredGrid");
  EXPECT_EQ(root.attr("header_type"), "UInt64");
  const XmlElement& grid = root.child("PUnstructuredGrid");
  EXPECT_EQ(grid.attr("GhostLevel"), "0");

  const auto listed = grid.all("Piece");
  ASSERT_EQ(listed.size(), pieces.size());
  for (std::size_t r = 0; r < pieces.size(); ++r) {
    EXPECT_EQ(listed[r]->attr("Source"), pieces[r]);
    EXPECT_TRUE(std::filesystem::exists(dir / listed[r]->attr("Source")));
  }

  const auto time = test::data_array_values<double>(grid.child("FieldData").array("TimeValue"));
  ASSERT_EQ(time.size(), 1u);
  EXPECT_EQ(std::bit_cast<std::uint64_t>(time[0]), std::bit_cast<std::uint64_t>(mesh.time));

  // Every PDataArray declaration must match the DataArray of the same name in the pieces.
  const XmlElement piece = test::parse_xml_file(dir / pieces[0]);
  const XmlElement& piece_grid = piece.child("UnstructuredGrid").child("Piece");
  const std::pair<const char*, const char*> sections[] = {
      {"PPointData", "PointData"}, {"PCellData", "CellData"}, {"PPoints", "Points"}};
  for (const auto& [parallel, serial] : sections) {
    const XmlElement& declared = grid.child(parallel);
    const XmlElement& written = piece_grid.child(serial);
    ASSERT_EQ(declared.children.size(), written.children.size()) << parallel;
    for (std::size_t i = 0; i < declared.children.size(); ++i) {
      const XmlElement& d = declared.children[i];
      const XmlElement& w = written.children[i];
      EXPECT_EQ(d.name, "PDataArray");
      EXPECT_EQ(d.attr("Name"), w.attr("Name"));
      EXPECT_EQ(d.attr("type"), w.attr("type"));
      const auto components = [](const XmlElement& e) {
        return e.has_attr("NumberOfComponents") ? e.attr("NumberOfComponents") : "1";
      };
      EXPECT_EQ(components(d), components(w)) << d.attr("Name");
    }
  }
}

TEST(Pvtu, NeedsAtLeastOnePiece) {
  test::ScratchDir dir("pvtu_none");
  const test::MixedMesh mesh;
  EXPECT_THROW(write_pvtu(dir / "x.pvtu", mesh.piece(), {}), InternalError);
}

} // namespace
} // namespace seam::io
