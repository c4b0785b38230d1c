#pragma once
// Large arrays that are written once from end to end (point coordinates, edge maps, triangle
// lists, the output mesh's vectors) pay one page fault per 4 KiB page on first touch, which on a
// virtual machine can be a large part of a run (tools/fault_cost.cpp measures a fault's cost).
// Transparent huge pages cut the number of faults by 512; prefault (below) makes a range resident
// in one call, huge pages or not.
//
// adviseHugePages asks Linux (madvise MADV_HUGEPAGE) to back the 2 MiB-aligned part of a range
// with huge pages; it must be called before the range is first written. Elsewhere, or when the
// kernel declines, it does nothing: it is a hint, never a requirement.
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <new>
#include <vector>

#if defined(__linux__)
#include <sys/mman.h>
#include <unistd.h>
#endif
#if defined(__GLIBC__)
#include <malloc.h>
#endif

namespace growth {

constexpr size_t kHugePageBytes = size_t(2) << 20;

inline void adviseHugePages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
  if (data == nullptr || bytes < kHugePageBytes) return; // smaller than one huge page
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(kHugePageBytes - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_HUGEPAGE);
#else
  (void)data;
  (void)bytes;
#endif
}

// Gives the heap's free pages back to the system. glibc keeps the memory of freed blocks that
// were not mapped on their own (its mmap threshold grows to the largest block freed, up to
// 32 MiB, so a working state's arrays often come from the heap): after a large working state is
// freed, a few megabytes of it stay resident and add to the next phase's peak. Costs a walk over
// the heap's free blocks; elsewhere it does nothing.
inline void releaseFreeHeap() {
#if defined(__GLIBC__)
  malloc_trim(0);
#endif
}

// Gives the whole pages inside [data, data + bytes) back to the system (madvise MADV_DONTNEED),
// for an array read once from front to back while what replaces it is built: the part already
// read stops taking memory. Those pages read as zeros afterwards: the caller must not read them
// again, only free the array. The partial pages at both ends are kept. Elsewhere it does nothing.
inline void discardPages(const void* data, size_t bytes) {
#if defined(__linux__) && defined(MADV_DONTNEED)
  static const size_t page = size_t(sysconf(_SC_PAGESIZE));
  if (data == nullptr || page == 0) return;
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(page - 1);
  if (end > begin) madvise(reinterpret_cast<void*>(begin), end - begin, MADV_DONTNEED);
#else
  (void)data;
  (void)bytes;
#endif
}

// Makes the pages of [data, data + bytes) resident at once (madvise MADV_POPULATE_WRITE, Linux
// 5.14 and later), for memory about to be written from end to end. Faulting pages in one at a
// time costs a trap per 4 KiB page; populating the range in one call costs a fraction of that
// (tools/fault_cost.cpp measures both). Below kPrefaultMinBytes the call costs more than it saves.
// Elsewhere, or on older kernels (EINVAL), it does nothing: pages then fault in as they are written.
// Returns whether the whole pages of the range were made resident.
constexpr size_t kPrefaultMinBytes = size_t(32) << 10;

inline bool prefault(void* data, size_t bytes) { // (not const: it writes the pages)
#if defined(__linux__)
#ifndef MADV_POPULATE_WRITE
#define GROWTH_MADV_POPULATE_WRITE 23 // <linux/mman.h>; older C libraries lack the name
#else
#define GROWTH_MADV_POPULATE_WRITE MADV_POPULATE_WRITE
#endif
  static const size_t page = size_t(sysconf(_SC_PAGESIZE));
  if (data == nullptr || bytes < kPrefaultMinBytes || page == 0) return false;
  // Whole pages only: the partial pages at both ends may be shared with other blocks.
  const std::uintptr_t begin = (reinterpret_cast<std::uintptr_t>(data) + page - 1) & ~(page - 1);
  const std::uintptr_t end = (reinterpret_cast<std::uintptr_t>(data) + bytes) & ~(page - 1);
  return end > begin && madvise(reinterpret_cast<void*>(begin), end - begin, GROWTH_MADV_POPULATE_WRITE) == 0;
#undef GROWTH_MADV_POPULATE_WRITE
#else
  (void)data;
  (void)bytes;
  return false;
#endif
}

// Makes room for n elements in v and advises huge pages for it; with `populate`, also makes the
// room for the n elements resident (prefault), for a v about to be filled with n elements. Only
// reserve() is used, so containers deriving from std::vector with state of their own (vcglib's
// vector_ocf, which reserves its optional components too) stay consistent.
template <class V>
void reserveHuge(V& v, size_t n, bool populate = false) {
  v.reserve(n);
  adviseHugePages(v.data(), v.capacity() * sizeof(typename V::value_type));
  if (populate && n > v.size())
    prefault(v.data() + v.size(), (n - v.size()) * sizeof(typename V::value_type));
}

// v = n copies of x, with huge pages advised and the pages made resident before the first write.
template <class T, class A>
void assignHuge(std::vector<T, A>& v, size_t n, const T& x) {
  if (v.capacity() < n) std::vector<T, A>().swap(v);
  reserveHuge(v, n, /*populate=*/true);
  v.assign(n, x);
}

// An allocator for large working arrays that are filled once: a block of kHugePageBytes or more
// is mapped on its own, starting on a 2 MiB boundary, and advised for huge pages as a whole; it
// is unmapped when freed, so nothing stays with the process. (A plain std::vector block starts
// 16 bytes into a page, so advising it leaves up to 2 MiB of its head to 4 KiB pages; here only
// the tail after the last whole 2 MiB page is.) The alignment costs address space only; the
// mapping is rounded up to a whole huge page only when that adds at most an eighth to the
// block. Smaller blocks come from malloc. Every block of kPrefaultMinBytes or more is made
// resident when it is allocated (prefault): these arrays are written soon after, whole (a queue
// level or an overflow pool growing by doubling touches at most twice what it holds).
template <class T>
struct HugeAllocator {
  using value_type = T;
  HugeAllocator() = default;
  template <class U>
  HugeAllocator(const HugeAllocator<U>&) noexcept {}

  // The mapping: whole 4 KiB pages, or whole 2 MiB pages when that adds at most an eighth (the
  // tail then gets a huge page too, for little memory).
  static size_t mappedBytes(size_t n) {
    const size_t bytes = n * sizeof(T);
    const size_t huge = (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
    return huge - bytes <= bytes / 8 ? huge : (bytes + 4095) & ~size_t(4095);
  }

  T* allocate(size_t n) {
    if (n > (size_t(-1) - kHugePageBytes) / sizeof(T)) throw std::bad_alloc();
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (n * sizeof(T) >= kHugePageBytes) {
      const size_t len = mappedBytes(n);
      void* raw = mmap(nullptr, len + kHugePageBytes, PROT_READ | PROT_WRITE, MAP_PRIVATE | MAP_ANONYMOUS, -1, 0);
      if (raw == MAP_FAILED) throw std::bad_alloc();
      const std::uintptr_t r = reinterpret_cast<std::uintptr_t>(raw);
      const std::uintptr_t a = (r + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
      if (a > r) munmap(raw, a - r);
      const std::uintptr_t end = r + len + kHugePageBytes;
      if (end > a + len) munmap(reinterpret_cast<void*>(a + len), end - (a + len));
      adviseHugePages(reinterpret_cast<void*>(a), len);
      prefault(reinterpret_cast<void*>(a), n * sizeof(T));
      return reinterpret_cast<T*>(a);
    }
#endif
    void* p = std::malloc(n == 0 ? 1 : n * sizeof(T));
    if (p == nullptr) throw std::bad_alloc();
    prefault(p, n * sizeof(T));
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t n) noexcept {
#if defined(__linux__) && defined(MADV_HUGEPAGE)
    if (n * sizeof(T) >= kHugePageBytes) {
      munmap(p, mappedBytes(n));
      return;
    }
#endif
    std::free(p);
  }

  template <class U>
  bool operator==(const HugeAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugeAllocator<U>&) const noexcept { return false; }
};

template <class T>
using HugeVector = std::vector<T, HugeAllocator<T>>;

} // namespace growth
