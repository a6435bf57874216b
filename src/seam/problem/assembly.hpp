#pragma once
// Global assembly of the bulk solid: internal forces and tangent of every local cell, surface
// loads on local facets, body forces. Residual convention r = f_int - f_ext.
#include "seam/la/petsc.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"

namespace seam::problem {

struct AssemblyStatus {
  double strain_energy = 0.0; ///< of this rank's cells
  bool inverted = false;      ///< some element has det F <= 0 (the step must be cut)
};

/// Adds this rank's contributions at displacement `u` (ghosts up to date) and time t into
/// `residual` and, if given, `tangent`. Both are assembled (collective) on return. `external`,
/// if given, receives f_ext alone.
AssemblyStatus assemble(const Model& model, const Discretization& disc, const la::Vector& u,
                        double t, la::Vector& residual, la::Matrix* tangent,
                        la::Vector* external = nullptr);

/// Adds the surface and body loads at displacement u (local form) and time t to `residual`
/// (and their tangent, times `tangent_scale`, to `tangent`; f_ext to `external`). Does not
/// assemble the PETSc objects. Returns true if a load kernel met an inverted element.
bool add_loads(const Model& model, const Discretization& disc, std::span<const double> u_local,
               double t, la::Vector& residual, la::Matrix* tangent, double tangent_scale,
               la::Vector* external);

/// The consistent mass matrix of this rank's cells, added into M (assembled on return).
void assemble_mass(const Model& model, const Discretization& disc, la::Matrix& M);

/// The energy-momentum step residual's static part: the algorithmic internal force
/// f_alg(u_n, u_next) (Simo & Tarnow / Gonzalez, solid/algorithmic_force.hpp) minus the loads
/// at the midpoint configuration and time t_mid, with the tangent d/du_next. strain_energy
/// is that of u_next.
AssemblyStatus assemble_algorithmic(const Model& model, const Discretization& disc,
                                    const la::Vector& u_n, const la::Vector& u_next, double t_mid,
                                    la::Vector& residual, la::Matrix* tangent,
                                    la::Vector* external);

} // namespace seam::problem
