#pragma once
// Weighted recursive coordinate bisection (RCB) of distributed points (facet centroids) over
// the ranks of a communicator: the independent interface distribution of the seed paper,
// Sect. 3.1 (its first step), done with coordinates instead of a graph, as Zoltan's and
// Tribol's RCB do.
//
// The point set is never gathered. Each cut is found by a few rounds of weight histograms
// (one Allreduce per round for all cuts of one tree level), so a partition costs
// O(levels * rounds) small collectives and no O(global) array on any rank. Weights are turned
// into integers (the global sum scaled to 2^50) so that every sum is exact and every rank takes
// the same decision. Ties along the cut axis (structured meshes: whole rows of centroids on one
// coordinate) are split by global id inside the thinnest slab the histogram reaches.
//
// The cut tree is kept: repartition() keeps the axes of every cut and only shifts the cut
// planes to the new points and weights, so facets away from the moving planes keep their rank
// (Zoltan's RCB_REUSE).
#include "seam/common/types.hpp"

#include <mpi.h>

#include <cstdint>
#include <span>
#include <vector>

namespace seam::parallel {

struct RcbOptions {
  int n_bins = 32;         ///< histogram bins per cut and round
  double tolerance = 1e-4; ///< a cut stops when its crossing bin holds at most this fraction
                           ///< of the weight being split
  int max_rounds = 64;     ///< per cut and phase (coordinate, then id)
};

/// One cut: a point (x, id) goes to the low side iff x[axis] < lo, or x[axis] < hi and
/// id < id_cut (lo <= hi; a plain plane has lo == hi).
struct RcbCut {
  int axis = 0;
  double lo = 0.0;
  double hi = 0.0;
  global_index id_cut = 0;
  bool low_side(const double* x, global_index id) const {
    return x[axis] < lo || (x[axis] < hi && id < id_cut);
  }
};

class Rcb {
public:
  explicit Rcb(int dim, const RcbOptions& options = {});

  /// Collective. New cuts for the points of all ranks (dim() values each), with non-negative
  /// weights (all zero: unit weights) and unique global ids; every cut splits along the longest
  /// extent of its points. Writes each local point's part (= rank) to `parts`.
  void partition(MPI_Comm comm, std::span<const double> points, std::span<const double> weights,
                 std::span<const global_index> ids, std::span<int> parts);

  /// Collective. As partition(), but keeps the axis of every cut of the previous partition and
  /// only moves its plane (falls back to partition() if there is none, or if the number of
  /// ranks changed).
  void repartition(MPI_Comm comm, std::span<const double> points, std::span<const double> weights,
                   std::span<const global_index> ids, std::span<int> parts);

  /// The part of a point under the current cuts (local; no communication).
  int part_of(const double* x, global_index id) const;

  int dim() const { return dim_; }
  int n_parts() const { return n_parts_; }
  bool has_cuts() const { return n_parts_ > 0; }
  /// The cuts, one per inner node of the tree, in the order they were made (level by level).
  std::vector<RcbCut> cuts() const;
  /// Histogram rounds (Allreduce pairs) the last call took, over all levels.
  int n_rounds() const { return n_rounds_; }
  /// Local. The cut tree of `n_parts` parts with `cuts` (as cuts() lists them, n_parts - 1),
  /// as the partition that made them left it: a restart continues the repartitions of a
  /// checkpointed run. InputError for another number of cuts.
  void restore(int n_parts, std::span<const RcbCut> cuts);

private:
  struct Node {
    int first_part = 0;
    int n_parts = 1;
    RcbCut cut;
    int low = -1; ///< children (tree node indices), -1 for a leaf
    int high = -1;
  };
  void run(MPI_Comm comm, std::span<const double> points, std::span<const double> weights,
           std::span<const global_index> ids, std::span<int> parts, bool keep_axes);
  /// nodes_ of a tree of `n_parts` parts, without cuts.
  void shape(int n_parts);

  int dim_;
  RcbOptions options_;
  int n_parts_ = 0;
  int n_rounds_ = 0;
  std::vector<Node> nodes_;
};

/// Collective. Total weight of each part over all ranks (weights all zero: unit weights), and
/// the ratio max/mean of them (1 if all parts are empty).
double part_imbalance(MPI_Comm comm, std::span<const double> weights, std::span<const int> parts,
                      int n_parts, std::vector<double>* part_weights = nullptr);

/// Collective. Number of local points (summed over ranks) whose part differs from the rank
/// that holds them: the facets a migration moves.
std::int64_t count_moving(MPI_Comm comm, std::span<const int> parts);

} // namespace seam::parallel
