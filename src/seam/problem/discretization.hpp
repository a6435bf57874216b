#pragma once
// The distributed layout: which cells this rank assembles, which nodes (and so dofs) it owns,
// its ghost nodes, and the local <-> global dof maps PETSc needs. Global dof of node n,
// component c: dim * (global number of n) + c, contiguous per rank.
//
// Two sources: a replicated mesh (every rank holds all of it and partitions it the same way),
// or this rank's part of a distributed mesh (mesh::distribute_mesh: owned cells, one ghost
// layer, interface cells). "Mesh node" and "cell" below are indices into mesh(), i.e. local
// indices of the part in the distributed case; node_gid / cell_gid give the ids of the mesh as
// read, which are the same on every rank.
#include "seam/common/mpi.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::problem {

class Discretization {
public:
  /// Replicated: every rank holds `mesh` whole.
  Discretization(const mesh::Mesh& mesh, Comm comm);
  /// Distributed: `part` is this rank's part (kept by reference, as the mesh above).
  Discretization(const mesh::DistributedMesh& part, Comm comm);

  const mesh::Mesh& mesh() const { return *mesh_; }
  Comm comm() const { return comm_; }
  int dim() const { return dim_; }

  /// True if mesh() is this rank's part of a distributed mesh.
  bool distributed() const { return distributed_; }
  /// Counts of the whole mesh (the same on every rank).
  std::int64_t n_global_nodes() const { return n_global_nodes_; }
  std::int64_t n_global_cells() const { return n_global_cells_; }
  /// Id in the mesh as read of mesh node n / cell c (n / c itself when replicated).
  std::int64_t node_gid(std::int32_t node) const { return distributed_ ? node_gid_[node] : node; }
  std::int64_t cell_gid(std::int32_t c) const { return distributed_ ? cell_gid_[c] : c; }
  /// Held cells of a role (mesh/distribute.hpp): owned, ghost layer, or held only for an
  /// interface side. A replicated mesh counts its cells of other ranks as ghosts.
  std::int32_t n_cells_held(mesh::CellRole role) const;
  /// Whether cell c is held only for an interface side (neither owned nor in the ghost layer).
  bool interface_only_cell(std::int32_t c) const {
    return distributed_ && cell_role_[static_cast<std::size_t>(c)] == mesh::CellRole::interface;
  }

  /// Cells this rank assembles (all cells whose partition is this rank).
  std::span<const std::int32_t> local_cells() const { return local_cells_; }
  /// Partition (rank) of every cell of mesh().
  std::span<const int> cell_part() const { return cell_part_; }
  bool is_local_cell(std::int32_t c) const { return cell_part_[c] == comm_.rank(); }

  /// Number of dofs owned by this rank and of all ranks.
  PetscInt n_owned_dofs() const { return n_owned_nodes_ * dim_; }
  PetscInt n_global_dofs() const { return static_cast<PetscInt>(n_global_nodes_) * dim_; }
  PetscInt first_owned_dof() const { return first_owned_node_ * dim_; }

  /// Global dof of mesh node n, component c.
  PetscInt global_dof(std::int32_t node, int c) const { return new_index_[node] * dim_ + c; }
  /// Owner rank of a mesh node.
  int node_owner(std::int32_t node) const { return node_owner_[node]; }
  bool owns_node(std::int32_t node) const { return node_owner_[node] == comm_.rank(); }
  /// Index of node n's first dof in the local (owned + ghost) vector form, or -1 if n is
  /// neither owned nor a ghost on this rank.
  std::int32_t local_dof(std::int32_t node, int c) const {
    const auto l = local_node_[node];
    return l < 0 ? -1 : l * dim_ + c;
  }
  bool has_node(std::int32_t node) const { return local_node_[node] >= 0; }
  /// Mesh nodes present locally (owned first, then ghosts), in local-vector order.
  std::span<const std::int32_t> local_nodes() const { return local_nodes_; }
  std::int32_t n_owned_nodes() const { return n_owned_nodes_; }

  /// A ghosted vector with this layout (owned dofs + the ghost nodes' dofs).
  la::Vector make_vector() const;
  /// The tangent matrix with exact preallocation of the bulk pattern.
  la::Matrix make_matrix() const;
  /// Reference coordinates as a PETSc vector (for the rigid-body near-null space).
  la::Vector coordinates_vector() const;

private:
  void number_local_nodes();

  const mesh::Mesh* mesh_;
  Comm comm_;
  int dim_;
  bool distributed_ = false;
  std::int64_t n_global_nodes_ = 0;
  std::int64_t n_global_cells_ = 0;
  std::span<const std::int64_t> node_gid_, cell_gid_;
  std::span<const mesh::CellRole> cell_role_;
  std::vector<int> cell_part_;
  std::vector<std::int32_t> local_cells_;
  std::vector<std::int64_t> new_index_;
  std::vector<int> node_owner_;
  std::int64_t first_owned_node_ = 0;
  std::int32_t n_owned_nodes_ = 0;
  std::vector<std::int32_t> local_node_;  // mesh node -> local node or -1
  std::vector<std::int32_t> local_nodes_; // local node -> mesh node
  std::vector<PetscInt> ghost_dofs_;
};

} // namespace seam::problem
