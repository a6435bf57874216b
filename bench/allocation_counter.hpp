#pragma once
// Heap allocation counting for seam-bench. allocation_counter.cpp replaces the global operator
// new / delete of the executable with counting versions and, on glibc, interposes malloc,
// calloc and realloc too, so that allocations that bypass operator new (Eigen's dynamic
// matrices use malloc) are seen as well. A benchmark reads the counters around the code it
// checks: AllocationCount::now() before and after, and the difference.
#include <cstdint>
#include <cstdlib> // defines __GLIBC__ on glibc

namespace seam::bench {

struct AllocationCount {
  std::uint64_t operator_new = 0; ///< calls of any global operator new
  std::uint64_t malloc = 0;       ///< calls of malloc, calloc, realloc (0 unless counts_malloc)
  static AllocationCount now();
  AllocationCount operator-(const AllocationCount& o) const {
    return {operator_new - o.operator_new, malloc - o.malloc};
  }
};

#if defined(__GLIBC__)
inline constexpr bool counts_malloc = true;
#else
inline constexpr bool counts_malloc = false;
#endif

} // namespace seam::bench
