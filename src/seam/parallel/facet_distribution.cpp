#include "seam/parallel/facet_distribution.hpp"

#include "seam/common/error.hpp"
#include "seam/parallel/exchange.hpp"
#include "seam/parallel/rcb.hpp"

#include <algorithm>

namespace seam::parallel {

FacetDistribution::FacetDistribution(MPI_Comm comm, int dim)
    : comm_(comm), dim_(dim), partition_(dim) {}

std::vector<global_index> FacetDistribution::distribute(std::span<const global_index> ids,
                                                        std::span<const double> centroids,
                                                        std::span<const double> work) {
  int size = 1;
  MPI_Comm_size(comm_, &size);
  const auto n = ids.size();
  SEAM_ASSERT(centroids.size() == n * static_cast<std::size_t>(dim_) && work.size() == n);
  std::vector<int> parts(n, 0);
  if (n_partitions_ == 0)
    partition_.partition(comm_, centroids, work, ids, parts);
  else
    partition_.repartition(comm_, centroids, work, ids, parts);
  ++n_partitions_;
  moved_ = count_moving(comm_, parts);
  // Send every facet id to its new rank.
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  for (const int p : parts) ++offsets[static_cast<std::size_t>(p) + 1];
  for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
  std::vector<global_index> send(n);
  {
    std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < n; ++i)
      send[static_cast<std::size_t>(next[static_cast<std::size_t>(parts[i])]++)] = ids[i];
  }
  std::vector<std::int64_t> recv_offsets;
  auto mine = alltoallv<global_index>(comm_, send, offsets, recv_offsets);
  std::sort(mine.begin(), mine.end());
  return mine;
}

FacetDistribution::State FacetDistribution::state() const {
  State s;
  s.n_partitions = n_partitions_;
  if (n_partitions_ == 0) return s;
  s.n_parts = partition_.close().n_parts();
  s.close = partition_.close().cuts();
  s.far = partition_.far().cuts();
  return s;
}

void FacetDistribution::restore(const State& state) {
  int size = 1;
  MPI_Comm_size(comm_, &size);
  SEAM_CHECK(state.n_partitions > 0 && state.n_parts == size, InputError,
             "facet distribution: a cut of ", state.n_parts, " parts (", state.n_partitions,
             " partitions) cannot continue on ", size, " ranks");
  partition_.restore(state.n_parts, state.close, state.far);
  n_partitions_ = state.n_partitions;
  moved_ = 0;
}

} // namespace seam::parallel
