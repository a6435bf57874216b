#include "seam/mesh/distribute.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/node_cells.hpp"
#include "seam/mesh/partition.hpp"
#include "seam/mesh/transfer.hpp"

#include <algorithm>

namespace seam::mesh {

std::int32_t DistributedMesh::count(CellRole role) const {
  return static_cast<std::int32_t>(std::count(cell_role.begin(), cell_role.end(), role));
}

namespace {

/// Cuts submeshes out of one global mesh for a fixed partition. The scratch maps (global ->
/// local index, -1 elsewhere) are reset after each part, so cutting all parts costs
/// O(n_parts * n_cells) for the per-part scans, not O(n_parts * n_nodes) in resets.
class Cutter {
public:
  Cutter(const Mesh& global, std::span<const int> cell_part, int n_parts,
         std::span<const std::string> interface_regions)
      : g_(global), cell_part_(cell_part), numbering_(number_nodes(global, cell_part, n_parts)),
        around_(node_cells(global)), local_cell_(global.n_cells(), -1),
        local_node_(global.n_nodes(), -1) {
    for (const auto& r : g_.regions)
      if (r.dim == g_.dim - 1 && std::find(interface_regions.begin(), interface_regions.end(),
                                           r.name) != interface_regions.end())
        interface_cells_.insert(interface_cells_.end(), r.facet_cell.begin(), r.facet_cell.end());
    std::sort(interface_cells_.begin(), interface_cells_.end());
    interface_cells_.erase(std::unique(interface_cells_.begin(), interface_cells_.end()),
                           interface_cells_.end());
  }

  DistributedMesh cut(int part) {
    DistributedMesh out;
    select(part, out);
    fill_mesh(out);
    for (const auto& r : g_.regions) out.mesh.regions.push_back(filter(r));
    out.node_offsets = numbering_.offsets;
    out.n_global_nodes = g_.n_nodes();
    out.n_global_cells = g_.n_cells();
    for (auto c : out.cell_gid) local_cell_[c] = -1;
    for (auto n : out.node_gid) local_node_[n] = -1;
    return out;
  }

private:
  // Held cells (own, then the layer around their nodes, then interface cells) and their nodes,
  // each sorted by global id: the monotone local numbering.
  void select(int part, DistributedMesh& out) {
    std::vector<std::int32_t> cells, nodes;
    auto hold = [&](std::int32_t c, CellRole role) {
      if (local_cell_[c] >= 0) return;
      local_cell_[c] = static_cast<std::int32_t>(role); // role until renumbered below
      cells.push_back(c);
    };
    for (std::int32_t c = 0; c < g_.n_cells(); ++c)
      if (cell_part_[c] == part) hold(c, CellRole::owned);
    const auto n_own = cells.size();
    for (std::size_t i = 0; i < n_own; ++i)
      for (auto n : g_.cell(cells[i]))
        for (auto nb : around_.of(n)) hold(nb, CellRole::ghost);
    for (auto c : interface_cells_) hold(c, CellRole::interface);
    std::sort(cells.begin(), cells.end());
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const auto c = cells[i];
      out.cell_gid.push_back(c);
      out.cell_role.push_back(static_cast<CellRole>(local_cell_[c]));
      out.cell_owner.push_back(cell_part_[c]);
      local_cell_[c] = static_cast<std::int32_t>(i);
      for (auto n : g_.cell(c))
        if (local_node_[n] < 0) {
          local_node_[n] = 0;
          nodes.push_back(n);
        }
    }
    std::sort(nodes.begin(), nodes.end());
    for (std::size_t i = 0; i < nodes.size(); ++i) {
      const auto n = nodes[i];
      local_node_[n] = static_cast<std::int32_t>(i);
      out.node_gid.push_back(n);
      out.node_owner.push_back(numbering_.owner[n]);
      out.node_index.push_back(numbering_.new_index[n]);
    }
  }

  void fill_mesh(DistributedMesh& out) const {
    auto& m = out.mesh;
    m.dim = g_.dim;
    m.x.reserve(out.node_gid.size() * static_cast<std::size_t>(g_.dim));
    for (auto n : out.node_gid) {
      const auto x = g_.node(static_cast<std::int32_t>(n));
      m.x.insert(m.x.end(), x.begin(), x.end());
    }
    std::vector<std::int32_t> nodes;
    for (auto c : out.cell_gid) {
      nodes.clear();
      for (auto n : g_.cell(static_cast<std::int32_t>(c))) nodes.push_back(local_node_[n]);
      m.add_cell(g_.cell_type[c], nodes);
    }
  }

  // Global -> local is increasing, so the filtered lists stay sorted (by (cell, local) for
  // facets) without another sort.
  Region filter(const Region& r) const {
    Region out;
    out.name = r.name;
    out.dim = r.dim;
    out.tag = r.tag;
    for (auto c : r.cells)
      if (local_cell_[c] >= 0) out.cells.push_back(local_cell_[c]);
    for (std::size_t k = 0; k < r.facet_cell.size(); ++k)
      if (const auto c = local_cell_[r.facet_cell[k]]; c >= 0) {
        out.facet_cell.push_back(c);
        out.facet_local.push_back(r.facet_local[k]);
      }
    for (auto n : r.nodes)
      if (local_node_[n] >= 0) out.nodes.push_back(local_node_[n]);
    return out;
  }

  const Mesh& g_;
  std::span<const int> cell_part_;
  NodeNumbering numbering_;
  NodeCells around_;
  std::vector<std::int32_t> interface_cells_;
  std::vector<std::int32_t> local_cell_; // global cell -> local cell (role while selecting)
  std::vector<std::int32_t> local_node_; // global node -> local node
};

} // namespace

DistributedMesh distribute_mesh(Mesh& global, MPI_Comm comm,
                                std::span<const std::string> interface_regions) {
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  // Partitioning is the only step that the input can make fail (more ranks than cells); its
  // error travels to every rank before anyone waits for a submesh.
  std::vector<int> cell_part;
  std::string error;
  if (rank == 0) {
    try {
      cell_part = partition_cells(global, size);
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  broadcast_text(comm, error);
  if (!error.empty()) throw InputError(error);

  DistributedMesh mine;
  if (rank == 0) {
    Cutter cutter(global, cell_part, size, interface_regions);
    // One part at a time: rank 0 holds the whole mesh and one packed submesh, never all.
    for (int r = 1; r < size; ++r) send_mesh(comm, r, cutter.cut(r));
    mine = cutter.cut(0);
  } else {
    mine = receive_mesh(comm, 0);
  }
  global = Mesh{};
  return mine;
}

} // namespace seam::mesh
