// The energy an energy-momentum step gains through contact (ContactConstraint::impact_gain,
// contact_impact.cpp) against a rigid plane: a node held active with a tensile multiplier
// (lambda_j < 0, as the cycling guard's union of a chattering active set can keep one) that
// starts the step at a positive gap pulls the body onto the plane, and its work
// -lambda_j g~_j(x_n) is counted, in the obstacle's rows; a compressive one is the obstacle's
// work, not counted. The block's bottom (length 1) starts the step 0.01 above the plane, so
// with lambda_j = -1 at every node the gain is 0.01 sum_j D_jj = 0.01. On 1 and 3 ranks.
#include "contact_run.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace seam::problem {
namespace {

/// The body's nodes moved by (0, dy) in u.
void lift(const ContactRun& run, double dy, la::Vector& u) {
  u.zero();
  std::vector<PetscInt> rows;
  std::vector<double> values;
  for (const auto node : run.mesh.region("body", 2).nodes) {
    if (!run.disc.owns_node(node)) continue;
    rows.push_back(run.disc.global_dof(node, 1));
    values.push_back(dy);
  }
  u.add_values(rows, values);
  u.assemble();
  u.update_ghosts();
}

TEST(ImpactGain, TensileNodesOnARigidPlaneCount) {
  Comm comm;
  const auto folder =
      std::filesystem::temp_directory_path() / ("seam_tensile_np" + std::to_string(comm.size()));
  if (comm.is_root()) {
    std::filesystem::remove_all(folder);
    std::filesystem::create_directories(folder);
    std::ofstream(folder / "case.geo") << kBlock;
    std::ofstream(folder / "case.yaml")
        << "dimension: 2\nmesh: {geo: case.geo}\n"
           "materials:\n  m: {model: neo_hooke, young: 100.0, poisson: 0.3, density: 1.0}\n"
           "bodies:\n  - {region: body, material: m}\n"
           "interfaces:\n  - {name: floor, type: contact, slave: bottom,\n"
           "     rigid_plane: {point: [0, 0], normal: [0, 1]}}\n"
           "time: {integrator: energy_momentum, end: 1.0, steps: 1}\n";
  }
  comm.barrier();
  {
    ContactRun run(comm, folder, false);
    ContactConstraint& contact = run.contact;
    la::Vector u_n = run.disc.make_vector(), u = run.disc.make_vector();
    lift(run, 0.01, u_n);
    contact.start_step(u_n);
    // Pressed 1e-3 into the plane: every bottom node active.
    lift(run, -1e-3, u);
    contact.evaluate(u, 1.0, true, run.timers);
    EXPECT_EQ(contact.n_active(), 17);
    contact.hold_sets(true);
    const auto gain_with = [&](double lambda) {
      contact.set_multipliers(std::vector<double>(contact.multipliers().size(), lambda));
      contact.evaluate(u, 1.0, false, run.timers);
      la::Vector d = run.disc.make_vector(), obstacle = run.disc.make_vector();
      const auto gain = contact.impact_gain(d, obstacle);
      const double d_norm = d.norm(), obstacle_norm = obstacle.norm(); // collective
      if (comm.is_root())
        std::printf("  lambda %+g: gain %.15g at %d nodes, |d| %g, |obstacle rows| %g\n", lambda,
                    gain.gain, gain.nodes, d_norm, obstacle_norm);
      EXPECT_EQ(d_norm, 0.0); // no rows between bodies here
      return std::make_pair(gain, obstacle_norm);
    };
    const auto [tensile, rows] = gain_with(-1.0);
    EXPECT_NEAR(tensile.gain, 0.01, 1e-12);
    EXPECT_EQ(tensile.nodes, 17);
    EXPECT_GT(rows, 0.0);
    const auto [compressive, none] = gain_with(1.0);
    EXPECT_EQ(compressive.gain, 0.0);
    EXPECT_EQ(none, 0.0);
    contact.hold_sets(false);
  }
  comm.barrier();
  if (comm.is_root()) std::filesystem::remove_all(folder);
}

} // namespace
} // namespace seam::problem
