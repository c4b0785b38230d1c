// Deterministic fork-join (growth/parallel.h): every item in exactly one part, parts contiguous
// and in order, part 0 on the calling thread, exceptions carried back to the caller.
#include <growth/parallel.h>

#include <gtest/gtest.h>

#include <atomic>
#include <chrono>
#include <stdexcept>
#include <thread>
#include <vector>

TEST(Parallel, PartsFollowTheWorkAndTheThreadCount) {
  EXPECT_EQ(growth::parallelParts(100000, 2, 1000), 2);
  EXPECT_EQ(growth::parallelParts(1500, 2, 1000), 1); // a part would get less than 1000
  EXPECT_EQ(growth::parallelParts(0, 4, 10), 1);
  EXPECT_EQ(growth::parallelParts(100, 1, 1), 1);
  EXPECT_EQ(growth::parallelParts(100, 3, 0), 3);
  EXPECT_GE(growth::automaticThreads(), 1);
  EXPECT_LE(growth::automaticThreads(), growth::kMaxThreads);
  EXPECT_EQ(growth::parallelParts(1000000, 0, 1), growth::automaticThreads());
}

TEST(Parallel, EveryItemInExactlyOnePartInOrder) {
  for (size_t n : {0u, 1u, 2u, 7u, 1000u})
    for (int parts : {1, 2, 3, 5}) {
      std::vector<int> owner(n, -1);
      std::vector<size_t> begin(size_t(parts), 0), end(size_t(parts), 0);
      std::vector<std::thread::id> who(static_cast<size_t>(parts));
      growth::parallelFor(n, parts, [&](size_t b, size_t e, int part) {
        begin[size_t(part)] = b;
        end[size_t(part)] = e;
        who[size_t(part)] = std::this_thread::get_id();
        for (size_t i = b; i < e; ++i) owner[i] = part;
      });
      for (size_t i = 0; i < n; ++i) ASSERT_GE(owner[i], 0) << "n " << n << " parts " << parts;
      for (size_t i = 1; i < n; ++i) EXPECT_LE(owner[i - 1], owner[i]); // contiguous, in part order
      EXPECT_EQ(who[0], std::this_thread::get_id());                    // part 0 runs here
      if (n >= 2)
        for (int k = 0; k < parts; ++k) {
          EXPECT_EQ(begin[size_t(k)], growth::partBegin(n, parts, k));
          EXPECT_EQ(end[size_t(k)], growth::partBegin(n, parts, k + 1));
        }
    }
}

TEST(Parallel, AnExceptionOfAnyPartReachesTheCallerAfterAllParts) {
  std::atomic<int> finished{0};
  EXPECT_THROW(growth::parallelFor(100, 3,
                                   [&](size_t, size_t, int part) {
                                     if (part == 2) throw std::runtime_error("part 2");
                                     ++finished;
                                   }),
               std::runtime_error);
  EXPECT_EQ(finished.load(), 2); // parts 0 and 1 ran to their end before the rethrow
  EXPECT_THROW(growth::parallelFor(100, 2, [&](size_t, size_t, int part) {
                 if (part == 0) throw std::logic_error("part 0");
               }),
               std::logic_error);
}

TEST(Parallel, ChunksCoverEveryItemOnceWorkerZeroHere) {
  for (size_t n : {0u, 1u, 5u, 1000u, 4097u})
    for (int workers : {1, 2, 3}) {
      std::vector<std::atomic<int>> seen(n);
      for (auto& s : seen) s = 0;
      std::atomic<int> chunksHere{0};
      const std::thread::id self = std::this_thread::get_id();
      growth::parallelChunks(n, workers, 64, [&](size_t b, size_t e, int worker) {
        EXPECT_LE(e - b, 64u);
        EXPECT_EQ(b % 64, 0u);
        if (worker == 0) {
          EXPECT_EQ(std::this_thread::get_id(), self);
          ++chunksHere;
        }
        for (size_t i = b; i < e; ++i) ++seen[i];
      });
      for (size_t i = 0; i < n; ++i) ASSERT_EQ(seen[i].load(), 1) << n << " " << workers;
    }
}

TEST(Parallel, AnExceptionInAChunkStopsTheOthersAndReachesTheCaller) {
  // Each chunk takes at least 50 µs, so the other worker cannot run through the remaining chunks
  // (10,000 of them: about 0.25 s at least) in the time the exception takes to unwind, even on a
  // loaded machine; with the chunks instantaneous, as before, it sometimes could.
  std::atomic<int> chunks{0};
  EXPECT_THROW(growth::parallelChunks(100000, 2, 10,
                                      [&](size_t b, size_t, int) {
                                        ++chunks;
                                        std::this_thread::sleep_for(std::chrono::microseconds(50));
                                        if (b == 500) throw std::runtime_error("chunk 50");
                                      }),
               std::runtime_error);
  EXPECT_LT(chunks.load(), 5000); // handing out stopped soon after the failure
}
