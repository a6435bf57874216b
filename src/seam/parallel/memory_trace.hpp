#pragma once
// Resident memory of this process by phase of a run (issue 12: where the peak of the largest
// rank is set). Linux reports the peak resident set (VmHWM) since the process started or since
// it was last reset through /proc/self/clear_refs; resetting it at every mark gives each
// phase's own peak. The run's overall peak is the largest of the phase peaks (the reset also
// resets getrusage's ru_maxrss, so peak_rss_mb() must be used instead of it).
#include <mpi.h>

#include <string>
#include <vector>

namespace seam::parallel {

struct MemoryPhase {
  std::string name;
  double peak_mb = 0.0;    ///< largest resident set between the previous mark and this one
  double current_mb = 0.0; ///< resident set at the mark
};

/// The resident set of this process now and its peak since the last reset (MB); zeros where
/// /proc is not available.
MemoryPhase memory_now(const std::string& name);

/// Records a phase on every rank (collective): this rank's peak since the previous mark and
/// its resident set now; then starts the next phase's peak. With SEAM_MEMORY_TRACE=1 in the
/// environment rank 0 prints one line per rank ("seam memory: PHASE rank R peak P MB current C
/// MB"). `once`: a phase already recorded is not recorded again (marks inside loops).
void mark_memory(MPI_Comm comm, const std::string& phase, bool once = false);

/// The phases recorded so far by this process, in order.
const std::vector<MemoryPhase>& memory_phases();

/// The peak resident set of this process over the whole run (MB): the largest phase peak and
/// the peak since the last mark.
double peak_rss_mb();

/// True if SEAM_MEMORY_TRACE is set to a value other than 0.
bool memory_trace_enabled();

} // namespace seam::parallel
