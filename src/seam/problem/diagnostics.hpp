#pragma once
// The level of SEAM_CONTACT_TRACE (docs/contact_dynamics.md, "Diagnosing a stalled Newton
// step"): 0 when unset or not 1, 2 or 3; 1 logs pairs, gap blocks, rejections and active nodes
// per Newton iteration; 2 adds the largest discrete-gradient corrections; 3 adds, instead of
// those, the line2 pairs whose block at x_{n+1} appeared, disappeared or changed its pre-check
// or overlap status since the last evaluation. Read once.
#include "seam/contact/gap_pair_log.hpp"

#include <string>
#include <vector>

namespace seam::problem {

int contact_trace_level();

/// Level 3: prints the pairs of `records` (gap_blocks of interface `name` at x_{n+1}) that are
/// new, gone or of another status than at the interface's last call, and keeps `records`.
void trace_gap_pairs(const std::string& name, std::vector<contact::GapPairRecord>& records);

} // namespace seam::problem
