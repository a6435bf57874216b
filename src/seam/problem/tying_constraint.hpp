#pragma once
// Condensation of dual-mortar mesh tying (ALGORITHMS.md §4): the slave displacements follow
// the master ones, d_S = P d_M with P = D^{-1} M (D diagonal for dual multipliers), which is
// written as d = T d~ with T the identity except for the slave rows. The Newton system becomes
// T^T K T d~ = -T^T r; the eliminated slave dofs get a unit diagonal and a zero right-hand
// side, and the multiplier is recovered from the slave rows: lambda_j = -r_j / D_jj.
// Slave nodes with every component prescribed ("bound") carry no multiplier: the mortar
// operators use the boundary-modified basis and those known displacements enter the slave
// rows of T next to the master ones, d_S = D^{-1} (M d_M - D_SB d_B). A partially prescribed
// slave node keeps its multiplier; its prescribed components are not tied (on a symmetry
// plane the traction component they drop vanishes).
#include "seam/la/petsc.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"

#include <functional>
#include <memory>
#include <vector>

namespace seam::problem {

/// The nodal dofs a tying constraint acts on: components 0 .. dim-1 of every node, in a
/// layout with one contiguous owned range per rank, and those of them with a prescribed
/// value. The solid's Discretization ties every dof of a node; a fluid's layout ties the
/// velocity and leaves the pressure dof of a vertex untied (docs/fluid.md, "Mesh tying").
struct TiedDofs {
  const mesh::Mesh* mesh = nullptr;
  Comm comm;
  int dim = 0;
  PetscInt first_owned = 0, n_owned = 0;
  std::function<bool(std::int32_t)> owns_node;
  /// A node's id in the mesh as read (the node id of the output), for messages.
  std::function<std::int64_t(std::int32_t)> node_id;
  /// Owner rank of a node (solid layout; distributed interfaces need it).
  std::function<int(std::int32_t)> node_owner;
  std::function<PetscInt(std::int32_t, int)> global_dof;
  std::function<std::int32_t(std::int32_t, int)> local_dof;
  /// Distributed interfaces name master nodes by their global node number (node_index), which
  /// need not be held here. The first dofs of such nodes (collective; all ranks call it), for
  /// a layout whose dofs are not dim * number + c (the fluid's); unset: the solid's layout.
  std::function<std::vector<PetscInt>(std::span<const std::int64_t>)> first_dofs_of;
  std::vector<PetscInt> prescribed; ///< owned dofs with a prescribed value
};

/// The dofs of a layout with the solid's interface (Discretization) or the fluid's
/// (FluidLayout: its components 0 .. dim-1 are the velocity), and the prescribed ones of its
/// model (`dirichlet`, entries with a global `dof`).
template <class Layout, class Prescribed>
TiedDofs tied_dofs(const Layout& layout, const Prescribed& model) {
  TiedDofs dofs;
  dofs.mesh = &layout.mesh();
  dofs.comm = layout.comm();
  dofs.dim = layout.dim();
  dofs.first_owned = layout.first_owned_dof();
  dofs.n_owned = layout.n_owned_dofs();
  dofs.owns_node = [&layout](std::int32_t n) { return layout.owns_node(n); };
  dofs.node_id = [&layout](std::int32_t n) { return layout.node_gid(n); };
  if constexpr (requires { layout.node_owner(std::int32_t{0}); })
    dofs.node_owner = [&layout](std::int32_t n) { return layout.node_owner(n); };
  dofs.global_dof = [&layout](std::int32_t n, int c) { return layout.global_dof(n, c); };
  dofs.local_dof = [&layout](std::int32_t n, int c) { return layout.local_dof(n, c); };
  if constexpr (requires { layout.first_dofs(std::span<const std::int64_t>()); })
    dofs.first_dofs_of = [&layout](std::span<const std::int64_t> numbers) {
      return layout.first_dofs(numbers);
    };
  for (const auto& d : model.dirichlet) dofs.prescribed.push_back(d.dof);
  return dofs;
}

class TyingConstraint {
public:
  TyingConstraint(const std::vector<meshtying::TiedInterface>& interfaces, TiedDofs dofs);
  TyingConstraint(const std::vector<meshtying::TiedInterface>& interfaces,
                  const Discretization& disc, const Model& model)
      : TyingConstraint(interfaces, tied_dofs(disc, model)) {}
  ~TyingConstraint();
  TyingConstraint(const TyingConstraint&) = delete;
  TyingConstraint& operator=(const TyingConstraint&) = delete;

  bool active() const { return active_; }
  /// Kt = T^T K T. When called again with the same K and the Kt it returned last time, only
  /// the numeric product is recomputed (the patterns of K and T are fixed).
  void condense_matrix(const la::Matrix& K, la::Matrix& Kt) const;
  /// rt = T^T r.
  void condense_vector(const la::Vector& r, la::Vector& rt) const;
  /// du = T dut.
  void expand(const la::Vector& dut, la::Vector& du) const;
  /// The eliminated (tied slave) dofs this rank owns.
  const std::vector<PetscInt>& eliminated_dofs() const { return eliminated_; }

  /// Per interface and slave node (side-local), the multiplier lambda (dim values) from the
  /// full residual r (owned + ghost values, local form): lambda = -D^{-1} T^T r_S (T = I
  /// unless the slave basis is modified). Replicated interface: this rank contributes the rows
  /// it owns, the caller sums over ranks. Distributed interface (collective): the multipliers
  /// of the slave nodes this rank owns, zero elsewhere.
  std::vector<double> multipliers(std::size_t interface, std::span<const double> r_local) const;
  /// D_jj of a tied slave node (side-local), 0 if untied.
  double d_diagonal(std::size_t interface, std::size_t slave_node) const {
    return d_diag_[interface][slave_node];
  }

private:
  const std::vector<meshtying::TiedInterface>& interfaces_;
  TiedDofs dofs_;
  bool active_ = false;
  la::Matrix T_;
  std::vector<PetscInt> eliminated_;
  std::vector<std::vector<double>> d_diag_;
  std::vector<std::vector<mortar::Triplet>> transforms_; ///< per interface: T of a modified basis
  mutable Mat last_product_ = nullptr; ///< the Kt of the last condense_matrix call ...
  mutable Mat last_matrix_ = nullptr;  ///< ... and its K (both referenced)
  void release_product() const;
};

} // namespace seam::problem
