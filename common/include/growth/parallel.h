#pragma once
// Deterministic fork-join over an index range, for independent per-item work (per box, per point).
//
// [0, n) is cut into contiguous parts, one per thread; part 0 runs on the calling thread (the only
// one that may report progress or be cancelled through growth::Progress), the others on threads
// started for the call and joined before it returns. The caller writes each item's result to its
// own slot of a pre-sized array and combines per-part counters in part order afterwards, so the
// result never depends on the number of threads or on their scheduling.
// parallelChunks() hands out small chunks in order to whichever thread is free instead: a thread
// slowed down by other load on the machine then simply takes fewer of them.
#include <algorithm>
#include <atomic>
#include <cstddef>
#include <exception>
#include <thread>
#include <vector>

namespace growth {

// Threads used when a caller asks for 0 ("automatic"): the hardware's, at most kMaxThreads.
constexpr int kMaxThreads = 8;
inline int automaticThreads() {
  const unsigned hw = std::thread::hardware_concurrency();
  return hw == 0 ? 1 : static_cast<int>(std::min<unsigned>(hw, kMaxThreads));
}

// Number of parts parallelFor() uses for n items: `threads` (0 = automatic), fewer when a part
// would get less than minPerPart items (starting a thread costs tens of microseconds).
inline int parallelParts(size_t n, int threads, size_t minPerPart) {
  if (threads <= 0) threads = automaticThreads();
  const size_t byWork = minPerPart > 0 ? n / minPerPart : n;
  return static_cast<int>(std::max<size_t>(1, std::min<size_t>(size_t(threads), byWork)));
}

// First item of part k of `parts` over [0, n) (part k is [partBegin(k), partBegin(k + 1))).
inline size_t partBegin(size_t n, int parts, int k) { return n * size_t(k) / size_t(parts); }

// Calls f(begin, end, part) for every part of [0, n) (see parallelParts), part 0 on this thread.
// An exception of any part is rethrown here after all parts have ended (the first in part order).
template <class F>
void parallelFor(size_t n, int parts, F&& f) {
  if (parts <= 1 || n < 2) {
    f(size_t(0), n, 0);
    return;
  }
  std::vector<std::exception_ptr> errors(static_cast<size_t>(parts));
  auto run = [&](int k) {
    try {
      f(partBegin(n, parts, k), partBegin(n, parts, k + 1), k);
    } catch (...) {
      errors[size_t(k)] = std::current_exception();
    }
  };
  std::vector<std::thread> workers;
  workers.reserve(size_t(parts - 1));
  int started = 1;
  for (; started < parts; ++started) {
    try {
      workers.emplace_back(run, started);
    } catch (...) {
      break; // no thread available: the remaining parts run here
    }
  }
  run(0);
  for (int k = started; k < parts; ++k) run(k);
  for (auto& t : workers) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

// Calls f(begin, end, worker) for the chunks [k·chunk, (k + 1)·chunk) ∩ [0, n), handed out in
// order to `workers` threads as they become free; worker 0 is the calling thread (the only one
// that may report progress). Which worker runs which chunk depends on scheduling, so f must write
// per-item results to their own slots and keep per-worker state only for things whose total does
// not depend on the split (scratch buffers, integer counts). An exception stops the handing out;
// the first one (in worker order) is rethrown here after all workers have ended.
template <class F>
void parallelChunks(size_t n, int workers, size_t chunk, F&& f) {
  chunk = std::max<size_t>(chunk, 1);
  if (workers <= 1 || n <= chunk) {
    for (size_t b = 0; b < n; b += chunk) f(b, std::min(n, b + chunk), 0);
    return;
  }
  std::atomic<size_t> next{0};
  std::atomic<bool> failed{false};
  std::vector<std::exception_ptr> errors(static_cast<size_t>(workers));
  auto run = [&](int w) {
    try {
      while (!failed.load(std::memory_order_relaxed)) {
        const size_t b = next.fetch_add(1, std::memory_order_relaxed) * chunk;
        if (b >= n) break;
        f(b, std::min(n, b + chunk), w);
      }
    } catch (...) {
      errors[size_t(w)] = std::current_exception();
      failed = true;
    }
  };
  std::vector<std::thread> threads;
  threads.reserve(size_t(workers - 1));
  for (int w = 1; w < workers; ++w) {
    try {
      threads.emplace_back(run, w);
    } catch (...) {
      break; // no thread available: fewer workers
    }
  }
  run(0);
  for (auto& t : threads) t.join();
  for (const auto& e : errors)
    if (e) std::rethrow_exception(e);
}

} // namespace growth
