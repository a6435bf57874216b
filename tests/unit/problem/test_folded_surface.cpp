// A contact surface folded back onto itself at a slave node (the unit normals of the node's
// facets cancel, so the node has no averaged normal) is an unusable iterate during a run:
// ContactConstraint::evaluate reports the node (folded_node(), its id in the mesh as read) and
// Newton fails the attempt with a message naming it, which the step control cuts, as an inverted
// element. On the mesh as read (the first evaluation of the run) it is an InputError. The
// 200 rings of examples/rings with generalized-alpha stopped at t = 0.285 on such an iterate.
//
// The case: a block on a wider base, `surface: [bottom, base_top]`. The bottom node at
// (0.5, 0) is moved by 2 h in x, beyond its right neighbour: its two facets then run in
// opposite directions and their normals cancel. Every rank must agree (np 1 and np 3).
#include "contact_run.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace seam::problem {
namespace {

std::filesystem::path write_case(const Comm& comm, const std::string& name) {
  return write_block_on_base(comm, "folded_" + name, "0", "time: {end: 1.0, steps: 1}\n");
}

void remove_case(const Comm& comm, const std::filesystem::path& folder) {
  comm.barrier();
  if (comm.is_root()) std::filesystem::remove_all(folder);
}

/// Moves the bottom node at (0.5, 0) by 2 h in x (its owner adds it); returns its id in the
/// mesh as read, the same on every rank.
std::int64_t fold_bottom(ContactRun& run, la::Vector& u) {
  const Discretization& disc = run.disc;
  std::int64_t id = -1;
  std::vector<PetscInt> rows;
  std::vector<double> values;
  for (const auto node : run.mesh.region("bottom", 1).nodes) {
    const double* x = &run.mesh.x[static_cast<std::size_t>(node) * 2];
    if (std::abs(x[0] - 0.5) > 1e-9 || std::abs(x[1]) > 1e-9) continue;
    id = disc.node_gid(node);
    if (!disc.owns_node(node)) continue;
    rows.push_back(disc.global_dof(node, 0));
    values.push_back(0.125);
  }
  u.add_values(rows, values);
  u.assemble();
  u.update_ghosts();
  return disc.comm().max(id);
}

TEST(FoldedSurface, DuringARunTheIterateFails) {
  Comm comm;
  const auto folder = write_case(comm, "run");
  {
    ContactRun run(comm, folder, false);
    la::Vector u = run.disc.make_vector();
    run.contact.start_step(u);
    run.contact.evaluate(u, 1.0, true, run.timers);
    EXPECT_EQ(run.contact.folded_node(), -1);
    const std::int64_t id = fold_bottom(run, u);
    ASSERT_GE(id, 0);
    EXPECT_NO_THROW(run.contact.evaluate(u, 1.0, false, run.timers));
    EXPECT_EQ(run.contact.folded_node(), id);
    // Through Newton: the bulk (whose elements at the node the fold inverts) is taken as
    // usable, so that the contact evaluation is what fails the attempt.
    const auto bulk = run.evaluator(1.0);
    const auto evaluate = [&](const la::Vector& state, la::Vector& r, la::Matrix* K,
                              la::Vector& f_ext) {
      auto status = bulk(state, r, K, f_ext);
      status.inverted = false;
      return status;
    };
    const NewtonResult res = run.newton.solve(u, 1.0, 1, evaluate);
    EXPECT_FALSE(res.converged);
    const std::string failure = res.failure;
    EXPECT_NE(failure.find("folds back onto itself at slave node " + std::to_string(id) + " "),
              std::string::npos)
        << failure;
    // Unfolded again: usable.
    la::Vector zero = run.disc.make_vector();
    run.contact.evaluate(zero, 1.0, false, run.timers);
    EXPECT_EQ(run.contact.folded_node(), -1);
  }
  remove_case(comm, folder);
}

TEST(FoldedSurface, OnTheMeshAsReadItIsAnInputError) {
  Comm comm;
  const auto folder = write_case(comm, "input");
  {
    ContactRun run(comm, folder, false);
    la::Vector u = run.disc.make_vector();
    const std::int64_t id = fold_bottom(run, u);
    run.contact.start_step(u);
    try {
      run.contact.evaluate(u, 1.0, true, run.timers);
      ADD_FAILURE() << "no InputError";
    } catch (const InputError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("slave node " + std::to_string(id) + ":"), std::string::npos)
          << message;
      EXPECT_NE(message.find("mesh as read"), std::string::npos) << message;
    }
  }
  remove_case(comm, folder);
}

} // namespace
} // namespace seam::problem
