#pragma once
// Nonlinear elastodynamics (seed paper Sect. 4.1): generalized-alpha (Chung & Hulbert 1993)
// and the energy-momentum method (Simo & Tarnow 1992; Gonzalez 2000), with mesh tying
// condensed or as a saddle point. steps.csv receives kinetic and internal energy, external
// work, linear and angular momentum every step.
#include "seam/io/config.hpp"
#include "seam/meshtying/tied_interface.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/tying_constraint.hpp"

namespace seam::problem {

/// Runs all time steps; writes output through `out`. Throws SolverError when a step fails
/// after its cuts (everything before is written).
void run_dynamic(const io::Config& config, const Model& model, const Discretization& disc,
                 const std::vector<meshtying::TiedInterface>& tied, const TyingConstraint& tying,
                 SaddlePoint& saddle, ContactConstraint& contact, Output& out,
                 const Checkpoints& checkpoints);

} // namespace seam::problem
