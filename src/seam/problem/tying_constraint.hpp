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

#include <memory>
#include <vector>

namespace seam::problem {

class TyingConstraint {
public:
  TyingConstraint(const std::vector<meshtying::TiedInterface>& interfaces,
                  const Discretization& disc, const Model& model);
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
  /// unless the slave basis is modified). This rank contributes the rows it owns; the caller
  /// sums over ranks.
  std::vector<double> multipliers(std::size_t interface, std::span<const double> r_local) const;
  /// D_jj of a tied slave node (side-local), 0 if untied.
  double d_diagonal(std::size_t interface, std::size_t slave_node) const {
    return d_diag_[interface][slave_node];
  }

private:
  const std::vector<meshtying::TiedInterface>& interfaces_;
  const Discretization& disc_;
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
