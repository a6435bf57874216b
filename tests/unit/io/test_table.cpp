// CSV tables: doubles round-trip exactly, rows reach the file as soon as they are added,
// strings stay as they are unless CSV needs quotes, fresh runs truncate and restarts append.
#include "seam/common/error.hpp"
#include "seam/io/table.hpp"
#include "test_vtu_xml.hpp"

#include <gtest/gtest.h>

#include <bit>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <random>
#include <sstream>

namespace seam::io {
namespace {

std::vector<std::string> lines_of(const std::string& file) {
  std::istringstream in(test::read_text_file(file));
  std::vector<std::string> lines;
  std::string line;
  while (std::getline(in, line)) lines.push_back(line);
  return lines;
}

std::vector<std::string> split(const std::string& line) {
  std::vector<std::string> fields;
  std::istringstream in(line);
  std::string field;
  while (std::getline(in, field, ',')) fields.push_back(field);
  return fields;
}

TEST(CsvTable, HeaderThenRows) {
  test::ScratchDir dir("csv_basic");
  const std::string file = dir / "reactions.csv";
  {
    CsvTable table(file, {"step", "time", "region", "fx", "fy", "fz"});
    table.add_row({1, 0.5, "bottom", 1.25, -2.0, 0.0});
    table.add_row({2, 1.0, std::string("top"), -1e-300, 3e10, -0.0});
  }
  const auto lines = lines_of(file);
  ASSERT_EQ(lines.size(), 3u);
  EXPECT_EQ(lines[0], "step,time,region,fx,fy,fz");
  EXPECT_EQ(lines[1], "1,0.5,bottom,1.25,-2,0");
  EXPECT_EQ(lines[2], "2,1,top,-1e-300,3e+10,-0");
}

TEST(CsvTable, DoublesRoundTripExactly) {
  test::ScratchDir dir("csv_doubles");
  const std::string file = dir / "steps.csv";
  std::vector<double> values{0.1,
                             1.0 / 3.0,
                             0.1 + 0.2,
                             -2.0 / 7.0,
                             std::numeric_limits<double>::max(),
                             std::numeric_limits<double>::min(),
                             std::numeric_limits<double>::denorm_min(),
                             std::numeric_limits<double>::epsilon(),
                             9007199254740993.0, // 2^53 + 1 rounds to 2^53
                             123456789.123456789,
                             -0.0};
  // Random bit patterns: every exponent range, every mantissa.
  std::mt19937_64 random(20240611);
  while (values.size() < 2000) {
    const double x = std::bit_cast<double>(random());
    if (std::isfinite(x)) values.push_back(x);
  }
  {
    CsvTable table(file, {"index", "value"});
    for (std::size_t i = 0; i < values.size(); ++i) table.add_row({i, values[i]});
  }
  const auto lines = lines_of(file);
  ASSERT_EQ(lines.size(), values.size() + 1);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const auto fields = split(lines[i + 1]);
    ASSERT_EQ(fields.size(), 2u);
    EXPECT_EQ(std::stoull(fields[0]), i);
    const double read = std::strtod(fields[1].c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(read), std::bit_cast<std::uint64_t>(values[i]))
        << fields[1];
    EXPECT_LE(fields[1].size(), 24u) << "not the shortest form: " << fields[1];
  }
}

TEST(CsvTable, IntegersAreWrittenAsIntegers) {
  test::ScratchDir dir("csv_int");
  const std::string file = dir / "t.csv";
  {
    CsvTable table(file, {"a", "b", "c"});
    table.add_row({std::numeric_limits<std::int64_t>::max(), -7, std::uint16_t(65535)});
  }
  EXPECT_EQ(lines_of(file)[1], "9223372036854775807,-7,65535");
}

TEST(CsvTable, EveryRowIsInTheFileAsSoonAsItIsAdded) {
  test::ScratchDir dir("csv_flush");
  const std::string file = dir / "newton.csv";
  CsvTable table(file, {"step", "iteration", "residual"});
  EXPECT_EQ(lines_of(file).size(), 1u); // the header, before any row
  for (int it = 0; it < 5; ++it) {
    table.add_row({1, it, std::pow(10.0, -2 * it)});
    // Read while the table is still open, as after a crash in the next iteration.
    const auto lines = lines_of(file);
    ASSERT_EQ(lines.size(), std::size_t(it + 2));
    EXPECT_EQ(split(lines.back())[1], std::to_string(it));
  }
}

TEST(CsvTable, StringsAreKeptAndQuotedOnlyWhenNeeded) {
  test::ScratchDir dir("csv_strings");
  const std::string file = dir / "interfaces.csv";
  {
    CsvTable table(file, {"interface", "note"});
    table.add_row({"upper_bottom-2", "plain text"});
    table.add_row({"a,b", "say \"hi\""});
  }
  const auto lines = lines_of(file);
  EXPECT_EQ(lines[1], "upper_bottom-2,plain text");
  EXPECT_EQ(lines[2], "\"a,b\",\"say \"\"hi\"\"\"");
}

TEST(CsvTable, FreshRunTruncatesRestartAppends) {
  test::ScratchDir dir("csv_modes");
  const std::string file = dir / "steps.csv";
  {
    CsvTable table(file, {"step", "time"});
    table.add_row({1, 0.1});
    table.add_row({2, 0.2});
  }
  {
    CsvTable restarted(file, {"step", "time"}, CsvTable::Mode::append);
    restarted.add_row({3, 0.3});
  }
  auto lines = lines_of(file);
  ASSERT_EQ(lines.size(), 4u);
  EXPECT_EQ(lines[0], "step,time");
  EXPECT_EQ(lines[3], "3,0.3");

  { CsvTable fresh(file, {"step", "time"}); }
  lines = lines_of(file);
  ASSERT_EQ(lines.size(), 1u);
  EXPECT_EQ(lines[0], "step,time");

  // Appending to a file that does not exist yet writes the header.
  { CsvTable appended(dir / "new.csv", {"x"}, CsvTable::Mode::append); }
  EXPECT_EQ(lines_of(dir / "new.csv"), std::vector<std::string>{"x"});
}

TEST(CsvTable, AppendingToADifferentTableIsAnInputError) {
  test::ScratchDir dir("csv_mismatch");
  const std::string file = dir / "steps.csv";
  { CsvTable table(file, {"step", "time"}); }
  EXPECT_THROW(CsvTable(file, {"step", "time", "residual"}, CsvTable::Mode::append), InputError);
}

TEST(CsvTable, RowOfTheWrongLengthIsRejected) {
  test::ScratchDir dir("csv_length");
  CsvTable table(dir / "t.csv", {"a", "b"});
  EXPECT_THROW(table.add_row({1.0}), InternalError);
  EXPECT_THROW(table.add_row({1.0, 2.0, 3.0}), InternalError);
  EXPECT_EQ(lines_of(dir / "t.csv").size(), 1u);
}

TEST(CsvTable, UnwritableFileIsAnInputError) {
  EXPECT_THROW(CsvTable("/nonexistent_seam_dir/steps.csv", {"step"}), InputError);
}

TEST(CsvTable, MovedTableKeepsWriting) {
  test::ScratchDir dir("csv_move");
  CsvTable a(dir / "t.csv", {"x"});
  CsvTable b = std::move(a);
  b.add_row({1});
  EXPECT_EQ(lines_of(dir / "t.csv"), (std::vector<std::string>{"x", "1"}));
}

} // namespace
} // namespace seam::io
