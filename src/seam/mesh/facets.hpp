#pragma once
// Facet topology of a mesh: which cells share a facet, and the boundary of the mesh. Facets are
// identified by their sorted corner nodes, so high-order nodes play no part in matching.
#include "seam/mesh/mesh.hpp"

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <unordered_map>
#include <vector>

namespace seam::mesh {

/// A facet seen from one cell: local facet index per fem::facet_nodes.
struct FacetRef {
  std::int32_t cell = -1;
  std::int8_t local = -1;
};

/// Facets as two parallel arrays (the layout of Region::facet_cell / facet_local).
struct FacetList {
  std::vector<std::int32_t> cell;
  std::vector<std::int8_t> local;
  std::int32_t size() const { return static_cast<std::int32_t>(cell.size()); }
};

/// Corner (vertex) nodes of facet `local` of cell c; returns their number (2, 3 or 4).
int facet_corners(const Mesh& mesh, std::int32_t c, int local, std::array<std::int32_t, 4>& out);

/// Hash map from a facet's sorted corner nodes to the cells that have it.
class FacetIndex {
public:
  /// The cells of one facet in increasing cell order: the first two, and how many there are
  /// (1 on the boundary, 2 inside, more only for a non-manifold mesh).
  struct Entry {
    std::array<FacetRef, 2> cells;
    int n_cells = 0;
  };

  explicit FacetIndex(const Mesh& mesh);

  /// The facet with these corner nodes (any order), or nullptr if no cell has it.
  const Entry* find(std::span<const std::int32_t> corners) const;
  /// The facet (c, local) as seen from the other cell sharing it, if there is one.
  std::optional<FacetRef> neighbour(const Mesh& mesh, FacetRef facet) const;

  std::size_t n_facets() const { return map_.size(); }

private:
  using Key = std::array<std::int32_t, 4>;
  struct KeyHash {
    std::size_t operator()(const Key& k) const noexcept;
  };
  static Key make_key(std::span<const std::int32_t> corners);

  std::unordered_map<Key, Entry, KeyHash> map_;
};

/// The boundary facets of the mesh (facets of exactly one cell), sorted by (cell, local).
FacetList exterior_facets(const Mesh& mesh);
/// The same, reusing an index built already.
FacetList exterior_facets(const Mesh& mesh, const FacetIndex& index);

} // namespace seam::mesh
