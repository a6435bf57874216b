#include "seam/mesh/node_cells.hpp"

namespace seam::mesh {

NodeCells node_cells(const Mesh& mesh) {
  const std::int32_t n_nodes = mesh.n_nodes();
  NodeCells out;
  out.offsets.assign(n_nodes + 1, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (auto n : mesh.cell(c)) ++out.offsets[n + 1];
  for (std::int32_t n = 0; n < n_nodes; ++n) out.offsets[n + 1] += out.offsets[n];
  out.cells.resize(out.offsets[n_nodes]);
  std::vector<std::int32_t> fill(out.offsets.begin(), out.offsets.end() - 1);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    for (auto n : mesh.cell(c)) out.cells[fill[n]++] = c;
  return out;
}

} // namespace seam::mesh
