#pragma once
// Thin helpers over MPI_COMM_WORLD-style communicators. seam always runs under MPI
// (serial = one rank); collectives are called by every rank, also on error paths.
#include <mpi.h>

#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace seam {

class Comm {
public:
  explicit Comm(MPI_Comm comm = MPI_COMM_WORLD) : comm_(comm) {}
  MPI_Comm get() const { return comm_; }
  int rank() const;
  int size() const;
  bool is_root() const { return rank() == 0; }

  double sum(double v) const;
  double max(double v) const;
  double min(double v) const;
  std::int64_t sum(std::int64_t v) const;
  std::int64_t max(std::int64_t v) const;
  int sum(int v) const;
  int max(int v) const;
  /// In-place element-wise sum over ranks.
  void sum_in_place(std::span<double> v) const;
  /// True on every rank if `v` is true on any rank (for collective error checks).
  bool any(bool v) const;
  void barrier() const;

  /// Broadcast from root; the vector is resized on the receiving ranks.
  template <class T> void broadcast(std::vector<T>& v, int root = 0) const {
    std::uint64_t n = v.size();
    MPI_Bcast(&n, 1, MPI_UINT64_T, root, comm_);
    v.resize(n);
    if (n) MPI_Bcast(v.data(), static_cast<int>(n * sizeof(T)), MPI_BYTE, root, comm_);
  }
  void broadcast(std::string& s, int root = 0) const;
  template <class T> void broadcast_value(T& v, int root = 0) const {
    MPI_Bcast(&v, sizeof(T), MPI_BYTE, root, comm_);
  }

private:
  MPI_Comm comm_;
};

} // namespace seam
