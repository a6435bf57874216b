#include "seam/problem/piece_grid.hpp"

#include "seam/fem/cell.hpp"

#include <utility>

namespace seam::problem {

PieceGrid::PieceGrid(const mesh::Mesh& mesh, std::span<const std::int32_t> cells, int rank,
                     std::vector<std::int32_t> numbering)
    : point_of(std::move(numbering)) {
  const bool first_touch = point_of.empty();
  if (first_touch) point_of.assign(static_cast<std::size_t>(mesh.n_nodes()), -1);
  for (auto c : cells) {
    const auto type = mesh.cell_type[c];
    const auto cell_nodes = mesh.cell(c);
    for (int k : fem::vtk_node_order(type)) {
      auto& p = point_of[cell_nodes[k]];
      if (p < 0 && first_touch) {
        p = static_cast<std::int32_t>(nodes.size());
        nodes.push_back(cell_nodes[k]);
      }
      connectivity.push_back(p);
    }
    offsets.push_back(static_cast<std::int32_t>(connectivity.size()));
    types.push_back(static_cast<std::uint8_t>(fem::vtk_type(type)));
    cell_rank.push_back(rank);
  }
}

io::VtuPiece PieceGrid::piece(int point_dim, std::span<const double> points, double time,
                              std::int64_t step) const {
  io::VtuPiece p;
  p.point_dim = point_dim;
  p.points = points;
  p.connectivity = connectivity;
  p.offsets = offsets;
  p.types = types;
  p.cell_data.emplace_back("rank", 1, std::span<const std::int32_t>(cell_rank));
  p.time = time;
  p.cycle = step;
  return p;
}

} // namespace seam::problem
