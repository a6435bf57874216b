#include "seam/mesh/msh_chunk.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <array>
#include <cstring>
#include <fstream>
#include <limits>
#include <sstream>

namespace seam::mesh {
namespace {

// The file as ASCII tokens or as binary values (MSH 4.1: int = 4 bytes, size_t and double = 8
// bytes, little endian as written; the format line's data size and the "1" after it say so).
class Input {
public:
  Input(const std::filesystem::path& path, std::string file)
      : in_(path, std::ios::binary), file_(std::move(file)) {
    SEAM_CHECK(in_.good(), InputError, "mesh file '", file_, "' cannot be opened");
  }
  bool binary = false;
  std::string section = "MeshFormat";

  template <class... Args> [[noreturn]] void fail(const Args&... args) {
    in_.clear();
    const auto at = static_cast<long long>(in_.tellg());
    SEAM_THROW(InputError, "mesh '", file_, "': $", section, ": ", args...,
               at >= 0 ? " (byte " + std::to_string(at) + ")" : std::string(" (end of file)"));
  }
  // Next line without its end of line; false at the end of the file.
  bool line(std::string& out) {
    if (!std::getline(in_, out)) return false;
    if (!out.empty() && out.back() == '\r') out.pop_back();
    return true;
  }
  std::uint64_t size() { return binary ? raw<std::uint64_t>() : text<std::uint64_t>("a count"); }
  std::uint64_t tag() { return binary ? raw<std::uint64_t>() : text<std::uint64_t>("a tag"); }
  int integer() { return binary ? raw<int>() : text<int>("an integer"); }
  double real() { return binary ? raw<double>() : text<double>("a number"); }
  // ASCII: the rest of the current line (after the values read from it).
  void end_line() {
    if (!binary) in_.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
  void skip_lines(std::uint64_t n) {
    for (std::uint64_t i = 0; i < n; ++i)
      if (!in_.ignore(std::numeric_limits<std::streamsize>::max(), '\n'))
        fail("the file ends inside the section");
  }
  void skip_bytes(std::uint64_t n) {
    in_.seekg(static_cast<std::streamoff>(n), std::ios::cur);
    if (!in_) fail("the file ends inside the section");
  }
  std::int64_t at() { return static_cast<std::int64_t>(in_.tellg()); }
  void seek(std::int64_t at) {
    in_.clear();
    in_.seekg(at);
  }
  template <class T> void raw_array(T* out, std::size_t n) {
    if (!in_.read(reinterpret_cast<char*>(out), static_cast<std::streamsize>(n * sizeof(T))))
      fail("the file ends inside the section");
  }
  // The closing $End<section> (after binary data comes a newline first).
  void expect_end() {
    std::string s;
    while (line(s) && s.empty()) {
    }
    if (s != "$End" + section) fail("expected $End", section, ", found '", s.substr(0, 40), "'");
  }

private:
  template <class T> T raw() {
    T v{};
    raw_array(&v, 1);
    return v;
  }
  template <class T> T text(const char* what) {
    T v{};
    if (!(in_ >> v)) fail(in_.eof() ? "the file ends where " : "expected ", what);
    return v;
  }
  std::ifstream in_;
  std::string file_;
};

struct Block {
  int dim = 0, entity = 0, type = 0;
  std::uint64_t count = 0;
  std::int64_t at = 0; // file offset of the block's elements
  int nodes = 0;       // nodes per element
};

void read_format(Input& in) {
  std::string version;
  int file_type = 0, data_size = 0;
  std::string s;
  while (in.line(s) && s.empty()) {
  }
  std::istringstream(s) >> version >> file_type >> data_size;
  if (version != "4.1")
    throw MshUnsupported("MSH version " + (version.empty() ? std::string("?") : version) +
                         " (the chunked reader reads 4.1)");
  if (data_size != 8) throw MshUnsupported("data size " + std::to_string(data_size));
  in.binary = file_type == 1;
  if (in.binary) {
    const int one = in.integer();
    if (one != 1) throw MshUnsupported("binary file of the other byte order");
  }
  in.expect_end();
}

void read_names(Input& in, MshChunk& out) {
  std::string s;
  while (in.line(s) && s.empty()) {
  }
  long long n = -1;
  std::istringstream(s) >> n;
  if (n < 0) in.fail("expected the number of names, got '", s.substr(0, 40), "'");
  for (long long i = 0; i < n; ++i) {
    if (!in.line(s)) in.fail("the file ends after ", i, " of ", n, " names");
    const auto q0 = s.find('"'), q1 = s.rfind('"');
    int dim = -1, tag = 0;
    std::istringstream(s.substr(0, q0)) >> dim >> tag;
    if (q0 == std::string::npos || q1 == q0 || dim < 0 || dim > 3 || tag <= 0)
      in.fail("expected DIM TAG \"NAME\", got '", s.substr(0, 40), "'");
    out.names[{dim, tag}] = s.substr(q0 + 1, q1 - q0 - 1);
  }
  in.expect_end();
}

void read_entities(Input& in, MshChunk& out) {
  std::array<std::uint64_t, 4> n{};
  for (auto& k : n) k = in.size();
  for (int dim = 0; dim < 4; ++dim)
    for (std::uint64_t e = 0; e < n[dim]; ++e) {
      const int tag = in.integer();
      for (int k = 0; k < (dim == 0 ? 3 : 6); ++k) in.real();
      const auto n_phys = in.size();
      if (n_phys > 1000) in.fail("entity ", tag, " has ", n_phys, " physical tags");
      auto& phys = out.physicals[{dim, tag}];
      for (std::uint64_t p = 0; p < n_phys; ++p) phys.push_back(std::abs(in.integer()));
      if (dim > 0) {
        const auto n_bound = in.size();
        for (std::uint64_t b = 0; b < n_bound; ++b) in.integer();
      }
    }
  in.end_line();
  in.expect_end();
}

void skip_nodes(Input& in, MshChunk& out) {
  const auto blocks = in.size(), n = in.size();
  out.node_blocks = blocks;
  out.min_node_tag = in.size();
  out.max_node_tag = in.size();
  in.end_line();
  out.nodes_at = in.at();
  std::uint64_t total = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    const int dim = in.integer();
    in.integer();
    const int parametric = in.integer();
    const auto count = in.size();
    in.end_line();
    total += count;
    if (total > n) in.fail("the blocks hold more nodes than the header's ", n);
    if (in.binary)
      in.skip_bytes(count * 8 * (4 + (parametric ? dim : 0)));
    else
      in.skip_lines(2 * count);
  }
  if (total != n) in.fail("the blocks hold ", total, " nodes, the header says ", n);
  in.expect_end();
}

int nodes_of_type(Input& in, int type, int entity) {
  try {
    return fem::n_nodes(fem::from_gmsh(type));
  } catch (const InputError& e) {
    throw MshUnsupported("element type " + std::to_string(type) + " in entity " +
                         std::to_string(entity));
  }
}

std::vector<Block> skip_elements(Input& in) {
  const auto blocks = in.size(), n = in.size();
  in.size();
  in.size();
  in.end_line();
  std::vector<Block> out;
  std::uint64_t total = 0;
  for (std::uint64_t b = 0; b < blocks; ++b) {
    Block k;
    k.dim = in.integer();
    k.entity = in.integer();
    k.type = in.integer();
    k.count = in.size();
    in.end_line();
    if (k.dim < 0 || k.dim > 3) in.fail("entity dimension ", k.dim);
    k.nodes = nodes_of_type(in, k.type, k.entity);
    k.at = in.at();
    total += k.count;
    if (total > n) in.fail("the blocks hold more elements than the header's ", n);
    if (in.binary)
      in.skip_bytes(k.count * 8 * static_cast<std::uint64_t>(1 + k.nodes));
    else
      in.skip_lines(k.count);
    out.push_back(k);
  }
  if (total != n) in.fail("the blocks hold ", total, " elements, the header says ", n);
  in.expect_end();
  return out;
}

// Elements [lo, hi) of the blocks `blocks` (in file order, counted together) into `out`.
void read_share(Input& in, const MshChunk& chunk, const std::vector<const Block*>& blocks,
                std::uint64_t lo, std::uint64_t hi, MshElements& out) {
  std::uint64_t start = 0;
  std::vector<std::uint64_t> words;
  for (const Block* b : blocks) {
    const auto s = std::max(lo, start), e = std::min(hi, start + b->count);
    start += b->count;
    if (s >= e) continue;
    const auto first = s - (start - b->count);
    const auto per = static_cast<std::uint64_t>(1 + b->nodes);
    in.seek(b->at);
    words.resize((e - s) * per);
    if (in.binary) {
      in.skip_bytes(first * per * 8);
      in.raw_array(words.data(), words.size());
    } else {
      in.skip_lines(first);
      for (auto& w : words) w = in.tag();
    }
    const auto type = fem::from_gmsh(b->type);
    for (std::uint64_t k = 0; k < e - s; ++k) {
      const auto* w = words.data() + k * per;
      if (w[0] == 0) in.fail("element tag 0 in entity ", b->entity);
      for (int a = 1; a <= b->nodes; ++a)
        if (w[a] < std::max<std::uint64_t>(chunk.min_node_tag, 1) || w[a] > chunk.max_node_tag)
          in.fail("element ", w[0], " has node ", w[a], ", outside the node tags [",
                  chunk.min_node_tag, ", ", chunk.max_node_tag, "]");
      out.tag.push_back(w[0]);
      out.type.push_back(type);
      out.entity.push_back(b->entity);
      out.nodes.insert(out.nodes.end(), w + 1, w + per);
      out.offsets.push_back(static_cast<std::int64_t>(out.nodes.size()));
    }
  }
}

} // namespace

MshChunk read_msh_chunk(const std::filesystem::path& path, int rank, int n_ranks) {
  MshChunk out;
  out.file = path.string();
  Input in(path, out.file);
  std::vector<Block> blocks;
  std::string s;
  bool format = false;
  while (in.line(s)) {
    if (s.empty()) continue;
    if (s.front() != '$') {
      in.section = "(between sections)";
      in.fail("unexpected text '", s.substr(0, 40), "'");
    }
    in.section = s.substr(1);
    if (s == "$MeshFormat") {
      read_format(in);
      out.binary = in.binary;
      format = true;
      continue;
    }
    if (!format) throw MshUnsupported("no $MeshFormat section first");
    if (s == "$PhysicalNames")
      read_names(in, out);
    else if (s == "$Entities")
      read_entities(in, out);
    else if (s == "$Nodes")
      skip_nodes(in, out);
    else if (s == "$Elements")
      blocks = skip_elements(in);
    else if (s == "$Periodic" || s == "$PartitionedEntities" || s == "$GhostElements")
      throw MshUnsupported(s + " section");
    else { // data sections ($NodeData, ...) and comments: skipped
      const std::string end = "$End" + in.section;
      while (in.line(s) && s != end) {
      }
      if (s != end) in.fail("the file ends without ", end);
    }
  }
  in.section = "MeshFormat";
  if (!format) in.fail("no $MeshFormat section (is this a .msh file?)");
  in.section = "Nodes";
  if (out.nodes_at < 0) in.fail("the file has no $Nodes section");
  in.section = "Elements";
  for (const auto& b : blocks)
    if (b.count > 0) out.dim = std::max(out.dim, b.dim);
  if (out.dim < 2) in.fail("no elements of dimension 2 or 3");

  std::vector<const Block*> top, lower;
  std::uint64_t n_top = 0, n_lower = 0;
  for (const auto& b : blocks) {
    if (b.dim == out.dim) {
      top.push_back(&b);
      n_top += b.count;
    } else if (const auto it = out.physicals.find({b.dim, b.entity});
               it != out.physicals.end() && !it->second.empty()) {
      lower.push_back(&b);
      n_lower += b.count;
    }
  }
  const auto share = [&](std::uint64_t n, int r) { return n * r / n_ranks; };
  out.n_cells = static_cast<std::int64_t>(n_top);
  out.first_cell = static_cast<std::int64_t>(share(n_top, rank));
  read_share(in, out, top, share(n_top, rank), share(n_top, rank + 1), out.cells);
  read_share(in, out, lower, share(n_lower, rank), share(n_lower, rank + 1), out.lower);
  return out;
}

std::vector<double> read_msh_nodes(const MshChunk& chunk, const std::vector<std::uint64_t>& tags) {
  Input in(chunk.file, chunk.file);
  in.binary = chunk.binary;
  in.section = "Nodes";
  in.seek(chunk.nodes_at);
  std::vector<double> x(3 * tags.size(), 0.0);
  std::vector<char> found(tags.size(), 0);
  std::vector<std::pair<std::uint64_t, std::size_t>> wanted; // (index in block, index in tags)
  for (std::uint64_t block = 0; block < chunk.node_blocks; ++block) {
    const int dim = in.integer();
    in.integer();
    const int parametric = in.integer();
    const auto count = in.size();
    in.end_line();
    // Tags first: remember which of the block's nodes are wanted.
    wanted.clear();
    constexpr std::uint64_t piece = 65536;
    std::vector<std::uint64_t> buffer(in.binary ? std::min(count, piece) : 0);
    for (std::uint64_t i = 0; i < count;) {
      const auto m = in.binary ? std::min(piece, count - i) : 1;
      if (in.binary) in.raw_array(buffer.data(), m);
      for (std::uint64_t k = 0; k < m; ++k) {
        const auto t = in.binary ? buffer[k] : in.tag();
        const auto it = std::lower_bound(tags.begin(), tags.end(), t);
        if (it != tags.end() && *it == t)
          wanted.emplace_back(i + k, static_cast<std::size_t>(it - tags.begin()));
      }
      i += m;
    }
    if (count > 0) in.end_line();
    // Then the coordinates, parsing only the wanted ones.
    const std::uint64_t stride = 3 + (parametric ? static_cast<std::uint64_t>(dim) : 0);
    std::uint64_t next = 0;
    for (const auto& [i, t] : wanted) {
      if (in.binary) {
        in.skip_bytes((i - next) * stride * 8);
        in.raw_array(x.data() + 3 * t, 3);
        in.skip_bytes((stride - 3) * 8);
      } else {
        in.skip_lines(i - next);
        for (int a = 0; a < 3; ++a) x[3 * t + a] = in.real();
        in.end_line();
      }
      found[t] = 1;
      next = i + 1;
    }
    if (in.binary)
      in.skip_bytes((count - next) * stride * 8);
    else
      in.skip_lines(count - next);
  }
  for (std::size_t t = 0; t < tags.size(); ++t)
    if (!found[t]) in.fail("node ", tags[t], " is used by an element but not defined");
  return x;
}

} // namespace seam::mesh
