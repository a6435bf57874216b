#pragma once
// CSV tables of the output directory (steps.csv, newton.csv, reactions.csv, ...): a header
// line, then one row per call, flushed at once so that a run that fails later keeps every row
// written before. Numbers are written in the shortest form that reads back to the same double;
// strings as they are, quoted (RFC 4180) only if they contain a comma, a quote or a line break.
#include <concepts>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <initializer_list>
#include <span>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

namespace seam::io {

/// One cell of a CSV row: a real number, an integer or a string.
class CsvValue {
public:
  template <std::floating_point T> CsvValue(T v) : value_(double(v)) {}
  template <std::integral T>
  requires(!std::same_as<T, bool> && !std::same_as<T, char>) CsvValue(T v)
      : value_(std::int64_t(v)) {}
  CsvValue(std::string_view s) : value_(s) {}
  CsvValue(const char* s) : value_(std::string_view(s)) {}
  CsvValue(const std::string& s) : value_(std::string_view(s)) {}

  /// Appends the CSV text of this value to `out`.
  void append_to(std::string& out) const;

private:
  std::variant<double, std::int64_t, std::string_view> value_;
};

class CsvTable {
public:
  enum class Mode {
    truncate, ///< fresh run: replace any old file, write the header
    append    ///< restart: keep the rows already there (the header must match)
  };

  /// Opens `file` and, unless appending to a file that already has rows, writes the header.
  /// Throws seam::InputError if the file cannot be opened, or if in append mode its first line
  /// is not this header.
  CsvTable(std::filesystem::path file, std::vector<std::string> columns,
           Mode mode = Mode::truncate);
  ~CsvTable();
  CsvTable(const CsvTable&) = delete;
  CsvTable& operator=(const CsvTable&) = delete;
  CsvTable(CsvTable&& other) noexcept;
  CsvTable& operator=(CsvTable&& other) noexcept;

  /// Writes one row (exactly one value per column) and flushes it to the file.
  void add_row(std::span<const CsvValue> values);
  void add_row(std::initializer_list<CsvValue> values) {
    add_row(std::span<const CsvValue>(values.begin(), values.size()));
  }

  std::span<const std::string> columns() const { return columns_; }
  const std::filesystem::path& path() const { return file_; }

private:
  void write(std::string_view text);

  std::filesystem::path file_;
  std::vector<std::string> columns_;
  std::FILE* stream_ = nullptr;
  std::string line_; // reused row buffer
};

} // namespace seam::io
