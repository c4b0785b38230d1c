#include <growth/parallel.h>
#include <growth/point_grid.h>
#include <growth/radix_order.h>

#include <algorithm>
#include <limits>
#include <numeric>

namespace growth {

// The definition C++14 needs for a static constexpr member that is bound to a reference
// (std::min): without it the link fails when the compiler does not fold the call (clang -O1).
constexpr std::int64_t PointGrid::kMaxCoord;

void PointGrid::build(const std::vector<Point>& points, double cellSize) {
  cellKey_.clear();
  cellStart_.clear();
  table_.clear();
  sortedPoint_.clear();
  pointIndex_.clear();
  maxCell_[0] = maxCell_[1] = maxCell_[2] = -1;
  builtSize_ = points.size();
  if (!(cellSize > 0) || !std::isfinite(cellSize)) return;

  Point lo(std::numeric_limits<double>::max(), std::numeric_limits<double>::max(),
           std::numeric_limits<double>::max());
  Point hi = -lo;
  HugeVector<std::uint32_t> valid;
  valid.reserve(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Point& p = points[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) continue;
    valid.push_back(static_cast<std::uint32_t>(i));
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], p[a]);
      hi[a] = std::max(hi[a], p[a]);
    }
  }
  if (valid.empty()) return;

  // Cells coarser than asked when the box would need more than 2^21 cells along an axis.
  double extent = std::max(hi[0] - lo[0], std::max(hi[1] - lo[1], hi[2] - lo[2]));
  cell_ = std::max(cellSize, extent / double(kMaxCoord - 1));
  inv_ = 1.0 / cell_;
  origin_ = lo;
  for (int a = 0; a < 3; ++a) maxCell_[a] = std::min(coord(hi[a], lo[a]), kMaxCoord);

  // Points ordered by cell key, stably (equal keys keep the input order, so queries visit points
  // deterministically): an LSD radix sort on the key's bits that can differ (the cell coordinates
  // are at most maxCell_), the order std::stable_sort gives. The keys are kept compact: each
  // coordinate in its own width (the same order as the packed key).
  auto bitsOf = [](std::int64_t v) {
    int b = 0;
    while (b < 63 && (std::int64_t(1) << b) <= v) ++b;
    return b;
  };
  const int bx = bitsOf(maxCell_[0]), by = bitsOf(maxCell_[1]), bz = bitsOf(maxCell_[2]);
  HugeVector<std::uint64_t> compact(valid.size());
  for (size_t i = 0; i < valid.size(); ++i) {
    const Point& p = points[valid[i]];
    compact[i] = (std::uint64_t(std::min(coord(p[0], lo[0]), kMaxCoord)) << (by + bz)) |
                 (std::uint64_t(std::min(coord(p[1], lo[1]), kMaxCoord)) << bz) |
                 std::uint64_t(std::min(coord(p[2], lo[2]), kMaxCoord));
  }
  const std::uint64_t yMask = (std::uint64_t(1) << by) - 1, zMask = (std::uint64_t(1) << bz) - 1;
  auto keyOf = [&](std::uint64_t c) {
    return pack(std::int64_t(c >> (by + bz)), std::int64_t((c >> bz) & yMask), std::int64_t(c & zMask));
  };
  HugeVector<std::uint32_t> order;
  stableRadixOrder(compact.data(), compact.size(), bx + by + bz, order);

  sortedPoint_.resize(valid.size());
  pointIndex_.resize(valid.size());
  // The cells are counted first, so that their arrays are made resident in one call each
  // (huge_pages.h) instead of page by page as they grow.
  {
    size_t cells = 0;
    for (size_t i = 0; i < order.size(); ++i) cells += (i == 0 || compact[order[i]] != compact[order[i - 1]]) ? 1 : 0;
    reserveHuge(cellKey_, cells, /*populate=*/true);
    reserveHuge(cellStart_, cells + 1, /*populate=*/true);
  }
  for (size_t i = 0; i < order.size(); ++i) {
    const std::uint32_t j = order[i];
    sortedPoint_[i] = points[valid[j]];
    pointIndex_[i] = valid[j];
    if (i == 0 || compact[j] != compact[order[i - 1]]) {
      cellKey_.push_back(keyOf(compact[j]));
      cellStart_.push_back(static_cast<std::uint32_t>(i));
    }
  }
  cellStart_.push_back(static_cast<std::uint32_t>(order.size()));

  size_t cap = 16;
  shift_ = 60;
  while (cap < 2 * cellKey_.size()) cap *= 2, --shift_;
  mask_ = cap - 1;
  assignHuge(table_, cap, std::int64_t(-1));
  for (size_t s = 0; s < cellKey_.size(); ++s) {
    size_t h = hash(cellKey_[s]);
    while (table_[h] >= 0) h = (h + 1) & mask_;
    table_[h] = static_cast<std::int64_t>(s);
  }
}

int PointGrid::nearest(const Point& c, double* squaredDistance, int exclude, double maxRadius) const {
  if (cellKey_.empty()) return -1;
  const std::int64_t cx = coord(c[0], origin_[0]), cy = coord(c[1], origin_[1]), cz = coord(c[2], origin_[2]);
  int best = -1;
  double bestD2 = maxRadius * maxRadius;
  const std::int64_t maxRing =
      std::max({maxCell_[0], maxCell_[1], maxCell_[2]}) +
      std::max({std::abs(cx), std::abs(cy), std::abs(cz)}) + 1;
  auto scanCell = [&](size_t slot) {
    for (size_t i = cellStart_[slot], e = cellStart_[slot + 1]; i < e; ++i) {
      const int idx = static_cast<int>(pointIndex_[i]);
      if (idx == exclude) continue;
      const double d2 = (sortedPoint_[i] - c).SquaredNorm();
      if (d2 < bestD2 || (d2 == bestD2 && (best < 0 || idx < best))) {
        bestD2 = d2;
        best = idx;
      }
    }
  };
  // Distance from c to the outside of the block of cells within Chebyshev distance r of its cell:
  // every point not in that block is at least this far (at least r cells, more when c is not at
  // its cell's border), so the search stops as soon as the best point found is closer.
  double slack = std::numeric_limits<double>::infinity();
  for (int a = 0; a < 3; ++a) {
    const std::int64_t ca = a == 0 ? cx : (a == 1 ? cy : cz);
    const double lo = origin_[a] + double(ca) * cell_;
    slack = std::min({slack, c[a] - lo, lo + cell_ - c[a]});
  }
  slack = std::max(slack, 0.0);
  for (std::int64_t ring = 0; ring <= maxRing; ++ring) {
    if (ring > 0 && best >= 0) {
      const double reach = double(ring - 1) * cell_ + slack;
      if (bestD2 <= reach * reach) break;
    }
    if (ring > 0 && double(ring - 1) * cell_ > maxRadius) break;
    // Far from the points with small cells, a shell has more cells than the grid has occupied
    // ones: then visit the remaining occupied cells directly, pruned by their box distance.
    const double outer = 2.0 * double(ring) + 1, inner = 2.0 * double(ring) - 1;
    const double shellCells = outer * outer * outer - inner * inner * inner;
    if (ring > 1 && shellCells > double(cellKey_.size())) {
      for (size_t slot = 0; slot < cellKey_.size(); ++slot) {
        const Key k = cellKey_[slot];
        const std::int64_t x = std::int64_t(k >> (2 * kBits)), y = std::int64_t((k >> kBits) & Key(kMaxCoord)),
                           z = std::int64_t(k & Key(kMaxCoord));
        if (std::max({std::abs(x - cx), std::abs(y - cy), std::abs(z - cz)}) < ring) continue; // seen
        double box2 = 0;
        const std::int64_t cc[3] = {x, y, z};
        for (int a = 0; a < 3; ++a) {
          const double lo = origin_[a] + double(cc[a]) * cell_, hi = lo + cell_;
          const double d = c[a] < lo ? lo - c[a] : (c[a] > hi ? c[a] - hi : 0.0);
          box2 += d * d;
        }
        if (box2 <= bestD2) scanCell(slot);
      }
      break;
    }
    for (std::int64_t x = cx - ring; x <= cx + ring; ++x)
      for (std::int64_t y = cy - ring; y <= cy + ring; ++y) {
        const bool faceXY = (x == cx - ring || x == cx + ring || y == cy - ring || y == cy + ring);
        const std::int64_t step = faceXY ? 1 : 2 * ring; // inside the shell only its two z faces
        for (std::int64_t z = cz - ring; z <= cz + ring; z += step) {
          const std::int64_t slot = findCell(x, y, z);
          if (slot >= 0) scanCell(static_cast<size_t>(slot));
        }
      }
  }
  if (squaredDistance != nullptr && best >= 0) *squaredDistance = bestD2;
  return best;
}

void PointGrid::nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared, int threads) const {
  stride = std::max<size_t>(stride, 1);
  squared.assign(builtSize_ == 0 ? 0 : (builtSize_ - 1) / stride + 1, -1.0);
  const size_t cells = cellKey_.size();
  if (cells == 0) return;
  // nearest() answers from rings 0 and 1 (the 3×3×3 cells around) or ring 2 (5×5×5) as soon as
  // its best is within (ring − 1)·cell + slack, slack being the query's distance to the outside
  // of its cell; the same tests here give the same values. Below 98 cells nearest() takes a
  // shortcut at ring 2 (all cells by box distance): there only rings 0 and 1 are done here.
  const bool ring2 = cells >= 98;
  // The cells are sorted by key (x, then y, then z): the cells of a column (X, Y) with z in a
  // range are consecutive slots, and as the cells are visited in order, the first slot of the
  // column (X + dx, Y + dy) at z − 2 only moves forward: one cursor per column offset, moved by
  // galloping, instead of a hash look-up per cell of the block.
  auto seek = [&](size_t from, Key target) {
    if (from >= cells || cellKey_[from] >= target) return from;
    size_t lo = from, step = 1;
    while (lo + step < cells && cellKey_[lo + step] < target) lo += step, step *= 2;
    const size_t hi = std::min(cells, lo + step + 1);
    return size_t(std::lower_bound(cellKey_.begin() + std::ptrdiff_t(lo), cellKey_.begin() + std::ptrdiff_t(hi), target) -
                  cellKey_.begin());
  };
  const int workers = parallelParts(cells, threads, 512);
  parallelChunks(cells, workers, 256, [&](size_t s0, size_t s1, int) {
    size_t cursor[25] = {}; // per column offset (dx + 2)·5 + (dy + 2): first slot at z − 2 or later
    struct Span {
      std::uint32_t b, e; // points [b, e)
    };
    Span inner[9], outer[25];
    for (size_t slot = s0; slot < s1; ++slot) {
      const size_t b = cellStart_[slot], e = cellStart_[slot + 1];
      bool any = false;
      for (size_t i = b; i < e && !any; ++i) any = pointIndex_[i] % stride == 0;
      if (!any) continue;
      const Key k = cellKey_[slot];
      const std::int64_t cx = std::int64_t(k >> (2 * kBits)), cy = std::int64_t((k >> kBits) & Key(kMaxCoord)),
                         cz = std::int64_t(k & Key(kMaxCoord));
      // Slots of column offset c between z0 and z1 (clamped to the grid): [first, end).
      auto column = [&](int c, std::int64_t z0, std::int64_t z1, size_t& first, size_t& end) {
        const std::int64_t x = cx + c / 5 - 2, y = cy + c % 5 - 2;
        first = end = 0;
        if (x < 0 || y < 0 || x > maxCell_[0] || y > maxCell_[1]) return;
        z0 = std::max<std::int64_t>(z0, 0);
        z1 = std::min(z1, maxCell_[2]);
        cursor[c] = seek(cursor[c], pack(x, y, std::max<std::int64_t>(cz - 2, 0)));
        first = seek(cursor[c], pack(x, y, z0));
        const Key last = pack(x, y, z1);
        end = first;
        while (end < cells && cellKey_[end] <= last) ++end;
      };
      int nInner = 0;
      for (int dx = -1; dx <= 1; ++dx)
        for (int dy = -1; dy <= 1; ++dy) {
          size_t f, t;
          column((dx + 2) * 5 + dy + 2, cz - 1, cz + 1, f, t);
          if (f < t) inner[nInner++] = Span{cellStart_[f], cellStart_[t]};
        }
      int nOuter = -1; // the 5×5×5 block's spans, gathered on first need
      for (size_t q = b; q < e; ++q) {
        const std::uint32_t idx = pointIndex_[q];
        if (idx % stride != 0) continue;
        const Point& c = sortedPoint_[q];
        double slack = std::numeric_limits<double>::infinity();
        const std::int64_t cc[3] = {cx, cy, cz};
        for (int a = 0; a < 3; ++a) {
          const double lo = origin_[a] + double(cc[a]) * cell_;
          slack = std::min({slack, c[a] - lo, lo + cell_ - c[a]});
        }
        slack = std::max(slack, 0.0);
        // Ring 0: the cell itself.
        double best = std::numeric_limits<double>::infinity();
        bool found = false;
        for (size_t i = b; i < e; ++i) {
          if (i == q) continue;
          const double d2 = (sortedPoint_[i] - c).SquaredNorm();
          if (d2 < best) best = d2;
          found = true;
        }
        if (!(found && best <= slack * slack)) {
          // The points of the spans but q itself, into best.
          auto scan = [&](const Span* spans, int count) {
            for (int s = 0; s < count; ++s)
              for (size_t i = spans[s].b; i < spans[s].e; ++i) {
                if (i == q) continue;
                const double d2 = (sortedPoint_[i] - c).SquaredNorm();
                if (d2 < best) best = d2;
                found = true;
              }
          };
          // Ring 1: the 3×3×3 block (the cell's own points again: the same minimum).
          scan(inner, nInner);
          const double reach1 = cell_ + slack; // nearest(): double(ring − 1)·cell + slack, ring 2
          if (!(found && best <= reach1 * reach1)) {
            bool done = false;
            if (ring2) {
              // Ring 2: the 5×5×5 block.
              if (nOuter < 0) {
                nOuter = 0;
                for (int col = 0; col < 25; ++col) {
                  size_t f, t;
                  column(col, cz - 2, cz + 2, f, t);
                  if (f < t) outer[nOuter++] = Span{cellStart_[f], cellStart_[t]};
                }
              }
              scan(outer, nOuter);
              const double reach2 = 2.0 * cell_ + slack; // ring 3
              done = found && best <= reach2 * reach2;
            }
            if (!done) {
              double d2 = -1;
              found = nearest(c, &d2, static_cast<int>(idx)) >= 0;
              best = d2;
            }
          }
        }
        if (found) squared[idx / stride] = best;
      }
    }
  });
}

size_t PointGrid::memoryBytes() const {
  return cellKey_.capacity() * sizeof(Key) + cellStart_.capacity() * sizeof(std::uint32_t) +
         table_.capacity() * sizeof(std::int64_t) + sortedPoint_.capacity() * sizeof(Point) +
         pointIndex_.capacity() * sizeof(std::uint32_t);
}

} // namespace growth
