#pragma once
// Master ghosting by bounding boxes (4C's "binning" strategy, without the bins): each rank
// publishes a few boxes covering its slave facets' search volumes, and every master facet is
// sent to exactly the ranks whose boxes its own volume overlaps. No rank receives the whole
// master surface, and no pair is lost: the search's k-DOP of a facet lies inside the facet's
// box (the axis slabs of the k-DOP are the box, rounded to float the same way), so a slave
// and a master facet whose volumes overlap have overlapping boxes.
#include "seam/common/types.hpp"
#include "seam/parallel/surface_part.hpp"
#include "seam/search/facets.hpp"

#include <mpi.h>

#include <array>
#include <span>
#include <vector>

namespace seam::parallel {

/// An axis-aligned box in float (components past dim unused); closed, like the k-DOP test.
struct Box {
  std::array<float, 3> lo{};
  std::array<float, 3> hi{};
};

inline bool overlap(const Box& a, const Box& b, int dim) {
  bool separated = false;
  for (int d = 0; d < dim; ++d) separated |= (a.lo[d] > b.hi[d]) | (b.lo[d] > a.hi[d]);
  return !separated;
}

/// The box of every facet's search volume widened by `inflation` (the axis slabs of the k-DOP
/// that search::Tree builds, bit for bit; with old_coords also over the step-start positions).
void facet_boxes(const search::FacetSurface& surface, double inflation, std::vector<Box>& out,
                 std::span<const double> old_coords = {});

/// At most max_boxes boxes that together cover `boxes`: a recursive median split of the boxes'
/// centres along the longest extent, each cluster replaced by its bounding box.
std::vector<Box> cluster_boxes(int dim, std::span<const Box> boxes, int max_boxes);

struct GhostingOptions {
  int boxes_per_rank = 32; ///< boxes each rank publishes for its slave part (>= 1)
};

/// Collective. Every rank passes the boxes of its region (e.g. cluster_boxes of its slave
/// facets) and the master facets it holds; returns the master facets, from all ranks, whose
/// box (facet_boxes with `inflation`) overlaps a box of this rank's region. The region boxes
/// are exchanged with one Allgatherv, the facets with one Alltoallv.
SurfacePart ghost_overlapping(MPI_Comm comm, std::span<const Box> region, const SurfacePart& master,
                              double inflation, ExchangeStats* stats = nullptr);

/// Collective. ghost_overlapping with the region = the clustered boxes of this rank's slave
/// facets (widened by the same inflation).
SurfacePart ghost_masters(MPI_Comm comm, const SurfacePart& slave, const SurfacePart& master,
                          double inflation, const GhostingOptions& options = {},
                          ExchangeStats* stats = nullptr);

/// Ghosting reused between searches, a Verlet list (docs/parallel.md, "Reused ghosting"): the
/// master facets are ghosted with volumes widened by inflation + skin / 2, and the exchange is
/// redone only when a rank's slave or master part is not the same facets as at the last
/// exchange or one of their nodes has moved more than skin / 2 since then (one collective
/// decision). While no node moved more than skin / 2, a slave and a master facet whose volumes
/// (widened by the inflation) overlap now had overlapping boxes widened by inflation + skin / 2
/// then, so the ghosts still hold every master facet the search can pair. In between, the
/// ghosts keep their facets and take their nodes' current positions from the caller. skin <= 0:
/// an exchange at every update.
class VerletGhosts {
public:
  VerletGhosts(MPI_Comm comm, double inflation, double skin, const GhostingOptions& options = {});

  /// Collective. The ghosts of `master` (the master facets this rank holds) for `slave` (this
  /// rank's slave part), exchanged anew or reused. `positions`: the current coordinates of
  /// every node id (dim per id; e.g. a side held whole), read for the nodes of reused ghosts;
  /// with a positive skin it must not be empty. With `position_ids` (sorted) `positions` holds
  /// dim values per entry of it instead, those of the node with that id (e.g. the nodes a rank
  /// holds, in global ids); a reused ghost's node must be among them. Returns true if it
  /// exchanged.
  bool update(const SurfacePart& slave, const SurfacePart& master,
              std::span<const double> positions, std::span<const global_index> position_ids = {});

  const SurfacePart& ghosts() const { return ghosts_; }
  double skin() const { return skin_; }
  std::int64_t n_exchanges() const { return n_exchanges_; }
  std::int64_t n_updates() const { return n_updates_; }
  /// Counts of the last exchange on this rank.
  const ExchangeStats& exchange_stats() const { return stats_; }

private:
  /// Whether `part` is the same facets and nodes as `ids` / `coords` and no node moved more
  /// than skin / 2 from `coords`.
  bool still_valid(const SurfacePart& part, const std::vector<global_index>& ids,
                   const std::vector<double>& coords) const;

  MPI_Comm comm_;
  double inflation_, skin_;
  GhostingOptions options_;
  SurfacePart ghosts_;
  bool exchanged_ = false;
  // The parts at the last exchange: their facets and node positions.
  std::vector<global_index> slave_ids_, master_ids_;
  std::vector<double> slave_coords_, master_coords_;
  std::int64_t n_exchanges_ = 0, n_updates_ = 0;
  ExchangeStats stats_;
};

} // namespace seam::parallel
