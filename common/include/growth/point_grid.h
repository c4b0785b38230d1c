#pragma once
// growth::PointIndex seen with the caller's point indices: queries report a point by its index in
// the array the grid was built from (the index reports its own, cell-ordered ones). For the
// sphere packer (splats, the sampling estimate) and the spacing estimates; Robust G2S uses the
// index itself, whose order it adopts.
#include <growth/point_index.h>

#include <growth/vec3.h>

#include <cstdint>
#include <limits>
#include <vector>

namespace growth {

class PointGrid {
public:
  using Point = Vec3d;

  PointGrid() = default;

  // Builds the grid over `points` (indices refer to this array) with cubic cells of side cellSize.
  // Non-finite points are skipped (never returned by queries).
  void build(const std::vector<Point>& points, double cellSize) {
    index_.build(points, cellSize > 0 && std::isfinite(cellSize) ? cellSize : 0.0);
  }

  size_t pointCount() const { return index_.size(); }
  size_t cellCount() const { return index_.cellCount(); }
  double cellSize() const { return index_.cellSize(); }
  const PointIndex& index() const { return index_; }

  // Calls f(index, squaredDistance) for every point with |p - c| <= radius.
  template <class F>
  void forEachInBall(const Point& c, double radius, F&& f) const {
    const std::vector<std::uint32_t>& order = index_.order();
    index_.forEachInBall(c, radius, [&](std::uint32_t i, double d2) { f(static_cast<int>(order[i]), d2); });
  }
  // The same visit, stopped as soon as f returns false (bounded work in dense clusters); returns
  // false when it was stopped.
  template <class F>
  bool forEachInBallWhile(const Point& c, double radius, F&& f) const {
    const std::vector<std::uint32_t>& order = index_.order();
    return !index_.anyInBall(c, radius, [&](std::uint32_t i, double d2) { return !f(static_cast<int>(order[i]), d2); });
  }

  // Index of the point closest to c, or -1 when the grid is empty. `exclude` is skipped.
  // `maxRadius` bounds the search (a point farther away is not returned). Among equal distances,
  // the lowest index.
  int nearest(const Point& c, double* squaredDistance = nullptr, int exclude = -1,
              double maxRadius = std::numeric_limits<double>::infinity()) const {
    const std::vector<std::uint32_t>& order = index_.order();
    const std::int64_t i = index_.nearestBy(c, maxRadius, squaredDistance, [&](std::uint32_t k) {
      return int(order[k]) == exclude ? std::int64_t(-1) : std::int64_t(order[k]);
    });
    return i < 0 ? -1 : static_cast<int>(order[size_t(i)]);
  }

  // For every point of the grid whose index i (into the built array) is a multiple of `stride`:
  // squared[i / stride] = the squared distance to its nearest other point, what
  // nearest(points[i], &d2, i) gives (-1 when there is none; `squared` is resized to cover every
  // multiple below the built array's size, and non-finite points keep -1). Runs on `threads`
  // threads (0 = automatic, parallel.h); the result is the same for any number.
  void nearestOtherSquaredDistances(size_t stride, std::vector<double>& squared, int threads = 0) const {
    index_.nearestOtherSquaredDistances(stride, squared, threads);
  }

  // Memory held by the grid, in bytes (for the benchmark's memory accounting).
  size_t memoryBytes() const { return index_.memoryBytes(); }

private:
  PointIndex index_;
};

} // namespace growth
