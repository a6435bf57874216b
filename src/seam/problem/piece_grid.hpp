#pragma once
// The topology of a rank's piece of the VTU fields, shared by the solid, fluid and FSI outputs.

#include "seam/io/vtu.hpp"
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::problem {

/// The VTU topology of a rank's piece of the fields: `cells` over the points they touch, in VTK
/// node order, with cell data `rank`. Points are numbered by `point_of` (mesh node -> point),
/// or, when it is empty, by first touch (then `point_of` and `nodes`, the mesh node of each
/// point, are filled).
struct PieceGrid {
  std::vector<std::int32_t> point_of, nodes;
  std::vector<std::int32_t> connectivity, offsets, cell_rank;
  std::vector<std::uint8_t> types;

  PieceGrid(const mesh::Mesh& mesh, std::span<const std::int32_t> cells, int rank,
            std::vector<std::int32_t> numbering = {});
  /// A piece over this grid with the given points (`point_dim` coordinates each), its fields
  /// still to be added but for `rank`.
  io::VtuPiece piece(int point_dim, std::span<const double> points, double time,
                     std::int64_t step) const;
};

} // namespace seam::problem
