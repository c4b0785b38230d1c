#pragma once
// A static spatial hash of points for nearest-neighbour and range queries.
//
// Only occupied cells are stored (an open-addressing hash from cell key to a cell slot), and the
// points are kept sorted by cell with their coordinates copied in that order, so a query walks
// contiguous memory. Memory grows with the number of points, never with the bounding box.
// Robust G2S, sec. 3 step 2 ("an original hash table data structure ... for the search of the
// nearest neighbourhoods"); the sphere packer uses the same hashing idea for its box grid.
#include <growth/huge_pages.h>

#include <vcg/space/point3.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace growth {

class PointGrid {
public:
  using Point = vcg::Point3d;

  PointGrid() = default;

  // Builds the grid over `points` (indices refer to this array) with cubic cells of side cellSize.
  // Non-finite points are skipped (never returned by queries).
  void build(const std::vector<Point>& points, double cellSize);

  size_t pointCount() const { return pointIndex_.size(); }
  size_t cellCount() const { return cellKey_.size(); }
  double cellSize() const { return cell_; }

  // Calls f(index, squaredDistance) for every point with |p - c| <= radius.
  template <class F>
  void forEachInBall(const Point& c, double radius, F&& f) const;
  // The same visit, stopped as soon as f returns false (bounded work in dense clusters); returns
  // false when it was stopped.
  template <class F>
  bool forEachInBallWhile(const Point& c, double radius, F&& f) const;

  // Index of the point closest to c, or -1 when the grid is empty. `exclude` is skipped.
  // `maxRadius` bounds the search (a point farther away is not returned).
  int nearest(const Point& c, double* squaredDistance = nullptr, int exclude = -1,
              double maxRadius = std::numeric_limits<double>::infinity()) const;

  // For every point of the grid whose index i (into the built array) is a multiple of `stride`:
  // squared[i / stride] = the squared distance to its nearest other point, bit for bit what
  // nearest(points[i], &d2, i) gives (-1 when there is none; `squared` is resized to cover every
  // multiple below the built array's size, and non-finite points keep -1). Computed cell by cell:
  // the points of a cell share the look-up of the 27 cells around it, and only the few whose
  // answer the ring search would look beyond those take nearest(). Runs on `threads` threads
  // (0 = automatic, parallel.h); the result is the same for any number.
  void nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared, int threads = 0) const;

  // Memory held by the grid, in bytes (for the benchmark's memory accounting).
  size_t memoryBytes() const;

private:
  using Key = std::uint64_t;
  static constexpr int kBits = 21;
  static constexpr std::int64_t kMaxCoord = (std::int64_t(1) << kBits) - 1;

  std::int64_t coord(double v, double origin) const {
    return static_cast<std::int64_t>(std::floor((v - origin) * inv_));
  }
  static Key pack(std::int64_t x, std::int64_t y, std::int64_t z) {
    return (Key(x) << (2 * kBits)) | (Key(y) << kBits) | Key(z);
  }
  // Fibonacci hashing: the top bits of the product depend on every bit of the key (bits 17 and
  // up, taken before, ignored a cell's x for tables below 2^25 slots: cells differing only in x
  // probed one run of slots).
  size_t hash(Key k) const { return static_cast<size_t>((k * 0x9E3779B97F4A7C15ull) >> shift_); }
  // Slot of a cell in cellStart_/cellKey_, or -1 when the cell is empty.
  std::int64_t findCell(std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (x < 0 || y < 0 || z < 0 || x > maxCell_[0] || y > maxCell_[1] || z > maxCell_[2]) return -1;
    const Key k = pack(x, y, z);
    size_t h = hash(k);
    for (;;) {
      const std::int64_t slot = table_[h];
      if (slot < 0) return -1;
      if (cellKey_[static_cast<size_t>(slot)] == k) return slot;
      h = (h + 1) & mask_;
    }
  }

  double cell_ = 1.0, inv_ = 1.0;
  Point origin_{0, 0, 0};
  size_t builtSize_ = 0;               // size of the array the grid was built over
  std::int64_t maxCell_[3] = {-1, -1, -1};
  std::vector<Key> cellKey_;           // per occupied cell
  std::vector<std::uint32_t> cellStart_; // CSR offsets into the sorted arrays, size cells+1
  std::vector<std::int64_t> table_;    // open addressing: slot of a cell, -1 when free
  size_t mask_ = 0;
  int shift_ = 63;                     // 64 − log2(table size)
  // Written once, point by point: huge pages (large clouds pay a page fault per 4 KiB otherwise).
  HugeVector<Point> sortedPoint_;      // coordinates in cell order
  HugeVector<std::uint32_t> pointIndex_; // original index, in cell order
};

template <class F>
void PointGrid::forEachInBall(const Point& c, double radius, F&& f) const {
  forEachInBallWhile(c, radius, [&f](int i, double d2) {
    f(i, d2);
    return true;
  });
}

template <class F>
bool PointGrid::forEachInBallWhile(const Point& c, double radius, F&& f) const {
  if (cellKey_.empty() || !(radius >= 0)) return true;
  const double r2 = radius * radius;
  const std::int64_t x0 = coord(c[0] - radius, origin_[0]), x1 = coord(c[0] + radius, origin_[0]);
  const std::int64_t y0 = coord(c[1] - radius, origin_[1]), y1 = coord(c[1] + radius, origin_[1]);
  const std::int64_t z0 = coord(c[2] - radius, origin_[2]), z1 = coord(c[2] + radius, origin_[2]);
  for (std::int64_t x = std::max<std::int64_t>(x0, 0); x <= std::min(x1, maxCell_[0]); ++x)
    for (std::int64_t y = std::max<std::int64_t>(y0, 0); y <= std::min(y1, maxCell_[1]); ++y)
      for (std::int64_t z = std::max<std::int64_t>(z0, 0); z <= std::min(z1, maxCell_[2]); ++z) {
        const std::int64_t slot = findCell(x, y, z);
        if (slot < 0) continue;
        const size_t b = cellStart_[static_cast<size_t>(slot)], e = cellStart_[static_cast<size_t>(slot) + 1];
        for (size_t i = b; i < e; ++i) {
          const Point& p = sortedPoint_[i];
          const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
          const double d2 = dx * dx + dy * dy + dz * dz;
          if (d2 <= r2 && !f(static_cast<int>(pointIndex_[i]), d2)) return false;
        }
      }
  return true;
}

} // namespace growth
