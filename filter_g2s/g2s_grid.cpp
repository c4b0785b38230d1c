#include "g2s_grid.h"

#include <growth/huge_pages.h>

#include <algorithm>

namespace growth {
namespace g2s {

// The definition C++14 needs for a static constexpr member bound to a reference (std::min).
constexpr std::int64_t MortonGrid::kMaxCoord;

namespace {
// Inverse of mortonSpread: gathers every third bit (bit 3i to bit i).
std::uint64_t mortonCompact(std::uint64_t v) {
  v &= 0x1249249249249249ull;
  v = (v | v >> 2) & 0x10c30c30c30c30c3ull;
  v = (v | v >> 4) & 0x100f00f00f00f00full;
  v = (v | v >> 8) & 0x1f0000ff0000ffull;
  v = (v | v >> 16) & 0x1f00000000ffffull;
  v = (v | v >> 32) & 0x1fffff;
  return v;
}
} // namespace

void MortonGrid::build(std::vector<P3> points, double cellSize) {
  const size_t n = points.size();
  pts_.clear();
  coords_.clear();
  stride_ = 0;
  order_.clear();
  table_.clear();
  brickOf_.clear();
  brickBase_.clear();
  brickOff_.clear();
  cells_ = 0;
  box_.SetNull();
  for (const P3& p : points) box_.Add(p);
  if (n == 0) return;

  const double extent = std::max(box_.DimX(), std::max(box_.DimY(), box_.DimZ()));
  cell_ = std::max(cellSize, extent / double(kMaxCoord - 1));
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1.0; // all points identical
  inv_ = 1.0 / cell_;
  for (int a = 0; a < 3; ++a) maxCell_[a] = std::min(coord(box_.max[a], a), kMaxCoord);

  // Cell keys, sorted with the point indices by a stable LSD radix sort on 16-bit digits (8-bit
  // digits below 2^17 points, where a 65536-entry count table would cost more than the passes;
  // the sorted order is the same) and only over the digits the keys use: equal keys keep the
  // input order, so the result is deterministic. Keys below 2^32 — every cloud whose box spans fewer than 2^10 cells per axis —
  // are packed with the index into one 64-bit word (half the memory of separate arrays).
  HugeVector<std::uint64_t> key;
  assignHuge(key, n, std::uint64_t(0));
  std::uint64_t maxKey = 0;
  for (size_t i = 0; i < n; ++i) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::uint64_t(std::min(std::max<std::int64_t>(coord(points[i][a], a), 0), maxCell_[a]));
    key[i] = morton(c[0], c[1], c[2]);
    maxKey = std::max(maxKey, key[i]);
  }
  assignHuge(order_, n, 0u);
  const int digit = n < (size_t(1) << 17) ? 8 : 16;
  const size_t digits = size_t(1) << digit, mask = digits - 1;
  std::vector<std::uint32_t> count(digits + 1);
  auto radix = [&](HugeVector<std::uint64_t>& v, int firstShift, int endShift, auto&& digitOf) {
    HugeVector<std::uint64_t> tmp;
    assignHuge(tmp, n, std::uint64_t(0));
    for (int shift = firstShift; shift < endShift; shift += digit) {
      std::fill(count.begin(), count.end(), 0u);
      for (size_t i = 0; i < n; ++i) ++count[digitOf(v[i], shift) + 1];
      if (count[digitOf(v[0], shift) + 1] == n) continue; // every key has this digit: no-op pass
      for (size_t d = 0; d < digits; ++d) count[d + 1] += count[d];
      for (size_t i = 0; i < n; ++i) tmp[count[digitOf(v[i], shift)]++] = v[i];
      v.swap(tmp);
    }
  };
  if (maxKey < (std::uint64_t(1) << 32)) {
    for (size_t i = 0; i < n; ++i) key[i] = key[i] << 32 | i;
    int bits = 0;
    while (bits < 32 && (maxKey >> bits) != 0) bits += digit;
    radix(key, 32, 32 + bits, [mask](std::uint64_t k, int shift) { return size_t((k >> shift) & mask); });
    for (size_t i = 0; i < n; ++i) {
      order_[i] = std::uint32_t(key[i]);
      key[i] >>= 32;
    }
  } else {
    // Wide keys: sort (key, index) pairs through an index permutation.
    std::vector<std::uint32_t> idx(n), idxTmp(n);
    for (size_t i = 0; i < n; ++i) idx[i] = std::uint32_t(i);
    HugeVector<std::uint64_t> keyTmp(n);
    for (int shift = 0; shift < 64 && (maxKey >> shift) != 0; shift += digit) {
      std::fill(count.begin(), count.end(), 0u);
      for (size_t i = 0; i < n; ++i) ++count[((key[i] >> shift) & mask) + 1];
      for (size_t d = 0; d < digits; ++d) count[d + 1] += count[d];
      for (size_t i = 0; i < n; ++i) {
        const std::uint32_t to = count[(key[i] >> shift) & mask]++;
        keyTmp[to] = key[i];
        idxTmp[to] = idx[i];
      }
      key.swap(keyTmp);
      idx.swap(idxTmp);
    }
    order_.swap(idx);
  }

  // Points into cell order in place (cycle by cycle), so no second copy of them is ever made.
  pts_.swap(points);
  {
    std::vector<bool> done(n, false);
    for (size_t start = 0; start < n; ++start) {
      if (done[start]) continue;
      const P3 first = pts_[start];
      size_t j = start;
      for (;;) {
        done[j] = true;
        const size_t from = order_[j];
        if (from == start) {
          pts_[j] = first;
          break;
        }
        pts_[j] = pts_[from];
        j = from;
      }
    }
  }
  stride_ = n + kNearPad; // padded for whole-vector loads
  assignHuge(coords_, 3 * stride_, std::numeric_limits<float>::max());
  float* fx = coords_.data();
  float* fy = fx + stride_;
  float* fz = fy + stride_;
  for (size_t i = 0; i < n; ++i) {
    fx[i] = float(pts_[i][0] - box_.min[0]);
    fy[i] = float(pts_[i][1] - box_.min[1]);
    fz[i] = float(pts_[i][2] - box_.min[2]);
  }
  // Float rounding of a relative coordinate is at most 2^-24 of the extent; the query centre's
  // as well: a distance computed in float errs by less than 4·√3·2^-24·extent (with margin).
  floatSlack_ = 8.0 * std::sqrt(3.0) * std::ldexp(extent, -24) + 1e-300;

  for (size_t i = 0; i < n; ++i) cells_ += (i == 0 || key[i] != key[i - 1]);

  // Cell lookups: bricks of 4×4×4 cells where that is compact (see brickOf_), else a hash table of
  // the occupied cells.
  if (buildBricks(key)) return;
  size_t cap = 16;
  while (cap < 4 * cells_) cap *= 2; // load <= 1/4: clustered keys make short probe runs
  mask_ = cap - 1;
  blockShift_ = 64 + 3; // 64 − log2(cap / 8)
  for (size_t c = cap; c > 1; c >>= 1) --blockShift_;
  table_.assign(cap, Slot());
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && key[j] == key[i]) ++j;
    size_t h = slotOf(key[i]);
    while (table_[h].key != kEmpty) h = (h + 1) & mask_;
    table_[h].key = key[i];
    table_[h].begin = static_cast<std::uint32_t>(i);
    table_[h].end = static_cast<std::uint32_t>(j);
    i = j;
  }
}

bool MortonGrid::buildBricks(const HugeVector<std::uint64_t>& key) {
  const size_t n = key.size();
  std::int64_t dim[3];
  double boxBricks = 1;
  for (int a = 0; a < 3; ++a) {
    dim[a] = (maxCell_[a] >> 2) + 1;
    boxBricks *= double(dim[a]);
  }
  // At most 4 bytes per point for the brick index of the box (a surface's box holds far fewer
  // bricks than points), and offsets that fit 16 bits.
  if (boxBricks > double(n)) return false;
  size_t bricks = 0;
  for (size_t i = 0; i < n; ++bricks) {
    size_t j = i + 1;
    while (j < n && (key[j] >> 6) == (key[i] >> 6)) ++j;
    if (j - i > 65535) return false;
    i = j;
  }
  for (int a = 0; a < 3; ++a) brickDim_[a] = dim[a];
  assignHuge(brickOf_, static_cast<size_t>(boxBricks), 0u);
  assignHuge(brickBase_, bricks, 0u);
  assignHuge(brickOff_, bricks * 65, std::uint16_t(0));
  size_t b = 0;
  for (size_t i = 0; i < n; ++b) {
    const std::uint64_t brick = key[i] >> 6;
    brickOf_[brickIndex(std::int64_t(mortonCompact(brick)), std::int64_t(mortonCompact(brick >> 1)),
                        std::int64_t(mortonCompact(brick >> 2)))] = static_cast<std::uint32_t>(b + 1);
    brickBase_[b] = static_cast<std::uint32_t>(i);
    std::uint16_t* off = &brickOff_[b * 65];
    size_t j = i;
    for (; j < n && (key[j] >> 6) == brick; ++j) ++off[(key[j] & 63) + 1];
    for (int c = 0; c < 64; ++c) off[c + 1] = static_cast<std::uint16_t>(off[c + 1] + off[c]);
    i = j;
  }
  return true;
}

std::int64_t MortonGrid::nearest(const P3& c, std::int64_t exclude, double maxRadius, double* squaredDistance) const {
  if (pts_.empty()) return -1;
  // Balls of doubling radius: once the best point found lies within the ball's radius, every
  // closer point was visited too.
  const double reach = (c - box_.Center()).Norm() + 0.5 * box_.Diag() + cell_;
  // Start at a quarter cell: the mesher's cells are several spacings wide.
  double radius = std::min(0.25 * cell_, maxRadius);
  for (;;) {
    std::int64_t best = -1;
    double bestD2 = std::numeric_limits<double>::infinity();
    forEachInBall(c, radius, [&](std::uint32_t i, double d2) {
      if (std::int64_t(i) == exclude) return;
      if (d2 < bestD2 || (d2 == bestD2 && std::int64_t(i) < best)) {
        bestD2 = d2;
        best = i;
      }
    });
    if (best >= 0 || radius >= maxRadius || radius >= reach) {
      if (best >= 0 && squaredDistance != nullptr) *squaredDistance = bestD2;
      return best;
    }
    radius = std::min(2.0 * radius, maxRadius);
  }
}

} // namespace g2s
} // namespace growth
