#include "seam/io/vtu.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <array>
#include <bit>
#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <set>
#include <system_error>
#include <type_traits>

namespace seam::io {

namespace {

constexpr std::string_view base64_alphabet =
    "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";

// RFC 4648, section 4: every 3 input bytes become 4 characters. VTK reads the byte-count
// header and the data of an uncompressed inline array as one continuous base64 stream, so the
// encoder carries the bytes of an incomplete group from one chunk to the next and pads only
// at the very end.
class Base64Stream {
public:
  explicit Base64Stream(std::string& out) : out_(out) {}

  void put(std::span<const std::byte> bytes) {
    std::size_t i = 0;
    while (n_pending_ > 0 && n_pending_ < 3 && i < bytes.size())
      pending_[n_pending_++] = bytes[i++];
    if (n_pending_ == 3) {
      emit_group(pending_[0], pending_[1], pending_[2]);
      n_pending_ = 0;
    }
    for (; i + 3 <= bytes.size(); i += 3) emit_group(bytes[i], bytes[i + 1], bytes[i + 2]);
    for (; i < bytes.size(); ++i) pending_[n_pending_++] = bytes[i];
  }

  void finish() {
    if (n_pending_ == 0) return;
    const auto b0 = std::to_integer<unsigned>(pending_[0]);
    const auto b1 = n_pending_ > 1 ? std::to_integer<unsigned>(pending_[1]) : 0u;
    const unsigned group = (b0 << 16) | (b1 << 8);
    out_ += base64_alphabet[(group >> 18) & 63];
    out_ += base64_alphabet[(group >> 12) & 63];
    out_ += n_pending_ > 1 ? base64_alphabet[(group >> 6) & 63] : '=';
    out_ += '=';
    n_pending_ = 0;
  }

private:
  void emit_group(std::byte a, std::byte b, std::byte c) {
    const unsigned group = (std::to_integer<unsigned>(a) << 16) |
                           (std::to_integer<unsigned>(b) << 8) | std::to_integer<unsigned>(c);
    const std::array<char, 4> chars{
        base64_alphabet[(group >> 18) & 63], base64_alphabet[(group >> 12) & 63],
        base64_alphabet[(group >> 6) & 63], base64_alphabet[group & 63]};
    out_.append(chars.data(), chars.size());
  }

  std::string& out_;
  std::array<std::byte, 3> pending_{};
  int n_pending_ = 0;
};

// Shortest decimal form that reads back to the same double (std::to_chars guarantees the
// round trip), so ASCII output and XML attributes are as exact as the binary form.
template <class T> void append_number(std::string& out, T value) {
  std::array<char, 32> buf{};
  const auto result = std::to_chars(buf.data(), buf.data() + buf.size(), value);
  SEAM_ASSERT(result.ec == std::errc());
  out.append(buf.data(), result.ptr);
}

void append_xml_escaped(std::string& out, std::string_view text) {
  for (const char c : text) {
    switch (c) {
    case '&':
      out += "&amp;";
      break;
    case '<':
      out += "&lt;";
      break;
    case '>':
      out += "&gt;";
      break;
    case '"':
      out += "&quot;";
      break;
    case '\'':
      out += "&apos;";
      break;
    default:
      out += c;
    }
  }
}

template <class T> constexpr std::string_view vtk_type_name() {
  if constexpr (std::is_same_v<T, double>)
    return "Float64";
  else if constexpr (std::is_same_v<T, std::int32_t>)
    return "Int32";
  else if constexpr (std::is_same_v<T, std::int64_t>)
    return "Int64";
  else if constexpr (std::is_same_v<T, std::uint8_t>)
    return "UInt8";
}

constexpr std::string_view byte_order =
    std::endian::native == std::endian::little ? "LittleEndian" : "BigEndian";

struct ArrayAttributes {
  std::string_view name;
  int n_components = 1;
  std::optional<std::size_t> n_tuples; // FieldData arrays only
};

void append_array_open_tag(std::string& out, std::string_view element, std::string_view type,
                           const ArrayAttributes& attrs) {
  out += '<';
  out += element;
  out += " type=\"";
  out += type;
  out += "\" Name=\"";
  append_xml_escaped(out, attrs.name);
  out += '"';
  if (attrs.n_components != 1) {
    out += " NumberOfComponents=\"";
    append_number(out, attrs.n_components);
    out += '"';
  }
  if (attrs.n_tuples) {
    out += " NumberOfTuples=\"";
    append_number(out, *attrs.n_tuples);
    out += '"';
  }
}

template <class T>
void append_data_array(std::string& out, std::string_view indent, const ArrayAttributes& attrs,
                       std::span<const T> values, VtkFormat format) {
  out += indent;
  append_array_open_tag(out, "DataArray", vtk_type_name<T>(), attrs);
  out += format == VtkFormat::binary ? " format=\"binary\">\n" : " format=\"ascii\">\n";
  out += indent;
  out += "  ";
  if (format == VtkFormat::binary) {
    // Uncompressed inline data: a UInt64 byte count, then the raw values (header_type="UInt64").
    const std::uint64_t n_bytes = values.size_bytes();
    Base64Stream stream(out);
    stream.put(std::as_bytes(std::span(&n_bytes, 1)));
    stream.put(std::as_bytes(values));
    stream.finish();
  } else {
    const std::size_t per_line = attrs.n_components > 1 ? std::size_t(attrs.n_components) : 8;
    for (std::size_t i = 0; i < values.size(); ++i) {
      if (i > 0) {
        if (i % per_line == 0) {
          out += '\n';
          out += indent;
          out += "  ";
        } else {
          out += ' ';
        }
      }
      if constexpr (std::is_same_v<T, std::uint8_t>)
        append_number(out, int(values[i]));
      else
        append_number(out, values[i]);
    }
  }
  out += '\n';
  out += indent;
  out += "</DataArray>\n";
}

void append_field(std::string& out, std::string_view indent, const DataField& field,
                  VtkFormat format) {
  const ArrayAttributes attrs{field.name, field.n_components, std::nullopt};
  std::visit([&](auto values) { append_data_array(out, indent, attrs, values, format); },
             field.values);
}

void append_header(std::string& out, std::string_view type) {
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"";
  out += type;
  out += "\" version=\"1.0\" byte_order=\"";
  out += byte_order;
  out += "\" header_type=\"UInt64\">\n";
}

void append_time_field_data(std::string& out, std::string_view indent, const VtuPiece& piece,
                            VtkFormat format) {
  if (!piece.time && !piece.cycle) return;
  out += indent;
  out += "<FieldData>\n";
  const std::string inner = std::string(indent) + "  ";
  if (piece.time) {
    const double t = *piece.time;
    append_data_array(out, inner, {"TimeValue", 1, 1}, std::span(&t, 1), format);
  }
  if (piece.cycle) {
    const std::int64_t c = *piece.cycle;
    append_data_array(out, inner, {"CYCLE", 1, 1}, std::span(&c, 1), format);
  }
  out += indent;
  out += "</FieldData>\n";
}

void check_field_declarations(std::span<const DataField> fields, std::string_view where) {
  std::set<std::string_view> names;
  for (const auto& f : fields) {
    SEAM_CHECK(!f.name.empty(), InternalError, "VTU output: a ", where, " field has no name");
    SEAM_CHECK(f.n_components >= 1, InternalError, "VTU output: ", where, " field '", f.name,
               "' has ", f.n_components, " components");
    SEAM_CHECK(names.insert(f.name).second, InternalError, "VTU output: two ", where,
               " fields are named '", f.name, "'");
  }
}

void check_piece(const VtuPiece& p) {
  SEAM_CHECK(p.point_dim >= 1 && p.point_dim <= 3, InternalError,
             "VTU output: point_dim must be 1, 2 or 3, not ", p.point_dim);
  SEAM_CHECK(p.points.size() % std::size_t(p.point_dim) == 0, InternalError,
             "VTU output: ", p.points.size(), " coordinates are not a multiple of point_dim ",
             p.point_dim);
  SEAM_CHECK(p.offsets.size() == p.types.size(), InternalError, "VTU output: ", p.offsets.size(),
             " offsets for ", p.types.size(), " cell types");
  std::int64_t previous = 0;
  for (const auto offset : p.offsets) {
    SEAM_CHECK(offset >= previous, InternalError,
               "VTU output: cell offsets must be non-decreasing end positions");
    previous = offset;
  }
  SEAM_CHECK(std::size_t(previous) == p.connectivity.size(), InternalError,
             "VTU output: the last offset (", previous, ") must equal the connectivity size (",
             p.connectivity.size(), ")");
  const auto n_points = std::int64_t(p.n_points());
  for (const auto node : p.connectivity)
    SEAM_CHECK(node >= 0 && node < n_points, InternalError, "VTU output: connectivity entry ", node,
               " is not a point of this piece (", n_points, " points)");

  check_field_declarations(p.point_data, "point");
  check_field_declarations(p.cell_data, "cell");
  for (const auto& f : p.point_data)
    SEAM_CHECK(f.size() == p.n_points() * std::size_t(f.n_components), InternalError,
               "VTU output: point field '", f.name, "' has ", f.size(), " values, expected ",
               p.n_points(), " x ", f.n_components);
  for (const auto& f : p.cell_data)
    SEAM_CHECK(f.size() == p.n_cells() * std::size_t(f.n_components), InternalError,
               "VTU output: cell field '", f.name, "' has ", f.size(), " values, expected ",
               p.n_cells(), " x ", f.n_components);
}

std::string vtu_document(const VtuPiece& p, VtkFormat format) {
  // Binary size, 4/3 for base64, plus the XML around it: one allocation for most files.
  std::size_t n_bytes = 24 * p.n_points() + 4 * p.connectivity.size() + 5 * p.n_cells();
  for (const auto& f : p.point_data) n_bytes += 8 * f.size();
  for (const auto& f : p.cell_data) n_bytes += 8 * f.size();
  std::string out;
  out.reserve(n_bytes / 3 * 4 + 4096);
  append_header(out, "UnstructuredGrid");
  out += "  <UnstructuredGrid>\n";
  append_time_field_data(out, "    ", p, format);
  out += "    <Piece NumberOfPoints=\"";
  append_number(out, p.n_points());
  out += "\" NumberOfCells=\"";
  append_number(out, p.n_cells());
  out += "\">\n";

  out += "      <PointData>\n";
  for (const auto& f : p.point_data) append_field(out, "        ", f, format);
  out += "      </PointData>\n      <CellData>\n";
  for (const auto& f : p.cell_data) append_field(out, "        ", f, format);
  out += "      </CellData>\n";

  // VTK points always have three coordinates; lower-dimensional meshes lie in z = 0 (y = 0).
  out += "      <Points>\n";
  std::vector<double> xyz;
  std::span<const double> coordinates = p.points;
  if (p.point_dim != 3) {
    xyz.assign(3 * p.n_points(), 0.0);
    for (std::size_t i = 0; i < p.n_points(); ++i)
      for (int a = 0; a < p.point_dim; ++a) xyz[3 * i + a] = p.points[i * p.point_dim + a];
    coordinates = xyz;
  }
  append_data_array(out, "        ", {"Points", 3, std::nullopt}, coordinates, format);
  out += "      </Points>\n      <Cells>\n";
  append_data_array(out, "        ", {"connectivity", 1, std::nullopt}, p.connectivity, format);
  append_data_array(out, "        ", {"offsets", 1, std::nullopt}, p.offsets, format);
  append_data_array(out, "        ", {"types", 1, std::nullopt}, p.types, format);
  out += "      </Cells>\n    </Piece>\n  </UnstructuredGrid>\n</VTKFile>\n";
  return out;
}

template <class T> void append_pdata_array(std::string& out, const ArrayAttributes& attrs) {
  out += "      ";
  append_array_open_tag(out, "PDataArray", vtk_type_name<T>(), attrs);
  out += "/>\n";
}

void append_pfields(std::string& out, std::span<const DataField> fields) {
  for (const auto& f : fields) {
    const ArrayAttributes attrs{f.name, f.n_components, std::nullopt};
    if (f.is_integer())
      append_pdata_array<std::int32_t>(out, attrs);
    else
      append_pdata_array<double>(out, attrs);
  }
}

std::string pvd_document(std::span<const PvdCollection::Entry> entries) {
  std::string out;
  out += "<?xml version=\"1.0\"?>\n<VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"";
  out += byte_order;
  out += "\">\n  <Collection>\n";
  for (const auto& e : entries) {
    out += "    <DataSet timestep=\"";
    append_number(out, e.time);
    out += "\" group=\"\" part=\"0\" file=\"";
    append_xml_escaped(out, e.file);
    out += "\"/>\n";
  }
  out += "  </Collection>\n</VTKFile>\n";
  return out;
}

} // namespace

std::size_t DataField::size() const {
  return std::visit([](auto v) { return v.size(); }, values);
}

std::size_t VtuPiece::n_points() const {
  return point_dim > 0 ? points.size() / std::size_t(point_dim) : 0;
}

std::string base64_encode(std::span<const std::byte> bytes) {
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  Base64Stream stream(out);
  stream.put(bytes);
  stream.finish();
  return out;
}

void write_file_atomically(const std::filesystem::path& file, std::string_view contents) {
  std::filesystem::path tmp = file;
  tmp += ".tmp";
  std::FILE* f = std::fopen(tmp.c_str(), "wb");
  SEAM_CHECK(f != nullptr, InputError, "cannot write ", file, ": ", std::strerror(errno));
  int error = 0;
  if (std::fwrite(contents.data(), 1, contents.size(), f) != contents.size())
    error = errno != 0 ? errno : EIO;
  if (std::fclose(f) != 0 && error == 0) error = errno != 0 ? errno : EIO;
  if (error != 0) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    SEAM_THROW(InputError, "cannot write ", file, ": ", std::strerror(error));
  }
  std::error_code ec;
  std::filesystem::rename(tmp, file, ec);
  if (ec) {
    std::error_code ignored;
    std::filesystem::remove(tmp, ignored);
    SEAM_THROW(InputError, "cannot write ", file, ": ", ec.message());
  }
}

void write_vtu(const std::filesystem::path& file, const VtuPiece& piece, VtkFormat format) {
  check_piece(piece);
  write_file_atomically(file, vtu_document(piece, format));
}

void write_pvtu(const std::filesystem::path& file, const VtuPiece& layout,
                std::span<const std::string> piece_files) {
  check_field_declarations(layout.point_data, "point");
  check_field_declarations(layout.cell_data, "cell");
  SEAM_CHECK(!piece_files.empty(), InternalError, "PVTU output: no pieces for ", file);

  std::string out;
  append_header(out, "PUnstructuredGrid");
  out += "  <PUnstructuredGrid GhostLevel=\"0\">\n";
  // ASCII: a single value each, and readers take the time from here without opening a piece.
  append_time_field_data(out, "    ", layout, VtkFormat::ascii);
  out += "    <PPointData>\n";
  append_pfields(out, layout.point_data);
  out += "    </PPointData>\n    <PCellData>\n";
  append_pfields(out, layout.cell_data);
  out += "    </PCellData>\n    <PPoints>\n";
  append_pdata_array<double>(out, {"Points", 3, std::nullopt});
  out += "    </PPoints>\n";
  for (const auto& piece : piece_files) {
    out += "    <Piece Source=\"";
    append_xml_escaped(out, piece);
    out += "\"/>\n";
  }
  out += "  </PUnstructuredGrid>\n</VTKFile>\n";
  write_file_atomically(file, out);
}

std::string step_file_name(std::string_view stem, std::int64_t step, std::string_view extension) {
  SEAM_CHECK(step >= 0, InternalError, "output file name for negative step ", step);
  std::string digits;
  append_number(digits, step);
  std::string name(stem);
  name += '_';
  if (digits.size() < 5) name.append(5 - digits.size(), '0');
  name += digits;
  name += extension;
  return name;
}

std::string piece_file_name(std::string_view stem, std::int64_t step, int rank) {
  std::string name = step_file_name(stem, step, "");
  name += "_p";
  append_number(name, rank);
  name += ".vtu";
  return name;
}

PvdCollection::PvdCollection(std::filesystem::path file) : file_(std::move(file)) {
  write();
}

PvdCollection::PvdCollection(std::filesystem::path file, std::vector<Entry> entries)
    : file_(std::move(file)), entries_(std::move(entries)) {
  write();
}

void PvdCollection::add(double time, std::string file) {
  entries_.push_back({time, std::move(file)});
  write();
}

void PvdCollection::write() const {
  write_file_atomically(file_, pvd_document(entries_));
}

} // namespace seam::io
