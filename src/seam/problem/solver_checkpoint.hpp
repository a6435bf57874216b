#pragma once
// The state the static and dynamic drivers keep from step to step, written to a checkpoint
// after a converged step and read back at a restart (checkpoint.hpp): step control, the step
// count, the accumulated external work, named vectors (displacement, velocity, acceleration,
// the last step's force), the contact state and the saddle-point multipliers, and the output
// counters.
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"

#include <utility>
#include <vector>

namespace seam::problem {

/// What the drivers carry from step to step besides vectors.
struct DriverState {
  int step = 0;
  double external_work = 0.0;
  /// Static runs: the times of the converged states before the last one that the initial
  /// guess extrapolates from, and how many of them are known (0 to 2; static_solver.cpp).
  double t_older = 0.0, t_oldest = 0.0;
  int n_known = 0;
  /// Dynamic runs with generalized-alpha's energy bound at impacts: whether the impact's
  /// transient (from the first active node through the release's ringing) still lasts.
  bool impact_transient = false;
  /// The linear solver's ordering choice (NewtonSolver::ordering_state); empty: none recorded.
  std::vector<double> ordering = {};
};

/// Writes checkpoint_NNNNN/ after converged step `state.step` if one is due. Collective.
void write_checkpoint(const Checkpoints& checkpoints, const DriverState& state,
                      const StepControl& control, const ContactConstraint& contact,
                      const SaddlePoint& saddle, const std::vector<meshtying::TiedInterface>& tied,
                      const Output& out,
                      const std::vector<std::pair<const char*, const la::Vector*>>& vectors);

/// Restores everything write_checkpoint wrote from the restart checkpoint; what the terminal
/// should say of it goes to out.note(). Collective.
DriverState read_checkpoint(const Checkpoints& checkpoints, StepControl& control,
                            ContactConstraint& contact, SaddlePoint& saddle,
                            const std::vector<meshtying::TiedInterface>& tied, const Output& out,
                            const std::vector<std::pair<const char*, la::Vector*>>& vectors);

} // namespace seam::problem
