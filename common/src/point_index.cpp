#include <growth/cloud_scale.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/parallel.h>
#include <growth/point_index.h>

#include <algorithm>
#include <utility>

namespace growth {

// std::min/max bind their arguments to references, which odr-uses the member: C++14 needs a
// definition (clang at -O1 with the sanitizers does not fold the call).
constexpr std::int64_t PointIndex::kMaxCoord;

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

bool finite(const Vec3d& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
} // namespace

void PointIndex::build(std::vector<P3> points, double cellSize) {
  builtSize_ = points.size();
  pts_.clear();
  coords_.clear();
  stride_ = 0;
  order_.clear();
  table_.clear();
  brickOf_.clear();
  brickBase_.clear();
  brickOff_.clear();
  sub_.clear();
  splitCells_ = 0;
  bricksOnly_ = false;
  cells_ = 0;
  farBegin_ = 0;
  box_.SetNull();
  bulk_.SetNull();
  // Non-finite points are dropped; `source` then maps the kept ones to the caller's indices.
  std::vector<std::uint32_t> source;
  if (!std::all_of(points.begin(), points.end(), finite)) {
    size_t kept = 0;
    for (size_t i = 0; i < points.size(); ++i) {
      if (!finite(points[i])) continue;
      source.push_back(std::uint32_t(i));
      points[kept++] = points[i];
    }
    points.resize(kept);
  }
  const size_t n = points.size();
  for (const P3& p : points) box_.Add(p);
  if (n == 0) return;

  // The bulk (growth::robustBox on a sample: any box around most points would do) anchors the
  // cells and the float coordinates.
  bulk_ = robustBox(points, 1024);
  fo_ = bulk_.Center();
  const double boxExtent = std::max(box_.DimX(), std::max(box_.DimY(), box_.DimZ()));
  const double bulkExtent = std::min(boxExtent, std::max(bulk_.DimX(), std::max(bulk_.DimY(), bulk_.DimZ())));
  cell_ = std::max(cellSize, bulkExtent / double(kMaxCoord - 1));
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = boxExtent / double(kMaxCoord - 1);
  if (!(cell_ > 0) || !std::isfinite(cell_)) cell_ = 1.0; // all points identical
  inv_ = 1.0 / cell_;
  // 2^21 cells per axis from the box's corner, or centred on the bulk when the box is larger.
  for (int a = 0; a < 3; ++a) origin_[a] = std::max(box_.min[a], fo_[a] - 0.5 * double(kMaxCoord) * cell_);
  for (int a = 0; a < 3; ++a) maxCell_[a] = std::min(coord(box_.max[a], a), kMaxCoord);

  // Cell keys, sorted with the point indices by a stable LSD radix sort on 16-bit digits (8-bit
  // digits below 2^17 points, where a 65536-entry count table would cost more than the passes;
  // the sorted order is the same) and only over the digits the keys use: equal keys keep the
  // input order, so the result is deterministic. Points beyond the 2^21 cells (far points) take
  // the key after the largest, so they come last, in input order. Keys below 2^32 — every cloud
  // whose box spans fewer than 2^10 cells per axis — are packed with the index into one 64-bit
  // word (half the memory of separate arrays).
  HugeVector<std::uint64_t> key;
  assignHuge(key, n, std::uint64_t(0));
  std::uint64_t maxKey = 0;
  size_t far = 0;
  for (size_t i = 0; i < n; ++i) {
    std::int64_t c[3];
    bool inRange = true;
    for (int a = 0; a < 3; ++a) {
      c[a] = coord(points[i][a], a);
      inRange &= c[a] >= 0 && c[a] <= kMaxCoord;
    }
    if (!inRange) {
      key[i] = kEmpty;
      ++far;
      continue;
    }
    key[i] = morton(std::uint64_t(c[0]), std::uint64_t(c[1]), std::uint64_t(c[2]));
    maxKey = std::max(maxKey, key[i]);
  }
  if (far > 0) {
    ++maxKey;
    for (size_t i = 0; i < n; ++i)
      if (key[i] == kEmpty) key[i] = maxKey;
  }
  farBegin_ = n - far;
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
  for (size_t i = 0; i < farBegin_; ++i) cells_ += (i == 0 || key[i] != key[i - 1]);
  splitCrowdedCells(key, farBegin_);
  if (!source.empty())
    for (std::uint32_t& o : order_) o = source[o];

  stride_ = n + kPad; // padded for whole-vector loads
  assignHuge(coords_, 3 * stride_, std::numeric_limits<float>::max());
  float* fx = coords_.data();
  float* fy = fx + stride_;
  float* fz = fy + stride_;
  for (size_t i = 0; i < n; ++i) {
    fx[i] = float(pts_[i][0] - fo_[0]);
    fy[i] = float(pts_[i][1] - fo_[1]);
    fz[i] = float(pts_[i][2] - fo_[2]);
  }

  // Cell lookups: bricks of 4×4×4 cells over the bulk where that is compact (see brickOf_), and
  // a hash table of the occupied cells when some lie outside the bricks.
  if (!buildBricks(key, farBegin_)) buildTable(key, farBegin_);
  // The common case of a cloud on a surface without far points: every point in the bricks.
  bricksOnly_ = !brickOf_.empty() && table_.empty() && farBegin_ == pts_.size();
}

void PointIndex::splitCrowdedCells(const HugeVector<std::uint64_t>& key, size_t cellPoints) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> code; // (sub-cell code, place in the cell)
  std::vector<P3> pts;
  std::vector<std::uint32_t> ord;
  for (size_t i = 0; i < cellPoints;) {
    size_t j = i + 1;
    while (j < cellPoints && key[j] == key[i]) ++j;
    if (j - i > kSplitPoints) {
      if (sub_.empty()) assignHuge(sub_, pts_.size(), std::uint64_t(0));
      ++splitCells_;
      // The sub-cell of each point at 2^kSplitBits per axis, from the same arithmetic as coord().
      code.clear();
      constexpr double kSubCells = double(std::int64_t(1) << kSplitBits);
      for (size_t k = i; k < j; ++k) {
        std::uint64_t s[3];
        for (int a = 0; a < 3; ++a) {
          const double t = (pts_[k][a] - origin_[a]) * inv_;
          const double f = (t - std::floor(t)) * kSubCells;
          s[a] = std::uint64_t(std::min(kSubCells - 1, std::max(0.0, std::floor(f))));
        }
        code.emplace_back(morton(s[0], s[1], s[2]), std::uint32_t(k - i));
      }
      std::stable_sort(code.begin(), code.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      pts.assign(pts_.begin() + std::ptrdiff_t(i), pts_.begin() + std::ptrdiff_t(j));
      ord.assign(order_.begin() + std::ptrdiff_t(i), order_.begin() + std::ptrdiff_t(j));
      for (size_t k = 0; k < j - i; ++k) {
        pts_[i + k] = pts[code[k].second];
        order_[i + k] = ord[code[k].second];
        sub_[i + k] = code[k].first;
      }
    }
    i = j;
  }
}

bool PointIndex::buildBricks(const HugeVector<std::uint64_t>& key, size_t n) {
  if (n == 0) return true; // only far points: no cell at all
  // The bricks of the bulk's box (clamped to the occupied cells).
  std::int64_t dim[3];
  double boxBricks = 1;
  for (int a = 0; a < 3; ++a) {
    const std::int64_t lo = std::min(std::max<std::int64_t>(coord(bulk_.min[a], a), 0), maxCell_[a]);
    const std::int64_t hi = std::min(std::max<std::int64_t>(coord(bulk_.max[a], a), 0), maxCell_[a]);
    brickLo_[a] = (lo >> 2) << 2;
    dim[a] = (hi >> 2) - (lo >> 2) + 1;
    boxBricks *= double(dim[a]);
  }
  // At most 4 bytes per point for the brick index of the box (a surface's box holds far fewer
  // bricks than points), and offsets that fit 16 bits.
  if (boxBricks > double(n)) return false;
  auto inside = [&](std::uint64_t brick, std::int64_t* b) {
    b[0] = std::int64_t(mortonCompact(brick)) - (brickLo_[0] >> 2);
    b[1] = std::int64_t(mortonCompact(brick >> 1)) - (brickLo_[1] >> 2);
    b[2] = std::int64_t(mortonCompact(brick >> 2)) - (brickLo_[2] >> 2);
    return b[0] >= 0 && b[1] >= 0 && b[2] >= 0 && b[0] < dim[0] && b[1] < dim[1] && b[2] < dim[2];
  };
  size_t bricks = 0;
  bool outside = false;
  for (size_t i = 0; i < n;) {
    size_t j = i + 1;
    while (j < n && (key[j] >> 6) == (key[i] >> 6)) ++j;
    std::int64_t b[3];
    if (inside(key[i] >> 6, b)) {
      if (j - i > 65535) return false;
      ++bricks;
    } else {
      outside = true;
    }
    i = j;
  }
  for (int a = 0; a < 3; ++a) {
    brickDim_[a] = dim[a];
    brickCellLo_[a] = brickLo_[a];
    brickCellHi_[a] = brickLo_[a] + 4 * dim[a] - 1;
  }
  assignHuge(brickOf_, static_cast<size_t>(boxBricks), 0u);
  brickBias_ = brickIndex(brickLo_[0] >> 2, brickLo_[1] >> 2, brickLo_[2] >> 2);
  assignHuge(brickBase_, bricks, 0u);
  assignHuge(brickOff_, bricks * 65, std::uint16_t(0));
  size_t b = 0;
  for (size_t i = 0; i < n;) {
    const std::uint64_t brick = key[i] >> 6;
    size_t j = i;
    std::int64_t at[3];
    if (!inside(brick, at)) {
      while (j < n && (key[j] >> 6) == brick) ++j;
      i = j;
      continue;
    }
    brickOf_[brickIndex(at[0], at[1], at[2])] = static_cast<std::uint32_t>(b + 1); // (at: from brickLo_)
    brickBase_[b] = static_cast<std::uint32_t>(i);
    std::uint16_t* off = &brickOff_[b * 65];
    for (; j < n && (key[j] >> 6) == brick; ++j) ++off[(key[j] & 63) + 1];
    for (int c = 0; c < 64; ++c) off[c + 1] = static_cast<std::uint16_t>(off[c + 1] + off[c]);
    i = j;
    ++b;
  }
  // Cells outside the bricks (far from the bulk) are found through the table, which holds them all.
  if (outside) buildTable(key, n);
  return true;
}

void PointIndex::buildTable(const HugeVector<std::uint64_t>& key, size_t n) {
  size_t cap = 16;
  while (cap < 4 * cells_) cap *= 2; // load <= 1/4: clustered keys make short probe runs
  mask_ = cap - 1;
  blockShift_ = 64 + 3; // 64 − log2(cap / 8)
  for (size_t c = cap; c > 1; c >>= 1) --blockShift_;
  assignHuge(table_, cap, Slot());
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

void PointIndex::nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared, int threads) const {
  stride = std::max<size_t>(stride, 1);
  const size_t n = pts_.size();
  squared.assign(builtSize_ == 0 ? 0 : (builtSize_ - 1) / stride + 1, -1.0);
  // In index order, so that consecutive queries touch the same cells; each value goes to its own
  // slot, so the parts do not interact.
  const int parts = parallelParts(n, threads, 4096);
  parallelFor(n, parts, [&](size_t begin, size_t end, int) {
    for (size_t i = begin; i < end; ++i) {
      if (order_[i] % stride != 0) continue;
      double d2 = -1;
      if (nearest(pts_[i], std::int64_t(i), std::numeric_limits<double>::infinity(), &d2) >= 0)
        squared[order_[i] / stride] = d2;
    }
  });
}

} // namespace growth
