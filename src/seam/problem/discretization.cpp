#include "seam/problem/discretization.hpp"

#include "seam/common/error.hpp"
#include "seam/mesh/node_cells.hpp"
#include "seam/mesh/partition.hpp"

#include <algorithm>

namespace seam::problem {

Discretization::Discretization(const mesh::Mesh& mesh, Comm comm)
    : mesh_(&mesh), comm_(comm), dim_(mesh.dim), n_global_nodes_(mesh.n_nodes()),
      n_global_cells_(mesh.n_cells()) {
  const int n_ranks = comm_.size();
  const int rank = comm_.rank();
  // Every rank holds the same mesh and METIS is deterministic, so every rank computes the
  // same partition; rank 0's copy is broadcast anyway to rule out any platform difference.
  if (comm_.is_root()) cell_part_ = mesh::partition_cells(mesh, n_ranks);
  comm_.broadcast(cell_part_);
  const auto numbering = mesh::number_nodes(mesh, cell_part_, n_ranks);
  new_index_ = numbering.new_index;
  node_owner_ = numbering.owner;
  first_owned_node_ = numbering.offsets[rank];
  n_owned_nodes_ = static_cast<std::int32_t>(numbering.offsets[rank + 1] - first_owned_node_);
  number_local_nodes();
}

Discretization::Discretization(const mesh::DistributedMesh& part, Comm comm)
    : mesh_(&part.mesh), comm_(comm), dim_(part.mesh.dim), distributed_(true),
      n_global_nodes_(part.n_global_nodes), n_global_cells_(part.n_global_cells),
      node_gid_(part.node_gid), cell_gid_(part.cell_gid), cell_role_(part.cell_role),
      cell_part_(part.cell_owner), new_index_(part.node_index), node_owner_(part.node_owner) {
  SEAM_CHECK(part.node_offsets.size() == static_cast<std::size_t>(comm_.size()) + 1, InternalError,
             "a mesh distributed over ", part.node_offsets.size() - 1, " ranks used on ",
             comm_.size());
  first_owned_node_ = part.node_offsets[comm_.rank()];
  n_owned_nodes_ =
      static_cast<std::int32_t>(part.node_offsets[comm_.rank() + 1] - first_owned_node_);
  number_local_nodes();
}

void Discretization::number_local_nodes() {
  const auto& mesh = *mesh_;
  const int rank = comm_.rank();
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_part_[c] == rank) local_cells_.push_back(c);

  // Local nodes: owned ones in global order, then ghosts (nodes of local cells owned elsewhere)
  // in global order. A distributed part holds every owned node (each lies on an own cell).
  const std::int32_t n_nodes = mesh.n_nodes();
  local_node_.assign(n_nodes, -1);
  std::vector<std::int32_t> owned, ghosts;
  for (std::int32_t n = 0; n < n_nodes; ++n)
    if (node_owner_[n] == rank) owned.push_back(n);
  SEAM_CHECK(static_cast<std::int32_t>(owned.size()) == n_owned_nodes_, InternalError, "rank ",
             rank, " holds ", owned.size(), " of its ", n_owned_nodes_, " owned nodes");
  std::vector<char> is_ghost(n_nodes, 0);
  for (auto c : local_cells_)
    for (auto n : mesh.cell(c))
      if (node_owner_[n] != rank && !is_ghost[n]) {
        is_ghost[n] = 1;
        ghosts.push_back(n);
      }
  auto by_global = [&](std::int32_t a, std::int32_t b) { return new_index_[a] < new_index_[b]; };
  std::sort(owned.begin(), owned.end(), by_global);
  std::sort(ghosts.begin(), ghosts.end(), by_global);
  local_nodes_ = owned;
  local_nodes_.insert(local_nodes_.end(), ghosts.begin(), ghosts.end());
  for (std::size_t i = 0; i < local_nodes_.size(); ++i)
    local_node_[local_nodes_[i]] = static_cast<std::int32_t>(i);
  for (auto n : ghosts)
    for (int c = 0; c < dim_; ++c) ghost_dofs_.push_back(global_dof(n, c));
}

std::int32_t Discretization::n_cells_held(mesh::CellRole role) const {
  if (!distributed_) {
    const auto owned = static_cast<std::int32_t>(local_cells_.size());
    if (role == mesh::CellRole::owned) return owned;
    return role == mesh::CellRole::ghost ? mesh_->n_cells() - owned : 0;
  }
  return static_cast<std::int32_t>(std::count(cell_role_.begin(), cell_role_.end(), role));
}

la::Vector Discretization::make_vector() const {
  return la::Vector(comm_.get(), n_owned_dofs(), ghost_dofs_);
}

la::Matrix Discretization::make_matrix() const {
  // Node graph of the owned nodes over ALL cells touching them (replicated mesh, or the ghost
  // layer of a distributed one: both hold every cell around an owned node), so rows that other
  // ranks add to are preallocated exactly as well.
  const auto& m = *mesh_;
  const std::int32_t n_nodes = m.n_nodes();
  const auto around = mesh::node_cells(m);
  const int rank = comm_.rank();
  std::vector<PetscInt> d_nnz(n_owned_dofs(), 0), o_nnz(n_owned_dofs(), 0);
  std::vector<std::int32_t> mark(n_nodes, -1);
  for (std::int32_t i = 0; i < n_owned_nodes_; ++i) {
    const auto node = local_nodes_[i];
    PetscInt d = 0, o = 0;
    for (auto c : around.of(node))
      for (auto nb : m.cell(c)) {
        if (mark[nb] == node) continue;
        mark[nb] = node;
        (node_owner_[nb] == rank ? d : o) += dim_;
      }
    for (int c = 0; c < dim_; ++c) {
      d_nnz[i * dim_ + c] = d;
      o_nnz[i * dim_ + c] = o;
    }
  }
  la::Matrix A(comm_.get(), n_owned_dofs(), d_nnz, o_nnz, dim_);
  // Fix the sparsity pattern once with explicit zeros: a later assembly that skips a cell
  // (e.g. an inverted element before a step cut) must not squeeze its entries out.
  std::vector<PetscInt> dofs;
  std::vector<double> zeros;
  for (auto c : local_cells_) {
    dofs.clear();
    for (auto n : m.cell(c))
      for (int i = 0; i < dim_; ++i) dofs.push_back(global_dof(n, i));
    zeros.assign(dofs.size() * dofs.size(), 0.0);
    A.add_values(dofs, dofs, zeros);
  }
  A.assemble();
  return A;
}

la::Vector Discretization::coordinates_vector() const {
  la::Vector x(comm_.get(), n_owned_dofs());
  {
    la::Vector::LocalView view(x, true);
    auto v = view.values();
    for (std::int32_t i = 0; i < n_owned_nodes_; ++i)
      for (int c = 0; c < dim_; ++c) v[i * dim_ + c] = mesh_->x[local_nodes_[i] * dim_ + c];
  }
  return x;
}

} // namespace seam::problem
