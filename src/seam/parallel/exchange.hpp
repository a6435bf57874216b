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

/// publish_from_owners for items that each rank holds in part (e.g. the slave nodes of a
/// contact side held in part): the owners send their nonzero items only to the ranks that hold
/// them, not to every rank. Made once for a fixed set of items per rank (collective: each rank
/// tells the owners which of their items it holds, one Alltoallv); each publish() is then one
/// Alltoallv in proportion to the nonzero items times the ranks holding each.
class HolderPublisher {
public:
  HolderPublisher(MPI_Comm comm, std::span<const std::int64_t> keys, std::span<const int> owners)
      : comm_(comm), keys_(keys.begin(), keys.end()), owners_(owners.begin(), owners.end()) {
    SEAM_ASSERT(keys.size() == owners.size());
    int size = 1;
    MPI_Comm_rank(comm, &rank_);
    MPI_Comm_size(comm, &size);
    for (std::size_t i = 0; i < keys_.size(); ++i) index_.emplace_back(keys_[i], i);
    std::sort(index_.begin(), index_.end());
    // The keys this rank holds without owning them, to their owners.
    std::vector<std::int64_t> offsets(static_cast<std::size_t>(size) + 1, 0);
    for (const int o : owners_)
      if (o != rank_) ++offsets[static_cast<std::size_t>(o) + 1];
    for (int r = 0; r < size; ++r) offsets[r + 1] += offsets[r];
    std::vector<std::int64_t> send(static_cast<std::size_t>(offsets[size]));
    {
      std::vector<std::int64_t> next(offsets.begin(), offsets.end() - 1);
      for (std::size_t i = 0; i < keys_.size(); ++i)
        if (owners_[i] != rank_) send[static_cast<std::size_t>(next[owners_[i]]++)] = keys_[i];
    }
    std::vector<std::int64_t> recv_offsets;
    const auto recv = alltoallv<std::int64_t>(comm, send, offsets, recv_offsets);
    // Per holding rank (in rank order), the owned items it holds.
    to_offsets_.assign(static_cast<std::size_t>(size) + 1, 0);
    for (int r = 0; r < size; ++r) {
      for (auto k = recv_offsets[r]; k < recv_offsets[r + 1]; ++k) {
        const auto i = find(recv[static_cast<std::size_t>(k)]);
        SEAM_CHECK(i >= 0 && owners_[static_cast<std::size_t>(i)] == rank_, InternalError,
                   "parallel: rank ", r, " holds item ", recv[static_cast<std::size_t>(k)],
                   ", which rank ", rank_, " does not own");
        to_items_.push_back(static_cast<std::size_t>(i));
      }
      to_offsets_[static_cast<std::size_t>(r) + 1] = static_cast<std::int64_t>(to_items_.size());
    }
  }

  /// Collective. As publish_from_owners: on return every item holds the values its owner sent,
  /// zero where the owner sent none. Returns the number of records this rank sent.
  std::size_t publish(std::span<double> values, int width) const {
    using Record = detail::KeyValues;
    SEAM_ASSERT(width >= 1 && width <= 4 &&
                values.size() == keys_.size() * static_cast<std::size_t>(width));
    const auto size = to_offsets_.size() - 1;
    std::vector<std::int64_t> offsets(size + 1, 0);
    std::vector<Record> send;
    for (std::size_t r = 0; r < size; ++r) {
      for (auto k = to_offsets_[r]; k < to_offsets_[r + 1]; ++k) {
        const auto i = to_items_[static_cast<std::size_t>(k)];
        if (!detail::any_nonzero(values, i, width)) continue;
        Record rec{keys_[i], {0.0, 0.0, 0.0, 0.0}};
        for (int c = 0; c < width; ++c) rec.v[c] = values[i * width + c];
        send.push_back(rec);
      }
      offsets[r + 1] = static_cast<std::int64_t>(send.size());
    }
    std::vector<std::int64_t> recv_offsets;
    const auto recv = alltoallv<Record>(comm_, send, offsets, recv_offsets);
    for (std::size_t i = 0; i < keys_.size(); ++i)
      if (owners_[i] != rank_)
        for (int c = 0; c < width; ++c) values[i * width + c] = 0.0;
    for (const auto& rec : recv) {
      const auto i = find(rec.key);
      SEAM_ASSERT(i >= 0);
      for (int c = 0; c < width; ++c) values[static_cast<std::size_t>(i) * width + c] = rec.v[c];
    }
    return send.size();
  }

private:
  std::int64_t find(std::int64_t key) const {
    const auto it = std::lower_bound(index_.begin(), index_.end(),
                                     std::pair<std::int64_t, std::size_t>{key, 0});
    return it != index_.end() && it->first == key ? static_cast<std::int64_t>(it->second) : -1;
  }

  MPI_Comm comm_;
  int rank_ = 0;
  std::vector<std::int64_t> keys_;
  std::vector<int> owners_;
  std::vector<std::pair<std::int64_t, std::size_t>> index_; ///< (key, item), sorted
  std::vector<std::size_t> to_items_;                       ///< owned items per holding rank
  std::vector<std::int64_t> to_offsets_; ///< where each rank's items start (size + 1)
};

} // namespace seam::parallel
