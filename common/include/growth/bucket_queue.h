#pragma once
// A bucketed priority queue: a fixed number of priority levels, each a strict FIFO.
//
// Both papers rank their work items on a small, finite set of levels (sphere packing, sec. 4.4:
// "each of these priorities is handled via its own queue that follows a strict first-in-first-out
// strategy"; Robust G2S, sec. 4.1: discrete priority index PI). Level 0 is the most urgent.
// push and pop are O(1) amortised; ties inside a level are broken first-in-first-out, which is the
// breadth-first tie-breaking both papers ask for.
#include <cassert>
#include <cstddef>
#include <memory>
#include <vector>

namespace growth {

// Alloc: the allocator of each level's storage (e.g. growth::HugeAllocator for large queues).
template <class T, class Alloc = std::allocator<T>>
class BucketQueue {
public:
  explicit BucketQueue(int levels = 1) : fifos_(static_cast<size_t>(levels)) { assert(levels > 0); }

  int levels() const { return static_cast<int>(fifos_.size()); }
  size_t size() const { return size_; }
  bool empty() const { return size_ == 0; }

  void push(int level, const T& item) {
    assert(level >= 0 && level < levels());
    fifos_[static_cast<size_t>(level)].push(item);
    if (level < best_) best_ = level;
    ++size_;
  }

  // The most urgent non-empty level; levels() when empty.
  int topLevel() {
    while (best_ < levels() && fifos_[static_cast<size_t>(best_)].empty()) ++best_;
    return best_;
  }

  // Removes and returns the oldest item of the most urgent non-empty level.
  T pop(int* level = nullptr) {
    const int l = topLevel();
    assert(l < levels());
    if (level != nullptr) *level = l;
    --size_;
    return fifos_[static_cast<size_t>(l)].pop();
  }

  // Bytes allocated for the items (capacity: what the queue held at its largest since the last release()).
  size_t memoryBytes() const {
    size_t b = fifos_.capacity() * sizeof(Fifo);
    for (const auto& f : fifos_) b += f.items.capacity() * sizeof(T);
    return b;
  }
  // Empties the queue and frees its storage.
  void release() {
    for (auto& f : fifos_) {
      f.clear();
      std::vector<T, Alloc>().swap(f.items);
    }
    size_ = 0;
    best_ = levels();
  }

  void clear() {
    for (auto& f : fifos_) f.clear();
    size_ = 0;
    best_ = levels();
  }

private:
  // A FIFO on a vector with a moving head; the consumed prefix is dropped once it dominates.
  struct Fifo {
    std::vector<T, Alloc> items;
    size_t head = 0;
    bool empty() const { return head == items.size(); }
    void push(const T& t) { items.push_back(t); }
    T pop() {
      T t = items[head++];
      if (head == items.size()) {
        items.clear();
        head = 0;
      } else if (head >= 4096 && head * 2 >= items.size()) {
        items.erase(items.begin(), items.begin() + static_cast<std::ptrdiff_t>(head));
        head = 0;
      }
      return t;
    }
    void clear() {
      items.clear();
      head = 0;
    }
  };

  std::vector<Fifo> fifos_;
  size_t size_ = 0;
  int best_ = 0;
};

} // namespace growth
