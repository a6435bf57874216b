#pragma once
// The cells around every node, as a compressed list: the cells of node n are
// cells[offsets[n] .. offsets[n + 1]), in increasing order. For sparsity patterns.
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::mesh {

struct NodeCells {
  std::vector<std::int32_t> offsets; ///< n_nodes + 1
  std::vector<std::int32_t> cells;

  std::span<const std::int32_t> of(std::int32_t node) const {
    return std::span(cells).subspan(offsets[node], offsets[node + 1] - offsets[node]);
  }
};

NodeCells node_cells(const Mesh& mesh);

} // namespace seam::mesh
