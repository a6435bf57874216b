#include "seam/mesh/facets.hpp"

#include "seam/common/error.hpp"

#include <algorithm>

namespace seam::mesh {

int facet_corners(const Mesh& mesh, std::int32_t c, int local, std::array<std::int32_t, 4>& out) {
  const auto type = mesh.cell_type[c];
  const auto local_nodes = fem::facet_nodes(type, local);
  // Facet node lists follow the facet type's own (Gmsh) order, corners first.
  const int n = fem::n_vertices(fem::facet_type(type, local));
  SEAM_ASSERT(n >= 1 && n <= 4);
  const auto nodes = mesh.cell(c);
  for (int i = 0; i < n; ++i) out[i] = nodes[local_nodes[i]];
  return n;
}

FacetIndex::Key FacetIndex::make_key(std::span<const std::int32_t> corners) {
  SEAM_ASSERT(!corners.empty() && corners.size() <= 4);
  Key key{-1, -1, -1, -1};
  // Insertion sort: at most four entries.
  const int n = static_cast<int>(corners.size());
  for (int i = 0; i < n; ++i) {
    const std::int32_t v = corners[i];
    int j = i;
    for (; j > 0 && key[j - 1] > v; --j) key[j] = key[j - 1];
    key[j] = v;
  }
  return key;
}

std::size_t FacetIndex::KeyHash::operator()(const Key& k) const noexcept {
  // 64-bit mix (splitmix64 finaliser) of the four indices; cheap and well spread.
  std::uint64_t h = 0x9e3779b97f4a7c15ULL;
  for (auto v : k) {
    h ^= static_cast<std::uint64_t>(static_cast<std::uint32_t>(v)) + 0x9e3779b97f4a7c15ULL +
         (h << 6) + (h >> 2);
    h = (h ^ (h >> 30)) * 0xbf58476d1ce4e5b9ULL;
    h = (h ^ (h >> 27)) * 0x94d049bb133111ebULL;
    h ^= h >> 31;
  }
  return static_cast<std::size_t>(h);
}

FacetIndex::FacetIndex(const Mesh& mesh) {
  std::size_t n_estimate = 0;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    n_estimate += static_cast<std::size_t>(fem::n_facets(mesh.cell_type[c]));
  map_.reserve(n_estimate / 2 + 1);
  std::array<std::int32_t, 4> corners{};
  // Cells in increasing order, so Entry::cells[0] is always the lowest-index cell.
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const int n_f = fem::n_facets(mesh.cell_type[c]);
    for (int f = 0; f < n_f; ++f) {
      const int n = facet_corners(mesh, c, f, corners);
      auto& entry = map_[make_key(std::span<const std::int32_t>(corners.data(), n))];
      if (entry.n_cells < 2) entry.cells[entry.n_cells] = {c, static_cast<std::int8_t>(f)};
      ++entry.n_cells;
    }
  }
}

const FacetIndex::Entry* FacetIndex::find(std::span<const std::int32_t> corners) const {
  if (corners.empty() || corners.size() > 4) return nullptr;
  const auto it = map_.find(make_key(corners));
  return it == map_.end() ? nullptr : &it->second;
}

std::optional<FacetRef> FacetIndex::neighbour(const Mesh& mesh, FacetRef facet) const {
  std::array<std::int32_t, 4> corners{};
  const int n = facet_corners(mesh, facet.cell, facet.local, corners);
  const auto* entry = find(std::span<const std::int32_t>(corners.data(), n));
  if (entry == nullptr || entry->n_cells != 2) return std::nullopt;
  return entry->cells[0].cell == facet.cell ? entry->cells[1] : entry->cells[0];
}

FacetList exterior_facets(const Mesh& mesh) {
  return exterior_facets(mesh, FacetIndex(mesh));
}

FacetList exterior_facets(const Mesh& mesh, const FacetIndex& index) {
  FacetList out;
  std::array<std::int32_t, 4> corners{};
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const int n_f = fem::n_facets(mesh.cell_type[c]);
    for (int f = 0; f < n_f; ++f) {
      const int n = facet_corners(mesh, c, f, corners);
      const auto* entry = index.find(std::span<const std::int32_t>(corners.data(), n));
      SEAM_ASSERT(entry != nullptr);
      if (entry->n_cells == 1) {
        out.cell.push_back(c);
        out.local.push_back(static_cast<std::int8_t>(f));
      }
    }
  }
  return out;
}

} // namespace seam::mesh
