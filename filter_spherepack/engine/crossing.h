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

} // namespace growth
