#include "seam/mesh/msh_check.hpp"

#include "seam/common/error.hpp"

#include <array>
#include <charconv>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

namespace seam::mesh::detail {
namespace {

// Nodes per element of the Gmsh types up to 19 (0 = unknown: left to Gmsh's own message).
constexpr std::array<int, 20> nodes_per_type{0, 2,  3,  4,  4,  8, 6, 5,  3,  6,
                                             9, 10, 27, 18, 14, 1, 8, 20, 15, 13};

// Text of the file quoted in a message: at most 60 characters, bytes that are not printable
// ASCII (a binary or corrupted file) as '?'.
std::string printable(std::string_view text) {
  std::string out(text.substr(0, 60));
  for (auto& c : out)
    if (static_cast<unsigned char>(c) < 32 || static_cast<unsigned char>(c) > 126) c = '?';
  return out;
}

// The tokens of one section with their line numbers.
class Tokens {
public:
  Tokens(const std::string& file, std::string section)
      : file_(file), section_(std::move(section)) {}
  void add_line(const std::string& line, int number) {
    std::istringstream in(line);
    std::string word;
    while (in >> word) words_.push_back({word, number});
  }
  bool done() const { return next_ == words_.size(); }
  // The next token as an integer in [low, high]; `what` names it in the message.
  long long integer(std::string_view what, long long low, long long high) {
    if (next_ == words_.size()) fail(last_line(), "the section ends where ", what, " was expected");
    const auto& [word, line] = words_[next_++];
    long long value = 0;
    const auto [end, ec] = std::from_chars(word.data(), word.data() + word.size(), value);
    if (ec != std::errc() || end != word.data() + word.size())
      fail(line, "expected ", what, " (an integer), got '", printable(word), "'");
    if (value < low || value > high)
      fail(line, what, " ", value, " is out of range [", low, ", ", high, "]");
    return value;
  }
  void skip(long long n) {
    if (n > static_cast<long long>(words_.size() - next_))
      fail(last_line(), "the section ends early: ", n, " more values were expected");
    next_ += static_cast<std::size_t>(n);
  }
  template <class... Args> [[noreturn]] void fail(int line, const Args&... args) const {
    SEAM_THROW(InputError, "mesh '", file_, "': line ", line, ": $", section_, ": ", args...);
  }
  int last_line() const { return words_.empty() ? 0 : words_.back().second; }

private:
  const std::string& file_;
  std::string section_;
  std::vector<std::pair<std::string, int>> words_;
  std::size_t next_ = 0;
};

constexpr long long max_count = 2'000'000'000; // seam's local indices are 32-bit

struct NodeRange {
  long long min = 1, max = 0;
};

NodeRange check_nodes(Tokens& t) {
  const auto blocks = t.integer("the number of entity blocks", 0, max_count);
  const auto n_nodes = t.integer("the number of nodes", 0, max_count);
  const auto min_tag = t.integer("the smallest node tag", 0, max_count * 8);
  const auto max_tag = t.integer("the largest node tag", 0, max_count * 8);
  long long total = 0;
  for (long long b = 0; b < blocks; ++b) {
    const auto dim = t.integer("an entity dimension", 0, 3);
    t.integer("an entity tag", 1, max_count);
    const auto parametric = t.integer("the parametric flag", 0, 1);
    const auto n = t.integer("the number of nodes in the block", 0, n_nodes - total);
    for (long long i = 0; i < n; ++i) t.integer("a node tag", std::max(min_tag, 1LL), max_tag);
    t.skip(n * (3 + (parametric ? dim : 0))); // coordinates, then parametric ones
    total += n;
  }
  if (total != n_nodes)
    t.fail(t.last_line(), "the blocks hold ", total, " nodes, the header says ", n_nodes);
  return {min_tag, max_tag};
}

void check_elements(Tokens& t, const NodeRange& nodes) {
  const auto blocks = t.integer("the number of entity blocks", 0, max_count);
  const auto n_elements = t.integer("the number of elements", 0, max_count);
  t.integer("the smallest element tag", 0, max_count * 8);
  t.integer("the largest element tag", 0, max_count * 8);
  long long total = 0;
  for (long long b = 0; b < blocks; ++b) {
    t.integer("an entity dimension", 0, 3);
    t.integer("an entity tag", 1, max_count);
    const auto type = t.integer("an element type", 1, 1000);
    const auto n = t.integer("the number of elements in the block", 0, n_elements - total);
    const int per = type < static_cast<long long>(nodes_per_type.size()) ? nodes_per_type[type] : 0;
    if (per == 0) return; // Gmsh names the unknown type
    for (long long e = 0; e < n; ++e) {
      t.integer("an element tag", 1, max_count * 8);
      for (int k = 0; k < per; ++k) t.integer("a node tag", std::max(nodes.min, 1LL), nodes.max);
    }
    total += n;
  }
  if (total != n_elements)
    t.fail(t.last_line(), "the blocks hold ", total, " elements, the header says ", n_elements);
}

void check_physical_names(const std::vector<std::pair<std::string, int>>& lines,
                          const std::string& file) {
  Tokens head(file, "PhysicalNames");
  if (lines.empty()) head.fail(0, "the section is empty");
  head.add_line(lines[0].first, lines[0].second);
  const auto n = head.integer("the number of names", 0, max_count);
  if (n != static_cast<long long>(lines.size()) - 1)
    head.fail(lines[0].second, "the header says ", n, " names, the section has ", lines.size() - 1,
              " lines");
  for (std::size_t i = 1; i < lines.size(); ++i) {
    const auto& [line, number] = lines[i];
    const auto quote = line.find('"');
    Tokens t(file, "PhysicalNames");
    t.add_line(line.substr(0, quote), number);
    t.integer("a dimension", 0, 3);
    t.integer("a physical tag", 1, max_count);
    if (quote == std::string::npos || line.find('"', quote + 1) == std::string::npos)
      t.fail(number, "expected DIM TAG \"NAME\", got '", printable(line), "'");
  }
}

} // namespace

void check_msh_structure(const std::filesystem::path& path, const std::string& file) {
  std::ifstream in(path);
  std::string line, section;
  int number = 0;
  std::map<std::string, std::vector<std::pair<std::string, int>>> sections;
  bool ascii4 = false;
  while (std::getline(in, line)) {
    ++number;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (section.empty()) {
      if (line.starts_with("$") && !line.starts_with("$End")) section = line.substr(1);
      continue;
    }
    if (line == "$End" + section) {
      if (section == "MeshFormat" && !sections[section].empty()) {
        std::string version, type;
        std::istringstream(sections[section][0].first) >> version >> type;
        ascii4 = version == "4.1" && type == "0";
        if (!ascii4) return; // .msh 2.2, 4.0 and binary files: Gmsh's reader copes
      }
      section.clear();
      continue;
    }
    if (section == "Nodes" || section == "Elements" || section == "PhysicalNames" ||
        section == "MeshFormat")
      sections[section].emplace_back(line, number);
  }
  if (!ascii4) return; // no format line: Gmsh names what is wrong
  if (const auto it = sections.find("PhysicalNames"); it != sections.end())
    check_physical_names(it->second, file);
  NodeRange nodes;
  if (const auto it = sections.find("Nodes"); it != sections.end()) {
    Tokens t(file, "Nodes");
    for (const auto& [text, n] : it->second) t.add_line(text, n);
    nodes = check_nodes(t);
  }
  if (const auto it = sections.find("Elements"); it != sections.end()) {
    Tokens t(file, "Elements");
    for (const auto& [text, n] : it->second) t.add_line(text, n);
    check_elements(t, nodes);
  }
}

} // namespace seam::mesh::detail
