// Weighted RCB: balance, independence of the input distribution, ties, and reuse of the cuts.
#include "parallel_test_support.hpp"
#include "seam/common/error.hpp"
#include "seam/parallel/rcb.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

namespace seam::parallel::test {
namespace {

/// n points of this rank: random in [0, 1]^dim, with ids rank + k * size (global n * size).
struct RandomPoints {
  std::vector<double> x, w;
  std::vector<global_index> id;
  std::vector<int> parts;
  RandomPoints(int dim, int n, unsigned seed, bool clustered_weights) {
    std::mt19937 gen(seed + 977u * static_cast<unsigned>(rank()));
    std::uniform_real_distribution<double> u(0.0, 1.0);
    for (int k = 0; k < n; ++k) {
      double r2 = 0.0;
      for (int d = 0; d < dim; ++d) {
        x.push_back(u(gen));
        r2 += (x.back() - 0.3) * (x.back() - 0.3);
      }
      // Clustered: heavy points near (0.3, ...), light elsewhere, as pairs in a contact zone.
      w.push_back(clustered_weights ? 1.0 + 50.0 * std::exp(-r2 / 0.01) : 1.0);
      id.push_back(rank() + static_cast<global_index>(k) * size());
    }
    parts.resize(n);
  }
};

TEST(Rcb, WeightedRandomPointsAreBalanced) {
  for (int dim : {2, 3})
    for (bool clustered : {false, true}) {
      RandomPoints p(dim, 3000, 11u + dim, clustered);
      Rcb rcb(dim);
      rcb.partition(world(), p.x, p.w, p.id, p.parts);
      EXPECT_LE(part_imbalance(world(), p.w, p.parts, size()), 1.05)
          << dim << "D, clustered " << clustered;
      // Every point's part is that of the kept cut tree.
      for (std::size_t i = 0; i < p.id.size(); ++i)
        EXPECT_EQ(p.parts[i], rcb.part_of(&p.x[i * dim], p.id[i]));
      EXPECT_EQ(static_cast<int>(rcb.cuts().size()), size() - 1);
    }
}

TEST(Rcb, TiesOfAStructuredGridAreSplitById) {
  // A 40 x 40 grid of centroids: whole rows share a coordinate; unit weights (empty span).
  const int n = 40;
  std::vector<double> x;
  std::vector<global_index> id;
  for (int k = rank(); k < n * n; k += size()) {
    x.insert(x.end(), {double(k % n), double(k / n)});
    id.push_back(k);
  }
  std::vector<int> parts(id.size());
  Rcb rcb(2);
  rcb.partition(world(), x, {}, id, parts);
  std::vector<double> count;
  part_imbalance(world(), {}, parts, size(), &count);
  // 1600 points over size parts: each gets the floor or the ceiling of the exact share.
  for (int r = 0; r < size(); ++r)
    EXPECT_LE(std::abs(count[r] - 1600.0 / size()), 1.0) << "part " << r;
}

TEST(Rcb, PartitionDoesNotDependOnTheInputDistribution) {
  const Mesh mesh = search::test::wavy_surface(20, 16, 0.0, 0.1, 0.0);
  std::map<global_index, int> by_id[2];
  for (int variant = 0; variant < 2; ++variant) {
    const SurfacePart part = variant == 0 ? round_robin_part(mesh) : block_part(mesh);
    Points pts(part);
    Rcb rcb(3);
    rcb.partition(world(), pts.x, {}, part.facet_ids, pts.parts);
    std::vector<GlobalPair> mine; // (id, part) pairs, reusing the record type
    for (local_index f = 0; f < part.n_facets(); ++f)
      mine.push_back({part.facet_ids[f], pts.parts[f]});
    for (const auto& [id, p] : gather_pairs(world(), mine))
      by_id[variant][id] = static_cast<int>(p);
  }
  EXPECT_EQ(by_id[0].size(), mesh.offsets.size() - 1);
  EXPECT_EQ(by_id[0], by_id[1]);
}

TEST(Rcb, RepartitionKeepsAxesAndMovesFewPoints) {
  const int dim = 3;
  RandomPoints p(dim, 2000, 5u, false);
  Rcb rcb(dim);
  rcb.partition(world(), p.x, p.w, p.id, p.parts);
  const std::vector<RcbCut> before = rcb.cuts();

  // Same input: the same cuts, no point changes part.
  std::vector<int> again(p.parts.size());
  rcb.repartition(world(), p.x, p.w, p.id, again);
  EXPECT_EQ(again, p.parts);

  // A weight change in a small region: the planes shift a little, few points change part.
  std::vector<double> w = p.w;
  for (std::size_t i = 0; i < p.id.size(); ++i)
    if (p.x[i * dim] < 0.1) w[i] = 3.0;
  std::vector<int> shifted(p.parts.size());
  rcb.repartition(world(), p.x, w, p.id, shifted);
  EXPECT_LE(part_imbalance(world(), w, shifted, size()), 1.05);
  const std::vector<RcbCut> after = rcb.cuts();
  ASSERT_EQ(after.size(), before.size());
  for (std::size_t k = 0; k < after.size(); ++k) EXPECT_EQ(after[k].axis, before[k].axis);

  std::int64_t changed = 0, total = static_cast<std::int64_t>(p.id.size());
  for (std::size_t i = 0; i < p.id.size(); ++i) changed += shifted[i] != p.parts[i];
  MPI_Allreduce(MPI_IN_PLACE, &changed, 1, MPI_INT64_T, MPI_SUM, world());
  MPI_Allreduce(MPI_IN_PLACE, &total, 1, MPI_INT64_T, MPI_SUM, world());
  // About a fifth of the weight moved into 10 % of the box; a fresh cut along other axes
  // would reshuffle most points, the shifted planes move well under a third of them.
  if (size() > 1) {
    EXPECT_LT(changed, total / 3);
  }
  if (size() == 1) {
    EXPECT_EQ(changed, 0);
  }
  // count_moving counts the points that do not stay on the rank holding them.
  std::int64_t expected = 0;
  for (const int part : shifted) expected += part != rank();
  MPI_Allreduce(MPI_IN_PLACE, &expected, 1, MPI_INT64_T, MPI_SUM, world());
  EXPECT_EQ(count_moving(world(), shifted), expected);
}

TEST(Rcb, BadInputOnOneRankThrowsOnEveryRank) {
  std::vector<double> x{0.5, 0.5};
  std::vector<double> w{rank() == size() - 1 ? -1.0 : 1.0};
  std::vector<global_index> id{rank()};
  std::vector<int> parts(1);
  Rcb rcb(2);
  EXPECT_THROW(rcb.partition(world(), x, w, id, parts), InputError);
  // The communicator is still usable: a valid call afterwards succeeds everywhere.
  w[0] = 1.0;
  rcb.partition(world(), x, w, id, parts);
  EXPECT_GE(parts[0], 0);
  EXPECT_LT(parts[0], size());
}

} // namespace
} // namespace seam::parallel::test
