#include "seam/problem/step_control.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace seam::problem {

double StepControl::next() const {
  double t_new = std::min(t_ + dt_, tc_.end);
  // Land exactly on the nominal times k * dt (no drift from repeated additions).
  const double k = std::round(t_new / tc_.dt);
  if (std::abs(t_new - k * tc_.dt) < 1e-9 * tc_.dt) t_new = tc_.time_at(static_cast<int>(k));
  return t_new;
}

bool StepControl::cut(const char* failure, double t_new, const Comm& comm) {
  if (cuts_ >= tc_.max_step_cuts) return false;
  ++cuts_;
  dt_ *= 0.5;
  if (comm.is_root())
    std::fprintf(stdout, "seam: %s at t = %g; cutting the step to dt = %g\n", failure, t_new, dt_);
  return true;
}

void StepControl::accept(double t_new) {
  t_ = t_new;
  if (cuts_ > 0) {
    // Grow back after a successful cut step, one halving at a time: cuts_ stays the number of
    // halvings in effect, so a later failure may halve down to dt / 2^max_step_cuts again.
    dt_ = std::min(2.0 * dt_, tc_.dt);
    cuts_ = dt_ >= tc_.dt ? 0 : cuts_ - 1;
  }
}

} // namespace seam::problem
