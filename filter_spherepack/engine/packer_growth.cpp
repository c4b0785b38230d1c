// Sec. 3.4-3.6 on every part of the cloud, sec. 3.3 starting each (packer_steps.h).
#include "packer_growth.h"

namespace growth {
namespace spherepack {
namespace detail {

// Sec. 3.4–3.6: the disk growing from the first pair; then sec. 3.3 again on every further part of
// the cloud. When the growth has stopped and points are left that no vertex reached, a new
// starting pair on the first of them in input order (every point is tried once, so the scan is
// linear), at least kStartClearancePerD·d from every vertex placed so far: a point with a vertex
// between d and that far lies on a surface already meshed there (a misregistered second scan
// layer, or the rim of a gap the growth left), and a start on it would only grow a separate sheet
// over or beside the mesh (docs/design/spherepack-every-part.md).
void growEveryPart(Growth& growth, const StartPair& first, const InputCloud& in, const std::vector<float>& radius,
                   const BoxGrid& grid, const Renumbering& order, double d, Stat& st) {
  growth.start(first.s1, first.splat1, first.s2, first.splat2);
  growth.run();
  st.componentsStarted = 1;
  bool nearMesh = false;
  auto farFromVertices = [&](const Vec3d& x) {
    if (growth.anyVertexCloserThan(x, d)) return false;
    if (!growth.anyVertexCloserThan(x, kStartClearancePerD * d)) return true;
    nearMesh = true;
    return false;
  };
  for (std::uint32_t k = 0; k < in.points.size(); ++k) {
    const std::uint32_t i = order.rankOf(k);
    if (!growth.lists().empty(i)) continue;
    StartPair pair;
    nearMesh = false;
    if (!startPairAt(i, in, radius, grid, order, d, farFromVertices, pair)) {
      st.startsRefusedNearMesh += nearMesh ? 1 : 0;
      continue;
    }
    growth.start(pair.s1, pair.splat1, pair.s2, pair.splat2);
    growth.run();
    ++st.componentsStarted;
  }
}

// Input points no vertex came within d of.
size_t unreachedPoints(const Growth& growth, size_t points) {
  size_t unreached = 0;
  for (std::uint32_t i = 0; i < points; ++i) {
    unreached += growth.lists().empty(i) ? 1 : 0;
  }
  return unreached;
}

} // namespace detail
} // namespace spherepack
} // namespace growth
