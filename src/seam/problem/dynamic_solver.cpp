#include "seam/problem/dynamic_solver.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/memory_trace.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/contact_velocity_update.hpp"
#include "seam/problem/newton.hpp"
#include "seam/problem/solver_checkpoint.hpp"

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <memory>
#include <span>
#include <string_view>

namespace seam::problem {

namespace {

/// Generalized-alpha parameters from the spectral radius at infinity (Chung & Hulbert 1993).
struct AlphaParameters {
  double alpha_m, alpha_f, beta, gamma;
  explicit AlphaParameters(double rho) {
    alpha_m = (2 * rho - 1) / (rho + 1);
    alpha_f = rho / (rho + 1);
    beta = 0.25 * (1 - alpha_m + alpha_f) * (1 - alpha_m + alpha_f);
    gamma = 0.5 - alpha_m + alpha_f;
  }
};

/// The initial velocity field from `initial_conditions` (owned dofs).
void initial_velocity(const io::Config& config, const Discretization& disc, la::Vector& v) {
  const auto& mesh = disc.mesh();
  const int dim = disc.dim();
  {
    la::Vector::LocalView view(v, true);
    auto vl = view.values();
    for (const auto& ic : config.initial_conditions) {
      const auto& region = find_region(mesh, ic.region, {0, 1, 2, 3}, "an initial condition");
      for (auto n : region.nodes) {
        if (!disc.owns_node(n)) continue;
        const double* X = &mesh.x[static_cast<std::size_t>(n) * dim];
        for (int c = 0; c < dim; ++c)
          vl[disc.local_dof(n, c)] = ic.velocity[c](0.0, X[0], X[1], dim == 3 ? X[2] : 0.0);
      }
    }
  }
  v.update_ghosts();
}

/// Linear and angular momentum of the mass M, velocity v, displacement u: p = sum_a (M v)_a,
/// L = sum_a x_a x (M v)_a with x = X + u.
void momenta(const Discretization& disc, const la::Matrix& M, const la::Vector& u,
             const la::Vector& v, la::Vector& work, std::array<double, 3>& p,
             std::array<double, 3>& L) {
  M.mult(v, work);
  const int dim = disc.dim();
  const auto& mesh = disc.mesh();
  double acc[6] = {0, 0, 0, 0, 0, 0};
  la::Vector::LocalView wv(work, false), uv(u, false);
  const auto w = wv.values();
  const auto ul = uv.values();
  const auto nodes = disc.local_nodes();
  for (std::int32_t i = 0; i < disc.n_owned_nodes(); ++i) {
    double x[3] = {0, 0, 0}, f[3] = {0, 0, 0};
    for (int c = 0; c < dim; ++c) {
      x[c] = mesh.x[static_cast<std::size_t>(nodes[i]) * dim + c] + ul[i * dim + c];
      f[c] = w[i * dim + c];
      acc[c] += f[c];
    }
    acc[3] += x[1] * f[2] - x[2] * f[1];
    acc[4] += x[2] * f[0] - x[0] * f[2];
    acc[5] += x[0] * f[1] - x[1] * f[0];
  }
  disc.comm().sum_in_place(std::span<double>(acc, 6));
  p = {acc[0], acc[1], acc[2]};
  L = {acc[3], acc[4], acc[5]};
}

/// Solves M x = b with x given at the prescribed dofs: M with their rows and columns replaced
/// by the identity, b shifted by the prescribed columns. M and the prescribed dofs are fixed for
/// the run, so that matrix is built and factorized at the first solve only; later solves reuse
/// the factorization (the persistency projection and the restart after a contact change solve
/// with it in many steps).
class FreeMassSolver {
public:
  FreeMassSolver(const Discretization& disc, const la::Matrix& M,
                 std::span<const PetscInt> prescribed)
      : M_(M), prescribed_(prescribed.begin(), prescribed.end()),
        solver_(disc.comm().get(), la::SolverKind::direct), mask_(disc.make_vector()),
        fixed_(disc.make_vector()) {
    const std::vector<double> ones(prescribed_.size(), 1.0);
    mask_.set_values(prescribed_, ones);
    mask_.assemble();
  }

  /// x from M x = b on the free dofs, x = `values` on the prescribed ones. b is overwritten.
  bool solve(const la::Vector& values, la::Vector& b, la::Vector& x) {
    if (!built_) {
      M_free_ = M_.copy();
      M_free_.zero_rows_columns(prescribed_);
      built_ = true;
    }
    const auto n = static_cast<std::size_t>(b.owned_size());
    {
      la::Vector::LocalView m(mask_, false), v(values, false), f(fixed_, true);
      for (std::size_t i = 0; i < n; ++i)
        f.values()[i] = m.values()[i] != 0.0 ? v.values()[i] : 0.0;
    }
    M_.mult(fixed_, x); // b_F -= M_FP x_P, then b_P = x_P
    b.axpy(-1.0, x);
    {
      la::Vector::LocalView m(mask_, false), f(fixed_, false), r(b, true);
      for (std::size_t i = 0; i < n; ++i)
        if (m.values()[i] != 0.0) r.values()[i] = f.values()[i];
    }
    return solver_.solve(M_free_, b, x);
  }

private:
  const la::Matrix& M_;
  std::vector<PetscInt> prescribed_;
  la::LinearSolver solver_;
  la::Vector mask_, fixed_;
  la::Matrix M_free_;
  bool built_ = false;
};

/// Persistency of the contacts that push at t_{n+1} (Laursen & Chawla 1997; Laursen & Love
/// 2002; docs/contact_dynamics.md §6): the velocity v is replaced by its projection in the mass
/// norm onto the velocities that keep the weighted gaps of the active slave nodes closed,
///   min_w 1/2 (w - v)^T M (w - v)  subject to  dg~_j/du (u) . w = 0  (j active at u),
/// i.e. w = v - M^-1 sum_j mu_j dg~_j/du, an impulse along the contact force directions (no
/// net force on two bodies: linear momentum is kept). The multipliers mu come from the contact
/// constraint itself: with the active set held, Newton finds z = argmin 1/2 |z - (u + eps v)|_M^2
/// with g~_A(z) = 0, whose contact force is f_c = eps sum_j mu_j dg~_j/du (first order in eps);
/// then w = v - M^-1 f_c / eps by a mass solve, the prescribed dofs kept. Returns false when
/// a solve failed (v is then unchanged).
bool project_onto_active_contacts(NewtonSolver& projector, FreeMassSolver& mass_solver,
                                  const ContactConstraint& contact, const la::Matrix& M,
                                  const la::Vector& u, double t, double eps, int step,
                                  la::Vector& v, la::Vector& z, la::Vector& target,
                                  la::Vector& work) {
  target.copy_from(u);
  target.axpy(eps, v);
  z.copy_from(u);
  z.update_ghosts();
  const auto res = projector.solve(
      z, t + eps, step, [&](const la::Vector& state, la::Vector& r, la::Matrix* K, la::Vector& f) {
        work.copy_from(state);
        work.axpy(-1.0, target);
        M.mult(work, r);
        if (K) {
          K->zero();
          K->axpy(1.0, M);
        }
        f.zero();
        return AssemblyStatus{};
      });
  if (!res.converged) return false;
  // The impulse -f_c / eps, taken by the free dofs.
  target.zero();
  contact.add_force(target);
  target.scale(-1.0 / eps);
  z.zero();
  if (!mass_solver.solve(z, target, work)) return false;
  v.axpy(1.0, work);
  v.update_ghosts();
  return true;
}

/// The contact velocity update of a step (contact_velocity_update.hpp) on the terminal, and a
/// warning for what it could not remove.
void log_contact_gain(const ContactGainRemoval& r, int step, double t, const Output& out) {
  char line[400];
  std::snprintf(line, sizeof line,
                "step %5d  contact velocity update: energy %.4e gained at %d slave node(s) that "
                "started the step beyond the other surface or were held active in tension; "
                "removed %.4e by the impulse "
                "(mu = %.4e), %.4e from the patch of %lld nodes (s = %.4e)",
                step, r.gain, r.nodes, r.impulse, r.mu, r.patch,
                static_cast<long long>(r.patch_nodes), r.s);
  out.note(line);
  const double left = r.gain - r.impulse - r.patch;
  if (left > 1e-9 * r.gain)
    out.warning(::seam::detail::concat("step ", step, " at t = ", t,
                                       ": the contact velocity update could not remove ", left,
                                       " of the energy ", r.gain,
                                       " the step gained through contact (no kinetic energy "
                                       "left in the contact patch's deformation)"));
}

/// The energy bound of a generalized-alpha step at an impact on the terminal, and a warning for
/// what it could not remove.
void log_energy_bound(double gain, double patch, std::int64_t patch_nodes, double whole, int step,
                      double t, const Output& out) {
  char line[300];
  std::snprintf(line, sizeof line,
                "step %5d  contact energy bound: the step at an impact gained %.4e; removed "
                "%.4e from the patch of %lld nodes, %.4e from the whole mesh",
                step, gain, patch, static_cast<long long>(patch_nodes), whole);
  out.note(line);
  const double left = gain - patch - whole;
  if (left > 1e-9 * gain)
    out.warning(::seam::detail::concat("step ", step, " at t = ", t,
                                       ": the contact energy bound could not remove ", left,
                                       " of the energy ", gain,
                                       " the step gained (no kinetic energy left in the "
                                       "bodies' deformation)"));
}

} // namespace

void run_dynamic(const io::Config& config, const Model& model, const Discretization& disc,
                 const std::vector<meshtying::TiedInterface>& tied, const TyingConstraint& tying,
                 SaddlePoint& saddle, ContactConstraint& contact, Output& out,
                 const Checkpoints& checkpoints) {
  const auto& tc = config.time;
  const bool emm = tc.integrator == io::Integrator::energy_momentum;
  const AlphaParameters ga(tc.rho_inf);
  NewtonSolver newton(config, model, disc, tying, saddle, contact, out);

  la::Matrix M = disc.make_matrix();
  {
    ScopedTimer timer(out.timers(), "assembly");
    assemble_mass(model, disc, M);
  }
  parallel::mark_memory(disc.comm().get(), "matrix_allocation");
  la::Vector u = disc.make_vector(), v = disc.make_vector(), a = disc.make_vector();
  la::Vector u_n = disc.make_vector(), v_n = disc.make_vector(), a_n = disc.make_vector();
  la::Vector work = disc.make_vector(), mid = disc.make_vector(), w2 = disc.make_vector();
  initial_velocity(config, disc, v);
  if (tying.active()) {
    // The velocity must satisfy the tying constraint: slave velocities follow the master's.
    work.copy_from(v);
    tying.expand(work, v);
    v.update_ghosts();
  }
  // Initial acceleration: a0 = 0 is exact for a stress-free, unloaded start (the seed's
  // examples); otherwise the first generalized-alpha steps carry a transient.

  auto record = [&](int step, double t, const NewtonResult& res, double internal,
                    double external_work) {
    StepRecord rec;
    rec.step = step;
    rec.time = t;
    rec.newton_iterations = res.iterations;
    rec.residual = res.residual;
    M.mult(v, work);
    rec.kinetic_energy = 0.5 * work.dot(v);
    rec.internal_energy = internal;
    rec.external_work = external_work;
    momenta(disc, M, u, v, work, rec.momentum, rec.angular_momentum);
    return rec;
  };

  // Generalized-alpha restarts from the acceleration of equilibrium after a step in which a
  // contact opened or closed (below): without mesh tying, whose constraint the acceleration
  // would have to satisfy as well.
  const bool restart_at_contact_change =
      !emm && contact.active() && !tying.active() && !saddle.active();
  // Generalized-alpha: persistency of the pushing contacts after every step with an active
  // node (docs/contact_dynamics.md §6; frictionless interfaces without mesh tying).
  const bool persistency =
      !emm && contact.active() && contact.frictionless() && !tying.active() && !saddle.active();
  // Energy-momentum: the energy a step gains where slave nodes start it beyond the other
  // surface is taken out of the velocities (remove_contact_gain; without mesh tying, whose
  // constraint the velocities would have to keep). SEAM_KEEP_CONTACT_GAIN=1 turns that off for
  // the tests that show the gain.
  static const bool keep_gain_for_tests = [] {
    const char* e = std::getenv("SEAM_KEEP_CONTACT_GAIN");
    return e != nullptr && std::string_view(e) == "1";
  }();
  const bool contact_gain_update = emm && contact.n_discrete_gradient() > 0 && !tying.active() &&
                                   !saddle.active() && !keep_gain_for_tests;
  // Generalized-alpha: a step at an impact (from the first step with an active node to the
  // first step after the release in which the energy falls) may not raise the energy beyond the
  // work of the loads and supports (and of moving obstacles); a rise is taken out of the velocity
  // of the contact patch relative to its rigid motion (docs/contact_dynamics.md §6, "The energy
  // bound at impacts"). SEAM_KEEP_CONTACT_GAIN=1 turns it off as well.
  const bool energy_bound =
      !emm && contact.active() && !tying.active() && !saddle.active() && !keep_gain_for_tests;
  std::unique_ptr<NewtonSolver> projector;
  // The projection moves the nodes by eps v with |eps v| = 1e-5 |X| (both root mean squares
  // 1e-5 apart): far above the round-off of the weighted gaps (1e-16 |X|, relative 1e-11) and
  // small against the facets; eps is at most the step (a step's travel).
  const double coordinate_scale = disc.coordinates_vector().norm();
  auto projection_step = [&](const la::Vector& velocity, double h) {
    const double speed = velocity.norm();
    return speed > 1e-5 * coordinate_scale / h ? 1e-5 * coordinate_scale / speed : h;
  };
  la::Vector z = disc.make_vector(), target = disc.make_vector();
  std::vector<PetscInt> prescribed;
  for (const auto& d : model.dirichlet) prescribed.push_back(d.dof);
  std::unique_ptr<FreeMassSolver> mass_solver;
  auto free_mass = [&]() -> FreeMassSolver& {
    if (!mass_solver) mass_solver = std::make_unique<FreeMassSolver>(disc, M, prescribed);
    return *mass_solver;
  };

  if (emm && contact.n_end_of_step() > 0 && disc.comm().is_root())
    std::printf(
        "seam: energy_momentum: %d contact interface(s) keep the contact force of the end "
        "of the step (2D faces mixing line2 and line3): momentum and energy are not conserved "
        "there (docs/contact_dynamics.md)\n",
        contact.n_end_of_step());
  StepControl control(tc);
  int step = 0;
  double external_work = 0.0;
  la::Vector force = disc.make_vector(), force_old = disc.make_vector(), du = disc.make_vector();
  // The state of the integrator: u, v and a (generalized-alpha's acceleration; zero with the
  // energy-momentum method) and the last step's force of the trapezoidal external work.
  // With the energy bound at impacts also the nodes of the last contact force (`seed`, the
  // patch the bound takes a gain from, kept through the release's transient).
  la::Vector seed = disc.make_vector();
  std::vector<std::pair<const char*, const la::Vector*>> state_out = {
      {"u", &u}, {"v", &v}, {"a", &a}, {"force_old", &force_old}};
  std::vector<std::pair<const char*, la::Vector*>> state_in = {
      {"u", &u}, {"v", &v}, {"a", &a}, {"force_old", &force_old}};
  if (energy_bound) {
    state_out.emplace_back("contact_seed", &seed);
    state_in.emplace_back("contact_seed", &seed);
  }
  bool restored_transient = false;
  if (checkpoints.restarting()) {
    const auto state = read_checkpoint(checkpoints, control, contact, saddle, tied, out, state_in);
    step = state.step;
    external_work = state.external_work;
    restored_transient = state.impact_transient;
    newton.restore_ordering_state(state.ordering);
  } else {
    out.initial(u);
  }
  // The energy bound's state: the energy K + U of t_n, the force whose work it allows at t_n
  // (bound_force), the nodes of the last contact force (the patch's seed), the number of active
  // nodes at t_n and whether the impact's transient lasts (a run continued from a checkpoint
  // takes the transient and the seed from it).
  la::Vector f_ext_new = disc.make_vector(), bound_old = disc.make_vector(),
             bound_new = disc.make_vector();
  double energy_old = 0.0;
  int active_n = 0;
  bool transient = false;
  // Loads on every dof, the supports' reactions on the prescribed ones: the total external
  // force without the rigid obstacles' contact forces, unless an obstacle moves (a fixed one
  // does no work; its trapezoidal f . du is the step's error at a touch or a release).
  auto bound_force = [&](const la::Vector& f_ext, const la::Vector& total, la::Vector& f) {
    f.copy_from(total);
    if (contact.moving_obstacle()) return;
    f.axpy(-1.0, f_ext);
    {
      la::Vector::LocalView view(f, true);
      std::vector<char> fixed(view.values().size(), 0);
      const PetscInt first = disc.first_owned_dof();
      for (const PetscInt dof : prescribed)
        if (dof >= first && dof < first + disc.n_owned_dofs())
          fixed[static_cast<std::size_t>(dof - first)] = 1;
      for (std::size_t i = 0; i < fixed.size(); ++i)
        if (!fixed[i]) view.values()[i] = 0.0;
    }
    f.axpy(1.0, f_ext);
  };
  if (energy_bound) {
    ScopedTimer timer(out.timers(), "assembly");
    const double strain = disc.comm().sum(
        assemble(model, disc, u, control.time(), work, nullptr, &f_ext_new).strain_energy);
    M.mult(v, work);
    energy_old = 0.5 * work.dot(v) + strain;
    bound_force(f_ext_new, force_old, bound_old);
    active_n = contact.n_active();
    transient = active_n > 0 || restored_transient;
  }
  while (control.running()) {
    const double t = control.time();
    const double t_new = control.next();
    const double h = t_new - t;
    u_n.copy_from(u);
    v_n.copy_from(v);
    a_n.copy_from(a);
    u_n.update_ghosts();
    if (emm) contact.start_step(u_n);

    NewtonSolver::Evaluator evaluate;
    if (emm) {
      // M (v_{n+1} - v_n)/h + f_alg(u_n, u_{n+1}) - f_ext(t_{n+1/2}) = 0 with
      // v_{n+1} = 2 (u_{n+1} - u_n)/h - v_n.
      evaluate = [&](const la::Vector& state, la::Vector& r, la::Matrix* K, la::Vector& f_ext) {
        const auto status =
            assemble_algorithmic(model, disc, u_n, state, 0.5 * (t + t_new), r, K, &f_ext);
        w2.copy_from(state);
        w2.axpy(-1.0, u_n);
        w2.axpy(-h, v_n);
        w2.scale(2.0 / (h * h));
        M.mult(w2, work);
        r.axpy(1.0, work);
        if (K) K->axpy(2.0 / (h * h), M);
        return status;
      };
    } else {
      // M a_{n+1-alpha_m} + r(u_{n+1-alpha_f}, t_{n+1-alpha_f}) = 0 (Chung & Hulbert 1993).
      const double t_m = (1 - ga.alpha_f) * t_new + ga.alpha_f * t;
      evaluate = [&](const la::Vector& state, la::Vector& r, la::Matrix* K, la::Vector& f_ext) {
        mid.copy_from(state);
        mid.scale(1 - ga.alpha_f);
        mid.axpy(ga.alpha_f, u_n);
        mid.update_ghosts();
        const auto status = assemble(model, disc, mid, t_m, r, K, &f_ext);
        // a_{n+1}(u) and a_{n+1-alpha_m} = (1 - alpha_m) a_{n+1} + alpha_m a_n.
        w2.copy_from(state);
        w2.axpy(-1.0, u_n);
        w2.axpy(-h, v_n);
        w2.scale(1.0 / (ga.beta * h * h));
        w2.axpy(-(1 - 2 * ga.beta) / (2 * ga.beta), a_n);
        w2.scale(1 - ga.alpha_m);
        w2.axpy(ga.alpha_m, a_n);
        M.mult(w2, work);
        r.axpy(1.0, work);
        if (K) {
          K->scale(1 - ga.alpha_f);
          K->axpy((1 - ga.alpha_m) / (ga.beta * h * h), M);
        }
        return status;
      };
    }
    const auto res = newton.solve(u, t_new, step + 1, evaluate);
    if (!res.converged) {
      newton.reject(u, u_n);
      control.fail(res, t_new, step, out, disc.comm());
      continue;
    }
    ++step;
    // New velocity and acceleration.
    if (emm) {
      v.copy_from(u);
      v.axpy(-1.0, u_n);
      v.scale(2.0 / h);
      v.axpy(-1.0, v_n);
    } else {
      a.copy_from(u);
      a.axpy(-1.0, u_n);
      a.axpy(-h, v_n);
      a.scale(1.0 / (ga.beta * h * h));
      a.axpy(-(1 - 2 * ga.beta) / (2 * ga.beta), a_n);
      v.copy_from(v_n);
      v.axpy(h * (1 - ga.gamma), a_n);
      v.axpy(h * ga.gamma, a);
    }
    v.update_ghosts();
    a.update_ghosts();
    if (contact_gain_update) {
      ScopedTimer timer(out.timers(), "contact_velocity_update");
      M.mult(v, work);
      const double energy = 0.5 * work.dot(v) + std::abs(res.strain_energy);
      const auto removal = remove_contact_gain(
          disc, contact, M, prescribed, u, energy,
          [&](la::Vector& b, la::Vector& x) {
            z.zero();
            return free_mass().solve(z, b, x);
          },
          v);
      if (removal.acted) log_contact_gain(removal, step, t_new, out);
    }
    if (persistency && contact.n_active() > 0) {
      if (!projector) {
        projector =
            std::make_unique<NewtonSolver>(config, model, disc, tying, saddle, contact, out);
        projector->set_logging(false);
      }
      ScopedTimer timer(out.timers(), "contact_persistency");
      const auto lambda = contact.multipliers();
      contact.hold_sets(true);
      const bool ok = project_onto_active_contacts(*projector, free_mass(), contact, M, u, t_new,
                                                   projection_step(v, h), step, v, z, target, work);
      contact.set_multipliers(lambda);
      contact.evaluate(u, t_new, false, out.timers());
      contact.hold_sets(false);
      if (!ok)
        out.warning(::seam::detail::concat("step ", step, " at t = ", t_new,
                                           ": the persistency projection of the contact "
                                           "velocities failed; the Newmark velocity is kept"));
    }
    // Strain energy at u_{n+1} (generalized-alpha evaluated the midpoint state).
    double internal = res.strain_energy;
    if (!emm) {
      ScopedTimer timer(out.timers(), "assembly");
      internal = disc.comm().sum(
          assemble(model, disc, u, t_new, work, nullptr, energy_bound ? &f_ext_new : nullptr)
              .strain_energy);
      if (restart_at_contact_change && contact.set_changed()) {
        // Chung & Hulbert's scheme starts from an acceleration in equilibrium with the forces
        // at t_0, M a_0 = f_ext - f_int - f_c, and assumes forces smooth in time. A contact
        // that opens or closes makes the contact force jump; the Newmark acceleration of that
        // step holds its averaged impulse, and carried into the next step (where, after a
        // release, no contact force acts) it excites the mesh's highest modes, whose energy
        // generalized-alpha moves between kinetic and strain energy from step to step (the bar
        // impact of test_self_contact.py gained 1.03e-4 of its energy two steps after the
        // bars separated). So the step after a change is a new start: a_{n+1} from the
        // equilibrium at t_{n+1} with the contact forces of the converged multipliers;
        // prescribed dofs keep their Newmark acceleration.
        contact.add_force(work);
        work.scale(-1.0);
        if (!free_mass().solve(a, work, w2))
          SEAM_THROW(SolverError,
                     "the mass matrix solve for the acceleration failed at t = ", t_new);
        a.copy_from(w2);
        a.update_ghosts();
      }
    }
    // External work of loads and supports, trapezoidal in the displacement increment.
    du.copy_from(u);
    du.axpy(-1.0, u_n);
    newton.total_external_force(force);
    if (emm) {
      // The loads of the energy-momentum step act at the midpoint: their work is F_mid . du.
      external_work += force.dot(du);
    } else {
      external_work += 0.5 * (force.dot(du) + force_old.dot(du));
      force_old.copy_from(force);
    }
    if (energy_bound) {
      ScopedTimer timer(out.timers(), "contact_energy_bound");
      bound_force(f_ext_new, force, bound_new);
      const double allowed = 0.5 * (bound_new.dot(du) + bound_old.dot(du));
      bound_old.copy_from(bound_new);
      const int active = contact.n_active();
      if (active > 0) {
        seed.zero();
        contact.add_force(seed);
      }
      M.mult(v, work);
      double kinetic = 0.5 * work.dot(v);
      const double gain = kinetic + internal - energy_old - allowed;
      const double round_off = 1e-13 * (kinetic + std::abs(internal));
      // After the release the restarted acceleration (above) rings in the stiff modes near the
      // contact, and generalized-alpha's energy rises for a few steps until its numerical
      // dissipation wins (the Hertz impact with the bound only while a node was active at t_n
      // or t_{n+1}: steps 51 to 54 after the release in step 49 gained up to 9.1e-4).
      transient = active > 0 || active_n > 0 || (transient && gain >= -round_off);
      if (transient && gain > round_off) {
        // Two layers of cells around the contact nodes first (as the energy-momentum update),
        // then, for what their relative motion does not hold, the whole mesh's.
        std::int64_t patch_nodes = 0, all_nodes = 0;
        double s_patch = 0.0, s_all = 0.0;
        const double patch =
            remove_from_patch(disc, M, prescribed, u, seed, 2, gain, v, patch_nodes, s_patch);
        const double whole = patch < gain * (1.0 - 1e-12)
                                 ? remove_from_patch(disc, M, prescribed, u, seed, -1, gain - patch,
                                                     v, all_nodes, s_all)
                                 : 0.0;
        log_energy_bound(gain, patch, patch_nodes, whole, step, t_new, out);
        M.mult(v, work);
        kinetic = 0.5 * work.dot(v);
      }
      energy_old = kinetic + internal;
      active_n = active;
    }
    auto rec = record(step, t_new, res, internal, external_work);
    if (contact.active()) {
      rec.active_nodes = contact.n_active();
      rec.slip_nodes = contact.n_slip();
      contact.balance();
      out.contact_state(contact.reports(u));
    }
    const bool last = t_new >= tc.end * (1.0 - 1e-12);
    out.step(rec, u, &v, newton.reactions(), newton.multipliers(tied), last);
    newton.accept();
    control.accept(t_new);
    DriverState written{step, external_work};
    written.impact_transient = energy_bound && transient;
    written.ordering = newton.ordering_state();
    write_checkpoint(checkpoints, written, control, contact, saddle, tied, out, state_out);
  }
  out.finish(true, step);
}

} // namespace seam::problem
