#pragma once
// Spatial hashing of the points for Robust G2S (sec. 3 step 2: "an original hash table data
// structure ... which makes possible a more efficient search for the nearest neighbourhoods").
//
// The grid *owns* the points and stores them sorted by cell, cells in Morton (Z-curve) order: the
// index of a point in the grid is its index everywhere in the mesher, so per-point arrays are laid
// out in space-filling-curve order and the advancing front walks memory coherently. Building is
// one stable LSD radix sort of the 63-bit cell keys. A query finds each cell's point range through
// bricks of 4×4×4 cells (an index over the box's bricks, then 16-bit offsets inside an occupied
// brick: three loads, no hashing) when the box holds at most one brick per point, as it does for
// points on a surface; otherwise it probes an open-addressing table whose 16-byte entries hold the
// cell key and its point range. Either way only occupied cells (bricks) carry ranges, so memory
// grows with the cloud, not with its bounding box. Coordinates are scanned contiguously.
//
// Compared with growth::PointGrid (separate key/start arrays, x-major order that is not the
// caller's point order, a second sort for a spatial order) this removes a build and two memory
// indirections per cell; tools/g2s_grid_bench.cpp measures both and vcglib's GridStaticPtr on the
// mesher's query pattern.
#include "g2s_near.h"

#include <growth/huge_pages.h>
#include <growth/morton.h>

#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

#if defined(__SSE2__)
#include <emmintrin.h>
#endif

namespace growth {
namespace g2s {

class MortonGrid {
public:
  using P3 = vcg::Point3d;

  // Takes the points (finite), sorts them into cell order with cubic cells of side `cellSize`
  // (enlarged when the box would need more than 2^21 cells along an axis). order()[i] is then
  // the caller's index of the point now at i.
  void build(std::vector<P3> points, double cellSize);

  size_t size() const { return pts_.size(); }
  const std::vector<P3>& points() const { return pts_; }
  const P3& point(std::uint32_t i) const { return pts_[i]; }
  const std::vector<std::uint32_t>& order() const { return order_; }
  // Replaces order() (after rebuilding the grid from its own points, to keep the caller's indices).
  void setOrder(std::vector<std::uint32_t> order) { order_.swap(order); }
  // Frees the search structure (float copies and cell table), keeping points() and order(): no
  // query may follow. For the output step, so that its memory peak does not add up with the search's.
  void releaseSearch() {
    HugeVector<float>().swap(coords_);
    HugeVector<Slot>().swap(table_);
    HugeVector<std::uint32_t>().swap(brickOf_);
    HugeVector<std::uint32_t>().swap(brickBase_);
    HugeVector<std::uint16_t>().swap(brickOff_);
  }
  // Frees the points too: only order() is left (size() is then 0).
  void releasePoints() { std::vector<P3>().swap(pts_); }
  double cellSize() const { return cell_; }
  size_t cellCount() const { return cells_; }
  // Cells are looked up through bricks (compact clouds) rather than the hash table.
  bool usesBricks() const { return !brickOf_.empty(); }
  const vcg::Box3d& box() const { return box_; }

  // Calls f(index, squaredDistance) for every point with |p − c| <= radius, cell by cell.
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
  // The points forEachNearBall(c, radius) visits, in the same order, written to `out` (cleared
  // first) with their float coordinates, by the vector scans of g2s_near.h.
  void gatherNear(const P3& c, double radius, NearList& out) const {
    out.clear();
    if (pts_.empty() || !(radius >= 0)) return;
    const double slack = floatSlack(c, radius);
    const float r2f = float((radius + slack) * (radius + slack));
    float fc[3];
    toFloat(c, fc);
    const float* fx = coords_.data();
    // The cells' ranges are collected first and scanned in one call (one call per cell costs as
    // much as the scan of a small cell).
    constexpr std::size_t kBatch = 32;
    std::uint32_t range[2 * kBatch];
    std::size_t ranges = 0, points = 0;
    auto flush = [&]() {
      out.appendWithin(fx, fx + stride_, fx + 2 * stride_, range, ranges, points, fc, r2f);
      ranges = points = 0;
    };
    visitCells(c, radius, [&](std::uint32_t begin, std::uint32_t end) {
      if (ranges == kBatch) flush();
      range[2 * ranges] = begin;
      range[2 * ranges + 1] = end;
      ++ranges;
      points += end - begin;
      return false;
    });
    if (ranges > 0) flush();
  }
  // The point's coordinates relative to floatOrigin(), in float.
  float fx(std::uint32_t i) const { return coords_[i]; }
  float fy(std::uint32_t i) const { return coords_[stride_ + i]; }
  float fz(std::uint32_t i) const { return coords_[2 * stride_ + i]; }
  // A bound on the error of a distance between c and a point within `radius` of it computed from
  // float coordinates (the point's fx/fy/fz, c's from toFloat). Rounding to float errs by at most
  // 2^-24 of a coordinate's magnitude, and both coordinates are at most |c − origin|∞ + radius (+
  // the slack itself) from the origin: 2·√3·2^-24·(|c − origin|∞ + 2·radius) bounds the error,
  // taken four times for the float arithmetic and margin. The origin is in the bulk of the cloud
  // (the centre of growth::robustBox), so a far point costs no precision near the others.
  double floatSlack(const P3& c, double radius) const {
    constexpr double kSlackPerMagnitude = 8.0 * 1.7320508075688772 / 16777216.0; // 8·√3·2^-24
    const double m = std::max(std::abs(c[0] - fo_[0]), std::max(std::abs(c[1] - fo_[1]), std::abs(c[2] - fo_[2])));
    return kSlackPerMagnitude * (m + 2.0 * radius) + 1e-300;
  }
  const P3& floatOrigin() const { return fo_; }
  void toFloat(const P3& c, float out[3]) const {
    for (int a = 0; a < 3; ++a) out[a] = float(c[a] - fo_[a]);
  }

  // Calls stop(index, squaredDistance) for the points with |p − c| <= radius until it returns
  // true; returns whether it did (early exit for emptiness tests).
  template <class F>
  bool anyInBall(const P3& c, double radius, F&& stop) const {
    return visitBall(c, radius, stop);
  }

  // The point nearest to c other than `exclude`, within maxRadius; -1 when there is none.
  std::int64_t nearest(const P3& c, std::int64_t exclude = -1,
                       double maxRadius = std::numeric_limits<double>::infinity(),
                       double* squaredDistance = nullptr) const;

  // For every point whose caller index order()[i] is a multiple of `stride`: squared[order()[i] /
  // stride] = the squared distance to its nearest other point (-1 when there is none), the values
  // growth::PointGrid::nearestOtherSquaredDistances gives over the caller's array.
  void nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared) const;

  size_t memoryBytes() const {
    return pts_.capacity() * sizeof(P3) + coords_.capacity() * sizeof(float) +
           order_.capacity() * sizeof(std::uint32_t) +
           table_.capacity() * sizeof(Slot) + (brickOf_.capacity() + brickBase_.capacity()) * sizeof(std::uint32_t) +
           brickOff_.capacity() * sizeof(std::uint16_t);
  }

  // Morton code helpers (public for the tests).
  static std::uint64_t spread(std::uint64_t x) { return mortonSpread(x); }
  static std::uint64_t morton(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
    return mortonCode(x, y, z);
  }

private:
  static constexpr std::int64_t kMaxCoord = (std::int64_t(1) << 21) - 1;
  static constexpr std::uint64_t kEmpty = ~std::uint64_t(0);
  static constexpr std::int64_t kMaxSpan = 16; // cells per axis handled by the fast query loop

  struct Slot {
    std::uint64_t key = kEmpty;
    std::uint32_t begin = 0, end = 0;
  };

  // Cell coordinate of v along an axis: -1 below the box, kMaxCoord + 1 far above (truncation
  // equals floor for the non-negative values that matter; callers clamp to [0, maxCell_]).
  std::int64_t coord(double v, int axis) const {
    const double c = (v - box_.min[axis]) * inv_;
    return c < 0 ? -1 : (c > double(kMaxCoord) ? kMaxCoord + 1 : static_cast<std::int64_t>(c));
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
    const double slack = floatSlack(c, radius);
    const float r2f = float((radius + slack) * (radius + slack));
    float fc[3];
    toFloat(c, fc);
    return visitCells(c, radius, [&](std::uint32_t begin, std::uint32_t end) {
      return scanCell<Exact>(begin, end, c, fc, r2, r2f, stop);
    });
  }

  // Calls cell(begin, end) for the point range of every occupied cell that the ball's bounding
  // box touches, until it returns true; returns whether it did.
  template <class F>
  bool visitCells(const P3& c, double radius, F&& cell) const {
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::max<std::int64_t>(coord(c[a] - radius, a), 0);
      hi[a] = std::min<std::int64_t>(coord(c[a] + radius, a), maxCell_[a]);
      if (lo[a] > hi[a]) return false;
    }
    if (!brickOf_.empty()) {
      if (double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1) > double(cells_)) {
        // More cells in the box than occupied ones: walk the occupied cells instead.
        for (size_t b = 0; b < brickBase_.size(); ++b)
          for (int k = 0; k < 64; ++k) {
            const std::uint16_t* off = &brickOff_[b * 65 + size_t(k)];
            if (off[0] != off[1] && cell(brickBase_[b] + off[0], brickBase_[b] + off[1])) return true;
          }
        return false;
      }
      // Morton place of a cell in its brick from the low two bits of each coordinate.
      static constexpr unsigned kPlace[4] = {0, 1, 8, 9};
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
          const size_t row = brickIndex(x >> 2, y >> 2, 0);
          const unsigned xy = kPlace[x & 3] | kPlace[y & 3] << 1;
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
            const std::uint32_t b = brickOf_[row + size_t(z >> 2)];
            if (b == 0) continue;
            const std::uint16_t* off = &brickOff_[size_t(b - 1) * 65 + (xy | kPlace[z & 3] << 2)];
            if (off[0] != off[1] && cell(brickBase_[b - 1] + off[0], brickBase_[b - 1] + off[1])) return true;
          }
        }
      return false;
    }
    // Morton bits of each cell coordinate in the (small) ranges, computed once per query.
    std::uint64_t ky[kMaxSpan], kz[kMaxSpan];
    if (hi[1] - lo[1] >= kMaxSpan || hi[2] - lo[2] >= kMaxSpan) return visitCellsWide(lo, hi, cell);
    for (std::int64_t y = lo[1]; y <= hi[1]; ++y) ky[y - lo[1]] = spread(std::uint64_t(y)) << 1;
    for (std::int64_t z = lo[2]; z <= hi[2]; ++z) kz[z - lo[2]] = spread(std::uint64_t(z)) << 2;
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x) {
      const std::uint64_t kx = spread(std::uint64_t(x));
      for (std::int64_t y = 0; y <= hi[1] - lo[1]; ++y) {
        const std::uint64_t kxy = kx | ky[y];
        for (std::int64_t z = 0; z <= hi[2] - lo[2]; ++z) {
          const Slot* s = find(kxy | kz[z]);
          if (s == nullptr) continue;
          if (cell(s->begin, s->end)) return true;
        }
      }
    }
    return false;
  }

  // Balls spanning many cells (seldom: large seed balls, the cylinder walk on coarse clouds).
  template <class F>
  bool visitCellsWide(const std::int64_t* lo, const std::int64_t* hi, F&& cell) const {
    if (double(hi[0] - lo[0] + 1) * double(hi[1] - lo[1] + 1) * double(hi[2] - lo[2] + 1) > double(cells_)) {
      // More cells in the box than occupied ones: walk the occupied cells instead.
      for (const Slot& s : table_) {
        if (s.key == kEmpty) continue;
        if (cell(s.begin, s.end)) return true;
      }
      return false;
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          const Slot* s = find(morton(std::uint64_t(x), std::uint64_t(y), std::uint64_t(z)));
          if (s != nullptr && cell(s->begin, s->end)) return true;
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
    // The coordinate arrays are padded (kNearPad), so the last, partial block of a cell is loaded
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
  // The points relative to fo_, in float, same order: x, y, z arrays of stride_ = n + kNearPad
  // (padded for whole-vector loads) in one block (one mapping, see HugeAllocator).
  HugeVector<float> coords_;
  size_t stride_ = 0;
  P3 fo_{0, 0, 0}; // origin of the float coordinates: the centre of the bulk of the points
  std::vector<std::uint32_t> order_;
  HugeVector<Slot> table_;
  // The alternative to table_ (then empty) when compact: bricks of 4×4×4 cells, aligned, so that
  // a brick's points are contiguous and the low 6 bits of a cell's key are its place in the brick.
  // brickOf_: per brick of the box (x-major), 1 + its index among the occupied bricks, 0 when
  // empty; brickBase_: an occupied brick's first point; brickOff_: 65 offsets from it per brick,
  // where its 64 cells begin in Morton order (the last one: its end). A lookup is three loads,
  // without hashing or probing.
  HugeVector<std::uint32_t> brickOf_, brickBase_;
  HugeVector<std::uint16_t> brickOff_;
  std::int64_t brickDim_[3] = {0, 0, 0};
  size_t brickIndex(std::int64_t x, std::int64_t y, std::int64_t z) const {
    return static_cast<size_t>((x * brickDim_[1] + y) * brickDim_[2] + z);
  }
  bool buildBricks(const HugeVector<std::uint64_t>& sortedKeys);
  vcg::Box3d box_;
  double cell_ = 1, inv_ = 1;
  std::int64_t maxCell_[3] = {-1, -1, -1};
  size_t cells_ = 0, mask_ = 0;
  int blockShift_ = 63;
};

} // namespace g2s
} // namespace growth
