#pragma once
// The slave facets of one interface spread over the ranks on their own (seed paper Sect. 3.1,
// steps one and two): each rank hands in the facets it holds, with their centroids and work
// (candidate pairs), the proximity split partitions the facets with work and the others
// separately by weighted RCB, and every facet is sent to its new rank. repartition() keeps
// the cut axes and only moves the planes (Zoltan's RCB_REUSE), so a rebalance after a sliding
// step moves the facets near the planes only.
//
// Facets are numbered 0 .. n_facets - 1 over the whole interface; the per-facet arrays are
// read at the facets a rank holds only.
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

  /// Collective. `held`: the facets this rank holds now (each facet on exactly one rank);
  /// `centroids`: dim values per facet; `work`: per facet (0 = no candidate pairs). Returns
  /// the facets this rank holds afterwards (sorted). The first call partitions from scratch,
  /// later ones keep the cut axes.
  std::vector<local_index> distribute(std::span<const local_index> held,
                                      std::span<const double> centroids,
                                      std::span<const double> work);

  /// Facets that changed rank in the last distribute(), summed over the ranks.
  std::int64_t moved() const { return moved_; }
  /// Partitions made so far (the first one included).
  int n_partitions() const { return n_partitions_; }

private:
  MPI_Comm comm_;
  int dim_;
  ProximityPartition partition_;
  std::int64_t moved_ = 0;
  int n_partitions_ = 0;
};

} // namespace seam::parallel
