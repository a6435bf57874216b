#pragma once
// Newton's method on the bulk system with its constraints: Dirichlet conditions (with a
// predictor that carries the prescribed increment), condensed mesh tying (T^T K T) or
// saddle-point mesh tying. What is solved (static equilibrium, a time step of a dynamic
// scheme) comes in as an evaluator of the residual and tangent.
#include "seam/io/config.hpp"
#include "seam/la/petsc.hpp"
#include "seam/problem/assembly.hpp"
#include "seam/problem/contact_constraint.hpp"
#include "seam/problem/discretization.hpp"
#include "seam/problem/linear_solver_choice.hpp"
#include "seam/problem/model.hpp"
#include "seam/problem/output.hpp"
#include "seam/problem/saddle_point.hpp"
#include "seam/problem/step_control.hpp"
#include "seam/problem/tying_constraint.hpp"

#include <functional>
#include <string>
#include <vector>

namespace seam::problem {

/// g = (prescribed values at time t) - u on the Dirichlet dofs, 0 elsewhere. Returns whether
/// any rank has a nonzero prescribed increment.
bool dirichlet_increment(const Model& model, const Discretization& disc, const la::Vector& u,
                         double t, la::Vector& g);
/// Zeroes the Dirichlet rows of r (they hold the reactions, kept in the full residual).
void zero_dirichlet_rows(const Model& model, const Discretization& disc, la::Vector& r);

struct NewtonResult {
  bool converged = false;
  int iterations = 0;
  double residual = 0.0;
  double strain_energy = 0.0;
  const char* failure = "";
};

/// Whether the bulk tangent of a static run is constant: every body linear_elastic (small
/// strain), no follower (pressure) loads on any rank, no saddle-point system. Collective.
bool constant_tangent(const Model& model, const Discretization& disc, bool saddle_point);

/// The share of the mesh's nodes on its boundary (nodes of exterior facets), over all ranks.
/// Collective.
double boundary_node_fraction(const Discretization& disc);

/// The linear solver of a solid's Newton system (linear_solver_choice.hpp).
la::SolverKind linear_solver_kind(const io::Config& config, const Discretization& disc,
                                  bool saddle_point);
/// The solver and why, for the run's header (collective): "direct (MUMPS)", "iterative (GMRES +
/// GAMG; auto: 3D, 107811 dofs >= 100000)".
std::string describe_linear_solver(const io::Config& config, const Discretization& disc,
                                   bool saddle_point);

class NewtonSolver {
public:
  NewtonSolver(const io::Config& config, const Model& model, const Discretization& disc,
               const TyingConstraint& tying, SaddlePoint& saddle, ContactConstraint& contact,
               Output& out)
      : config_(config), model_(model), disc_(disc), tying_(tying), saddle_(saddle),
        contact_(contact), out_(out), K_(disc.make_matrix()), r_(disc.make_vector()),
        r_full_(disc.make_vector()), rt_(disc.make_vector()), du_(disc.make_vector()),
        dut_(disc.make_vector()), g_(disc.make_vector()), f_ext_(disc.make_vector()),
        u_base_(disc.make_vector()),
        solver_(disc.comm().get(),
                linear_solver_kind(config, disc, saddle.active() || contact.saddle_point())),
        line_search_(config.solver.newton.line_search && contact.active() && !saddle.active()) {
    for (const auto& d : model_.dirichlet) dirichlet_rows_.push_back(d.dof);
    // Rows fixed in the Newton system: Dirichlet dofs and (with condensed tying) the
    // eliminated slave dofs, whose rows of T^T K T are empty.
    fixed_rows_ = dirichlet_rows_;
    if (tying.active())
      fixed_rows_.insert(fixed_rows_.end(), tying.eliminated_dofs().begin(),
                         tying.eliminated_dofs().end());
    const auto X = disc.coordinates_vector();
    reference_coordinates_ = X.norm();
    iterative_ = linear_solver_kind(config, disc, saddle.active() || contact.saddle_point()) ==
                 la::SolverKind::iterative;
    if (iterative_) K_.set_near_null_space(X);
    // Within a load step the Newton matrices differ little: GAMG's hierarchy of the first
    // solve preconditions the later ones (la::LinearSolver::keep_preconditioner).
    solver_.keep_preconditioner(iterative_);
  }

  /// Whether the bulk tangent is the same at every state of a load step: assembled at the
  /// first iteration only, the later ones assemble the residual alone (static runs of
  /// linear_elastic bodies without follower loads and saddle points: constant_tangent()).
  void set_constant_tangent(bool on) { constant_tangent_ = on; }

  /// Newton iterations at time t from the last converged u. The first iteration is the
  /// predictor: it is linearized at the old state and carries the increment of the prescribed
  /// displacements as an inhomogeneous constraint, so the interior follows the moving
  /// boundary instead of being left behind (which would invert the elements next to it).
  /// Evaluates r = f_int - f_ext (plus any inertia), its tangent K (unless K is null: the
  /// residual alone) and f_ext alone at u.
  using Evaluator = std::function<AssemblyStatus(const la::Vector& u, la::Vector& r, la::Matrix* K,
                                                 la::Vector& f_ext)>;
  NewtonResult solve(la::Vector& u, double t, int step, const Evaluator& evaluate);

  /// A failed attempt: back to the last converged displacements u_old and multipliers.
  void reject(la::Vector& u, const la::Vector& u_old) {
    u.copy_from(u_old);
    u.update_ghosts();
    saddle_.restore();
    contact_.restore();
  }
  /// Whether the iterations go to newton.csv (on by default; auxiliary solves turn it off).
  void set_logging(bool on) { logging_ = on; }

  /// A converged step: its multipliers are where the next failed attempt returns to.
  /// The linear solver's ordering choice (la::LinearSolver::ordering_state), for checkpoints.
  std::vector<double> ordering_state() const { return solver_.ordering_state(); }
  void restore_ordering_state(std::span<const double> s) { solver_.restore_ordering_state(s); }
  void accept() {
    saddle_.save();
    contact_.save();
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

  /// All forces the surroundings exert on the bodies at the last evaluation: applied loads plus
  /// support reactions, f_ext + (f_int - f_ext) = f_int at equilibrium.
  /// With contact the bulk residual is taken and the contact forces between deformable bodies
  /// (two bodies, self contact) added back, so that only the rigid obstacles' contact forces
  /// count as external actions: the work of the forces the bodies exert on each other (what an
  /// impact dissipates, or a step would gain) stays in the energy balance.
  void total_external_force(la::Vector& out) const {
    out.copy_from(f_ext_);
    out.axpy(1.0, contact_.active() ? r_ : r_full_);
    if (contact_.active()) contact_.add_force(out, true);
  }

  /// The Lagrange multipliers of every mesh-tying interface (per slave node, dim values), on
  /// every rank (a distributed interface: of the slave nodes the rank owns): unknowns of the
  /// saddle-point system, or recovered from the slave rows of the residual before condensation,
  /// lambda = -r_S / D_SS. Collective.
  std::vector<std::vector<double>>
  multipliers(const std::vector<meshtying::TiedInterface>& tied) const {
    std::vector<std::vector<double>> out;
    la::Vector::LocalView r_view(r_, false);
    for (std::size_t k = 0; k < tied.size(); ++k) {
      if (tied[k].strategy == io::Strategy::saddle_point) {
        out.push_back(saddle_.multipliers(k));
      } else {
        out.push_back(tying_.multipliers(k, r_view.values()));
        if (!tied[k].distributed) disc_.comm().sum_in_place(out.back());
      }
    }
    return out;
  }

private:
  /// The state of one Newton iterate.
  struct State {
    AssemblyStatus assembly;
    int changes = 0;        ///< contact status changes against the previous evaluation, and frozen
                            ///< frictional nodes whose status violates its condition
    int status_changes = 0; ///< the status changes alone
    double norm = 0.0;      ///< residual norm of the free dofs (and constraints)
    double full_norm = 0.0; ///< with the reaction rows
    bool decided = false;   ///< the contact statuses were decided at this iterate
  };
  /// Evaluates the iterate u: r_, K_, f_ext_ (condensed by the tying into rt_, Kt_), the
  /// contact state with its statuses decided there (`first`: the first iteration of the step;
  /// `retrial`: a shortened correction, ContactConstraint::evaluate), r_full_ and the norms.
  /// Returns why the iterate is unusable, or "". `tangent` false: the residual alone, K_ is
  /// left as it was (tangent_current_ says so).
  const char* evaluate_state(const la::Vector& u, double t, bool first, bool retrial,
                             const Evaluator& evaluate, State& state, bool tangent = true);
  /// Whether iteration `it` is expected to converge, so that its evaluation may leave out the
  /// tangent: the last correction changed no contact status and, extrapolated quadratically
  /// from the last two residuals (|r_k| ~ |r_k-1|^2 / |r_k-2|), the residual falls below a
  /// tenth of the tolerance. Plain and condensed systems only (no saddle point, no tying).
  bool expect_convergence(int it, double tolerance, double reference) const;
  /// Diagnostics (newton_diagnostics.cpp): SEAM_CONTACT_TRACE=1 (or 2) and
  /// SEAM_NEWTON_CHECK=STEP:IT.
  static bool trace_contact();
  static bool check_requested(int step, int iteration);
  /// The correction du_ (and the multipliers' change from lambda_old) against differences of
  /// the residual along it; prints and ends the run.
  [[noreturn]] void check_correction(la::Vector& u, double t, int step, int it,
                                     const Evaluator& evaluate,
                                     const std::vector<double>& lambda_old);
  /// The last linear solve into summary.json's counts; a change of the factorization's
  /// ordering on the terminal.
  void count_linear_solve();
  /// u += du_ (and the prescribed values made exact after a predictor); ghosts updated.
  void apply_increment(la::Vector& u, double t, bool predictor);

  const io::Config& config_;
  const Model& model_;
  const Discretization& disc_;
  const TyingConstraint& tying_;
  SaddlePoint& saddle_;
  ContactConstraint& contact_;
  Output& out_;
  la::Matrix K_, Kt_;
  la::Vector r_, r_full_, rt_, du_, dut_, g_, f_ext_;
  la::Vector u_base_; ///< the iterate a correction starts from (line search)
  std::vector<PetscInt> fixed_rows_;
  la::LinearSolver solver_;
  /// Backtracking line search on condensed contact corrections (solver.newton.line_search;
  /// not with saddle points).
  bool line_search_ = false;
  /// Contact multipliers before a correction, after it in full, and at a trial point.
  std::vector<double> lambda_base_, lambda_full_, lambda_trial_;
  double full_increment_ = 0.0; ///< |du_| of the last correction in full
  std::vector<PetscInt> dirichlet_rows_;
  /// A contact status changed at an evaluation since the last factorization (or the step
  /// began): the direct solver must factor the next matrix (la::LinearSolver::allow_factor_reuse).
  bool statuses_changed_ = true;
  double last_increment_ = 0.0;
  double last_norm_ = 0.0;      // residual norm of the previous iteration
  double older_norm_ = 0.0;     // and of the one before (0 at the first two iterations)
  int last_changes_ = 0;        // contact status changes of the previous iteration
  bool tangent_current_ = true; ///< K_ belongs to the last evaluated state
  std::string failure_;         // the message of the last failed evaluation that names a node
  bool logging_ = true;
  bool iterative_ = false;             // the Newton systems go to GMRES + GAMG (inexact Newton)
  bool constant_tangent_ = false;      // set_constant_tangent
  double reference_coordinates_ = 0.0; // |X|, the scale of round-off in X + u
};

} // namespace seam::problem
