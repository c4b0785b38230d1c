#include <growth/huge_pages.h>

#include <gtest/gtest.h>

#include <cstdint>
#include <numeric>
#include <string>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif

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

#if defined(__linux__)
// prefault makes every whole page of the range resident before it is written (one madvise call
// instead of a fault per page), leaves the contents as they were (zeros in a fresh mapping) and
// touches nothing outside the range's whole pages.
TEST(HugePages, PrefaultMakesTheWholePagesOfTheRangeResident) {
  const size_t page = size_t(sysconf(_SC_PAGESIZE)), pages = 64;
  void* raw = mmap(nullptr, pages * page, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
  ASSERT_NE(raw, MAP_FAILED);
  auto* bytes = static_cast<unsigned char*>(raw);
  auto resident = [&]() {
    std::vector<unsigned char> vec(pages);
    EXPECT_EQ(mincore(raw, pages * page, vec.data()), 0);
    std::string r;
    for (unsigned char c : vec) r += (c & 1) ? '1' : '0';
    return r;
  };
  ASSERT_EQ(resident(), std::string(pages, '0'));
  // From the middle of page 8 to the middle of page 56: pages 9..55 are whole.
  if (!growth::prefault(bytes + 8 * page + page / 2, 48 * page)) {
    munmap(raw, pages * page);
    GTEST_SKIP() << "MADV_POPULATE_WRITE is not available (Linux < 5.14): prefault is a no-op here";
  }
  EXPECT_EQ(resident(), std::string(9, '0') + std::string(47, '1') + std::string(8, '0'));
  // Too small a range to be worth a call: nothing happens.
  EXPECT_FALSE(growth::prefault(bytes, growth::kPrefaultMinBytes - 1));
  EXPECT_EQ(resident(), std::string(9, '0') + std::string(47, '1') + std::string(8, '0'));
  for (size_t i = 9 * page; i < 56 * page; i += 997) EXPECT_EQ(bytes[i], 0u);
  munmap(raw, pages * page);
}

// reserveHuge with populate keeps the vector's contract: size and contents unchanged, room for n.
TEST(HugePages, ReserveHugePopulatedKeepsTheContents) {
  std::vector<std::uint32_t> v{7, 8, 9};
  growth::reserveHuge(v, 1 << 20, /*populate=*/true);
  EXPECT_EQ(v, (std::vector<std::uint32_t>{7, 8, 9}));
  EXPECT_GE(v.capacity(), size_t(1) << 20);
  growth::HugeVector<std::uint64_t> h(size_t(1) << 19, 5); // allocated populated (4 MiB)
  EXPECT_EQ(std::accumulate(h.begin(), h.end(), std::uint64_t(0)), std::uint64_t(5) << 19);
}
#endif
