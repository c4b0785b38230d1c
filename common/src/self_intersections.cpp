#include <growth/error.h>
#include <growth/exact_predicates.h>
#include <growth/morton.h>
#include <growth/parallel.h>
#include <growth/self_intersections.h>

#include <algorithm>
#include <cfloat>
#include <cmath>
#include <queue>
#include <string>

namespace growth {

namespace {

using Point = Vec3d;

// ---------------------------------------------------------------------------------------------
// Exact tests on closed triangles, segments and points. Only signs of orient3d / orient2d and
// comparisons of input coordinates: nothing is constructed, so nothing is rounded.

// orient2d of the projections of a, b, c onto the coordinate plane without axis k, with the
// coordinates in cyclic order (k+1, k+2), so that its sign is the sign of the k-th component of
// the normal (b−a)×(c−a).
inline int orient2dDrop(const Point& a, const Point& b, const Point& c, int k) {
  const int i = k == 2 ? 0 : k + 1, j = k == 0 ? 2 : k - 1;
  return orient2d(a[i], a[j], b[i], b[j], c[i], c[j]);
}

inline bool collinear(const Point& a, const Point& b, const Point& c) {
  return orient2dDrop(a, b, c, 2) == 0 && orient2dDrop(a, b, c, 0) == 0 && orient2dDrop(a, b, c, 1) == 0;
}

// A coordinate plane onto which the projection of the triangle's plane is one-to-one: an axis k
// whose orient2dDrop is not zero, the normal's largest component first (the filter then decides
// at once); −1 for a triangle whose corners are collinear (a segment or a point).
int projectionAxis(const Point& a, const Point& b, const Point& c) {
  const Point n = (b - a) ^ (c - a);
  const double m0 = std::abs(n[0]), m1 = std::abs(n[1]), m2 = std::abs(n[2]);
  const int first = m0 >= m1 && m0 >= m2 ? 0 : (m1 >= m2 ? 1 : 2);
  if (orient2dDrop(a, b, c, first) != 0) return first;
  for (int k = 0; k < 3; ++k)
    if (k != first && orient2dDrop(a, b, c, k) != 0) return k;
  return -1;
}

// A face's plane, for side tests cheaper than orient3d: n = (b − a) × (c − a) from its corners
// a, b, c, rounded, and per component the sum of the magnitudes of its two products. The side of
// p is the sign of n·(p − a), which passes each of its six monomials through 8 roundings (three
// differences, two products, a subtraction, two additions), like orient3d's value: its error is
// at most γ8·P, P the sum of the monomials' magnitudes, and nAbs·|p − a| >= (1−u)^8·P, so the same
// bound 10u·nAbs·|p − a| applies (growth/exact_predicates.h). Undecided cases go to orient3d.
struct Plane {
  double n[3];
  double nAbs[3];
};

Plane planeOf(const Point& a, const Point& b, const Point& c) {
  const double ux = b[0] - a[0], uy = b[1] - a[1], uz = b[2] - a[2];
  const double wx = c[0] - a[0], wy = c[1] - a[1], wz = c[2] - a[2];
  const double p0 = uy * wz, q0 = uz * wy, p1 = uz * wx, q1 = ux * wz, p2 = ux * wy, q2 = uy * wx;
  return Plane{{p0 - q0, p1 - q1, p2 - q2}, {std::abs(p0) + std::abs(q0), std::abs(p1) + std::abs(q1), std::abs(p2) + std::abs(q2)}};
}

// A face's corners (in some rotation of its order), its projection axis (−1: degenerate), and its
// plane with the corner it was computed from.
struct Tri {
  const Point* v[3];
  int axis;
  const Plane* plane;
  const Point* base;
  const Point& operator[](int i) const { return *v[i]; }
};

Tri rotated(const std::vector<Point>& pos, const Triangle& t, int first, int axis, const Plane* plane) {
  static constexpr int kNext[5] = {0, 1, 2, 0, 1};
  return Tri{{&pos[t[size_t(first)]], &pos[t[size_t(kNext[first + 1])]], &pos[t[size_t(kNext[first + 2])]]}, axis, plane, &pos[t[0]]};
}

// orient3d(t0, t1, t2, p), through t's plane when that decides (any rotation of t's corners has
// the orientation of its plane; orient3d(a, b, c, p) is the opposite sign of n·(p − a)).
inline int side(const Tri& t, const Point& p) {
  constexpr double kBound = 10.0 * (DBL_EPSILON / 2);
  const Point& a = *t.base;
  const double dx = p[0] - a[0], dy = p[1] - a[1], dz = p[2] - a[2];
  const double value = t.plane->n[0] * dx + t.plane->n[1] * dy + t.plane->n[2] * dz;
  const double permanent = t.plane->nAbs[0] * std::abs(dx) + t.plane->nAbs[1] * std::abs(dy) + t.plane->nAbs[2] * std::abs(dz);
  if (permanent >= 1e-270) {
    const double bound = kBound * permanent;
    if (value > bound) return -1;
    if (-value > bound) return 1;
  }
  return orient3d(t[0], t[1], t[2], p);
}

// x, known to lie in the plane of the non-degenerate triangle t, is in the closed triangle.
bool containsCoplanar(const Tri& t, const Point& x) {
  const int o0 = orient2dDrop(t[0], t[1], x, t.axis), o1 = orient2dDrop(t[1], t[2], x, t.axis);
  if (o0 * o1 < 0) return false;
  const int o2 = orient2dDrop(t[2], t[0], x, t.axis);
  // Inside the closed triangle exactly when no two of the three edge sides disagree (the three
  // cannot all be zero for a non-degenerate triangle).
  return !((o0 > 0 || o1 > 0 || o2 > 0) && (o0 < 0 || o1 < 0 || o2 < 0));
}

// x, collinear with p and q in the projection without axis k, lies on the closed segment p–q.
bool withinSegment(const Point& p, const Point& q, const Point& x, int k) {
  for (int i = 0; i < 3; ++i) {
    if (i == k) continue;
    if (x[i] < std::min(p[i], q[i]) || x[i] > std::max(p[i], q[i])) return false;
  }
  return true;
}

// Closed segments p–q and r–s (either may be a point) meet, all four points lying in one plane
// whose projection without axis k is one-to-one.
bool segmentsMeetCoplanar(const Point& p, const Point& q, const Point& r, const Point& s, int k) {
  const int d1 = orient2dDrop(p, q, r, k), d2 = orient2dDrop(p, q, s, k);
  if (d1 * d2 > 0) return false; // r and s strictly on one side of line p–q
  const int d3 = orient2dDrop(r, s, p, k), d4 = orient2dDrop(r, s, q, k);
  if (d3 * d4 > 0) return false;
  if (d1 * d2 < 0 && d3 * d4 < 0) return true; // proper crossing
  // An endpoint on the other segment's line (or both segments on one line, or points).
  return (d1 == 0 && withinSegment(p, q, r, k)) || (d2 == 0 && withinSegment(p, q, s, k)) ||
         (d3 == 0 && withinSegment(r, s, p, k)) || (d4 == 0 && withinSegment(r, s, q, k));
}

// Closed segment p–q (or point) in the plane of the non-degenerate triangle t meets t.
bool segmentMeetsTriangleCoplanar(const Point& p, const Point& q, const Tri& t) {
  if (containsCoplanar(t, p) || containsCoplanar(t, q)) return true;
  for (int i = 0; i < 3; ++i)
    if (segmentsMeetCoplanar(p, q, t[i], t[(i + 1) % 3], t.axis)) return true;
  return false;
}

// Closed segment p–q (or point) meets the closed non-degenerate triangle t; sp, sq are
// orient3d(t0, t1, t2, ·) of p and q.
bool segmentMeetsTriangle(const Point& p, const Point& q, int sp, int sq, const Tri& t) {
  if (sp * sq > 0) return false;
  if (sp == 0 && sq == 0) return segmentMeetsTriangleCoplanar(p, q, t);
  if (sp == 0) return containsCoplanar(t, p); // q off the plane: p is the only candidate
  if (sq == 0) return containsCoplanar(t, q);
  // p and q strictly on opposite sides: the segment crosses the plane at one point, which is in
  // the closed triangle exactly when the line p–q passes no two edges on opposite sides.
  const int o0 = orient3d(p, q, t[0], t[1]), o1 = orient3d(p, q, t[1], t[2]);
  if (o0 * o1 < 0) return false;
  const int o2 = orient3d(p, q, t[2], t[0]);
  return !((o0 > 0 || o1 > 0 || o2 > 0) && (o0 < 0 || o1 < 0 || o2 < 0));
}

// Closed segments p–q and r–s in space (either may be a point) meet.
bool segmentsMeet(const Point& p, const Point& q, const Point& r, const Point& s) {
  if (orient3d(p, q, r, s) != 0) return false;
  // Coplanar: project on a coordinate plane one-to-one on their plane, if they span one.
  const Point* triple[4][3] = {{&p, &q, &r}, {&p, &q, &s}, {&p, &r, &s}, {&q, &r, &s}};
  for (const auto& t : triple)
    for (int k = 0; k < 3; ++k)
      if (orient2dDrop(*t[0], *t[1], *t[2], k) != 0) return segmentsMeetCoplanar(p, q, r, s, k);
  // All four on one line: compare along an axis on which they are not all equal.
  for (int k = 0; k < 3; ++k) {
    if (p[k] == q[k] && p[k] == r[k] && p[k] == s[k]) continue;
    return std::max(std::min(p[k], q[k]), std::min(r[k], s[k])) <= std::min(std::max(p[k], q[k]), std::max(r[k], s[k]));
  }
  return true; // all at one point
}

// Closed triangles f and g (either may be degenerate) have a point in common.
bool trianglesMeet(const Tri& f, const Tri& g) {
  if (f.axis >= 0 && g.axis >= 0) {
    int sg[3], sf[3];
    for (int i = 0; i < 3; ++i) sg[i] = side(f, g[i]);
    if ((sg[0] > 0 && sg[1] > 0 && sg[2] > 0) || (sg[0] < 0 && sg[1] < 0 && sg[2] < 0)) return false;
    for (int i = 0; i < 3; ++i) sf[i] = side(g, f[i]);
    if ((sf[0] > 0 && sf[1] > 0 && sf[2] > 0) || (sf[0] < 0 && sf[1] < 0 && sf[2] < 0)) return false;
    // Their intersection, if any, is convex; a point of it extreme along the line where the
    // planes meet (or any extreme point, when coplanar) lies on an edge of one of them, so
    // testing the six edges against the other triangle decides.
    for (int i = 0; i < 3; ++i)
      if (segmentMeetsTriangle(g[i], g[(i + 1) % 3], sg[i], sg[(i + 1) % 3], f)) return true;
    for (int i = 0; i < 3; ++i)
      if (segmentMeetsTriangle(f[i], f[(i + 1) % 3], sf[i], sf[(i + 1) % 3], g)) return true;
    return false;
  }
  if (f.axis >= 0 || g.axis >= 0) {
    // A segment (the union of the degenerate face's three edges) against a triangle.
    const Tri& t = f.axis >= 0 ? f : g;
    const Tri& s = f.axis >= 0 ? g : f;
    int sides[3];
    for (int i = 0; i < 3; ++i) sides[i] = side(t, s[i]);
    for (int i = 0; i < 3; ++i)
      if (segmentMeetsTriangle(s[i], s[(i + 1) % 3], sides[i], sides[(i + 1) % 3], t)) return true;
    return false;
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (segmentsMeet(f[i], f[(i + 1) % 3], g[j], g[(j + 1) % 3])) return true;
  return false;
}

// The rays from v through s and through t (s, t ≠ v) coincide: collinear, same direction.
bool sameRay(const Point& v, const Point& s, const Point& t) {
  if (s == v || t == v || !collinear(v, s, t)) return false;
  for (int k = 0; k < 3; ++k)
    if (s[k] != v[k]) return (s[k] > v[k]) == (t[k] > v[k]); // t−v is a nonzero multiple of s−v
  return false;
}

// The ray from t0 through s (s ≠ t0) lies in the closed wedge of the non-degenerate triangle t at
// its corner t0 (spanned by t1 − t0 and t2 − t0).
bool rayInWedge(const Point& s, const Tri& t) {
  if (s == t[0] || side(t, s) != 0) return false;
  const int sigma = orient2dDrop(t[0], t[1], t[2], t.axis);
  return sigma * orient2dDrop(t[0], t[1], s, t.axis) >= 0 && sigma * orient2dDrop(t[0], s, t[2], t.axis) >= 0;
}

// f = (v, a, b) and g = (v, c, d), sharing the vertex v, have a point in common other than v.
// Both are convex and contain v, so they do exactly when the cones they span at v share a ray.
bool meetBeyondVertex(const Tri& f, const Tri& g) {
  if (f.axis >= 0 && g.axis >= 0) {
    const int sc = side(f, g[1]), sd = side(f, g[2]);
    if (sc * sd > 0) return false; // g \ {v} strictly on one side of f's plane
    const int sa = side(g, f[1]), sb = side(g, f[2]);
    if (sa * sb > 0) return false;
    // The farthest common point from v on a shared ray lies on the far edge a–b of f or c–d of
    // g (neither of which contains v), so these two segment tests decide.
    return segmentMeetsTriangle(g[1], g[2], sc, sd, f) || segmentMeetsTriangle(f[1], f[2], sa, sb, g);
  }
  // A degenerate face spans at v the rays through its two other corners (a ray, a line, or
  // nothing when they coincide with v).
  if (g.axis >= 0) return rayInWedge(f[1], g) || rayInWedge(f[2], g);
  if (f.axis >= 0) return rayInWedge(g[1], f) || rayInWedge(g[2], f);
  return sameRay(f[0], f[1], g[1]) || sameRay(f[0], f[1], g[2]) || sameRay(f[0], f[2], g[1]) ||
         sameRay(f[0], f[2], g[2]);
}

// f = (u, w, a) and the face (u, w, b) with projection axis bAxis, sharing the edge u–w, overlap
// beyond that edge.
bool foldOver(const Tri& f, const Point& b, int bAxis) {
  const Point &u = f[0], &w = f[1], &a = f[2];
  if (f.axis >= 0 && bAxis >= 0)
    return side(f, b) == 0 && orient2dDrop(u, w, a, f.axis) * orient2dDrop(u, w, b, f.axis) > 0;
  // A non-degenerate face meets the line u–w only in the edge, so a degenerate face on that line
  // cannot overlap it beyond the edge.
  if (f.axis >= 0 || bAxis >= 0) return false;
  if (u == w) return sameRay(u, a, b);
  // Both on the line u–w: they overlap beyond the edge when they stick out at the same end.
  for (int k = 0; k < 3; ++k) {
    if (u[k] == w[k]) continue;
    const double lo = std::min(u[k], w[k]), hi = std::max(u[k], w[k]);
    return (a[k] < lo && b[k] < lo) || (a[k] > hi && b[k] > hi);
  }
  return false;
}

// The pair test, on faces a and b with distinct vertex indices, their projection axes and planes.
bool pairIntersects(const std::vector<Point>& pos, const Triangle& a, int aAxis, const Plane& aPlane, const Triangle& b,
                    int bAxis, const Plane& bPlane) {
  int shared = 0, ai[3] = {0, 0, 0}, bi[3] = {0, 0, 0};
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      if (a[size_t(i)] == b[size_t(j)]) {
        ai[shared] = i;
        bi[shared] = j;
        ++shared;
      }
  switch (shared) {
  case 0:
    return trianglesMeet(rotated(pos, a, 0, aAxis, &aPlane), rotated(pos, b, 0, bAxis, &bPlane));
  case 1:
    return meetBeyondVertex(rotated(pos, a, ai[0], aAxis, &aPlane), rotated(pos, b, bi[0], bAxis, &bPlane));
  case 2: {
    // Start f after its unshared corner: f = (u, w, a_third).
    const int aThird = 3 - ai[0] - ai[1], bThird = 3 - bi[0] - bi[1];
    return foldOver(rotated(pos, a, (aThird + 1) % 3, aAxis, &aPlane), pos[b[size_t(bThird)]], bAxis);
  }
  default:
    return true; // the same three vertices
  }
}

bool properFace(const Triangle& t) { return t[0] != t[1] && t[1] != t[2] && t[2] != t[0]; }

// ---------------------------------------------------------------------------------------------
// Broad phase.
//
// A uniform grid of cubic cells. Each short face is listed in every cell its box covers: (cell
// key, face) entries sorted by the key, the Morton code of the cell, with a stable radix sort, so
// that the faces of a cell are a run, in input order, and runs come in Morton order (neighbouring
// cells, which share most of their faces, are processed one after the other: the faces' data stay
// in cache whatever the input order). Two faces of a run are a candidate pair when
// their boxes overlap and the run's cell is their reference cell: the cell of the lowest corner of
// the boxes' overlap, which both boxes cover, so each pair is tested exactly once.
//
// Long faces (a box more than kMaxCellsPerAxis cells long on some axis) are not listed: each looks
// up the runs of the cells its box covers, or, when these are more than the faces, checks every
// short face's box; and checks the long faces after it. To bound that work, the cell doubles
// until the long faces' cost, Σ min(cells of the box, faces), is at most kLongBudget times the
// number of faces: a few very long faces cost a few passes over the boxes, many longish ones
// a coarser grid.

// Cell side in mean edge lengths: faces per cell and cells per face both stay small.
constexpr double kCellEdges = 1.5;
// A face whose box is longer than this many cells along some axis is a long face.
constexpr double kMaxCellsPerAxis = 4.0;
// Work allowed for the long faces, in units of the number of faces.
constexpr double kLongBudget = 4.0;

struct Box {
  double lo[3], hi[3];
};

inline bool boxesOverlap(const Box& a, const Box& b) {
  return a.lo[0] <= b.hi[0] && b.lo[0] <= a.hi[0] && a.lo[1] <= b.hi[1] && b.lo[1] <= a.hi[1] &&
         a.lo[2] <= b.hi[2] && b.lo[2] <= a.hi[2];
}

// Integer cell coordinates, relative to the mesh's lowest corner.
struct Cell {
  std::int32_t c[3];
};

struct Grid {
  Point origin;
  double side = 1;

  // Points are never below the origin (the mesh's lowest corner), so truncation is the floor.
  std::int32_t cellOf(double x, int k) const { return std::int32_t((x - origin[k]) / side); }
  Cell cellOf(const double* p) const { return {{cellOf(p[0], 0), cellOf(p[1], 1), cellOf(p[2], 2)}}; }
  std::uint64_t key(std::int32_t x, std::int32_t y, std::int32_t z) const {
    return mortonCode(std::uint64_t(x), std::uint64_t(y), std::uint64_t(z));
  }
  // Cells a box of this extent covers along one axis, at most.
  double span(double extent) const { return std::floor(extent / side) + 2; }
};

// The cell of the lowest corner of the overlap of two overlapping boxes whose lowest cells are a
// and b (the cell of a maximum is the maximum of the cells) is `at`.
inline bool referenceCellIs(const Cell& a, const Cell& b, const Cell& at) {
  return std::max(a.c[0], b.c[0]) == at.c[0] && std::max(a.c[1], b.c[1]) == at.c[1] && std::max(a.c[2], b.c[2]) == at.c[2];
}

// Stable LSD radix sort of 64-bit entries by their bits [low, low + bits).
void sortEntries(std::vector<std::uint64_t>& entries, int low, int bits) {
  constexpr int kDigit = 11;
  constexpr std::uint64_t kMask = (1u << kDigit) - 1;
  std::vector<std::uint64_t> tmp(entries.size());
  std::vector<std::uint32_t> count(size_t(1) << kDigit);
  for (int shift = low; shift < low + bits; shift += kDigit) {
    std::fill(count.begin(), count.end(), 0u);
    for (const std::uint64_t e : entries) ++count[(e >> shift) & kMask];
    std::uint32_t at = 0;
    for (auto& c : count) {
      const std::uint32_t k = c;
      c = at;
      at += k;
    }
    for (const std::uint64_t e : entries) tmp[count[(e >> shift) & kMask]++] = e;
    entries.swap(tmp);
  }
}

using PairList = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

} // namespace

bool facesIntersect(const std::vector<Vec3d>& pos, const Triangle& a, const Triangle& b) {
  if (!properFace(a) || !properFace(b)) return false;
  for (const Triangle* t : {&a, &b})
    for (std::uint32_t v : *t)
      if (v >= pos.size()) throw Error("facesIntersect: vertex index " + std::to_string(v) + " out of range");
  // Boxes apart on an axis: no common point (and no shared vertex), decided by comparisons alone
  // before the planes and projection axes are made (most pairs the callers test are such).
  for (int k = 0; k < 3; ++k) {
    const double aLo = std::min({pos[a[0]][k], pos[a[1]][k], pos[a[2]][k]}), aHi = std::max({pos[a[0]][k], pos[a[1]][k], pos[a[2]][k]});
    const double bLo = std::min({pos[b[0]][k], pos[b[1]][k], pos[b[2]][k]}), bHi = std::max({pos[b[0]][k], pos[b[1]][k], pos[b[2]][k]});
    if (aHi < bLo || bHi < aLo) return false;
  }
  const Plane aPlane = planeOf(pos[a[0]], pos[a[1]], pos[a[2]]), bPlane = planeOf(pos[b[0]], pos[b[1]], pos[b[2]]);
  return pairIntersects(pos, a, projectionAxis(pos[a[0]], pos[a[1]], pos[a[2]]), aPlane, b,
                        projectionAxis(pos[b[0]], pos[b[1]], pos[b[2]]), bPlane);
}

std::vector<std::pair<std::uint32_t, std::uint32_t>> findSelfIntersections(const std::vector<Vec3d>& pos,
                                                                          const std::vector<Triangle>& faces,
                                                                          const std::vector<char>* alive, int threads) {
  if (alive && alive->size() != faces.size())
    throw Error("findSelfIntersections: " + std::to_string(alive->size()) + " alive flags for " +
                std::to_string(faces.size()) + " faces");
  // The faces taking part, in increasing index order.
  std::vector<std::uint32_t> id;
  id.reserve(faces.size());
  for (size_t f = 0; f < faces.size(); ++f) {
    if (alive && !(*alive)[f]) continue;
    const Triangle& t = faces[f];
    if (t[0] >= pos.size() || t[1] >= pos.size() || t[2] >= pos.size())
      throw Error("findSelfIntersections: face " + std::to_string(f) + " has a vertex index out of range");
    if (!properFace(t)) continue;
    bool finite = true;
    for (std::uint32_t v : t) finite &= std::isfinite(pos[v][0]) && std::isfinite(pos[v][1]) && std::isfinite(pos[v][2]);
    if (finite) id.push_back(std::uint32_t(f));
  }
  const size_t n = id.size();
  PairList result;
  if (n < 2) return result;
  const int parts = parallelParts(n, threads, 4096);

  // Per face: box, projection axis, plane; the longest extents, the mesh's box, the edge lengths.
  std::vector<Box> box(n);
  std::vector<signed char> axis(n); // −1: degenerate
  std::vector<Plane> plane(n);
  std::vector<double> extent(n), partEdges(static_cast<size_t>(parts), 0.0);
  std::vector<Box> partBox(static_cast<size_t>(parts));
  parallelFor(n, parts, [&](size_t begin, size_t end, int part) {
    Box all = {{HUGE_VAL, HUGE_VAL, HUGE_VAL}, {-HUGE_VAL, -HUGE_VAL, -HUGE_VAL}};
    double edges = 0;
    for (size_t i = begin; i < end; ++i) {
      const Triangle& t = faces[id[i]];
      const Point &a = pos[t[0]], &b = pos[t[1]], &c = pos[t[2]];
      extent[i] = 0;
      for (int k = 0; k < 3; ++k) {
        box[i].lo[k] = std::min({a[k], b[k], c[k]});
        box[i].hi[k] = std::max({a[k], b[k], c[k]});
        extent[i] = std::max(extent[i], box[i].hi[k] - box[i].lo[k]);
        all.lo[k] = std::min(all.lo[k], box[i].lo[k]);
        all.hi[k] = std::max(all.hi[k], box[i].hi[k]);
      }
      edges += (a - b).Norm() + (b - c).Norm() + (c - a).Norm();
      axis[i] = static_cast<signed char>(projectionAxis(a, b, c));
      plane[i] = planeOf(a, b, c);
    }
    partBox[size_t(part)] = all;
    partEdges[size_t(part)] = edges;
  });
  Box all = partBox[0];
  double edges = 0;
  for (int part = 0; part < parts; ++part) {
    edges += partEdges[size_t(part)];
    for (int k = 0; k < 3; ++k) {
      all.lo[k] = std::min(all.lo[k], partBox[size_t(part)].lo[k]);
      all.hi[k] = std::max(all.hi[k], partBox[size_t(part)].hi[k]);
    }
  }

  // The cell side (the result does not depend on it, only which pairs are candidates).
  Grid grid;
  grid.origin = Point(all.lo[0], all.lo[1], all.lo[2]);
  const double across = std::max({all.hi[0] - all.lo[0], all.hi[1] - all.lo[1], all.hi[2] - all.lo[2]});
  // An entry packs a cell's Morton code above a face index of faceBits bits in 64 bits, so at most
  // 2^cellBits − 1 cells along an axis (cellBits = 14 for a million faces): the cells grow if needed.
  int faceBits = 1;
  while ((std::uint64_t(1) << faceBits) < n) ++faceBits;
  const int cellBits = std::min(21, (64 - faceBits) / 3);
  grid.side = std::max(kCellEdges * edges / double(3 * n), across / double((1u << cellBits) - 1));
  if (!(grid.side > 0) || !std::isfinite(grid.side)) grid.side = 1; // every face a single point
  for (;;) {
    double longCost = 0;
    for (size_t i = 0; i < n; ++i) {
      if (grid.span(extent[i]) <= kMaxCellsPerAxis + 1) continue;
      double cells = 1;
      for (int k = 0; k < 3; ++k) cells *= grid.span(box[i].hi[k] - box[i].lo[k]);
      longCost += std::min(cells, double(n));
    }
    if (longCost <= kLongBudget * double(n) || grid.side >= across) break;
    grid.side *= 2;
  }
  int bits = 1; // per axis, for the largest cell coordinate
  while (bits < cellBits && double(std::uint64_t(1) << bits) <= across / grid.side) ++bits;
  const std::uint64_t faceMask = (std::uint64_t(1) << faceBits) - 1;
  std::vector<Cell> lo(n);
  std::vector<char> isLong(n);
  std::vector<std::uint32_t> longFaces;
  for (size_t i = 0; i < n; ++i) {
    lo[i] = grid.cellOf(box[i].lo);
    isLong[i] = grid.span(extent[i]) > kMaxCellsPerAxis + 1;
    if (isLong[i]) longFaces.push_back(std::uint32_t(i));
  }
  std::vector<double>().swap(extent);

  // The (cell, face) entries of the short faces, sorted by cell: the runs of one cell.
  std::vector<size_t> partStart(static_cast<size_t>(parts) + 1, 0);
  parallelFor(n, parts, [&](size_t begin, size_t end, int part) {
    size_t count = 0;
    for (size_t i = begin; i < end; ++i) {
      if (isLong[i]) continue;
      const Cell hi = grid.cellOf(box[i].hi);
      count += size_t(hi.c[0] - lo[i].c[0] + 1) * size_t(hi.c[1] - lo[i].c[1] + 1) * size_t(hi.c[2] - lo[i].c[2] + 1);
    }
    partStart[size_t(part) + 1] = count;
  });
  for (int part = 0; part < parts; ++part) partStart[size_t(part) + 1] += partStart[size_t(part)];
  std::vector<std::uint64_t> entries(partStart.back());
  parallelFor(n, parts, [&](size_t begin, size_t end, int part) {
    std::uint64_t* out = entries.data() + partStart[size_t(part)];
    for (size_t i = begin; i < end; ++i) {
      if (isLong[i]) continue;
      const Cell hi = grid.cellOf(box[i].hi);
      for (std::int32_t x = lo[i].c[0]; x <= hi.c[0]; ++x)
        for (std::int32_t y = lo[i].c[1]; y <= hi.c[1]; ++y)
          for (std::int32_t z = lo[i].c[2]; z <= hi.c[2]; ++z) *out++ = grid.key(x, y, z) << faceBits | i;
    }
  });
  sortEntries(entries, faceBits, 3 * bits);
  std::vector<std::uint32_t> runStart;
  std::vector<Cell> runCell;
  std::vector<std::uint64_t> runKey;
  for (size_t e = 0; e < entries.size(); ++e)
    if (e == 0 || entries[e] >> faceBits != entries[e - 1] >> faceBits) {
      const std::uint64_t key = entries[e] >> faceBits;
      runStart.push_back(std::uint32_t(e));
      runKey.push_back(key);
      Cell c = {{0, 0, 0}}; // the key's bits are the coordinates' bits, interleaved
      for (int b = 0; b < bits; ++b)
        for (int k = 0; k < 3; ++k) c.c[k] |= std::int32_t((key >> (3 * b + k)) & 1u) << b;
      runCell.push_back(c);
    }
  runStart.push_back(std::uint32_t(entries.size()));
  const size_t runs = runKey.size();

  auto test = [&](std::uint32_t i, std::uint32_t j, PairList& out) {
    if (pairIntersects(pos, faces[id[i]], axis[i], plane[i], faces[id[j]], axis[j], plane[j]))
      out.emplace_back(std::min(id[i], id[j]), std::max(id[i], id[j]));
  };

  // Pairs of short faces, each tested in the run of its reference cell only.
  const int workers = parallelParts(runs, threads, 1 << 12);
  std::vector<PairList> found(static_cast<size_t>(std::max(workers, 1)));
  parallelChunks(runs, workers, 1 << 10, [&](size_t begin, size_t end, int w) {
    PairList& out = found[size_t(w)];
    for (size_t r = begin; r < end; ++r)
      for (std::uint32_t x = runStart[r]; x < runStart[r + 1]; ++x) {
        const std::uint32_t i = std::uint32_t(entries[x] & faceMask);
        for (std::uint32_t y = x + 1; y < runStart[r + 1]; ++y) {
          const std::uint32_t j = std::uint32_t(entries[y] & faceMask);
          if (boxesOverlap(box[i], box[j]) && referenceCellIs(lo[i], lo[j], runCell[r])) test(i, j, out);
        }
      }
  });

  // Long faces: against the short faces listed in the cells their box covers, or against every
  // short face's box when there are more such cells than faces; and against the long faces after
  // them.
  std::vector<PairList> foundLong(longFaces.size());
  parallelChunks(longFaces.size(), parallelParts(longFaces.size(), threads, 1), 1, [&](size_t begin, size_t end, int) {
    for (size_t l = begin; l < end; ++l) {
      const std::uint32_t i = longFaces[l];
      PairList& out = foundLong[l];
      const Cell hi = grid.cellOf(box[i].hi);
      double boxCells = 1;
      for (int k = 0; k < 3; ++k) boxCells *= double(hi.c[k] - lo[i].c[k] + 1);
      if (boxCells <= double(n)) {
        for (std::int32_t x = lo[i].c[0]; x <= hi.c[0]; ++x)
          for (std::int32_t y = lo[i].c[1]; y <= hi.c[1]; ++y)
            for (std::int32_t z = lo[i].c[2]; z <= hi.c[2]; ++z) {
              const std::uint64_t key = grid.key(x, y, z);
              const auto it = std::lower_bound(runKey.begin(), runKey.end(), key);
              if (it == runKey.end() || *it != key) continue;
              const size_t r = size_t(it - runKey.begin());
              for (std::uint32_t e = runStart[r]; e < runStart[r + 1]; ++e) {
                const std::uint32_t j = std::uint32_t(entries[e] & faceMask);
                if (boxesOverlap(box[i], box[j]) && referenceCellIs(lo[i], lo[j], runCell[r])) test(i, j, out);
              }
            }
      } else {
        for (std::uint32_t j = 0; j < n; ++j)
          if (!isLong[j] && boxesOverlap(box[i], box[j])) test(i, j, out);
      }
      for (size_t m = l + 1; m < longFaces.size(); ++m)
        if (boxesOverlap(box[i], box[longFaces[m]])) test(i, longFaces[m], out);
    }
  });

  size_t total = 0;
  for (const auto& v : found) total += v.size();
  for (const auto& v : foundLong) total += v.size();
  result.reserve(total);
  for (const auto& v : found) result.insert(result.end(), v.begin(), v.end());
  for (const auto& v : foundLong) result.insert(result.end(), v.begin(), v.end());
  std::sort(result.begin(), result.end());
  return result;
}

size_t removeSelfIntersections(const std::vector<Vec3d>& pos, const std::vector<Triangle>& faces,
                               std::vector<char>& alive, int threads) {
  if (alive.size() != faces.size())
    throw Error("removeSelfIntersections: " + std::to_string(alive.size()) + " alive flags for " +
                std::to_string(faces.size()) + " faces");
  const PairList pairs = findSelfIntersections(pos, faces, &alive, threads);
  if (pairs.empty()) return 0;

  // The conflict graph (faces as nodes, pairs as edges) in compressed rows.
  std::vector<std::uint32_t> degree(faces.size() + 1, 0);
  for (const auto& p : pairs) {
    ++degree[p.first + 1];
    ++degree[p.second + 1];
  }
  std::vector<std::uint32_t> start(degree);
  for (size_t f = 0; f < faces.size(); ++f) start[f + 1] += start[f];
  std::vector<std::uint32_t> neighbour(start.back());
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (const auto& p : pairs) {
      neighbour[fill[p.first]++] = p.second;
      neighbour[fill[p.second]++] = p.first;
    }
  }
  degree.erase(degree.begin()); // degree[f] = pairs of face f still standing

  // Greedy cover: the face in most remaining pairs first, the lowest index among equals. A heap
  // of (degree, −index) with stale entries skipped (every change of a degree pushes a new one).
  std::priority_queue<std::pair<std::uint32_t, std::int64_t>> heap;
  for (size_t f = 0; f < faces.size(); ++f)
    if (degree[f] > 0) heap.emplace(degree[f], -std::int64_t(f));
  size_t removed = 0;
  while (!heap.empty()) {
    const auto top = heap.top();
    heap.pop();
    const size_t f = size_t(-top.second);
    if (degree[f] == 0 || degree[f] != top.first) continue;
    alive[f] = 0;
    ++removed;
    degree[f] = 0;
    for (std::uint32_t k = start[f]; k < start[f + 1]; ++k) {
      const std::uint32_t g = neighbour[k];
      if (degree[g] == 0) continue;
      if (--degree[g] > 0) heap.emplace(degree[g], -std::int64_t(g));
    }
  }
  return removed;
}

} // namespace growth
