#include "seam/parallel/memory_trace.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <string_view>

namespace seam::parallel {

namespace {

std::vector<MemoryPhase>& phases() {
  static std::vector<MemoryPhase> recorded;
  return recorded;
}

/// The value in kB of a "Key:   123 kB" line of /proc/self/status, in MB.
double status_mb(const std::string& text, std::string_view key) {
  const auto at = text.find(key);
  if (at == std::string::npos) return 0.0;
  return std::strtod(text.c_str() + at + key.size(), nullptr) / 1024.0;
}

/// Starts a new peak: Linux >= 4.0 resets VmHWM to the current resident set on "5".
void reset_peak() {
  std::ofstream clear("/proc/self/clear_refs");
  if (clear) clear << "5";
}

} // namespace

bool memory_trace_enabled() {
  const char* v = std::getenv("SEAM_MEMORY_TRACE");
  return v != nullptr && *v != '\0' && std::strcmp(v, "0") != 0;
}

MemoryPhase memory_now(const std::string& name) {
  std::ifstream in("/proc/self/status");
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  MemoryPhase p;
  p.name = name;
  p.peak_mb = status_mb(text, "VmHWM:");
  p.current_mb = status_mb(text, "VmRSS:");
  return p;
}

void mark_memory(MPI_Comm comm, const std::string& phase, bool once) {
  auto& recorded = phases();
  // The same decision on every rank: the phase list is the same on all of them.
  if (once && std::any_of(recorded.begin(), recorded.end(),
                          [&](const MemoryPhase& p) { return p.name == phase; }))
    return;
  recorded.push_back(memory_now(phase));
  reset_peak();
  if (!memory_trace_enabled()) return;
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  const double mine[2] = {recorded.back().peak_mb, recorded.back().current_mb};
  std::vector<double> all(rank == 0 ? 2 * static_cast<std::size_t>(size) : 0);
  MPI_Gather(mine, 2, MPI_DOUBLE, all.data(), 2, MPI_DOUBLE, 0, comm);
  if (rank != 0) return;
  for (int r = 0; r < size; ++r)
    std::printf("seam memory: %-22s rank %3d peak %9.1f MB current %9.1f MB\n", phase.c_str(), r,
                all[2 * r], all[2 * r + 1]);
  std::fflush(stdout);
}

const std::vector<MemoryPhase>& memory_phases() {
  return phases();
}

double peak_rss_mb() {
  double peak = memory_now("").peak_mb;
  for (const auto& p : phases()) peak = std::max(peak, p.peak_mb);
  return peak;
}

} // namespace seam::parallel
