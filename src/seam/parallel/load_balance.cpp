#include "seam/parallel/load_balance.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace seam::parallel {

double WorkStats::imbalance() const {
  if (max <= 0.0) return 1.0;
  return min > 0.0 ? max / min : std::numeric_limits<double>::infinity();
}

double WorkStats::max_over_mean() const {
  return mean > 0.0 ? max / mean : 1.0;
}

WorkStats work_stats(std::span<const double> per_rank) {
  WorkStats s;
  if (per_rank.empty()) return s;
  s.min = *std::min_element(per_rank.begin(), per_rank.end());
  s.max = *std::max_element(per_rank.begin(), per_rank.end());
  double sum = 0.0;
  for (const double v : per_rank) sum += v;
  s.mean = sum / static_cast<double>(per_rank.size());
  return s;
}

WorkStats work_stats(MPI_Comm comm, double local) {
  int size = 1;
  MPI_Comm_size(comm, &size);
  double v[3] = {local, -local, local}; // min, -max, sum
  MPI_Allreduce(MPI_IN_PLACE, v, 2, MPI_DOUBLE, MPI_MIN, comm);
  MPI_Allreduce(MPI_IN_PLACE, v + 2, 1, MPI_DOUBLE, MPI_SUM, comm);
  return {v[0], v[2] / size, -v[1]};
}

LoadMonitor::LoadMonitor(double tolerance) : tolerance_(tolerance) {
  SEAM_CHECK(tolerance >= 1.0, InputError,
             "parallel.rebalance_tolerance must be >= 1 (eq. 21's eps), got ", tolerance);
}

bool LoadMonitor::needs_rebalance(const WorkStats& time) const {
  // T_max / T_min > eps, written without the division so that an idle rank (T_min = 0) asks
  // for rebalancing and an idle interface (all zero) does not.
  return time.max > tolerance_ * time.min;
}

BalanceDecision LoadMonitor::evaluate(MPI_Comm comm, const RankWork& mine) const {
  check_collectively(comm, !(mine.seconds >= 0.0) || mine.pairs < 0 || mine.integration_cells < 0,
                     "load monitor: work must be non-negative");
  BalanceDecision d;
  d.time = work_stats(comm, mine.seconds);
  d.pairs = work_stats(comm, static_cast<double>(mine.pairs));
  d.integration_cells = work_stats(comm, static_cast<double>(mine.integration_cells));
  d.rebalance = needs_rebalance(d.time);
  return d;
}

std::vector<double> pairs_per_facet(std::span<const search::CandidatePair> pairs,
                                    local_index n_slave) {
  std::vector<double> count(n_slave, 0.0);
  for (const auto& p : pairs) {
    SEAM_ASSERT(p.slave >= 0 && p.slave < n_slave);
    count[p.slave] += 1.0;
  }
  return count;
}

ProximityPartition::ProximityPartition(int dim, const RcbOptions& options)
    : close_(dim, options), far_(dim, options) {}

void ProximityPartition::partition(MPI_Comm comm, std::span<const double> points,
                                   std::span<const double> work, std::span<const global_index> ids,
                                   std::span<int> parts) {
  run(comm, points, work, ids, parts, false);
}

void ProximityPartition::repartition(MPI_Comm comm, std::span<const double> points,
                                     std::span<const double> work,
                                     std::span<const global_index> ids, std::span<int> parts) {
  run(comm, points, work, ids, parts, true);
}

void ProximityPartition::restore(int n_parts, std::span<const RcbCut> close,
                                 std::span<const RcbCut> far) {
  close_.restore(n_parts, close);
  far_.restore(n_parts, far);
}

void ProximityPartition::run(MPI_Comm comm, std::span<const double> points,
                             std::span<const double> work, std::span<const global_index> ids,
                             std::span<int> parts, bool keep) {
  const int dim = close_.dim();
  const std::size_t n = ids.size();
  check_collectively(comm, work.size() != n || points.size() != n * dim || parts.size() != n,
                     "proximity partition: one work value, dim coordinates and one part per facet");
  // Split the facets into the two sets, partition each, scatter the parts back.
  std::vector<double> pts[2], wts[2];
  std::vector<global_index> gid[2];
  std::vector<std::size_t> where[2];
  for (std::size_t i = 0; i < n; ++i) {
    const int set = work[i] > 0.0 ? 0 : 1;
    pts[set].insert(pts[set].end(), points.begin() + i * dim, points.begin() + (i + 1) * dim);
    wts[set].push_back(set == 0 ? work[i] : 1.0);
    gid[set].push_back(ids[i]);
    where[set].push_back(i);
  }
  Rcb* rcb[2] = {&close_, &far_};
  for (int set = 0; set < 2; ++set) {
    std::vector<int> p(gid[set].size());
    if (keep)
      rcb[set]->repartition(comm, pts[set], wts[set], gid[set], p);
    else
      rcb[set]->partition(comm, pts[set], wts[set], gid[set], p);
    for (std::size_t k = 0; k < p.size(); ++k) parts[where[set][k]] = p[k];
  }
}

} // namespace seam::parallel
