#pragma once
// Energy-momentum contact through an impact (docs/contact_dynamics.md §5, "Penetration at the
// start of the step: the contact velocity update"). A step of the discrete-gradient contact
// force changes the energy by -sum_j lambda_j g~_j(x_n); slave nodes that start it beyond the
// other surface make it gain G = sum_j max(0, -lambda_j g~_j(x_n)). After the step G is taken
// out of the kinetic energy, the positions left as they are, in two stages that both keep the
// linear and angular momentum exactly:
// 1. an impulse along d = sum_j e_j grad g~_j(x_{n+1}), e_j = max(0, -lambda_j g~_j(x_n))
//    (Laursen & Love 2002's velocity update along the contact force; d has no resultant and
//    no moment about x_{n+1}): v <- v - mu M^-1 d, the prescribed dofs kept, at most all the
//    kinetic energy along it;
// 2. what that could not remove, from the velocity of the contact patch (the nodes of d and two
//    layers of cells around them) relative to its rigid motion: v <- v - s delta with
//    R^T M delta = 0 for the rigid motions R of the whole mesh at x_{n+1}.
#include "seam/la/petsc.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/discretization.hpp"

#include <cstdint>
#include <functional>
#include <span>

namespace seam::problem {

/// What remove_contact_gain did in a step.
struct ContactGainRemoval {
  bool acted = false;   ///< G exceeded the round-off of the energy
  double gain = 0.0;    ///< G
  int nodes = 0;        ///< slave nodes carrying more than 1e-6 of G
  double impulse = 0.0; ///< removed by stage 1
  double mu = 0.0;
  double patch = 0.0; ///< removed by stage 2
  double s = 0.0;
  std::int64_t patch_nodes = 0;
};

/// Takes up to G out of the kinetic energy of the velocity of a patch relative to its rigid
/// motion (stage 2 above): the patch is the nodes where `seed` is nonzero grown by `layers`
/// layers of cells (every node for layers < 0), without the prescribed dofs; v <- v - s delta
/// with M delta free of resultant and moment, so that both momenta are kept. Returns the
/// energy removed (less than G when the patch's relative motion holds less). Collective.
double remove_from_patch(const Discretization& disc, const la::Matrix& M,
                         std::span<const PetscInt> prescribed, const la::Vector& u,
                         const la::Vector& seed, int layers, double G, la::Vector& v,
                         std::int64_t& patch_nodes, double& s);

/// The contact velocity update after a converged energy-momentum step at displacement u with
/// velocity v (updated in place). `energy` is the scale below which G is round-off (1e-13 of
/// it); `mass_solve(b, x)` gives x = M^-1 b on the free dofs and zero on the prescribed ones
/// (b is overwritten; false on failure). Collective.
ContactGainRemoval
remove_contact_gain(const Discretization& disc, const ContactConstraint& contact,
                    const la::Matrix& M, std::span<const PetscInt> prescribed, const la::Vector& u,
                    double energy, const std::function<bool(la::Vector&, la::Vector&)>& mass_solve,
                    la::Vector& v);

} // namespace seam::problem
