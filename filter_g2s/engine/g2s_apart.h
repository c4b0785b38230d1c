#pragma once
// Cheap sufficient tests that two faces do not intersect (in the sense of
// growth/self_intersections.h), for the repairs after the growth (g2s_repair.cpp): each answers
// "apart" only when rounding cannot have decided it, so that the exact test (facesIntersect) is
// left only the pairs that pass neither. They change no decision, only its cost.
#include "g2s_geometry.h"

#include <growth/manifold_cleanup.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace growth {
namespace g2s {

// Face t's plane, made once for the many faces tested against t: a corner, the normal as computed
// and its length, and the products the margins below are made of.
struct PlaneOf {
  P3 a, n;
  double nNorm, scale, edges;
  PlaneOf(const std::vector<P3>& pos, const Triangle& t) : a(pos[t[0]]) {
    const P3 &b = pos[t[1]], &c = pos[t[2]];
    n = (b - a) ^ (c - a);
    nNorm = n.Norm();
    edges = (b - a).Norm() * (c - a).Norm();
    scale = nNorm * ((b - a).Norm() + (c - a).Norm());
  }
};
// The points of u that are not points of t lie strictly on one side of t's plane, by far more than
// the rounding error of the side test. u then meets that plane only in the points the two share,
// so the two meet at their shared point or edge only (without a fold-over). Applied both ways
// round.
inline bool apartByPlane(const std::vector<P3>& pos, const PlaneOf& plane, const Triangle& t, const Triangle& u) {
  int above = 0, below = 0;
  for (std::uint32_t v : u) {
    if (v == t[0] || v == t[1] || v == t[2]) continue;
    const P3 d = pos[v] - plane.a;
    const double side = plane.n * d, margin = 1e-9 * (plane.scale + plane.nNorm * d.Norm());
    above += side > margin;
    below += side < -margin;
    if (!(side > margin || side < -margin)) return false;
  }
  return (above == 0) != (below == 0);
}
inline bool apartByPlane(const std::vector<P3>& pos, const Triangle& t, const Triangle& u) {
  return apartByPlane(pos, PlaneOf(pos, t), t, u);
}
// A second cheap sufficient test, for faces t and u that share at most one point and that the
// plane test cannot part (side by side on a flat piece of surface): seen along t's normal, a line
// through an edge of one of them has that face's third point strictly on one side and every point
// of the other face strictly on the other side, but for the edge's own end points. Any common
// point of the two faces would show as a common point of their shadows, which meet on that line
// at most in the shared point: so they have no point in common other than their shared point.
// The sides are n·((e1 − e0) × (x − e0)), n t's normal as computed (its rounding error is below
// 4u·|b − a|·|c − a|, the value's below 20u·|b − a|·|c − a|·|e1 − e0|·|x − e0|); each must exceed
// 1e-9 of that product, or nothing is claimed (slivers, faces across t's plane).
inline bool apartInShadow(const std::vector<P3>& pos, const PlaneOf& plane, const Triangle& t, const Triangle& u) {
  int shared = 0;
  for (std::uint32_t v : u) shared += v == t[0] || v == t[1] || v == t[2];
  if (shared > 1) return false;
  auto side = [&](const P3& e0, const P3& e1, const P3& x, double& margin) {
    const P3 d = e1 - e0, y = x - e0;
    margin = 1e-9 * plane.edges * d.Norm() * y.Norm();
    return plane.n * (d ^ y);
  };
  // The line through edge own[k]–own[k+1] parts `other` from `own`.
  auto parts = [&](const Triangle& own, const Triangle& other) {
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i0 = own[k], i1 = own[(k + 1) % 3], i2 = own[(k + 2) % 3];
      double m;
      const double s = side(pos[i0], pos[i1], pos[i2], m);
      if (!(m > 1e-250) || !(std::abs(s) > m)) continue;
      bool apart = true;
      for (std::uint32_t w : other) {
        if (w == i0 || w == i1) continue;
        double mw;
        const double sw = w == i2 ? 0.0 : side(pos[i0], pos[i1], pos[w], mw);
        if (w == i2 || !(mw > 1e-250) || !(s > 0 ? sw < -mw : sw > mw)) {
          apart = false;
          break;
        }
      }
      if (apart) return true;
    }
    return false;
  };
  return parts(t, u) || parts(u, t);
}

} // namespace g2s
} // namespace growth
