#pragma once
// Crossing check of the sphere packer (Lipschütz et al., sec. 3.6, fig. 4b).
//
// Before a candidate c is inserted with its edges c–a and c–b, c and the two prospective edges,
// and the existing edges in the vicinity of c, are projected along the approximated surface
// normal at c (the box normal, sec. 4.1) onto a plane; "the vicinity of v_c is bounded by d in
// normal direction". The candidate is discarded when one of its new edges crosses an existing
// edge in that projection. This is what keeps the output manifold when d is too large for the
// reach of the surface or the cloud does not sample a manifold (fig. 4a).
//
// Choices where the paper is silent: an existing edge is in the vicinity when some point of it is
// within d of c in the normal direction (its height interval meets [−d, d]); edges that share an
// endpoint with a new edge only touch it and do not count; crossings are proper crossings of the
// projected segments. Every such edge has an endpoint within √5·d of c (within d in height, and
// within 2d sideways since edges of G are d long and the crossing point is within d of c), so the
// caller gathers the vertices within crossingSearchRadius(d) of c.
#include "borders.h"
#include "splats.h"

#include <growth/vec3.h>

#include <cstdint>
#include <vector>

namespace growth {

inline double crossingSearchRadius(double d) { return 2.2360679774997898 * d * (1 + 1e-9); }

// Proper crossing of the 2D segments p1–p2 and q1–q2 (touching or collinear overlap is not a
// crossing).
inline bool segmentsCross2D(double p1x, double p1y, double p2x, double p2y, double q1x, double q1y, double q2x,
                            double q2y) {
  auto orient = [](double ax, double ay, double bx, double by, double cx, double cy) {
    return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
  };
  const double o1 = orient(p1x, p1y, p2x, p2y, q1x, q1y), o2 = orient(p1x, p1y, p2x, p2y, q2x, q2y);
  if (!((o1 > 0 && o2 < 0) || (o1 < 0 && o2 > 0))) return false;
  const double o3 = orient(q1x, q1y, q2x, q2y, p1x, p1y), o4 = orient(q1x, q1y, q2x, q2y, p2x, p2y);
  return (o3 > 0 && o4 < 0) || (o3 < 0 && o4 > 0);
}

// True when, projected along the unit normal n at the candidate position c, one of the new edges
// c–a or c–b (a, b vertices of g) crosses an edge of g with an endpoint in `nearby` (vertices
// within crossingSearchRadius(d) of c) that lies within d of c in the direction of n.
bool newEdgesCross(const BorderGraph& g, const Vec3d& c, std::uint32_t a, std::uint32_t b, const Vec3d& n,
                   double d, const std::vector<std::uint32_t>& nearby);

// The same, counting only the existing edges x–y for which keep(x, y) is true (the remesher leaves
// out the edges on the other side of a crease, which its projection along n sees edge-on).
template <class Keep>
bool newEdgesCrossIf(const BorderGraph& g, const Vec3d& c, std::uint32_t a, std::uint32_t b, const Vec3d& n,
                     double d, const std::vector<std::uint32_t>& nearby, Keep&& keep) {
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
      if (!keep(x, y)) continue;
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
