#include "seam/problem/static_solver.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/solver_checkpoint.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace seam::problem {

void run_static(const io::Config& config, const Model& model, const Discretization& disc,
                const std::vector<meshtying::TiedInterface>& tied, const TyingConstraint& tying,
                SaddlePoint& saddle, ContactConstraint& contact, Output& out,
                const Checkpoints& checkpoints) {
  const auto& tc = config.time;
  NewtonSolver newton(config, model, disc, tying, saddle, contact, out);
  newton.set_constant_tangent(
      constant_tangent(model, disc, saddle.active() || contact.saddle_point()));
  parallel::mark_memory(disc.comm().get(), "matrix_allocation");
  la::Vector u = disc.make_vector();
  la::Vector u_saved = disc.make_vector();

  const double end = tc.end;
  StepControl control(tc);
  int step = 0;
  // Work of all external actions (loads and supports) on the body, trapezoidal in the
  // displacement increments; for a hyperelastic body it tends to the strain energy.
  double external_work = 0.0;
  la::Vector force_old = disc.make_vector(), force = disc.make_vector();
  la::Vector du = disc.make_vector();
  // The two states before the last one, u_{n-1} and u_{n-2}, for the initial guess; n_known
  // of them are known (the static start u_0 = 0 at t = 0 is one; a checkpoint keeps them).
  la::Vector u_older = disc.make_vector(), u_oldest = disc.make_vector();
  double t_older = 0.0, t_oldest = 0.0;
  int n_known = 0;
  if (checkpoints.restarting()) {
    const auto state = read_checkpoint(
        checkpoints, control, contact, saddle, tied, out,
        {{"u", &u}, {"force_old", &force_old}, {"u_older", &u_older}, {"u_oldest", &u_oldest}});
    step = state.step;
    external_work = state.external_work;
    t_older = state.t_older;
    t_oldest = state.t_oldest;
    n_known = state.n_known;
    newton.restore_ordering_state(state.ordering);
  } else {
    out.initial(u);
  }
  bool may_extrapolate = config.solver.newton.initial_guess == io::InitialGuess::extrapolated;
  while (control.running()) {
    const double t_new = control.next();
    const double t_old = control.time();
    u_saved.copy_from(u);
    // Initial guess: the last converged states extrapolated in t instead of u_n, by the
    // Lagrange polynomial through the last three (quadratic; linear while only two exist),
    //   u_{n+1}^0 = sum_k u_k prod_{m != k} (t_{n+1} - t_m) / (t_k - t_m),  k, m in {n-2, n-1, n}.
    // The contact search and the active set of the first iteration are then evaluated where
    // the body is about to be: slave nodes that the extrapolated motion presses into the
    // obstacle start active (lambda - c g > 0 with g < 0), so a growing or moving contact zone
    // is mostly found before the first solve instead of one or two iterations after it. On
    // the Hertz example the quadratic guess left no active-set change after the first
    // iteration where the linear one left 6 (docs/performance.md). Only the start changes:
    // the step converges to the same equilibrium.
    const bool extrapolated = may_extrapolate && n_known >= 1;
    if (extrapolated && n_known == 2) {
      const double t = t_new, t0 = t_oldest, t1 = t_older, t2 = t_old;
      const double l0 = (t - t1) * (t - t2) / ((t0 - t1) * (t0 - t2));
      const double l1 = (t - t0) * (t - t2) / ((t1 - t0) * (t1 - t2));
      const double l2 = (t - t0) * (t - t1) / ((t2 - t0) * (t2 - t1));
      u.scale(l2);
      u.axpy(l1, u_older);
      u.axpy(l0, u_oldest);
      u.update_ghosts();
    } else if (extrapolated) {
      const double ratio = (t_new - t_old) / (t_old - t_older);
      u.scale(1.0 + ratio);
      u.axpy(-ratio, u_older);
      u.update_ghosts();
    }
    const auto res =
        newton.solve(u, t_new, step + 1,
                     [&](const la::Vector& state, la::Vector& r, la::Matrix* K, la::Vector& f_ext) {
                       return assemble(model, disc, state, t_new, r, K, &f_ext);
                     });
    if (!res.converged) {
      newton.reject(u, u_saved);
      if (extrapolated) {
        // An extrapolation too far for Newton (a turning load, an inverted element): the same
        // step again from the last converged state before any cut.
        may_extrapolate = false;
        continue;
      }
      control.fail(res, t_new, step, out, disc.comm());
      continue;
    }
    may_extrapolate = config.solver.newton.initial_guess == io::InitialGuess::extrapolated;
    u_oldest.copy_from(u_older);
    t_oldest = t_older;
    u_older.copy_from(u_saved);
    t_older = t_old;
    n_known = std::min(n_known + 1, 2);
    ++step;
    du.copy_from(u);
    du.axpy(-1.0, u_saved);
    newton.total_external_force(force);
    external_work += 0.5 * (force.dot(du) + force_old.dot(du));
    force_old.copy_from(force);
    const auto reactions = newton.reactions();
    StepRecord rec;
    rec.step = step;
    rec.time = t_new;
    rec.newton_iterations = res.iterations;
    rec.residual = res.residual;
    rec.internal_energy = res.strain_energy;
    rec.external_work = external_work;
    if (contact.active()) {
      rec.active_nodes = contact.n_active();
      rec.slip_nodes = contact.n_slip();
      contact.balance();
      out.contact_state(contact.reports(u));
    }
    const bool last = t_new >= end * (1.0 - 1e-12);
    out.step(rec, u, nullptr, reactions, newton.multipliers(tied), last);
    newton.accept();
    control.accept(t_new);
    DriverState written{step, external_work, t_older, t_oldest, n_known};
    written.ordering = newton.ordering_state();
    write_checkpoint(
        checkpoints, written, control, contact, saddle, tied, out,
        {{"u", &u}, {"force_old", &force_old}, {"u_older", &u_older}, {"u_oldest", &u_oldest}});
  }
  out.finish(true, step);
}

} // namespace seam::problem
