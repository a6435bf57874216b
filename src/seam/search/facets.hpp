#pragma once
// The search's view of a surface: facets given by node coordinates and connectivity, as flat
// arrays. The search knows nothing of meshes, dofs or mortar; the caller extracts the facets.
#include "seam/common/types.hpp"

#include <span>

namespace seam::search {

/// Non-owning view of a facet surface. Facet f has the nodes
/// connectivity[offsets[f] .. offsets[f+1]), which index `coords` (dim values per node).
/// Supported facets: line2/line3 in 2D; tri3, tri6, quad4, quad8, quad9 in 3D, corners first and
/// ordered so that the right-hand rule gives the outward normal (used only by self contact).
struct FacetSurface {
  int dim = 3;
  std::span<const double> coords;
  std::span<const local_index> offsets;
  std::span<const local_index> connectivity;

  local_index n_facets() const {
    return offsets.empty() ? 0 : static_cast<local_index>(offsets.size() - 1);
  }
  local_index n_nodes() const { return static_cast<local_index>(coords.size() / dim); }
};

/// Throws InputError unless `surface` is well formed: dim 2 or 3, coordinate count a multiple of
/// dim, offsets starting at 0 that match the connectivity (or no offsets: no facets), node
/// indices in range, supported node counts per facet and finite coordinates.
void check_surface(const FacetSurface& surface);

/// Number of corner nodes of a facet with `n_nodes` nodes (2 in 2D; 3 or 4 in 3D).
int n_corners(int dim, int n_nodes);

/// Shortest non-degenerate corner-to-corner edge of all facets (0 if every edge has zero
/// length). Times a user factor it gives the inflation of the bounding volumes (ALGORITHMS.md
/// Sect. 6: eps * l_min).
double min_edge_length(const FacetSurface& surface);

} // namespace seam::search
