// Eq. (21)'s monitor and the proximity split of the contact zone.
#include "parallel_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/parallel/facet_distribution.hpp"
#include "seam/parallel/load_balance.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>

namespace seam::parallel::test {
namespace {

TEST(LoadMonitor, StatisticsAndTheDecisionOfEquation21) {
  const std::vector<double> t{2.0, 1.0, 3.0, 2.0};
  const WorkStats s = work_stats(t);
  EXPECT_EQ(s.min, 1.0);
  EXPECT_EQ(s.max, 3.0);
  EXPECT_EQ(s.mean, 2.0);
  EXPECT_EQ(s.imbalance(), 3.0);
  EXPECT_EQ(s.max_over_mean(), 1.5);

  const LoadMonitor monitor; // eps = 1.2
  EXPECT_EQ(monitor.tolerance(), 1.2);
  EXPECT_TRUE(monitor.needs_rebalance(s));
  EXPECT_FALSE(monitor.needs_rebalance(work_stats(std::vector<double>{1.0, 1.19, 1.1})));
  EXPECT_TRUE(monitor.needs_rebalance(work_stats(std::vector<double>{1.0, 1.21})));
  // An idle rank forces a rebalance; an idle interface does not.
  EXPECT_TRUE(monitor.needs_rebalance(work_stats(std::vector<double>{0.0, 1.0})));
  EXPECT_EQ(work_stats(std::vector<double>{0.0, 1.0}).imbalance(),
            std::numeric_limits<double>::infinity());
  EXPECT_FALSE(monitor.needs_rebalance(work_stats(std::vector<double>{0.0, 0.0})));
  EXPECT_EQ(work_stats(std::vector<double>{0.0, 0.0}).imbalance(), 1.0);
  EXPECT_FALSE(LoadMonitor(2.0).needs_rebalance(work_stats(std::vector<double>{1.0, 2.0})));
  EXPECT_THROW(LoadMonitor(0.9), InputError);
}

TEST(LoadMonitor, EvaluateGathersTheSameDecisionOnEveryRank) {
  RankWork mine;
  mine.seconds = 1.0 + 0.1 * rank(); // T_max / T_min = 1 + 0.1 (size - 1)
  mine.pairs = 10 * (rank() + 1);
  mine.integration_cells = 100;
  const BalanceDecision d = LoadMonitor(1.2).evaluate(world(), mine);
  EXPECT_DOUBLE_EQ(d.time.min, 1.0);
  EXPECT_DOUBLE_EQ(d.time.max, 1.0 + 0.1 * (size() - 1));
  EXPECT_DOUBLE_EQ(d.pairs.mean, 5.0 * (size() + 1));
  EXPECT_DOUBLE_EQ(d.integration_cells.imbalance(), 1.0);
  EXPECT_EQ(d.rebalance, size() >= 4); // 1.3 > 1.2 at np = 4; 1.2 is not > 1.2 at np = 3
  int decided = d.rebalance ? 1 : 0, all = 0;
  MPI_Allreduce(&decided, &all, 1, MPI_INT, MPI_SUM, world());
  EXPECT_TRUE(all == 0 || all == size());
}

TEST(LoadMonitor, PairsPerFacet) {
  const std::vector<search::CandidatePair> p{{0, 3}, {2, 1}, {0, 4}};
  EXPECT_EQ(pairs_per_facet(p, 3), (std::vector<double>{2.0, 0.0, 1.0}));
}

TEST(ProximityPartition, ContactZoneAndRestAreBalancedSeparately) {
  // 3000 points per rank on the unit square; those within 0.15 of (0.2, 0.7) have work (pairs).
  std::mt19937 gen(31u + rank());
  std::uniform_real_distribution<double> u(0.0, 1.0);
  std::vector<double> x, work;
  std::vector<global_index> id;
  for (int k = 0; k < 3000; ++k) {
    const double a = u(gen), b = u(gen);
    x.insert(x.end(), {a, b});
    const double r = std::hypot(a - 0.2, b - 0.7);
    work.push_back(r < 0.15 ? std::floor(1.0 + 8.0 * (0.15 - r) / 0.15) : 0.0);
    id.push_back(rank() + static_cast<global_index>(k) * size());
  }
  std::vector<int> parts(id.size());
  ProximityPartition split(2);
  split.partition(world(), x, work, id, parts);

  std::vector<double> close_w, far_w;
  std::vector<int> close_p, far_p;
  for (std::size_t i = 0; i < id.size(); ++i) {
    (work[i] > 0 ? close_w : far_w).push_back(work[i] > 0 ? work[i] : 1.0);
    (work[i] > 0 ? close_p : far_p).push_back(parts[i]);
  }
  // Pair work and facets without pairs are each balanced to 5 %.
  EXPECT_LE(part_imbalance(world(), close_w, close_p, size()), 1.05);
  EXPECT_LE(part_imbalance(world(), far_w, far_p, size()), 1.05);
  // A single RCB of unit weights leaves the contact work concentrated at np >= 4.
  Rcb plain(2);
  std::vector<int> plain_parts(id.size());
  plain.partition(world(), x, {}, id, plain_parts);
  std::vector<int> plain_close;
  for (std::size_t i = 0; i < id.size(); ++i)
    if (work[i] > 0) plain_close.push_back(plain_parts[i]);
  if (size() >= 4) {
    EXPECT_GT(part_imbalance(world(), close_w, plain_close, size()), 1.5);
  }

  // Repartition with the same input keeps every facet where it is.
  std::vector<int> again(id.size());
  split.repartition(world(), x, work, id, again);
  EXPECT_EQ(again, parts);
}

// The facets of an interface cross the ranks by their global ids (cell id of the mesh as read
// * 8 + local facet, beyond 32 bits on large meshes): each id ends on exactly one rank, the
// facets with work are balanced, and a repartition with the same input moves none.
TEST(FacetDistribution, MovesFacetsByTheirGlobalIds) {
  constexpr std::int64_t n = 600;
  const auto gid = [](std::int64_t f) { return (std::int64_t{3'000'000'000} + 7 * f) * 8 + f % 6; };
  std::vector<global_index> ids;
  std::vector<double> centroids, work;
  for (std::int64_t f = rank(); f < n; f += size()) { // held round robin, unrelated to geometry
    ids.push_back(gid(f));
    const double x = static_cast<double>(f % 30) / 30.0, y = static_cast<double>(f / 30) / 20.0;
    centroids.push_back(x);
    centroids.push_back(y);
    work.push_back(x < 0.3 ? 5.0 : 0.0); // a contact zone on one side
  }
  FacetDistribution distribution(world(), 2);
  const auto mine = distribution.distribute(ids, centroids, work);
  EXPECT_TRUE(std::is_sorted(mine.begin(), mine.end()));
  std::vector<std::int64_t> offsets;
  auto all = allgatherv<global_index>(world(), mine, offsets);
  std::sort(all.begin(), all.end());
  std::vector<global_index> expected;
  for (std::int64_t f = 0; f < n; ++f) expected.push_back(gid(f));
  std::sort(expected.begin(), expected.end());
  EXPECT_EQ(all, expected);
  // The work per rank: the contact zone spread over every rank.
  double my_work = 0.0;
  for (const auto id : mine) {
    const auto f = (id / 8 - std::int64_t{3'000'000'000}) / 7;
    my_work += f % 30 < 9 ? 5.0 : 0.0;
  }
  double least = 0.0, most = 0.0;
  MPI_Allreduce(&my_work, &least, 1, MPI_DOUBLE, MPI_MIN, world());
  MPI_Allreduce(&my_work, &most, 1, MPI_DOUBLE, MPI_MAX, world());
  EXPECT_GT(least, 0.0);
  EXPECT_LE(most, 1.1 * least + 10.0);
  // Handed back as they are now: the same cut, nothing moves.
  std::vector<double> c2, w2;
  for (const auto id : mine) {
    const auto f = (id / 8 - std::int64_t{3'000'000'000}) / 7;
    c2.push_back(static_cast<double>(f % 30) / 30.0);
    c2.push_back(static_cast<double>(f / 30) / 20.0);
    w2.push_back(f % 30 < 9 ? 5.0 : 0.0);
  }
  EXPECT_EQ(distribution.distribute(mine, c2, w2), mine);
  EXPECT_EQ(distribution.moved(), 0);
}

// A restart continues the repartitions from a checkpoint: a distribution restored from
// another's state() hands out the same facets as the original at its next call, where a new
// one partitions anew (the contact zone has turned, so new cuts take other axes).
TEST(FacetDistribution, RestoredStateContinuesTheRepartitions) {
  const auto facets = [](auto&& zone, std::span<const global_index> ids, std::vector<double>& c,
                         std::vector<double>& w) {
    c.clear();
    w.clear();
    for (const auto f : ids) {
      const double x = static_cast<double>(f % 30) / 30.0, y = static_cast<double>(f / 30) / 20.0;
      c.push_back(x);
      c.push_back(y);
      w.push_back(zone(x, y) ? 5.0 : 0.0);
    }
  };
  std::vector<global_index> ids;
  for (global_index f = rank(); f < 600; f += size()) ids.push_back(f);
  std::vector<double> c, w;
  facets([](double x, double) { return x < 0.3; }, ids, c, w); // along y
  FacetDistribution original(world(), 2);
  EXPECT_EQ(original.state().n_partitions, 0);
  const auto mine = original.distribute(ids, c, w);
  const auto state = original.state();
  EXPECT_EQ(state.n_parts, size());
  EXPECT_EQ(state.n_partitions, 1);
  EXPECT_EQ(state.close.size(), static_cast<std::size_t>(size() - 1));
  FacetDistribution restored(world(), 2), fresh(world(), 2);
  restored.restore(state);
  EXPECT_EQ(restored.n_partitions(), 1);
  facets([](double, double y) { return y < 0.3; }, mine, c, w); // along x
  const auto next = original.distribute(mine, c, w);
  EXPECT_EQ(restored.distribute(mine, c, w), next);
  EXPECT_EQ(restored.n_partitions(), 2);
  const auto anew = fresh.distribute(mine, c, w);
  int differs = anew != next;
  MPI_Allreduce(MPI_IN_PLACE, &differs, 1, MPI_INT, MPI_MAX, world());
  if (size() > 1) {
    EXPECT_EQ(differs, 1);
  }
  // A state of another number of ranks, or trees of another size, is refused.
  auto other = state;
  other.n_parts = size() + 1;
  EXPECT_THROW(restored.restore(other), InputError);
  other = state;
  other.close.emplace_back();
  EXPECT_THROW(restored.restore(other), InputError);
}

} // namespace
} // namespace seam::parallel::test
