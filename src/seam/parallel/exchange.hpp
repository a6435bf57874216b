#pragma once
// Collective exchange helpers over MPI_Alltoall(v)/Allgather(v) for trivially copyable records.
// Every rank calls them, also with nothing to send, so that no error path skips a collective.
#include "seam/common/error.hpp"

#include <mpi.h>

#include <algorithm>
#include <cstdint>
#include <limits>
#include <span>
#include <type_traits>
#include <utility>
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

/// Collective. Item i of this rank has the key keys[i] (the same item on several ranks has the
/// same key), the owner rank owners[i] and `width` (<= 3) values from values[i * width]. The
/// values of a key are summed over the ranks on its owner, in rank order: on return the items
/// this rank owns hold the sums and the others zero.
inline void sum_on_owners(MPI_Comm comm, std::span<const std::int64_t> keys,
                          std::span<const int> owners, std::span<double> values, int width) {
  struct Record {
    std::int64_t key;
    double v[3];
  };
  SEAM_ASSERT(width >= 1 && width <= 3 && keys.size() == owners.size() &&
              values.size() == keys.size() * static_cast<std::size_t>(width));
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  const auto nonzero = [&](std::size_t i) {
    for (int c = 0; c < width; ++c)
      if (values[i * width + c] != 0.0) return true;
    return false;
  };
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (nonzero(i)) ++offsets[static_cast<std::size_t>(owners[i]) + 1];
  for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
  std::vector<Record> send(static_cast<std::size_t>(offsets[size]));
  {
    std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (!nonzero(i)) continue;
      Record rec{keys[i], {0.0, 0.0, 0.0}};
      for (int c = 0; c < width; ++c) rec.v[c] = values[i * width + c];
      send[static_cast<std::size_t>(next[owners[i]]++)] = rec;
    }
  }
  std::vector<std::int64_t> recv_offsets;
  const auto recv = alltoallv<Record>(comm, send, offsets, recv_offsets);
  std::vector<std::pair<std::int64_t, std::size_t>> mine;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    for (int c = 0; c < width; ++c) values[i * width + c] = 0.0;
    if (owners[i] == rank) mine.emplace_back(keys[i], i);
  }
  std::sort(mine.begin(), mine.end());
  for (const auto& rec : recv) {
    const auto it = std::lower_bound(mine.begin(), mine.end(),
                                     std::pair<std::int64_t, std::size_t>{rec.key, 0});
    SEAM_ASSERT(it != mine.end() && it->first == rec.key);
    for (int c = 0; c < width; ++c) values[it->second * width + c] += rec.v[c];
  }
}

} // namespace seam::parallel
