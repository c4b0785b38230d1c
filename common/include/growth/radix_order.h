#pragma once
// The stable sorting permutation of integer keys by LSD radix sort, 11-bit digits over the low
// `bits` bits of the keys (the bits that can differ): order[0..n) lists the indices 0..n−1 by
// increasing key, equal keys in increasing index, the order std::stable_sort would give. Linear in
// n per digit; used to put points in cell order (PointGrid) and in a spatial order (the sphere
// packer's renumbering).
#include <growth/huge_pages.h>

#include <cstddef>
#include <cstdint>
#include <numeric>
#include <vector>

namespace growth {

template <class Order>
void stableRadixOrder(const std::uint64_t* key, std::size_t n, int bits, Order& order) {
  constexpr int kDigit = 11;
  constexpr std::uint64_t kDigitMask = (std::uint64_t(1) << kDigit) - 1;
  order.resize(n);
  std::iota(order.begin(), order.end(), typename Order::value_type(0));
  if (bits <= 0) return;
  Order tmp;
  assignHuge(tmp, n, typename Order::value_type(0));
  std::vector<std::uint32_t> count(std::size_t(1) << kDigit);
  for (int shift = 0; shift < bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0u);
    for (const auto j : order) ++count[std::size_t((key[j] >> shift) & kDigitMask)];
    std::uint32_t at = 0;
    for (auto& c : count) {
      const std::uint32_t k = c;
      c = at;
      at += k;
    }
    for (const auto j : order) tmp[count[std::size_t((key[j] >> shift) & kDigitMask)]++] = j;
    order.swap(tmp);
  }
}

} // namespace growth
