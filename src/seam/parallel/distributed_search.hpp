#pragma once
// The contact search of one interface distributed over the ranks (seed paper Sect. 3.1-3.2):
// each rank holds a part of the slave surface (e.g. after an Rcb partition and migrate), gets
// the master facets that can meet it by ghosting, and runs seam::search::InterfaceSearch on its
// part. Every candidate pair is found on exactly one rank, the one holding its slave facet.
#include "seam/common/types.hpp"
#include "seam/parallel/ghosting.hpp"
#include "seam/parallel/surface_part.hpp"
#include "seam/search/interface_search.hpp"

#include <mpi.h>

#include <compare>
#include <cstdint>
#include <optional>
#include <span>
#include <vector>

namespace seam::parallel {

/// A candidate pair in global facet ids.
struct GlobalPair {
  global_index slave;
  global_index master;
  friend bool operator==(const GlobalPair&, const GlobalPair&) = default;
  friend auto operator<=>(const GlobalPair&, const GlobalPair&) = default;
};

/// Collective. The inflation of the whole interface, as search::InterfaceSearch computes it
/// for whole surfaces: factor * the shortest edge of both surfaces (of one of them if the
/// other has no edge of positive length).
double global_inflation(MPI_Comm comm, const SurfacePart& slave, const SurfacePart& master,
                        double factor);

struct DistributedSearchOptions {
  search::BoundingVolume volume = search::BoundingVolume::kdop;
  double rebuild_factor = 1.5; ///< see search::TreeOptions
  GhostingOptions ghosting;
  /// Verlet skin of the ghosting (VerletGhosts): 0 ghosts anew at every find_pairs().
  double skin = 0.0;
};

/// What the last find_pairs() did on this rank.
struct SearchStats {
  local_index n_slave = 0;
  local_index n_ghosts = 0; ///< master facets received (own ones included)
  std::int64_t n_pairs = 0;
  ExchangeStats ghosting;
  bool rebuilt = false;        ///< trees built anew (the slave part or the ghosts changed)
  bool exchanged = false;      ///< the ghosts were exchanged anew (not reused)
  double ghost_seconds = 0.0;  ///< boxes, Allgatherv and Alltoallv
  double search_seconds = 0.0; ///< tree build or refit, and traversal
};

class DistributedSearch {
public:
  /// `inflation` (absolute, the same on every rank; see global_inflation) widens every volume,
  /// in the ghosting as in the search.
  DistributedSearch(MPI_Comm comm, double inflation, const DistributedSearchOptions& options = {});

  /// Collective. Ghosts the master facets that can meet `slave` (this rank's slave part) from
  /// `master` (the master facets this rank holds; any distribution) and finds the pairs. The
  /// trees are refitted if the slave part and the ghost set are the same facets as in the
  /// previous call, built anew otherwise. With a skin the ghosts of an earlier call are reused
  /// while they can be (VerletGhosts), their nodes placed at `master_positions` (indexed by
  /// master node id, or by the position of the id in `position_ids` if given).
  void find_pairs(const SurfacePart& slave, const SurfacePart& master,
                  std::span<const double> master_positions = {},
                  std::span<const global_index> position_ids = {});

  /// Pairs of the last call: slave = facet index in the slave part passed, master = facet
  /// index in ghosts().
  const std::vector<search::CandidatePair>& pairs() const { return pairs_; }
  const SurfacePart& ghosts() const { return ghosting_.ghosts(); }
  const SearchStats& stats() const { return stats_; }
  /// Ghost exchanges and find_pairs() calls so far.
  std::int64_t n_exchanges() const { return ghosting_.n_exchanges(); }
  std::int64_t n_searches() const { return ghosting_.n_updates(); }
  double inflation() const { return inflation_; }

  /// The pairs of the last call in global ids, sorted.
  std::vector<GlobalPair> global_pairs() const;

private:
  MPI_Comm comm_;
  double inflation_;
  DistributedSearchOptions options_;
  VerletGhosts ghosting_;
  std::vector<global_index> slave_ids_;
  std::vector<local_index> slave_connectivity_; // what the trees were built on
  std::vector<global_index> ghost_ids_;
  std::optional<search::InterfaceSearch> search_;
  std::vector<search::CandidatePair> pairs_;
  SearchStats stats_;
};

/// Collective. The pairs of every rank, concatenated (for tests and reports: O(global)).
std::vector<GlobalPair> gather_pairs(MPI_Comm comm, const std::vector<GlobalPair>& local);

} // namespace seam::parallel
