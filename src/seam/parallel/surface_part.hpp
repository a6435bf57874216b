#pragma once
// One rank's part of a distributed facet surface, and its migration between ranks.
//
// A part is a small self-contained surface: its facets with their global ids, and its own node
// table (global node ids, coordinates) that the local connectivity indexes. search::FacetSurface
// views it directly, so the existing search runs on a part unchanged.
#include "seam/common/types.hpp"
#include "seam/search/facets.hpp"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace seam::parallel {

struct SurfacePart {
  int dim = 3;
  std::vector<global_index> facet_ids;   ///< global id of each facet
  std::vector<local_index> offsets{0};   ///< facet f: connectivity[offsets[f] .. offsets[f+1])
  std::vector<local_index> connectivity; ///< local node numbers
  std::vector<global_index> node_ids;    ///< global id of each local node
  std::vector<double> coords;            ///< dim values per local node

  local_index n_facets() const { return static_cast<local_index>(facet_ids.size()); }
  local_index n_nodes() const { return static_cast<local_index>(node_ids.size()); }
  search::FacetSurface view() const { return {dim, coords, offsets, connectivity}; }
};

/// The facets `facets` of a surface given by flat arrays with global numbering (connectivity
/// into global node ids, coordinates of every node of `all_coords` indexed by node id): for
/// tests and benchmarks that generate a surface and keep a part of it.
SurfacePart extract_part(int dim, std::span<const double> all_coords,
                         std::span<const local_index> offsets,
                         std::span<const local_index> connectivity,
                         std::span<const local_index> facets);

/// Centroid (mean of the nodes) of every facet, dim values per facet.
void facet_centroids(const SurfacePart& part, std::vector<double>& out);

/// Counts of one exchange, on this rank.
struct ExchangeStats {
  std::int64_t facets_sent = 0;     ///< to other ranks
  std::int64_t bytes_sent = 0;      ///< to other ranks (the message to itself is not counted)
  std::int64_t facets_received = 0; ///< from all ranks, itself included
};

/// Collective. Sends facet send_facets[k] for k in [send_offsets[r], send_offsets[r+1]) to rank
/// r (a facet may go to several ranks) and returns the facets this rank receives, sorted by
/// global facet id, with a node table of the nodes they use (a node sent by several ranks with
/// the same id is kept once; ranks must agree on its coordinates).
SurfacePart send_facets(MPI_Comm comm, const SurfacePart& part,
                        std::span<const std::int64_t> send_offsets,
                        std::span<const local_index> send_facets, ExchangeStats* stats = nullptr);

/// Collective. Moves every facet f to rank dest[f] (e.g. the result of an Rcb partition).
SurfacePart migrate(MPI_Comm comm, const SurfacePart& part, std::span<const int> dest,
                    ExchangeStats* stats = nullptr);

} // namespace seam::parallel
