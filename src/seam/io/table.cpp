#include "seam/io/table.hpp"

#include "seam/common/error.hpp"

#include <array>
#include <cerrno>
#include <charconv>
#include <cstring>
#include <fstream>
#include <system_error>
#include <utility>

namespace seam::io {

namespace {

template <class T> void append_number(std::string& out, T value) {
  // std::to_chars without a precision gives the shortest text that reads back to exactly the
  // same value: full precision without the noise digits of %.17g.
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  SEAM_ASSERT(result.ec == std::errc());
  out.append(buf.data(), result.ptr);
}

std::string header_line(std::span<const std::string> columns) {
  std::string line;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    if (i > 0) line += ',';
    CsvValue(columns[i]).append_to(line);
  }
  return line;
}

} // namespace

void CsvValue::append_to(std::string& out) const {
  if (const auto* d = std::get_if<double>(&value_)) {
    append_number(out, *d);
  } else if (const auto* i = std::get_if<std::int64_t>(&value_)) {
    append_number(out, *i);
  } else {
    const auto s = std::get<std::string_view>(value_);
    if (s.find_first_of(",\"\r\n") == std::string_view::npos) {
      out += s;
      return;
    }
    // RFC 4180, section 2.6-2.7: enclose in quotes, double the quotes inside.
    out += '"';
    for (const char c : s) {
      if (c == '"') out += '"';
      out += c;
    }
    out += '"';
  }
}

CsvTable::CsvTable(std::filesystem::path file, std::vector<std::string> columns, Mode mode)
    : file_(std::move(file)), columns_(std::move(columns)) {
  SEAM_CHECK(!columns_.empty(), InternalError, "CSV table ", file_, " has no columns");
  const std::string header = header_line(columns_);

  bool write_header = true;
  if (mode == Mode::append) {
    std::ifstream existing(file_);
    std::string first_line;
    if (existing && std::getline(existing, first_line)) {
      if (!first_line.empty() && first_line.back() == '\r') first_line.pop_back();
      SEAM_CHECK(first_line == header, InputError, "cannot append to ", file_,
                 ": its header is\n  ", first_line, "\nbut this run writes\n  ", header);
      write_header = false;
    }
  }

  stream_ = std::fopen(file_.c_str(), mode == Mode::append ? "ab" : "wb");
  SEAM_CHECK(stream_ != nullptr, InputError, "cannot write ", file_, ": ", std::strerror(errno));
  if (write_header) write(header + '\n');
}

CsvTable::~CsvTable() {
  if (stream_ != nullptr) std::fclose(stream_);
}

CsvTable::CsvTable(CsvTable&& other) noexcept
    : file_(std::move(other.file_)), columns_(std::move(other.columns_)),
      stream_(std::exchange(other.stream_, nullptr)), line_(std::move(other.line_)) {}

CsvTable& CsvTable::operator=(CsvTable&& other) noexcept {
  if (this != &other) {
    if (stream_ != nullptr) std::fclose(stream_);
    file_ = std::move(other.file_);
    columns_ = std::move(other.columns_);
    stream_ = std::exchange(other.stream_, nullptr);
    line_ = std::move(other.line_);
  }
  return *this;
}

void CsvTable::add_row(std::span<const CsvValue> values) {
  SEAM_CHECK(stream_ != nullptr, InternalError, "CSV table used after being moved from");
  SEAM_CHECK(values.size() == columns_.size(), InternalError, "CSV table ", file_, ": a row of ",
             values.size(), " values for ", columns_.size(), " columns");
  line_.clear();
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (i > 0) line_ += ',';
    values[i].append_to(line_);
  }
  line_ += '\n';
  write(line_);
}

void CsvTable::write(std::string_view text) {
  // One fwrite per line and a flush: the row reaches the file before the next step starts.
  const bool ok =
      std::fwrite(text.data(), 1, text.size(), stream_) == text.size() && std::fflush(stream_) == 0;
  SEAM_CHECK(ok, InputError, "cannot write ", file_, ": ", std::strerror(errno));
}

} // namespace seam::io
