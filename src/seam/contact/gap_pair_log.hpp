#pragma once
// Diagnostics of the 2D weighted-gap blocks (SEAM_CONTACT_TRACE=3, docs/contact_dynamics.md,
// "Diagnosing a stalled Newton step"): while a log is set, ContactInterface::gap_blocks records
// every line2 pair it evaluates, so that the pairs whose block appears or disappears between two
// Newton iterates can be named.
#include <cstdint>
#include <vector>

namespace seam::contact {

struct GapPairRecord {
  std::int64_t slave_nodes[2] = {0, 0};  ///< mesh nodes of the slave facet
  std::int64_t master_nodes[2] = {0, 0}; ///< mesh nodes of the master facet
  int status = 0;                        ///< 0 a block, 1 dropped by the pre-check, 2 no overlap
  bool kept = false;    ///< integrated without the pre-check (keep_prechecked_pairs)
  double alignment = 0; ///< n_s . n_m of the facets' chords
  double gap[2] = {0, 0};
};

namespace detail {
/// Set (non-null) by the caller around a gap_blocks call it wants recorded.
extern std::vector<GapPairRecord>* gap_pair_log;
} // namespace detail

} // namespace seam::contact
