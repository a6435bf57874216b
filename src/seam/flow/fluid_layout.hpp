#pragma once
// The dof layout of a fluid field: every node carries the velocity (dim dofs), every vertex
// of a Taylor-Hood cell the pressure as well, one dof after its velocity. A node's dofs are
// contiguous, numbered in the order of the global node numbering (mesh::number_nodes, or the
// node_index of a distributed mesh), so that every rank owns one contiguous range (PETSc's
// layout). The local (ghosted) vector form holds the owned dofs, then the ghost nodes' dofs
// node by node (ghost nodes: the nodes of this rank's cells that other ranks own).
//
// Two sources, as for the solid's Discretization: a replicated mesh (fluid-structure runs),
// or this rank's part of a distributed mesh (mesh::distribute_mesh: owned cells, one ghost
// layer). Then "node" and "cell" are indices into the part, every array here is sized by the
// part, and the first dofs of the ghost nodes come from their owners (one ghost update).
#include "seam/common/mpi.hpp"
#include "seam/la/petsc.hpp"
#include "seam/mesh/distribute.hpp"
#include "seam/mesh/mesh.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::flow {

class FluidLayout {
public:
  /// Replicated: every rank holds `mesh` whole.
  FluidLayout(const mesh::Mesh& mesh, Comm comm);
  /// Distributed: `part` is this rank's part (kept by reference).
  FluidLayout(const mesh::DistributedMesh& part, Comm comm);

  const mesh::Mesh& mesh() const { return *mesh_; }
  /// This rank's part of a distributed mesh, or null when the mesh is replicated.
  const mesh::DistributedMesh* part() const { return part_; }
  /// Counts of the whole mesh (the same on every rank).
  std::int64_t n_global_nodes() const { return n_global_nodes_; }
  std::int64_t n_global_cells() const { return n_global_cells_; }
  /// Id in the mesh as read of node n / cell c (n / c itself when replicated).
  std::int64_t node_gid(std::int32_t n) const { return part_ ? part_->node_gid[n] : n; }
  std::int64_t cell_gid(std::int32_t c) const { return part_ ? part_->cell_gid[c] : c; }
  int node_owner(std::int32_t node) const { return node_owner_[node]; }
  Comm comm() const { return comm_; }
  int dim() const { return dim_; }

  std::span<const std::int32_t> local_cells() const { return local_cells_; }
  bool is_local_cell(std::int32_t c) const { return cell_part_[c] == comm_.rank(); }
  bool owns_node(std::int32_t node) const { return node_owner_[node] == comm_.rank(); }
  bool has_pressure(std::int32_t node) const { return has_pressure_[node] != 0; }

  PetscInt n_owned_dofs() const { return n_owned_dofs_; }
  PetscInt n_global_dofs() const { return n_global_dofs_; }
  PetscInt first_owned_dof() const { return first_owned_dof_; }

  /// Global dof of velocity component c (< dim) of a node, or of its pressure (c = dim; the
  /// node must be a vertex).
  PetscInt global_dof(std::int32_t node, int c) const { return first_dof_[node] + c; }
  /// The same in the local form; -1 if the node is neither owned nor a ghost here.
  std::int32_t local_dof(std::int32_t node, int c) const {
    return local_first_[node] < 0 ? -1 : local_first_[node] + c;
  }
  /// The global dofs of cell c in the layout of fluid::navier_stokes: the velocity of all
  /// nodes node-major, then the pressure of the vertices. Returns their number.
  int cell_dofs(std::int32_t c, std::span<PetscInt> out) const;
  /// The same in the local form.
  int cell_local_dofs(std::int32_t c, std::span<std::int32_t> out) const;

  /// The owned global dofs of the velocity and of the pressure, ascending (the index sets of
  /// a fieldsplit preconditioner).
  void owned_fields(std::vector<PetscInt>& velocity, std::vector<PetscInt>& pressure) const;

  /// Nodal values (dim per mesh node, node-major) into the velocity entries this rank owns
  /// of a layout vector, and back from a ghosted vector into every node of this rank's cells
  /// (the other nodes get 0): how nodal fields (the mesh displacement) are made consistent
  /// across ranks and stored in checkpoints.
  void nodal_to_vector(std::span<const double> nodal, la::Vector& v) const;
  void vector_to_nodal(const la::Vector& v, std::span<double> nodal) const;

  /// The first global dofs of the nodes with the given global node numbers (node_index of a
  /// distributed mesh; held here or not), from their owners. Collective.
  std::vector<PetscInt> first_dofs(std::span<const std::int64_t> numbers) const;

  la::Vector make_vector() const;
  /// The Jacobian with exact preallocation and its pattern fixed with explicit zeros.
  la::Matrix make_matrix() const;

private:
  void number_ghosts();

  const mesh::Mesh* mesh_;
  const mesh::DistributedMesh* part_ = nullptr;
  Comm comm_;
  int dim_;
  std::vector<int> cell_part_;
  std::vector<std::int32_t> local_cells_;
  std::vector<int> node_owner_;
  std::vector<char> has_pressure_;
  std::vector<PetscInt> first_dof_;       // mesh node -> its first global dof
  std::vector<std::int32_t> local_first_; // mesh node -> its first local dof, or -1
  std::vector<PetscInt> ghost_dofs_;
  PetscInt n_owned_dofs_ = 0, n_global_dofs_ = 0, first_owned_dof_ = 0;
  std::int64_t n_global_nodes_ = 0, n_global_cells_ = 0;
};

} // namespace seam::flow
