#include "crossing.h"
#include "splats.h"

namespace growth {

bool newEdgesCross(const BorderGraph& g, const Vec3d& c, std::uint32_t a, std::uint32_t b, const Vec3d& n,
                   double d, const std::vector<std::uint32_t>& nearby) {
  Vec3d e1, e2;
  tangentFrame(n, e1, e2);
  struct P {
    double x, y, h;
  };
  auto project = [&](const Vec3d& p) {
    const Vec3d v = p - c;
    return P{v * e1, v * e2, v * n};
  };
  const P pa = project(g.position(a)), pb = project(g.position(b));
  for (std::uint32_t x : nearby) {
    const P px = project(g.position(x));
    for (int k = 0; k < g.degree(x); ++k) {
      const std::uint32_t y = g.neighbour(x, k);
      const P py = project(g.position(y));
      // Vicinity: the edge's height interval meets [−d, d].
      if ((px.h > d && py.h > d) || (px.h < -d && py.h < -d)) continue;
      if (x != a && y != a && segmentsCross2D(0, 0, pa.x, pa.y, px.x, px.y, py.x, py.y)) return true;
      if (x != b && y != b && segmentsCross2D(0, 0, pb.x, pb.y, px.x, px.y, py.x, py.y)) return true;
    }
  }
  return false;
}

} // namespace growth
