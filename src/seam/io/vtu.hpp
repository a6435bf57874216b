#pragma once
// VTK XML output for ParaView: one UnstructuredGrid piece (.vtu), the parallel header that
// references the pieces of all ranks (.pvtu) and the time collection (.pvd).
// File format: "VTK File Formats", VTK User's Guide 11th ed., section 19.3 (XML formats);
// https://docs.vtk.org/en/latest/design_documents/VTKFileFormats.html
//
// No MPI here: every rank writes its own piece, rank 0 writes the .pvtu and the .pvd.
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <utility>
#include <variant>
#include <vector>

namespace seam::io {

/// How DataArray values are stored: inline base64 (compact, exact, the default) or ASCII
/// (readable; doubles in shortest round-trip form, so also exact).
enum class VtkFormat { binary, ascii };

/// A named point or cell field: n_components values per point/cell, point/cell-major
/// (values[i * n_components + c]). Real fields are written as Float64, integer fields
/// (rank, contact status) as Int32.
struct DataField {
  std::string name;
  int n_components = 1;
  std::variant<std::span<const double>, std::span<const std::int32_t>> values;

  DataField(std::string name, int n_components, std::span<const double> values)
      : name(std::move(name)), n_components(n_components), values(values) {}
  DataField(std::string name, int n_components, std::span<const std::int32_t> values)
      : name(std::move(name)), n_components(n_components), values(values) {}

  bool is_integer() const { return values.index() == 1; }
  std::size_t size() const;
};

/// One piece of an unstructured grid, as views on the caller's arrays. Cells use VTK's own
/// layout: `connectivity` lists the point indices of every cell in VTK node order (permute
/// with fem::vtk_node_order), `offsets[c]` is the end of cell c in `connectivity`, `types[c]`
/// the VTK cell type id (fem::vtk_type).
struct VtuPiece {
  int point_dim = 3;              ///< coordinates per point in `points` (1, 2 or 3); z = 0 is added
  std::span<const double> points; ///< n_points * point_dim, point-major
  std::span<const std::int32_t> connectivity;
  std::span<const std::int32_t> offsets;
  std::span<const std::uint8_t> types;
  std::vector<DataField> point_data;
  std::vector<DataField> cell_data;
  std::optional<double> time;        ///< written as FieldData "TimeValue" (ParaView's time)
  std::optional<std::int64_t> cycle; ///< written as FieldData "CYCLE" (the step number)

  std::size_t n_points() const;
  std::size_t n_cells() const { return types.size(); }
};

/// Writes `piece` to `file` (.vtu). The file is written under a temporary name and renamed,
/// so a reader never sees a half-written file. Throws seam::InternalError if the arrays are
/// inconsistent (sizes, offsets, indices out of range) and seam::InputError if the file cannot
/// be written.
void write_vtu(const std::filesystem::path& file, const VtuPiece& piece,
               VtkFormat format = VtkFormat::binary);

/// Writes the parallel header `file` (.pvtu) that references `piece_files` (paths relative to
/// the directory of `file`, one per rank, in rank order). Field names, component counts and
/// types, and the time, are taken from `layout` (usually rank 0's own piece; its arrays
/// are not read, so they may be empty).
void write_pvtu(const std::filesystem::path& file, const VtuPiece& layout,
                std::span<const std::string> piece_files);

/// "results_00042.vtu" for (stem "results", step 42, extension ".vtu"); at least 5 digits.
std::string step_file_name(std::string_view stem, std::int64_t step, std::string_view extension);
/// "results_00042_p3.vtu": the piece of `rank` for step `step`.
std::string piece_file_name(std::string_view stem, std::int64_t step, int rank);

/// The ParaView time collection (.pvd): one data set per written step. The whole file is
/// rewritten (atomically) after every add(), so a run that fails later still leaves a valid
/// collection of everything written so far.
class PvdCollection {
public:
  struct Entry {
    double time;
    std::string file; ///< relative to the directory of the .pvd
  };

  /// Starts a fresh collection and writes it (empty) at once, replacing any old file.
  explicit PvdCollection(std::filesystem::path file);
  /// Continues a collection (a restart) with its entries so far, written at once.
  PvdCollection(std::filesystem::path file, std::vector<Entry> entries);

  void add(double time, std::string file);
  std::span<const Entry> entries() const { return entries_; }
  const std::filesystem::path& path() const { return file_; }

private:
  void write() const;

  std::filesystem::path file_;
  std::vector<Entry> entries_;
};

/// RFC 4648 base64 (standard alphabet, '=' padding) of `bytes`.
std::string base64_encode(std::span<const std::byte> bytes);

/// Writes `contents` to a temporary file next to `file`, then renames it over `file`
/// (rename(2) replaces atomically on POSIX). Throws seam::InputError naming the file on
/// failure. Shared by all writers of the output directory.
void write_file_atomically(const std::filesystem::path& file, std::string_view contents);

} // namespace seam::io
