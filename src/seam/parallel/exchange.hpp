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

namespace detail {
/// The values of one item, sent with its key (sum_on_owners, publish_from_owners).
struct KeyValues {
  std::int64_t key;
  double v[4];
};
inline bool any_nonzero(std::span<const double> values, std::size_t i, int width) {
  for (int c = 0; c < width; ++c)
    if (values[i * width + c] != 0.0) return true;
  return false;
}
} // namespace detail

/// Collective. Item i of this rank has the key keys[i] (the same item on several ranks has the
/// same key), the owner rank owners[i] and `width` (<= 4) values from values[i * width]. The
/// values of a key are summed over the ranks on its owner, in rank order: on return the items
/// this rank owns hold the sums and the others zero. Items whose values are all zero are not
/// sent, so the exchange is in proportion to the nonzero items. Returns the number of items
/// this rank sent.
inline std::size_t sum_on_owners(MPI_Comm comm, std::span<const std::int64_t> keys,
                                 std::span<const int> owners, std::span<double> values, int width) {
  using Record = detail::KeyValues;
  SEAM_ASSERT(width >= 1 && width <= 4 && keys.size() == owners.size() &&
              values.size() == keys.size() * static_cast<std::size_t>(width));
  int rank = 0, size = 1;
  MPI_Comm_rank(comm, &rank);
  MPI_Comm_size(comm, &size);
  std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
  for (std::size_t i = 0; i < keys.size(); ++i)
    if (detail::any_nonzero(values, i, width)) ++offsets[static_cast<std::size_t>(owners[i]) + 1];
  for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
  std::vector<Record> send(static_cast<std::size_t>(offsets[size]));
  {
    std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
    for (std::size_t i = 0; i < keys.size(); ++i) {
      if (!detail::any_nonzero(values, i, width)) continue;
      Record rec{keys[i], {0.0, 0.0, 0.0, 0.0}};
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
  return send.size();
}

/// Collective; the counterpart of sum_on_owners for items that every rank holds. The items
/// this rank owns (owners[i] == rank) whose `width` (<= 4) values are not all zero go to every
/// rank (one Allgatherv); on return every item holds the values its owner sent, zero where
/// the owner sent none. What is exchanged is in proportion to the nonzero items, not to all
/// keys. Returns the number of items this rank published.
inline std::size_t publish_from_owners(MPI_Comm comm, std::span<const std::int64_t> keys,
                                       std::span<const int> owners, std::span<double> values,
                                       int width) {
  using Record = detail::KeyValues;
  SEAM_ASSERT(width >= 1 && width <= 4 && keys.size() == owners.size() &&
              values.size() == keys.size() * static_cast<std::size_t>(width));
  int rank = 0;
  MPI_Comm_rank(comm, &rank);
  std::vector<Record> mine;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    if (owners[i] != rank || !detail::any_nonzero(values, i, width)) continue;
    Record rec{keys[i], {0.0, 0.0, 0.0, 0.0}};
    for (int c = 0; c < width; ++c) rec.v[c] = values[i * width + c];
    mine.push_back(rec);
  }
  std::vector<std::int64_t> offsets;
  auto all = allgatherv<Record>(comm, mine, offsets);
  std::sort(all.begin(), all.end(), [](const Record& a, const Record& b) { return a.key < b.key; });
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const auto it = std::lower_bound(all.begin(), all.end(), keys[i],
                                     [](const Record& a, std::int64_t k) { return a.key < k; });
    const bool found = it != all.end() && it->key == keys[i];
    for (int c = 0; c < width; ++c) values[i * width + c] = found ? it->v[c] : 0.0;
  }
  return mine.size();
}

} // namespace seam::parallel
