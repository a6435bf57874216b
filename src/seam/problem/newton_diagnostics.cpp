// Diagnostics of a stalled Newton step (docs/contact_dynamics.md, "Diagnosing a stalled Newton
// step"), off unless asked for by environment variables; they change nothing in the run except
// that the checked run ends after the check.
//
// SEAM_CONTACT_TRACE=1: a line per contact side and iteration with the candidate pairs, the
// overlapping gap blocks (with hashes of both sets), the active nodes and the nodes with a gap
// row (ContactConstraint::trace).
//
// SEAM_NEWTON_CHECK=STEP:IT: at iteration IT of the first attempt of step STEP, after the
// saddle-point solve of the Newton correction v = (dd, dlambda), the whole nonlinear system
//   F(d, lambda) = [ r(d) + B(d)^T lambda (free rows) ; constraint rows ]
// (r the bulk residual of the time step with inertia, the constraint rows
// ContactConstraint::constraint_values: g~_j on active nodes, lambda_j on inactive ones) is
// evaluated along v with the statuses held (hold_sets), and printed:
//  - the linear solve's relative residual |A x - b| / |b|;
//  - for a = 1, 0.5, 0.1, ... 1e-6: the linear model's error along v,
//      |F(a v) - (1 - a) F(0)| / (a |F(0)|)   (displacement and constraint rows apart),
//    which falls like a if J is the derivative of F, and levels off at |J_true v - J v| / |F|
//    where the assembled J is not; and the central difference |(F(a v) - F(-a v)) / 2a + F(0)|
//    / |F(0)|;
//  - the rows with the largest entries of F(v) (the residual the full correction leaves) and
//    of the central-difference error at a = 1e-3, with their nodes, positions and contact
//    statuses.
// Then the run stops (exit code 3). np = 1 (the rows listed are rank 0's).
#include "seam/problem/diagnostics.hpp"
#include "seam/problem/newton.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <numeric>
#include <span>
#include <string>

namespace seam::problem {

namespace {

/// The indices of the (at most 12) entries of `values` with the largest magnitudes, largest
/// first.
std::vector<std::size_t> largest_entries(std::span<const double> values) {
  std::vector<std::size_t> order(values.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t n = std::min<std::size_t>(12, order.size());
  std::partial_sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(n), order.end(),
                    [&](auto a, auto b) { return std::abs(values[a]) > std::abs(values[b]); });
  order.resize(n);
  return order;
}

bool parse_check(int& step, int& iteration) {
  const char* v = std::getenv("SEAM_NEWTON_CHECK");
  return v != nullptr && std::sscanf(v, "%d:%d", &step, &iteration) == 2;
}

} // namespace

bool NewtonSolver::trace_contact() {
  return contact_trace_level() >= 1;
}

bool NewtonSolver::check_requested(int step, int iteration) {
  int s = 0, i = 0;
  return parse_check(s, i) && s == step && i == iteration;
}

[[noreturn]] void NewtonSolver::check_correction(la::Vector& u, double t, int step, int it,
                                                 const Evaluator& evaluate,
                                                 const std::vector<double>& lambda_old) {
  const auto& comm = disc_.comm();
  const int dim = disc_.dim();
  const bool root = comm.is_root();
  const auto lambda_new = contact_.multipliers();
  std::vector<double> dl(lambda_new.size());
  for (std::size_t i = 0; i < dl.size(); ++i) dl[i] = lambda_new[i] - lambda_old[i];
  la::Vector u0 = disc_.make_vector(), v = disc_.make_vector();
  u0.copy_from(u);
  v.copy_from(du_);
  la::Vector state = disc_.make_vector();
  la::Vector f_ext = disc_.make_vector();
  contact_.hold_sets(true);
  // F at (u0 + a v, lambda_old + a dlambda), statuses held.
  la::Vector bulk = disc_.make_vector(); // the bulk part (inertia, stress, loads) of the last F
  const auto F = [&](double a, la::Vector& out_d, std::vector<double>& out_c) {
    state.copy_from(u0);
    state.axpy(a, v);
    state.update_ghosts();
    std::vector<double> lambda(lambda_old.size());
    for (std::size_t i = 0; i < lambda.size(); ++i) lambda[i] = lambda_old[i] + a * dl[i];
    evaluate(state, out_d, nullptr, f_ext);
    bulk.copy_from(out_d);
    zero_dirichlet_rows(model_, disc_, bulk);
    contact_.set_multipliers(lambda);
    contact_.evaluate(state, t, false, out_.timers());
    contact_.hold_sets(true);
    contact_.add_force(out_d);
    zero_dirichlet_rows(model_, disc_, out_d);
    out_c = contact_.constraint_values();
  };
  // The largest rows of a vector of displacement rows, with their nodes.
  la::Vector::LocalView uv(u0, false);
  const auto ul = uv.values();
  const auto& X = disc_.mesh().x;
  std::vector<std::pair<std::int32_t, int>> dof_node(
      static_cast<std::size_t>(disc_.n_owned_dofs()));
  for (std::int32_t n = 0; n < disc_.mesh().n_nodes(); ++n)
    if (disc_.has_node(n) && disc_.owns_node(n))
      for (int c = 0; c < dim; ++c) {
        const auto i = static_cast<std::size_t>(disc_.local_dof(n, c));
        if (i < dof_node.size()) dof_node[i] = {n, c};
      }
  const auto largest_rows = [&](const char* what, const la::Vector& d) {
    if (!root) return;
    la::Vector::LocalView view(d, false);
    const auto values = view.values();
    std::printf("  %s, displacement rows:\n", what);
    for (const auto i : largest_entries(values)) {
      const auto [node, comp] = dof_node[i];
      const auto p = static_cast<std::size_t>(node) * dim;
      std::printf("    %11.4e  node %lld %c at (%.5f, %.5f)  %s\n", values[i],
                  static_cast<long long>(disc_.node_gid(node)), "xyz"[comp],
                  X[p] + ul[disc_.local_dof(node, 0)], X[p + 1] + ul[disc_.local_dof(node, 1)],
                  contact_.describe_node(node).c_str());
    }
  };
  la::Vector F0 = disc_.make_vector(), bulk0 = disc_.make_vector();
  std::vector<double> F0c;
  F(0.0, F0, F0c);
  bulk0.copy_from(bulk);
  const auto norm_c = [](const std::vector<double>& c) {
    return std::sqrt(std::inner_product(c.begin(), c.end(), c.begin(), 0.0));
  };
  const double n0d = F0.norm(), n0c = norm_c(F0c);
  if (root)
    std::printf("newton check, step %d iteration %d, t = %.9g: |F| displacement rows %.4e, "
                "constraint rows %.4e; |dd| %.4e, |dlambda| %.4e; linear solve |Ax - b|/|b| "
                "%.3e\n",
                step, it, t, n0d, n0c, v.norm(), norm_c(dl), contact_.last_solve_residual());
  for (const auto& line : contact_.trace())
    if (root) std::printf("  at d: %s\n", line.c_str());
  la::Vector central_error = disc_.make_vector();
  std::vector<double> central_error_c;
  la::Vector full = disc_.make_vector();
  std::vector<double> full_c;
  // Second differences F(a v) + F(-a v) - 2 F(0) ~ a^2 F''[v, v], of the bulk part and of the
  // contact force apart: which of them bends the residual within the correction.
  la::Vector bulk_second = disc_.make_vector(), contact_second = disc_.make_vector();
  la::Vector Fa = disc_.make_vector(), Fb = disc_.make_vector(), e = disc_.make_vector();
  std::vector<double> Fac, Fbc, ec;
  for (const double a : {1.0, 0.1, 0.01}) {
    F(a, Fa, Fac);
    bulk_second.copy_from(bulk);
    contact_second.copy_from(Fa);
    contact_second.axpy(-1.0, bulk);
    F(-a, Fb, Fbc);
    bulk_second.axpy(1.0, bulk);
    contact_second.axpy(1.0, Fb);
    contact_second.axpy(-1.0, bulk);
    bulk_second.axpy(-2.0, bulk0);
    contact_second.axpy(-2.0, F0);
    contact_second.axpy(2.0, bulk0);
    if (root)
      std::printf("  a = %7.1e  second differences / a^2: bulk %.4e, contact force %.4e\n", a,
                  bulk_second.norm() / (a * a), contact_second.norm() / (a * a));
    if (a == 1.0) {
      largest_rows("second difference at a = 1, bulk", bulk_second);
      largest_rows("second difference at a = 1, contact force", contact_second);
    }
  }
  for (const double a : {1.0, 0.5, 0.1, 1e-2, 1e-3, 1e-4, 1e-5, 1e-6}) {
    F(a, Fa, Fac);
    if (a == 1.0) {
      full.copy_from(Fa);
      full_c = Fac;
      for (const auto& line : contact_.trace())
        if (root) std::printf("  at d + dd: %s\n", line.c_str());
    }
    // Forward: |F(a) - (1 - a) F0| / (a |F0|).
    e.copy_from(Fa);
    e.axpy(-(1.0 - a), F0);
    ec.resize(Fac.size());
    for (std::size_t i = 0; i < ec.size(); ++i) ec[i] = Fac[i] - (1.0 - a) * F0c[i];
    const double fwd_d = e.norm() / (a * n0d), fwd_c = norm_c(ec) / (a * n0c);
    // Central: (F(a) - F(-a)) / 2a + F0.
    F(-a, Fb, Fbc);
    e.copy_from(Fa);
    e.axpy(-1.0, Fb);
    e.scale(0.5 / a);
    e.axpy(1.0, F0);
    for (std::size_t i = 0; i < ec.size(); ++i) ec[i] = (Fac[i] - Fbc[i]) * 0.5 / a + F0c[i];
    if (root)
      std::printf("  a = %7.1e  |F(a)| %.4e / %.4e  forward %.3e / %.3e  central %.3e / %.3e "
                  "(displacement / constraint rows, relative)\n",
                  a, Fa.norm(), norm_c(Fac), fwd_d, fwd_c, e.norm() / n0d, norm_c(ec) / n0c);
    if (a == 1e-3) {
      central_error.copy_from(e);
      central_error_c = ec;
    }
  }
  const auto largest = [&](const char* what, const la::Vector& d, const std::vector<double>& c) {
    if (!root) return;
    largest_rows(what, d);
    std::printf("  %s, constraint rows:\n", what);
    for (const auto k : largest_entries(c))
      std::printf("    %11.4e  %s\n", c[k], contact_.describe_multiplier(k).c_str());
  };
  // Statuses and multipliers of d + dd for the descriptions of F(v)'s rows.
  F(1.0, Fa, Fac);
  largest("F(d + dd): the residual the full correction leaves", full, full_c);
  F(0.0, Fa, Fac);
  largest("central difference at a = 1e-3 + F(d): J_true v - J v", central_error, central_error_c);
  contact_.hold_sets(false);
  std::fflush(stdout);
  comm.barrier();
  std::exit(3);
}

} // namespace seam::problem
