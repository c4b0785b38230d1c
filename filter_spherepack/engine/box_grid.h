#pragma once
// Box grid of the sphere-packing mesher (Lipschütz et al., sec. 4.1).
//
// Space is partitioned into cubes ("boxes") of side d. Each box refers to the input points (and
// their splats) that are at most d away from it. Only occupied boxes are stored: an open-addressing
// hash from the box's integer coordinates to a box id, and the point lists in one CSR array, so
// memory grows with the cloud (about 21 references per point: the volume of a box grown by d is
// (1 + 6 + 3π + 4π/3)·d³), never with its bounding box (sec. 4.1 weighs the uniform grid against
// the hash; we take the hash for the memory bound).
//
// Per box, as in sec. 4.1:
//  1. normal filter: n̄ = Σ n_p over the box's points (not normalised); when |n̄| >= 0.1, the
//     points with <n_p, n̄> < 0 are dropped from the box;
//  2. box normal n_b = argmax over a fixed sampling S_F of the sphere of min_p <n_p, n>;
//  3. a box where "d is too large" for the cloud: its box normal has a negative scalar product
//     with the normals of points registered in it, before or after the filter (points the filter
//     dropped, when they are a real share of the box, or a best minimum below zero), so manifold
//     output is no longer guaranteed.
//     Such boxes are counted so that the caller can warn.
#include <growth/huge_pages.h>

#include <growth/vec3.h>

#include <cmath>
#include <cstddef>
#include <atomic>
#include <cstdint>
#include <memory>
#include <thread>
#include <utility>
#include <vector>

namespace growth {

// Growable open-addressing hash from a 64-bit key to a non-negative int value. Lookups never
// allocate; iteration order is never used (determinism comes from the values, assigned in
// insertion order by the callers).
class KeyHash {
public:
  using Key = std::uint64_t;
  explicit KeyHash(size_t expected = 16) { reset(expected); }

  void reset(size_t expected) {
    size_t cap = 16;
    while (cap * kLoadDen < expected * kLoadNum) cap *= 2;
    // Written whole here: made resident in one call (huge_pages.h), not page by page.
    assignHuge(slots_, cap, Slot{0, -1});
    mask_ = cap - 1;
    shift_ = 64;
    for (size_t c = cap; c > 1; c >>= 1) --shift_;
    size_ = 0;
  }
  size_t size() const { return size_; }
  size_t memoryBytes() const { return slots_.capacity() * sizeof(Slot); }

  // Value stored for k, or -1.
  int find(Key k) const {
    size_t h = slot(k);
    for (;;) {
      const Slot& s = slots_[h];
      if (s.val < 0) return -1;
      if (s.key == k) return s.val;
      h = (h + 1) & mask_;
    }
  }
  // Value stored for k; when absent, stores `value` and returns it.
  int findOrInsert(Key k, int value) {
    if ((size_ + 1) * kLoadNum > slots_.size() * kLoadDen) grow();
    size_t h = slot(k);
    for (;;) {
      Slot& s = slots_[h];
      if (s.val < 0) {
        s = Slot{k, value};
        ++size_;
        return value;
      }
      if (s.key == k) return s.val;
      h = (h + 1) & mask_;
    }
  }
  // Replaces the value of an existing key (no-op when absent).
  void set(Key k, int value) {
    size_t h = slot(k);
    for (;;) {
      Slot& s = slots_[h];
      if (s.val < 0) return;
      if (s.key == k) {
        s.val = value;
        return;
      }
      h = (h + 1) & mask_;
    }
  }

private:
  // At most kLoadDen / kLoadNum = 3/4 of the slots are used: probes stay short (linear probing,
  // about 2.5 slots per successful look-up), with a third of the memory of a half-full table.
  static constexpr size_t kLoadNum = 4, kLoadDen = 3;
  // A key and its value side by side, 12 bytes: a probe reads one cache line, not two.
#pragma pack(push, 4)
  struct Slot {
    Key key;
    std::int32_t val; // -1: empty
  };
#pragma pack(pop)
  static_assert(sizeof(Slot) == 12, "packed slot");
  // Fibonacci hashing: the top bits of the product depend on every bit of the key (the bits just
  // above bit 20, taken before, ignored the x of a box key and the first vertex of an edge key,
  // so keys that differ only there all probed one run of slots).
  size_t slot(Key k) const { return static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> shift_); }
  void grow() {
    HugeVector<Slot> old;
    old.swap(slots_);
    reset(old.size());
    for (const Slot& s : old)
      if (s.val >= 0) findOrInsert(s.key, s.val);
  }
  HugeVector<Slot> slots_;
  size_t mask_ = 0, size_ = 0;
  int shift_ = 64; // 64 − log2(capacity)
};

// Integer box coordinates of a cubic partition of space with side `side` and a fixed origin,
// packed into 64-bit keys (21 bits per axis).
class BoxIndexer {
public:
  static constexpr int kBits = 21;
  static constexpr std::int64_t kMax = (std::int64_t(1) << kBits) - 1;

  BoxIndexer() = default;
  BoxIndexer(const Vec3d& origin, double side) : origin_(origin), side_(side), inv_(1.0 / side) {}

  double side() const { return side_; }
  const Vec3d& origin() const { return origin_; }
  // Far outside the indexable range (and for NaN) the coordinate saturates at ±kFar, which
  // valid() refuses and which a range of boxes spans once: converting a double beyond the range of
  // int64 is undefined behaviour (a start point given at 1e235, fuzz/regressions/cloud/).
  static constexpr std::int64_t kFar = std::int64_t(1) << 40;
  std::int64_t coord(double v, int axis) const {
    const double c = std::floor((v - origin_[axis]) * inv_);
    if (c >= double(kFar)) return kFar;
    if (!(c > -double(kFar))) return -kFar;
    return static_cast<std::int64_t>(c);
  }
  static bool valid(std::int64_t x, std::int64_t y, std::int64_t z) {
    return x >= 0 && y >= 0 && z >= 0 && x <= kMax && y <= kMax && z <= kMax;
  }
  static KeyHash::Key pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (KeyHash::Key(x) << (2 * kBits)) | (KeyHash::Key(y) << kBits) | KeyHash::Key(z);
  }
  // Key of the box containing p; false when p is outside the indexable range.
  bool keyOf(const Vec3d& p, KeyHash::Key& key) const {
    const std::int64_t x = coord(p[0], 0), y = coord(p[1], 1), z = coord(p[2], 2);
    if (!valid(x, y, z)) return false;
    key = pack(x, y, z);
    return true;
  }
  // Lower corner of box (x, y, z).
  Vec3d corner(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return Vec3d(origin_[0] + double(x) * side_, origin_[1] + double(y) * side_,
                        origin_[2] + double(z) * side_);
  }

private:
  Vec3d origin_{0, 0, 0};
  double side_ = 1, inv_ = 1;
};

// Box id by box key (BoxIndexer::pack), in blocks of 4 x 4 x 4 boxes: a hash from the block's key
// to the block, and each block's 64 ids side by side. Neighbouring boxes then share a block (one
// or a few cache lines), and the hash has a fraction of the keys: the box grid's look-ups, which
// come in a spatial order, hit the cache instead of a random slot of a table the size of the
// boxes. The same answers as a KeyHash of the box keys.
class BoxIdIndex {
public:
  using Key = KeyHash::Key;
  void reset(size_t expectedBoxes) {
    blocks_.reset(expectedBoxes / 16 + 16);
    HugeVector<std::int32_t>().swap(ids_);
    size_ = 0;
  }
  size_t size() const { return size_; }
  size_t memoryBytes() const { return blocks_.memoryBytes() + ids_.capacity() * sizeof(std::int32_t); }
  // Value stored for k, or -1.
  int find(Key k) const {
    const int b = blocks_.find(blockOf(k));
    return b < 0 ? -1 : ids_[size_t(b) * 64 + localOf(k)];
  }
  // Value stored for k; when absent, stores `value` and returns it.
  int findOrInsert(Key k, int value) {
    const int blocks = int(ids_.size() / 64);
    const int b = blocks_.findOrInsert(blockOf(k), blocks);
    if (b == blocks) ids_.resize(ids_.size() + 64, -1);
    std::int32_t& id = ids_[size_t(b) * 64 + localOf(k)];
    if (id < 0) {
      id = value;
      ++size_;
    }
    return id;
  }

private:
  // Keys are x << 42 | y << 21 | z (21 bits each): the block drops the two low bits of each.
  static constexpr Key kLow = (Key(1) << 21) - 1;
  static Key blockOf(Key k) { return ((k >> 44) << 38) | (((k >> 23) & (kLow >> 2)) << 19) | ((k & kLow) >> 2); }
  static size_t localOf(Key k) { return size_t(((k >> 42) & 3) << 4 | ((k >> 21) & 3) << 2 | (k & 3)); }
  KeyHash blocks_;
  HugeVector<std::int32_t> ids_;
  size_t size_ = 0;
};

// The fixed finite sampling S_F of the unit sphere used for box normals (sec. 4.1): the cell
// centres of a cube map with 2^level × 2^level cells per face, 6·4^level directions (level 6:
// 24,576 directions, about 1.4° apart). The paper leaves S_F open; the cube map's quadtree lets
// the argmax be found by branch and bound, exactly over S_F, in a few dozen evaluations instead
// of |S_F| (each evaluation costs one pass over the box's normals).
class SphereSampling {
public:
  explicit SphereSampling(int level = 6);
  int level() const { return level_; }
  size_t size() const { return size_t(6) << (2 * level_); }
  // The i-th direction of S_F (unit length), i in [0, size()).
  Vec3d direction(size_t i) const;

  // argmax over n in S_F of min_k <normals[idx[k]], n>, by branch and bound (exact over S_F).
  // *minDot receives the maximised minimum. count must be > 0.
  Vec3d maxMinDirection(const std::vector<Vec3d>& normals, const std::uint32_t* idx,
                               size_t count, double* minDot = nullptr) const;
  // The same by testing every direction of S_F (reference for tests).
  Vec3d maxMinDirectionBruteForce(const std::vector<Vec3d>& normals, const std::uint32_t* idx,
                                         size_t count, double* minDot = nullptr) const;

  // A direction maxMinDirection() returns (a direction of S_F, or (0, 0, 1) for no normals) in two
  // bytes, and back bit for bit: the box normals are stored so. Level 6 at most.
  static constexpr std::uint16_t kUpCode = 0xffff; // (0, 0, 1)
  std::uint16_t code(const Vec3d& dir) const;
  Vec3d decode(std::uint16_t code) const;

  // A lower bound of maxMinDirection()'s value, at the cost of one pass over the normals: their
  // minimum at the direction of S_F nearest to their sum (the search's first guess); −∞ when the
  // normals sum to zero.
  double quickLowerBound(const std::vector<Vec3d>& normals, const std::uint32_t* idx, size_t count) const;

private:
  // The leaf of S_F holding the direction of the summed normals; false when they sum to zero.
  bool sumLeaf(const std::vector<Vec3d>& normals, const std::uint32_t* idx, size_t count,
               Vec3d& dir) const;
  // warm: a direction of S_F to start from (its value is a first lower bound), or null.
  Vec3d branchAndBound(const std::vector<Vec3d>& normals, const std::uint32_t* idx, size_t count,
                              double* minDot, const Vec3d* warm) const;
  Vec3d faceDirection(int face, double u, double v) const;
  // A direction of S_F: the centre of a leaf cell, computed when needed (a normalisation; the
  // search visits a few leaves per box, each then costing a pass over the box's normals), rather
  // than a table of all 24,576 (590 KB held for the whole session).
  Vec3d leafCentre(int face, std::uint32_t col, std::uint32_t row) const;
  size_t cellIndex(int face, int depth, std::uint32_t x, std::uint32_t y) const {
    return tables_->offset[size_t(depth)] + ((size_t(face) << (2 * depth)) | (size_t(y) << depth) | x);
  }
  int level_;
  // Per quadtree cell above the leaves: centre direction and cos/sin of the largest angle from
  // the centre to the cell's corners (precomputed once: the search then needs no trigonometry).
  // Immutable once built, so copies of an instance share them.
  struct CellInfo {
    Vec3d centre;
    double cosAlpha, sinAlpha;
  };
  struct Tables {
    std::vector<size_t> offset;
    std::vector<CellInfo> cell;
  };
  std::shared_ptr<const Tables> tables_;
  // Scratch of the searches: an instance is not meant to be shared between threads, but a copy
  // (cheap: it shares the tables) can be used by another thread.
  struct Cell {
    double bound;
    int face, depth;
    std::uint32_t x, y;
    bool operator<(const Cell& o) const { return bound < o.bound; }
  };
  mutable std::vector<Cell> heap_;
  mutable std::vector<std::uint32_t> active_;
};

// Sec. 4.1 normal filter on one box: returns how many of idx[0..count) remain (kept in order at
// the front of idx). Threshold on |Σ n_p|: below it all points are kept.
size_t filterBoxNormals(const std::vector<Vec3d>& normals, std::uint32_t* idx, size_t count,
                        double threshold = 0.1);

// Sec. 4.1's normal filter, and two-sided boxes (beyond the paper). The box's normals split into
// two groups: by the sign of <n_p, n̄> (n̄ the summed normal), or, when |n̄| < threshold (the
// normals cancel), by the sign along the axis they spread along most. When the second group
// holds at least BoxGrid::kOpposedShare of the points and kTwoSidedMinPoints points, the box is
// two-sided: idx is reordered to the first group, then the second, each in its order, and both
// are kept as the box's two layers (the paper's filter would drop the second). Otherwise the
// paper's filter: with |n̄| >= threshold the points of the second group are dropped (the others
// kept in order at the front of idx), else all are kept. Points that face sideways (a plate's
// rim) go to one layer only (docs/design/spherepack-thin-parts.md).
constexpr size_t kTwoSidedMinPoints = 4;
struct BoxLayers {
  size_t firstEnd = 0;        // points kept (not two-sided), or the first layer's end (two-sided)
  bool twoSided = false;
  Vec3d split{0, 0, 0}; // two-sided: <n, split> >= 0 for the first layer's normals
};
BoxLayers filterOrSplitBox(const std::vector<Vec3d>& normals, std::uint32_t* idx, size_t count,
                           std::vector<std::uint32_t>& scratch, double threshold = 0.1);

class Progress;

class BoxGrid {
public:
  // Builds the grid of side `side` over the points (with unit normals), applies the normal filter
  // and computes the box normals. `progress` (optional) is updated with fractions of the build.
  // The filter and the box normals run on `threads` threads (0 = automatic, parallel.h); the grid
  // is the same for any number. `normals` must outlive the grid: the normals of the boxes that
  // hold no input point are computed from them when first asked for.
  // deferNormals: the normals of the boxes holding input points are left for startNormals() /
  // finishNormals() (or first use) too, so that they can be computed while the caller works on.
  // listOrder (optional, a permutation of the point indices): the order of the points in every
  // box's list (default: increasing index). Box ids are given in order of first appearance in it.
  // extraReach (optional, one value per point): a point with extraReach[i] > 0 is referred to by
  // the boxes within side + extraReach[i] (at most side + kMaxExtraReach·side) instead of side:
  // the boxes its splat (a disk of that radius) comes within d of, so that a vertex anywhere within
  // d of the disk finds it (sec. 4.4), also where the splats are larger than d.
  static constexpr double kMaxExtraReach = 6;
  // The largest extent of the points (per axis) that build() can index with boxes of this side:
  // 2^21 − 1 boxes per axis (BoxIndexer), less the margins of the farthest reach on both sides.
  static double maxExtent(double side) { return (double(BoxIndexer::kMax) - 2 * (kMaxExtraReach + 4) - 1) * side; }
  // splatRadius (optional, one value per point, with `normals` the splats' disks): only the boxes
  // that some splat's disk meets are built (their lists, normals and flags, as above); the others,
  // which no vertex can lie in (the vertices lie on the splats), are gathered from an index of the
  // points by their own boxes when first asked for, with the same lists, layers and normals. On a
  // surface sampled at d of a few spacings the disks meet a tenth of the boxes within d of a point,
  // and those hold half the references. `points` and `listOrder` must then outlive the grid too.
  void build(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals, double side,
             Progress* progress = nullptr, int threads = 0, bool deferNormals = false,
             const std::vector<std::uint32_t>* listOrder = nullptr, const std::vector<float>* extraReach = nullptr,
             const std::vector<float>* splatRadius = nullptr);

  BoxGrid() = default;
  BoxGrid(const BoxGrid&) = delete;
  BoxGrid& operator=(const BoxGrid&) = delete;
  ~BoxGrid() { stopNormals(); }

  // The deferred box normals: startNormals() computes them on one more thread while the caller
  // goes on (when `threads` allows more than one; 0 = automatic), nearest to `from` first (where
  // the caller will ask first), then the other boxes' normals; finishNormals() stops that thread
  // and computes the deferred ones still missing.
  // Meanwhile boxNormal() is safe to call from one thread: a box not done yet is computed there
  // (or awaited when the other thread is at it). The values are the same whoever computes them;
  // dTooLargeCount() is final after finishNormals().
  void startNormals(int threads, const Vec3d& from);
  void finishNormals();

  double side() const { return index_.side(); }
  const BoxIndexer& indexer() const { return index_; }
  // Boxes of the partition that refer to a point (ids 0 .. boxCount() − 1); the second layers of
  // the two-sided boxes have the ids after them (up to layerCount()).
  size_t boxCount() const { return layerBoxes_ > 0 ? layerBoxes_ : normalCode_.size(); }
  size_t layerCount() const { return normalCode_.size(); }
  size_t twoSidedBoxes() const { return layerCount() - boxCount(); }
  // Id of the box containing p, or -1 when that box refers to no point. In a two-sided box, the
  // layer of the points whose normals the paper's filter keeps.
  int boxOf(const Vec3d& p) const {
    KeyHash::Key k;
    if (!index_.keyOf(p, k)) return -1;
    const int b = hash_.find(k);
    return b >= 0 || !lazy_ ? b : gatheredBox(k);
  }
  // The same, but in a two-sided box the layer of the side `normal` faces (the normal of the
  // splat or vertex that asks; a zero normal gets the first layer). Its points, box normal and
  // checks are that side's alone, so both sides of a plate thinner than the box's reach are
  // meshed (the paper's filter drops one of them).
  int boxOf(const Vec3d& p, const Vec3d& normal) const {
    const int b = boxOf(p);
    if (size_t(b) >= built_) { // -1, or a gathered box
      if (b < 0 || gathered_[size_t(b) - built_].twin < 0) return b;
      const int second = gathered_[size_t(b) - built_].twin;
      return normal * gathered_[size_t(second) - built_].split < 0 ? second : b;
    }
    if (twin_.empty() || twin_[size_t(b)] < 0) return b;
    const int second = twin_[size_t(b)];
    return normal * split_[size_t(second) - layerBoxes_] < 0 ? second : b;
  }
  // Points of a box (after the normal filter), in increasing index order (or build()'s listOrder).
  const std::uint32_t* pointsBegin(int box) const {
    return size_t(box) < built_ ? points_.data() + start_[size_t(box)] : gathered_[size_t(box) - built_].points.data();
  }
  const std::uint32_t* pointsEnd(int box) const { return pointsBegin(box) + pointCount(box); }
  size_t pointCount(int box) const {
    return size_t(box) < built_ ? start_[size_t(box) + 1] - start_[size_t(box)]
                                : gathered_[size_t(box) - built_].points.size();
  }
  // The box normal (sec. 4.1). Computed by build() (or startNormals()) for most boxes, on first
  // use for the others: the same value either way, but a first use writes to the grid, so these
  // accessors must not be called from several threads at once.
  Vec3d boxNormal(int box) const {
    if (size_t(box) >= built_) return sampling_.decode(gathered_[size_t(box) - built_].normalCode);
    if (state_[size_t(box)].load(std::memory_order_acquire) != kDone) ensureNormal(box);
    return sampling_.decode(normalCode_[size_t(box)]);
  }
  // max over S_F of min_p <n_p, n>, rounded to float (keeping its sign): negative means d looked
  // too large in this box.
  double boxMinDot(int box) const {
    if (size_t(box) >= built_) return double(gathered_[size_t(box) - built_].minDot);
    if (state_[size_t(box)].load(std::memory_order_acquire) != kDone) ensureNormal(box);
    return double(minDot_[size_t(box)]);
  }
  // Sec. 4.1: d is too large in a box when its box normal has a negative scalar product with the
  // normals of points registered in it, before the normal filter (which drops the points whose
  // normals oppose the box's summed normal: when they are a real share of the box) or after it.
  // Points opposed before the filter count when they are at least this share of the box's
  // points (and at least four): thin plates with 2:1 point counts on their sides give a third, a
  // box across a fold up to a half; scattered flipped normals (1 in 17 in the tests) stay below.
  static constexpr double kOpposedShare = 0.25;
  bool dTooLarge(int box) const {
    const std::uint8_t f = size_t(box) < built_ ? flags_[size_t(box)] : gathered_[size_t(box) - built_].flags;
    return (f & kOpposed) != 0 || boxMinDot(box) < 0;
  }
  size_t dTooLargeCount() const { return dTooLargeCount_.load(); }
  size_t droppedByFilter() const { return dropped_; } // point references removed by the filter
  // Points whose boxes in reach were not all among the 27 around their own box (rounding at a box
  // face); build() takes a slower path for them.
  size_t pointsAtBoxFaces() const { return facePoints_; }
  size_t references() const { return points_.size(); }
  // Boxes (layers) gathered on first use so far (build()'s splatRadius).
  size_t gatheredBoxes() const { return gathered_.size(); }
  size_t memoryBytes() const;
  // Frees the grid (after finishNormals()); the counts stay. The grid is empty afterwards.
  void release();

private:
  static constexpr int kSpan = 16; // boxes per axis within the largest reach (2·7 + 2)
  class Builder; // build()'s passes and working arrays (box_grid.cpp)
  BoxIndexer index_;
  BoxIdIndex hash_;
  std::vector<std::uint32_t> start_;   // CSR offsets, boxCount()+1
  HugeVector<std::uint32_t> points_;   // point indices per box (about 21 per point: huge pages)
  // Box normal states: not computed, being computed (by the other thread), done.
  static constexpr std::uint8_t kNone = 0, kBusy = 1, kDone = 2;
  // Computes box's normal with `sampling` unless another thread claimed it (then waits for it).
  void computeNormal(int box, const SphereSampling& sampling) const;
  void ensureNormal(int box) const { computeNormal(box, sampling_); }
  void stopNormals();

  std::vector<std::int32_t> twin_;     // per layer: the other layer of a two-sided box, or -1
                                       // (empty when no box is two-sided)
  std::vector<Vec3d> split_;    // per second layer (id − boxCount()): the direction that
                                       // splits its box (its side: <n, split> < 0)
  size_t layerBoxes_ = 0;              // boxCount() when some box is two-sided, else 0
  // Per box: the box normal (SphereSampling::code), and the best minimum as a float of the same sign.
  mutable std::vector<std::uint16_t> normalCode_;
  mutable std::vector<float> minDot_;
  // Stores box b's normal and minimum (the sign of minDot kept where float rounds it to zero).
  void storeNormal(size_t b, const Vec3d& normal, double minDot) const;
  std::unique_ptr<std::atomic<std::uint8_t>[]> state_; // per box: kNone, kBusy, kDone
  // Per box, set by build(): kCounted, a box that counts for dTooLargeCount (all but those the
  // quick test cleared); kOpposed, a box that saw two sides (counted as "d too large" by build()).
  static constexpr std::uint8_t kCounted = 1, kOpposed = 2;
  std::vector<std::uint8_t> flags_;
  std::vector<std::uint32_t> pending_; // deferred boxes, for startNormals()/finishNormals()
  std::vector<Vec3d> pendingCorner_; // their lower corners, until startNormals() orders them
  mutable SphereSampling sampling_{0}; // for the box normals computed on first use
  // The boxes not built (build()'s splatRadius), gathered on first use by the thread that asks
  // (the one that may call boxNormal(); the other thread only computes normals of built boxes).
  // Layers of built boxes have ids below built_, gathered layers from built_ on.
  size_t built_ = 0;
  bool lazy_ = false;
  const std::vector<Vec3d>* points3_ = nullptr;
  const std::vector<std::uint32_t>* listOrder_ = nullptr; // build()'s (null: the identity)
  std::vector<std::uint32_t> ownStart_; // CSR offsets of ownPoints_, by the id of the points' own box
  HugeVector<std::uint32_t> ownPoints_; // the points of reach `side` in each own box (list positions)
  std::vector<std::pair<std::uint32_t, double>> far_; // the other points (list positions), with their reach
  struct Gathered {
    std::vector<std::uint32_t> points;
    std::uint16_t normalCode = SphereSampling::kUpCode;
    float minDot = 0;
    std::uint8_t flags = 0;
    std::int32_t twin = -1;
    Vec3d split{0, 0, 0};
  };
  static constexpr int kNoBox = 0x7fffffff;       // gatheredIds_: no point within reach
  mutable KeyHash gatheredIds_{16};              // box key -> first gathered layer id, or kNoBox
  mutable std::vector<Gathered> gathered_;
  mutable size_t gatheredReferences_ = 0;
  // Id of the box with key k gathered (the first layer), or -1 when no point reaches it.
  int gatheredBox(KeyHash::Key k) const;
  // Whether a point at p with reach `reach` refers to box (x, y, z): the slabs and the test of
  // build() (Builder::forBoxesWithin), to the last bit.
  bool refers(const Vec3d& p, double reach, std::int64_t x, std::int64_t y, std::int64_t z) const;
  const std::vector<Vec3d>* normals_ = nullptr;
  mutable std::atomic<size_t> dTooLargeCount_{0};
  size_t dropped_ = 0, facePoints_ = 0;
  std::thread background_;
  std::atomic<bool> stop_{false};
};

// Squared distance from p to the axis-aligned cube [lo, lo + side]^3.
inline double squaredDistanceToBox(const Vec3d& p, const Vec3d& lo, double side) {
  double s = 0;
  for (int a = 0; a < 3; ++a) {
    const double v = p[a] < lo[a] ? lo[a] - p[a] : (p[a] > lo[a] + side ? p[a] - lo[a] - side : 0.0);
    s += v * v;
  }
  return s;
}

} // namespace growth
