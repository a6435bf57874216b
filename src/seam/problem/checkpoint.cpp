#include "seam/problem/checkpoint.hpp"

#include "seam/common/collective.hpp"

#include "seam/common/error.hpp"
#include "seam/io/vtu.hpp"

#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

namespace seam::problem {

namespace {

constexpr const char* magic = "seam checkpoint 1\n";
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

void RecordWriter::append(const std::string& name, char type, const void* data, std::size_t bytes) {
  const auto n = static_cast<std::uint32_t>(name.size());
  const auto size = static_cast<std::uint64_t>(bytes);
  records_.append(reinterpret_cast<const char*>(&n), sizeof n);
  records_ += name;
  records_ += type;
  records_.append(reinterpret_cast<const char*>(&size), sizeof size);
  records_.append(static_cast<const char*>(data), bytes);
}

void RecordWriter::put(const std::string& name, std::span<const double> values) {
  append(name, real_type, values.data(), values.size_bytes());
}
void RecordWriter::put(const std::string& name, std::span<const std::int64_t> values) {
  append(name, integer_type, values.data(), values.size_bytes());
}
void RecordWriter::put(const std::string& name, const std::string& text) {
  append(name, text_type, text.data(), text.size());
}

std::string RecordWriter::document() const {
  std::string out = magic;
  out += records_;
  // Trailer: the byte count of the records and their checksum.
  const std::uint64_t size = records_.size();
  const std::uint64_t sum = fnv1a(records_.data(), records_.size());
  out.append(reinterpret_cast<const char*>(&size), sizeof size);
  out.append(reinterpret_cast<const char*>(&sum), sizeof sum);
  return out;
}

// ---- RecordReader -----------------------------------------------------------------------

RecordReader::RecordReader(std::filesystem::path file) : file_(std::move(file)) {
  bool ok = false;
  const std::string bytes = read_file(file_, ok);
  if (!ok) fail("cannot be read (missing file)");
  const std::size_t head = std::strlen(magic);
  if (bytes.compare(0, head, magic) != 0) fail("is not a seam checkpoint (unknown first line)");
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
  // Per node of the mesh as read (node_gid): the local entries of this rank's nodes, and on
  // rank 0 the global dof of every node, from the owners (the mesh may be distributed).
  const int dim = disc.dim();
  CanonicalOrder order;
  order.size = static_cast<std::size_t>(disc.n_global_nodes()) * static_cast<std::size_t>(dim);
  order.local.assign(order.size, -1);
  std::vector<std::int64_t> owned; // pairs (node id, its first global dof)
  for (std::int32_t node = 0; node < disc.mesh().n_nodes(); ++node) {
    if (!disc.has_node(node)) continue;
    const auto id = static_cast<std::size_t>(disc.node_gid(node));
    for (int c = 0; c < dim; ++c) order.local[id * dim + c] = disc.local_dof(node, c);
    if (disc.owns_node(node)) {
      owned.push_back(static_cast<std::int64_t>(id));
      owned.push_back(disc.global_dof(node, 0));
    }
  }
  const auto all = gather_to_root(disc.comm(), owned);
  if (disc.comm().is_root()) {
    order.global.assign(order.size, -1);
    for (std::size_t k = 0; k + 1 < all.size(); k += 2)
      for (int c = 0; c < dim; ++c)
        order.global[static_cast<std::size_t>(all[k]) * dim + c] =
            static_cast<PetscInt>(all[k + 1] + c);
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

Checkpoints::Checkpoints(const io::Config& config, MeshIdentity mesh, Comm comm,
                         CanonicalOrder order, const std::string& input,
                         std::filesystem::path output_dir, const std::string& restart)
    : mesh_(mesh), comm_(comm), order_(std::move(order)), every_(config.output.checkpoint_every),
      dir_(std::move(output_dir)) {
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
  if (static_cast<std::uint64_t>(r.integer("input_hash")) != input_hash_)
    r.fail("was written for another input file (hash " +
           hex(static_cast<std::uint64_t>(r.integer("input_hash"))) + ", " + input + " has " +
           hex(input_hash_) + "); restart with the input that wrote it");
  restart_dir_ = restart_output_directory(restart);
  restart_step_ = static_cast<int>(r.integer("step"));
  restart_time_ = r.real("time");
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
  w.put_integer("dimension", m.dim);
  w.put_integer("mesh_nodes", m.nodes);
  w.put_integer("mesh_cells", m.cells);
  w.put_integer("mesh_hash", static_cast<std::int64_t>(m.hash));
  w.put_integer("input_hash", static_cast<std::int64_t>(input_hash_));
  w.put_integer("ranks", comm_.size());
  w.put_integer("step", step);
  w.put_real("time", time);
  return w;
}

void Checkpoints::commit(const RecordWriter& writer, int step) const {
  const auto& comm = comm_;
  std::string error;
  if (comm.is_root()) {
    char name[32];
    std::snprintf(name, sizeof name, "checkpoint_%05d", step);
    const auto dir = dir_ / name;
    std::error_code ec;
    std::filesystem::create_directories(dir, ec);
    if (ec) {
      error = "cannot create " + dir.string() + ": " + ec.message();
    } else {
      try {
        io::write_file_atomically(dir / "state.bin", writer.document());
      } catch (const InputError& e) {
        error = e.what();
      }
    }
  }
  comm.broadcast(error);
  if (!error.empty()) SEAM_THROW(InputError, error);
}

void Checkpoints::put_vector(RecordWriter& writer, const std::string& name,
                             const la::Vector& v) const {
  // Rank 0 gathers every entry in the canonical order; the others ask for nothing.
  const la::Gather gather(v, order_.global);
  std::vector<double> values;
  gather(v, values);
  writer.put(name, values);
}

void Checkpoints::get_vector(const std::string& name, la::Vector& v) const {
  const auto values = reader_.reals(name, order_.size);
  {
    la::Vector::LocalView view(v, true);
    auto vl = view.values();
    for (std::size_t i = 0; i < order_.size; ++i)
      if (order_.local[i] >= 0) vl[static_cast<std::size_t>(order_.local[i])] = values[i];
  }
  v.update_ghosts();
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
