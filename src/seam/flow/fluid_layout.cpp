#include "seam/flow/fluid_layout.hpp"

#include "seam/mesh/node_cells.hpp"
#include "seam/mesh/partition.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>

namespace seam::flow {

FluidLayout::FluidLayout(const mesh::Mesh& mesh, Comm comm)
    : mesh_(&mesh), comm_(comm), dim_(mesh.dim) {
  const int rank = comm_.rank();
  // The same partition and node numbering as the solid's Discretization.
  if (comm_.is_root()) cell_part_ = mesh::partition_cells(mesh, comm_.size());
  comm_.broadcast(cell_part_);
  const auto numbering = mesh::number_nodes(mesh, cell_part_, comm_.size());
  node_owner_ = numbering.owner;
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_part_[c] == rank) local_cells_.push_back(c);

  const std::int32_t n_nodes = mesh.n_nodes();
  has_pressure_.assign(n_nodes, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto nodes = mesh.cell(c);
    for (int k = 0; k < fem::n_vertices(mesh.cell_type[c]); ++k) has_pressure_[nodes[k]] = 1;
  }
  // Global numbering node after node in the order of the node numbering: each rank's owned
  // nodes are consecutive there, so its dofs are too.
  first_dof_.assign(n_nodes, 0);
  PetscInt next = 0;
  for (std::size_t g = 0; g < numbering.old_index.size(); ++g) {
    const auto node = numbering.old_index[g];
    if (static_cast<std::int64_t>(g) == numbering.offsets[rank]) first_owned_dof_ = next;
    first_dof_[node] = next;
    next += dim_ + has_pressure_[node];
  }
  n_global_dofs_ = next;
  n_owned_dofs_ = 0;
  for (std::int32_t n = 0; n < n_nodes; ++n)
    if (node_owner_[n] == rank) n_owned_dofs_ += dim_ + has_pressure_[n];

  n_global_nodes_ = n_nodes;
  n_global_cells_ = mesh.n_cells();
  number_ghosts();
}

FluidLayout::FluidLayout(const mesh::DistributedMesh& part, Comm comm)
    : mesh_(&part.mesh), part_(&part), comm_(comm), dim_(part.mesh.dim),
      cell_part_(part.cell_owner), node_owner_(part.node_owner),
      n_global_nodes_(part.n_global_nodes), n_global_cells_(part.n_global_cells) {
  const auto& mesh = part.mesh;
  const int rank = comm_.rank();
  const std::int32_t n_nodes = mesh.n_nodes();
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c)
    if (cell_part_[c] == rank) local_cells_.push_back(c);
  // A node is a vertex of every cell around it or of none (a conforming mesh), so the cells
  // held decide it for every node held.
  has_pressure_.assign(n_nodes, 0);
  for (std::int32_t c = 0; c < mesh.n_cells(); ++c) {
    const auto nodes = mesh.cell(c);
    for (int k = 0; k < fem::n_vertices(mesh.cell_type[c]); ++k) has_pressure_[nodes[k]] = 1;
  }
  // The owned nodes in global order, their dofs after those of the lower ranks.
  std::vector<std::int32_t> owned, others;
  for (std::int32_t n = 0; n < n_nodes; ++n) (node_owner_[n] == rank ? owned : others).push_back(n);
  std::sort(owned.begin(), owned.end(), [&](std::int32_t a, std::int32_t b) {
    return part.node_index[a] < part.node_index[b];
  });
  for (auto n : owned) n_owned_dofs_ += dim_ + has_pressure_[n];
  long long mine = n_owned_dofs_, before = 0;
  MPI_Exscan(&mine, &before, 1, MPI_LONG_LONG, MPI_SUM, comm_.get());
  if (rank == 0) before = 0;
  first_owned_dof_ = static_cast<PetscInt>(before);
  n_global_dofs_ = static_cast<PetscInt>(comm_.sum(static_cast<std::int64_t>(mine)));
  first_dof_.assign(n_nodes, -1);
  PetscInt next = first_owned_dof_;
  for (auto n : owned) {
    first_dof_[n] = next;
    next += dim_ + has_pressure_[n];
  }
  // The first dofs of the other nodes held, from their owners: one ghosted vector over the
  // global node numbers (exact in double up to 2^53 dofs).
  std::vector<PetscInt> ghost_nodes;
  for (auto n : others) ghost_nodes.push_back(static_cast<PetscInt>(part.node_index[n]));
  la::Vector first(comm_.get(), static_cast<PetscInt>(owned.size()), ghost_nodes);
  {
    la::Vector::LocalView view(first, true);
    auto v = view.values();
    const auto offset = part.node_offsets[rank];
    for (auto n : owned) v[part.node_index[n] - offset] = static_cast<double>(first_dof_[n]);
  }
  first.update_ghosts();
  {
    la::Vector::LocalView view(first, false);
    const auto v = view.values();
    for (std::size_t k = 0; k < others.size(); ++k)
      first_dof_[others[k]] = static_cast<PetscInt>(v[owned.size() + k]);
  }
  number_ghosts();
}

void FluidLayout::number_ghosts() {
  const auto& mesh = *mesh_;
  const int rank = comm_.rank();
  const std::int32_t n_nodes = mesh.n_nodes();
  local_first_.assign(n_nodes, -1);
  for (std::int32_t n = 0; n < n_nodes; ++n)
    if (node_owner_[n] == rank)
      local_first_[n] = static_cast<std::int32_t>(first_dof_[n] - first_owned_dof_);
  std::vector<std::int32_t> ghosts;
  std::vector<char> seen(n_nodes, 0);
  for (auto c : local_cells_)
    for (auto n : mesh.cell(c))
      if (node_owner_[n] != rank && !seen[n]) {
        seen[n] = 1;
        ghosts.push_back(n);
      }
  std::sort(ghosts.begin(), ghosts.end(),
            [&](std::int32_t a, std::int32_t b) { return first_dof_[a] < first_dof_[b]; });
  auto local = static_cast<std::int32_t>(n_owned_dofs_);
  for (auto n : ghosts) {
    local_first_[n] = local;
    for (int c = 0; c < dim_ + has_pressure_[n]; ++c) ghost_dofs_.push_back(first_dof_[n] + c);
    local += dim_ + has_pressure_[n];
  }
}

void FluidLayout::nodal_to_vector(std::span<const double> nodal, la::Vector& v) const {
  {
    la::Vector::LocalView view(v, true);
    auto values = view.values();
    for (std::int32_t n = 0; n < mesh_->n_nodes(); ++n)
      if (owns_node(n))
        for (int i = 0; i < dim_; ++i)
          values[local_dof(n, i)] = nodal[static_cast<std::size_t>(n) * dim_ + i];
  }
  v.update_ghosts();
}

void FluidLayout::vector_to_nodal(const la::Vector& v, std::span<double> nodal) const {
  la::Vector::LocalView view(v, false);
  const auto values = view.values();
  for (std::int32_t n = 0; n < mesh_->n_nodes(); ++n)
    for (int i = 0; i < dim_; ++i)
      nodal[static_cast<std::size_t>(n) * dim_ + i] =
          local_first_[n] < 0 ? 0.0 : values[local_dof(n, i)];
}

int FluidLayout::cell_dofs(std::int32_t c, std::span<PetscInt> out) const {
  const auto nodes = mesh_->cell(c);
  int k = 0;
  for (auto n : nodes)
    for (int i = 0; i < dim_; ++i) out[k++] = first_dof_[n] + i;
  for (int v = 0; v < fem::n_vertices(mesh_->cell_type[c]); ++v)
    out[k++] = first_dof_[nodes[v]] + dim_;
  return k;
}

int FluidLayout::cell_local_dofs(std::int32_t c, std::span<std::int32_t> out) const {
  const auto nodes = mesh_->cell(c);
  int k = 0;
  for (auto n : nodes)
    for (int i = 0; i < dim_; ++i) out[k++] = local_dof(n, i);
  for (int v = 0; v < fem::n_vertices(mesh_->cell_type[c]); ++v)
    out[k++] = local_dof(nodes[v], dim_);
  return k;
}

void FluidLayout::owned_fields(std::vector<PetscInt>& velocity,
                               std::vector<PetscInt>& pressure) const {
  velocity.clear();
  pressure.clear();
  for (std::int32_t n = 0; n < mesh_->n_nodes(); ++n) {
    if (!owns_node(n)) continue;
    for (int i = 0; i < dim_; ++i) velocity.push_back(first_dof_[n] + i);
    if (has_pressure_[n]) pressure.push_back(first_dof_[n] + dim_);
  }
  std::sort(velocity.begin(), velocity.end());
  std::sort(pressure.begin(), pressure.end());
}

std::vector<PetscInt> FluidLayout::first_dofs(std::span<const std::int64_t> numbers) const {
  std::vector<PetscInt> out(numbers.size(), 0);
  if (!part_) { // replicated: the numbers are mesh nodes
    for (std::size_t k = 0; k < numbers.size(); ++k) out[k] = first_dof_[numbers[k]];
    return out;
  }
  // Ask each number's owner (node_offsets), which answers from its owned nodes.
  const int np = comm_.size();
  const auto& offsets = part_->node_offsets;
  const auto owner = [&](std::int64_t i) {
    return static_cast<int>(std::upper_bound(offsets.begin(), offsets.end(), i) - offsets.begin() -
                            1);
  };
  std::vector<std::size_t> order(numbers.size());
  for (std::size_t k = 0; k < order.size(); ++k) order[k] = k;
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return owner(numbers[a]) < owner(numbers[b]);
  });
  std::vector<std::int64_t> ask, ask_offsets(static_cast<std::size_t>(np) + 1, 0);
  for (auto k : order) {
    ask.push_back(numbers[k]);
    ++ask_offsets[static_cast<std::size_t>(owner(numbers[k])) + 1];
  }
  for (int r = 0; r < np; ++r) ask_offsets[r + 1] += ask_offsets[r];
  std::vector<std::int64_t> asked_offsets, back_offsets;
  const auto asked =
      parallel::alltoallv<std::int64_t>(comm_.get(), ask, ask_offsets, asked_offsets);
  // This rank's owned nodes by global number.
  const auto first_owned = offsets[comm_.rank()];
  std::vector<PetscInt> owned_first(
      static_cast<std::size_t>(offsets[comm_.rank() + 1] - first_owned));
  for (std::int32_t n = 0; n < mesh_->n_nodes(); ++n)
    if (owns_node(n))
      owned_first[static_cast<std::size_t>(part_->node_index[n] - first_owned)] = first_dof_[n];
  std::vector<PetscInt> answers(asked.size());
  for (std::size_t k = 0; k < asked.size(); ++k)
    answers[k] = owned_first[static_cast<std::size_t>(asked[k] - first_owned)];
  const auto back =
      parallel::alltoallv<PetscInt>(comm_.get(), answers, asked_offsets, back_offsets);
  for (std::size_t j = 0; j < order.size(); ++j) out[order[j]] = back[j];
  return out;
}

la::Vector FluidLayout::make_vector() const {
  return la::Vector(comm_.get(), n_owned_dofs_, ghost_dofs_);
}

la::Matrix FluidLayout::make_matrix() const {
  // Every dof of a node couples with every dof of the nodes of the cells around it.
  const auto& m = *mesh_;
  const std::int32_t n_nodes = m.n_nodes();
  const auto around = mesh::node_cells(m);
  const int rank = comm_.rank();
  std::vector<PetscInt> d_nnz(n_owned_dofs_, 0), o_nnz(n_owned_dofs_, 0);
  std::vector<std::int32_t> mark(n_nodes, -1);
  for (std::int32_t node = 0; node < n_nodes; ++node) {
    if (node_owner_[node] != rank) continue;
    PetscInt d = 0, o = 0;
    for (auto c : around.of(node))
      for (auto nb : m.cell(c)) {
        if (mark[nb] == node) continue;
        mark[nb] = node;
        (node_owner_[nb] == rank ? d : o) += dim_ + has_pressure_[nb];
      }
    const auto first = first_dof_[node] - first_owned_dof_;
    for (int c = 0; c < dim_ + has_pressure_[node]; ++c) {
      d_nnz[first + c] = d;
      o_nnz[first + c] = o;
    }
  }
  la::Matrix A(comm_.get(), n_owned_dofs_, d_nnz, o_nnz, 1);
  std::vector<PetscInt> dofs(fem::max_cell_nodes * 4);
  std::vector<double> zeros;
  for (auto c : local_cells_) {
    const int n = cell_dofs(c, dofs);
    zeros.assign(static_cast<std::size_t>(n) * n, 0.0);
    A.add_values(std::span(dofs.data(), n), std::span(dofs.data(), n), zeros);
  }
  A.assemble();
  return A;
}

} // namespace seam::flow
