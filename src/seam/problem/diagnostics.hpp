#pragma once
// The level of SEAM_CONTACT_TRACE (docs/contact_dynamics.md, "Diagnosing a stalled Newton
// step"): 0 when unset or not 1 or 2; 1 logs pairs, gap blocks, rejections and active nodes per
// Newton iteration; 2 adds the largest discrete-gradient corrections. Read once.

namespace seam::problem {

int contact_trace_level();

} // namespace seam::problem
