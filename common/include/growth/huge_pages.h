#pragma once
// Large arrays that are written once from end to end (point coordinates, edge maps, triangle
// lists, the output mesh's vectors) pay one page fault per 4 KiB page on first touch; on the
// virtual machines this project is measured on a fault costs about 16 µs, which for the 361k-point
// bunny adds up to a third of the run. Transparent huge pages cut the number of faults by 512.
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

// Makes room for n elements in v (without touching the new room) and advises huge pages for it.
// Only reserve() is used, so containers deriving from std::vector with state of their own
// (vcglib's vector_ocf, which reserves its optional components too) stay consistent.
template <class V>
void reserveHuge(V& v, size_t n) {
  v.reserve(n);
  adviseHugePages(v.data(), v.capacity() * sizeof(typename V::value_type));
}

// v = n copies of x, with huge pages advised before the first touch.
template <class T, class A>
void assignHuge(std::vector<T, A>& v, size_t n, const T& x) {
  if (v.capacity() < n) std::vector<T, A>().swap(v);
  reserveHuge(v, n);
  v.assign(n, x);
}

// An allocator for working arrays that are filled once: blocks of kHugeAllocMin bytes or more
// are 2 MiB-aligned, rounded up to whole 2 MiB pages and advised for huge pages as a whole. A
// plain std::vector block starts 16 bytes into a 4 KiB page, so advising it leaves its unaligned
// head and tail — up to 2 MiB at each end — to 4 KiB pages, and arrays under 4 MiB get no huge
// page at all; with this allocator a 1 MiB array costs one fault instead of 256. The rounding
// costs address space, not memory: pages never touched are never backed.
constexpr size_t kHugeAllocMin = size_t(256) << 10;

template <class T>
struct HugeAllocator {
  using value_type = T;
  HugeAllocator() = default;
  template <class U>
  HugeAllocator(const HugeAllocator<U>&) noexcept {}

  T* allocate(size_t n) {
    if (n > size_t(-1) / sizeof(T)) throw std::bad_alloc();
    const size_t bytes = n * sizeof(T);
    void* p = nullptr;
    if (bytes >= kHugeAllocMin) {
      const size_t rounded = (bytes + kHugePageBytes - 1) & ~(kHugePageBytes - 1);
#if defined(__linux__)
      if (posix_memalign(&p, kHugePageBytes, rounded) != 0) p = nullptr;
      if (p != nullptr) adviseHugePages(p, rounded);
#else
      p = std::malloc(bytes);
#endif
    } else {
      p = std::malloc(bytes == 0 ? 1 : bytes);
    }
    if (p == nullptr) throw std::bad_alloc();
    return static_cast<T*>(p);
  }
  void deallocate(T* p, size_t) noexcept { std::free(p); }

  template <class U>
  bool operator==(const HugeAllocator<U>&) const noexcept { return true; }
  template <class U>
  bool operator!=(const HugeAllocator<U>&) const noexcept { return false; }
};

template <class T>
using HugeVector = std::vector<T, HugeAllocator<T>>;

} // namespace growth
