#pragma once
// The moving mesh of a fluid (ALE) as a field of its own: which nodes move and how, from the
// input (`mesh_motion` of the fluid bodies, `mesh_displacement` conditions), and the mesh
// displacement at a time. A pseudo-elastic body's nodes follow linear elasticity on the
// reference mesh with Jacobian-based stiffening (ale/mesh_motion.hpp), with its own dof
// layout (a Discretization: dim dofs per node) and a stiffness assembled and kept once: each
// time only the boundary data change. Its Dirichlet data: `mesh_displacement` conditions,
// zero on the rest of the mesh's boundary, and the motion of the nodes it shares with bodies
// that do not move pseudo-elastically (prescribed, or fixed). The system matrix is the same
// every step, so its factorization is kept. On a distributed mesh the solve is distributed
// too (a Discretization of the part): each rank sets up its owned rows and returns the
// displacement of the nodes of its cells, made consistent by one ghost update.
#include "seam/flow/fluid_layout.hpp"
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/discretization.hpp"

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

namespace seam::flow {

class FluidMeshMotion {
public:
  /// Checks the input's mesh motion against the mesh (InputError, located).
  FluidMeshMotion(const io::Config& config, const FluidLayout& layout);
  ~FluidMeshMotion();

  /// Whether the fluid mesh moves at all.
  bool moving() const { return moving_; }
  /// The displacement at time t of the nodes of this rank's cells, node-major (n_nodes * dim
  /// of mesh(); 0 at the other nodes held). Collective. False if the linear solver failed.
  bool displacement(double t, std::vector<double>& d);

private:
  // Where a node's displacement comes from: the elastic solve (free), zero, a boundary
  // condition or a prescribed body's expressions.
  struct Source {
    enum Kind : std::int8_t { free, zero, condition, body } kind = free;
    int index = -1; ///< into config.boundary_conditions or config.bodies
  };
  void value_at(const Source& s, double t, std::int32_t node, double* d) const;
  /// The layout, stiffness and solver of the elastic solve (PETSc), at first use.
  void build_solve();

  const io::Config& config_;
  const FluidLayout& layout_;
  bool moving_ = false;
  bool elastic_solve_ = false;              // some rank holds pseudo-elastic cells
  std::vector<Source> source_;              // per mesh node
  std::vector<char> elastic_;               // per mesh node: in a pseudo-elastic cell
  std::vector<std::int32_t> elastic_cells_; // sorted
  std::vector<int> cell_body_; // per cell: the body whose mesh motion it follows, or -1
  std::unique_ptr<problem::Discretization> disc_; // of the pseudo-elastic solve, if any
  std::optional<la::Matrix> K_;                   // the stiffness
  std::optional<la::Matrix> K_system_; // the same, prescribed rows and columns as identity
  std::unique_ptr<la::LinearSolver> solver_;
  std::vector<PetscInt> fixed_; // owned dofs of the solve with a given value
};

} // namespace seam::flow
