#pragma once
// Test-only readers, written independently of the writers they check: a strict little XML
// parser (enough for VTK XML files: declaration, elements, attributes, text, the five
// predefined entities) and an RFC 4648 base64 decoder.
#include <cctype>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <unistd.h>

namespace seam::test {

struct XmlElement {
  std::string name;
  std::map<std::string, std::string> attributes;
  std::string text; // concatenated character data directly inside this element
  std::vector<XmlElement> children;

  const std::string& attr(const std::string& key) const {
    const auto it = attributes.find(key);
    if (it == attributes.end()) throw std::runtime_error("no attribute " + key + " on " + name);
    return it->second;
  }
  bool has_attr(const std::string& key) const { return attributes.count(key) > 0; }
  std::vector<const XmlElement*> all(std::string_view child_name) const {
    std::vector<const XmlElement*> out;
    for (const auto& c : children)
      if (c.name == child_name) out.push_back(&c);
    return out;
  }
  const XmlElement& child(std::string_view child_name) const {
    const auto found = all(child_name);
    if (found.size() != 1)
      throw std::runtime_error("expected one <" + std::string(child_name) + "> in <" + name +
                               ">, found " + std::to_string(found.size()));
    return *found.front();
  }
  /// The DataArray child with attribute Name == array_name.
  const XmlElement& array(std::string_view array_name) const {
    for (const auto& c : children)
      if ((c.name == "DataArray" || c.name == "PDataArray") && c.has_attr("Name") &&
          c.attr("Name") == array_name)
        return c;
    throw std::runtime_error("no DataArray " + std::string(array_name) + " in <" + name + ">");
  }
};

class XmlParser {
public:
  explicit XmlParser(std::string_view text) : s_(text) {}

  /// Parses a whole document; throws std::runtime_error on anything malformed.
  XmlElement document() {
    skip_space();
    if (s_.substr(pos_, 5) == "<?xml") {
      const auto end = s_.find("?>", pos_);
      if (end == std::string_view::npos) fail("unterminated XML declaration");
      pos_ = end + 2;
    }
    skip_space();
    XmlElement root = element();
    skip_space();
    if (pos_ != s_.size()) fail("content after the root element");
    return root;
  }

private:
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("XML: " + what + " at offset " + std::to_string(pos_));
  }
  static bool is_space(char c) { return c == ' ' || c == '\n' || c == '\t' || c == '\r'; }
  static bool is_name_char(char c) {
    return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ':' ||
           c == '.';
  }
  void skip_space() {
    while (pos_ < s_.size() && is_space(s_[pos_])) ++pos_;
  }
  void expect(char c) {
    if (pos_ >= s_.size() || s_[pos_] != c) fail(std::string("expected '") + c + "'");
    ++pos_;
  }
  std::string name() {
    const auto start = pos_;
    while (pos_ < s_.size() && is_name_char(s_[pos_])) ++pos_;
    if (pos_ == start) fail("expected a name");
    return std::string(s_.substr(start, pos_ - start));
  }
  std::string decode_entities(std::string_view raw) const {
    std::string out;
    for (std::size_t i = 0; i < raw.size(); ++i) {
      if (raw[i] == '<') fail("'<' in text or attribute");
      if (raw[i] != '&') {
        out += raw[i];
        continue;
      }
      const auto semi = raw.find(';', i);
      if (semi == std::string_view::npos) fail("unterminated entity");
      const auto entity = raw.substr(i + 1, semi - i - 1);
      if (entity == "amp")
        out += '&';
      else if (entity == "lt")
        out += '<';
      else if (entity == "gt")
        out += '>';
      else if (entity == "quot")
        out += '"';
      else if (entity == "apos")
        out += '\'';
      else
        fail("unknown entity &" + std::string(entity) + ";");
      i = semi;
    }
    return out;
  }
  XmlElement element() {
    expect('<');
    XmlElement e;
    e.name = name();
    for (;;) {
      const bool had_space = pos_ < s_.size() && is_space(s_[pos_]);
      skip_space();
      if (pos_ >= s_.size()) fail("unterminated start tag");
      if (s_[pos_] == '/') {
        ++pos_;
        expect('>');
        return e;
      }
      if (s_[pos_] == '>') {
        ++pos_;
        break;
      }
      if (!had_space) fail("attributes must be separated by space");
      std::string key = name();
      skip_space();
      expect('=');
      skip_space();
      const char quote = pos_ < s_.size() ? s_[pos_] : '\0';
      if (quote != '"' && quote != '\'') fail("attribute value not quoted");
      ++pos_;
      const auto end = s_.find(quote, pos_);
      if (end == std::string_view::npos) fail("unterminated attribute value");
      std::string value = decode_entities(s_.substr(pos_, end - pos_));
      pos_ = end + 1;
      if (!e.attributes.emplace(std::move(key), std::move(value)).second)
        fail("duplicate attribute");
    }
    for (;;) {
      const auto lt = s_.find('<', pos_);
      if (lt == std::string_view::npos) fail("missing </" + e.name + ">");
      e.text += decode_entities(s_.substr(pos_, lt - pos_));
      pos_ = lt;
      if (s_.substr(pos_, 2) == "</") {
        pos_ += 2;
        if (name() != e.name) fail("mismatched end tag for <" + e.name + ">");
        skip_space();
        expect('>');
        return e;
      }
      e.children.push_back(element());
    }
  }

  std::string_view s_;
  std::size_t pos_ = 0;
};

/// A fresh directory under the system temporary directory, removed with its contents at the
/// end of the test.
class ScratchDir {
public:
  explicit ScratchDir(const std::string& name)
      : path_(std::filesystem::temp_directory_path() /
              ("seam_io_" + name + "_" + std::to_string(::getpid()))) {
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    std::filesystem::remove_all(path_, ignored);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  const std::filesystem::path& path() const { return path_; }
  std::string operator/(const std::string& file) const { return (path_ / file).string(); }

private:
  std::filesystem::path path_;
};

inline std::string read_text_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + path);
  std::ostringstream s;
  s << in.rdbuf();
  return s.str();
}

inline XmlElement parse_xml_file(const std::string& path) {
  const std::string text = read_text_file(path);
  return XmlParser(text).document();
}

/// Strict RFC 4648 decoding (standard alphabet, '=' padding only at the end); surrounding
/// whitespace is ignored.
inline std::vector<std::byte> base64_decode(std::string_view text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.front())))
    text.remove_prefix(1);
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back())))
    text.remove_suffix(1);
  if (text.size() % 4 != 0) throw std::runtime_error("base64 length not a multiple of 4");
  auto value = [](char c) -> int {
    if (c >= 'A' && c <= 'Z') return c - 'A';
    if (c >= 'a' && c <= 'z') return c - 'a' + 26;
    if (c >= '0' && c <= '9') return c - '0' + 52;
    if (c == '+') return 62;
    if (c == '/') return 63;
    throw std::runtime_error(std::string("invalid base64 character '") + c + "'");
  };
  std::vector<std::byte> out;
  for (std::size_t i = 0; i < text.size(); i += 4) {
    const bool last = i + 4 == text.size();
    const int n_pad = last ? (text[i + 3] == '=') + (text[i + 2] == '=') : 0;
    if (n_pad == 1 && text[i + 2] == '=') throw std::runtime_error("bad base64 padding");
    std::uint32_t group = 0;
    for (int k = 0; k < 4; ++k) group = (group << 6) | (k < 4 - n_pad ? value(text[i + k]) : 0);
    out.push_back(std::byte((group >> 16) & 0xff));
    if (n_pad < 2) out.push_back(std::byte((group >> 8) & 0xff));
    if (n_pad < 1) out.push_back(std::byte(group & 0xff));
  }
  return out;
}

/// The values of a VTK DataArray element, decoded from format="binary" (UInt64 byte count
/// header + raw little-endian values in one base64 stream) or format="ascii".
template <class T> std::vector<T> data_array_values(const XmlElement& array) {
  std::vector<T> values;
  const std::string& format = array.attr("format");
  if (format == "binary") {
    const auto bytes = base64_decode(array.text);
    if (bytes.size() < 8) throw std::runtime_error("binary DataArray shorter than its header");
    std::uint64_t n_bytes = 0;
    std::memcpy(&n_bytes, bytes.data(), 8);
    if (n_bytes != bytes.size() - 8 || n_bytes % sizeof(T) != 0)
      throw std::runtime_error("binary DataArray header does not match its data");
    values.resize(n_bytes / sizeof(T));
    if (n_bytes > 0) std::memcpy(values.data(), bytes.data() + 8, n_bytes);
  } else if (format == "ascii") {
    std::istringstream in(array.text);
    std::string token;
    while (in >> token) {
      if constexpr (std::is_floating_point_v<T>)
        values.push_back(std::strtod(token.c_str(), nullptr));
      else
        values.push_back(static_cast<T>(std::stoll(token)));
    }
  } else {
    throw std::runtime_error("unknown DataArray format " + format);
  }
  return values;
}

} // namespace seam::test
