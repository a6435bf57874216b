#pragma once
// One side of a mortar interface taken out of the mesh: the facets of a boundary region as
// flat arrays over side-local node numbers, in the layouts the search (FacetSurface) and the
// mortar integration (FacetSet) read.
#include "seam/mesh/mesh.hpp"
#include "seam/mortar/facet.hpp"
#include "seam/parallel/surface_part.hpp"
#include "seam/search/facets.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::meshtying {

struct InterfaceSide {
  int dim = 3;
  std::vector<std::int32_t> mesh_nodes; ///< side-local node -> mesh node (sorted)
  std::vector<double> coordinates;      ///< side-local nodes, dim values each
  std::vector<fem::CellType> types;     ///< per facet
  std::vector<local_index> offsets{0};  ///< n_facets + 1
  std::vector<local_index> nodes;       ///< side-local node indices, fem facet order

  local_index n_facets() const { return static_cast<local_index>(types.size()); }
  mortar::FacetSet facet_set() const { return {dim, coordinates, types, offsets, nodes}; }
  search::FacetSurface surface() const { return {dim, coordinates, offsets, nodes}; }
  /// Refreshes `coordinates` from mesh coordinates plus an optional displacement
  /// (dim values per mesh node, empty = reference configuration).
  void update_coordinates(const mesh::Mesh& mesh, std::span<const double> displacement = {});
};

/// The facets of a boundary region (dimension mesh.dim - 1) oriented out of their cells.
InterfaceSide extract_side(const mesh::Mesh& mesh, const mesh::Region& region);

/// The global id of every facet of `region` (of a side extracted from it): the id of its cell
/// in the mesh as read (`cell_gid(local cell)`) * 8 + its local facet index. The same on every
/// rank that holds the facet, and increasing along the side when the local cells are numbered
/// in the order of the mesh as read (mesh/distribute.hpp), as the region's facets are sorted by
/// (cell, local facet).
template <class CellGid>
std::vector<std::int64_t> facet_gids(const mesh::Region& region, const CellGid& cell_gid) {
  std::vector<std::int64_t> ids(static_cast<std::size_t>(region.n_facets()));
  for (std::size_t f = 0; f < ids.size(); ++f)
    ids[f] = static_cast<std::int64_t>(cell_gid(region.facet_cell[f])) * 8 + region.facet_local[f];
  return ids;
}

/// The facets `facets` of `side` at its current coordinates as a surface part with global ids
/// (the layout the ghosting and the distributed search exchange): `facet_ids` and `node_ids`
/// give the id of every facet and node of the side. `scratch` is reused between calls.
void side_part(const InterfaceSide& side, std::span<const std::int64_t> facet_ids,
               std::span<const std::int64_t> node_ids, std::span<const local_index> facets,
               std::vector<local_index>& scratch, parallel::SurfacePart& out);

} // namespace seam::meshtying
