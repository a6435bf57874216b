#pragma once
// Quasi-static load stepping with Newton's method and automatic step cutting: a failed step
// (no convergence, inverted element, failed linear solve) is halved and retried, and the step
// size grows back after success; the run gives up (SolverError) only when the cuts of one
// step are exhausted, after every converged step was written.
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/tying_constraint.hpp"

namespace seam::problem {

/// Runs all load steps; writes output through `out`. Throws SolverError on failure.
void run_static(const io::Config& config, const Model& model, const Discretization& disc,
                const std::vector<meshtying::TiedInterface>& tied, const TyingConstraint& tying,
                SaddlePoint& saddle, ContactConstraint& contact, Output& out,
                const Checkpoints& checkpoints);

} // namespace seam::problem
