#include "seam/mesh/gmsh_reader.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/cell_geometry.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/mesh/msh_check.hpp"

#include <gmsh.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <clocale>
#include <cmath>
#include <fstream>
#include <map>
#include <mutex>
#include <string>
#include <unordered_map>
#include <utility>
#include <vector>

namespace seam::mesh {
namespace {

std::mutex& gmsh_mutex() {
  static std::mutex m;
  return m;
}

// One Gmsh session per read. Gmsh keeps options in a global context that gmsh::clear() does
// not reset, so a .geo setting e.g. Mesh.RecombineAll would otherwise change every later read;
// finalize + initialize restores the defaults. AbortOnError = 0 makes Gmsh log errors instead
// of throwing out of its parser (which leaves the parser unusable) or exiting; Terminal = 0
// keeps it silent. Errors are collected through the logger after each step.
class GmshSession {
public:
  explicit GmshSession(std::string file) : file_(std::move(file)) {
    // Gmsh 4.8 honours -noenv (do not append to PATH and PYTHONPATH on every initialize) only
    // as argv[0]; it sets the C locale, which is what it needs while reading, and the caller's
    // locale comes back in the destructor.
    if (const char* locale = std::setlocale(LC_ALL, nullptr)) saved_locale_ = locale;
    std::array<char*, 1> argv{noenv_.data()};
    gmsh::initialize(static_cast<int>(argv.size()), argv.data(), false);
    gmsh::option::setNumber("General.Terminal", 0);
    gmsh::option::setNumber("General.AbortOnError", 0);
    gmsh::option::setNumber("General.Verbosity", 1); // log errors only
    gmsh::logger::start();
  }
  ~GmshSession() {
    try {
      gmsh::logger::stop();
      gmsh::finalize();
    } catch (...) { // a destructor must not throw; nothing more to clean up
    }
    if (!saved_locale_.empty()) std::setlocale(LC_ALL, saved_locale_.c_str());
  }
  GmshSession(const GmshSession&) = delete;
  GmshSession& operator=(const GmshSession&) = delete;

  const std::string& file() const { return file_; }

  // Run one Gmsh step; anything Gmsh reported as an error becomes an InputError naming the file.
  template <class F> void run(std::string_view doing, F&& step) {
    std::string thrown;
    try {
      step();
    } catch (const std::string& s) {
      thrown = s;
    } catch (const std::exception& e) {
      thrown = e.what();
    } catch (...) {
      thrown = "unknown Gmsh failure";
    }
    std::vector<std::string> log;
    gmsh::logger::get(log);
    std::string errors;
    for (std::size_t i = n_seen_; i < log.size(); ++i) {
      std::string_view line = log[i];
      if (!line.starts_with("Error")) continue;
      line.remove_prefix(std::min(line.size(), line.find(':') + 1));
      while (!line.empty() && line.front() == ' ') line.remove_prefix(1);
      errors += (errors.empty() ? "" : "; ") + std::string(line);
    }
    n_seen_ = log.size();
    if (errors.empty()) errors = thrown;
    if (!errors.empty()) SEAM_THROW(InputError, "mesh '", file_, "': ", doing, ": ", errors);
  }

private:
  std::string noenv_ = "-noenv";
  std::string saved_locale_;
  std::string file_;
  std::size_t n_seen_ = 0;
};

// Gmsh tag -> index. Gmsh numbers nodes and elements densely in practice, so a flat table is
// the common case; sparse numberings (hand-written or merged files) fall back to a hash map.
class TagMap {
public:
  explicit TagMap(std::span<const std::size_t> tags) {
    std::size_t max_tag = 0;
    for (auto t : tags) max_tag = std::max(max_tag, t);
    dense_mode_ = max_tag <= 4 * tags.size() + 1024;
    if (dense_mode_) {
      dense_.assign(max_tag + 1, -1);
      for (std::size_t i = 0; i < tags.size(); ++i) dense_[tags[i]] = static_cast<std::int32_t>(i);
    } else {
      sparse_.reserve(tags.size());
      for (std::size_t i = 0; i < tags.size(); ++i)
        sparse_.emplace(tags[i], static_cast<std::int32_t>(i));
    }
  }
  std::int32_t find(std::size_t tag) const {
    if (dense_mode_) return tag < dense_.size() ? dense_[tag] : -1;
    const auto it = sparse_.find(tag);
    return it == sparse_.end() ? -1 : it->second;
  }

private:
  bool dense_mode_ = true;
  std::vector<std::int32_t> dense_;
  std::unordered_map<std::size_t, std::int32_t> sparse_;
};

struct Elements {
  std::vector<int> types;
  std::vector<std::vector<std::size_t>> tags;
  std::vector<std::vector<std::size_t>> nodes;
};

Elements get_elements(GmshSession& g, int dim, int tag) {
  Elements e;
  g.run("reading elements",
        [&] { gmsh::model::mesh::getElements(e.types, e.tags, e.nodes, dim, tag); });
  return e;
}

int gmsh_type_dimension(GmshSession& g, int type) {
  std::string name;
  int dim = 0, order = 0, n_nodes = 0, n_primary = 0;
  std::vector<double> local;
  g.run("reading element properties", [&] {
    gmsh::model::mesh::getElementProperties(type, name, dim, order, n_nodes, local, n_primary);
  });
  return dim;
}

fem::CellType convert_type(const GmshSession& g, int gmsh_type, std::string_view where) {
  try {
    return fem::from_gmsh(gmsh_type);
  } catch (const InputError& e) {
    SEAM_THROW(InputError, "mesh '", g.file(), "'", where, ": ", e.what());
  }
}

std::string lower_extension(const std::filesystem::path& file) {
  std::string ext = file.extension().string();
  for (auto& ch : ext) ch = static_cast<char>(std::tolower(static_cast<unsigned char>(ch)));
  return ext;
}

bool is_geometry_extension(std::string_view ext) {
  static constexpr std::array<std::string_view, 7> geometry{
      ".geo", ".geo_unrolled", ".step", ".stp", ".brep", ".iges", ".igs"};
  return std::find(geometry.begin(), geometry.end(), ext) != geometry.end();
}

void check_options(const std::string& file, const ReadOptions& options) {
  SEAM_CHECK(options.order >= 0 && options.order <= 2, InputError, "mesh '", file,
             "': element order must be 1 or 2, not ", options.order);
  SEAM_CHECK(options.dim == 0 || options.dim == 2 || options.dim == 3, InputError, "mesh '", file,
             "': dimension must be 2 or 3, not ", options.dim);
  SEAM_CHECK(!options.size || (std::isfinite(*options.size) && *options.size > 0), InputError,
             "mesh '", file, "': mesh size must be positive");
}

void check_file(const std::filesystem::path& path, const std::string& file) {
  std::error_code ec;
  SEAM_CHECK(std::filesystem::exists(path, ec), InputError, "mesh file '", file,
             "' does not exist");
  SEAM_CHECK(std::filesystem::is_regular_file(path, ec), InputError, "mesh file '", file,
             "' is not a regular file");
  SEAM_CHECK(std::ifstream(path).good(), InputError, "mesh file '", file, "' cannot be opened");
}

// What the element kernels cannot integrate: a node with a non-finite coordinate, or a cell
// whose reference map folds over or collapses (det dX/dxi <= 0 at a point of the kernels'
// quadrature rule: misordered, coincident or misplaced nodes). Such a cell would otherwise end
// the run as an inverted element after all its step cuts.
void check_geometry(const GmshSession& g, const Mesh& mesh, std::span<const std::size_t> node_tags,
                    std::span<const std::size_t> cell_tags) {
  const auto dim = static_cast<std::size_t>(mesh.dim);
  for (std::size_t i = 0; i < mesh.x.size(); ++i)
    SEAM_CHECK(std::isfinite(mesh.x[i]), InputError, "mesh '", g.file(), "': node ",
               node_tags[i / dim], " has a coordinate that is not a finite number");
  std::array<double, 9> J{};
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto type = mesh.cell_type[c];
    const auto rule = fem::quadrature(type, fem::default_quadrature_degree(type));
    for (int q = 0; q < rule.n_points; ++q) {
      const double det = jacobian(mesh, c, &rule.points[q * rule.dim], J);
      SEAM_CHECK(det > 0.0, InputError, "mesh '", g.file(), "': element ",
                 cell_tags[static_cast<std::size_t>(c)], " (", fem::name(type),
                 ") is inverted or degenerate: det(dX/dxi) = ", det,
                 " <= 0 inside it (misordered, coincident or misplaced nodes)");
    }
  }
}

// Cells: the elements of the top dimension, ordered by element tag so that the result does not
// depend on how the file groups elements (by entity in .msh 4, by type elsewhere).
struct CellRecord {
  std::size_t tag;
  fem::CellType type;
  const std::size_t* nodes;
};

std::vector<CellRecord> collect_cells(GmshSession& g, const Elements& all, int top,
                                      std::span<const int> type_dims) {
  std::vector<CellRecord> cells;
  for (std::size_t i = 0; i < all.types.size(); ++i) {
    if (type_dims[i] != top) continue;
    const auto type = convert_type(g, all.types[i], "");
    const auto n = static_cast<std::size_t>(fem::n_nodes(type));
    SEAM_ASSERT(all.nodes[i].size() == n * all.tags[i].size());
    for (std::size_t e = 0; e < all.tags[i].size(); ++e)
      cells.push_back({all.tags[i][e], type, all.nodes[i].data() + e * n});
  }
  std::sort(cells.begin(), cells.end(),
            [](const CellRecord& a, const CellRecord& b) { return a.tag < b.tag; });
  return cells;
}

// Nodes: the ones cells use, in increasing node tag; fills x and cell connectivity.
std::vector<std::size_t> build_nodes_and_cells(GmshSession& g, std::span<const CellRecord> cells,
                                               Mesh& mesh) {
  std::vector<std::size_t> used;
  for (const auto& c : cells) used.insert(used.end(), c.nodes, c.nodes + fem::n_nodes(c.type));
  std::sort(used.begin(), used.end());
  used.erase(std::unique(used.begin(), used.end()), used.end());

  std::vector<std::size_t> node_tags;
  std::vector<double> coords, parametric;
  g.run("reading nodes",
        [&] { gmsh::model::mesh::getNodes(node_tags, coords, parametric, -1, -1, false, false); });
  const TagMap gmsh_node(node_tags);
  const int dim = mesh.dim;
  mesh.x.resize(used.size() * static_cast<std::size_t>(dim));
  double extent = 0, max_z = 0;
  for (std::size_t i = 0; i < used.size(); ++i) {
    const auto k = gmsh_node.find(used[i]);
    SEAM_CHECK(k >= 0, InputError, "mesh '", g.file(), "': node ", used[i],
               " is used by an element but not defined");
    const double* p = coords.data() + 3 * static_cast<std::size_t>(k);
    for (int a = 0; a < dim; ++a) {
      mesh.x[i * static_cast<std::size_t>(dim) + static_cast<std::size_t>(a)] = p[a];
      extent = std::max(extent, std::abs(p[a]));
    }
    max_z = std::max(max_z, std::abs(p[2]));
  }
  // A 2D analysis is in the x-y plane; a surface mesh elsewhere in space is not a 2D mesh.
  SEAM_CHECK(dim == 3 || max_z <= 1e-12 * std::max(extent, 1.0), InputError, "mesh '", g.file(),
             "': a 2D mesh must lie in the plane z = 0, but a node has |z| = ", max_z);

  const TagMap mesh_node(used);
  std::array<std::int32_t, fem::max_cell_nodes> local{};
  for (const auto& c : cells) {
    const int n = fem::n_nodes(c.type);
    for (int i = 0; i < n; ++i) local[i] = mesh_node.find(c.nodes[i]);
    mesh.add_cell(c.type, std::span<const std::int32_t>(local.data(), static_cast<std::size_t>(n)));
  }
  return used;
}

void sort_unique(std::vector<std::int32_t>& v) {
  std::sort(v.begin(), v.end());
  v.erase(std::unique(v.begin(), v.end()), v.end());
}

struct RegionContext {
  GmshSession& g;
  const Mesh& mesh;
  const TagMap& mesh_node;                // Gmsh node tag -> mesh node
  std::span<const std::size_t> cell_tags; // sorted Gmsh element tags of the cells
  const FacetIndex& facets;
};

std::int32_t region_node(const RegionContext& ctx, const Region& r, std::size_t tag) {
  const auto n = ctx.mesh_node.find(tag);
  SEAM_CHECK(n >= 0, InputError, "mesh '", ctx.g.file(), "': region '", r.name, "' has node ", tag,
             ", which belongs to no cell of dimension ", ctx.mesh.dim);
  return n;
}

void add_cells(const RegionContext& ctx, const Elements& e, Region& r) {
  for (const auto& tags : e.tags)
    for (auto tag : tags) {
      const auto it = std::lower_bound(ctx.cell_tags.begin(), ctx.cell_tags.end(), tag);
      SEAM_ASSERT(it != ctx.cell_tags.end() && *it == tag);
      const auto c = static_cast<std::int32_t>(it - ctx.cell_tags.begin());
      r.cells.push_back(c);
      for (auto n : ctx.mesh.cell(c)) r.nodes.push_back(n);
    }
}

void add_facets(const RegionContext& ctx, const Elements& e, Region& r) {
  std::array<std::int32_t, 4> corners{};
  for (std::size_t i = 0; i < e.types.size(); ++i) {
    const auto type = convert_type(ctx.g, e.types[i], ", region '" + r.name + "'");
    const auto n_nodes = static_cast<std::size_t>(fem::n_nodes(type));
    const int n_corners = fem::n_vertices(type);
    for (std::size_t k = 0; k < e.tags[i].size(); ++k) {
      const std::size_t* nodes = e.nodes[i].data() + k * n_nodes;
      for (int a = 0; a < n_corners; ++a) corners[a] = region_node(ctx, r, nodes[a]);
      const auto* entry = ctx.facets.find(
          std::span<const std::int32_t>(corners.data(), static_cast<std::size_t>(n_corners)));
      SEAM_CHECK(entry != nullptr, InputError, "mesh '", ctx.g.file(), "': element ", e.tags[i][k],
                 " of boundary region '", r.name, "' is not a facet of any cell of dimension ",
                 ctx.mesh.dim);
      r.facet_cell.push_back(entry->cells[0].cell);
      r.facet_local.push_back(entry->cells[0].local);
    }
  }
}

// Once all entities are in: sort the (cell, local) pairs, drop duplicates (the same facet in
// two entities of the group) and collect the facets' nodes, high-order ones included.
void finish_facets(const RegionContext& ctx, Region& r) {
  r.sort_facets();
  for (std::size_t k = 0; k < r.facet_cell.size(); ++k) {
    const auto cell_nodes = ctx.mesh.cell(r.facet_cell[k]);
    const auto type = ctx.mesh.cell_type[r.facet_cell[k]];
    for (auto a : fem::facet_nodes(type, r.facet_local[k])) r.nodes.push_back(cell_nodes[a]);
  }
}

void add_nodes(const RegionContext& ctx, const Elements& e, Region& r) {
  for (const auto& nodes : e.nodes)
    for (auto tag : nodes) r.nodes.push_back(region_node(ctx, r, tag));
}

std::vector<Region> read_regions(const RegionContext& ctx) {
  gmsh::vectorpair groups;
  ctx.g.run("reading physical groups", [&] { gmsh::model::getPhysicalGroups(groups); });
  std::sort(groups.begin(), groups.end());
  std::vector<Region> regions;
  std::map<std::pair<int, std::string>, int> seen;
  for (const auto& [dim, tag] : groups) {
    Region r;
    r.dim = dim;
    r.tag = tag;
    ctx.g.run("reading physical names", [&] { gmsh::model::getPhysicalName(dim, tag, r.name); });
    if (r.name.empty()) r.name = std::to_string(dim) + ":" + std::to_string(tag);
    const auto [it, inserted] = seen.emplace(std::make_pair(dim, r.name), tag);
    SEAM_CHECK(inserted, InputError, "mesh '", ctx.g.file(), "': physical groups ", it->second,
               " and ", tag, " of dimension ", dim, " are both named '", r.name, "'");
    std::vector<int> entities;
    ctx.g.run("reading physical groups",
              [&] { gmsh::model::getEntitiesForPhysicalGroup(dim, tag, entities); });
    for (int entity : entities) {
      const auto elements = get_elements(ctx.g, dim, entity);
      if (dim == ctx.mesh.dim)
        add_cells(ctx, elements, r);
      else if (dim == ctx.mesh.dim - 1)
        add_facets(ctx, elements, r);
      else
        add_nodes(ctx, elements, r);
    }
    if (dim == ctx.mesh.dim - 1) finish_facets(ctx, r);
    sort_unique(r.cells);
    sort_unique(r.nodes);
    regions.push_back(std::move(r));
  }
  return regions;
}

Mesh extract_mesh(GmshSession& g, const ReadOptions& options) {
  const auto all = get_elements(g, -1, -1);
  std::vector<int> type_dims(all.types.size());
  int top = -1;
  for (std::size_t i = 0; i < all.types.size(); ++i) {
    type_dims[i] = gmsh_type_dimension(g, all.types[i]);
    if (!all.tags[i].empty()) top = std::max(top, type_dims[i]);
  }
  SEAM_CHECK(top >= 2, InputError, "mesh '", g.file(), "': no elements of dimension 2 or 3",
             top < 0 ? std::string(" (no elements at all)")
                     : " (highest element dimension is " + std::to_string(top) + ")");
  SEAM_CHECK(options.dim == 0 || options.dim == top, InputError, "mesh '", g.file(),
             "': the mesh has dimension ", top, " but dimension ", options.dim, " was asked for");

  Mesh mesh;
  mesh.dim = top;
  const auto cells = collect_cells(g, all, top, type_dims);
  const auto used = build_nodes_and_cells(g, cells, mesh);
  std::vector<std::size_t> cell_tags(cells.size());
  for (std::size_t c = 0; c < cells.size(); ++c) cell_tags[c] = cells[c].tag;
  SEAM_CHECK(std::adjacent_find(cell_tags.begin(), cell_tags.end()) == cell_tags.end(), InputError,
             "mesh '", g.file(), "': two elements share a tag");
  check_geometry(g, mesh, used, cell_tags);

  const TagMap mesh_node(used);
  const FacetIndex facets(mesh);
  mesh.regions = read_regions({g, mesh, mesh_node, cell_tags, facets});
  return mesh;
}

} // namespace

namespace {

// Opens `path` in the session; geometry files are meshed with the caller's options.
bool open_and_mesh(GmshSession& g, const std::filesystem::path& path, const ReadOptions& options) {
  const std::string& file = g.file();
  const auto ext = lower_extension(path);
  const bool geometry = is_geometry_extension(ext);
  g.run("reading", [&] { gmsh::open(file); });
  if (geometry) {
    // Options given by the caller override what the geometry file sets, hence after open().
    g.run("setting mesh options", [&] {
      if (options.size) gmsh::option::setNumber("Mesh.MeshSizeMax", *options.size);
      if (options.order > 0) gmsh::option::setNumber("Mesh.ElementOrder", options.order);
      if (options.serendipity) gmsh::option::setNumber("Mesh.SecondOrderIncomplete", 1);
    });
    g.run("meshing", [&] { gmsh::model::mesh::generate(gmsh::model::getDimension()); });
  }
  return geometry;
}

void check_input(const std::filesystem::path& path, const ReadOptions& options) {
  const std::string file = path.string();
  check_options(file, options);
  check_file(path, file);
  const auto ext = lower_extension(path);
  SEAM_CHECK(is_geometry_extension(ext) || ext == ".msh", InputError, "mesh '", file,
             "': unknown extension '", ext, "' (expected .msh, or a geometry file such as .geo)");
  if (!is_geometry_extension(ext)) detail::check_msh_structure(path, file);
}

} // namespace

Mesh read_mesh(const std::filesystem::path& path, const ReadOptions& options) {
  check_input(path, options);
  const std::lock_guard lock(gmsh_mutex());
  GmshSession g(path.string());
  open_and_mesh(g, path, options);
  return extract_mesh(g, options);
}

void mesh_to_msh(const std::filesystem::path& geometry, const ReadOptions& options,
                 const std::filesystem::path& msh) {
  check_input(geometry, options);
  SEAM_CHECK(is_geometry_extension(lower_extension(geometry)), InputError, "mesh '",
             geometry.string(), "': not a geometry file");
  const std::lock_guard lock(gmsh_mutex());
  GmshSession g(geometry.string());
  open_and_mesh(g, geometry, options);
  g.run("writing " + msh.string(), [&] {
    gmsh::option::setNumber("Mesh.MshFileVersion", 4.1);
    gmsh::option::setNumber("Mesh.Binary", 1);
    // Every element, as read_mesh takes the cells of entities outside physical groups too.
    gmsh::option::setNumber("Mesh.SaveAll", 1);
    gmsh::write(msh.string());
  });
}

} // namespace seam::mesh
