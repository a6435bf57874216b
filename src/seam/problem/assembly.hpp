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

} // namespace seam::problem
