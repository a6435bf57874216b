// The JSON writer: exact layout of a small document, escaping (RFC 8259, section 7), numbers
// that round-trip, and, where Python is installed, a check by an independent JSON parser.
#include "seam/common/error.hpp"
#include "seam/io/json.hpp"
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

TEST(Json, PrettyPrintedLayout) {
  Json doc = Json::object();
  doc["status"] = "converged";
  doc["steps"] = 10;
  doc["wall_seconds"] = 1.5;
  doc["ok"] = true;
  doc["nothing"] = nullptr;
  doc["timings"]["assembly"] = 0.25;
  doc["timings"]["mortar"] = 2;
  doc["list"].push_back(1);
  doc["list"].push_back("a");
  doc["empty_array"] = Json::array();
  doc["empty_object"] = Json::object();
  doc["steps"] = 11; // assigning again replaces, in place
  const std::string expected = R"({
  "status": "converged",
  "steps": 11,
  "wall_seconds": 1.5,
  "ok": true,
  "nothing": null,
  "timings": {
    "assembly": 0.25,
    "mortar": 2
  },
  "list": [
    1,
    "a"
  ],
  "empty_array": [],
  "empty_object": {}
})";
  EXPECT_EQ(doc.dump(), expected);
  EXPECT_EQ(doc.size(), 9u);
  EXPECT_EQ(doc.at("timings").at("mortar").kind(), Json::Kind::integer);
}

TEST(Json, Escaping) {
  constexpr char raw[] = "q\"b\\s/\b\f\n\r\t\x01\x1f\x7f \xc3\xa9 nul:\0!";
  const std::string text(raw, sizeof(raw) - 1); // keeps the embedded NUL
  EXPECT_EQ(json_quote(text),
            "\"q\\\"b\\\\s/\\b\\f\\n\\r\\t\\u0001\\u001f\x7f \xc3\xa9 nul:\\u0000!\"");
  // Keys are escaped the same way.
  Json doc;
  doc["a\"b"] = 1;
  EXPECT_EQ(doc.dump(), "{\n  \"a\\\"b\": 1\n}");
}

TEST(Json, NumbersRoundTripAndNonFiniteBecomesNull) {
  std::vector<double> values{0.1, 1.0 / 3.0, -0.0, 1e300, 5e-324, 6.02214076e23};
  std::mt19937_64 random(8259);
  while (values.size() < 500) {
    const double x = std::bit_cast<double>(random());
    if (std::isfinite(x)) values.push_back(x);
  }
  Json array = Json::array();
  for (const double x : values) array.push_back(x);
  array.push_back(std::numeric_limits<double>::infinity());
  array.push_back(std::nan(""));
  array.push_back(std::numeric_limits<std::int64_t>::min());

  std::istringstream lines(array.dump(0));
  std::string line;
  std::vector<std::string> items;
  while (std::getline(lines, line))
    if (line != "[" && line != "]")
      items.push_back(line.back() == ',' ? line.substr(0, line.size() - 1) : line);
  ASSERT_EQ(items.size(), values.size() + 3);
  for (std::size_t i = 0; i < values.size(); ++i) {
    const double read = std::strtod(items[i].c_str(), nullptr);
    EXPECT_EQ(std::bit_cast<std::uint64_t>(read), std::bit_cast<std::uint64_t>(values[i]))
        << items[i];
  }
  EXPECT_EQ(items[values.size()], "null");
  EXPECT_EQ(items[values.size() + 1], "null");
  EXPECT_EQ(items[values.size() + 2], "-9223372036854775808");
}

TEST(Json, WrongKindsAreRejected) {
  Json number = 3.0;
  EXPECT_THROW(number["key"], InternalError);
  EXPECT_THROW(number.push_back(1), InternalError);
  Json object = Json::object();
  EXPECT_THROW(object.push_back(1), InternalError);
  EXPECT_THROW((void)object.at("missing"), InternalError);
}

TEST(Json, WriteJsonEndsWithNewlineAndLeavesNoTemporary) {
  test::ScratchDir dir("json_write");
  Json doc;
  doc["status"] = "failed";
  write_json(dir.path() / "summary.json", doc);
  EXPECT_EQ(test::read_text_file(dir / "summary.json"), "{\n  \"status\": \"failed\"\n}\n");
  EXPECT_FALSE(std::filesystem::exists(dir / "summary.json.tmp"));
  EXPECT_THROW(write_json("/nonexistent_seam_dir/summary.json", doc), InputError);
}

// Python's json module reads the file: every control character, quote and backslash must come
// back as the same code point, every number as the same double.
TEST(Json, PythonJsonModuleReadsItBack) {
  if (std::system("python3 -c 'import json' > /dev/null 2>&1") != 0)
    GTEST_SKIP() << "python3 not available";
  test::ScratchDir dir("json_python");
  std::string all_ascii;
  for (int c = 0; c < 128; ++c) all_ascii += char(c);
  all_ascii += "\xc3\xa9"; // U+00E9 in UTF-8
  const double numbers[] = {0.1 + 0.2, -1.0 / 3.0, 1e-310, 12345.0};
  Json doc;
  doc["text"] = all_ascii;
  doc["nested"]["numbers"] = Json::array();
  for (const double x : numbers) doc["nested"]["numbers"].push_back(x);
  doc["nested"]["flag"] = false;
  write_json(dir.path() / "doc.json", doc);

  const std::string script = dir / "read.py";
  {
    std::ofstream out(script);
    out << "import json, sys\n"
           "d = json.load(open(sys.argv[1], encoding='utf-8'))\n"
           "print(*[ord(c) for c in d['text']])\n"
           "print(*[repr(float(x)) for x in d['nested']['numbers']])\n"
           "print(d['nested']['flag'] is False)\n";
  }
  const std::string command =
      "python3 " + script + " " + (dir / "doc.json") + " > " + (dir / "out.txt") + " 2>&1";
  ASSERT_EQ(std::system(command.c_str()), 0) << test::read_text_file(dir / "out.txt");
  std::istringstream out(test::read_text_file(dir / "out.txt"));
  std::string line;
  std::getline(out, line);
  std::istringstream codes(line);
  std::vector<int> code_points;
  for (int c = 0; codes >> c;) code_points.push_back(c);
  ASSERT_EQ(code_points.size(), 129u);
  for (int c = 0; c < 128; ++c) EXPECT_EQ(code_points[c], c);
  EXPECT_EQ(code_points[128], 0xe9);
  std::getline(out, line);
  std::istringstream reprs(line);
  for (const double x : numbers) {
    std::string token;
    reprs >> token;
    EXPECT_EQ(std::bit_cast<std::uint64_t>(std::strtod(token.c_str(), nullptr)),
              std::bit_cast<std::uint64_t>(x))
        << token;
  }
  std::getline(out, line);
  EXPECT_EQ(line, "True");
}

} // namespace
} // namespace seam::io
