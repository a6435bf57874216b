#pragma once
// Dynamic load balancing of an interface (seed paper Sect. 3.1, steps two and three):
// the monitor of eq. (21), IF T_max / T_min > eps -> redistribute, over each rank's measured
// interface evaluation time, with the work counts (pairs, integration cells) reported beside;
// and the proximity split, which balances the facets with candidate pairs (the contact zone,
// where all the integration work is) separately from the rest.
#include "seam/common/types.hpp"
#include "seam/parallel/rcb.hpp"
#include "seam/search/traversal.hpp"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace seam::parallel {

/// min / mean / max of one quantity over the ranks.
struct WorkStats {
  double min = 0.0;
  double mean = 0.0;
  double max = 0.0;
  /// max / min, eq. (21)'s ratio: 1 when all are zero, +inf when only the minimum is.
  double imbalance() const;
  /// max / mean (1 when all are zero): the usual measure of a partition.
  double max_over_mean() const;
};

/// Statistics of per-rank values (local; e.g. gathered from parallel.csv).
WorkStats work_stats(std::span<const double> per_rank);
/// Collective: statistics of `local` over the ranks of comm.
WorkStats work_stats(MPI_Comm comm, double local);

/// One rank's interface work in the last step.
struct RankWork {
  double seconds = 0.0;   ///< measured interface evaluation time
  std::int64_t pairs = 0; ///< candidate pairs evaluated
  std::int64_t integration_cells = 0;
};

struct BalanceDecision {
  WorkStats time;
  WorkStats pairs;
  WorkStats integration_cells;
  bool rebalance = false;
};

/// Eq. (21): rebalance when T_max > tolerance * T_min (CONTRACT.md parallel.rebalance_tolerance,
/// default 1.2). Counts are reported but do not decide: time is what the paper balances.
class LoadMonitor {
public:
  explicit LoadMonitor(double tolerance = 1.2);
  double tolerance() const { return tolerance_; }

  /// Local decision from already gathered statistics.
  bool needs_rebalance(const WorkStats& time) const;
  /// Collective: gathers every rank's work of the last step and decides (the same on all ranks).
  BalanceDecision evaluate(MPI_Comm comm, const RankWork& mine) const;

private:
  double tolerance_;
};

/// Candidate pairs of each slave facet (index < n_slave): the weights of the contact zone.
std::vector<double> pairs_per_facet(std::span<const search::CandidatePair> pairs,
                                    local_index n_slave);

/// The paper's second step: facets with work > 0 (those with candidate pairs, weighted by
/// their work) and the other facets (unit weights) are each partitioned by RCB over all ranks,
/// and each facet takes its rank from the partition it belongs to. Both cut trees are kept for
/// repartition().
class ProximityPartition {
public:
  explicit ProximityPartition(int dim, const RcbOptions& options = {});

  /// Collective. points: dim values per local facet; work: e.g. pairs_per_facet.
  void partition(MPI_Comm comm, std::span<const double> points, std::span<const double> work,
                 std::span<const global_index> ids, std::span<int> parts);
  /// Collective. Keeps the axes of both trees, shifting their planes.
  void repartition(MPI_Comm comm, std::span<const double> points, std::span<const double> work,
                   std::span<const global_index> ids, std::span<int> parts);

  const Rcb& close() const { return close_; }
  const Rcb& far() const { return far_; }
  /// Local. Both trees as a partition into `n_parts` parts left them (Rcb::restore).
  void restore(int n_parts, std::span<const RcbCut> close, std::span<const RcbCut> far);

private:
  void run(MPI_Comm comm, std::span<const double> points, std::span<const double> work,
           std::span<const global_index> ids, std::span<int> parts, bool keep);
  Rcb close_;
  Rcb far_;
};

} // namespace seam::parallel
