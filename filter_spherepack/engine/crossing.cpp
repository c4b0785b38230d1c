#include "crossing.h"

namespace growth {

bool newEdgesCross(const BorderGraph& g, const Vec3d& c, std::uint32_t a, std::uint32_t b, const Vec3d& n,
                   double d, const std::vector<std::uint32_t>& nearby) {
  return newEdgesCrossIf(g, c, a, b, n, d, nearby, [](std::uint32_t, std::uint32_t) { return true; });
}

} // namespace growth
