#pragma once
// The time left on the step lines of every kind of run (solids, fluids, fluid-structure).
#include <string>

namespace seam::problem {

/// Seconds left: the mean wall time per unit of simulated time so far (`elapsed` seconds for
/// `simulated` time) times the simulated time still to go; -1 (unknown) before any time passed.
double time_left(double elapsed, double simulated, double remaining);

/// A duration for the terminal, to the precision a user plans with: "42 s", "3 min 05 s",
/// "2 h 07 min"; "?" for an unknown (negative) duration.
std::string duration_text(double seconds);

/// The step line: "step N  t = T  newton K  residual R  wall W s  left L" (flushed).
void print_step_line(int step, double t, int newton_iterations, double residual, double wall,
                     double left);

} // namespace seam::problem
