#pragma once
// Geometric predicates of Robust G2S (Di Angelo, Di Stefano, Giaccari), in double precision.
//
// - Gabriel 2-simplex (G2S): a triangle whose smallest circumscribing ball — centred at its
//   circumcentre, in its plane, radius the circumradius — holds no other input point (sec. 2.3).
// - Search region (sec. 3.2, fig. 2): a sphere of radius r centred in the front triangle's plane
//   on the free edge's perpendicular bisector, on the side away from the front triangle.
// - Flatness (sec. 4.1): the angle β between the normals of the front triangle and of the
//   candidate triangle, both taken in the orientation of the growing mesh.
#include <growth/vec3.h>

#include <algorithm>
#include <cmath>

namespace growth {
namespace g2s {

using P3 = Vec3d;

// A point at squared distance d2 from a ball's centre lies strictly inside when d2 is below
// radius2 by more than this relative margin. Points on the sphere (within rounding) do not count,
// so cocircular configurations (regular grids) keep both of their Delaunay triangles valid.
constexpr double kInsideMargin = 1e-10;

inline bool strictlyInside(double d2, double radius2) { return d2 < radius2 * (1.0 - kInsideMargin); }

struct Ball {
  P3 centre;
  double radius2 = 0; // squared radius
};

// The smallest ball through a, b, c (circumcentre in the plane of the triangle). False when the
// triangle is degenerate (its vertices collinear up to rounding): no such ball exists.
inline bool circumBall(const P3& a, const P3& b, const P3& c, Ball& ball) {
  const P3 u = b - a, v = c - a;
  const P3 w = u ^ v;
  const double w2 = w.SquaredNorm(), u2 = u.SquaredNorm(), v2 = v.SquaredNorm();
  // sin² of the angle at a below 1e-20: collinear for every practical purpose.
  if (!(w2 > 1e-20 * u2 * v2) || !(w2 > 0)) return false;
  const P3 off = ((v ^ w) * u2 + (w ^ u) * v2) / (2.0 * w2);
  ball.centre = a + off;
  ball.radius2 = off.SquaredNorm();
  return std::isfinite(ball.radius2);
}

// The smallest ball holding a, b and c: the ball on the longest edge for a right or obtuse
// triangle, else the circumball (unlike circumBall, it stays at the triangle's own scale for a
// sliver). False when the triangle is degenerate.
inline bool smallestEnclosingBall(const P3& a, const P3& b, const P3& c, Ball& ball) {
  const double ab2 = (b - a).SquaredNorm(), bc2 = (c - b).SquaredNorm(), ca2 = (a - c).SquaredNorm();
  if (ab2 >= bc2 + ca2) ball.centre = (a + b) * 0.5, ball.radius2 = 0.25 * ab2;
  else if (bc2 >= ab2 + ca2) ball.centre = (b + c) * 0.5, ball.radius2 = 0.25 * bc2;
  else if (ca2 >= ab2 + bc2) ball.centre = (c + a) * 0.5, ball.radius2 = 0.25 * ca2;
  else return circumBall(a, b, c, ball);
  return true;
}

// Unit normal of triangle (a, b, c) by the right-hand rule; (0,0,0) when degenerate.
inline P3 unitNormal(const P3& a, const P3& b, const P3& c) {
  P3 n = (b - a) ^ (c - a);
  const double len = n.Norm();
  return len > 0 ? n / len : P3(0, 0, 0);
}

// The growing direction of the free edge a→b of front triangle (a, b, c): the unit vector in the
// triangle's plane, orthogonal to ab, pointing away from c. (0,0,0) when (a, b, c) is degenerate.
inline P3 growingDirection(const P3& a, const P3& b, const P3& c) {
  const P3 n = (b - a) ^ (c - a);
  P3 d = (b - a) ^ n;
  const double len = d.Norm();
  return len > 0 ? d / len : P3(0, 0, 0);
}

// Search sphere of radius r for the free edge a→b (sec. 3.2): its centre lies on the edge's axis
// in the front triangle's plane, in the growing direction `dir`. The paper fixes the centre's line
// but not its distance from the edge; we put it where the sphere passes through both edge
// endpoints (distance sqrt(r² − |ab|²/4)), so that for the initial radius r = |ab| it is centred
// on the apex of the equilateral triangle over ab — the ideal next point — and, as r grows, the
// spheres are nested on the growing side of the edge: a point found at one radius is found at
// every larger one, and the region never reaches behind the edge.
inline P3 searchCentre(const P3& a, const P3& b, const P3& dir, double r) {
  const P3 m = (a + b) * 0.5;
  const double h2 = 0.25 * (b - a).SquaredNorm();
  return m + dir * std::sqrt(std::max(r * r - h2, 0.0));
}

// Angle β in [0, π] between two normals (not necessarily unit).
inline double angleBetween(const P3& n1, const P3& n2) {
  return std::atan2((n1 ^ n2).Norm(), n1 * n2);
}

// Flatness priority level pl_f in [1, m] of an angle β in [0, π] (sec. 4.1: pl_f = 1 for β = 0,
// pl_f = m for β = π; equal-width classes).
inline int flatnessLevel(double betaRad, int m) {
  const double pi = 3.14159265358979323846;
  const int l = 1 + static_cast<int>(std::floor(betaRad / pi * m));
  return std::min(std::max(l, 1), m);
}

// Priority index of eq. 4.1: PI = m·(pl_d − 1) + pl_f, in [1, n·m]; smaller is more urgent.
inline int priorityIndex(int sizeLevel, int flatLevel, int m) { return m * (sizeLevel - 1) + flatLevel; }

// Radius of search level i in [1, n]: n equal steps from the edge length to the maximum radius
// (sec. 3.2: "from an initial value ... equal to the length of the free edge ... to an assigned
// maximum value according to a given step value"; sec. 4.1: the step is the size priority pl_d).
inline double searchRadius(int level, int n, double edgeLength, double maxRadius) {
  if (maxRadius <= edgeLength || n <= 1) return n <= 1 ? std::max(edgeLength, maxRadius) : edgeLength;
  return edgeLength + (maxRadius - edgeLength) * double(level - 1) / double(n - 1);
}

} // namespace g2s
} // namespace growth
