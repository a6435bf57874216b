// The cycling guard of the active set (contact/active_set_cycles.hpp): sequences of node
// statuses that cycle with periods 2 to 8 are caught (period 2 at its first return, longer ones
// when the cycle repeats for two iterations), with the per-node maximum over the cycle; a
// single return, a set kept, and a period of 9 are not; a retracted trial (line search) leaves
// the sequence of iterates as it was.
#include "seam/contact/active_set_cycles.hpp"

#include <gtest/gtest.h>

#include <vector>

namespace seam::contact {
namespace {

using Set = std::vector<char>;

/// Set number i of a cycle of `period` sets over 10 nodes: node j is active (1) in set i when
/// (j + i) % period == 0, so that every set differs from the others; node 9 is in slip (2) in
/// set 0 only.
Set cycle_set(std::size_t i, std::size_t period) {
  Set s(10, 0);
  for (std::size_t j = 0; j < 9; ++j) s[j] = (j + i) % period == 0 ? 1 : 0;
  if (i % period == 0) s[9] = 2;
  return s;
}

TEST(ActiveSetCycles, EveryPeriodUpToEightIsCaught) {
  // Period 2 at its first return; periods 3 .. 8 one iteration later, when the set after the
  // return repeats as well.
  for (std::size_t period = 2; period <= ActiveSetCycles::max_period; ++period) {
    ActiveSetCycles guard;
    guard.start(cycle_set(0, period));
    Set alternating;
    const std::size_t caught = period == 2 ? 2 : period + 1;
    for (std::size_t i = 1; i < caught; ++i) {
      Set next = cycle_set(i, period);
      ASSERT_EQ(guard.guard(next, alternating), 0u) << "period " << period << " iterate " << i;
      EXPECT_EQ(next, cycle_set(i, period));
    }
    Set next = cycle_set(caught, period);
    ASSERT_EQ(guard.guard(next, alternating), period);
    // The maximum over the cycle: each of the first nine nodes is active in one of its sets,
    // node 9 keeps its slip status.
    for (std::size_t j = 0; j < 9; ++j) {
      EXPECT_EQ(next[j], 1) << "period " << period << " node " << j;
      EXPECT_EQ(alternating[j], 1);
    }
    EXPECT_EQ(next[9], 2);
    EXPECT_EQ(alternating[9], 1);
  }
}

TEST(ActiveSetCycles, PeriodFourAfterAConvergingStart) {
  // A search that first changes monotonically, then cycles through four sets (the corner-first
  // block impact): caught when the set after the return to the cycle's first set repeats too.
  ActiveSetCycles guard;
  guard.start({0, 0, 0, 0});
  Set alternating;
  const std::vector<Set> sequence = {{1, 0, 0, 0}, {1, 1, 0, 0}, {1, 1, 1, 0}, {1, 0, 1, 0},
                                     {0, 1, 1, 1}, {1, 1, 0, 1}, {1, 1, 1, 0}, {1, 0, 1, 0}};
  for (std::size_t i = 0; i + 1 < sequence.size(); ++i) {
    Set next = sequence[i];
    ASSERT_EQ(guard.guard(next, alternating), 0u) << "iterate " << i;
  }
  Set next = sequence.back();
  ASSERT_EQ(guard.guard(next, alternating), 4u);
  EXPECT_EQ(next, (Set{1, 1, 1, 1}));
  EXPECT_EQ(alternating, (Set{1, 1, 1, 1}));
}

TEST(ActiveSetCycles, ASingleReturnIsNotACycleOfPeriodThreeOrMore) {
  // A converging search may meet an earlier set once (A B C A D ...): nothing is frozen.
  ActiveSetCycles guard;
  guard.start({1, 0, 0});
  Set alternating;
  for (const Set& s : {Set{0, 1, 0}, Set{0, 0, 1}, Set{1, 0, 0}, Set{1, 1, 1}, Set{1, 1, 1}}) {
    Set next = s;
    EXPECT_EQ(guard.guard(next, alternating), 0u);
    EXPECT_EQ(next, s);
  }
}

TEST(ActiveSetCycles, NoCycleIsReportedWithoutAReturn) {
  // A kept set is convergence, not a cycle; a period of 9 exceeds the guard.
  ActiveSetCycles guard;
  guard.start({1, 0});
  Set alternating;
  Set next = {1, 0};
  EXPECT_EQ(guard.guard(next, alternating), 0u);
  EXPECT_EQ(guard.guard(next, alternating), 0u);
  const std::size_t period = ActiveSetCycles::max_period + 1;
  ActiveSetCycles long_cycle;
  long_cycle.start(cycle_set(0, period));
  for (std::size_t i = 1; i <= period + 1; ++i) {
    Set s = cycle_set(i, period);
    EXPECT_EQ(long_cycle.guard(s, alternating), 0u) << "iterate " << i;
    EXPECT_EQ(s, cycle_set(i, period));
  }
}

TEST(ActiveSetCycles, PeriodTwoKeepsTheFormerUnionOfTheLastTwoSets) {
  ActiveSetCycles guard;
  guard.start({0, 1, 0});
  Set alternating;
  Set a = {1, 0, 0};
  EXPECT_EQ(guard.guard(a, alternating), 0u);
  Set b = {0, 1, 0}; // back to the start
  EXPECT_EQ(guard.guard(b, alternating), 2u);
  EXPECT_EQ(b, (Set{1, 1, 0}));
  EXPECT_EQ(alternating, (Set{1, 1, 0}));
}

TEST(ActiveSetCycles, ARetractedTrialLeavesTheSequenceOfIterates) {
  // A B C C A B: the statuses of six Newton iterates (the fourth kept C), a cycle seen with
  // period 4 at the last one. With a line search the fourth iterate's correction is shortened
  // and C decided again there: retracted first, the guard sees the same sequence and period;
  // recorded twice, C stretches the cycle to period 5.
  const Set A{1, 0, 0}, B{0, 1, 0}, C{0, 0, 1};
  const auto last_period = [&](bool retrial, bool retract) {
    ActiveSetCycles guard;
    guard.start(A);
    Set alternating;
    std::vector<Set> sets{B, C, C};
    if (retrial) sets.push_back(C);
    sets.push_back(A);
    std::size_t period = 0;
    for (std::size_t i = 0; i < sets.size(); ++i) {
      if (retrial && retract && i == 3) guard.retract();
      Set next = sets[i];
      period = guard.guard(next, alternating);
      EXPECT_EQ(period, 0u) << "iterate " << i;
    }
    Set next = B;
    return guard.guard(next, alternating);
  };
  EXPECT_EQ(last_period(false, false), 4u);
  EXPECT_EQ(last_period(true, true), 4u);
  EXPECT_EQ(last_period(true, false), 5u);
}

TEST(ActiveSetCycles, PartsAgreeOnTheWholeSetsCycle) {
  // Nodes 0, 1 on one part, 2, 3 on another (a slave side held in part): the whole set
  // alternates at node 0 only. Each part compares its own nodes and the parts agree (equal
  // where equal on both: here the whole's comparisons, in the same order); the part whose
  // nodes never change then takes the cycle too, as the whole does, and freezes nothing.
  const std::vector<Set> whole{{0, 0, 0, 0}, {1, 0, 0, 0}, {0, 0, 0, 0}};
  std::vector<bool> results;
  ActiveSetCycles all;
  all.start(whole[0]);
  Set alternating, next;
  std::size_t period = 0;
  for (std::size_t i = 1; i < whole.size(); ++i) {
    next = whole[i];
    period = all.guard(next, alternating, [&](bool equal) {
      results.push_back(equal);
      return equal;
    });
  }
  ASSERT_EQ(period, 2u);
  EXPECT_EQ(next, (Set{1, 0, 0, 0}));
  for (const std::size_t first : {std::size_t{0}, std::size_t{2}}) {
    const auto part = [&](const Set& set) { return Set{set[first], set[first + 1]}; };
    ActiveSetCycles guard, alone;
    guard.start(part(whole[0]));
    alone.start(part(whole[0]));
    std::size_t k = 0, mine = 0, without = 0;
    Set p, q;
    for (std::size_t i = 1; i < whole.size(); ++i) {
      p = part(whole[i]);
      q = p;
      mine = guard.guard(p, alternating, [&](bool equal) {
        const bool others = results[k++];
        return equal && others;
      });
      without = alone.guard(q, alternating);
    }
    EXPECT_EQ(k, results.size()) << "part " << first;
    EXPECT_EQ(mine, 2u) << "part " << first;
    EXPECT_EQ(p, part(next)) << "part " << first;
    // Alone, the part whose nodes keep their status sees no cycle.
    EXPECT_EQ(without, first == 0 ? 2u : 0u) << "part " << first;
  }
}

} // namespace
} // namespace seam::contact
