#include "seam/problem/static_solver.hpp"

#include "seam/common/error.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/saddle_point.hpp"

#include <cmath>
#include <cstdio>
#include <limits>

namespace seam::problem {

namespace {

/// g = (prescribed values at time t) - u on the Dirichlet dofs, 0 elsewhere. Returns whether
/// any rank has a nonzero prescribed increment.
bool dirichlet_increment(const Model& model, const Discretization& disc, const la::Vector& u,
                         double t, la::Vector& g) {
  bool nonzero = false;
  {
    la::Vector::LocalView gv(g, true);
    la::Vector::LocalView uv(u, false);
    auto gl = gv.values();
    const auto ul = uv.values();
    std::fill(gl.begin(), gl.end(), 0.0);
    const auto& x = disc.mesh().x;
    const int dim = disc.dim();
    const PetscInt first = disc.first_owned_dof();
    for (const auto& d : model.dirichlet) {
      const double* p = &x[static_cast<std::size_t>(d.node) * dim];
      const auto i = d.dof - first;
      gl[i] = model.dirichlet_values[d.expression](t, p[0], p[1], dim == 3 ? p[2] : 0.0) - ul[i];
      nonzero = nonzero || gl[i] != 0.0;
    }
  }
  return disc.comm().any(nonzero);
}

/// Zeroes the Dirichlet rows of r (they hold the reactions, kept in the full residual).
void zero_dirichlet_rows(const Model& model, const Discretization& disc, la::Vector& r) {
  la::Vector::LocalView view(r, true);
  auto v = view.values();
  const PetscInt first = disc.first_owned_dof();
  for (const auto& d : model.dirichlet) v[d.dof - first] = 0.0;
}

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
  double strain_energy = 0.0;
  const char* failure = "";
};

class NewtonSolver {
public:
  NewtonSolver(const io::Config& config, const Model& model, const Discretization& disc,
               const TyingConstraint& tying, SaddlePoint& saddle, Output& out)
      : config_(config), model_(model), disc_(disc), tying_(tying), saddle_(saddle), out_(out),
        K_(disc.make_matrix()), r_(disc.make_vector()), r_full_(disc.make_vector()),
        rt_(disc.make_vector()), du_(disc.make_vector()), dut_(disc.make_vector()),
        g_(disc.make_vector()), f_ext_(disc.make_vector()),
        solver_(disc.comm().get(), config.solver.linear == io::LinearSolverKind::direct
                                       ? la::SolverKind::direct
                                       : la::SolverKind::iterative) {
    for (const auto& d : model_.dirichlet) dirichlet_rows_.push_back(d.dof);
    // Rows fixed in the Newton system: Dirichlet dofs and (with condensed tying) the
    // eliminated slave dofs, whose rows of T^T K T are empty.
    fixed_rows_ = dirichlet_rows_;
    if (tying.active())
      fixed_rows_.insert(fixed_rows_.end(), tying.eliminated_dofs().begin(),
                         tying.eliminated_dofs().end());
    if (config.solver.linear == io::LinearSolverKind::iterative)
      K_.set_near_null_space(disc.coordinates_vector());
  }

  /// Newton iterations at time t from the last converged u. The first iteration is the
  /// predictor: it is linearized at the old state and carries the increment of the prescribed
  /// displacements as an inhomogeneous constraint, so the interior follows the moving
  /// boundary instead of being left behind (which would invert the elements next to it).
  NewtonResult solve(la::Vector& u, double t, int step) {
    NewtonResult res;
    const auto& nc = config_.solver.newton;
    double reference = 0.0;
    const bool moving_boundary = dirichlet_increment(model_, disc_, u, t, g_);
    for (int it = 0; it <= nc.max_iterations; ++it) {
      AssemblyStatus status;
      {
        ScopedTimer timer(out_.timers(), "assembly");
        status = assemble(model_, disc_, u, t, r_, &K_, &f_ext_);
      }
      if (disc_.comm().any(status.inverted)) {
        res.failure = "an element is inverted (det F <= 0)";
        return res;
      }
      if (saddle_.active()) saddle_.add_interface_forces(r_);
      // The Newton system: condensed by T when mesh tying is condensed, else K and r as they are.
      la::Matrix* K_sys = &K_;
      la::Vector* r_sys = &r_;
      la::Vector* d_sys = &du_;
      if (tying_.active()) {
        ScopedTimer timer(out_.timers(), "mortar");
        tying_.condense_matrix(K_, Kt_);
        tying_.condense_vector(r_, rt_);
        K_sys = &Kt_;
        r_sys = &rt_;
        d_sys = &dut_;
      }
      const double full_norm = r_sys->norm();
      r_full_.copy_from(*r_sys);
      zero_dirichlet_rows(model_, disc_, *r_sys);
      double norm = r_sys->norm();
      if (saddle_.active()) norm = std::hypot(norm, saddle_.constraint_norm(u));
      if (!std::isfinite(norm) || !std::isfinite(full_norm)) {
        res.failure = "the residual is not finite";
        return res;
      }
      // Relative residual: against the first residual of the step and the force level of
      // the system (reactions and external loads), so that a step with a tiny increment is
      // not asked to go below round-off.
      // After a predictor the reference is taken from the first corrector, whose residual
      // reflects the prescribed motion.
      const bool predictor = it == 0 && moving_boundary;
      if (it == 0 || (it == 1 && moving_boundary))
        reference = std::max({reference, norm, full_norm, f_ext_.norm()});
      // Or the last correction was negligible against the displacement: on stiff, badly
      // conditioned systems the residual stagnates at the linear solver's round-off level
      // above tol * reference while the state no longer changes.
      const bool small_increment =
          it >= 2 && last_increment_ <= nc.tolerance * std::max(u.norm(), 1e-300);
      const bool converged =
          !predictor && (norm <= nc.tolerance * reference || reference == 0.0 || small_increment);
      out_.newton({step, it, norm, it == 0 ? 0.0 : last_increment_, 0});
      res.residual = reference > 0 ? norm / reference : 0.0;
      res.iterations = it;
      res.strain_energy = disc_.comm().sum(status.strain_energy);
      if (converged) {
        res.converged = true;
        return res;
      }
      if (it == nc.max_iterations) break;
      r_sys->scale(-1.0);
      bool solved;
      if (saddle_.active()) {
        ScopedTimer timer(out_.timers(), "linear_solve");
        solved = saddle_.solve(K_, r_, u, dirichlet_rows_, predictor ? &g_ : nullptr, solver_, du_);
      } else {
        K_sys->zero_rows_columns(fixed_rows_, predictor ? &g_ : nullptr,
                                 predictor ? r_sys : nullptr);
        ScopedTimer timer(out_.timers(), "linear_solve");
        d_sys->zero();
        solved = solver_.solve(*K_sys, *r_sys, *d_sys);
      }
      if (solved && tying_.active()) tying_.expand(dut_, du_);
      if (!solved) {
        res.failure = "the linear solver failed";
        return res;
      }
      last_increment_ = du_.norm();
      u.axpy(1.0, du_);
      if (predictor) {
        // The constrained rows of the solve return the prescribed increment up to round-off;
        // make the prescribed values exact.
        dirichlet_increment(model_, disc_, u, t, g_);
        u.axpy(1.0, g_);
      }
      u.update_ghosts();
    }
    res.failure = "Newton's method did not converge";
    return res;
  }

  /// Reaction force per reaction region (dim values each), summed over ranks: the full
  /// residual f_int - f_ext at the region's nodes.
  std::vector<double> reactions() const {
    const int dim = disc_.dim();
    std::vector<double> out(model_.reaction_regions.size() * dim, 0.0);
    la::Vector::LocalView view(r_full_, false);
    const auto r = view.values();
    for (std::size_t k = 0; k < model_.reaction_regions.size(); ++k)
      for (auto n : model_.reaction_regions[k].owned_nodes)
        for (int c = 0; c < dim; ++c) out[k * dim + c] += r[disc_.local_dof(n, c)];
    disc_.comm().sum_in_place(out);
    return out;
  }

  /// All forces the surroundings exert on the body at the last evaluation: applied loads plus
  /// support reactions, f_ext + (f_int - f_ext) = f_int at equilibrium.
  void total_external_force(la::Vector& out) const {
    out.copy_from(f_ext_);
    out.axpy(1.0, r_full_);
  }

  /// The Lagrange multipliers of every mesh-tying interface (per slave node, dim values), on
  /// every rank: unknowns of the saddle-point system, or recovered from the slave rows of the
  /// residual before condensation, lambda = -r_S / D_SS. Collective.
  std::vector<std::vector<double>>
  multipliers(const std::vector<meshtying::TiedInterface>& tied) const {
    std::vector<std::vector<double>> out;
    la::Vector::LocalView r_view(r_, false);
    for (std::size_t k = 0; k < tied.size(); ++k) {
      if (tied[k].strategy == io::Strategy::saddle_point) {
        out.push_back(saddle_.multipliers(k));
      } else {
        out.push_back(tying_.multipliers(k, r_view.values()));
        disc_.comm().sum_in_place(out.back());
      }
    }
    return out;
  }

private:
  const io::Config& config_;
  const Model& model_;
  const Discretization& disc_;
  const TyingConstraint& tying_;
  SaddlePoint& saddle_;
  Output& out_;
  la::Matrix K_, Kt_;
  la::Vector r_, r_full_, rt_, du_, dut_, g_, f_ext_;
  std::vector<PetscInt> fixed_rows_;
  la::LinearSolver solver_;
  std::vector<PetscInt> dirichlet_rows_;
  double last_increment_ = 0.0;
};

} // namespace

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
    const auto res = newton.solve(u, t_new, step + 1);
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
