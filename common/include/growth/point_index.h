#pragma once
// The spatial index of the points, for both filters (Robust G2S, sec. 3 step 2: "an original hash
// table data structure ... which makes possible a more efficient search for the nearest
// neighbourhoods"; the sphere packer's splats and sampling estimate; the mean spacing).
//
// The index *owns* the points and stores them sorted by cell, cells in Morton (Z-curve) order:
// index i of a point in the index is its place in that order, and order()[i] its index in the
// caller's array (G2S uses the index's order for all its per-point arrays, so the advancing front
// walks memory coherently; growth::PointGrid translates back to the caller's indices). Building is
// one stable LSD radix sort of the cell keys. A query finds each cell's point range through bricks
// of 4×4×4 cells (an index over the bricks of the bulk's box, then 16-bit offsets inside an
// occupied brick: three loads, no hashing) when that box holds at most one brick per point, as it
// does for points on a surface; cells outside it, or all cells of a cloud too spread for bricks,
// are found through an open-addressing table whose 16-byte entries hold the cell key and its point
// range. Only occupied cells (bricks) carry ranges, so memory grows with the cloud, not with its
// bounding box. Coordinates are scanned contiguously, as float copies, four at a time.
//
// Robust to far points and dense clusters:
// - The bulk of the cloud is growth::robustBox (quantiles of a sample): the float coordinates are
//   relative to its centre and the float error bound is per query (floatSlack), so a far point
//   costs the others no precision; the bricks cover the bulk's box, so a far point does not turn
//   them off; cells are at least the bulk's extent / 2^21, and points beyond 2^21 cells of the
//   bulk (absurdly far) are kept apart in a list that only queries reaching that far scan.
// - A cell holding more than kSplitPoints points (a dense cluster) has its points ordered by the
//   Morton code of their place inside the cell at 2^kSplitBits sub-cells per axis: its sub-cells
//   of every level are contiguous ranges (an implicit octree), and a query descends it to the
//   sub-cells its ball's box touches, so its cost follows the local density, not the cell's count.
#include <growth/cloud_scale.h>
#include <growth/huge_pages.h>
#include <growth/morton.h>

#include <growth/vec3.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace growth {

class PointIndex {
public:
  using P3 = Vec3d;

  // Float coordinate arrays hold this many entries past the last point (whole-vector loads).
  static constexpr std::size_t kPad = 16;
  // Cells with more points than this are split (see above); sub-cells of at most kSplitLeaf points
  // are scanned whole.
  static constexpr std::uint32_t kSplitPoints = 256;
  static constexpr std::uint32_t kSplitLeaf = 32;
  static constexpr int kSplitBits = 21;

  // Takes the points, drops the non-finite ones, and sorts the rest into cell order with cubic
  // cells of side `cellSize` (enlarged to the bulk's extent / 2^21 when smaller). order()[i] is then
  // the caller's index of the point now at i.
  void build(std::vector<P3> points, double cellSize);

  size_t size() const { return pts_.size(); }
  // Size of the array the index was built from (non-finite points included).
  size_t builtSize() const { return builtSize_; }
  const std::vector<P3>& points() const { return pts_; }
  const P3& point(std::uint32_t i) const { return pts_[i]; }
  const std::vector<std::uint32_t>& order() const { return order_; }
  // Replaces order() (after rebuilding the index from its own points, to keep the caller's indices).
  void setOrder(std::vector<std::uint32_t> order) { order_.swap(order); }
  // Frees the search structure (float copies and cell tables), keeping points() and order(): no
  // query may follow. For G2S's output step, so that its memory peak does not add up with the search's.
  void releaseSearch() {
    HugeVector<float>().swap(coords_);
    HugeVector<Slot>().swap(table_);
    HugeVector<std::uint32_t>().swap(brickOf_);
    HugeVector<std::uint32_t>().swap(brickBase_);
    HugeVector<std::uint16_t>().swap(brickOff_);
    HugeVector<std::uint64_t>().swap(sub_);
    bricksOnly_ = false;
  }
  // Frees the points too: only order() is left (size() is then 0).
  void releasePoints() { std::vector<P3>().swap(pts_); }
  double cellSize() const { return cell_; }
  size_t cellCount() const { return cells_; }
  // Cells of the bulk are looked up through bricks (compact clouds) rather than the hash table.
  bool usesBricks() const { return !brickOf_.empty(); }
  // Points beyond 2^21 cells of the bulk, scanned apart; cells split into sub-cells.
  size_t farPointCount() const { return pts_.size() - farBegin_; }
  size_t splitCellCount() const { return splitCells_; }
  // The bounding box of the points (far ones included) and the robust box of their bulk.
  const Box3d& box() const { return box_; }
  const Box3d& bulkBox() const { return bulk_; }

  // When set (single-threaded callers only), every query adds the number of points it scans to
  // *counter: a deterministic measure of the index's work.
  void setVisitCounter(std::uint64_t* counter) { visited_ = counter; }

protected:
  // Adds n points scanned to the visit counter, if any. (Per query in the hot gathers, which sum
  // their ranges anyway, rather than per cell: a load and a branch per cell would slow them.)
  __attribute__((always_inline)) void countVisited(std::uint64_t n) const {
    if (__builtin_expect(visited_ != nullptr, 0)) *visited_ += n;
  }
  // forEachRange without the visit counter (the caller counts).
  template <class F>
  __attribute__((always_inline)) bool forEachRangeUncounted(const P3& c, double radius, F&& range) const {
    if (pts_.empty() || !(radius >= 0)) return false;
    return visitCells(c, radius, range);
  }

public:

  // Calls f(index, squaredDistance) for every point with |p − c| <= radius.
  template <class F>
  void forEachInBall(const P3& c, double radius, F&& f) const {
    visitBall(c, radius, [&](std::uint32_t i, double d2) {
      f(i, d2);
      return false;
    });
  }
  // Calls f(index) for every point whose float coordinates are within radius + floatSlack() of
  // c: a superset of the ball, by at most the float rounding, without exact double checks (for
  // callers that test the points again anyway, in float with the same slack, then exactly).
  template <class F>
  void forEachNearBall(const P3& c, double radius, F&& f) const {
    visitBall<false>(c, radius, [&](std::uint32_t i, double) {
      f(i);
      return false;
    });
  }
  // Calls stop(index, squaredDistance) for the points with |p − c| <= radius until it returns
  // true; returns whether it did (early exit for emptiness tests).
  template <class F>
  bool anyInBall(const P3& c, double radius, F&& stop) const {
    return visitBall(c, radius, stop);
  }
  // Calls range(begin, end) for index ranges that together hold every point within `radius` of c
  // (and others near it: whole cells or sub-cells), until it returns true; returns whether it did.
  template <class F>
  bool forEachRange(const P3& c, double radius, F&& range) const {
    if (pts_.empty() || !(radius >= 0)) return false;
    return visitCells(c, radius, [&](std::uint32_t begin, std::uint32_t end) {
      countVisited(end - begin);
      return range(begin, end);
    });
  }

  // Calls f(begin, end) for the point range of every occupied cell (the far points, kept apart,
  // excluded): from the bricks, or the table when there is one (it then holds every cell).
  template <class F>
  void forEachCell(F&& f) const {
    if (!table_.empty()) {
      for (const Slot& s : table_)
        if (s.key != kEmpty) f(s.begin, s.end);
      return;
    }
    for (size_t b = 0; b < brickBase_.size(); ++b)
      for (size_t k = 0; k < 64; ++k) {
        const std::uint16_t* off = &brickOff_[b * 65 + k];
        if (off[0] != off[1]) f(brickBase_[b] + off[0], brickBase_[b] + off[1]);
      }
  }
  // The corner (lowest coordinates) of the cell that holds point i (not a far point).
  P3 cellCorner(std::uint32_t i) const {
    P3 c;
    for (int a = 0; a < 3; ++a) c[a] = origin_[a] + double(coord(pts_[i][a], a)) * cell_;
    return c;
  }

  // The point's coordinates relative to floatOrigin(), in float.
  float fx(std::uint32_t i) const { return coords_[i]; }
  float fy(std::uint32_t i) const { return coords_[stride_ + i]; }
  float fz(std::uint32_t i) const { return coords_[2 * stride_ + i]; }
  const float* floatX() const { return coords_.data(); }
  const float* floatY() const { return coords_.data() + stride_; }
  const float* floatZ() const { return coords_.data() + 2 * stride_; }
  // A bound on the error of a distance between c and a point within `radius` of it computed from
  // float coordinates (the point's fx/fy/fz, c's from toFloat). Rounding to float errs by at most
  // 2^-24 of a coordinate's magnitude, and both coordinates are at most |c − origin|∞ + radius (+
  // the slack itself) from the origin: 2·√3·2^-24·(|c − origin|∞ + 2·radius) bounds the error,
  // taken four times for the float arithmetic and margin. The origin is the centre of the bulk,
  // so a far point costs no precision near the others.
  double floatSlack(const P3& c, double radius) const {
    const double m = std::max(std::abs(c[0] - fo_[0]), std::max(std::abs(c[1] - fo_[1]), std::abs(c[2] - fo_[2])));
    return kSlackPerMagnitude * (m + 2.0 * radius) + 1e-300;
  }
  // The same bound from c's float coordinates fc (toFloat(c, fc)), cheaper in the hot queries: a
  // float errs by at most 2^-24 of its value, so |c − origin|∞ <= max|fc|·(1 + 2^-23).
  double floatSlack(const float* fc, double radius) const {
    const float m = std::max(std::abs(fc[0]), std::max(std::abs(fc[1]), std::abs(fc[2])));
    return kSlackPerMagnitude * (double(m) * (1.0 + 1.0 / 8388608.0) + 2.0 * radius) + 1e-300;
  }
  const P3& floatOrigin() const { return fo_; }
  void toFloat(const P3& c, float out[3]) const {
    for (int a = 0; a < 3; ++a) out[a] = float(c[a] - fo_[a]);
  }

  // The point nearest to c other than `exclude`, within maxRadius (equal distances: the lowest
  // index); -1 when there is none.
  std::int64_t nearest(const P3& c, std::int64_t exclude = -1,
                       double maxRadius = std::numeric_limits<double>::infinity(),
                       double* squaredDistance = nullptr) const {
    return nearestBy(c, maxRadius, squaredDistance, [exclude](std::uint32_t i) {
      return std::int64_t(i) == exclude ? -1 : std::int64_t(i);
    });
  }
  // The same with the points ranked by rank(i): skipped when negative, and among equal distances
  // the lowest rank wins (growth::PointGrid ranks by the caller's index).
  template <class Rank>
  std::int64_t nearestBy(const P3& c, double maxRadius, double* squaredDistance, Rank&& rank) const;

  // For every point whose caller index order()[i] is a multiple of `stride`: squared[order()[i] /
  // stride] = the squared distance to its nearest other point (-1 when there is none; `squared`
  // covers every multiple below builtSize()). Runs on `threads` threads (0 = automatic,
  // parallel.h); the values do not depend on their number.
  void nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared, int threads = 1) const;

  size_t memoryBytes() const {
    return pts_.capacity() * sizeof(P3) + coords_.capacity() * sizeof(float) +
           order_.capacity() * sizeof(std::uint32_t) + table_.capacity() * sizeof(Slot) +
           (brickOf_.capacity() + brickBase_.capacity()) * sizeof(std::uint32_t) + sub_.capacity() * sizeof(std::uint64_t) +
           brickOff_.capacity() * sizeof(std::uint16_t);
  }

  // Morton code helpers (public for the tests).
  static std::uint64_t spread(std::uint64_t x) { return mortonSpread(x); }
  static std::uint64_t morton(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    return mortonCode(x, y, z);
  }

private:
  static constexpr double kSlackPerMagnitude = 8.0 * 1.7320508075688772 / 16777216.0; // 8·√3·2^-24
  static constexpr std::int64_t kMaxCoord = (std::int64_t(1) << 21) - 1;
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  static constexpr std::int64_t kMaxSpan = 16; // cells per axis handled by the fast query loop

  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t begin = 0, end = 0;
  };

  // Cell coordinate of v along an axis: -1 below the range, kMaxCoord + 1 above it (truncation
  // equals floor for the non-negative values that matter; callers clamp to [0, maxCell_]).
  std::int64_t coord(double v, int axis) const {
    const double c = (v - origin_[axis]) * inv_;
    return !(c >= 0) ? -1 : (c > double(kMaxCoord) ? kMaxCoord + 1 : static_cast<std::int64_t>(c)); // NaN: -1
  }
  // Table index of a cell key: the 2×2×2 block of cells (key >> 3) is hashed, the cell's place
  // in its block (key & 7) kept, so the cells a query probes — neighbours in space — mostly share
  // a block and land in neighbouring slots (shared cache lines), while distant blocks spread.
  size_t slotOf(std::uint64_t key) const {
    return static_cast<size_t>((((key >> 3) * 0x9E3779B97F4A7C15ull) >> blockShift_) << 3 | (key & 7)) & mask_;
  }
  const Slot* find(std::uint64_t key) const {
    size_t h = slotOf(key);
    for (;;) {
      const Slot& s = table_[h];
      if (s.key == key) return &s;
      if (s.key == kEmpty) return nullptr;
      h = (h + 1) & mask_;
    }
  }

  template <bool Exact = true, class F>
  bool visitBall(const P3& c, double radius, F&& stop) const {
    if (pts_.empty() || !(radius >= 0)) return false;
    const double r2 = radius * radius;
    // Float prefilter radius: distances computed from the float coordinates are within
    // floatSlack(c, radius) of the exact ones, so no point within `radius` is missed; hits are
    // re-checked exactly in double.
    float fc[3];
    toFloat(c, fc);
    const double slack = floatSlack(fc, radius);
    const float r2f = float((radius + slack) * (radius + slack));
    return visitCells(c, radius, [&](std::uint32_t begin, std::uint32_t end) {
      countVisited(end - begin);
      return scanCell<Exact>(begin, end, c, fc, r2, r2f, stop);
    });
  }

  // Calls cell(begin, end) for the point ranges of every occupied cell that the ball's bounding
  // box touches (sub-cells of split cells, the far points when it reaches beyond the range), until
  // it returns true; returns whether it did.
  template <class F>
  __attribute__((always_inline)) bool visitCells(const P3& c, double radius, F&& cell) const {
    std::int64_t lo[3], hi[3];
    if (__builtin_expect(bricksOnly_, 1)) {
      // Every point in the bricks (no far points, no table): clamp to them, no other test. The
      // same cells as max(coord(c − r), lo) .. min(coord(c + r), hi) of the bricks' cells (both
      // >= 0), computed without branches: clamped in double, then truncated (a floor there), a
      // negative or NaN upper end giving -1 (an empty range) as coord does.
      bool empty = false;
      for (int a = 0; a < 3; ++a) {
        const double l = (c[a] - radius - origin_[a]) * inv_, h = (c[a] + radius - origin_[a]) * inv_;
        const double cellLo = double(brickCellLo_[a]), cellHi = double(brickCellHi_[a]);
        lo[a] = static_cast<std::int64_t>(std::min(std::max(cellLo, l), cellHi + 1.0));
        hi[a] = static_cast<std::int64_t>(std::min(cellHi, h >= 0 ? h : -1.0));
        empty |= lo[a] > hi[a];
      }
      if (empty) return false;
      return splitCells_ == 0 ? visitBricks<false>(lo, hi, c, radius, cell) : visitBricks<true>(lo, hi, c, radius, cell);
    }
    for (int a = 0; a < 3; ++a) {
      lo[a] = coord(c[a] - radius, a);
      hi[a] = coord(c[a] + radius, a);
    }
    if (__builtin_expect(farBegin_ < pts_.size(), 0) &&
        (lo[0] < 0 || lo[1] < 0 || lo[2] < 0 || hi[0] > kMaxCoord || hi[1] > kMaxCoord || hi[2] > kMaxCoord) &&
        range(std::uint32_t(farBegin_), std::uint32_t(pts_.size()), cell))
      return true; // the box reaches outside the 2^21 cells of the range: the far points too
    bool empty = false;
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(lo[a], 0);
      hi[a] = std::min<std::int64_t>(hi[a], maxCell_[a]);
      empty |= lo[a] > hi[a];
    }
    if (empty) return false;
    // (Two instances: the test for split cells costs the common loop a tenth of its time.)
    return splitCells_ == 0 ? visitCellRange<false>(lo, hi, c, radius, cell)
                            : visitCellRange<true>(lo, hi, c, radius, cell);
  }

  // The cells [lo, hi], all inside the bricks: three loads per cell (or a walk of the occupied
  // cells when the box holds more cells than are occupied).
  template <bool Split, class F>
  __attribute__((always_inline)) bool visitBricks(const std::int64_t* lo, const std::int64_t* hi, const P3& c,
                                                  double radius, F&& cell) const {
    auto visit = [&](std::uint32_t begin, std::uint32_t end) {
      if (!Split || end - begin <= kSplitPoints) return range(begin, end, cell);
      return visitSplit(begin, end, c, radius, cell);
    };
    if (moreCellsThanOccupied(lo, hi)) {
      // More cells in the box than occupied ones: walk the occupied cells instead.
      for (size_t b = 0; b < brickBase_.size(); ++b)
        for (int k = 0; k < 64; ++k) {
          const std::uint16_t* off = &brickOff_[b * 65 + size_t(k)];
          if (off[0] != off[1] && visit(brickBase_[b] + off[0], brickBase_[b] + off[1])) return true;
        }
      return false;
    }
    // Morton place of a cell in its brick from the low two bits of each coordinate.
    static constexpr unsigned kPlace[4] = {0, 1, 8, 9};
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        const size_t row = brickIndex(x >> 2, y >> 2, 0) - brickBias_; // (unsigned: wraps back)
        const unsigned xy = kPlace[x & 3] | kPlace[y & 3] << 1;
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const std::uint32_t b = brickOf_[row + size_t(z >> 2)];
          if (b == 0) continue;
          const std::uint16_t* off = &brickOff_[size_t(b - 1) * 65 + (xy | kPlace[z & 3] << 2)];
          if (off[0] != off[1] && visit(brickBase_[b - 1] + off[0], brickBase_[b - 1] + off[1])) return true;
        }
      }
    return false;
  }

  // visitCells for the cells [lo, hi] (clamped to the occupied ones), split cells only if Split.
  template <bool Split, class F>
  __attribute__((always_inline)) bool visitCellRange(std::int64_t* lo, std::int64_t* hi, const P3& c, double radius,
                                                     F&& cell) const {
    auto visit = [&](std::uint32_t begin, std::uint32_t end) {
      if (!Split || end - begin <= kSplitPoints) return range(begin, end, cell);
      return visitSplit(begin, end, c, radius, cell);
    };
    if (!brickOf_.empty()) {
      bool inBricks = lo[0] >= brickCellLo_[0] && lo[1] >= brickCellLo_[1] && lo[2] >= brickCellLo_[2] &&
                      hi[0] <= brickCellHi_[0] && hi[1] <= brickCellHi_[1] && hi[2] <= brickCellHi_[2];
      if (!inBricks && table_.empty()) {
        // No occupied cell outside the bricks: clamp to them.
        for (int a = 0; a < 3; ++a) {
          lo[a] = std::max(lo[a], brickCellLo_[a]);
          hi[a] = std::min(hi[a], brickCellHi_[a]);
          if (lo[a] > hi[a]) return false;
        }
        inBricks = true;
      }
      const double boxCells = double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1);
      // (A box of more cells than are occupied is walked through the table when there is one.)
      if (inBricks && (table_.empty() || !(boxCells > double(cells_)))) return visitBricks<Split>(lo, hi, c, radius, cell);
    }
    if (double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1) > double(cells_)) {
      // More cells in the box than occupied ones: walk the occupied cells instead.
      for (const Slot& s : table_)
        if (s.key != kEmpty && visit(s.begin, s.end)) return true;
      return false;
    }
    if (hi[1] - lo[1] >= kMaxSpan || hi[2] - lo[2] >= kMaxSpan) {
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
            const Slot* s = find(morton(std::uint64_t(x), std::uint64_t(y), std::uint64_t(z)));
            if (s != nullptr && visit(s->begin, s->end)) return true;
          }
      return false;
    }
    // Morton bits of each cell coordinate in the (small) ranges, computed once per query.
    std::uint64_t ky[kMaxSpan], kz[kMaxSpan];
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y) ky[y - lo[1]] = spread(std::uint64_t(y)) << 1;
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) kz[z - lo[2]] = spread(std::uint64_t(z)) << 2;
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
      const std::uint64_t kx = spread(std::uint64_t(x));
      for (std::int64_t y = 0; y <= hi[1] - lo[1]; ++y) {
        const std::uint64_t kxy = kx | ky[y];
        for (std::int64_t z = 0; z <= hi[2] - lo[2]; ++z) {
          const Slot* s = find(kxy | kz[z]);
          if (s != nullptr && visit(s->begin, s->end)) return true;
        }
      }
    }
    return false;
  }

  // The box [lo, hi] (non-empty) holds more cells than are occupied. (In integers for the usual
  // small boxes: the conversions to double cost a query's scan of a cell.)
  __attribute__((always_inline)) bool moreCellsThanOccupied(const std::int64_t* lo, const std::int64_t* hi) const {
    const std::uint64_t sx = std::uint64_t(hi[0] - lo[0] + 1), sy = std::uint64_t(hi[1] - lo[1] + 1),
                        sz = std::uint64_t(hi[2] - lo[2] + 1);
    if ((sx | sy | sz) < 1024) return sx * sy * sz > cells_;
    return double(sx) * double(sy) * double(sz) > double(cells_);
  }

  template <class F>
  __attribute__((always_inline)) bool range(std::uint32_t begin, std::uint32_t end, F&& cell) const {
    return cell(begin, end);
  }

  // A split cell [begin, end): its points are ordered by sub_ (the Morton code of their sub-cell
  // at 2^kSplitBits per axis inside the cell). Descends the octree of sub-cells from the cell,
  // calling cell(b, e) for the sub-cells of at most kSplitLeaf points (or of the finest level)
  // that the ball's box touches.
  template <class F>
  __attribute__((noinline)) bool visitSplit(std::uint32_t begin, std::uint32_t end, const P3& c, double radius, F&& cell) const {
    // The cell's corner: from any of its points (all share the cell).
    // (The box is widened by a millionth of a cell: a point's sub-cell is computed from rounded
    // coordinates.)
    double corner[3], lo[3], hi[3];
    const double margin = 1e-6 * cell_;
    for (int a = 0; a < 3; ++a) {
      corner[a] = origin_[a] + double(coord(pts_[begin][a], a)) * cell_;
      lo[a] = c[a] - radius - corner[a] - margin;
      hi[a] = c[a] + radius - corner[a] + margin;
    }
    struct Node {
      std::uint32_t begin, end;
      std::uint64_t code;
      int level;
    };
    Node stack[8 * kSplitBits + 1];
    int top = 0;
    stack[top++] = Node{begin, end, 0, 0};
    while (top > 0) {
      const Node n = stack[--top];
      if (n.end - n.begin <= kSplitLeaf || n.level == kSplitBits) {
        if (range(n.begin, n.end, cell)) return true;
        continue;
      }
      // Children in reverse, so they are visited in Morton order.
      const int shift = 3 * (kSplitBits - n.level - 1);
      const double side = std::ldexp(cell_, -(n.level + 1));
      std::uint32_t childEnd = n.end;
      for (int k = 7; k >= 0; --k) {
        const std::uint64_t code = n.code << 3 | std::uint64_t(k);
        const std::uint64_t first = code << shift;
        const std::uint32_t childBegin = std::uint32_t(
            std::lower_bound(sub_.begin() + n.begin, sub_.begin() + childEnd, first) - sub_.begin());
        if (childBegin < childEnd) {
          // The child's box: sub-cell coordinates from the code's bits at this level.
          bool touches = true;
          for (int a = 0; a < 3; ++a) {
            std::uint64_t cc = 0;
            for (int l = 0; l <= n.level; ++l) cc = cc << 1 | ((code >> (3 * (n.level - l) + a)) & 1u);
            const double b0 = double(cc) * side;
            touches &= !(hi[a] < b0 || lo[a] > b0 + side);
          }
          if (touches) stack[top++] = Node{childBegin, childEnd, code, n.level + 1};
        }
        childEnd = childBegin;
      }
    }
    return false;
  }

  // Scans the points [begin, end) of one cell: a float test four at a time (SSE2) on the SoA
  // copy, then the exact double test on the hits.
  template <bool Exact, class F>
  bool scanCell(std::uint32_t begin, std::uint32_t end, const P3& c, const float* fc, double r2, float r2f,
                F&& stop) const {
    std::uint32_t i = begin;
    const float* fx = coords_.data();
    const float* fy = fx + stride_;
    const float* fz = fy + stride_;
    auto exact = [&](std::uint32_t k) {
      if (!Exact) return stop(k, 0.0);
      const P3& p = pts_[k];
      const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
      const double d2 = dx * dx + dy * dy + dz * dz;
      return d2 <= r2 && stop(k, d2);
    };
#if defined(__SSE2__)
    // The coordinate arrays are padded (kPad), so the last, partial block of a cell is loaded
    // whole and its lanes past `end` are masked off.
    const __m128 cx = _mm_set1_ps(fc[0]), cy = _mm_set1_ps(fc[1]), cz = _mm_set1_ps(fc[2]);
    const __m128 rr = _mm_set1_ps(r2f);
    for (; i < end; i += 4) {
      const __m128 dx = _mm_sub_ps(_mm_loadu_ps(fx + i), cx);
      const __m128 dy = _mm_sub_ps(_mm_loadu_ps(fy + i), cy);
      const __m128 dz = _mm_sub_ps(_mm_loadu_ps(fz + i), cz);
      const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
      int mask = _mm_movemask_ps(_mm_cmple_ps(d2, rr));
      if (end - i < 4) mask &= (1 << (end - i)) - 1;
      while (mask != 0) {
        const int k = __builtin_ctz(static_cast<unsigned>(mask));
        mask &= mask - 1;
        if (exact(i + std::uint32_t(k))) return true;
      }
    }
#else
    for (; i < end; ++i) {
      const float dx = fx[i] - fc[0], dy = fy[i] - fc[1], dz = fz[i] - fc[2];
      if (dx * dx + dy * dy + dz * dz <= r2f && exact(i)) return true;
    }
#endif
    return false;
  }

  std::vector<P3> pts_;
  size_t builtSize_ = 0;
  // The points relative to fo_, in float, same order: x, y, z arrays of stride_ = n + kPad
  // (padded for whole-vector loads) in one block (one mapping, see HugeAllocator).
  HugeVector<float> coords_;
  size_t stride_ = 0;
  P3 fo_{0, 0, 0}; // origin of the float coordinates: the centre of the bulk
  std::vector<std::uint32_t> order_;
  HugeVector<Slot> table_;
  // Bricks of 4×4×4 cells over the bulk's box, aligned, so that a brick's points are contiguous
  // and the low 6 bits of a cell's key are its place in the brick. brickOf_: per brick of that
  // box (x-major, from brickLo_), 1 + its index among the occupied bricks, 0 when empty;
  // brickBase_: an occupied brick's first point; brickOff_: 65 offsets from it per brick, where
  // its 64 cells begin in Morton order (the last one: its end). A lookup is three loads, without
  // hashing or probing. Cells outside that box, when there are any, are in table_ (which then
  // holds every cell).
  HugeVector<std::uint32_t> brickOf_, brickBase_;
  HugeVector<std::uint16_t> brickOff_;
  std::int64_t brickDim_[3] = {0, 0, 0}; // bricks per axis
  std::int64_t brickLo_[3] = {0, 0, 0};  // first cell of the bricks' box (a multiple of 4)
  std::int64_t brickCellLo_[3] = {0, 0, 0}, brickCellHi_[3] = {-1, -1, -1}; // its cells, inclusive
  // brickOf_[brickIndex(X, Y, Z) − brickBias_] is the entry of brick (X, Y, Z) of the range.
  size_t brickBias_ = 0;
  bool bricksOnly_ = false; // every point in the bricks: visitCells' fast path
  size_t brickIndex(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<size_t>((x * brickDim_[1] + y) * brickDim_[2] + z);
  }
  bool buildBricks(const HugeVector<std::uint64_t>& sortedKeys, size_t cellPoints);
  void buildTable(const HugeVector<std::uint64_t>& sortedKeys, size_t cellPoints);
  void splitCrowdedCells(const HugeVector<std::uint64_t>& sortedKeys, size_t cellPoints);
  // Per point of a split cell, the Morton code of its sub-cell (see visitSplit); empty when no
  // cell is split.
  HugeVector<std::uint64_t> sub_;
  size_t splitCells_ = 0;
  Box3d box_, bulk_;
  P3 origin_{0, 0, 0}; // corner of cell (0, 0, 0)
  double cell_ = 1, inv_ = 1;
  std::int64_t maxCell_[3] = {-1, -1, -1};
  size_t cells_ = 0, mask_ = 0, farBegin_ = 0;
  int blockShift_ = 63;
  std::uint64_t* visited_ = nullptr;
};

template <class Rank>
std::int64_t PointIndex::nearestBy(const P3& c, double maxRadius, double* squaredDistance, Rank&& rank) const {
  if (pts_.empty()) return -1;
  // Balls of doubling radius: once the best point found lies within the ball's radius, every
  // closer point was visited too.
  const double reach = (c - box_.Center()).Norm() + 0.5 * box_.Diag() + cell_;
  // Start at a quarter cell: cells are several spacings wide.
  double radius = std::min(0.25 * cell_, maxRadius);
  for (;;) {
    std::int64_t best = -1, bestRank = -1;
    double bestD2 = std::numeric_limits<double>::infinity();
    forEachInBall(c, radius, [&](std::uint32_t i, double d2) {
      const std::int64_t r = rank(i);
      if (r < 0) return;
      if (d2 < bestD2 || (d2 == bestD2 && r < bestRank)) {
        bestD2 = d2;
        best = i;
        bestRank = r;
      }
    });
    if (best >= 0 || radius >= maxRadius || radius >= reach) {
      if (best >= 0 && squaredDistance != nullptr) *squaredDistance = bestD2;
      return best;
    }
    radius = std::min(2.0 * radius, maxRadius);
  }
}

} // namespace growth
