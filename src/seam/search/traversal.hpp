#pragma once
// Queries on search trees: the dual-tree traversal of two surfaces (seed paper Sect. 3.2), the
// single-tree self-contact query, and brute-force references with the same overlap tests.
#include "seam/common/types.hpp"
#include "seam/search/tree.hpp"

#include <numbers>
#include <vector>

namespace seam::search {

/// A candidate pair: facet numbers in the slave and the master surface (for self contact two
/// facets of the same surface, slave < master; roles are assigned later, see assign_roles).
struct CandidatePair {
  local_index slave;
  local_index master;
  friend bool operator==(const CandidatePair&, const CandidatePair&) = default;
  friend auto operator<=>(const CandidatePair&, const CandidatePair&) = default;
};

/// Every pair (s, m) whose bounding volumes overlap, in traversal order (sort if an order is
/// needed). Both trees must have the same dimension and volume type. `out` is overwritten.
void find_pairs(const Tree& slave, const Tree& master, std::vector<CandidatePair>& out);
std::vector<CandidatePair> find_pairs(const Tree& slave, const Tree& master);

struct SelfContactOptions {
  /// Two facets are candidates only if their normals may be at least this far apart (radians).
  /// Touching solid boundaries have opposed outward normals, so the default pi/2 loses no
  /// contact; 0 disables the normal-cone test (then the tree needs no cones).
  double min_normal_angle = 0.5 * std::numbers::pi;
};

/// Self contact of one surface: every pair of facets (a < b) whose volumes overlap, that share
/// no node, and whose normal cones allow an angle of at least min_normal_angle. Subtrees whose
/// normal cone is narrower than min_normal_angle / 2 (smooth patches) are not searched within.
/// Needs a tree built with TreeOptions::normal_cones unless min_normal_angle <= 0.
void find_self_pairs(const Tree& tree, std::vector<CandidatePair>& out,
                     const SelfContactOptions& options = {});
std::vector<CandidatePair> find_self_pairs(const Tree& tree,
                                           const SelfContactOptions& options = {});

/// References for tests and benchmarks: the same tests applied to all N x M (or N (N-1) / 2)
/// facet pairs, sorted.
std::vector<CandidatePair> find_pairs_brute_force(const Tree& slave, const Tree& master);
std::vector<CandidatePair> find_self_pairs_brute_force(const Tree& tree,
                                                       const SelfContactOptions& options = {});

} // namespace seam::search
