// A slave node that a frozen or held active set keeps active but that has no pair at the
// current iterate (D_jj = 0) has no gap row and no force column: kept active, it makes the
// saddle point of energy-momentum contact (and of standard multipliers) singular. This is what
// stopped the 200 rings of examples/rings at t = 0.66 (MUMPS INFO(1) = -10): the cycling guard
// froze the union of the active sets of a cycle, and a node of that union whose facets the self
// contact search had made master only lost its pairs. ContactConstraint::evaluate releases such
// a node (inactive, lambda_j = 0) and counts it (n_released()).
//
// The case: a block pressed onto a wider base, both boundaries one `surface:` interface,
// energy-momentum contact. With the pressed state's active set held (hold_sets, the same branch
// as a set frozen by the cycling guard) the block is lifted by twice its height, beyond the
// search's reach (every pair gone), or slid sideways until most of its bottom leaves the base
// (some pairs gone). Each time the held active nodes without a pair must be released and the
// saddle point must solve. Without the release the lifted case keeps every node active with
// empty rows and the linear solver fails.
#include "contact_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace seam::problem {
namespace {

struct Outcome {
  int active_before = 0, active_after = 0, released = 0;
  bool solved = false, finite = false;
};

/// Presses the block, holds the active set, moves the block rigidly by (dx, dy) and solves
/// the saddle point there.
Outcome held_set_after_motion(const std::string& name, double dx, double dy) {
  Comm comm;
  const auto folder =
      write_block_on_base(comm, "released_" + name, "'-0.01*t'",
                          "time: {integrator: energy_momentum, end: 2.0, steps: 2}\n"
                          "solver: {newton: {tolerance: 1e-11, max_iterations: 40}}\n");
  ContactRun run(comm, folder, false);
  const Discretization& disc = run.disc;
  const Model& model = run.model;
  ContactConstraint& contact = run.contact;
  la::Vector u = disc.make_vector();
  Outcome o;
  contact.start_step(u);
  EXPECT_TRUE(run.newton.solve(u, 1.0, 1, run.evaluator(1.0)).converged) << name << ": press";
  run.newton.accept();
  contact.start_step(u);
  o.active_before = contact.n_active();

  // The pressed state's set held; the block (its own nodes) moved rigidly.
  contact.hold_sets(true);
  {
    std::vector<PetscInt> rows;
    std::vector<double> values;
    for (const auto node : run.mesh.region("body", 2).nodes) {
      if (!disc.owns_node(node)) continue;
      rows.push_back(disc.global_dof(node, 0));
      values.push_back(dx);
      rows.push_back(disc.global_dof(node, 1));
      values.push_back(dy);
    }
    u.add_values(rows, values);
    u.assemble();
    u.update_ghosts();
  }
  const double t = 2.0;
  contact.evaluate(u, t, false, run.timers);
  o.active_after = contact.n_active();
  o.released = contact.n_released();

  la::Matrix K = disc.make_matrix();
  la::Vector r = disc.make_vector(), f_ext = disc.make_vector(), dd = disc.make_vector();
  assemble(model, disc, u, t, r, &K, &f_ext);
  la::Vector minus_r = disc.make_vector();
  minus_r.copy_from(r);
  minus_r.scale(-1.0);
  zero_dirichlet_rows(model, disc, minus_r);
  std::vector<PetscInt> dirichlet;
  for (const auto& d : model.dirichlet) dirichlet.push_back(d.dof);
  la::LinearSolver solver(comm.get(), la::SolverKind::direct);
  o.solved = contact.solve_saddle_point(K, minus_r, dirichlet, nullptr, solver, dd, run.timers);
  o.finite = std::isfinite(dd.norm());
  for (const double l : contact.multipliers()) o.finite = o.finite && std::isfinite(l);
  contact.hold_sets(false);
  if (comm.is_root()) {
    std::printf("  %-8s active %d -> %d, released %d, saddle point %s\n", name.c_str(),
                o.active_before, o.active_after, o.released, o.solved ? "solved" : "failed");
    std::filesystem::remove_all(folder);
  }
  comm.barrier();
  return o;
}

TEST(ReleasedNodes, HeldNodesWithoutPairsAreReleased) {
  // Lifted beyond the search's reach: every held node has lost its pairs.
  const Outcome lift = held_set_after_motion("lifted", 0.0, 0.5);
  EXPECT_GT(lift.active_before, 0);
  EXPECT_EQ(lift.active_after, 0);
  EXPECT_EQ(lift.released, lift.active_before);
  EXPECT_TRUE(lift.solved);
  EXPECT_TRUE(lift.finite);
  // Slid by 1.1: the block's bottom overlaps the base on [1.1, 1.3] only.
  const Outcome slide = held_set_after_motion("slid", 1.1, 0.0);
  EXPECT_GT(slide.released, 0);
  EXPECT_EQ(slide.active_after + slide.released, slide.active_before);
  EXPECT_TRUE(slide.solved);
  EXPECT_TRUE(slide.finite);
}

} // namespace
} // namespace seam::problem
