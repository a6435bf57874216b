#pragma once
// Work that only rank 0 does (reading or writing files) inside collective code: an InputError
// there must reach every rank, or the others would wait forever in the next collective.
#include "seam/common/error.hpp"
#include "seam/common/mpi.hpp"

#include <string>

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

} // namespace seam
