#include "seam/io/json.hpp"

#include "seam/common/error.hpp"
#include "seam/io/vtu.hpp" // write_file_atomically

#include <array>
#include <charconv>
#include <cmath>
#include <system_error>

namespace seam::io {

namespace {

template <class T> void append_number(std::string& out, T value) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  SEAM_ASSERT(result.ec == std::errc());
  out.append(buf.data(), result.ptr);
}

void append_quoted(std::string& out, std::string_view text) {
  constexpr std::string_view hex = "0123456789abcdef";
  out += '"';
  for (const char c : text) {
    switch (c) {
    case '"':
      out += "\\\"";
      break;
    case '\\':
      out += "\\\\";
      break;
    case '\b':
      out += "\\b";
      break;
    case '\f':
      out += "\\f";
      break;
    case '\n':
      out += "\\n";
      break;
    case '\r':
      out += "\\r";
      break;
    case '\t':
      out += "\\t";
      break;
    default:
      if (static_cast<unsigned char>(c) < 0x20) {
        const auto code = static_cast<unsigned char>(c);
        out += "\\u00";
        out += hex[code >> 4];
        out += hex[code & 15];
      } else {
        out += c;
      }
    }
  }
  out += '"';
}

void append_newline(std::string& out, int indent, int level) {
  out += '\n';
  out.append(std::size_t(indent) * std::size_t(level), ' ');
}

} // namespace

Json& Json::operator[](std::string_view key) {
  if (kind_ == Kind::null) kind_ = Kind::object;
  SEAM_CHECK(kind_ == Kind::object, InternalError, "JSON: member '", key,
             "' requested of a value that is not an object");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return items_[i];
  keys_.emplace_back(key);
  items_.emplace_back();
  return items_.back();
}

const Json& Json::at(std::string_view key) const {
  SEAM_CHECK(kind_ == Kind::object, InternalError, "JSON: member '", key,
             "' requested of a value that is not an object");
  for (std::size_t i = 0; i < keys_.size(); ++i)
    if (keys_[i] == key) return items_[i];
  SEAM_THROW(InternalError, "JSON: no member '", key, "'");
}

Json& Json::push_back(Json value) {
  if (kind_ == Kind::null) kind_ = Kind::array;
  SEAM_CHECK(kind_ == Kind::array, InternalError,
             "JSON: push_back on a value that is not an array");
  items_.push_back(std::move(value));
  return items_.back();
}

void Json::append_to(std::string& out, int indent, int level) const {
  switch (kind_) {
  case Kind::null:
    out += "null";
    break;
  case Kind::boolean:
    out += boolean_ ? "true" : "false";
    break;
  case Kind::integer:
    append_number(out, integer_);
    break;
  case Kind::real:
    if (std::isfinite(real_))
      append_number(out, real_);
    else
      out += "null";
    break;
  case Kind::string:
    append_quoted(out, string_);
    break;
  case Kind::array:
  case Kind::object: {
    const bool is_object = kind_ == Kind::object;
    out += is_object ? '{' : '[';
    if (items_.empty()) {
      out += is_object ? '}' : ']';
      break;
    }
    for (std::size_t i = 0; i < items_.size(); ++i) {
      if (i > 0) out += ',';
      append_newline(out, indent, level + 1);
      if (is_object) {
        append_quoted(out, keys_[i]);
        out += ": ";
      }
      items_[i].append_to(out, indent, level + 1);
    }
    append_newline(out, indent, level);
    out += is_object ? '}' : ']';
    break;
  }
  }
}

std::string Json::dump(int indent) const {
  std::string out;
  append_to(out, indent, 0);
  return out;
}

std::string json_quote(std::string_view text) {
  std::string out;
  append_quoted(out, text);
  return out;
}

void write_json(const std::filesystem::path& file, const Json& document) {
  write_file_atomically(file, document.dump() + '\n');
}

} // namespace seam::io
