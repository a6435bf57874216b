// Sums on the owners of shared items and their publication to every rank (exchange.hpp), as
// the contact constraint uses them for the nodal mortar sums, against the values computed on
// every rank directly.
#include "parallel_test_support.hpp"
#include "seam/parallel/exchange.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <vector>

namespace seam::parallel::test {
namespace {

constexpr int n_items = 23;
constexpr int width = 4;

/// Rank r's share of item k, component c: nonzero on every second rank for k % 3 != 0, so that
/// some items have parts on several ranks, some on one and items k % 3 == 0 none.
double part(int r, int k, int c) {
  if (k % 3 == 0 || (k + r) % 2 != 0) return 0.0;
  return 1.0 + r + 10.0 * k + 0.25 * c;
}

int owner_of(int k) {
  return (7 * k) % size();
}

TEST(SumOnOwners, OwnersHoldTheSumsAndOnlyNonzeroItemsAreSent) {
  std::vector<std::int64_t> keys(n_items);
  std::vector<int> owners(n_items);
  std::vector<double> v(static_cast<std::size_t>(n_items) * width);
  std::size_t nonzero = 0;
  for (int k = 0; k < n_items; ++k) {
    keys[k] = 1000 + k; // keys need not be indices
    owners[k] = owner_of(k);
    for (int c = 0; c < width; ++c) v[k * width + c] = part(rank(), k, c);
    nonzero += part(rank(), k, 0) != 0.0;
  }
  EXPECT_EQ(sum_on_owners(world(), keys, owners, v, width), nonzero);
  for (int k = 0; k < n_items; ++k)
    for (int c = 0; c < width; ++c) {
      double want = 0.0;
      for (int r = 0; r < size(); ++r) want += part(r, k, c);
      EXPECT_EQ(v[k * width + c], owners[k] == rank() ? want : 0.0) << "item " << k;
    }
}

TEST(PublishFromOwners, EveryRankGetsTheOwnersValues) {
  std::vector<std::int64_t> keys(n_items);
  std::vector<int> owners(n_items);
  std::vector<double> v(static_cast<std::size_t>(n_items) * width);
  std::size_t published = 0;
  for (int k = 0; k < n_items; ++k) {
    keys[k] = 2 * k;
    owners[k] = owner_of(k);
    // The owner holds the value; every other rank holds garbage that must be replaced, also
    // for items whose owner holds zeros (k % 3 == 0), which are not sent.
    const bool mine = owners[k] == rank();
    for (int c = 0; c < width; ++c)
      v[k * width + c] = mine ? (k % 3 == 0 ? 0.0 : k + 0.5 * c) : -1.0 - rank();
    published += mine && k % 3 != 0;
  }
  EXPECT_EQ(publish_from_owners(world(), keys, owners, v, width), published);
  for (int k = 0; k < n_items; ++k)
    for (int c = 0; c < width; ++c)
      EXPECT_EQ(v[k * width + c], k % 3 == 0 ? 0.0 : k + 0.5 * c) << "item " << k;
}

TEST(HolderPublisher, TheHoldersGetTheOwnersValuesAndNoOtherRank) {
  // Rank r holds item k if it owns it or (k + r) % 3 != 0: items held by some ranks only,
  // listed in a rank-dependent order.
  std::vector<std::int64_t> keys;
  std::vector<int> owners;
  for (int k = n_items - 1; k >= 0; --k)
    if (owner_of(k) == rank() || (k + rank()) % 3 != 0) {
      keys.push_back(5 * k + 1);
      owners.push_back(owner_of(k));
    }
  const HolderPublisher publisher(world(), keys, owners);
  const auto value = [](int k, int c) { return k % 4 == 0 ? 0.0 : k + 0.5 * c; };
  std::vector<double> v(keys.size() * width);
  std::size_t published = 0;
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const int k = static_cast<int>(keys[i] / 5);
    const bool mine = owners[i] == rank();
    for (int c = 0; c < width; ++c) v[i * width + c] = mine ? value(k, c) : -1.0 - rank();
  }
  // The records sent: one per other rank holding a nonzero owned item.
  for (int k = 0; k < n_items; ++k)
    if (owner_of(k) == rank() && k % 4 != 0)
      for (int r = 0; r < size(); ++r) published += r != rank() && (k + r) % 3 != 0;
  EXPECT_EQ(publisher.publish(v, width), published);
  for (std::size_t i = 0; i < keys.size(); ++i)
    for (int c = 0; c < width; ++c)
      EXPECT_EQ(v[i * width + c], value(static_cast<int>(keys[i] / 5), c)) << "key " << keys[i];
  // Again with other values: the publisher is reused.
  for (std::size_t i = 0; i < keys.size(); ++i)
    for (int c = 0; c < width; ++c) v[i * width + c] = owners[i] == rank() ? 2.0 : 7.0;
  publisher.publish(v, width);
  for (const double x : v) EXPECT_EQ(x, 2.0);
}

} // namespace
} // namespace seam::parallel::test
