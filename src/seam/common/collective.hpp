#pragma once
// Work that only rank 0 does (reading or writing files) inside collective code: an InputError
// there must reach every rank, or the others would wait forever in the next collective; and
// what rank 0 gathers for it.
#include "seam/common/error.hpp"
#include "seam/common/mpi.hpp"

#include <mpi.h>

#include <string>
#include <vector>

namespace seam {

/// Rank 0 runs `f`; an InputError there is re-thrown on every rank. Collective.
template <class F> void on_root_collectively(const Comm& comm, F&& f) {
  std::string error;
  if (comm.is_root()) {
    try {
      f();
    } catch (const InputError& e) {
      error = e.what();
    }
  }
  comm.broadcast(error);
  if (!error.empty()) throw InputError(error);
}

/// All ranks' entries of `local` (trivially copyable), in rank order, on rank 0 (empty
/// elsewhere). Collective.
template <class T> std::vector<T> gather_to_root(const Comm& comm, const std::vector<T>& local) {
  const int np = comm.size();
  const int bytes = static_cast<int>(local.size() * sizeof(T));
  std::vector<int> counts(static_cast<std::size_t>(np), 0), offsets(counts.size(), 0);
  MPI_Gather(&bytes, 1, MPI_INT, counts.data(), 1, MPI_INT, 0, comm.get());
  int total = 0;
  for (int r = 0; r < np; ++r) {
    offsets[static_cast<std::size_t>(r)] = total;
    total += counts[static_cast<std::size_t>(r)];
  }
  std::vector<T> out(comm.is_root() ? static_cast<std::size_t>(total) / sizeof(T) : 0);
  MPI_Gatherv(local.data(), bytes, MPI_BYTE, out.data(), counts.data(), offsets.data(), MPI_BYTE, 0,
              comm.get());
  return out;
}

} // namespace seam
