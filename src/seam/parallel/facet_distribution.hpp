#pragma once
// The slave facets of one interface spread over the ranks on their own (seed paper Sect. 3.1,
// steps one and two): each rank hands in the facets it holds, with their centroids and work
// (candidate pairs), the proximity split partitions the facets with work and the others
// separately by weighted RCB, and every facet is sent to its new rank. repartition() keeps
// the cut axes and only moves the planes (Zoltan's RCB_REUSE), so a rebalance after a sliding
// step moves the facets near the planes only.
//
// Facets cross the ranks by their global ids; a rank passes and receives the facets it holds
// only.
#include "seam/common/types.hpp"
#include "seam/parallel/load_balance.hpp"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace seam::parallel {

class FacetDistribution {
public:
  FacetDistribution(MPI_Comm comm, int dim);

  /// Collective. `ids`: the global ids of the facets this rank holds now (each facet on exactly
  /// one rank); `centroids`: dim values and `work`: one value per facet of `ids` (0 = no
  /// candidate pairs). Returns the ids of the facets this rank holds afterwards (sorted). The
  /// first call partitions from scratch, later ones keep the cut axes.
  std::vector<global_index> distribute(std::span<const global_index> ids,
                                       std::span<const double> centroids,
                                       std::span<const double> work);

  /// Facets that changed rank in the last distribute(), summed over the ranks.
  std::int64_t moved() const { return moved_; }
  /// Partitions made so far (the first one included).
  int n_partitions() const { return n_partitions_; }

  /// What the next distribute() continues from besides its arguments (the same on every
  /// rank): the partitions made so far and the cuts of the proximity split's two trees, whose
  /// axes a repartition keeps. Empty cuts before the first partition.
  struct State {
    int n_parts = 0;
    int n_partitions = 0;
    std::vector<RcbCut> close, far;
  };
  State state() const;
  /// Local. Continues from the state() of a distribution on as many ranks (a restart that
  /// keeps the facets where the checkpointed run had them). InputError for a state of
  /// another number of ranks or of malformed trees.
  void restore(const State& state);

private:
  MPI_Comm comm_;
  int dim_;
  ProximityPartition partition_;
  std::int64_t moved_ = 0;
  int n_partitions_ = 0;
};

} // namespace seam::parallel
