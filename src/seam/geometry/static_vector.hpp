#pragma once
// A vector with a compile-time capacity and a run-time size, stored inline. The geometry
// kernels run once per element pair (or per integration cell), so their polygons and cell
// lists must not touch the heap; the capacities follow from the element types (a clip of
// an n-gon by an m-gon has at most n + m vertices).
#include <array>
#include <cstddef>

#include "seam/common/error.hpp"

namespace seam::geometry {

template <class T, int Capacity> class StaticVector {
public:
  static constexpr int capacity = Capacity;

  StaticVector() = default;
  // Copies move only the live elements: the per-pair polygons are copied often and are
  // mostly far from full.
  StaticVector(const StaticVector& other) : n_(other.n_) {
    for (int i = 0; i < n_; ++i)
      data_[static_cast<std::size_t>(i)] = other.data_[static_cast<std::size_t>(i)];
  }
  StaticVector& operator=(const StaticVector& other) {
    n_ = other.n_;
    for (int i = 0; i < n_; ++i)
      data_[static_cast<std::size_t>(i)] = other.data_[static_cast<std::size_t>(i)];
    return *this;
  }

  int size() const { return n_; }
  bool empty() const { return n_ == 0; }
  bool full() const { return n_ == Capacity; }
  void clear() { n_ = 0; }

  void push_back(const T& value) {
    SEAM_ASSERT(n_ < Capacity);
    data_[static_cast<std::size_t>(n_++)] = value;
  }
  void pop_back() {
    SEAM_ASSERT(n_ > 0);
    --n_;
  }
  /// Remove the element at position i, keeping the order of the others.
  void erase(int i) {
    SEAM_ASSERT(i >= 0 && i < n_);
    for (int k = i; k + 1 < n_; ++k)
      data_[static_cast<std::size_t>(k)] = data_[static_cast<std::size_t>(k + 1)];
    --n_;
  }

  T& operator[](int i) {
    SEAM_ASSERT(i >= 0 && i < n_);
    return data_[static_cast<std::size_t>(i)];
  }
  const T& operator[](int i) const {
    SEAM_ASSERT(i >= 0 && i < n_);
    return data_[static_cast<std::size_t>(i)];
  }
  T& back() { return (*this)[n_ - 1]; }
  const T& back() const { return (*this)[n_ - 1]; }

  T* begin() { return data_.data(); }
  T* end() { return data_.data() + n_; }
  const T* begin() const { return data_.data(); }
  const T* end() const { return data_.data() + n_; }

private:
  // Left uninitialized: only the first n_ elements are ever read, and zero-filling the whole
  // capacity on every construction would cost more than the geometry itself.
  std::array<T, static_cast<std::size_t>(Capacity)> data_;
  int n_ = 0;
};

} // namespace seam::geometry
