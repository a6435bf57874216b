#include "seam/mesh/mesh.hpp"

#include "seam/common/error.hpp"

#include <algorithm>
#include <tuple>

namespace seam::mesh {

void Mesh::add_cell(fem::CellType type, std::span<const std::int32_t> nodes) {
  SEAM_ASSERT(static_cast<int>(nodes.size()) == fem::n_nodes(type));
  cell_type.push_back(type);
  cell_nodes.insert(cell_nodes.end(), nodes.begin(), nodes.end());
  cell_offsets.push_back(static_cast<std::int64_t>(cell_nodes.size()));
}

void Region::sort_facets() {
  std::vector<std::pair<std::int32_t, std::int8_t>> pairs(facet_cell.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) pairs[k] = {facet_cell[k], facet_local[k]};
  std::sort(pairs.begin(), pairs.end());
  pairs.erase(std::unique(pairs.begin(), pairs.end()), pairs.end());
  facet_cell.resize(pairs.size());
  facet_local.resize(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) std::tie(facet_cell[k], facet_local[k]) = pairs[k];
}

const Region* Mesh::find_region(std::string_view name, int region_dim) const {
  for (const auto& r : regions)
    if (r.name == name && (region_dim < 0 || r.dim == region_dim)) return &r;
  return nullptr;
}

const Region& Mesh::region(std::string_view name, int region_dim) const {
  if (const auto* r = find_region(name, region_dim)) return *r;
  std::string known;
  for (const auto& r : regions)
    known += (known.empty() ? "" : ", ") + r.name + " (dim " + std::to_string(r.dim) + ")";
  SEAM_THROW(InputError, "the mesh has no region '", name, "'",
             region_dim >= 0 ? " of dimension " + std::to_string(region_dim) : std::string(),
             "; its regions are: ", known.empty() ? "none" : known);
}

void Mesh::check() const {
  SEAM_CHECK(dim == 2 || dim == 3, InternalError, "mesh dimension ", dim, " is not 2 or 3");
  SEAM_CHECK(x.size() % static_cast<std::size_t>(dim) == 0, InternalError,
             "mesh coordinate array size ", x.size(), " is not a multiple of ", dim);
  const auto n_c = static_cast<std::size_t>(n_cells());
  SEAM_CHECK(cell_offsets.size() == n_c + 1 && cell_offsets.front() == 0 &&
                 cell_offsets.back() == static_cast<std::int64_t>(cell_nodes.size()),
             InternalError, "mesh cell offsets are inconsistent with ", n_c, " cells");
  const std::int32_t n_n = n_nodes();
  for (std::size_t c = 0; c < n_c; ++c) {
    const auto t = cell_type[c];
    SEAM_CHECK(fem::dimension(t) == dim, InternalError, "cell ", c, " (", fem::name(t),
               ") has not the mesh dimension ", dim);
    SEAM_CHECK(cell_offsets[c + 1] - cell_offsets[c] == fem::n_nodes(t), InternalError, "cell ", c,
               " (", fem::name(t), ") has ", cell_offsets[c + 1] - cell_offsets[c], " nodes");
  }
  for (auto n : cell_nodes)
    SEAM_CHECK(n >= 0 && n < n_n, InternalError, "cell node index ", n, " out of range");
  for (const auto& r : regions) {
    SEAM_CHECK(r.facet_cell.size() == r.facet_local.size(), InternalError, "region ", r.name,
               ": facet arrays differ in size");
    for (auto c : r.cells)
      SEAM_CHECK(c >= 0 && c < n_cells(), InternalError, "region ", r.name, ": cell ", c,
                 " out of range");
    for (std::size_t k = 0; k < r.facet_cell.size(); ++k) {
      const auto c = r.facet_cell[k];
      SEAM_CHECK(c >= 0 && c < n_cells(), InternalError, "region ", r.name, ": facet cell ", c,
                 " out of range");
      SEAM_CHECK(r.facet_local[k] >= 0 && r.facet_local[k] < fem::n_facets(cell_type[c]),
                 InternalError, "region ", r.name, ": local facet ", int{r.facet_local[k]},
                 " out of range");
    }
    for (auto n : r.nodes)
      SEAM_CHECK(n >= 0 && n < n_n, InternalError, "region ", r.name, ": node ", n,
                 " out of range");
    SEAM_CHECK(std::is_sorted(r.nodes.begin(), r.nodes.end()), InternalError, "region ", r.name,
               ": nodes not sorted");
  }
}

} // namespace seam::mesh
