#pragma once
// Wall-clock phase timers for summary.json (assembly, mortar, search, linear_solve, output).
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
  void add(const std::string& phase, double seconds) { seconds_[phase] += seconds; }
  double get(const std::string& phase) const {
    auto it = seconds_.find(phase);
    return it == seconds_.end() ? 0.0 : it->second;
  }
  const std::map<std::string, double>& all() const { return seconds_; }

private:
  std::map<std::string, double> seconds_;
};

/// Adds the time between construction and destruction to one phase.
class ScopedTimer {
public:
  ScopedTimer(PhaseTimers& timers, std::string phase)
      : timers_(timers), phase_(std::move(phase)), start_(wall_seconds()) {}
  ~ScopedTimer() { timers_.add(phase_, wall_seconds() - start_); }
  ScopedTimer(const ScopedTimer&) = delete;
  ScopedTimer& operator=(const ScopedTimer&) = delete;

private:
  PhaseTimers& timers_;
  std::string phase_;
  double start_;
};

} // namespace seam
