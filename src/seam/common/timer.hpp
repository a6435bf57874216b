#pragma once
// Phase timers for summary.json (assembly, mortar, search, linear_solve, output): wall-clock
// seconds, and the CPU seconds of the calling thread where a ScopedTimer measured them.
#include <chrono>
#include <ctime>
#include <map>
#include <string>

namespace seam {

inline double wall_seconds() {
  using clock = std::chrono::steady_clock;
  static const auto start = clock::now();
  return std::chrono::duration<double>(clock::now() - start).count();
}

/// CPU time of the calling thread: the work a rank did, unaffected by other processes that
/// share its core.
inline double cpu_seconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

class PhaseTimers {
public:
  void add(const std::string& phase, double seconds, double cpu = 0.0) {
    seconds_[phase] += seconds;
    cpu_[phase] += cpu;
  }
  double get(const std::string& phase) const { return find(seconds_, phase); }
  double get_cpu(const std::string& phase) const { return find(cpu_, phase); }
  const std::map<std::string, double>& all() const { return seconds_; }

private:
  static double find(const std::map<std::string, double>& m, const std::string& phase) {
    auto it = m.find(phase);
    return it == m.end() ? 0.0 : it->second;
  }
  std::map<std::string, double> seconds_, cpu_;
};

/// Adds the time between construction and destruction to one phase.
class ScopedTimer {
public:
  ScopedTimer(PhaseTimers& timers, std::string phase)
      : timers_(timers), phase_(std::move(phase)), start_(wall_seconds()),
        start_cpu_(cpu_seconds()) {}
  ~ScopedTimer() { timers_.add(phase_, wall_seconds() - start_, cpu_seconds() - start_cpu_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
  PhaseTimers& timers_;
  std::string phase_;
  double start_, start_cpu_;
};

} // namespace seam
