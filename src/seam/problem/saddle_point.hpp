#pragma once
// Mesh tying as a saddle-point problem (seed paper eqs. (17)-(20)): the Lagrange multipliers
// are unknowns next to the displacements,
//     [ K   B^T ] [du]        [ r + B^T lambda ]
//     [ B   0   ] [dlambda] = -[ B u            ],   B = [D on slave dofs, -M on master dofs],
// for standard or dual multipliers. With dual multipliers on tri6/quad8 (modified slave basis,
// d_S = T d~_S) the slave block of B is D T^{-1}. The augmented matrix is assembled as a nested
// matrix and converted to AIJ for the direct solver; on every rank the rows are its displacement
// dofs followed by its multiplier dofs (one per tied slave node and component, owned with the
// node).
#include "seam/la/petsc.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"

#include <cstdint>
#include <span>
#include <vector>

namespace seam::problem {

class SaddlePoint {
public:
  SaddlePoint(const std::vector<meshtying::TiedInterface>& interfaces, const Discretization& disc,
              const Model& model);
  ~SaddlePoint();
  SaddlePoint(const SaddlePoint&) = delete;
  SaddlePoint& operator=(const SaddlePoint&) = delete;

  bool active() const { return active_; }
  /// r += B^T lambda (the interface forces).
  void add_interface_forces(la::Vector& r) const;
  /// ||B u||: the constraint residual.
  double constraint_norm(const la::Vector& u);
  /// Solves the linearized saddle-point system for du (and updates lambda). `minus_r` is
  /// -(r + B^T lambda) with zero Dirichlet rows; `dirichlet` are the fixed displacement dofs;
  /// `g`, if given, their prescribed increments. Returns false if the linear solver failed.
  bool solve(const la::Matrix& K, const la::Vector& minus_r, const la::Vector& u,
             const std::vector<PetscInt>& dirichlet, const la::Vector* g, la::LinearSolver& solver,
             la::Vector& du);
  /// Keeps the multipliers of the last converged state (restore after a failed step).
  void save();
  void restore();
  /// lambda of interface k per slave node (dim values each), on every rank (collective); of a
  /// distributed interface, those of the slave nodes this rank owns (zero elsewhere).
  std::vector<double> multipliers(std::size_t k) const;
  /// Sets lambda (and the saved copy) of every interface from values per slave node as
  /// multipliers() returns them (a restart).
  void set_multipliers(const std::vector<std::vector<double>>& values);
  /// The multipliers of interface k that this rank owns (checkpoints: no rank gathers them):
  /// keys (the slave node's id in the mesh as read times dim plus the component) and values.
  void owned_multipliers(std::size_t k, std::vector<std::int64_t>& keys,
                         std::vector<double>& values) const;
  /// Sets them (and the saved copy) from values in the order of owned_multipliers' keys.
  void set_owned_multipliers(std::size_t k, std::span<const double> values);

private:
  struct LmDof {
    std::size_t interface;
    std::size_t slave_node;
    int component;
  };
  const std::vector<meshtying::TiedInterface>& interfaces_;
  const Discretization& disc_;
  bool active_ = false;
  PetscInt n_lm_ = 0;                  ///< owned multiplier dofs
  PetscInt first_lm_ = 0;              ///< first owned multiplier dof (multiplier numbering)
  PetscInt aug_offset_ = 0;            ///< augmented index = displacement dof + aug_offset_ (owned)
  std::vector<LmDof> lm_dofs_;         ///< owned, in local order
  std::vector<PetscInt> all_first_lm_; ///< per rank
  Mat B_ = nullptr, BT_ = nullptr;
  la::Vector lambda_, lambda_saved_, constraint_;
};

} // namespace seam::problem
