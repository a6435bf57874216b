#pragma once
// A mesh as flat arrays: the whole mesh as read (on rank 0, or on every rank for runs that keep
// it replicated), or one rank's part of it in local numbering (distribute.hpp). The partition
// (partition.hpp) decides what each rank assembles.
#include "seam/fem/cell.hpp"

#include <cstdint>
#include <span>
#include <string>
#include <string_view>
#include <vector>

namespace seam::mesh {

/// A Gmsh physical group.
struct Region {
  std::string name; ///< physical name, or "<dim>:<tag>" for an unnamed group
  int dim = 0;      ///< dimension of the physical group
  int tag = 0;      ///< Gmsh physical tag
  /// dim == mesh dim: the cells of the region, sorted.
  std::vector<std::int32_t> cells;
  /// dim == mesh dim - 1: the region's facets as (cell, local facet index per
  /// fem::facet_nodes), sorted by (cell, local). A facet shared by two cells (an interface
  /// inside the mesh) refers to the cell with the lower index.
  std::vector<std::int32_t> facet_cell;
  std::vector<std::int8_t> facet_local;
  /// Every dimension: the sorted, unique mesh nodes of the region (for facet regions: all
  /// nodes of the cells' facets, high-order ones included).
  std::vector<std::int32_t> nodes;

  std::int32_t n_facets() const { return static_cast<std::int32_t>(facet_cell.size()); }
  /// Sorts the facets by (cell, local) and drops repeated ones (the same facet listed twice,
  /// e.g. by two entities or two groups), as the facet arrays must be.
  void sort_facets();
};

struct Mesh {
  int dim = 0;           ///< spatial dimension = dimension of the cells (2 or 3)
  std::vector<double> x; ///< node coordinates, n_nodes * dim, node-major
  std::vector<fem::CellType> cell_type;
  std::vector<std::int64_t> cell_offsets{0}; ///< n_cells + 1; cell c has nodes [off[c], off[c+1])
  std::vector<std::int32_t> cell_nodes;      ///< per cell in Gmsh (= fem) node order
  std::vector<Region> regions;

  std::int32_t n_nodes() const {
    return dim > 0 ? static_cast<std::int32_t>(x.size() / static_cast<std::size_t>(dim)) : 0;
  }
  std::int32_t n_cells() const { return static_cast<std::int32_t>(cell_type.size()); }

  std::span<const std::int32_t> cell(std::int32_t c) const {
    const auto begin = static_cast<std::size_t>(cell_offsets[c]);
    const auto end = static_cast<std::size_t>(cell_offsets[c + 1]);
    return std::span<const std::int32_t>(cell_nodes).subspan(begin, end - begin);
  }
  /// Coordinates of node n (dim values).
  std::span<const double> node(std::int32_t n) const {
    return std::span<const double>(x).subspan(static_cast<std::size_t>(n) * dim,
                                              static_cast<std::size_t>(dim));
  }

  /// Append a cell (used by readers and by tests that build meshes by hand).
  void add_cell(fem::CellType type, std::span<const std::int32_t> nodes);

  /// The region with this name (and dimension, if dim >= 0); nullptr if there is none.
  const Region* find_region(std::string_view name, int dim = -1) const;
  /// As find_region, but a missing region is an InputError listing the regions there are.
  const Region& region(std::string_view name, int dim = -1) const;

  /// Throws InternalError if the arrays are inconsistent (sizes, offsets, node indices out of
  /// range, cell dimension != dim, region indices out of range): the reader never produces
  /// such a mesh, so this guards meshes built or transferred by code. O(size of the mesh).
  void check() const;
};

} // namespace seam::mesh
