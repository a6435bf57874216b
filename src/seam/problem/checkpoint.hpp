#pragma once
// Checkpoints and restart (CONTRACT.md "Checkpoints"). A checkpoint is the directory
// checkpoint_NNNNN/ in the output directory with the file state.bin and one file
// part_RRRRR.bin per rank that wrote it: named records (reals, integers, text) behind a magic
// line and followed by their byte count and an FNV-1a checksum, so that a truncated or damaged
// file is found before anything is read from it.
// state.bin holds what is not sized by the mesh or an interface. Nothing is gathered: the
// nodal vectors and the contact interface state per slave node are written by the ranks that
// own the entries into their part files, with their index in a rank-independent order (per
// mesh node in node id order, the node's dofs in order; the node id for a slave node), and a
// restart on any number of ranks routes them to the ranks that hold them (no rank holds a
// whole vector); per-rank pieces of operators (triplets) stay in the part of the rank that
// integrated them and are taken by the rank that reads that part.
// The input file's and the mesh's hashes are stored with them: a checkpoint of another input
// or mesh is an input error, except an input that differs only in its time step (`dt:` or
// `steps:`), which continues with the new step (StepControl::set_state).
#include "seam/io/config.hpp"
#include "seam/io/table.hpp"
#include "seam/io/vtu.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/discretization.hpp"

#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace seam::problem {

/// Named records, built on every rank: the shared records (rank 0's copy is the one written to
/// state.bin) and this rank's part (part_RRRRR.bin).
class RecordWriter {
public:
  /// A record of this rank's part file.
  void put_part(const std::string& name, std::span<const double> values);
  void put_part(const std::string& name, std::span<const std::int64_t> values);
  /// The part file: magic line, records, byte count, checksum.
  std::string part_document() const;
  void put(const std::string& name, std::span<const double> values);
  void put(const std::string& name, std::span<const std::int64_t> values);
  void put(const std::string& name, const std::string& text);
  void put_real(const std::string& name, double value) { put(name, std::span(&value, 1)); }
  void put_integer(const std::string& name, std::int64_t value) { put(name, std::span(&value, 1)); }
  /// The whole file: magic line, records, byte count, checksum.
  std::string document() const;

private:
  static void append(std::string& records, const std::string& name, char type, const void* data,
                     std::size_t bytes);
  std::string records_, part_;
};

/// The records of a file written by RecordWriter; every accessor throws InputError naming the
/// file and the record when it is missing or of another size.
class RecordReader {
public:
  RecordReader() = default;
  /// Reads and verifies `file` (magic line, byte count, checksum).
  explicit RecordReader(std::filesystem::path file);

  bool has(const std::string& name) const { return records_.count(name) > 0; }
  /// `expected` values, or any number when it is omitted.
  std::vector<double> reals(const std::string& name,
                            std::optional<std::size_t> expected = std::nullopt) const;
  std::vector<std::int64_t> integers(const std::string& name,
                                     std::optional<std::size_t> expected = std::nullopt) const;
  std::string text(const std::string& name) const;
  double real(const std::string& name) const { return reals(name, 1)[0]; }
  std::int64_t integer(const std::string& name) const { return integers(name, 1)[0]; }
  const std::filesystem::path& path() const { return file_; }
  /// InputError: "checkpoint FILE: MESSAGE".
  [[noreturn]] void fail(const std::string& message) const;

private:
  struct Record {
    char type;
    std::string bytes;
  };
  const Record& get(const std::string& name, char type) const;
  std::filesystem::path file_;
  std::map<std::string, Record> records_;
};

/// What a checkpoint records of the mesh as read, so that a restart with another mesh is
/// refused: taken from the whole mesh (on rank 0 before the mesh is distributed), or from the
/// parts of a distributed mesh (collective; the same value).
struct MeshIdentity {
  int dim = 0;
  std::int64_t nodes = 0, cells = 0;
  std::uint64_t hash = 0;
};
MeshIdentity identify(const mesh::Mesh& m);
MeshIdentity identify(const mesh::DistributedMesh& d, const Comm& comm);

/// The rank-independent order in which a field's vectors are stored: per mesh node in node id
/// order, its dofs in the field's order. Each rank lists only the entries it holds.
struct CanonicalOrder {
  /// Per entry this rank holds (owned or ghost): its index in the stored order, its local
  /// (ghosted) index, and whether this rank owns it (each entry has one owner, who writes it).
  std::vector<std::int64_t> index;
  std::vector<std::int32_t> local;
  std::vector<char> owned;
  /// The number of stored entries over all ranks.
  std::int64_t size = 0;
  void add(std::int64_t i, std::int32_t l, bool own) {
    index.push_back(i);
    local.push_back(l);
    owned.push_back(own ? 1 : 0);
  }
};
/// Solids: dim displacement dofs per node.
CanonicalOrder nodal_order(const Discretization& disc);

/// The checkpoints of one run: writing them every `output.checkpoint_every` converged steps,
/// and the one it restarts from.
/// Throws `error` of the lowest rank that has one (non-empty) as InputError on every rank: the
/// same message everywhere, so that rank 0 prints the file another rank could not read or
/// write. Collective.
void throw_collectively(const Comm& comm, std::string error);

class Checkpoints {
public:
  /// `problem` names the kind of run ("solid", "fluid", "fluid-structure"), recorded in every
  /// checkpoint. `restart` empty: a fresh run. Otherwise the checkpoint directory is read and
  /// checked against the kind of run, the input file and the mesh (InputError on any
  /// mismatch). Collective.
  Checkpoints(const io::Config& config, std::string problem, MeshIdentity mesh, Comm comm,
              CanonicalOrder order, const std::string& input, std::filesystem::path output_dir,
              const std::string& restart);

  bool restarting() const { return restarting_; }
  /// The checkpoint restarted from (restarting() only).
  const RecordReader& restart() const { return reader_; }
  int restart_step() const { return restart_step_; }
  double restart_time() const { return restart_time_; }
  /// results.pvd's entries up to the restart step, relative to `output_dir` (the files stay
  /// where the run that wrote the checkpoint put them).
  std::vector<io::PvdCollection::Entry> pvd_entries(const std::filesystem::path& output_dir) const;

  /// A checkpoint is due after converged step `step`.
  bool due(int step) const { return every_ > 0 && step % every_ == 0; }
  /// A writer holding the identification records (kind of run, input and mesh hashes, step).
  RecordWriter begin(int step, double time) const;
  /// Writes checkpoint_NNNNN/: every rank its part file, then rank 0 state.bin. Collective.
  void commit(const RecordWriter& writer, int step) const;

  /// v's owned values as record `name` of this rank's part (in the order of the part's
  /// record `index`).
  void put_vector(RecordWriter& writer, const std::string& name, const la::Vector& v) const;
  /// Record `name` of the restart checkpoint into v (owned and ghost entries). Collective.
  void get_vector(const std::string& name, la::Vector& v) const;
  /// Keyed records of the restart checkpoint's part files: record `keys` holds one key in
  /// [0, n_keys) per item (each item in one part), record `name` `width` values per item. Returns
  /// the values of the items `wanted` (width each, in that order): each rank sends the items
  /// of the part files it read to a rank chosen by key, which answers the ranks that ask for
  /// them, so no rank gathers the items (per slave node interface state, nodal vectors).
  /// InputError on every rank when a record is missing or damaged or an item wanted is in no
  /// part. Collective.
  std::vector<double> get_keyed(const std::string& keys, const std::string& name, int width,
                                std::int64_t n_keys, std::span<const std::int64_t> wanted) const;
  /// The part files of the restart checkpoint this rank read are part r, r + size, ... (of a
  /// checkpoint written on more ranks; none on ranks beyond those that wrote it).
  /// Calls `read` with each of them; an InputError there stops every rank with its message.
  /// Collective.
  void read_parts(const std::function<void(const RecordReader&)>& read) const;

  /// The mode of an output table: a fresh file, or (restarting) the file continued after its
  /// rows past the checkpoint's step are dropped. Rank 0.
  io::CsvTable::Mode table_mode(const std::filesystem::path& file) const;

private:
  std::string problem_;
  MeshIdentity mesh_;
  Comm comm_;
  CanonicalOrder order_;
  int every_ = 0;
  double dt_ = 0.0; ///< the input's time step
  std::filesystem::path dir_;
  std::uint64_t input_hash_ = 0;
  bool restarting_ = false;
  RecordReader reader_;
  /// The part files of the restart checkpoint this rank reads (files r, r + size, ...).
  std::vector<RecordReader> parts_;
  int restart_step_ = 0;
  double restart_time_ = 0.0;
  std::vector<io::PvdCollection::Entry> pvd_;
  std::filesystem::path restart_dir_; ///< where the checkpoint's run wrote its output
};

/// The entries of results.pvd so far (null on ranks other than 0) as the output records
/// a restart continues from.
void put_pvd(RecordWriter& writer, const io::PvdCollection* pvd);

/// FNV-1a 64-bit hash of bytes (checksums and the input/mesh identity of a checkpoint).
std::uint64_t fnv1a(const void* data, std::size_t bytes,
                    std::uint64_t hash = 0xcbf29ce484222325ULL);

/// Keeps the header and the rows of the CSV file whose first column (the step) is at most
/// `step`: a run that continued past the checkpoint left rows that the restart writes again.
/// Nothing happens when the file does not exist.
void drop_rows_after(const std::filesystem::path& file, int step);

/// The output directory of a restart without -o: the directory that holds the checkpoint.
std::filesystem::path restart_output_directory(const std::string& restart);

} // namespace seam::problem
