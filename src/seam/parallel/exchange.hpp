#pragma once
// Collective exchange helpers over MPI_Alltoall(v)/Allgather(v) for trivially copyable records.
// Every rank calls them, also with nothing to send, so that no error path skips a collective.
#include "seam/common/error.hpp"

#include <mpi.h>

#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <vector>

namespace seam::parallel {

namespace detail {
inline int checked_count(std::size_t n) {
  SEAM_CHECK(n <= static_cast<std::size_t>(std::numeric_limits<int>::max()), InternalError,
             "parallel: message of ", n, " bytes exceeds MPI's int count");
  return static_cast<int>(n);
}
} // namespace detail

/// Sends send[send_offsets[r] .. send_offsets[r+1]) to rank r (send_offsets has size + 1
/// entries) and returns what every rank sent here, in rank order; recv_offsets (size + 1) says
/// where each source's records start.
template <class T>
std::vector<T> alltoallv(MPI_Comm comm, std::span<const T> send,
                         std::span<const std::int64_t> send_offsets,
                         std::vector<std::int64_t>& recv_offsets) {
  static_assert(std::is_trivially_copyable_v<T>);
  int size = 1;
  MPI_Comm_size(comm, &size);
  SEAM_ASSERT(send_offsets.size() == static_cast<std::size_t>(size) + 1);
  std::vector<int> scount(size), sdispl(size), rcount(size), rdispl(size);
  for (int r = 0; r < size; ++r) {
    scount[r] = detail::checked_count((send_offsets[r + 1] - send_offsets[r]) * sizeof(T));
    sdispl[r] = detail::checked_count(send_offsets[r] * sizeof(T));
  }
  MPI_Alltoall(scount.data(), 1, MPI_INT, rcount.data(), 1, MPI_INT, comm);
  recv_offsets.assign(size + 1, 0);
  for (int r = 0; r < size; ++r) recv_offsets[r + 1] = recv_offsets[r] + rcount[r] / sizeof(T);
  for (int r = 0; r < size; ++r) rdispl[r] = detail::checked_count(recv_offsets[r] * sizeof(T));
  std::vector<T> recv(recv_offsets[size]);
  MPI_Alltoallv(send.data(), scount.data(), sdispl.data(), MPI_BYTE, recv.data(), rcount.data(),
                rdispl.data(), MPI_BYTE, comm);
  return recv;
}

/// Every rank's `local` records, concatenated in rank order; offsets (size + 1) as above.
template <class T>
std::vector<T> allgatherv(MPI_Comm comm, std::span<const T> local,
                          std::vector<std::int64_t>& offsets) {
  static_assert(std::is_trivially_copyable_v<T>);
  int size = 1;
  MPI_Comm_size(comm, &size);
  const int mine = detail::checked_count(local.size() * sizeof(T));
  std::vector<int> count(size), displ(size);
  MPI_Allgather(&mine, 1, MPI_INT, count.data(), 1, MPI_INT, comm);
  offsets.assign(size + 1, 0);
  for (int r = 0; r < size; ++r) offsets[r + 1] = offsets[r] + count[r] / sizeof(T);
  for (int r = 0; r < size; ++r) displ[r] = detail::checked_count(offsets[r] * sizeof(T));
  std::vector<T> all(offsets[size]);
  MPI_Allgatherv(local.data(), mine, MPI_BYTE, all.data(), count.data(), displ.data(), MPI_BYTE,
                 comm);
  return all;
}

/// Throws `message` as InputError on every rank if `bad` holds on any rank (one Allreduce), so
/// that a check made on one rank's data never leaves the others waiting in a collective.
inline void check_collectively(MPI_Comm comm, bool bad, const char* message) {
  int local = bad ? 1 : 0, any = 0;
  MPI_Allreduce(&local, &any, 1, MPI_INT, MPI_MAX, comm);
  SEAM_CHECK(!any, InputError, message, bad ? "" : " (on another rank)");
}

} // namespace seam::parallel
