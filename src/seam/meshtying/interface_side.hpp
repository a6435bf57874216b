#pragma once
// One side of a mortar interface taken out of the mesh: the facets of a boundary region as
// flat arrays over side-local node numbers, in the layouts the search (FacetSurface) and the
// mortar integration (FacetSet) read.
#include "seam/mesh/mesh.hpp"
#include "seam/mortar/facet.hpp"
#include "seam/search/facets.hpp"

#include <cstdint>
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

} // namespace seam::meshtying
