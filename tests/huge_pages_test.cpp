#include <growth/huge_pages.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

// The advice is only a hint: whatever the kernel does, contents and sizes must be as asked.
TEST(HugePages, AssignAndReserveKeepTheVectorContract) {
  std::vector<std::uint32_t> v{1, 2, 3};
  growth::assignHuge(v, size_t(3) << 20, 7u); // 12 MiB: large enough to be advised
  ASSERT_EQ(v.size(), size_t(3) << 20);
  EXPECT_EQ(v.front(), 7u);
  EXPECT_EQ(v.back(), 7u);
  EXPECT_EQ(std::accumulate(v.begin(), v.end(), std::uint64_t(0)), std::uint64_t(7) * (size_t(3) << 20));

  std::vector<double> w{1.5, 2.5};
  growth::reserveHuge(w, size_t(1) << 20);
  EXPECT_GE(w.capacity(), size_t(1) << 20);
  ASSERT_EQ(w.size(), 2u); // existing elements kept
  EXPECT_EQ(w[1], 2.5);

  std::vector<char> small;
  growth::assignHuge(small, 10, 'x'); // below the threshold: plain assign
  EXPECT_EQ(std::string(small.begin(), small.end()), "xxxxxxxxxx");
  growth::adviseHugePages(nullptr, 1 << 30); // ignored
}

TEST(HugePages, HugeVectorBehavesLikeAVectorAndAlignsLargeBlocks) {
  growth::HugeVector<std::uint32_t> v(size_t(1) << 20, 5u); // 4 MiB: mapped on its own
#if defined(__linux__)
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % growth::kHugePageBytes, 0u);
#endif
  EXPECT_EQ(std::accumulate(v.begin(), v.end(), std::uint64_t(0)), std::uint64_t(5) << 20);
  v.resize(v.size() * 3, 1u); // reallocation keeps the contents
  EXPECT_EQ(v[0], 5u);
  EXPECT_EQ(v.back(), 1u);
  growth::HugeVector<std::uint32_t> copy(v);
  EXPECT_TRUE(copy == v);
  growth::HugeVector<char> small(3, 'y'); // below the threshold: plain malloc
  EXPECT_EQ(std::string(small.begin(), small.end()), "yyy");
  growth::HugeVector<double> empty;
  empty.reserve(0);
  EXPECT_TRUE(empty.empty());
}

// discardPages frees the whole pages inside the range and nothing outside it.
TEST(HugePages, DiscardPagesFreesOnlyWholePagesInsideTheRange) {
  std::vector<std::uint32_t> v(size_t(1) << 20); // 4 MiB
  std::iota(v.begin(), v.end(), 1u);
  const size_t half = v.size() / 2 + 123;          // not on a page boundary
  growth::discardPages(v.data(), half * sizeof(std::uint32_t));
  // Everything after the range is kept.
  for (size_t i = half; i < v.size(); ++i) ASSERT_EQ(v[i], std::uint32_t(i + 1)) << i;
#if defined(__linux__)
  // Inside, the whole pages now read as zeros (private anonymous memory given back); the partial
  // page at the start is kept.
  const std::uintptr_t page = std::uintptr_t(sysconf(_SC_PAGESIZE));
  const std::uintptr_t base = reinterpret_cast<std::uintptr_t>(v.data());
  const size_t firstWhole = ((base + page - 1) / page * page - base) / sizeof(std::uint32_t);
  const size_t endWhole = ((base + half * sizeof(std::uint32_t)) / page * page - base) / sizeof(std::uint32_t);
  ASSERT_LT(firstWhole, endWhole);
  for (size_t i = firstWhole; i < endWhole; ++i) ASSERT_EQ(v[i], 0u) << i;
  for (size_t i = 0; i < firstWhole; ++i) ASSERT_EQ(v[i], std::uint32_t(i + 1)) << i;
  for (size_t i = endWhole; i < half; ++i) ASSERT_EQ(v[i], std::uint32_t(i + 1)) << i;
#endif
  growth::discardPages(nullptr, 1 << 20); // ignored
  growth::discardPages(v.data(), 100);    // no whole page: nothing happens
  EXPECT_EQ(v.back(), std::uint32_t(v.size()));
}
