#pragma once
// Step size control shared by the solid, dynamic and fluid-structure drivers (docs/input.md
// §6.3): steps land on the nominal times k dt; a failed step is halved and retried, the size
// grows back after success (a halving taken back with each doubling); the run gives up when a
// step fails at dt / 2^max_step_cuts.
#include "seam/common/mpi.hpp"
#include "seam/io/config.hpp"

#include <algorithm>

namespace seam::problem {

struct NewtonResult;
class Output;

class StepControl {
public:
  explicit StepControl(const io::TimeConfig& tc) : tc_(tc), dt_(tc.dt) {}
  bool running() const { return t_ < tc_.end * (1.0 - 1e-12); }
  double time() const { return t_; }
  /// The end of the next attempted step.
  double next() const;
  /// A failed attempt ending at t_new: halves the step, printing `seam: <failure> at t = T;
  /// cutting the step to dt = DT` on rank 0, and returns true; false (nothing changed) when
  /// the step has used its `max_step_cuts`.
  bool cut(const char* failure, double t_new, const Comm& comm);
  /// A failed attempt at t_new after `step` converged steps of a solid run: cut, or give up
  /// (SolverError, after summary.json).
  void fail(const NewtonResult& result, double t_new, int step, Output& out, const Comm& comm);
  /// A converged step ending at t_new.
  void accept(double t_new);
  int cuts() const { return cuts_; }
  /// What a checkpoint keeps: the time reached, the step size and the cuts in effect.
  struct State {
    double t, dt;
    int cuts;
  };
  State state() const { return {t_, dt_, cuts_}; }
  /// A restart: the step in effect, or the input's step when no cut is (a restart may change
  /// the step, Checkpoints).
  void set_state(const State& s) {
    t_ = s.t;
    dt_ = s.cuts == 0 ? tc_.dt : std::min(s.dt, tc_.dt);
    cuts_ = s.cuts;
  }

private:
  const io::TimeConfig& tc_;
  double t_ = 0.0, dt_;
  int cuts_ = 0;
};

} // namespace seam::problem
