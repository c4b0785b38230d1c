// Splats (sec. 3.2) and their local sizes (sec. 4.3): rotation onto the tangent plane, Delaunay
// flips of the central fan, farthest Voronoi vertex; global size when switched off.
#include "box_grid.h"
#include <growth/cloud_generator.h>
#include <growth/point_grid.h>
#include "splats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numeric>

using Point3d = growth::Vec3d;

TEST(Splats, TangentFrameIsOrthonormalAndRightHanded) {
  growth::Random rnd(1);
  for (int k = 0; k < 100; ++k) {
    const Point3d n = rnd.unitVector();
    Point3d e1, e2;
    growth::tangentFrame(n, e1, e2);
    EXPECT_NEAR(e1.Norm(), 1, 1e-12);
    EXPECT_NEAR(e2.Norm(), 1, 1e-12);
    EXPECT_NEAR(e1 * n, 0, 1e-12);
    EXPECT_NEAR(e2 * n, 0, 1e-12);
    EXPECT_NEAR(e1 * e2, 0, 1e-12);
    EXPECT_NEAR(((e1 ^ e2) - n).Norm(), 0, 1e-12);
  }
}

TEST(Splats, DistanceToDiskAndProjection) {
  const Point3d c(1, 1, 1), n(0, 0, 1);
  const double r = 0.5;
  EXPECT_NEAR(growth::squaredDistanceToDisk(Point3d(1.2, 1, 1.3), c, n, r), 0.09, 1e-12); // above the disk
  EXPECT_NEAR(growth::squaredDistanceToDisk(Point3d(2, 1, 1), c, n, r), 0.25, 1e-12);     // beside the rim
  EXPECT_NEAR(growth::squaredDistanceToDisk(Point3d(2, 1, 2), c, n, r), 0.25 + 1, 1e-12);
  EXPECT_NEAR((growth::projectOntoDisk(Point3d(2, 1, 2), c, n, r) - Point3d(1.5, 1, 1)).Norm(), 0, 1e-12);
  EXPECT_NEAR((growth::projectOntoDisk(Point3d(1.1, 1.2, -3), c, n, r) - Point3d(1.1, 1.2, 1)).Norm(), 0, 1e-12);
}

namespace {
std::vector<Point3d> hexLattice(double h, int rings, const Point3d& centre, bool skipCentre) {
  std::vector<Point3d> v;
  for (int i = -rings; i <= rings; ++i)
    for (int j = -rings; j <= rings; ++j) {
      if (skipCentre && i == 0 && j == 0) continue;
      const double x = h * (i + 0.5 * j), y = h * (std::sqrt(3.0) / 2 * j);
      if (std::hypot(x, y) <= rings * h + 1e-9) v.emplace_back(centre[0] + x, centre[1] + y, centre[2]);
    }
  return v;
}
} // namespace

TEST(LocalSplatRadius, HexLatticeKeepsTheSixNeighboursAndGivesTheCircumradius) {
  const double h = 0.1;
  const auto nb = hexLattice(h, 3, Point3d(0, 0, 0), true);
  ASSERT_GT(nb.size(), 20u);
  std::vector<int> kept;
  const double r = growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb, &kept);
  EXPECT_NEAR(r, h / std::sqrt(3.0), 1e-12);
  ASSERT_EQ(kept.size(), 6u); // the far rings are flipped away
  for (int k : kept) EXPECT_NEAR(nb[size_t(k)].Norm(), h, 1e-12);
}

TEST(LocalSplatRadius, SquareLatticeGivesHalfTheDiagonal) {
  const double h = 0.2;
  std::vector<Point3d> nb;
  for (int i = -3; i <= 3; ++i)
    for (int j = -3; j <= 3; ++j)
      if (i != 0 || j != 0) nb.emplace_back(h * i, h * j, 0);
  EXPECT_NEAR(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb), h / std::sqrt(2.0), 1e-12);
}

TEST(LocalSplatRadius, RotationKeepsDistancesOnACurvedNeighbourhood) {
  // Lattice points lifted onto a sphere touching the plane at p: after the rotation back onto
  // T_p they sit at their 3D distance from p, in their original directions.
  const double R = 0.5, h = 0.1;
  const auto flat = hexLattice(h, 2, Point3d(0, 0, 0), true);
  std::vector<Point3d> curved, rotated;
  for (const auto& q : flat) {
    const double rho = q.Norm(), phi = rho / R; // arc length rho on the sphere
    const Point3d dir = q / rho;
    const Point3d onSphere = dir * (R * std::sin(phi)) + Point3d(0, 0, R - R * std::cos(phi));
    curved.push_back(onSphere);
    rotated.push_back(dir * onSphere.Norm());
  }
  const double a = growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), curved);
  const double b = growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), rotated);
  EXPECT_NEAR(a, b, 1e-12);
  EXPECT_GT(a, 0);
}

TEST(LocalSplatRadius, FlipRemovesAPointBehindANearerOne) {
  // Square of four neighbours at distance 1, plus a far point in a diagonal direction: the far
  // point's spoke is not Delaunay and is flipped away; the radius is that of the square fan.
  std::vector<Point3d> nb{Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(-1, 0, 0), Point3d(0, -1, 0),
                          Point3d(3, 3, 0)};
  std::vector<int> kept;
  const double r = growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb, &kept);
  EXPECT_NEAR(r, std::sqrt(0.5), 1e-12);
  EXPECT_EQ(kept.size(), 4u);
  EXPECT_EQ(std::count(kept.begin(), kept.end(), 4), 0);
  // A point just inside the circle through p and two square neighbours is a Delaunay neighbour.
  // (The other three quadrants still give sqrt(0.5).)
  nb.back() = Point3d(0.9, 0.9, 0);
  EXPECT_NEAR(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb, &kept), std::sqrt(0.5), 1e-12);
  EXPECT_EQ(kept.size(), 5u);
  for (const Point3d& q : {Point3d(-0.9, -0.9, 0), Point3d(-0.9, 0.9, 0), Point3d(0.9, -0.9, 0)}) nb.push_back(q);
  EXPECT_LT(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb, &kept), std::sqrt(0.5));
}

TEST(LocalSplatRadius, OpenFanIsUnbounded) {
  // Neighbours only on one side (a boundary point): no bounded Voronoi cell.
  std::vector<Point3d> nb{Point3d(1, 0, 0), Point3d(1, 1, 0), Point3d(0, 1, 0), Point3d(-1, 1, 0), Point3d(-1, 0.01, 0)};
  EXPECT_LT(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), nb), 0);
  EXPECT_LT(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), {Point3d(1, 0, 0), Point3d(0, 1, 0)}), 0);
  // Points on the normal line have no direction in the tangent plane and are ignored.
  EXPECT_LT(growth::localSplatRadius(Point3d(0, 0, 0), Point3d(0, 0, 1), {Point3d(0, 0, 1), Point3d(0, 0, -2), Point3d(1, 0, 0)}), 0);
}

namespace {
growth::Cloud sphereCloud(size_t n) {
  growth::CloudSpec spec;
  spec.count = n;
  spec.seed = 3;
  return growth::generateCloud(spec);
}
} // namespace

TEST(SplatRadii, GlobalSizeWhenLocalIsOff) {
  const auto c = sphereCloud(2000);
  const auto r = growth::computeSplatRadii(c.points, c.normals, 0.07, 0.0, false);
  ASSERT_EQ(r.size(), c.points.size());
  for (float x : r) EXPECT_EQ(x, 0.07f);
}

TEST(SplatRadii, LocalSizesAreSmallerAndStillCoverTheSphere) {
  const auto c = sphereCloud(10000);
  const double s = 0.1;
  growth::SplatSizeStats st;
  const auto r = growth::computeSplatRadii(c.points, c.normals, s, 0.05, true, &st);
  EXPECT_EQ(st.unbounded, 0u); // a closed, densely sampled surface: every fan closes
  EXPECT_LT(st.meanRadius, 0.6 * s);
  for (float x : r) EXPECT_LE(x, float(s));
  // Covered: every probe point of the true sphere projects (along the splat normal) into some
  // splat whose plane passes within a small distance of it.
  growth::PointGrid grid;
  grid.build(c.points, s);
  growth::Random rnd(77);
  size_t uncovered = 0;
  for (int k = 0; k < 20000; ++k) {
    const Point3d x = rnd.unitVector();
    bool covered = false;
    grid.forEachInBall(x, s, [&](int i, double) {
      const Point3d v = x - c.points[size_t(i)];
      const double h = v * c.normals[size_t(i)];
      if ((v - c.normals[size_t(i)] * h).Norm() <= r[size_t(i)]) covered = true;
    });
    uncovered += covered ? 0 : 1;
  }
  EXPECT_EQ(uncovered, 0u);
}

// The radii are computed on several threads: the same radii, bit for bit, and the same counts for
// any number of them (an open patch: boundary points with unbounded cells, and clamped ones).
TEST(SplatRadii, SameRadiiForAnyNumberOfThreads) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Patch;
  spec.count = 12000;
  spec.seed = 6;
  spec.nonUniform = true;
  const auto c = growth::generateCloud(spec);
  const double s = 0.03;
  growth::SplatSizeStats one;
  const auto r1 = growth::computeSplatRadii(c.points, c.normals, s, 0.05, true, &one, nullptr, 1);
  EXPECT_GT(one.unbounded, 0u);
  EXPECT_GT(one.clamped, 0u);
  for (int threads : {2, 3, 7}) {
    growth::SplatSizeStats st;
    const auto r = growth::computeSplatRadii(c.points, c.normals, s, 0.05, true, &st, nullptr, threads);
    ASSERT_EQ(r, r1) << threads << " threads";
    EXPECT_EQ(st.unbounded, one.unbounded);
    EXPECT_EQ(st.clamped, one.clamped);
    EXPECT_EQ(st.meanRadius, one.meanRadius);
  }
}

// The neighbourhood grows until it holds every Delaunay neighbour (within 2r): the radii do not
// depend on the first reach, from a fraction of the spacing to the largest one (2s), and the
// largest takes every point that can matter.
TEST(SplatRadii, RadiiDoNotDependOnTheFirstReach) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 8000;
  spec.seed = 12;
  spec.nonUniform = true;
  const auto c = growth::generateCloud(spec);
  const double s = 0.3; // about 5 spacings
  growth::SplatSizeStats ref;
  const auto r0 = growth::computeSplatRadii(c.points, c.normals, s, 2 * s, true, &ref, nullptr, 1);
  EXPECT_EQ(ref.unbounded, 0u);
  size_t local = 0;
  for (float r : r0) local += r < float(s) ? 1 : 0;
  EXPECT_EQ(local, c.points.size());
  for (double reach : {0.005, 0.03, 0.1}) {
    growth::SplatSizeStats st;
    const auto r = growth::computeSplatRadii(c.points, c.normals, s, reach, true, &st, nullptr, 2);
    ASSERT_EQ(r, r0) << "first reach " << reach;
  }
}

// Points renumbered with their original indices as rankIndex: the same radius for every point.
TEST(SplatRadii, RenumberedPointsGetTheSameRadii) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 12000;
  spec.seed = 8;
  spec.nonUniform = true;
  const auto c = growth::generateCloud(spec);
  const size_t n = c.points.size();
  growth::Random rnd(3);
  std::vector<std::uint32_t> orig(n), rank(n);
  for (size_t i = 0; i < n; ++i) orig[i] = std::uint32_t(i);
  for (size_t i = n - 1; i > 0; --i) std::swap(orig[i], orig[size_t(rnd.uniform(0, double(i + 1))) % (i + 1)]);
  for (size_t i = 0; i < n; ++i) rank[orig[i]] = std::uint32_t(i);
  std::vector<Point3d> pts(n), nrm(n);
  for (size_t i = 0; i < n; ++i) pts[i] = c.points[orig[i]], nrm[i] = c.normals[orig[i]];
  const double s = 0.12;
  growth::SplatSizeStats sa, sb;
  const auto ra = growth::computeSplatRadii(c.points, c.normals, s, 0.05, true, &sa, nullptr, 2);
  const auto rb = growth::computeSplatRadii(pts, nrm, s, 0.05, true, &sb, nullptr, 2, &orig);
  for (size_t i = 0; i < n; ++i) ASSERT_EQ(rb[i], ra[orig[i]]) << i;
  EXPECT_EQ(sb.unbounded, sa.unbounded);
  EXPECT_EQ(sb.clamped, sa.clamped);
}

// The local splat radius as computed by the plain code that the faster scratch arrays and sort
// replaced (verbatim): the rewrite must give the same radius and the same fan, bit for
// bit, on every kind of neighbourhood.
namespace reference {
using growth::tangentFrame;
struct Q {
  double x, y;
  double angle;
  double dist2;
  int index;
};
inline double cross(const Q& a, const Q& b) { return a.x * b.y - a.y * b.x; }
// A monotonic function of the polar angle of (x, y) over [0, 2π), in [0, 4): the same cyclic
// order as atan2 without the trigonometry.
inline double pseudoAngle(double x, double y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}
inline double orient(const Q& a, const Q& b, double cx, double cy) {
  return (b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x);
}
// > 0 when d lies inside the circumcircle of the counter-clockwise triangle (origin, b, c).
inline double inCircleOrigin(const Q& b, const Q& c, const Q& d) {
  const double b2 = b.x * b.x + b.y * b.y, c2 = c.x * c.x + c.y * c.y, d2 = d.x * d.x + d.y * d.y;
  return -(b.x * (c.y * d2 - c2 * d.y) - b.y * (c.x * d2 - c2 * d.x) + b2 * (c.x * d.y - c.y * d.x));
}

// Scratch buffers of the computation, reused from point to point.
struct FanScratch {
  std::vector<Q> fan;
  std::vector<int> prev, next, work;
  std::vector<char> alive;
};

double fanRadius(const growth::Vec3d& p, const growth::Vec3d& n, const std::vector<growth::Vec3d>& neighbours,
                 std::vector<int>* keptOut, FanScratch& scratch) {
  std::vector<Q>& fan = scratch.fan;
  std::vector<int>&prev = scratch.prev, &next = scratch.next, &work = scratch.work;
  std::vector<char>& alive = scratch.alive;
  fan.clear();
  if (keptOut != nullptr) keptOut->clear();

  growth::Vec3d e1, e2;
  tangentFrame(n, e1, e2);
  // Rotation about p onto T_p inside the plane spanned by n and p_i - p: the tangential part of
  // p_i - p, rescaled to the full distance |p_i - p|.
  // (e1, e2 are orthogonal to n, so <t, e> = <p_i − p, e>, and |t|² = |p_i − p|² − h².)
  for (size_t i = 0; i < neighbours.size(); ++i) {
    const growth::Vec3d v = neighbours[i] - p;
    const double len2 = v.SquaredNorm();
    const double h = v * n;
    const double tlen2 = len2 - h * h;
    if (!(tlen2 > 1e-24 * len2)) continue; // on the normal line: no direction in T_p
    const double scale = std::sqrt(len2 / tlen2);
    Q q;
    q.x = (v * e1) * scale;
    q.y = (v * e2) * scale;
    q.angle = pseudoAngle(q.x, q.y);
    q.dist2 = len2;
    q.index = static_cast<int>(i);
    fan.push_back(q);
  }
  std::sort(fan.begin(), fan.end(), [](const Q& a, const Q& b) {
    if (a.angle != b.angle) return a.angle < b.angle;
    if (a.dist2 != b.dist2) return a.dist2 < b.dist2;
    return a.index < b.index;
  });
  // The same direction (up to rounding): only the nearer point can be a Delaunay neighbour.
  {
    size_t w = 0;
    for (size_t i = 0; i < fan.size(); ++i) {
      if (w > 0) {
        const Q& a = fan[w - 1];
        const double c = cross(a, fan[i]);
        if (c * c <= 1e-24 * a.dist2 * fan[i].dist2 && a.x * fan[i].x + a.y * fan[i].y > 0) {
          if (fan[i].dist2 < a.dist2) fan[w - 1] = fan[i];
          continue;
        }
      }
      fan[w++] = fan[i];
    }
    fan.resize(w);
    // The same check across the seam of the sort.
    if (fan.size() > 1) {
      const Q &a = fan.back(), &b = fan.front();
      const double c = cross(a, b);
      if (c * c <= 1e-24 * a.dist2 * b.dist2 && a.x * b.x + a.y * b.y > 0) {
        if (a.dist2 < b.dist2) fan.front() = a;
        fan.pop_back();
      }
    }
  }
  const int m = static_cast<int>(fan.size());
  if (m < 3) return -1;

  prev.resize(size_t(m));
  next.resize(size_t(m));
  alive.assign(size_t(m), 1);
  for (int i = 0; i < m; ++i) prev[size_t(i)] = i - 1, next[size_t(i)] = i + 1;
  prev[0] = m - 1;
  next[size_t(m - 1)] = 0;
  work.resize(size_t(m));
  std::iota(work.begin(), work.end(), 0);
  std::reverse(work.begin(), work.end()); // popped from the back: index 0 first
  int count = m;

  // Flip central edges p–q_i that are not locally Delaunay; a flipped q_i leaves the fan.
  while (!work.empty() && count > 3) {
    const int i = work.back();
    work.pop_back();
    if (!alive[size_t(i)]) continue;
    const int j = prev[size_t(i)], l = next[size_t(i)];
    const Q &qj = fan[size_t(j)], &qi = fan[size_t(i)], &ql = fan[size_t(l)];
    // Both fan triangles (p, q_j, q_i) and (p, q_i, q_l) must exist (angles in (0, π)).
    if (!(cross(qj, qi) > 0) || !(cross(qi, ql) > 0)) continue;
    // The quadrilateral p, q_j, q_i, q_l must be convex for the flip: p and q_i on opposite sides
    // of the new diagonal q_j–q_l.
    const double sp = orient(qj, ql, 0.0, 0.0), si = orient(qj, ql, qi.x, qi.y);
    if (!(sp > 0 && si < 0)) continue;
    if (!(inCircleOrigin(qj, qi, ql) > 0)) continue; // locally Delaunay: keep
    alive[size_t(i)] = 0;
    --count;
    next[size_t(j)] = l;
    prev[size_t(l)] = j;
    work.push_back(l);
    work.push_back(j);
  }

  // The fan must be closed (every angle below π) for p's Voronoi cell to be bounded.
  int start = 0;
  while (!alive[size_t(start)]) ++start;
  double radius = 0;
  int i = start;
  do {
    const int l = next[size_t(i)];
    const Q &a = fan[size_t(i)], &b = fan[size_t(l)];
    const double c = cross(a, b);
    if (!(c > 0) || l == i) return -1;
    // Circumradius of (p, a, b) = distance from p to the Voronoi vertex of the three.
    const double ab2 = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
    radius = std::max(radius, std::sqrt(a.dist2 * b.dist2 * ab2) / (2.0 * c));
    if (keptOut != nullptr) keptOut->push_back(a.index);
    i = l;
  } while (i != start);
  return radius;
}

double localSplatRadius(const growth::Vec3d& p, const growth::Vec3d& n, const std::vector<growth::Vec3d>& neighbours,
                        std::vector<int>* keptOut) {
  FanScratch scratch;
  return fanRadius(p, n, neighbours, keptOut, scratch);
}
} // namespace reference

TEST(SplatRadii, LocalRadiusIsThatOfTheReferenceImplementation) {
  growth::Random rnd(21);
  size_t bounded = 0;
  for (int trial = 0; trial < 3000; ++trial) {
    const Point3d p(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1));
    const Point3d n = rnd.unitVector();
    Point3d e1, e2;
    growth::tangentFrame(n, e1, e2);
    std::vector<Point3d> nb;
    const int kind = trial % 6;
    const int count = 1 + int(rnd.uniform(0, kind == 5 ? 80 : 30));
    for (int k = 0; k < count; ++k) {
      double u = rnd.uniform(-1, 1), v = rnd.uniform(-1, 1), h = rnd.uniform(-0.2, 0.2);
      if (kind == 1) u = std::round(u * 4) / 4, v = std::round(v * 4) / 4, h = 0; // lattice: cocircular ties
      if (kind == 2) {                                                            // regular polygon
        const double a = 2 * M_PI * k / count;
        u = std::cos(a), v = std::sin(a), h = 0;
      }
      nb.push_back(p + e1 * u + e2 * v + n * h);
      if (kind == 3 && k % 3 == 0) nb.push_back(p + (e1 * u + e2 * v) * 2.0); // same direction, farther
      if (kind == 4 && k % 4 == 0) nb.push_back(p + n * rnd.uniform(-1, 1));  // on the normal line
      if (kind == 4 && k % 5 == 0) nb.push_back(p + e1 * u + e2 * v - n * h); // mirror: equal angle and distance
    }
    std::vector<int> keptA, keptB;
    const double a = growth::localSplatRadius(p, n, nb, &keptA);
    const double b = reference::localSplatRadius(p, n, nb, &keptB);
    ASSERT_EQ(a, b) << "trial " << trial;
    ASSERT_EQ(keptA, keptB) << "trial " << trial;
    bounded += a >= 0 ? 1 : 0;
  }
  EXPECT_GT(bounded, 1000u);
}
