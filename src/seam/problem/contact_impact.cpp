// The energy an energy-momentum step gains through contact (docs/contact_dynamics.md §5,
// "Penetration at the start of the step"). With the discrete-gradient force every step satisfies
//   E_{n+1} - E_n = -sum_j lambda_j g~_j(x_n)   (+ the work of the loads, - the frictional
//   dissipation; lambda_j the normal part of a frictional multiplier),
// a loss where a node takes contact from a positive gap and zero in persistent contact. A slave
// node that starts the step beyond the other surface (g~_j(x_n) < 0: a master node of the last
// step that self contact makes a slave now, or a node whose pair did not exist at x_n) makes the
// step gain e_j = -lambda_j g~_j(x_n). The solver removes that gain from the kinetic energy by an
// impulse along d = sum_j e_j grad g~_j(x_{n+1}) (dynamic_solver.cpp): each g~_j between two
// deformable bodies is invariant under rigid motions, so d has no resultant and no moment about
// x_{n+1}, and the impulse keeps both momenta.
// A node held active with a tensile multiplier (lambda_j < 0: the cycling guard's union of a
// chattering active set, kept for the rest of the step) pulls the surfaces together, and its
// work -lambda_j g~_j(x_n) > 0 from a positive gap is created energy as well, also against a
// rigid obstacle; there its rows go to `obstacle` (the patch of the update's second stage only:
// an impulse along them would change the momenta, which the obstacle's force does not account).
#include "seam/problem/contact_constraint.hpp"

#include "seam/parallel/exchange.hpp"

#include <algorithm>

namespace seam::problem {

ContactConstraint::ImpactGain ContactConstraint::impact_gain(la::Vector& d,
                                                             la::Vector& obstacle) const {
  ImpactGain out;
  std::vector<PetscInt> rows, obstacle_rows;
  std::vector<double> values, obstacle_values, gains;
  for (const auto& s : sides_) {
    if (!s.discrete_gradient) continue;
    // With friction the normal part n_j . lambda_j takes the discrete gradient; the tangential
    // part's work is the step's dissipation, lambda_t,j . u~_j, a function of the positions
    // only, so the update (velocities only) leaves it as interfaces.csv reports it.
    const auto lambda = normal_multipliers(s);
    // Against a rigid obstacle g~_j(x_n) < 0 with lambda_j > 0 only where the obstacle moved
    // into the body in the step (every converged state has g~_j >= 0 against the obstacle's
    // position then): that gain is the obstacle's work, not an error of the step. Only tensile
    // multipliers count there.
    const bool rigid = s.itf.rigid();
    if (rigid) {
      bool tensile = false;
      for (std::size_t j = 0; j < lambda.size(); ++j)
        tensile = tensile || (lambda[j] < 0.0 && s.node_owners[j] == disc_.comm().rank());
      if (disc_.comm().max(tensile ? 1.0 : 0.0) == 0.0) continue;
    }
    // The weighted gaps at x_n of the pairs of the last evaluate(), as the discrete gradient
    // took them (the same blocks at the same displacement), summed over the ranks.
    std::vector<contact::GapBlock> start;
    s.itf.gap_blocks(u_mesh_start_, contact::GapOrder::value, start);
    std::vector<double> gap_start(lambda.size(), 0.0);
    for (const auto& b : start)
      for (std::size_t r = 0; r < b.slave.size(); ++r)
        gap_start[static_cast<std::size_t>(b.slave[r])] += b.gap[r];
    // Summed on the owners of the nodes and published to their holders (a side held in part
    // holds its part's nodes only).
    parallel::sum_on_owners(disc_.comm().get(), s.node_keys, s.node_owners, gap_start, 1);
    publish(s, gap_start, 1);
    std::vector<double> e(gap_start.size(), 0.0);
    for (std::size_t j = 0; j < e.size(); ++j) {
      e[j] = rigid && !(lambda[j] < 0.0) ? 0.0 : std::max(0.0, -lambda[j] * gap_start[j]);
      // Each node's gain counted by its owner.
      if (s.node_owners[j] == disc_.comm().rank()) {
        out.gain += e[j];
        gains.push_back(e[j]);
      }
    }
    // This rank's part of grad g~_j(x_{n+1}) (the gap rows of the last evaluate()).
    for (const auto& g : s.lin.gap_gradient)
      if (const double w = e[static_cast<std::size_t>(g.row)]; w > 0.0) {
        (rigid ? obstacle_rows : rows).push_back(global_dof(g.col));
        (rigid ? obstacle_values : values).push_back(w * g.value);
      }
  }
  out.gain = disc_.comm().sum(out.gain);
  out.nodes = static_cast<int>(disc_.comm().sum(static_cast<double>(
      std::count_if(gains.begin(), gains.end(), [&](double x) { return x > 1e-6 * out.gain; }))));
  d.add_values(rows, values);
  d.assemble();
  obstacle.add_values(obstacle_rows, obstacle_values);
  obstacle.assemble();
  return out;
}

} // namespace seam::problem
