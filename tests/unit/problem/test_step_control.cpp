// `max_step_cuts` bounds the halvings of the step in effect (docs/input.md §6.3): after a step
// cut down to dt / 2^k, each converged step doubles dt and takes one halving back, so a later
// failure at dt / 2 may halve again down to the same smallest step dt / 2^max_step_cuts. The
// 200 rings of examples/rings stopped at t = 1.0286 because the count of halvings stayed at 5
// while dt grew back from dt / 32 to dt / 2: the first failure at dt / 2 ended the run.
#include "seam/problem/step_control.hpp"

#include <gtest/gtest.h>

namespace seam::problem {
namespace {

io::TimeConfig five_cuts() {
  io::TimeConfig tc;
  tc.integrator = io::Integrator::energy_momentum;
  tc.end = 1.0;
  tc.dt = 0.01;
  tc.n_steps = 100;
  tc.max_step_cuts = 5;
  return tc;
}

TEST(StepControl, HalvingsTakenBackAsTheStepGrows) {
  Comm comm;
  const auto tc = five_cuts();
  StepControl sc(tc);
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(sc.cut("failed", sc.next(), comm));
  EXPECT_FALSE(sc.cut("failed", sc.next(), comm)); // dt / 32 is the smallest step
  EXPECT_NEAR(sc.next(), tc.dt / 32, 1e-15);
  // Four converged steps grow the step back to dt / 2: one halving is left in effect.
  for (int i = 0; i < 4; ++i) sc.accept(sc.next());
  EXPECT_EQ(sc.cuts(), 1);
  const double t = sc.time();
  EXPECT_NEAR(sc.next() - t, tc.dt / 2, 1e-15);
  // A failure there halves again, down to dt / 32 and not below.
  for (int i = 0; i < 4; ++i) ASSERT_TRUE(sc.cut("failed", sc.next(), comm)) << i;
  EXPECT_NEAR(sc.next() - t, tc.dt / 32, 1e-15);
  EXPECT_FALSE(sc.cut("failed", sc.next(), comm));
}

TEST(StepControl, BackAtTheNominalStep) {
  Comm comm;
  const auto tc = five_cuts();
  StepControl sc(tc);
  ASSERT_TRUE(sc.cut("failed", sc.next(), comm));
  ASSERT_TRUE(sc.cut("failed", sc.next(), comm));
  sc.accept(sc.next());
  sc.accept(sc.next());
  EXPECT_EQ(sc.cuts(), 0);
  EXPECT_NEAR(sc.next() - sc.time(), tc.dt, 1e-15);
  sc.accept(sc.next());
  EXPECT_EQ(sc.cuts(), 0);
}

} // namespace
} // namespace seam::problem
