// Checkpoint record files: values read back bit for bit, and every kind of damage (truncation,
// an altered byte, trailing bytes, a foreign file, a missing record, a record of another size)
// is an InputError naming the file. drop_rows_after keeps the header and the rows up to a step.
#include "seam/common/error.hpp"
#include "seam/problem/checkpoint.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>

#include <unistd.h>

namespace seam::problem {
namespace {

// One directory per process: the np = 1 and np = 3 runs of this binary, and the ranks of one
// run, write the same file names at the same time.
std::filesystem::path scratch(const std::string& name) {
  const auto dir =
      std::filesystem::temp_directory_path() / ("seam_unit_problem_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  return dir / name;
}

void write(const std::filesystem::path& file, const std::string& bytes) {
  std::ofstream(file, std::ios::binary) << bytes;
}

std::string read(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

std::string sample() {
  RecordWriter w;
  const std::vector<double> u = {1.0 / 3.0, -0.0, std::numeric_limits<double>::denorm_min(),
                                 std::nextafter(1.0, 2.0), -1e300};
  const std::vector<std::int64_t> ids = {0, -1, std::numeric_limits<std::int64_t>::max()};
  w.put("u", u);
  w.put("ids", ids);
  w.put("files", std::string("results_00000.vtu\nresults_00003.pvtu\n"));
  w.put_real("time", 0.1 + 0.2);
  w.put_integer("step", 3);
  w.put("empty", std::vector<double>{});
  return w.document();
}

TEST(CheckpointRecords, RoundTripBitForBit) {
  const auto file = scratch("round_trip.bin");
  write(file, sample());
  const RecordReader r(file);
  const auto u = r.reals("u", 5);
  EXPECT_EQ(u[0], 1.0 / 3.0);
  EXPECT_TRUE(std::signbit(u[1]));
  EXPECT_EQ(u[2], std::numeric_limits<double>::denorm_min());
  EXPECT_EQ(u[3], std::nextafter(1.0, 2.0));
  EXPECT_EQ(r.integers("ids")[2], std::numeric_limits<std::int64_t>::max());
  EXPECT_EQ(r.text("files"), "results_00000.vtu\nresults_00003.pvtu\n");
  EXPECT_EQ(r.real("time"), 0.1 + 0.2);
  EXPECT_EQ(r.integer("step"), 3);
  EXPECT_TRUE(r.reals("empty").empty());
  EXPECT_FALSE(r.has("v"));
}

void expect_rejected(const std::string& bytes, const std::string& words) {
  const auto file = scratch("damaged.bin");
  write(file, bytes);
  try {
    RecordReader r(file);
    FAIL() << "accepted a file that should be rejected (" << words << ")";
  } catch (const InputError& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find(file.string()), std::string::npos) << what;
    EXPECT_NE(what.find(words), std::string::npos) << what;
  }
}

TEST(CheckpointRecords, DamageIsAnInputError) {
  const std::string good = sample();
  // Every truncation point, an altered bit at every byte after the magic line, extra bytes.
  for (std::size_t n = 0; n < good.size(); ++n) {
    const auto file = scratch("cut.bin");
    write(file, good.substr(0, n));
    EXPECT_THROW(RecordReader r(file), InputError) << "cut at " << n;
  }
  const std::size_t head = good.find('\n') + 1;
  for (std::size_t i = head; i < good.size(); ++i) {
    std::string bad = good;
    bad[i] = static_cast<char>(bad[i] ^ 0x10);
    const auto file = scratch("flip.bin");
    write(file, bad);
    EXPECT_THROW(RecordReader r(file), InputError) << "bit flipped at byte " << i;
  }
  expect_rejected(good + "x", "trailing");
  expect_rejected("step,time\n1,0.5\n", "not a seam checkpoint");
  // A checkpoint of another format (the first line's number) names both formats.
  ASSERT_EQ(good.compare(0, 18, "seam checkpoint 2\n"), 0);
  expect_rejected("seam checkpoint 1\n" + good.substr(18),
                  "is of checkpoint format 1, written by another version of seam; this seam "
                  "reads format 2");
  EXPECT_THROW(RecordReader r(scratch("no_such_file.bin")), InputError);
}

TEST(CheckpointRecords, MissingOrMisfitRecord) {
  const auto file = scratch("records.bin");
  write(file, sample());
  const RecordReader r(file);
  EXPECT_THROW(r.reals("v"), InputError);
  EXPECT_THROW(r.reals("u", 6), InputError);
  EXPECT_THROW(r.integers("u"), InputError); // a record of reals read as integers
  EXPECT_THROW(r.text("step"), InputError);
}

TEST(CheckpointRecords, DropRowsAfterStep) {
  const auto file = scratch("steps.csv");
  write(file, "step,time,x\n1,0.1,a\n2,0.2,b\n3,0.3,c\n3,0.3,d\n4,0.4,e\n5,0.5");
  drop_rows_after(file, 3);
  EXPECT_EQ(read(file), "step,time,x\n1,0.1,a\n2,0.2,b\n3,0.3,c\n3,0.3,d\n");
  drop_rows_after(scratch("absent.csv"), 3); // nothing to continue: nothing happens
  EXPECT_FALSE(std::filesystem::exists(scratch("absent.csv")));
}

} // namespace
} // namespace seam::problem
