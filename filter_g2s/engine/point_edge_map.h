#pragma once
// The point–edge map (PEM) of Robust G2S, sec. 3.2 step 4.3: for every point, the edges incident
// to it and the directions in which triangles traverse them.
//
// A consistently oriented 2-manifold traverses every directed edge (half-edge) at most once: an
// edge with one triangle is traversed one way, an edge with two triangles once each way. So the
// paper's two topological rules for a new triangle — "an edge that already pertains to another
// triangle must be traversed with consistent orientation" and (implicitly) "no edge gets a third
// triangle" — are together exactly "none of the new triangle's three half-edges is used yet"
// (canAddTriangle). Boundary (free) edges are the edges used in one direction only.
//
// Storage is compact and flat: each point owns an inline block of kInline 32-bit entries (the
// neighbour's index plus two direction bits and one marker bit); a point with more neighbours
// chains further blocks from a shared pool. Valences of interpolating meshes are about 6, so
// almost every lookup is a scan of one cache line. No std::map/std::set, no per-point allocation.
//
// A point holds at most capacity() (kMaxEntries unless set) entries (one per neighbour it ever had an edge with). The pole
// of a sphere sampled on a latitude–longitude grid has one per longitude, hundreds; lookups at a
// point scan its entries, so the cap also bounds the work a single point can cost. A caller asks
// hasRoom() before adding a triangle with new edges (canAddTriangle includes it) and leaves the
// edge open where a point is full: the mesh degrades there, locally, instead of failing.
#include <growth/huge_pages.h>

#include <cassert>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace growth {

class PointEdgeMap {
public:
  // Largest number of points (indices use 29 bits of an entry).
  static constexpr std::uint32_t kMaxPoints = (1u << 29) - 1;
  // Largest number of entries (neighbours) of one point: the default capacity, and the most
  // setCapacity() allows (counts are 16-bit).
  static constexpr std::uint32_t kMaxEntries = 4096;

  PointEdgeMap() = default;
  explicit PointEdgeMap(size_t points) { reset(points); }

  void reset(size_t points) {
    if (points > kMaxPoints) throw std::length_error("PointEdgeMap: too many points");
    assignHuge(slot_, points * kInline, 0u);
    assignHuge(count_, points, std::uint16_t(0));
    pool_.clear();
  }

  size_t pointCount() const { return count_.size(); }

  // Entries one point may hold, in [2, kMaxEntries] (kMaxEntries unless set): a smaller capacity
  // lets tests reach the degraded case with small clouds.
  void setCapacity(std::uint32_t maxEntries) {
    if (maxEntries < 2 || maxEntries > kMaxEntries) throw std::invalid_argument("PointEdgeMap: capacity out of range");
    capacity_ = maxEntries;
  }
  std::uint32_t capacity() const { return capacity_; }

  // Frees all storage (the map is then empty, for no points); reset() makes it usable again.
  void release() {
    HugeVector<std::uint32_t>().swap(slot_);
    HugeVector<std::uint16_t>().swap(count_);
    HugeVector<std::uint32_t>().swap(pool_);
  }

  // Half-edge a→b is traversed by a triangle.
#if defined(__GNUC__)
  __attribute__((always_inline)) // the mesher's most frequent test, see find()
#endif
  bool used(std::uint32_t a, std::uint32_t b) const {
    const std::uint32_t* e = find(a, b);
    return e != nullptr && (*e & kOut) != 0;
  }
  // Number of triangles on edge {a, b} (0, 1 or 2).
  int triangles(std::uint32_t a, std::uint32_t b) const {
    const std::uint32_t* e = find(a, b);
    return e == nullptr ? 0 : int((*e & kOut) != 0) + int((*e & kIn) != 0);
  }
  // Number of edges at v that carry at least one triangle.
  int degree(std::uint32_t v) const {
    int d = 0;
    forEachEntry(v, [&](std::uint32_t e) { d += (e & (kOut | kIn)) != 0; });
    return d;
  }
  // v is a vertex of no triangle.
  bool isolated(std::uint32_t v) const { return degree(v) == 0; }
  // v has an edge with exactly one triangle (it lies on a front or a boundary).
  bool hasFreeEdge(std::uint32_t v) const {
    bool f = false;
    forEachEntry(v, [&](std::uint32_t e) { f = f || ((e & kOut) != 0) != ((e & kIn) != 0); });
    return f;
  }
  // v is a vertex of some triangle and all its edges have two triangles: its fan is closed (or
  // all its fans are), so a new triangle at v would make it non-manifold.
  bool closed(std::uint32_t v) const { return !isolated(v) && !hasFreeEdge(v); }

  // None of the half-edges a→b, b→c, c→a is used: adding the triangle keeps every edge at two
  // triangles at most, traversed once in each direction; and its new edges find room.
  bool canAddTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    return a != b && b != c && c != a && !used(a, b) && !used(b, c) && !used(c, a) && hasRoom(a, b, c);
  }

  // Entries (neighbours, with or without triangles now) of v.
  std::uint32_t entries(std::uint32_t v) const { return count_[v]; }
  // v and w have an entry for each other (they share or shared an edge).
  bool hasEntry(std::uint32_t v, std::uint32_t w) const { return find(v, w) != nullptr; }
  // Every point of triangle (a, b, c) has room for the entries its edges would add.
  bool hasRoom(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    // Almost always far from full: three loads decide.
    const std::uint32_t cap = capacity_;
    if (count_[a] + 2u <= cap && count_[b] + 2u <= cap && count_[c] + 2u <= cap) return true;
    return hasRoomNearFull(a, b, c);
  }

  // Records triangle (a, b, c). Returns a bit mask of its edges that were new (had no triangle):
  // bit 0 for {a,b}, bit 1 for {b,c}, bit 2 for {c,a}. Precondition: canAddTriangle(a, b, c)
  // (std::length_error, with the map unchanged, when a point has no room).
  unsigned addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    // Checked before anything changes, so a refused triangle leaves the map as it was.
    if (!hasRoom(a, b, c)) throw std::length_error("PointEdgeMap: a triangle was added at a point with no room left");
    assert(canAddTriangle(a, b, c));
    unsigned fresh = 0;
    fresh |= addHalfEdge(a, b) ? 1u : 0u;
    fresh |= addHalfEdge(b, c) ? 2u : 0u;
    fresh |= addHalfEdge(c, a) ? 4u : 0u;
    return fresh;
  }

  // Forgets triangle (a, b, c) (its three half-edges must be used).
  void removeTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
    removeHalfEdge(a, b);
    removeHalfEdge(b, c);
    removeHalfEdge(c, a);
  }

  // Reverses every half-edge at v: v→w is used afterwards exactly when w→v was. Applied at every
  // vertex of a set of triangles that are all flipped (a whole connected component: every edge at
  // its vertices is one of its own), it records the flip in one pass over their entries, where
  // removing and adding each triangle again would look up six entries per triangle.
  void reverseAt(std::uint32_t v) {
    visitEntries(*this, v, [](std::uint32_t& e) {
      const std::uint32_t out = e & kOut, in = e & kIn;
      e = (e & ~(kOut | kIn)) | (out != 0 ? kIn : 0u) | (in != 0 ? kOut : 0u);
    });
  }

  // Calls f(w, outUsed, inUsed) for every edge {v, w} carrying a triangle: outUsed when v→w is
  // traversed, inUsed when w→v is.
  template <class F>
  void forEachEdge(std::uint32_t v, F&& f) const {
    forEachEntry(v, [&](std::uint32_t e) {
      if ((e & (kOut | kIn)) != 0) f(e & kIndex, (e & kOut) != 0, (e & kIn) != 0);
    });
  }

  // Calls f(w) for every w with v→w traversed and w→v not (the free edges that leave v), in the
  // order forEachEdge gives them, until f returns true; returns whether it did. (The mesher's ear
  // test at every search: the inline block's entries are picked by one vector compare.)
  template <class F>
  bool anyOutOnly(std::uint32_t v, F&& f) const {
    const std::uint32_t n = count_[v];
#if defined(__SSE2__)
    if (n <= kInline) {
      const std::uint32_t* blk = &slot_[size_t(v) * kInline];
      const __m128i bits = _mm_set1_epi32(static_cast<int>(kOut | kIn));
      const __m128i want = _mm_set1_epi32(static_cast<int>(kOut));
      const __m128i lo = _mm_cmpeq_epi32(_mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(blk)), bits), want);
      const __m128i hi =
          _mm_cmpeq_epi32(_mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(blk + 4)), bits), want);
      unsigned match = (unsigned(_mm_movemask_ps(_mm_castsi128_ps(lo))) |
                        unsigned(_mm_movemask_ps(_mm_castsi128_ps(hi))) << 4) &
                       ((1u << n) - 1u);
      for (; match != 0; match &= match - 1)
        if (f(blk[__builtin_ctz(match)] & kIndex)) return true;
      return false;
    }
#endif
    bool done = false;
    forEachEntry(v, [&](std::uint32_t e) {
      if (!done && (e & (kOut | kIn)) == kOut) done = f(e & kIndex);
    });
    return done;
  }

  // A marker bit per half-edge entry v→w (for walks such as boundary-loop tracing).
  bool marked(std::uint32_t v, std::uint32_t w) const {
    const std::uint32_t* e = find(v, w);
    return e != nullptr && (*e & kMark) != 0;
  }
  void setMark(std::uint32_t v, std::uint32_t w, bool on) {
    std::uint32_t* e = find(v, w);
    if (e != nullptr) *e = on ? (*e | kMark) : (*e & ~kMark);
  }

  void clearMarks() {
    for (std::uint32_t& e : slot_) e &= ~kMark;
    for (std::uint32_t& e : pool_) e &= ~kMark;
  }

  size_t memoryBytes() const {
    return slot_.capacity() * sizeof(std::uint32_t) + count_.capacity() * sizeof(std::uint16_t) +
           pool_.capacity() * sizeof(std::uint32_t);
  }

private:
  static constexpr std::uint32_t kInline = 8;          // entries per block (one is the link when chained)
  static constexpr std::uint32_t kIndex = (1u << 29) - 1;
  static constexpr std::uint32_t kMark = 1u << 29;
  static constexpr std::uint32_t kOut = 1u << 30;       // v→w used
  static constexpr std::uint32_t kIn = 1u << 31;        // w→v used

  // Entries of v: count_[v] of them. With count <= kInline all are inline; otherwise the inline
  // block holds kInline-1 entries and its last slot the index of the next block in pool_, which
  // holds kInline-1 entries and a link again (the last block may be partly filled).
  template <class F>
  void forEachEntry(std::uint32_t v, F&& f) const {
    visitEntries(*this, v, [&](const std::uint32_t& e) { f(e); });
  }
  // The same walk for a const map (entries read) or not (entries may be written): Self is
  // PointEdgeMap or const PointEdgeMap.
  template <class Self, class F>
  static void visitEntries(Self& self, std::uint32_t v, F&& f) {
    const std::uint32_t n = self.count_[v];
    auto* blk = &self.slot_[size_t(v) * kInline];
    if (n <= kInline) {
      for (std::uint32_t i = 0; i < n; ++i) f(blk[i]);
      return;
    }
    std::uint32_t left = n;
    for (;;) {
      const std::uint32_t here = left <= kInline ? left : kInline - 1;
      for (std::uint32_t i = 0; i < here; ++i) f(blk[i]);
      left -= here;
      if (left == 0) return;
      blk = &self.pool_[blk[kInline - 1]];
    }
  }

  // hasRoom where a point may be full: counts the entries the triangle would add. Kept out of
  // line so that the hot callers (addTriangle, the mesher's tests) stay small.
#if defined(__GNUC__)
  __attribute__((noinline, cold))
#endif
  bool hasRoomNearFull(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
    const std::uint32_t cap = capacity_;
    const unsigned ab = !hasEntry(a, b), bc = !hasEntry(b, c), ca = !hasEntry(c, a);
    return count_[a] + ab + ca <= cap && count_[b] + ab + bc <= cap && count_[c] + bc + ca <= cap;
  }

  std::uint32_t* find(std::uint32_t v, std::uint32_t w) {
    return const_cast<std::uint32_t*>(static_cast<const PointEdgeMap*>(this)->find(v, w));
  }
  // Inlined into the hot callers (used(), addTriangle) even where they grew past the compiler's
  // limits: it is most of their work, usually a scan of one cache line.
#if defined(__GNUC__)
  __attribute__((always_inline))
#endif
  const std::uint32_t* find(std::uint32_t v, std::uint32_t w) const {
    std::uint32_t n = count_[v];
    const std::uint32_t* blk = &slot_[size_t(v) * kInline];
#if defined(__SSE2__)
    // All entries inline (almost always): the block's eight entries compared at once, instead of
    // a loop whose exit depends on where w is (a mispredicted branch per lookup). Entries past
    // count_[v] are masked off; w occurs at most once.
    if (n <= kInline) {
      static_assert(kInline == 8, "two 4-lane compares per block");
      const __m128i key = _mm_set1_epi32(static_cast<int>(w));
      const __m128i index = _mm_set1_epi32(static_cast<int>(kIndex));
      const __m128i lo = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(blk)), index);
      const __m128i hi = _mm_and_si128(_mm_loadu_si128(reinterpret_cast<const __m128i*>(blk + 4)), index);
      const unsigned match = (unsigned(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(lo, key)))) |
                              unsigned(_mm_movemask_ps(_mm_castsi128_ps(_mm_cmpeq_epi32(hi, key)))) << 4) &
                             ((1u << n) - 1u);
      return match != 0 ? blk + __builtin_ctz(match) : nullptr;
    }
#endif
    for (;;) {
      const std::uint32_t here = n <= kInline ? n : kInline - 1;
      for (std::uint32_t i = 0; i < here; ++i)
        if ((blk[i] & kIndex) == w) return &blk[i];
      n -= here;
      if (n == 0) return nullptr;
      blk = &pool_[blk[kInline - 1]];
    }
  }

  // Appends an entry for w at v (no check for an existing one).
  std::uint32_t* append(std::uint32_t v, std::uint32_t w) {
    const std::uint32_t n = count_[v];
    assert(n < capacity_); // addTriangle checked hasRoom()
    // Find the last block and how many entries it holds (at most kInline).
    bool inPool = false;
    size_t base = size_t(v) * kInline;
    std::uint32_t rem = n;
    while (rem > kInline) {
      rem -= kInline - 1;
      base = (inPool ? pool_[base + kInline - 1] : slot_[base + kInline - 1]);
      inPool = true;
    }
    ++count_[v];
    if (rem < kInline) {
      std::uint32_t* e = inPool ? &pool_[base + rem] : &slot_[base + rem];
      *e = w;
      return e;
    }
    // The last block is full: chain a new block, moving the block's last entry there.
    const std::uint32_t nb = static_cast<std::uint32_t>(pool_.size());
    pool_.resize(pool_.size() + kInline, 0);
    std::uint32_t& link = inPool ? pool_[base + kInline - 1] : slot_[base + kInline - 1];
    pool_[nb] = link;
    link = nb;
    pool_[nb + 1] = w;
    return &pool_[nb + 1];
  }

  // Marks v→w used; returns true when the edge {v, w} had no triangle before.
  bool addHalfEdge(std::uint32_t v, std::uint32_t w) {
    std::uint32_t* ev = find(v, w);
    bool fresh = false;
    if (ev == nullptr) {
      ev = append(v, w);
      fresh = true;
    } else {
      fresh = (*ev & (kOut | kIn)) == 0;
    }
    *ev |= kOut;
    std::uint32_t* ew = find(w, v);
    if (ew == nullptr) ew = append(w, v);
    *ew |= kIn;
    return fresh;
  }

  void removeHalfEdge(std::uint32_t v, std::uint32_t w) {
    std::uint32_t* ev = find(v, w);
    if (ev != nullptr) *ev &= ~kOut;
    std::uint32_t* ew = find(w, v);
    if (ew != nullptr) *ew &= ~kIn;
  }

  HugeVector<std::uint32_t> slot_;    // kInline per point
  HugeVector<std::uint16_t> count_;   // entries per point
  HugeVector<std::uint32_t> pool_;    // overflow blocks of kInline
  std::uint32_t capacity_ = kMaxEntries;
};

} // namespace growth
