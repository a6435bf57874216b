#include "seam/problem/static_solver.hpp"

#include "seam/common/error.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/saddle_point.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace seam::problem {

void run_static(const io::Config& config, const Model& model, const Discretization& disc,
                const std::vector<meshtying::TiedInterface>& tied, const TyingConstraint& tying,
                SaddlePoint& saddle, Output& out) {
  const auto& tc = config.time;
  NewtonSolver newton(config, model, disc, tying, saddle, out);
  la::Vector u = disc.make_vector();
  la::Vector u_saved = disc.make_vector();
  out.initial(u);

  const double end = tc.end;
  const double dt0 = tc.dt;
  double t = 0.0, dt = dt0;
  int step = 0, cuts = 0;
  // Work of all external actions (loads and supports) on the body, trapezoidal in the
  // displacement increments; for a hyperelastic body it tends to the strain energy.
  double external_work = 0.0;
  la::Vector force_old = disc.make_vector(), force = disc.make_vector();
  la::Vector du = disc.make_vector();
  while (t < end * (1.0 - 1e-12)) {
    double t_new = std::min(t + dt, end);
    {
      // Land exactly on the nominal times k * dt (no drift from repeated additions).
      const double k = std::round(t_new / dt0);
      if (std::abs(t_new - k * dt0) < 1e-9 * dt0) t_new = tc.time_at(static_cast<int>(k));
    }
    u_saved.copy_from(u);
    const auto res =
        newton.solve(u, t_new, step + 1,
                     [&](const la::Vector& state, la::Vector& r, la::Matrix& K, la::Vector& f_ext) {
                       return assemble(model, disc, state, t_new, r, &K, &f_ext);
                     });
    if (!res.converged) {
      u.copy_from(u_saved);
      u.update_ghosts();
      saddle.restore();
      if (cuts >= tc.max_step_cuts) {
        out.finish(false, step);
        SEAM_THROW(SolverError, res.failure, " at t = ", t_new, " after ", cuts, " step cuts; the ",
                   step, " converged steps are written in ", out.directory().string());
      }
      ++cuts;
      dt *= 0.5;
      if (disc.comm().is_root())
        std::fprintf(stdout, "seam: %s at t = %g; cutting the step to dt = %g\n", res.failure,
                     t_new, dt);
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
    const bool last = t_new >= end * (1.0 - 1e-12);
    out.step(rec, u, nullptr, reactions, newton.multipliers(tied), last);
    saddle.save();
    t = t_new;
    if (cuts > 0) {
      dt = std::min(2.0 * dt, dt0); // grow back after a successful cut step
      if (dt >= dt0) cuts = 0;
    }
  }
  out.finish(true, step);
}

} // namespace seam::problem
