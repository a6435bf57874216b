#include "seam/io/config_reader.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <cmath>

namespace seam::io {

std::string to_string(const Mark& mark) {
  std::string text = mark.file;
  if (mark.line > 0) text += seam::detail::concat(":", mark.line, ":", mark.column);
  if (!mark.key_path.empty()) text += ": " + mark.key_path;
  return text;
}

void fail_at(const Mark& mark, std::string_view message) {
  throw InputError(seam::detail::concat(to_string(mark), ": ", message));
}

namespace detail {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  // Wagner-Fischer with one row; keys are short, so this is never hot.
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      const std::size_t substitute = diagonal + (a[i - 1] == b[j - 1] ? 0 : 1);
      row[j] = std::min({row[j - 1] + 1, above + 1, substitute});
      diagonal = above;
    }
  }
  return row[b.size()];
}

std::string did_you_mean(std::string_view word, std::span<const std::string_view> candidates) {
  std::string lower(word);
  std::transform(lower.begin(), lower.end(), lower.begin(),
                 [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
  std::string_view best;
  std::size_t best_distance = std::string::npos;
  for (const std::string_view candidate : candidates) {
    const std::size_t distance = edit_distance(lower, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  // A typo changes a few letters; beyond a third of the word it is a different word.
  const std::size_t tolerance = std::max<std::size_t>(2, word.size() / 3);
  if (best.empty() || best_distance > tolerance) return {};
  return concat(" (did you mean '", best, "'?)");
}

std::string quoted_list(std::span<const std::string_view> words) {
  std::string text;
  for (const std::string_view word : words) {
    if (!text.empty()) text += ", ";
    text += concat("'", word, "'");
  }
  return text;
}

std::string format_number(double value) {
  std::array<char, 32> buffer{};
  const auto result = std::to_chars(buffer.data(), buffer.data() + buffer.size(), value);
  return {buffer.data(), result.ptr};
}

namespace {

std::optional<double> parse_number(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-' && text[1] != '+')
    text.remove_prefix(1);
  double value = 0.0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size() || !std::isfinite(value))
    return std::nullopt;
  return value;
}

std::optional<int> parse_integer(std::string_view text) {
  if (text.size() > 1 && text.front() == '+' && text[1] != '-') text.remove_prefix(1);
  int value = 0;
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  if (error != std::errc{} || end != text.data() + text.size()) return std::nullopt;
  return value;
}

std::string child_path(const std::string& parent, std::string_view key) {
  return parent.empty() ? std::string(key) : concat(parent, ".", key);
}

} // namespace

Node::Node(YAML::Node yaml, std::string file, std::string path)
    : yaml_(std::move(yaml)), file_(std::move(file)), path_(std::move(path)) {}

Node::Node(YAML::Node yaml, std::string file, std::string path, YAML::Mark at)
    : yaml_(std::move(yaml)), file_(std::move(file)), path_(std::move(path)), at_(at) {}

Mark Node::mark() const {
  const YAML::Mark at = at_ ? *at_ : yaml_.Mark();
  if (at.is_null()) return Mark{file_, 0, 0, path_};
  return Mark{file_, at.line + 1, at.column + 1, path_};
}

void Node::fail(std::string_view message) const {
  fail_at(mark(), message);
}

std::string Node::describe() const {
  if (!yaml_.IsDefined() || yaml_.IsNull()) return "nothing";
  if (yaml_.IsScalar()) return concat("'", yaml_.Scalar(), "'");
  if (yaml_.IsSequence()) return "a list";
  return "a mapping";
}

std::string Node::string() const {
  if (!yaml_.IsScalar()) fail(concat("expected a name, got ", describe()));
  return yaml_.Scalar();
}

double Node::number() const {
  const auto value = yaml_.IsScalar() ? parse_number(yaml_.Scalar()) : std::nullopt;
  if (!value) fail(concat("expected a number, got ", describe()));
  return *value;
}

int Node::integer() const {
  const auto value = yaml_.IsScalar() ? parse_integer(yaml_.Scalar()) : std::nullopt;
  if (!value) fail(concat("expected an integer, got ", describe()));
  return *value;
}

bool Node::boolean() const {
  if (yaml_.IsScalar() && (yaml_.Scalar() == "true" || yaml_.Scalar() == "false"))
    return yaml_.Scalar() == "true";
  fail(concat("expected true or false, got ", describe()));
}

Expression Node::expression() const {
  if (!yaml_.IsScalar()) fail(concat("expected a number or an expression, got ", describe()));
  if (const auto value = parse_number(yaml_.Scalar())) return Expression(*value);
  try {
    return Expression(yaml_.Scalar());
  } catch (const InputError& error) {
    fail(concat(error.what(), "\n    expected an expression in t, x, y, z (constants _pi, _e; "
                              "muparser syntax, e.g. \"2*sin(_pi*t)*(t<=0.5)\")"));
  }
}

std::vector<Node> Node::sequence() const {
  if (!yaml_.IsSequence()) fail(concat("expected a list, got ", describe()));
  std::vector<Node> items;
  items.reserve(yaml_.size());
  for (std::size_t i = 0; i < yaml_.size(); ++i)
    items.emplace_back(yaml_[i], file_, concat(path_, "[", i, "]"));
  return items;
}

std::vector<Node> Node::sequence(std::size_t length, std::string_view what) const {
  if (!yaml_.IsSequence())
    fail(concat("expected a list of ", length, " ", what, ", got ", describe()));
  if (yaml_.size() != length) fail(concat("expected ", length, " ", what, ", got ", yaml_.size()));
  return sequence();
}

std::array<double, 3> Node::point(int dimension) const {
  const auto items = sequence(static_cast<std::size_t>(dimension),
                              concat("coordinates (dimension is ", dimension, ")"));
  std::array<double, 3> coordinates{};
  for (std::size_t i = 0; i < items.size(); ++i) coordinates[i] = items[i].number();
  return coordinates;
}

std::vector<Expression> Node::expressions(int dimension) const {
  const auto items = sequence(static_cast<std::size_t>(dimension),
                              concat("components (dimension is ", dimension, ")"));
  std::vector<Expression> values;
  values.reserve(items.size());
  for (const Node& item : items) values.push_back(item.expression());
  return values;
}

void Node::fail_unknown_value(std::string_view word,
                              std::span<const std::string_view> allowed) const {
  fail(concat("unknown value '", word, "'", did_you_mean(word, allowed), "; expected one of ",
              quoted_list(allowed)));
}

Map::Map(const Node& node, std::initializer_list<std::string_view> allowed) : node_(node) {
  read(std::span<const std::string_view>(allowed.begin(), allowed.size()), false);
}

Map::Map(const Node& node) : node_(node) {
  read({}, true);
}

void Map::read(std::span<const std::string_view> allowed, bool any_key) {
  const YAML::Node& yaml = node_.yaml();
  if (yaml.IsNull()) return;
  if (!yaml.IsMap()) node_.fail(concat("expected a mapping (key: value), got ", node_.describe()));
  for (auto it = yaml.begin(); it != yaml.end(); ++it) {
    const Node key(it->first, node_.file(), node_.path());
    if (!it->first.IsScalar()) key.fail(concat("expected a key name, got ", key.describe()));
    const std::string name = it->first.Scalar();
    const Node value =
        it->second.IsNull()
            ? Node(it->second, node_.file(), child_path(node_.path(), name), it->first.Mark())
            : Node(it->second, node_.file(), child_path(node_.path(), name));
    const Node key_at(it->first, node_.file(), value.path());
    if (!any_key && std::find(allowed.begin(), allowed.end(), name) == allowed.end()) {
      key_at.fail(concat("unknown key '", name, "'", did_you_mean(name, allowed),
                         "; allowed here: ", quoted_list(allowed)));
    }
    for (const auto& [seen, first] : entries_) {
      if (seen == name) {
        key_at.fail(concat("key '", name, "' given twice (first at line ", first.mark().line, ")"));
      }
    }
    entries_.emplace_back(name, value);
  }
}

bool Map::has(std::string_view key) const {
  return get(key).has_value();
}

std::optional<Node> Map::get(std::string_view key) const {
  for (const auto& [name, value] : entries_)
    if (name == key) return value;
  return std::nullopt;
}

Node Map::required(std::string_view key) const {
  auto value = get(key);
  if (!value) node_.fail(concat("missing required key '", key, "'"));
  return *value;
}

void Map::forbid(std::string_view key, bool forbidden, std::string_view reason) const {
  if (!forbidden) return;
  if (const auto value = get(key)) value->fail(concat("'", key, "' ", reason));
}

} // namespace detail
} // namespace seam::io
