#include "seam/parallel/distributed_search.hpp"

#include "seam/common/error.hpp"
#include "seam/common/timer.hpp"
#include "seam/parallel/exchange.hpp"

#include <algorithm>
#include <limits>

namespace seam::parallel {

double global_inflation(MPI_Comm comm, const SurfacePart& slave, const SurfacePart& master,
                        double factor) {
  check_collectively(comm, !(factor >= 0.0), "distributed search: inflation factor must be >= 0");
  constexpr double inf = std::numeric_limits<double>::infinity();
  // Shortest positive edge of each surface over all ranks (+inf: none).
  double l[2] = {inf, inf};
  const SurfacePart* parts[2] = {&slave, &master};
  for (int k = 0; k < 2; ++k)
    if (parts[k]->n_facets() > 0) {
      const double e = search::min_edge_length(parts[k]->view());
      if (e > 0.0) l[k] = e;
    }
  MPI_Allreduce(MPI_IN_PLACE, l, 2, MPI_DOUBLE, MPI_MIN, comm);
  const double l_min = std::min(l[0], l[1]);
  return std::isfinite(l_min) ? factor * l_min : 0.0;
}

DistributedSearch::DistributedSearch(MPI_Comm comm, double inflation,
                                     const DistributedSearchOptions& options)
    : comm_(comm), inflation_(inflation), options_(options),
      ghosting_(comm, inflation, options.skin, options.ghosting) {
  SEAM_CHECK(inflation >= 0.0, InputError, "distributed search: inflation must be >= 0");
}

void DistributedSearch::find_pairs(const SurfacePart& slave, const SurfacePart& master,
                                   std::span<const double> master_positions,
                                   std::span<const global_index> position_ids) {
  stats_ = {};
  const double t0 = wall_seconds();
  stats_.exchanged = ghosting_.update(slave, master, master_positions, position_ids);
  if (stats_.exchanged) stats_.ghosting = ghosting_.exchange_stats();
  const auto& ghosts = ghosting_.ghosts();
  const double t1 = wall_seconds();

  // Trees kept while both sides are the same facets (the usual Newton iteration).
  const bool same = search_ && slave.facet_ids == slave_ids_ &&
                    slave.connectivity == slave_connectivity_ && ghosts.facet_ids == ghost_ids_;
  pairs_.clear();
  if (slave.n_facets() > 0 && ghosts.n_facets() > 0) {
    if (same) {
      search_->update(slave.coords, ghosts.coords);
    } else {
      search::SearchOptions so;
      so.volume = options_.volume;
      so.rebuild_factor = options_.rebuild_factor;
      so.inflation = inflation_;
      search_.emplace(slave.view(), ghosts.view(), so);
      slave_connectivity_ = slave.connectivity;
      ghost_ids_ = ghosts.facet_ids;
      stats_.rebuilt = true;
    }
    pairs_ = search_->find_pairs();
  } else {
    search_.reset();
  }
  slave_ids_ = slave.facet_ids;
  stats_.search_seconds = wall_seconds() - t1;
  stats_.ghost_seconds = t1 - t0;
  stats_.n_slave = slave.n_facets();
  stats_.n_ghosts = ghosts.n_facets();
  stats_.n_pairs = static_cast<std::int64_t>(pairs_.size());
}

std::vector<GlobalPair> DistributedSearch::global_pairs() const {
  std::vector<GlobalPair> out;
  out.reserve(pairs_.size());
  const auto& ghosts = ghosting_.ghosts();
  for (const auto& p : pairs_) out.push_back({slave_ids_[p.slave], ghosts.facet_ids[p.master]});
  std::sort(out.begin(), out.end());
  return out;
}

std::vector<GlobalPair> gather_pairs(MPI_Comm comm, const std::vector<GlobalPair>& local) {
  std::vector<std::int64_t> offsets;
  return allgatherv<GlobalPair>(comm, local, offsets);
}

} // namespace seam::parallel
