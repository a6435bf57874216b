// The .vtu writer, checked by reading the file back with the independent XML/base64 readers
// of test_vtu_xml.hpp and comparing every value bit for bit.
#include "seam/common/error.hpp"
#include "seam/io/vtu.hpp"
#include "test_vtu_mesh.hpp"
#include "test_vtu_xml.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <filesystem>

namespace seam::io {
namespace {

using test::XmlElement;

template <class T>
void expect_bits_equal(const std::vector<T>& got, const std::vector<T>& expected,
                       const std::string& what) {
  ASSERT_EQ(got.size(), expected.size()) << what;
  for (std::size_t i = 0; i < got.size(); ++i) {
    if constexpr (std::is_same_v<T, double>)
      EXPECT_EQ(std::bit_cast<std::uint64_t>(got[i]), std::bit_cast<std::uint64_t>(expected[i]))
          << what << "[" << i << "] = " << got[i] << ", expected " << expected[i];
    else
      EXPECT_EQ(got[i], expected[i]) << what << "[" << i << "]";
  }
}

void expect_array_header(const XmlElement& array, const std::string& type, int n_components,
                         VtkFormat format) {
  EXPECT_EQ(array.attr("type"), type) << array.attr("Name");
  const int declared =
      array.has_attr("NumberOfComponents") ? std::stoi(array.attr("NumberOfComponents")) : 1;
  EXPECT_EQ(declared, n_components) << array.attr("Name");
  EXPECT_EQ(array.attr("format"), format == VtkFormat::binary ? "binary" : "ascii");
}

void check_mixed_mesh_file(const std::string& file, VtkFormat format) {
  const test::MixedMesh mesh;
  const XmlElement root = test::parse_xml_file(file);
  ASSERT_EQ(root.name, "VTKFile");
  EXPECT_EQ(root.attr("type"), "UnstructuredGrid");
  EXPECT_EQ(root.attr("header_type"), "UInt64");
  EXPECT_EQ(root.attr("byte_order"), "LittleEndian");
  const XmlElement& grid = root.child("UnstructuredGrid");

  const XmlElement& field_data = grid.child("FieldData");
  const XmlElement& time = field_data.array("TimeValue");
  EXPECT_EQ(time.attr("NumberOfTuples"), "1");
  expect_bits_equal(test::data_array_values<double>(time), {mesh.time}, "TimeValue");
  const XmlElement& cycle = field_data.array("CYCLE");
  EXPECT_EQ(test::data_array_values<std::int64_t>(cycle), std::vector<std::int64_t>{7});

  const XmlElement& piece = grid.child("Piece");
  EXPECT_EQ(piece.attr("NumberOfPoints"), "9");
  EXPECT_EQ(piece.attr("NumberOfCells"), "2");

  const XmlElement& points = piece.child("Points").child("DataArray");
  expect_array_header(points, "Float64", 3, format);
  expect_bits_equal(test::data_array_values<double>(points), mesh.points, "points");

  const XmlElement& cells = piece.child("Cells");
  const XmlElement& connectivity = cells.array("connectivity");
  expect_array_header(connectivity, "Int32", 1, format);
  expect_bits_equal(test::data_array_values<std::int32_t>(connectivity), mesh.connectivity,
                    "connectivity");
  expect_bits_equal(test::data_array_values<std::int32_t>(cells.array("offsets")), mesh.offsets,
                    "offsets");
  const XmlElement& types = cells.array("types");
  expect_array_header(types, "UInt8", 1, format);
  expect_bits_equal(test::data_array_values<std::uint8_t>(types), mesh.types, "types");

  const XmlElement& point_data = piece.child("PointData");
  ASSERT_EQ(point_data.children.size(), 2u);
  expect_array_header(point_data.array("displacement"), "Float64", 3, format);
  expect_bits_equal(test::data_array_values<double>(point_data.array("displacement")),
                    mesh.displacement, "displacement");
  expect_array_header(point_data.array("status"), "Int32", 1, format);
  expect_bits_equal(test::data_array_values<std::int32_t>(point_data.array("status")), mesh.status,
                    "status");

  const XmlElement& cell_data = piece.child("CellData");
  ASSERT_EQ(cell_data.children.size(), 3u);
  expect_array_header(cell_data.array("von_mises"), "Float64", 1, format);
  expect_bits_equal(test::data_array_values<double>(cell_data.array("von_mises")), mesh.von_mises,
                    "von_mises");
  expect_array_header(cell_data.array("stress"), "Float64", 6, format);
  expect_bits_equal(test::data_array_values<double>(cell_data.array("stress")), mesh.stress,
                    "stress");
  expect_array_header(cell_data.array("rank"), "Int32", 1, format);
  expect_bits_equal(test::data_array_values<std::int32_t>(cell_data.array("rank")), mesh.rank,
                    "rank");
}

TEST(Base64, Rfc4648TestVectors) {
  // RFC 4648, section 10.
  const std::pair<std::string_view, std::string_view> vectors[] = {{"", ""},
                                                                   {"f", "Zg=="},
                                                                   {"fo", "Zm8="},
                                                                   {"foo", "Zm9v"},
                                                                   {"foob", "Zm9vYg=="},
                                                                   {"fooba", "Zm9vYmE="},
                                                                   {"foobar", "Zm9vYmFy"}};
  for (const auto& [plain, encoded] : vectors)
    EXPECT_EQ(base64_encode(std::as_bytes(std::span(plain.data(), plain.size()))), encoded)
        << "'" << plain << "'";
}

TEST(Base64, EveryByteValueAndLengthRoundTrips) {
  std::vector<std::byte> bytes;
  for (int i = 0; i < 256; ++i) bytes.push_back(std::byte(255 - i));
  for (std::size_t n = 0; n <= bytes.size(); n += 1 + n / 16) {
    const auto part = std::span(bytes).first(n);
    const std::string encoded = base64_encode(part);
    EXPECT_EQ(encoded.size(), (n + 2) / 3 * 4);
    const auto decoded = test::base64_decode(encoded);
    EXPECT_TRUE(std::equal(decoded.begin(), decoded.end(), part.begin(), part.end())) << n;
  }
}

TEST(Vtu, MixedMeshBinaryRoundTripsBitExactly) {
  test::ScratchDir dir("vtu_binary");
  const test::MixedMesh mesh;
  write_vtu(dir / "mixed.vtu", mesh.piece());
  check_mixed_mesh_file(dir / "mixed.vtu", VtkFormat::binary);
  // Written under a temporary name, then renamed: nothing else is left behind.
  EXPECT_EQ(std::distance(std::filesystem::directory_iterator(dir.path()),
                          std::filesystem::directory_iterator()),
            1);
}

TEST(Vtu, MixedMeshAsciiRoundTripsBitExactly) {
  test::ScratchDir dir("vtu_ascii");
  const test::MixedMesh mesh;
  write_vtu(dir / "mixed.vtu", mesh.piece(), VtkFormat::ascii);
  check_mixed_mesh_file(dir / "mixed.vtu", VtkFormat::ascii);
}

TEST(Vtu, TwoDimensionalPointsGetZeroZ) {
  test::ScratchDir dir("vtu_2d");
  // A unit square split into a quad and a triangle: points given with two coordinates.
  const std::vector<double> xy{0.0, 0.0, 0.5, 0.0, 0.5, 1.0 / 3.0, 0.0, 1.0, 1.0, 0.1};
  const std::vector<std::int32_t> connectivity{0, 1, 2, 3, 1, 4, 2};
  const std::vector<std::int32_t> offsets{4, 7};
  const std::vector<std::uint8_t> types{test::vtk_quad, test::vtk_triangle};
  const std::vector<double> u{0.1, -0.2, 0.3, -0.4, 0.5, -0.6, 0.7, -0.8, 0.9, -1.0};
  VtuPiece piece;
  piece.point_dim = 2;
  piece.points = xy;
  piece.connectivity = connectivity;
  piece.offsets = offsets;
  piece.types = types;
  piece.point_data.emplace_back("u", 2, std::span<const double>(u));
  write_vtu(dir / "square.vtu", piece);

  const XmlElement root = test::parse_xml_file(dir / "square.vtu");
  const XmlElement& grid_piece = root.child("UnstructuredGrid").child("Piece");
  EXPECT_EQ(grid_piece.attr("NumberOfPoints"), "5");
  const auto xyz = test::data_array_values<double>(grid_piece.child("Points").child("DataArray"));
  ASSERT_EQ(xyz.size(), 15u);
  for (std::size_t i = 0; i < 5; ++i) {
    EXPECT_EQ(std::bit_cast<std::uint64_t>(xyz[3 * i]), std::bit_cast<std::uint64_t>(xy[2 * i]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(xyz[3 * i + 1]),
              std::bit_cast<std::uint64_t>(xy[2 * i + 1]));
    EXPECT_EQ(std::bit_cast<std::uint64_t>(xyz[3 * i + 2]), 0u); // +0.0
  }
  expect_bits_equal(test::data_array_values<double>(grid_piece.child("PointData").array("u")), u,
                    "u");
  // No time given: no FieldData.
  EXPECT_TRUE(root.child("UnstructuredGrid").all("FieldData").empty());
}

TEST(Vtu, EmptyPieceIsValid) {
  test::ScratchDir dir("vtu_empty");
  VtuPiece piece;
  piece.point_data.emplace_back("displacement", 3, std::span<const double>());
  piece.cell_data.emplace_back("rank", 1, std::span<const std::int32_t>());
  write_vtu(dir / "empty.vtu", piece);
  const XmlElement root = test::parse_xml_file(dir / "empty.vtu");
  const XmlElement& p = root.child("UnstructuredGrid").child("Piece");
  EXPECT_EQ(p.attr("NumberOfPoints"), "0");
  EXPECT_EQ(p.attr("NumberOfCells"), "0");
  EXPECT_TRUE(test::data_array_values<double>(p.child("Points").child("DataArray")).empty());
  EXPECT_TRUE(test::data_array_values<double>(p.child("PointData").array("displacement")).empty());
}

TEST(Vtu, SpecialCharactersInNamesAreEscaped) {
  test::ScratchDir dir("vtu_names");
  const std::vector<double> x{0, 0, 0};
  const std::vector<double> value{1.5};
  VtuPiece piece;
  piece.points = x;
  const std::string name = "a<b>&\"c'";
  piece.point_data.emplace_back(name, 1, std::span<const double>(value));
  write_vtu(dir / "names.vtu", piece);
  const XmlElement root = test::parse_xml_file(dir / "names.vtu");
  const XmlElement& data = root.child("UnstructuredGrid").child("Piece").child("PointData");
  EXPECT_EQ(data.child("DataArray").attr("Name"), name);
}

TEST(Vtu, RewritingReplacesTheFile) {
  test::ScratchDir dir("vtu_rewrite");
  test::MixedMesh mesh;
  write_vtu(dir / "mixed.vtu", mesh.piece());
  mesh.time = 2.5;
  write_vtu(dir / "mixed.vtu", mesh.piece());
  const XmlElement root = test::parse_xml_file(dir / "mixed.vtu");
  const auto t = test::data_array_values<double>(
      root.child("UnstructuredGrid").child("FieldData").array("TimeValue"));
  EXPECT_EQ(t, std::vector<double>{2.5});
}

TEST(Vtu, InconsistentArraysAreRejected) {
  test::ScratchDir dir("vtu_bad");
  const test::MixedMesh mesh;
  const std::string file = dir / "bad.vtu";
  auto expect_rejected = [&](const VtuPiece& p, const char* why) {
    EXPECT_THROW(write_vtu(file, p), InternalError) << why;
    EXPECT_FALSE(std::filesystem::exists(file)) << why;
  };

  VtuPiece p = mesh.piece();
  p.offsets = std::span(mesh.offsets).first(1);
  expect_rejected(p, "fewer offsets than types");

  const std::vector<std::int32_t> short_offsets{8, 11};
  p = mesh.piece();
  p.offsets = short_offsets;
  expect_rejected(p, "last offset short of the connectivity");

  const std::vector<std::int32_t> decreasing{8, 4};
  p = mesh.piece();
  p.offsets = decreasing;
  expect_rejected(p, "decreasing offsets");

  std::vector<std::int32_t> connectivity = mesh.connectivity;
  connectivity.back() = 9;
  p = mesh.piece();
  p.connectivity = connectivity;
  expect_rejected(p, "node index past the points");

  p = mesh.piece();
  p.point_data.emplace_back("short", 3, std::span(mesh.displacement).first(26));
  expect_rejected(p, "point field with too few values");

  p = mesh.piece();
  p.cell_data.emplace_back("rank", 1, std::span<const std::int32_t>(mesh.rank));
  expect_rejected(p, "duplicate field name");

  p = mesh.piece();
  p.point_dim = 4;
  expect_rejected(p, "point_dim 4");
}

TEST(Vtu, UnwritableDirectoryIsAnInputError) {
  const test::MixedMesh mesh;
  EXPECT_THROW(write_vtu("/nonexistent_seam_dir/out.vtu", mesh.piece()), InputError);
}

TEST(Vtu, StepAndPieceFileNames) {
  EXPECT_EQ(step_file_name("results", 0, ".vtu"), "results_00000.vtu");
  EXPECT_EQ(step_file_name("results", 42, ".pvtu"), "results_00042.pvtu");
  EXPECT_EQ(step_file_name("results", 1234567, ".vtu"), "results_1234567.vtu");
  EXPECT_EQ(piece_file_name("results", 42, 3), "results_00042_p3.vtu");
}

} // namespace
} // namespace seam::io
