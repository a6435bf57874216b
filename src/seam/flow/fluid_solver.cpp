#include "seam/flow/fluid_solver.hpp"

#include "seam/ale/mesh_motion.hpp"
#include "seam/common/error.hpp"
#include "seam/flow/fluid_layout.hpp"
#include "seam/flow/fluid_mesh_motion.hpp"
#include "seam/flow/fluid_model.hpp"
#include "seam/flow/fluid_output.hpp"
#include "seam/flow/fluid_pcd.hpp"
#include "seam/fluid/navier_stokes.hpp"
#include "seam/problem/checkpoint.hpp"
#include "seam/problem/linear_solver_choice.hpp"
#include "seam/problem/step_control.hpp"
#include "seam/problem/tying_constraint.hpp"
#include "seam/solid/loads.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <functional>
#include <memory>
#include <optional>

namespace seam::flow {

using problem::BodyLoad;
using problem::CanonicalOrder;
using problem::Checkpoints;
using problem::find_region;
using problem::LinearSolverChoice;
using problem::MeshIdentity;
using problem::RecordWriter;
using problem::RestartFrom;
using problem::StepControl;
using problem::SystemKind;
using problem::tied_dofs;
using problem::TyingConstraint;

namespace {

constexpr int max_cell_dofs = fem::max_cell_nodes * 4;
// The largest relative tolerance of an iterative linear solve in Newton's method.
constexpr double forcing_max = 1e-2;

// One cell's coordinates, velocity, pressure and dofs, gathered from the local vector form.
struct CellData {
  int n_dofs = 0;
  std::array<double, fem::max_cell_nodes * 3> x{}, u{}, u_dot{}, w{};
  bool unsteady = false, moving = false;
  std::array<double, 8> p{};
  std::array<PetscInt, max_cell_dofs> dofs{};
  std::array<std::int32_t, max_cell_dofs> local{};
  std::array<double, max_cell_dofs> r{};
  std::array<double, max_cell_dofs * max_cell_dofs> K{};
};

// The mesh an assembly integrates on: the coordinates of every node (node-major, the
// reference mesh's if the mesh is fixed) and, in ALE time integration, the mesh velocity of
// every node (empty: at rest).
struct MeshState {
  std::span<const double> x;
  std::span<const double> w;
};

// The state an assembly evaluates: the velocity from `u` (and its rate from `u_dot`, if
// given), the pressure from `p`; the weights of the Jacobian (fluid::FluidElementInput).
struct EvaluationState {
  const la::Vector* u;
  const la::Vector* p;
  const la::Vector* u_dot = nullptr;
  double state_weight = 1.0;
  double mass_weight = 0.0;
  double time_step = 0.0; // 0: steady
  /// The consistent initial state: K by (u_dot, p) at the given u (fluid::FluidElementInput).
  bool initial_rate = false;
};

void gather(const FluidLayout& layout, const MeshState& ms, std::span<const double> u,
            std::span<const double> p, std::span<const double> u_dot, std::int32_t c, CellData& d) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  const auto nodes = mesh.cell(c);
  d.n_dofs = layout.cell_dofs(c, d.dofs);
  layout.cell_local_dofs(c, d.local);
  const int nu = static_cast<int>(nodes.size()) * dim;
  for (std::size_t a = 0; a < nodes.size(); ++a)
    for (int i = 0; i < dim; ++i) d.x[a * dim + i] = ms.x[nodes[a] * dim + i];
  d.moving = !ms.w.empty();
  if (d.moving)
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < dim; ++i) d.w[a * dim + i] = ms.w[nodes[a] * dim + i];
  for (int k = 0; k < nu; ++k) d.u[k] = u[d.local[k]];
  d.unsteady = !u_dot.empty();
  if (d.unsteady)
    for (int k = 0; k < nu; ++k) d.u_dot[k] = u_dot[d.local[k]];
  for (int k = nu; k < d.n_dofs; ++k) d.p[k - nu] = p[d.local[k]];
}

fluid::FluidElementInput element_input(const FluidModel& model, const FluidLayout& layout,
                                       std::int32_t c, const CellData& d) {
  const auto type = layout.mesh().cell_type[c];
  const int dim = layout.dim();
  const auto n = static_cast<std::size_t>(fem::n_nodes(type) * dim);
  fluid::FluidElementInput in;
  in.cell = type;
  in.dim = dim;
  in.fluid = model.fluids[model.cell_fluid[c]];
  in.x = std::span<const double>(d.x.data(), n);
  in.u = std::span<const double>(d.u.data(), n);
  in.p = std::span<const double>(d.p.data(), fem::n_vertices(type));
  if (d.unsteady) in.u_dot = std::span<const double>(d.u_dot.data(), n);
  if (d.moving) in.mesh_velocity = std::span<const double>(d.w.data(), n);
  return in;
}

// r (and K) at the state (ghosts up to date) and time t; both assembled on return.
// Returns whether a cell of this rank is inverted.
bool assemble(const FluidModel& model, const FluidLayout& layout, const MeshState& ms,
              const EvaluationState& state, double t, la::Vector& r, la::Matrix* K) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  r.zero();
  if (K) K->zero();
  bool inverted = false;
  CellData d;
  la::Vector::LocalView u_view(*state.u, false), p_view(*state.p, false);
  std::optional<la::Vector::LocalView> u_dot_view;
  if (state.u_dot) u_dot_view.emplace(*state.u_dot, false);
  const auto u_dot = u_dot_view ? u_dot_view->values() : std::span<double>();
  // Body forces per cell: the sum of every body_force condition on it.
  std::vector<const BodyLoad*> cell_loads;
  for (auto c : layout.local_cells()) {
    gather(layout, ms, u_view.values(), p_view.values(), u_dot, c, d);
    auto in = element_input(model, layout, c, d);
    in.state_weight = state.state_weight;
    in.mass_weight = state.mass_weight;
    in.time_step = state.time_step;
    in.initial_rate = state.initial_rate;
    cell_loads.clear();
    for (const auto& load : model.body_loads)
      if (std::binary_search(load.cells.begin(), load.cells.end(), c)) cell_loads.push_back(&load);
    const fluid::BodyForce force = [&](const double* x, double* value) {
      for (const auto* load : cell_loads)
        for (std::size_t k = 0; k < load->components.size(); ++k)
          value[load->components[k]] += load->value[k](t, x[0], x[1], dim == 3 ? x[2] : 0.0);
    };
    if (!cell_loads.empty()) in.body_force = &force;
    const auto nd = static_cast<std::size_t>(d.n_dofs);
    if (!fluid::navier_stokes(in, std::span(d.r.data(), nd),
                              K ? std::span(d.K.data(), nd * nd) : std::span<double>())) {
      inverted = true;
      continue;
    }
    const std::span<const PetscInt> dofs(d.dofs.data(), nd);
    r.add_values(dofs, std::span<const double>(d.r.data(), nd));
    if (K) K->add_values(dofs, dofs, std::span<const double>(d.K.data(), nd * nd));
  }
  // Pressure (-p n) and traction loads on boundary facets: the velocity rows of their nodes.
  std::array<double, fem::max_facet_nodes * 3> X{}, zero{}, rf{};
  std::array<PetscInt, fem::max_facet_nodes * 3> fdofs{};
  for (const auto& load : model.surface_loads)
    for (const auto& f : load.facets) {
      const auto type = mesh.cell_type[f.cell];
      const auto local = fem::facet_nodes(type, f.local);
      const auto nodes = mesh.cell(f.cell);
      const auto nf = local.size() * dim;
      for (std::size_t a = 0; a < local.size(); ++a)
        for (int i = 0; i < dim; ++i) {
          X[a * dim + i] = ms.x[nodes[local[a]] * dim + i];
          fdofs[a * dim + i] = layout.global_dof(nodes[local[a]], i);
        }
      const solid::FacetInput in{fem::facet_type(type, f.local), dim,
                                 std::span<const double>(X.data(), nf),
                                 std::span<const double>(zero.data(), nf), 0};
      const auto at = [&](const io::Expression& e, const double* x) {
        return e(t, x[0], x[1], dim == 3 ? x[2] : 0.0);
      };
      if (load.type == io::BoundaryType::pressure) {
        solid::follower_pressure(in, [&](const double* x) { return at(load.value[0], x); },
                                 std::span(rf.data(), nf), {});
      } else {
        solid::dead_traction(
            in,
            [&](const double* x, double* value) {
              for (int i = 0; i < dim; ++i) value[i] = 0.0;
              for (std::size_t k = 0; k < load.components.size(); ++k)
                value[load.components[k]] = at(load.value[k], x);
            },
            std::span(rf.data(), nf));
      }
      r.add_values(std::span<const PetscInt>(fdofs.data(), nf),
                   std::span<const double>(rf.data(), nf));
    }
  r.assemble();
  if (K) K->assemble();
  return inverted;
}

// The prescribed values at time t written into w (owned entries), ghosts updated. With
// `rate_step` > 0 the rates at t instead, as the consistent initial state wants them: the time
// derivative of every velocity condition (one-sided second-order differences of its
// expression, step `rate_step`, so that it is not evaluated before t) and the value of a pinned
// pressure (the state holds the pressure itself there).
void impose(const FluidModel& model, const FluidLayout& layout, double t, la::Vector& w,
            double rate_step = 0.0) {
  {
    la::Vector::LocalView view(w, true);
    auto v = view.values();
    const auto& x = layout.mesh().x;
    const int dim = layout.dim();
    for (const auto& d : model.dirichlet) {
      const double* p = &x[static_cast<std::size_t>(d.node) * dim];
      const auto at = [&](double s) {
        return model.values[d.expression](s, p[0], p[1], dim == 3 ? p[2] : 0.0);
      };
      const double h = d.dof == layout.global_dof(d.node, dim) ? 0.0 : rate_step;
      v[d.dof - layout.first_owned_dof()] =
          h > 0.0 ? (-3.0 * at(t) + 4.0 * at(t + h) - at(t + 2.0 * h)) / (2.0 * h) : at(t);
    }
  }
  w.update_ghosts();
}

// The force the fluid exerts on each force group: minus the momentum residual at its nodes
// (the reaction of the wall; Giles, Larson, Levenstam & Suli 1997 show that this residual
// form converges at the rate of the energy norm, faster than the stress at the wall).
std::vector<std::array<double, 3>> forces(const FluidModel& model, const FluidLayout& layout,
                                          const la::Vector& r_full) {
  const int dim = layout.dim();
  std::vector<double> sum(model.forces.size() * 3, 0.0);
  {
    la::Vector::LocalView view(r_full, false);
    const auto r = view.values();
    for (std::size_t k = 0; k < model.forces.size(); ++k)
      for (auto n : model.forces[k].owned_nodes)
        for (int i = 0; i < dim; ++i) sum[k * 3 + i] -= r[layout.local_dof(n, i)];
  }
  layout.comm().sum_in_place(sum);
  std::vector<std::array<double, 3>> out(model.forces.size());
  for (std::size_t k = 0; k < out.size(); ++k)
    out[k] = {sum[3 * k], sum[3 * k + 1], sum[3 * k + 2]};
  return out;
}

FluidErrors errors(const io::Config& config, const FluidModel& model, const FluidLayout& layout,
                   const MeshState& ms, const la::Vector& w, double t) {
  const int dim = layout.dim();
  const auto& ue = config.output.exact_velocity;
  const auto& pe = config.output.exact_pressure;
  fluid::ExactVelocity u_exact;
  fluid::ExactPressure p_exact;
  if (!ue.empty())
    u_exact = [&](const double* x, double* value) {
      for (int i = 0; i < dim; ++i) value[i] = ue[i](t, x[0], x[1], dim == 3 ? x[2] : 0.0);
    };
  if (!pe.empty())
    p_exact = [&](const double* x) { return pe[0](t, x[0], x[1], dim == 3 ? x[2] : 0.0); };
  std::vector<double> sum(4, 0.0);
  {
    CellData d;
    la::Vector::LocalView view(w, false);
    for (auto c : layout.local_cells()) {
      gather(layout, ms, view.values(), view.values(), {}, c, d);
      const auto e = fluid::error_integrals(element_input(model, layout, c, d), u_exact, p_exact);
      for (int k = 0; k < 4; ++k) sum[k] += e[k];
    }
  }
  layout.comm().sum_in_place(sum);
  FluidErrors out;
  out.velocity_l2 = std::sqrt(sum[0]);
  const double p2 = model.pressure_pinned ? sum[1] - sum[2] * sum[2] / sum[3] : sum[1];
  out.pressure_l2 = std::sqrt(std::max(0.0, p2));
  return out;
}

// `initial_conditions`: the velocity at t = 0 on the nodes of their regions (zero elsewhere).
void set_initial_velocity(const io::Config& config, const FluidLayout& layout, la::Vector& w) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  {
    la::Vector::LocalView view(w, true);
    auto v = view.values();
    for (const auto& ic : config.initial_conditions) {
      const auto& region = find_region(mesh, ic.region, {0, 1, 2, 3}, "an initial condition");
      for (auto n : region.nodes) {
        if (!layout.owns_node(n)) continue;
        const double* x = &mesh.x[static_cast<std::size_t>(n) * dim];
        for (int i = 0; i < dim; ++i)
          v[layout.local_dof(n, i)] = ic.velocity[i](0.0, x[0], x[1], dim == 3 ? x[2] : 0.0);
      }
    }
  }
  w.update_ghosts();
}

struct NewtonOutcome {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
  const char* failure = "";
};

/// The stored order of fluid vectors: per node of the mesh as read (node_gid), dim + 1 slots,
/// its velocity and then its pressure (held on the vertices of Taylor-Hood cells and every
/// node of equal-order ones; the slot of a node without one stays unused), so that every
/// rank finds a node's entries from its id alone, without a count over the nodes before it.
CanonicalOrder fluid_order(const FluidLayout& layout) {
  const int dim = layout.dim();
  CanonicalOrder order;
  order.size = layout.n_global_nodes() * (dim + 1);
  for (std::int32_t n = 0; n < layout.mesh().n_nodes(); ++n)
    for (int c = 0; c < dim + (layout.has_pressure(n) ? 1 : 0); ++c)
      if (layout.local_dof(n, c) >= 0)
        order.add(layout.node_gid(n) * (dim + 1) + c, layout.local_dof(n, c), layout.owns_node(n));
  return order;
}

LinearSolverChoice fluid_linear_solver(const io::Config& config, const FluidLayout& layout) {
  return choose_linear_solver(config.solver.linear, layout.dim(), layout.n_global_dofs(),
                              SystemKind::fluid);
}

// The velocity block's preconditioner of the iterative solver (docs/fluid.md, "Solving"):
// BoomerAMG for steady flow, whose iterations per Newton step it keeps from growing under
// refinement; ILU(0) in generalized-alpha, whose mass term makes the block diagonally
// dominant and ILU(0) the cheaper of the two (measured on DFG 2D-3).
la::LinearSolver::VelocityBlock fluid_velocity_block(const io::Config& config) {
  return config.time.integrator == io::Integrator::generalized_alpha
             ? la::LinearSolver::VelocityBlock::ilu
             : la::LinearSolver::VelocityBlock::amg;
}

// The run header's and summary.json's name of the linear solver, e.g. "direct (MUMPS; auto: a
// fluid)", "iterative (FGMRES + Schur fieldsplit: BoomerAMG velocity, BoomerAMG selfp)".
std::string describe_fluid_linear_solver(const io::Config& config, const FluidLayout& layout) {
  const bool amg = fluid_velocity_block(config) == la::LinearSolver::VelocityBlock::amg;
  const bool pcd = pcd_requested();
  const auto choice = fluid_linear_solver(config, layout);
  std::string text = describe(choice, std::string("FGMRES + Schur fieldsplit: ") +
                                          (amg ? "BoomerAMG velocity, " : "ILU(0) velocity, ") +
                                          (pcd ? "PCD" : "BoomerAMG selfp"));
  // PCD preconditions the iterative solve's Schur block: say when a direct solve leaves it out.
  if (pcd && choice.kind != la::SolverKind::iterative)
    text += "; -fluid_schur pcd unused: set solver.linear: iterative";
  return text;
}

class FluidNewton {
public:
  /// `tying`: the condensed mesh tying of fluid subdomains, or null.
  FluidNewton(const io::Config& config, const FluidModel& model, const FluidLayout& layout,
              FluidOutput& out, const TyingConstraint* tying)
      : config_(config), model_(model), layout_(layout), out_(out), tying_(tying),
        K_(layout.make_matrix()), r_(layout.make_vector()), rt_(layout.make_vector()),
        r_full_(layout.make_vector()), dw_(layout.make_vector()), dwt_(layout.make_vector()),
        // `auto`: linear_solver_choice.hpp.
        solver_(layout.comm().get(), fluid_linear_solver(config, layout).kind) {
    for (const auto& d : model.dirichlet) fixed_.push_back(d.dof);
    iterative_ = fluid_linear_solver(config, layout).kind == la::SolverKind::iterative;
    if (iterative_) {
      // Velocity | pressure: a Schur-complement fieldsplit (la::LinearSolver::set_fields).
      std::vector<PetscInt> velocity, pressure;
      layout.owned_fields(velocity, pressure);
      solver_.set_fields(velocity, pressure, fluid_velocity_block(config));
      // `-fluid_schur pcd`: the pressure convection-diffusion Schur block (fluid_pcd.hpp).
      if (pcd_requested()) {
        pcd_ = std::make_unique<PressureConvectionDiffusion>(model, layout);
        solver_.set_schur_preconditioner([this](Vec x, Vec y) { pcd_->apply(x, y); });
      }
    }
  }

  /// The residual scale of the run so far (the largest first residual of a step): part of
  /// the state a checkpoint keeps.
  double reference() const { return reference_; }
  /// The weights of the Jacobian for the PCD preconditioner (steady: {1, 0, 1}).
  void set_pcd_weights(const PcdWeights& weights) { pcd_weights_ = weights; }
  /// The configuration and mesh velocity (nodal; empty: the reference mesh, at rest) the PCD
  /// preconditioner's operators are built in: those the equations are integrated with.
  void set_pcd_mesh(std::span<const double> x, std::span<const double> mesh_velocity) {
    pcd_x_ = x;
    pcd_mesh_velocity_ = mesh_velocity;
  }
  void set_reference(double reference) { reference_ = reference; }
  /// The tying constraint, built anew when the mesh moves (null: none).
  void set_tying(const TyingConstraint* tying) { tying_ = tying; }

  /// Evaluates r and K at the unknowns w (ghosts up to date); returns "inverted".
  using Evaluator = std::function<bool(const la::Vector& w, la::Vector& r, la::Matrix& K)>;
  /// Writes the prescribed values of the unknowns (the velocity conditions' rows).
  using Prescriber = std::function<void(la::Vector& w)>;

  /// The consistent initial state of generalized-alpha: y = (u_dot, p) at t = 0 from the
  /// momentum equations at the initial velocity and the time derivative of the continuity
  /// equation. The problem is linear: one Newton correction solves it (a flow already at
  /// rest in its rates has a residual of round-off that no correction reduces). Not recorded
  /// in newton.csv, and the residual scale of the steps is kept apart.
  NewtonOutcome solve_initial(la::Vector& y, const Evaluator& evaluate,
                              const Prescriber& prescribe) {
    const double keep = reference_;
    reference_ = 0.0;
    linear_ = true;
    const auto res = solve(y, 0.0, 0, evaluate, &prescribe);
    linear_ = false;
    reference_ = keep;
    return res;
  }

  /// Newton's method for step `step` (0: the initial state, not recorded) at time t; the
  /// prescribed values are those of the velocity conditions at t unless `prescribe` is given.
  NewtonOutcome solve(la::Vector& w, double t, int step, const Evaluator& evaluate,
                      const Prescriber* prescribe = nullptr) {
    NewtonOutcome res;
    const auto& nc = config_.solver.newton;
    if (prescribe)
      (*prescribe)(w);
    else
      impose(model_, layout_, t, w);
    if (tying_) {
      // The tied slave velocities from the master ones (and the prescribed slave ones), so
      // that the state satisfies the constraint; the increments d = T d~ keep it.
      tying_->expand(w, dw_);
      w.copy_from(dw_);
      w.update_ghosts();
    }
    double last_increment = 0.0;
    for (int it = 0; it <= nc.max_iterations; ++it) {
      bool inverted;
      {
        ScopedTimer timer(out_.timers(), "assembly");
        inverted = evaluate(w, r_, K_);
      }
      if (layout_.comm().any(inverted)) {
        res.failure = "a fluid cell is inverted (det J <= 0)";
        return res;
      }
      r_full_.copy_from(r_);
      // The Newton system: condensed by T (T^T K T, T^T r) when fluid subdomains are tied.
      la::Matrix* K_sys = &K_;
      la::Vector* r_sys = &r_;
      la::Vector* d_sys = &dw_;
      if (tying_) {
        tying_->condense_matrix(K_, Kt_);
        tying_->condense_vector(r_, rt_);
        K_sys = &Kt_;
        r_sys = &rt_;
        d_sys = &dwt_;
      }
      {
        la::Vector::LocalView view(*r_sys, true);
        auto v = view.values();
        for (auto dof : fixed_) v[dof - layout_.first_owned_dof()] = 0.0;
      }
      const double norm = r_sys->norm();
      if (!std::isfinite(norm)) {
        res.failure = "the residual is not finite";
        return res;
      }
      // Relative to the largest first residual of the run and to the force level of the
      // system (the full residual, whose velocity-condition rows carry the reactions), as
      // for solids: a later step whose boundary data barely changed, or a state that already
      // solves the equations (its first residual is round-off), is not asked to go below
      // round-off of the flow it starts from.
      if (it == 0) reference_ = std::max({reference_, norm, r_full_.norm()});
      if (step > 0) out_.newton(step, it, norm, last_increment);
      res.iterations = it;
      res.residual = reference_ > 0.0 ? norm / reference_ : 0.0;
      const bool stalled = it >= 2 && last_increment <= 1e-14 * w.norm();
      if (norm <= nc.tolerance * reference_ || reference_ == 0.0 || stalled ||
          (linear_ && it == 1)) {
        res.converged = true;
        return res;
      }
      if (it == nc.max_iterations) break;
      K_sys->zero_rows_columns(fixed_);
      // Inexact Newton (Dembo, Eisenstat & Steihaug 1982): a forcing term proportional to
      // the relative residual keeps the convergence quadratic; 1e-10 for the linear problem
      // of the initial state, solved in one correction.
      if (iterative_)
        solver_.set_relative_tolerance(linear_ ? 1e-10
                                               : std::clamp(norm / reference_, 1e-10, forcing_max));
      if (pcd_)
        pcd_->update(w, linear_ ? PcdWeights{0.0, 1.0, 1.0} : pcd_weights_, pcd_x_,
                     pcd_mesh_velocity_);
      r_sys->scale(-1.0);
      d_sys->zero();
      bool solved;
      {
        ScopedTimer timer(out_.timers(), "linear_solve");
        solved = solver_.solve(*K_sys, *r_sys, *d_sys);
      }
      out_.linear_iterations(solver_.last_iterations());
      if (solved && tying_) tying_->expand(dwt_, dw_);
      if (!solved) {
        res.failure = "the linear solver failed";
        return res;
      }
      {
        // The prescribed values stay as impose() set them: the constrained rows of an
        // iterative solve return zero only up to its tolerance.
        la::Vector::LocalView view(dw_, true);
        auto v = view.values();
        for (const auto dof : fixed_) v[dof - layout_.first_owned_dof()] = 0.0;
      }
      last_increment = dw_.norm();
      w.axpy(1.0, dw_);
      w.update_ghosts();
    }
    res.failure = "Newton's method did not converge";
    return res;
  }

  /// The full residual (velocity-condition rows included) of the last evaluation.
  const la::Vector& full_residual() const { return r_full_; }

private:
  const io::Config& config_;
  const FluidModel& model_;
  const FluidLayout& layout_;
  FluidOutput& out_;
  const TyingConstraint* tying_;
  la::Matrix K_, Kt_;
  la::Vector r_, rt_, r_full_, dw_, dwt_;
  la::LinearSolver solver_;
  bool iterative_ = false;
  std::unique_ptr<PressureConvectionDiffusion> pcd_;
  PcdWeights pcd_weights_;
  std::span<const double> pcd_x_, pcd_mesh_velocity_;
  std::vector<PetscInt> fixed_;
  double reference_ = 0.0;
  bool linear_ = false; // the problem is linear: converged after one correction
};

// Whether some cell of this rank is inverted in the configuration x (all ranks agree).
bool any_inverted(const FluidLayout& layout, std::span<const double> x) {
  const auto& mesh = layout.mesh();
  const int dim = mesh.dim;
  std::array<double, fem::max_cell_nodes * 3> xc{};
  bool inverted = false;
  for (auto c : layout.local_cells()) {
    const auto nodes = mesh.cell(c);
    for (std::size_t a = 0; a < nodes.size(); ++a)
      for (int i = 0; i < dim; ++i) xc[a * dim + i] = x[nodes[a] * dim + i];
    if (ale::inverted(mesh.cell_type[c], std::span<const double>(xc.data(), nodes.size() * dim))) {
      inverted = true;
      break;
    }
  }
  return layout.comm().any(inverted);
}

// A nodal field (dim per mesh node, consistent on the nodes of this rank's cells) in a
// checkpoint: in the velocity slots of a layout vector, so stored in the fluid's order.
void put_nodal(const Checkpoints& checkpoints, RecordWriter& writer, const FluidLayout& layout,
               const std::string& name, std::span<const double> nodal) {
  la::Vector v = layout.make_vector();
  v.zero();
  layout.nodal_to_vector(nodal, v);
  checkpoints.put_vector(writer, name, v);
}

void get_nodal(const Checkpoints& checkpoints, const FluidLayout& layout, const std::string& name,
               std::vector<double>& nodal) {
  la::Vector v = layout.make_vector();
  checkpoints.get_vector(name, v);
  nodal.assign(static_cast<std::size_t>(layout.mesh().n_nodes()) * layout.dim(), 0.0);
  layout.vector_to_nodal(v, nodal);
}

// The moving mesh over the steps (ALE): the mesh displacement d and its rate at the last
// converged step, and the configuration and mesh velocity of the step being solved.
struct MovingMesh {
  std::vector<double> X, d, d_dot, d_new, d_dot_new, x, w;

  explicit MovingMesh(const mesh::Mesh& mesh) : X(mesh.x), x(mesh.x) {}
  /// The configuration X + d(t) itself (static runs, error norms).
  std::span<const double> at(const std::vector<double>& disp) {
    for (std::size_t k = 0; k < X.size(); ++k) x[k] = X[k] + disp[k];
    return x;
  }
};

// Sets up the tied interfaces of the fluid subdomains. In the reference configuration (`x`
// empty) the mesh initialization moves slave nodes onto the master side before anything is
// integrated; in a moved configuration x (nodal, mesh.x's layout) the operators are integrated
// on the interface where the mesh has moved it, and the mesh keeps its reference coordinates.
using TyingSetup =
    std::function<std::vector<meshtying::TiedInterface>(PhaseTimers&, std::span<const double> x)>;

// The run on a layout, replicated or distributed (fluid_solver.hpp).
FluidRunInfo run_on(const io::Config& config, const FluidLayout& layout, const TyingSetup& setup,
                    const std::function<MeshIdentity()>& identity, const std::filesystem::path& dir,
                    bool quiet, bool check_only, const RestartFrom& restart) {
  const auto& mesh = layout.mesh();
  const auto comm = layout.comm();
  const auto model = build_fluid_model(config, layout);
  FluidMeshMotion motion(config, layout);
  // Tied fluid subdomains: the mortar operators, once on a fixed mesh.
  PhaseTimers setup_timers;
  auto tied = setup(setup_timers, {});
  FluidRunInfo info{static_cast<long long>(layout.n_global_dofs())};
  if (check_only) return info;
  std::optional<TyingConstraint> tying;
  if (!tied.empty()) {
    tying.emplace(tied, tied_dofs(layout, model)); // the velocity; the pressure is untied
    if (!tying->active()) tying.reset();
  }
  const Checkpoints checkpoints(config, "fluid", identity(), comm, fluid_order(layout),
                                restart.input, dir, restart.checkpoint);
  FluidOutput out(config, layout, model, dir, quiet,
                  checkpoints.restarting() ? &checkpoints : nullptr);
  {
    std::array<double, 4> counts{};
    for (const auto& t : tied) {
      counts[0] += static_cast<double>(t.local_slave_facets);
      counts[1] += static_cast<double>(t.local_master_ghosts);
      counts[2] += static_cast<double>(t.local_pairs);
      counts[3] += static_cast<double>(t.local_integration_cells);
    }
    out.set_interface_counts(counts);
  }
  if (comm.is_root() && !quiet)
    std::printf("seam: %s\n  fluid: %lld nodes, %lld cells, %lld dofs, %d rank(s)%s; "
                "output in %s\n",
                config.title.empty() ? config.source.c_str() : config.title.c_str(),
                static_cast<long long>(layout.n_global_nodes()),
                static_cast<long long>(layout.n_global_cells()), info.n_dofs, comm.size(),
                motion.moving() ? ", moving mesh" : "", dir.c_str());
  const auto solver_name = describe_fluid_linear_solver(config, layout);
  if (comm.is_root() && !quiet) std::printf("  linear solver: %s\n", solver_name.c_str());
  out.set_linear_solver(solver_name);
  FluidNewton newton(config, model, layout, out, tying ? &*tying : nullptr);
  // On a moving mesh the tied interface moves with it: D and M are integrated again in the
  // configuration of every step (ties(x)), and the constraint built anew from them.
  const auto ties = [&](std::span<const double> x) {
    if (!tying) return;
    PhaseTimers timers;
    tying.reset();
    tied = setup(timers, x);
    tying.emplace(tied, tied_dofs(layout, model));
    newton.set_tying(&*tying);
  };
  la::Vector w = layout.make_vector(), w_old = layout.make_vector();
  set_initial_velocity(config, layout, w);
  impose(model, layout, 0.0, w);
  const bool exact = !config.output.exact_velocity.empty() || !config.output.exact_pressure.empty();
  const auto& tc = config.time;
  // Generalized-alpha for first-order systems (Jansen, Whiting & Hulbert 2000, eqs. 17-19 and
  // 26-27): second order and unconditionally stable for alpha_m >= alpha_f >= 1/2, with the
  // high-frequency damping set by rho_inf.
  const bool unsteady = tc.integrator == io::Integrator::generalized_alpha;
  const auto ga = ale::GeneralizedAlpha::from_rho_inf(tc.rho_inf);
  const double alpha_m = ga.alpha_m, alpha_f = ga.alpha_f, gamma = ga.gamma;
  la::Vector u_dot = layout.make_vector(), u_dot_new = layout.make_vector();
  la::Vector u_dot_m = layout.make_vector(), w_f = layout.make_vector();
  // The mesh: fixed (the reference coordinates), or moving with its displacement at t = 0 and
  // the rate of it there (central differences of the displacement in t; linear in the data).
  MovingMesh mm(mesh);
  MeshState ms{mesh.x, {}};
  if (motion.moving()) {
    std::vector<double> plus, minus;
    const double delta = 1e-4 * tc.dt;
    if (!motion.displacement(0.0, mm.d) || !motion.displacement(delta, plus) ||
        !motion.displacement(-delta, minus))
      SEAM_THROW(SolverError, "the linear solver of the pseudo-elastic mesh failed at t = 0");
    mm.d_dot.resize(mm.d.size());
    for (std::size_t k = 0; k < mm.d.size(); ++k)
      mm.d_dot[k] = unsteady ? (plus[k] - minus[k]) / (2.0 * delta) : 0.0;
    mm.w = unsteady ? mm.d_dot : std::vector<double>();
    ms = {mm.at(mm.d), mm.w};
    if (any_inverted(layout, ms.x))
      SEAM_THROW(SolverError, "a fluid cell is inverted (det J <= 0) by the mesh displacement at "
                              "t = 0");
    ties(ms.x);
  }
  if (tying) { // the initial state satisfies the tying constraint at t = 0 (slave: P v_M)
    tying->expand(w, w_old);
    w.copy_from(w_old);
    w.update_ghosts();
  }
  // The consistent initial state of generalized-alpha: the velocity's rate and the pressure
  // at t = 0 that satisfy the momentum equations at the initial velocity, with the rates of
  // the velocity conditions and div u_dot = 0 (the projection of the initial acceleration).
  // Started from u_dot = 0 and p = 0 instead, the integrator carries the error of the start
  // as a mode multiplied by -(1 - alpha_f) / alpha_f (pressure) and (1 - 1 / gamma) (rate)
  // every step. A restart continues from its stored state. Only on Taylor-Hood cells: the
  // stabilized cells' continuity rows hold the rate only through the PSPG term, and the
  // system they give at t = 0 was found singular (the free stream of test_ale.py); they start
  // from u_dot = 0, p = 0 as before.
  bool stabilized = false;
  for (auto c : layout.local_cells())
    stabilized = stabilized || fluid::is_stabilized(mesh.cell_type[c]);
  if (unsteady && !checkpoints.restarting() && !comm.any(stabilized)) {
    la::Vector y = layout.make_vector();
    const FluidNewton::Evaluator initial = [&](const la::Vector& yk, la::Vector& r, la::Matrix& K) {
      return assemble(model, layout, ms, {&w, &yk, &yk, 0.0, 1.0, tc.dt, true}, 0.0, r, &K);
    };
    const FluidNewton::Prescriber rates = [&](la::Vector& yk) {
      impose(model, layout, 0.0, yk, 1e-4 * tc.dt);
    };
    newton.set_pcd_mesh(ms.x, ms.w);
    const auto res = newton.solve_initial(y, initial, rates);
    if (!res.converged)
      SEAM_THROW(SolverError, res.failure,
                 " in the consistent initial state (the velocity's rate "
                 "and the pressure at t = 0)");
    u_dot.copy_from(y);
    u_dot.update_ghosts();
    {
      la::Vector::LocalView wv(w, true), yv(y, false);
      for (std::int32_t n = 0; n < mesh.n_nodes(); ++n)
        if (layout.owns_node(n) && layout.has_pressure(n)) {
          const auto k = layout.local_dof(n, layout.dim());
          wv.values()[k] = yv.values()[k];
        }
    }
    w.update_ghosts();
  }
  // The residual of the step holds the forces at t_{n+alpha_f}; they are reported at t_{n+1},
  // F_{n+1} = (F_{n+alpha_f} - (1 - alpha_f) F_n) / alpha_f, from the initial state's forces.
  std::vector<std::array<double, 3>> last_forces;
  if (unsteady) {
    la::Vector r0 = layout.make_vector();
    assemble(model, layout, ms, {&w, &w, &u_dot}, 0.0, r0, nullptr);
    last_forces = forces(model, layout, r0);
  }
  // Steps as the solid runs them (docs/input.md §6.3): a failed Newton attempt restores the
  // last converged state and halves the step.
  StepControl control(tc);
  int step = 0;
  if (checkpoints.restarting()) {
    const auto& r = checkpoints.restart();
    step = checkpoints.restart_step();
    control.set_state({checkpoints.restart_time(), r.real("control.dt"),
                       static_cast<int>(r.integer("control.cuts"))});
    newton.set_reference(r.real("newton.reference"));
    checkpoints.get_vector("w", w);
    if (unsteady) {
      checkpoints.get_vector("u_dot", u_dot);
      const auto f = r.reals("last_forces", last_forces.size() * 3);
      for (std::size_t g = 0; g < last_forces.size(); ++g)
        for (int i = 0; i < 3; ++i) last_forces[g][i] = f[g * 3 + i];
    }
    if (motion.moving()) {
      get_nodal(checkpoints, layout, "mesh.d", mm.d);
      get_nodal(checkpoints, layout, "mesh.d_dot", mm.d_dot);
    }
    if (comm.is_root() && !quiet)
      std::printf("  restarting from %s: step %d, t = %.17g\n", restart.checkpoint.c_str(), step,
                  control.time());
  }
  while (control.running()) {
    const double t = control.time(), t_new = control.next();
    w_old.copy_from(w);
    w_old.update_ghosts();
    const double h = t_new - t;
    // The mesh of the step: its displacement at t_new, checked for inverted cells, then the
    // configuration and mesh velocity the equations are integrated with (steady: the mesh at
    // t_new at rest; generalized-alpha: ale::step_mesh).
    NewtonOutcome res;
    if (motion.moving()) {
      if (!motion.displacement(t_new, mm.d_new)) {
        res.failure = "the linear solver of the pseudo-elastic mesh failed";
      } else if (any_inverted(layout, mm.at(mm.d_new))) {
        res.failure = "a fluid cell is inverted (det J <= 0) by the mesh motion";
      } else {
        ties(mm.x); // the tied interface at t_new (mm.x = X + d_new)
        if (unsteady) {
          mm.d_dot_new.resize(mm.d.size());
          ale::step_mesh(ga, h, mm.X, mm.d, mm.d_new, mm.d_dot, mm.x, mm.w, mm.d_dot_new);
          ms = {mm.x, mm.w};
        } else {
          ms = {mm.x, {}};
        }
      }
    }
    const FluidNewton::Evaluator steady = [&](const la::Vector& wk, la::Vector& r, la::Matrix& K) {
      return assemble(model, layout, ms, {&wk, &wk}, t_new, r, &K);
    };
    // u_dot_{n+1} = (u_{n+1} - u_n) / (gamma h) - (1 - gamma) / gamma u_dot_n, and the
    // intermediate states u_{n+alpha_f}, u_dot_{n+alpha_m}; loads at t_{n+alpha_f}.
    const FluidNewton::Evaluator generalized_alpha = [&](const la::Vector& wk, la::Vector& r,
                                                         la::Matrix& K) {
      u_dot_new.copy_from(wk);
      u_dot_new.axpy(-1.0, w_old);
      u_dot_new.scale(1.0 / (gamma * h));
      u_dot_new.axpy(-(1.0 - gamma) / gamma, u_dot);
      u_dot_m.copy_from(u_dot);
      u_dot_m.scale(1.0 - alpha_m);
      u_dot_m.axpy(alpha_m, u_dot_new);
      u_dot_m.update_ghosts();
      w_f.copy_from(w_old);
      w_f.scale(1.0 - alpha_f);
      w_f.axpy(alpha_f, wk);
      w_f.update_ghosts();
      newton.set_pcd_weights({alpha_f, alpha_m / (gamma * h), alpha_f * alpha_f});
      return assemble(model, layout, ms, {&w_f, &w_f, &u_dot_m, alpha_f, alpha_m / (gamma * h), h},
                      t + alpha_f * h, r, &K);
    };
    if (*res.failure == '\0') {
      newton.set_pcd_mesh(ms.x, ms.w);
      res = newton.solve(w, t_new, step + 1, unsteady ? generalized_alpha : steady);
    }
    if (!res.converged) {
      w.copy_from(w_old);
      w.update_ghosts();
      if (control.cut(res.failure, t_new, comm)) continue;
      out.finish(false, step);
      SEAM_THROW(SolverError, res.failure, " at t = ", t_new, " after ", control.cuts(),
                 " step cuts; the ", step, " converged steps are written in ", dir.string());
    }
    if (unsteady) {
      u_dot.copy_from(u_dot_new); // of the converged state: its last evaluation
      u_dot.update_ghosts();
    }
    if (motion.moving()) {
      mm.d.swap(mm.d_new);
      if (unsteady) mm.d_dot.swap(mm.d_dot_new);
    }
    ++step;
    control.accept(t_new);
    FluidStepRecord rec;
    rec.step = step;
    rec.time = t_new;
    rec.newton_iterations = res.iterations;
    rec.residual = res.residual;
    rec.forces = forces(model, layout, newton.full_residual());
    if (unsteady) {
      for (std::size_t g = 0; g < rec.forces.size(); ++g)
        for (int i = 0; i < 3; ++i)
          rec.forces[g][i] = (rec.forces[g][i] - (1.0 - alpha_f) * last_forces[g][i]) / alpha_f;
      last_forces = rec.forces;
    }
    // Errors on the mesh at t_{n+1}.
    const MeshState now{motion.moving() ? mm.at(mm.d) : std::span<const double>(mesh.x), {}};
    if (exact) rec.errors = errors(config, model, layout, now, w, t_new);
    out.step(rec, w, motion.moving() ? std::span<const double>(mm.d) : std::span<const double>(),
             !control.running());
    if (checkpoints.due(step)) {
      const auto c = control.state();
      auto writer = checkpoints.begin(step, c.t);
      writer.put_real("control.dt", c.dt);
      writer.put_integer("control.cuts", c.cuts);
      writer.put_real("newton.reference", newton.reference());
      checkpoints.put_vector(writer, "w", w);
      if (unsteady) {
        checkpoints.put_vector(writer, "u_dot", u_dot);
        std::vector<double> f;
        for (const auto& g : last_forces) f.insert(f.end(), g.begin(), g.end());
        writer.put("last_forces", f);
      }
      // The moving mesh: its displacement and rate at t, in the velocity slots of the
      // stored order (nodal, written by the owners).
      if (motion.moving()) {
        put_nodal(checkpoints, writer, layout, "mesh.d", mm.d);
        put_nodal(checkpoints, writer, layout, "mesh.d_dot", mm.d_dot);
      }
      out.write_checkpoint(writer);
      checkpoints.commit(writer, step);
    }
  }
  out.finish(true, step);
  return info;
}

} // namespace

FluidRunInfo run_fluid(const io::Config& config, mesh::DistributedMesh& part,
                       const MeshIdentity& identity, Comm comm, const std::filesystem::path& dir,
                       bool quiet, const RestartFrom& restart, bool check_only) {
  const FluidLayout layout(part, comm);
  return run_on(
      config, layout,
      [&](PhaseTimers& timers, std::span<const double> x) {
        if (x.empty()) return meshtying::setup_mesh_tying(config, part, comm.get(), timers);
        // The interface where the mesh has moved it: set up on the moved coordinates, whose
        // slave nodes the mesh initialization may shift; the mesh keeps its own.
        std::vector<double> moved(x.begin(), x.end());
        part.mesh.x.swap(moved);
        try {
          auto tied = meshtying::setup_mesh_tying(config, part, comm.get(), timers);
          part.mesh.x.swap(moved);
          return tied;
        } catch (...) {
          part.mesh.x.swap(moved);
          throw;
        }
      },
      [&] { return identity; }, dir, quiet, check_only, restart);
}

} // namespace seam::flow
