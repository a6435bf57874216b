#pragma once
// Allocator for the search trees' large flat arrays. A 1e6-facet tree spans about 100 MB that
// the traversal reads in a spatial, not linear, order; with 4 KiB pages nearly every node visit
// is a TLB miss. Arrays of at least 4 MiB are therefore aligned to 2 MiB and, on Linux, marked
// for transparent huge pages (which most systems grant on request only, "madvise" mode).
#include <cstddef>
#include <cstdlib>
#include <new>

#if defined(__linux__)
#include <sys/mman.h>
#endif

namespace seam::search::detail {

template <class T> struct HugePageAllocator {
  using value_type = T;
  static constexpr std::size_t huge_page = std::size_t(2) << 20;
  static constexpr std::size_t threshold = std::size_t(4) << 20;

  HugePageAllocator() = default;
  template <class U> HugePageAllocator(const HugePageAllocator<U>&) noexcept {}

  T* allocate(std::size_t n) {
    const std::size_t bytes = n * sizeof(T);
    if (bytes < threshold) return static_cast<T*>(::operator new(bytes));
    const std::size_t rounded = (bytes + huge_page - 1) / huge_page * huge_page;
    void* p = std::aligned_alloc(huge_page, rounded);
    if (p == nullptr) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    madvise(p, rounded, MADV_HUGEPAGE); // a hint: failure only costs speed
#endif
    return static_cast<T*>(p);
  }

  void deallocate(T* p, std::size_t n) noexcept {
    if (n * sizeof(T) < threshold)
      ::operator delete(p);
    else
      std::free(p);
  }

  template <class U> bool operator==(const HugePageAllocator<U>&) const noexcept {
    return true;
  }
};

} // namespace seam::search::detail
