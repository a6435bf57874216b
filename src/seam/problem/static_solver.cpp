#include "seam/problem/static_solver.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/solver_checkpoint.hpp"

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
  if (checkpoints.restarting()) {
    const auto state = read_checkpoint(checkpoints, control, contact, saddle, tied,
                                       {{"u", &u}, {"force_old", &force_old}});
    step = state.step;
    external_work = state.external_work;
  } else {
    out.initial(u);
  }
  while (control.running()) {
    const double t_new = control.next();
    u_saved.copy_from(u);
    const auto res =
        newton.solve(u, t_new, step + 1,
                     [&](const la::Vector& state, la::Vector& r, la::Matrix& K, la::Vector& f_ext) {
                       return assemble(model, disc, state, t_new, r, &K, &f_ext);
                     });
    if (!res.converged) {
      newton.reject(u, u_saved);
      control.fail(res, t_new, step, out, disc.comm());
      continue;
    }
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
    write_checkpoint(checkpoints, {step, external_work}, control, contact, saddle, tied, out,
                     {{"u", &u}, {"force_old", &force_old}});
  }
  out.finish(true, step);
}

} // namespace seam::problem
