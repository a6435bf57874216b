#pragma once
// A small JSON document builder and pretty printer (RFC 8259) for summary.json. Objects keep
// their keys in insertion order, so the file reads in the order the run filled it in.
#include <concepts>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace seam::io {

class Json {
public:
  enum class Kind { null, boolean, integer, real, string, array, object };

  Json() = default; ///< null
  Json(std::nullptr_t) {}
  template <std::same_as<bool> T> Json(T b) : kind_(Kind::boolean), boolean_(b) {}
  template <std::integral T>
  requires(!std::same_as<T, bool>) Json(T i) : kind_(Kind::integer), integer_(std::int64_t(i)) {}
  template <std::floating_point T> Json(T x) : kind_(Kind::real), real_(double(x)) {}
  Json(std::string s) : kind_(Kind::string), string_(std::move(s)) {}
  Json(std::string_view s) : kind_(Kind::string), string_(s) {}
  Json(const char* s) : kind_(Kind::string), string_(s) {}

  static Json array() { return Json(Kind::array); }
  static Json object() { return Json(Kind::object); }

  Kind kind() const { return kind_; }
  /// Number of elements (array) or members (object); 0 otherwise.
  std::size_t size() const { return items_.size(); }

  /// Object member `key`, appended (as null) if absent. A null value becomes an empty object
  /// first, so nested objects can be filled in directly: j["timings"]["mortar"] = 1.5.
  /// Throws seam::InternalError on any other kind.
  Json& operator[](std::string_view key);
  /// Object member `key`; throws seam::InternalError if absent or not an object.
  const Json& at(std::string_view key) const;
  /// Appends to an array (a null value becomes an empty array first).
  Json& push_back(Json value);

  /// The document as text: `indent` spaces per level, a newline after every element; numbers
  /// in the shortest form that reads back to the same double; non-finite reals as null
  /// (JSON has no inf/nan).
  std::string dump(int indent = 2) const;

private:
  explicit Json(Kind k) : kind_(k) {}
  void append_to(std::string& out, int indent, int level) const;

  Kind kind_ = Kind::null;
  bool boolean_ = false;
  std::int64_t integer_ = 0;
  double real_ = 0.0;
  std::string string_;
  std::vector<std::string> keys_; // object: keys_[i] names items_[i]
  std::vector<Json> items_;       // array elements or object values
};

/// `text` as a JSON string literal, quotes included: '"' and '\' are escaped, control
/// characters become \b \f \n \r \t or \u00XX (RFC 8259, section 7); other bytes (UTF-8)
/// are kept.
std::string json_quote(std::string_view text);

/// Writes `document.dump()` and a final newline to `file` atomically (temporary name, then
/// rename). Throws seam::InputError if the file cannot be written.
void write_json(const std::filesystem::path& file, const Json& document);

} // namespace seam::io
