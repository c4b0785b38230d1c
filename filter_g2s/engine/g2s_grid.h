#pragma once
// Robust G2S's view of the shared point index (growth::PointIndex, sec. 3 step 2): the index the
// mesher owns its points in, plus the gathering of a ball's points into a NearList for the vector
// scans of g2s_near.h.
#include "g2s_near.h"

#include <growth/point_index.h>

#include <cstddef>
#include <cstdint>

namespace growth {
namespace g2s {

static_assert(kNearPad <= PointIndex::kPad, "the scans load whole vectors past the index's last point");

class MortonGrid : public PointIndex {
public:
  // The points forEachNearBall(c, radius) visits, in the same order, written to `out` (cleared
  // first) with their float coordinates, by the vector scans of g2s_near.h.
  void gatherNear(const P3& c, double radius, NearList& out) const {
    out.clear();
    if (size() == 0 || !(radius >= 0)) return;
    float fc[3];
    toFloat(c, fc);
    const double slack = floatSlack(fc, radius);
    const float r2f = float((radius + slack) * (radius + slack));
    // The ranges are collected first and scanned in one call (one call per cell costs as much as
    // the scan of a small cell).
    constexpr std::size_t kBatch = 32;
    std::uint32_t range[2 * kBatch];
    std::size_t ranges = 0, points = 0, scanned = 0;
    const float *x = floatX(), *y = floatY(), *z = floatZ();
    forEachRangeUncounted(c, radius, [&](std::uint32_t begin, std::uint32_t end) {
      if (ranges == kBatch) {
        out.appendWithin(x, y, z, range, ranges, points, fc, r2f);
        scanned += points;
        ranges = points = 0;
      }
      range[2 * ranges] = begin;
      range[2 * ranges + 1] = end;
      ++ranges;
      points += end - begin;
      return false;
    });
    if (ranges > 0) out.appendWithin(x, y, z, range, ranges, points, fc, r2f);
    scanned += points;
    countVisited(scanned);
  }
};

} // namespace g2s
} // namespace growth
