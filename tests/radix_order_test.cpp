#include <growth/radix_order.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <random>
#include <vector>

// The permutation is the one std::stable_sort gives: increasing key, equal keys by index. Keys
// spanning several 11-bit digits, with many repeats, so both the digit passes and the stability
// are exercised.
TEST(RadixOrder, IsTheStableSortingPermutation) {
  std::mt19937_64 rng(7);
  for (int bits : {1, 11, 12, 23, 40, 63}) {
    std::vector<std::uint64_t> key(5000);
    for (auto& k : key) k = (rng() >> (64 - bits)) & ~std::uint64_t(3); // repeats: low bits cleared
    std::vector<std::uint32_t> expect(key.size());
    for (std::uint32_t i = 0; i < expect.size(); ++i) expect[i] = i;
    std::stable_sort(expect.begin(), expect.end(), [&](std::uint32_t a, std::uint32_t b) { return key[a] < key[b]; });
    std::vector<std::uint32_t> order;
    growth::stableRadixOrder(key.data(), key.size(), bits, order);
    EXPECT_EQ(order, expect) << bits << " bits";
  }
}

TEST(RadixOrder, NoBitsGivesTheIdentity) {
  const std::vector<std::uint64_t> key(10, 0);
  growth::HugeVector<std::uint32_t> order;
  growth::stableRadixOrder(key.data(), key.size(), 0, order);
  for (std::uint32_t i = 0; i < order.size(); ++i) EXPECT_EQ(order[i], i);
  EXPECT_EQ(order.size(), key.size());
}
