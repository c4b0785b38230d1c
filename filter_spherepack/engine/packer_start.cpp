// Sec. 3.3: the starting pairs (packer_steps.h).
#include "packer_steps.h"

#include <growth/error.h>

#include <limits>

namespace growth {
namespace spherepack {
namespace detail {

// Closest splat to x (smallest distance to its disk) and the projection of x onto it (sec. 3.3).
// The splats of the box containing x (all points within d of it) are searched; when x is farther
// than d from every point, all splats are when `searchAll` (user-given points), none otherwise.
bool projectOntoClosestSplat(const Vec3d& x, const Vec3d& side, const InputCloud& in,
                             const std::vector<float>& radius, const BoxGrid& grid, const Renumbering& order,
                             bool searchAll, Vec3d& proj, std::uint32_t& splat) {
  double best = std::numeric_limits<double>::infinity();
  std::int64_t bestIdx = -1;
  auto consider = [&](std::uint32_t i) {
    const double dd = squaredDistanceToDisk(x, in.points[i], in.normals[i], radius[i]);
    if (dd < best) best = dd, bestIdx = i;
  };
  const int box = grid.boxOf(x, side);
  if (box >= 0) {
    for (const std::uint32_t* it = grid.pointsBegin(box); it != grid.pointsEnd(box); ++it) consider(*it);
  }
  if (bestIdx < 0 && searchAll) // all points: of equally close ones, the first in input order
    for (std::uint32_t i = 0; i < in.points.size(); ++i) {
      const double dd = squaredDistanceToDisk(x, in.points[i], in.normals[i], radius[i]);
      if (dd < best || (dd == best && bestIdx >= 0 && order.origOf(i) < order.origOf(std::uint32_t(bestIdx))))
        best = dd, bestIdx = i;
    }
  if (bestIdx < 0) return false;
  splat = static_cast<std::uint32_t>(bestIdx);
  proj = projectOntoDisk(x, in.points[splat], in.normals[splat], radius[splat]);
  return true;
}

// Sec. 3.3: the first starting pair, projected onto their closest splats, between d and 2d apart:
// the user's two points, or "around the maximum z-coordinate of the input".
StartPair firstStartPair(const InputCloud& in, const std::vector<float>& radius, const BoxGrid& grid,
                         const Renumbering& order, double d, double s, const Params& params) {
  StartPair first;
  bool haveFirst = false;
  auto noVertexYet = [](const Vec3d&) { return true; };
  if (params.useStartPoints) {
    for (const auto& q : params.startPoint)
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
        throw Error("The starting points must have finite coordinates.");
    const Vec3d anySide(0, 0, 0);
    projectOntoClosestSplat(params.startPoint[0], anySide, in, radius, grid, order, true, first.s1, first.splat1);
    projectOntoClosestSplat(params.startPoint[1], anySide, in, radius, grid, order, true, first.s2, first.splat2);
    const double dist = (first.s1 - first.s2).Norm();
    if (dist < d || dist > 2 * d)
      throw Error("The two starting points, projected onto their closest splats, are " + fmt(dist) +
                  " apart; they must be between d = " + fmt(d) + " and 2d = " + fmt(2 * d) +
                  " apart (paper, section 3.3). Move them, or let the filter choose them.");
    haveFirst = true;
  } else {
    // Automatic: the highest points in turn; when none of the 64 highest can start, the first
    // usable point in input order.
    std::vector<std::uint32_t> highest;
    reserveHuge(highest, in.points.size(), /*populate=*/true);
    highest.resize(in.points.size());
    for (std::uint32_t i = 0; i < highest.size(); ++i) highest[i] = i;
    const size_t tries = std::min<size_t>(highest.size(), 64);
    std::partial_sort(highest.begin(), highest.begin() + std::ptrdiff_t(tries), highest.end(),
                      [&](std::uint32_t a, std::uint32_t b) {
                        return in.points[a][2] != in.points[b][2] ? in.points[a][2] > in.points[b][2]
                                                                  : order.origOf(a) < order.origOf(b);
                      });
    for (size_t t = 0; t < tries && !haveFirst; ++t)
      haveFirst = startPairAt(highest[t], in, radius, grid, order, d, noVertexYet, first);
    for (std::uint32_t k = 0; k < in.points.size() && !haveFirst; ++k)
      haveFirst = startPairAt(order.rankOf(k), in, radius, grid, order, d, noVertexYet, first);
    if (!haveFirst)
      throw Error("Could not place two starting vertices between d and 2d apart anywhere on the cloud: d = " +
                  fmt(d) + " is probably too large for it, or the splats too small (s = " + fmt(s) +
                  "). Try the default d, or give the starting points by hand.");
  }
  return first;
}

} // namespace detail
} // namespace spherepack
} // namespace growth
