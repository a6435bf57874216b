#include "seam/problem/checkpoint.hpp"

#include "seam/common/collective.hpp"

#include "seam/common/error.hpp"
#include "seam/io/vtu.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace seam::problem {

namespace {

// The format's number is raised whenever the records change meaning (format 2: records keyed by
// mesh-file node ids, contact sides and fluid-structure state per owner); a checkpoint of
// another format is refused with its number, not read as damaged or as another mesh.
constexpr const char* magic_prefix = "seam checkpoint ";
constexpr int format = 2;
const std::string magic = magic_prefix + std::to_string(format) + "\n";
constexpr char real_type = 'r', integer_type = 'i', text_type = 't';

std::string read_file(const std::filesystem::path& file, bool& ok) {
  std::ifstream in(file, std::ios::binary);
  ok = static_cast<bool>(in);
  std::ostringstream s;
  if (ok) s << in.rdbuf();
  return s.str();
}

template <class T> T take(const std::string& bytes, std::size_t& pos, bool& ok) {
  T v{};
  if (pos + sizeof(T) > bytes.size()) {
    ok = false;
    return v;
  }
  std::memcpy(&v, bytes.data() + pos, sizeof(T));
  pos += sizeof(T);
  return v;
}

// A sum of per-cell hashes (cell id, type, node ids, node coordinates): independent of how the
// cells are spread over ranks, so the whole mesh and a distributed one read from a file
// (which no rank holds whole) give the same value.
std::uint64_t cell_hash(const mesh::Mesh& m, std::int32_t c, std::int64_t gid,
                        std::span<const std::int64_t> node_gid) {
  std::uint64_t h = fnv1a(&gid, sizeof gid);
  h = fnv1a(&m.cell_type[c], sizeof(m.cell_type[c]), h);
  for (auto n : m.cell(c)) {
    const std::int64_t g = node_gid.empty() ? n : node_gid[n];
    h = fnv1a(&g, sizeof g, h);
    h = fnv1a(m.node(n).data(), sizeof(double) * static_cast<std::size_t>(m.dim), h);
  }
  return h;
}

std::string hex(std::uint64_t v) {
  char s[32];
  std::snprintf(s, sizeof s, "%016llx", static_cast<unsigned long long>(v));
  return s;
}

// `text` with the value of its entry `key:` (the time step: `dt` or `steps`) replaced by
// `value`; empty when the text has not exactly one such entry.
std::string with_entry(const std::string& text, const std::string& key, const std::string& value) {
  std::string out;
  int found = 0;
  for (std::size_t at = text.find(key); at != std::string::npos; at = text.find(key, at + 1)) {
    if (at > 0 && std::string(" \t\n{,").find(text[at - 1]) == std::string::npos) continue;
    std::size_t v = at + key.size();
    while (v < text.size() && (text[v] == ' ' || text[v] == '\t')) ++v;
    if (v >= text.size() || text[v] != ':') continue;
    for (++v; v < text.size() && (text[v] == ' ' || text[v] == '\t');) ++v;
    std::size_t end = v;
    while (end < text.size() && std::string(",}# \t\r\n").find(text[end]) == std::string::npos)
      ++end;
    if (++found > 1) return {};
    out = text.substr(0, v) + value + text.substr(end);
  }
  return out;
}

std::string shortest(double v) {
  char s[32];
  const auto r = std::to_chars(s, s + sizeof s, v);
  return std::string(s, r.ptr);
}

} // namespace

std::uint64_t fnv1a(const void* data, std::size_t bytes, std::uint64_t hash) {
  const auto* p = static_cast<const unsigned char*>(data);
  for (std::size_t i = 0; i < bytes; ++i) {
    hash ^= p[i];
    hash *= 0x100000001b3ULL;
  }
  return hash;
}

// ---- RecordWriter -----------------------------------------------------------------------

void RecordWriter::append(std::string& records, const std::string& name, char type,
                          const void* data, std::size_t bytes) {
  const auto n = static_cast<std::uint32_t>(name.size());
  const auto size = static_cast<std::uint64_t>(bytes);
  records.append(reinterpret_cast<const char*>(&n), sizeof n);
  records += name;
  records += type;
  records.append(reinterpret_cast<const char*>(&size), sizeof size);
  records.append(static_cast<const char*>(data), bytes);
}

void RecordWriter::put(const std::string& name, std::span<const double> values) {
  append(records_, name, real_type, values.data(), values.size_bytes());
}
void RecordWriter::put(const std::string& name, std::span<const std::int64_t> values) {
  append(records_, name, integer_type, values.data(), values.size_bytes());
}
void RecordWriter::put(const std::string& name, const std::string& text) {
  append(records_, name, text_type, text.data(), text.size());
}
void RecordWriter::put_part(const std::string& name, std::span<const double> values) {
  append(part_, name, real_type, values.data(), values.size_bytes());
}
void RecordWriter::put_part(const std::string& name, std::span<const std::int64_t> values) {
  append(part_, name, integer_type, values.data(), values.size_bytes());
}

namespace {

std::string document_of(const std::string& records) {
  std::string out = magic;
  out += records;
  // Trailer: the byte count of the records and their checksum.
  const std::uint64_t size = records.size();
  const std::uint64_t sum = fnv1a(records.data(), records.size());
  out.append(reinterpret_cast<const char*>(&size), sizeof size);
  out.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  return out;
}

std::string part_name(std::int64_t rank) {
  char name[32];
  std::snprintf(name, sizeof name, "part_%05lld.bin", static_cast<long long>(rank));
  return name;
}

} // namespace

void throw_collectively(const Comm& comm, std::string error) {
  const int mine = error.empty() ? comm.size() : comm.rank();
  int first = mine;
  MPI_Allreduce(&mine, &first, 1, MPI_INT, MPI_MIN, comm.get());
  if (first == comm.size()) return;
  comm.broadcast(error, first);
  SEAM_THROW(InputError, error);
}

std::string RecordWriter::document() const {
  return document_of(records_);
}
std::string RecordWriter::part_document() const {
  return document_of(part_);
}

// ---- RecordReader -----------------------------------------------------------------------

RecordReader::RecordReader(std::filesystem::path file) : file_(std::move(file)) {
  bool ok = false;
  const std::string bytes = read_file(file_, ok);
  if (!ok) fail("cannot be read (missing file)");
  const std::size_t head = magic.size();
  if (bytes.compare(0, head, magic) != 0) {
    const std::size_t prefix = std::strlen(magic_prefix);
    if (bytes.compare(0, prefix, magic_prefix) != 0)
      fail("is not a seam checkpoint (unknown first line)");
    const auto eol = bytes.find('\n', prefix);
    fail("is of checkpoint format " +
         bytes.substr(prefix,
                      eol == std::string::npos ? 8 : std::min<std::size_t>(eol - prefix, 8)) +
         ", written by another version of seam; this seam reads format " + std::to_string(format) +
         ": rerun to write a checkpoint of this version");
  }
  if (bytes.size() < head + 16) fail("is truncated");
  std::size_t pos = bytes.size() - 16;
  const auto size = take<std::uint64_t>(bytes, pos, ok);
  const auto sum = take<std::uint64_t>(bytes, pos, ok);
  if (size != bytes.size() - head - 16) fail("is truncated or has trailing bytes");
  if (sum != fnv1a(bytes.data() + head, size)) fail("is damaged (checksum mismatch)");
  pos = head;
  const std::size_t end = bytes.size() - 16;
  while (pos < end) {
    const auto n = take<std::uint32_t>(bytes, pos, ok);
    if (!ok || pos + n + 1 + 8 > end) fail("is damaged (bad record header)");
    std::string name = bytes.substr(pos, n);
    pos += n;
    const char type = bytes[pos++];
    const auto length = take<std::uint64_t>(bytes, pos, ok);
    if (!ok || length > end - pos) fail("is damaged (record '" + name + "' runs past the end)");
    records_[name] = {type, bytes.substr(pos, length)};
    pos += length;
  }
}

void RecordReader::fail(const std::string& message) const {
  SEAM_THROW(InputError, "checkpoint ", file_.string(), ": ", message);
}

const RecordReader::Record& RecordReader::get(const std::string& name, char type) const {
  const auto it = records_.find(name);
  if (it == records_.end()) fail("has no record '" + name + "'");
  if (it->second.type != type) fail("record '" + name + "' has the wrong type");
  return it->second;
}

std::vector<double> RecordReader::reals(const std::string& name,
                                        std::optional<std::size_t> expected) const {
  const auto& r = get(name, real_type);
  std::vector<double> out(r.bytes.size() / sizeof(double));
  if (r.bytes.size() % sizeof(double) != 0 || (expected && out.size() != *expected))
    fail(::seam::detail::concat("record '", name, "' holds ", out.size(), " values, expected ",
                                expected ? *expected : 0));
  // An empty record has no storage to copy (memcpy with a null pointer is undefined).
  if (!out.empty()) std::memcpy(out.data(), r.bytes.data(), r.bytes.size());
  return out;
}

std::vector<std::int64_t> RecordReader::integers(const std::string& name,
                                                 std::optional<std::size_t> expected) const {
  const auto& r = get(name, integer_type);
  std::vector<std::int64_t> out(r.bytes.size() / sizeof(std::int64_t));
  if (r.bytes.size() % sizeof(std::int64_t) != 0 || (expected && out.size() != *expected))
    fail(::seam::detail::concat("record '", name, "' holds ", out.size(), " values, expected ",
                                expected ? *expected : 0));
  // An empty record has no storage to copy (memcpy with a null pointer is undefined).
  if (!out.empty()) std::memcpy(out.data(), r.bytes.data(), r.bytes.size());
  return out;
}

std::string RecordReader::text(const std::string& name) const {
  return get(name, text_type).bytes;
}

// ---- Checkpoints ------------------------------------------------------------------------

CanonicalOrder nodal_order(const Discretization& disc) {
  // Per node of the mesh as read (node_gid), dim entries; this rank lists the nodes it holds.
  const int dim = disc.dim();
  CanonicalOrder order;
  order.size = disc.n_global_nodes() * dim;
  for (std::int32_t node = 0; node < disc.mesh().n_nodes(); ++node) {
    if (!disc.has_node(node)) continue;
    const std::int64_t id = disc.node_gid(node);
    for (int c = 0; c < dim; ++c)
      order.add(id * dim + c, disc.local_dof(node, c), disc.owns_node(node));
  }
  return order;
}

MeshIdentity identify(const mesh::Mesh& m) {
  std::uint64_t h = fnv1a(&m.dim, sizeof(m.dim));
  for (std::int32_t c = 0; c < m.n_cells(); ++c) h += cell_hash(m, c, c, {});
  return {m.dim, m.n_nodes(), m.n_cells(), h};
}

MeshIdentity identify(const mesh::DistributedMesh& d, const Comm& comm) {
  const auto& m = d.mesh;
  std::uint64_t h = 0, sum = 0;
  for (std::int32_t c = 0; c < m.n_cells(); ++c)
    if (d.cell_role[c] == mesh::CellRole::owned) h += cell_hash(m, c, d.cell_gid[c], d.node_gid);
  MPI_Allreduce(&h, &sum, 1, MPI_UINT64_T, MPI_SUM, comm.get());
  return {m.dim, d.n_global_nodes, d.n_global_cells, sum + fnv1a(&m.dim, sizeof(m.dim))};
}

Checkpoints::Checkpoints(const io::Config& config, std::string problem, MeshIdentity mesh,
                         Comm comm, CanonicalOrder order, const std::string& input,
                         std::filesystem::path output_dir, const std::string& restart)
    : problem_(std::move(problem)), mesh_(mesh), comm_(comm), order_(std::move(order)),
      every_(config.output.checkpoint_every), dt_(config.time.dt), dir_(std::move(output_dir)) {
  bool ok = false;
  const std::string text = read_file(input, ok);
  input_hash_ = fnv1a(text.data(), text.size());
  if (restart.empty()) return;
  restarting_ = true;
  const std::filesystem::path dir(restart);
  if (!std::filesystem::is_directory(dir))
    SEAM_THROW(InputError, "--restart ", restart,
               ": no such checkpoint directory (expected DIR/checkpoint_NNNNN)");
  reader_ = RecordReader(dir / "state.bin");
  const auto& r = reader_;
  const auto& m = mesh;
  // The kind of run first: a checkpoint of another kind holds other records.
  if (r.has("problem") && r.text("problem") != problem_)
    r.fail("was written by a " + r.text("problem") + " run; " + input + " describes a " + problem_ +
           " run");
  if (r.integer("dimension") != m.dim)
    r.fail(::seam::detail::concat("was written by a run in dimension ", r.integer("dimension"),
                                  "; the input has dimension ", m.dim));
  if (r.integer("mesh_nodes") != m.nodes || r.integer("mesh_cells") != m.cells)
    r.fail(::seam::detail::concat("was written for a mesh of ", r.integer("mesh_nodes"),
                                  " nodes and ", r.integer("mesh_cells"),
                                  " cells; the input's has ", m.nodes, " nodes and ", m.cells,
                                  " cells"));
  if (static_cast<std::uint64_t>(r.integer("mesh_hash")) != m.hash)
    r.fail("was written for another mesh (same size, other coordinates or connectivity)");
  const auto stored_hash = static_cast<std::uint64_t>(r.integer("input_hash"));
  if (stored_hash != input_hash_) {
    // An input that differs only in the time step continues with the new step: the state at
    // the restart time (displacement, velocity, generalized-alpha's acceleration, the fluid's
    // rates) does not depend on the step, and the integrators take each step's size as it
    // comes (as after a step cut). The checkpoint's step: its record, or (checkpoints of
    // earlier versions) the step in effect when no cut was.
    const double old_dt = r.has("time.dt") ? r.real("time.dt")
                          : r.has("control.dt") && r.integer("control.cuts") == 0
                              ? r.real("control.dt")
                              : 0.0;
    bool only_dt = false;
    if (old_dt > 0.0 && old_dt != dt_) {
      const std::string steps = std::to_string(std::llround(config.time.end / old_dt));
      for (const auto& candidate :
           {with_entry(text, "dt", shortest(old_dt)), with_entry(text, "steps", steps)})
        only_dt |= !candidate.empty() && fnv1a(candidate.data(), candidate.size()) == stored_hash;
    }
    if (!only_dt)
      r.fail("was written for another input file (hash " + hex(stored_hash) + ", " + input +
             " has " + hex(input_hash_) +
             "); restart with the input that wrote it (only the "
             "time step may differ)");
    if (comm_.is_root())
      std::printf("  restarting with dt = %g: the checkpoint's run had dt = %g (the state at "
                  "t = %g continues with the new step)\n",
                  dt_, old_dt, r.real("time"));
  }
  restart_dir_ = restart_output_directory(restart);
  restart_step_ = static_cast<int>(r.integer("step"));
  restart_time_ = r.real("time");
  if (!r.has("vector_parts"))
    r.fail("was written by an earlier seam, which stored the fields whole in state.bin; "
           "rerun to write a checkpoint of this version");
  // The part files this rank reads; a missing or damaged one stops every rank.
  const auto n_parts = r.integer("vector_parts");
  std::string error;
  try {
    for (std::int64_t f = comm_.rank(); f < n_parts; f += comm_.size())
      parts_.emplace_back(dir / part_name(f));
  } catch (const InputError& e) {
    error = e.what();
  }
  throw_collectively(comm_, error);
  // Output counters (Output::write_checkpoint), read here so that every rank checks them.
  std::istringstream files(r.text("output.pvd_files"));
  for (const double t : r.reals("output.pvd_times")) {
    std::string file;
    if (!std::getline(files, file)) r.fail("record 'output.pvd_files' has fewer files than times");
    pvd_.push_back({t, file});
  }
}

std::vector<io::PvdCollection::Entry>
Checkpoints::pvd_entries(const std::filesystem::path& output_dir) const {
  auto entries = pvd_;
  std::error_code ec;
  const auto from = std::filesystem::weakly_canonical(restart_dir_, ec);
  const auto to = std::filesystem::weakly_canonical(output_dir, ec);
  if (!ec && from != to)
    for (auto& e : entries) e.file = (from / e.file).lexically_relative(to).string();
  return entries;
}

RecordWriter Checkpoints::begin(int step, double time) const {
  RecordWriter w;
  const auto& m = mesh_;
  w.put("problem", problem_);
  w.put_integer("dimension", m.dim);
  w.put_integer("mesh_nodes", m.nodes);
  w.put_integer("mesh_cells", m.cells);
  w.put_integer("mesh_hash", static_cast<std::int64_t>(m.hash));
  w.put_integer("input_hash", static_cast<std::int64_t>(input_hash_));
  w.put_integer("ranks", comm_.size());
  w.put_integer("vector_parts", comm_.size());
  w.put_integer("step", step);
  w.put_real("time", time);
  w.put_real("time.dt", dt_); // the input's step (a restart may change it)
  std::vector<std::int64_t> owned;
  for (std::size_t k = 0; k < order_.index.size(); ++k)
    if (order_.owned[k]) owned.push_back(order_.index[k]);
  w.put_part("index", owned);
  return w;
}

void Checkpoints::commit(const RecordWriter& writer, int step) const {
  const auto& comm = comm_;
  char name[32];
  std::snprintf(name, sizeof name, "checkpoint_%05d", step);
  const auto dir = dir_ / name;
  std::string error;
  if (comm.is_root()) {
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) error = "cannot create " + dir.string() + ": " + ec.message();
  }
  comm.broadcast(error);
  if (!error.empty()) SEAM_THROW(InputError, error);
  // Every rank its part, then rank 0 the shared records: state.bin is written last, so a
  // checkpoint with a state.bin has all its parts.
  const auto write = [&](const std::filesystem::path& file, const std::string& text) {
    try {
      io::write_file_atomically(file, text);
    } catch (const InputError& e) {
      error = e.what();
    }
  };
  write(dir / part_name(comm.rank()), writer.part_document());
  throw_collectively(comm, error);
  if (comm.is_root()) write(dir / "state.bin", writer.document());
  comm.broadcast(error);
  if (!error.empty()) SEAM_THROW(InputError, error);
}

void Checkpoints::put_vector(RecordWriter& writer, const std::string& name,
                             const la::Vector& v) const {
  std::vector<double> values;
  {
    const la::Vector::LocalView view(v, false);
    const auto vl = view.values();
    for (std::size_t k = 0; k < order_.index.size(); ++k)
      if (order_.owned[k]) values.push_back(vl[static_cast<std::size_t>(order_.local[k])]);
  }
  writer.put_part(name, values);
}

namespace {

struct Entry {
  std::int64_t index;
  double value;
};

} // namespace

void Checkpoints::get_vector(const std::string& name, la::Vector& v) const {
  const auto& order = order_;
  const auto held = get_keyed("index", name, 1, order.size, order.index);
  {
    la::Vector::LocalView view(v, true);
    auto vl = view.values();
    for (std::size_t k = 0; k < held.size(); ++k)
      if (order.local[k] >= 0) vl[static_cast<std::size_t>(order.local[k])] = held[k];
  }
  v.update_ghosts();
}

std::vector<double> Checkpoints::get_keyed(const std::string& keys, const std::string& name,
                                           int width, std::int64_t n_keys,
                                           std::span<const std::int64_t> wanted) const {
  const int np = comm_.size();
  const auto w = static_cast<std::int64_t>(width);
  // Item k's value c is entry k * width + c.
  const auto home = [np](std::int64_t i) { return static_cast<int>(i % np); };
  // The entries of the part files this rank read go to the rank that keeps entry i
  // (i mod np) ...
  std::vector<std::vector<Entry>> out(static_cast<std::size_t>(np));
  std::string error; // a bad record stops every rank, not only the one reading it
  try {
    for (const auto& part : parts_) {
      const auto index = part.integers(keys);
      const auto values = part.reals(name, index.size() * static_cast<std::size_t>(width));
      for (std::size_t k = 0; k < index.size(); ++k) {
        if (index[k] < 0 || index[k] >= n_keys)
          part.fail("record '" + keys + "' holds an entry out of range");
        for (std::int64_t c = 0; c < w; ++c) {
          const std::int64_t i = index[k] * w + c;
          out[static_cast<std::size_t>(home(i))].push_back(
              {i, values[k * static_cast<std::size_t>(width) + static_cast<std::size_t>(c)]});
        }
      }
    }
  } catch (const InputError& e) {
    error = e.what();
  }
  throw_collectively(comm_, error);
  std::vector<Entry> send;
  std::vector<std::int64_t> offsets(1, 0), recv_offsets;
  for (const auto& o : out) {
    send.insert(send.end(), o.begin(), o.end());
    offsets.push_back(static_cast<std::int64_t>(send.size()));
  }
  auto kept = parallel::alltoallv<Entry>(comm_.get(), send, offsets, recv_offsets);
  std::sort(kept.begin(), kept.end(),
            [](const Entry& a, const Entry& b) { return a.index < b.index; });
  // ... which answers the requests of the ranks that hold it.
  std::vector<std::vector<std::int64_t>> ask(static_cast<std::size_t>(np));
  std::vector<std::vector<std::size_t>> slot(static_cast<std::size_t>(np));
  for (std::size_t k = 0; k < wanted.size(); ++k)
    for (std::int64_t c = 0; c < w; ++c) {
      const std::int64_t i = wanted[k] * w + c;
      ask[static_cast<std::size_t>(home(i))].push_back(i);
      slot[static_cast<std::size_t>(home(i))].push_back(k * static_cast<std::size_t>(width) +
                                                        static_cast<std::size_t>(c));
    }
  std::vector<std::int64_t> asked;
  offsets.assign(1, 0);
  for (const auto& a : ask) {
    asked.insert(asked.end(), a.begin(), a.end());
    offsets.push_back(static_cast<std::int64_t>(asked.size()));
  }
  std::vector<std::int64_t> asked_offsets;
  const auto requests =
      parallel::alltoallv<std::int64_t>(comm_.get(), asked, offsets, asked_offsets);
  std::vector<double> answers(requests.size(), 0.0);
  bool missing = false;
  for (std::size_t k = 0; k < requests.size(); ++k) {
    const auto it = std::lower_bound(kept.begin(), kept.end(), requests[k],
                                     [](const Entry& e, std::int64_t i) { return e.index < i; });
    if (it == kept.end() || it->index != requests[k])
      missing = true;
    else
      answers[k] = it->value;
  }
  if (comm_.any(missing))
    SEAM_THROW(InputError, "checkpoint ", reader_.path().parent_path().string(), ": record '", name,
               "' of its part files lacks entries (a part file of another "
               "run?)");
  std::vector<std::int64_t> back_offsets;
  const auto values =
      parallel::alltoallv<double>(comm_.get(), answers, asked_offsets, back_offsets);
  std::vector<double> held(wanted.size() * static_cast<std::size_t>(width), 0.0);
  for (int r = 0; r < np; ++r)
    for (std::size_t j = 0; j < slot[static_cast<std::size_t>(r)].size(); ++j)
      held[slot[static_cast<std::size_t>(r)][j]] =
          values[static_cast<std::size_t>(back_offsets[r]) + j];
  return held;
}

void Checkpoints::read_parts(const std::function<void(const RecordReader&)>& read) const {
  std::string error;
  try {
    for (const auto& part : parts_) read(part);
  } catch (const InputError& e) {
    error = e.what();
  }
  throw_collectively(comm_, error);
}

io::CsvTable::Mode Checkpoints::table_mode(const std::filesystem::path& file) const {
  if (!restarting_) return io::CsvTable::Mode::truncate;
  drop_rows_after(file, restart_step_);
  return io::CsvTable::Mode::append;
}

void put_pvd(RecordWriter& writer, const io::PvdCollection* pvd) {
  std::vector<double> times;
  std::string files;
  if (pvd)
    for (const auto& e : pvd->entries()) {
      times.push_back(e.time);
      files += e.file + "\n";
    }
  writer.put("output.pvd_times", times);
  writer.put("output.pvd_files", files);
}

void drop_rows_after(const std::filesystem::path& file, int step) {
  if (!std::filesystem::exists(file)) return;
  bool ok = false;
  const std::string text = read_file(file, ok);
  if (!ok) SEAM_THROW(InputError, "cannot read ", file.string(), " to continue it");
  std::string out;
  std::istringstream in(text);
  std::string line;
  bool header = true;
  while (std::getline(in, line)) {
    if (!header) {
      // The first column is the step; a row cut short by a crash has no complete step.
      const auto comma = line.find(',');
      if (comma == std::string::npos) continue;
      char* end = nullptr;
      const long s = std::strtol(line.c_str(), &end, 10);
      if (end != line.c_str() + comma || s > step) continue;
    }
    header = false;
    out += line;
    out += '\n';
  }
  io::write_file_atomically(file, out);
}

std::filesystem::path restart_output_directory(const std::string& restart) {
  auto dir = std::filesystem::path(restart);
  if (!dir.has_filename()) dir = dir.parent_path(); // "DIR/checkpoint_00010/"
  auto parent = dir.parent_path();
  return parent.empty() ? std::filesystem::path(".") : parent;
}

} // namespace seam::problem
