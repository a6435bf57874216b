#include "seam/problem/newton.hpp"

#include "seam/common/error.hpp"
#include "seam/fem/cell.hpp"
#include "seam/mesh/facets.hpp"
#include "seam/parallel/memory_trace.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace seam::problem {

namespace {
// A correction below this fraction of |X + u| is round-off: a few hundred ulps.
constexpr double roundoff_increment = 256 * std::numeric_limits<double>::epsilon();
// Near the solution Newton divides the residual by orders of magnitude per iteration; one that
// keeps more than this fraction of the last residual has stopped decreasing.
constexpr double stagnation_ratio = 0.25;
// No floor lies this high: a residual that stagnates above it is a failure, not round-off.
constexpr double max_floor_residual = 1e-8;
// Line search on contact corrections (NewtonSolver::solve): a correction shortened to alpha
// must reduce the residual norm by the fraction sufficient_decrease * alpha (Armijo's rule,
// Armijo 1966, on the residual norm); alpha is halved down to min_step, which is then taken
// as it is.
constexpr double sufficient_decrease = 1e-4;
constexpr double min_step = 1.0 / 16.0;
// A correction whose trial point is unusable (an inverted element, a residual that is not
// finite) is halved until it is usable and reduces the residual, down to this fraction; the
// attempt then fails. Shorter corrections only creep (a 2D ironing step taken in full: 1/1024
// of a correction per iteration and no convergence).
constexpr double min_usable_step = min_step;
} // namespace

/// g = (prescribed values at time t) - u on the Dirichlet dofs, 0 elsewhere. Returns whether
/// any rank has a nonzero prescribed increment.
bool dirichlet_increment(const Model& model, const Discretization& disc, const la::Vector& u,
                         double t, la::Vector& g) {
  bool nonzero = false;
  int bad = -1; // the first expression whose value is not finite
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
      const double value =
          model.dirichlet_values[d.expression](t, p[0], p[1], dim == 3 ? p[2] : 0.0);
      if (!std::isfinite(value) && bad < 0) bad = d.expression;
      gl[i] = value - ul[i];
      nonzero = nonzero || gl[i] != 0.0;
    }
  }
  // A value that is not finite (1/0, sqrt(-1)) is an input error at the condition, on every rank.
  const int first_bad = disc.comm().max(bad);
  if (first_bad >= 0) {
    char when[32];
    std::snprintf(when, sizeof when, "%.6g", t);
    const auto k = static_cast<std::size_t>(first_bad);
    io::fail_at(model.dirichlet_marks[k], "the Dirichlet value '" +
                                              model.dirichlet_values[k].source() +
                                              "' is not finite at t = " + when);
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

bool constant_tangent(const Model& model, const Discretization& disc, bool saddle_point) {
  const bool linear =
      std::all_of(model.materials.begin(), model.materials.end(),
                  [](const auto& m) { return m.model == solid::MaterialModel::linear_elastic; });
  const bool follower =
      std::any_of(model.surface_loads.begin(), model.surface_loads.end(),
                  [](const SurfaceLoad& l) { return l.type == io::BoundaryType::pressure; });
  return !saddle_point && linear && !disc.comm().any(follower);
}

double boundary_node_fraction(const Discretization& disc) {
  // The ghost layer holds every cell around an owned node, so a facet through an owned node is
  // exterior on this rank exactly when it is exterior in the whole mesh.
  const auto& mesh = disc.mesh();
  std::vector<char> on_boundary(static_cast<std::size_t>(mesh.n_nodes()), 0);
  const auto facets = mesh::exterior_facets(mesh);
  for (std::int32_t f = 0; f < facets.size(); ++f) {
    const auto c = facets.cell[static_cast<std::size_t>(f)];
    const auto nodes = mesh.cell(c);
    for (const int k :
         fem::facet_nodes(mesh.cell_type[c], facets.local[static_cast<std::size_t>(f)]))
      on_boundary[static_cast<std::size_t>(nodes[k])] = 1;
  }
  std::int64_t count = 0;
  for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
    if (on_boundary[static_cast<std::size_t>(n)] && disc.owns_node(n)) ++count;
  const auto total = disc.n_global_nodes();
  return total > 0 ? static_cast<double>(disc.comm().sum(count)) / static_cast<double>(total) : 0.0;
}

namespace {

LinearSolverChoice solid_linear_solver(const io::Config& config, const Discretization& disc,
                                       bool saddle_point) {
  const auto dofs = disc.n_global_dofs();
  // The share of boundary nodes decides only between the two thresholds of `auto`.
  const bool between = config.solver.linear == io::LinearSolverKind::automatic && disc.dim() == 3 &&
                       !saddle_point && dofs >= auto_iterative_compact_dofs &&
                       dofs < auto_iterative_dofs;
  return choose_linear_solver(config.solver.linear, disc.dim(), dofs,
                              saddle_point ? SystemKind::saddle_point : SystemKind::solid,
                              between ? boundary_node_fraction(disc) : 1.0);
}

} // namespace

la::SolverKind linear_solver_kind(const io::Config& config, const Discretization& disc,
                                  bool saddle_point) {
  return solid_linear_solver(config, disc, saddle_point).kind;
}

std::string describe_linear_solver(const io::Config& config, const Discretization& disc,
                                   bool saddle_point) {
  if (saddle_point)
    return describe(solid_linear_solver(config, disc, true),
                    "FGMRES + Schur fieldsplit: GAMG, selfp ILU(0)");
  return describe(solid_linear_solver(config, disc, false));
}

bool NewtonSolver::expect_convergence(int it, double tolerance, double reference) const {
  if (it < 2 || constant_tangent_ || saddle_.active() || tying_.active() ||
      contact_.saddle_point() || last_changes_ != 0 || !(older_norm_ > 0.0))
    return false;
  return last_norm_ * last_norm_ / older_norm_ <= 0.1 * tolerance * reference;
}

const char* NewtonSolver::evaluate_state(const la::Vector& u, double t, bool first, bool retrial,
                                         const Evaluator& evaluate, State& state, bool tangent) {
  {
    ScopedTimer timer(out_.timers(), "assembly");
    // A constant tangent keeps the one of the first iteration. The plain system may zero the
    // fixed rows and columns of K_ itself: doing that again changes nothing.
    const bool keep = (constant_tangent_ && !first) || !tangent;
    state.assembly = evaluate(u, r_, keep ? nullptr : &K_, f_ext_);
    tangent_current_ = tangent || constant_tangent_;
  }
  parallel::mark_memory(disc_.comm().get(), "first_assembly", true);
  if (disc_.comm().any(state.assembly.inverted)) return "an element is inverted (det F <= 0)";
  if (saddle_.active()) saddle_.add_interface_forces(r_);
  state.changes = 0;
  state.status_changes = 0;
  if (contact_.active()) {
    state.changes = contact_.evaluate(u, t, first, out_.timers(), retrial);
    // A folded contact surface is an unusable iterate, as an inverted element is.
    if (const auto node = contact_.folded_node(); node >= 0) {
      // Its text is read through the pointer returned (the line search keeps that of the full
      // correction while it evaluates shorter ones): the capacity holds any such message, so
      // the buffer is never moved once it was returned.
      const std::string message =
          ::seam::detail::concat("the contact surface folds back onto itself at slave node ", node,
                                 " (the normals of its facets cancel)");
      failure_.reserve(256);
      failure_.assign(message.data(), message.size());
      return failure_.c_str();
    }
    state.status_changes = state.changes - contact_.n_inconsistent();
    state.decided = true;
    if (state.changes != 0) statuses_changed_ = true;
  }
  // The Newton system: condensed by T when mesh tying is condensed, else K and r as they are.
  la::Vector* r_sys = &r_;
  if (tying_.active()) {
    ScopedTimer timer(out_.timers(), "mortar");
    tying_.condense_matrix(K_, Kt_);
    tying_.condense_vector(r_, rt_);
    r_sys = &rt_;
  }
  if (contact_.active()) {
    // The residual with the contact forces of the current multipliers, and the
    // complementarity residual; the system itself is condensed by the caller.
    r_full_.copy_from(r_);
    contact_.add_force(r_full_);
    state.full_norm = r_full_.norm();
    rt_.copy_from(r_full_);
    zero_dirichlet_rows(model_, disc_, rt_);
    state.norm = std::hypot(rt_.norm(), contact_.complementarity_norm());
  } else {
    state.full_norm = r_sys->norm();
    r_full_.copy_from(*r_sys);
    zero_dirichlet_rows(model_, disc_, *r_sys);
    state.norm = r_sys->norm();
  }
  if (saddle_.active()) state.norm = std::hypot(state.norm, saddle_.constraint_norm(u));
  if (!std::isfinite(state.norm) || !std::isfinite(state.full_norm))
    return "the residual is not finite";
  return "";
}

NewtonResult NewtonSolver::solve(la::Vector& u, double t, int step, const Evaluator& evaluate) {
  NewtonResult res;
  const auto& nc = config_.solver.newton;
  double reference = 0.0;
  const bool moving_boundary = dirichlet_increment(model_, disc_, u, t, g_);
  int stalled = 0;     // consecutive converged iterations changed only by frozen frictional nodes
  bool search = false; // the last correction may be shortened (line search)
  solver_.rebuild_preconditioner();
  statuses_changed_ = true;
  for (int it = 0; it <= nc.max_iterations; ++it) {
    State state;
    // The evaluation that ends a step needs no tangent: where convergence is expected, the
    // residual alone, and the tangent after all if the iterate does not converge.
    const char* failure = evaluate_state(u, t, it == 0, false, evaluate, state,
                                         !expect_convergence(it, nc.tolerance, reference));
    // Relative residual: against the first residual of the step and the force level of
    // the system (reactions and external loads), so that a step with a tiny increment is
    // not asked to go below round-off.
    // After a predictor the reference is taken from the first corrector, whose residual
    // reflects the prescribed motion.
    const bool predictor = it == 0 && moving_boundary;
    if (!*failure && (it == 0 || (it == 1 && moving_boundary)))
      reference = std::max({reference, state.norm, state.full_norm, f_ext_.norm()});
    // Or the residual has reached its round-off floor: the tolerance lies below what the
    // arithmetic resolves (the floor grows with |u| and, in dynamics, with M/dt^2, so a step
    // cut would only raise it). Either the last correction was within the tolerance of |u|
    // (on stiff, badly conditioned systems the residual stagnates at the linear solver's
    // round-off while the state no longer changes), or it was a few hundred ulps of the
    // current configuration X + u and the residual no longer falls, where Newton's quadratic
    // convergence would divide it by orders of magnitude.
    struct Convergence {
      double solution = 0.0;
      bool meets_tolerance = false, at_floor = false, converged = false;
    };
    const auto assess = [&](const State& s) {
      Convergence c;
      c.solution = u.norm() + reference_coordinates_;
      const bool negligible_increment = it >= 2 && last_increment_ <= nc.tolerance * u.norm();
      const bool roundoff = it >= 2 && last_increment_ <= roundoff_increment * c.solution &&
                            s.norm > stagnation_ratio * last_norm_ &&
                            s.norm <= max_floor_residual * reference;
      c.meets_tolerance = s.norm <= nc.tolerance * reference || reference == 0.0;
      c.at_floor = !c.meets_tolerance && (negligible_increment || roundoff);
      c.converged = !predictor && s.changes == 0 && (c.meets_tolerance || c.at_floor);
      return c;
    };
    Convergence conv;
    if (search) {
      // Backtracking of the last correction (docs/input.md §6.1). A trial point that is
      // unusable (an element inverted, a residual that is not finite) is never taken: if the
      // full correction's is, the correction is halved (the multipliers with it), whatever
      // statuses it changes, until its trial point is usable and reduces the residual norm by
      // the fraction sufficient_decrease * alpha, down to min_usable_step (else the attempt
      // fails). Otherwise, at a usable point where the statuses it was
      // computed with still hold and the residual norm did not fall by the fraction
      // sufficient_decrease * alpha, the correction is halved further and the statuses are
      // decided again there, down to min_step; a trial point at which a status changes ends
      // the search, so status-changing corrections go in full (or as far as they stay usable),
      // as the semi-smooth Newton method has them. Not below the residual where round-off
      // floors lie (§6.1).
      const char* full_failure = failure;
      const double full_norm = state.norm;
      double alpha = 1.0;
      for (;;) {
        if (!*failure) {
          conv = assess(state);
          const bool armijo = state.norm <= (1.0 - sufficient_decrease * alpha) * last_norm_;
          if (*full_failure) {
            // The full correction left the region where Newton's model holds: a shortened one
            // is taken only where it reduces the residual, status changes or not.
            if (armijo || conv.converged) break;
          } else {
            const bool decreased = state.status_changes != 0 || conv.converged ||
                                   state.norm <= max_floor_residual * reference || armijo;
            if (decreased || alpha <= min_step) break;
          }
        }
        if (alpha <= min_usable_step) {
          // No usable point reduces the residual: the attempt fails as the full correction did.
          if (*full_failure) failure = full_failure;
          break;
        }
        // The statuses decided at this trial point stand for the iteration until replaced.
        const bool retrial = state.decided;
        alpha *= 0.5;
        u.copy_from(u_base_);
        u.axpy(alpha, du_);
        u.update_ghosts();
        for (std::size_t i = 0; i < lambda_trial_.size(); ++i)
          lambda_trial_[i] = lambda_base_[i] + alpha * (lambda_full_[i] - lambda_base_[i]);
        contact_.set_multipliers(lambda_trial_);
        last_increment_ = alpha * full_increment_;
        state = State{};
        failure = evaluate_state(u, t, false, retrial, evaluate, state);
      }
      if (alpha < 1.0 && logging_) {
        char line[240];
        if (*full_failure)
          std::snprintf(line, sizeof line,
                        "step %5d  iteration %3d  line search: correction shortened to %g "
                        "(residual %9.3e; with the full correction %s; %9.3e before)",
                        step, it, alpha, *failure ? std::nan("") : state.norm, full_failure,
                        last_norm_);
        else
          std::snprintf(line, sizeof line,
                        "step %5d  iteration %3d  line search: correction shortened to %g "
                        "(residual %9.3e, %9.3e with the full correction, %9.3e before)",
                        step, it, alpha, state.norm, full_norm, last_norm_);
        out_.note(line);
      }
    }
    if (*failure) {
      res.failure = failure;
      return res;
    }
    if (!search) conv = assess(state);
    // Frictional nodes frozen by the cycling guard whose status holds its condition in neither
    // stick nor slip (beyond the hysteresis band) count as changes. Once they are the only
    // changes left at a converged residual, nothing can change any more in this step (their
    // statuses stay frozen): after three such iterations the step is cut instead of iterating
    // up to the limit.
    const int changes = state.changes;
    const double norm = state.norm;
    const bool frozen_only =
        changes > 0 && contact_.active() && changes == contact_.n_inconsistent();
    stalled = frozen_only && (conv.meets_tolerance || conv.at_floor) ? stalled + 1 : 0;
    if (logging_) out_.newton({step, it, norm, it == 0 ? 0.0 : last_increment_, changes});
    if (logging_ && contact_.active() && trace_contact())
      for (const auto& line : contact_.trace())
        out_.note(::seam::detail::concat("step ", step, "  iteration ", it, "  ", line));
    if (const int released = contact_.active() ? contact_.n_released() : 0;
        logging_ && released > 0) {
      char line[200];
      std::snprintf(line, sizeof line,
                    "step %5d  iteration %3d  contact: %d node(s) held active by the cycling guard "
                    "had no pair (D_jj = 0) and were released",
                    step, it, released);
      out_.note(line);
    }
    older_norm_ = it == 0 ? 0.0 : last_norm_;
    last_norm_ = norm;
    last_changes_ = changes;
    res.residual = reference > 0 ? norm / reference : 0.0;
    res.iterations = it;
    res.strain_energy = disc_.comm().sum(state.assembly.strain_energy);
    if (conv.converged) {
      if (conv.at_floor)
        out_.warning(::seam::detail::concat(
            "step ", step, " at t = ", t, ": relative residual ", res.residual,
            " stays above the tolerance ", nc.tolerance, " while the last increment is ",
            last_increment_ / conv.solution, " of the solution (round-off floor); step accepted"));
      if (const int on_cone = contact_.n_on_cone(); on_cone > 0)
        out_.warning(::seam::detail::concat(
            "step ", step, " at t = ", t, ": ", on_cone,
            " frictional node(s) alternated between stick and slip and were accepted on their "
            "friction cone within 0.1 % of the bound (stick/slip hysteresis band)"));
      res.converged = true;
      return res;
    }
    if (stalled >= 3) {
      res.failure = "frictional nodes frozen between stick and slip hold neither status";
      return res;
    }
    search = false;
    if (it == nc.max_iterations) break;
    // Inexact Newton: the Krylov solve needs to reduce its residual only to 1e-2 of the
    // residual Newton stops at (tolerance times the reference), which leaves the quadratic
    // convergence and the iteration count as they are (Eisenstat & Walker 1996 choose the
    // forcing term from the residual decrease; here it is bounded by the target instead).
    // Between 1e-10 (the exact solve of `linear: iterative`) and 1e-3; -ksp_rtol overrides.
    // A predictor's right-hand side carries the prescribed motion, not the residual: exact.
    // The direct solver takes it for its GMRES over a kept factorization (not below 1e-13).
    solver_.set_relative_tolerance(
        predictor || norm <= 0.0 ? 1e-10
                                 : std::clamp(1e-2 * nc.tolerance * reference / norm, 1e-10, 1e-3));
    if (contact_.saddle_point()) {
      // Standard multipliers: displacements and multipliers together (contact_constraint.hpp).
      rt_.copy_from(r_);
      zero_dirichlet_rows(model_, disc_, rt_);
      rt_.scale(-1.0);
      const bool check = logging_ && check_requested(step, it);
      const auto lambda_old = check ? contact_.multipliers() : std::vector<double>();
      search = line_search_ && !predictor;
      if (search) {
        u_base_.copy_from(u);
        lambda_base_ = contact_.multipliers();
      }
      if (!contact_.solve_saddle_point(K_, rt_, dirichlet_rows_, predictor ? &g_ : nullptr, solver_,
                                       du_, out_.timers())) {
        res.failure = "the linear solver failed";
        return res;
      }
      count_linear_solve();
      if (!predictor) zero_dirichlet_rows(model_, disc_, du_);
      if (check) check_correction(u, t, step, it, evaluate, lambda_old);
      if (search) {
        // The solve returns the new multipliers, not their correction.
        lambda_full_ = contact_.multipliers();
        lambda_trial_.resize(lambda_full_.size());
      }
      apply_increment(u, t, predictor);
      full_increment_ = last_increment_;
      continue;
    }
    if (!tangent_current_) {
      // Convergence was expected at this iterate: its tangent now (the same residual with it).
      ScopedTimer timer(out_.timers(), "assembly");
      evaluate(u, r_, &K_, f_ext_);
      if (!contact_.active()) zero_dirichlet_rows(model_, disc_, r_);
      tangent_current_ = true;
    }
    la::Matrix* K_sys = tying_.active() ? &Kt_ : &K_;
    la::Vector* r_sys = tying_.active() ? &rt_ : &r_;
    la::Vector* d_sys = tying_.active() ? &dut_ : &du_;
    if (contact_.active()) {
      contact_.condense(K_, r_, Kt_, rt_, out_.timers());
      zero_dirichlet_rows(model_, disc_, rt_);
      K_sys = &Kt_;
      r_sys = &rt_;
    }
    parallel::mark_memory(disc_.comm().get(), "first_condensation", true);
    r_sys->scale(-1.0);
    bool solved;
    if (saddle_.active()) {
      ScopedTimer timer(out_.timers(), "linear_solve");
      solved = saddle_.solve(K_, r_, u, dirichlet_rows_, predictor ? &g_ : nullptr, solver_, du_);
    } else {
      K_sys->zero_rows_columns(fixed_rows_, predictor ? &g_ : nullptr, predictor ? r_sys : nullptr);
      // GAMG needs the bulk's block size and rigid-body modes on the condensed system too.
      if (iterative_ && K_sys != &K_) K_sys->share_near_null_space(K_);
      ScopedTimer timer(out_.timers(), "linear_solve");
      d_sys->zero();
      // While no contact status has changed since the last factorization, the new tangent
      // differs from the factored one by the change of the state alone: GMRES preconditioned
      // by that factorization solves it exactly at the cost of a few triangular solves.
      solver_.allow_factor_reuse(!iterative_ && !statuses_changed_ && !predictor);
      solved = solver_.solve(*K_sys, *r_sys, *d_sys);
      if (solver_.last_solve_built()) statuses_changed_ = false;
    }
    count_linear_solve();
    if (solved && tying_.active()) tying_.expand(dut_, du_);
    // A corrector leaves the prescribed values as they are. Its constrained rows return zero
    // only up to the Krylov tolerance of an iterative solve; left in, those errors would move
    // the prescribed values in every iteration without the residual (whose constrained rows
    // hold the reactions) ever seeing it, and the step would converge to another problem.
    if (solved && !predictor) zero_dirichlet_rows(model_, disc_, du_);
    search = solved && line_search_ && !predictor;
    if (search) {
      u_base_.copy_from(u);
      lambda_base_ = contact_.multipliers();
    }
    if (solved && contact_.active()) {
      ScopedTimer timer(out_.timers(), "condensation");
      contact_.recover(K_, r_, du_);
    }
    if (!solved) {
      res.failure = "the linear solver failed";
      return res;
    }
    if (search) {
      lambda_full_ = contact_.multipliers();
      lambda_trial_.resize(lambda_full_.size());
    }
    apply_increment(u, t, predictor);
    full_increment_ = last_increment_;
  }
  res.failure = "Newton's method did not converge";
  return res;
}

void NewtonSolver::count_linear_solve() {
  if (!logging_) return;
  out_.linear_solve(solver_.last_iterations(), solver_.last_solve_built());
  out_.factorizations(solver_.symbolic_analyses(), solver_.ordering());
  if (auto note = solver_.take_ordering_note(); !note.empty()) out_.note(note);
}

void NewtonSolver::apply_increment(la::Vector& u, double t, bool predictor) {
  // The first solve has set up the preconditioner (GAMG's hierarchy) or the factorization.
  parallel::mark_memory(disc_.comm().get(), "first_linear_solve", true);
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

void StepControl::fail(const NewtonResult& result, double t_new, int step, Output& out,
                       const Comm& comm) {
  if (cut(result.failure, t_new, comm)) return;
  out.finish(false, step);
  SEAM_THROW(SolverError, result.failure, " at t = ", t_new, " after ", cuts_, " step cuts; the ",
             step, " converged steps are written in ", out.directory().string());
}

} // namespace seam::problem
