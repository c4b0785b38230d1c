// Vertex candidates (fig. 4c): the circle of points at distance d from both parents cut by a
// splat's disk; per-splat lists of the vertices within d (sec. 4.4).
#include "box_grid.h"
#include "candidates.h"
#include <growth/cloud_generator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <tuple>

using Point3d = growth::Vec3d;

TEST(ParentCircle, PointsAreAtDistanceDFromBothParents) {
  growth::Random rnd(4);
  const double d = 0.3;
  for (int k = 0; k < 200; ++k) {
    const Point3d a(rnd.uniform(-1, 1), rnd.uniform(-1, 1), rnd.uniform(-1, 1));
    const Point3d b = a + rnd.unitVector() * rnd.uniform(d, 2 * d);
    const auto c = growth::parentCircle(a, b, d);
    ASSERT_TRUE(c.valid);
    EXPECT_NEAR((c.centre - (a + b) * 0.5).Norm(), 0, 1e-15);
    EXPECT_NEAR(c.radius * c.radius + 0.25 * (b - a).SquaredNorm(), d * d, 1e-14);
  }
  EXPECT_FALSE(growth::parentCircle(Point3d(0, 0, 0), Point3d(0.61, 0, 0), 0.3).valid); // farther than 2d
  EXPECT_FALSE(growth::parentCircle(Point3d(1, 1, 1), Point3d(1, 1, 1), 0.3).valid);     // one point
  const auto touching = growth::parentCircle(Point3d(0, 0, 0), Point3d(0.6, 0, 0), 0.3);
  ASSERT_TRUE(touching.valid);
  EXPECT_EQ(touching.radius, 0.0);
}

TEST(CircleSplat, IntersectionsAreOnTheCircleThePlaneAndTheDisk) {
  growth::Random rnd(8);
  const double d = 0.2;
  int found = 0;
  for (int k = 0; k < 2000; ++k) {
    const Point3d a(0, 0, 0), b = rnd.unitVector() * rnd.uniform(d, 2 * d);
    const Point3d p = (a + b) * 0.5 + rnd.inBall(0.25);
    const Point3d n = rnd.unitVector();
    const double s = rnd.uniform(0.02, 0.3);
    const auto c = growth::parentCircle(a, b, d);
    Point3d x[2];
    int root[2];
    const int m = growth::circleSplatIntersections(c, p, n, s, x, root);
    for (int j = 0; j < m; ++j) {
      ++found;
      EXPECT_NEAR((x[j] - a).Norm(), d, 1e-12);
      EXPECT_NEAR((x[j] - b).Norm(), d, 1e-12);
      EXPECT_NEAR((x[j] - p) * n, 0, 1e-12);
      EXPECT_LE((x[j] - p).Norm(), s * (1 + 1e-12));
      // The same root recomputed gives the same point, bit for bit (candidates are stored as
      // (parents, splat, root) and recomputed when popped).
      Point3d y;
      ASSERT_TRUE(growth::circleSplatPoint(c, p, n, s, root[j], y));
      EXPECT_EQ(x[j], y);
    }
    // And every root circleSplatPoint() accepts is one of them (a tangent circle's two equal
    // roots count once).
    for (int r = 0; r < 2; ++r) {
      Point3d y;
      if (!growth::circleSplatPoint(c, p, n, s, r, y)) continue;
      bool listed = false;
      for (int j = 0; j < m; ++j) listed = listed || x[j] == y;
      EXPECT_TRUE(listed) << "trial " << k << " root " << r;
    }
    // Completeness: dense samples of the circle on the plane and inside the disk are near a root.
    Point3d e1, e2;
    growth::tangentFrame(c.axis, e1, e2);
    for (int t = 0; t < 720; ++t) {
      const double th = 2 * M_PI * t / 720;
      const Point3d q = c.centre + (e1 * std::cos(th) + e2 * std::sin(th)) * c.radius;
      if (std::abs((q - p) * n) > 1e-4 || (q - p).Norm() > 0.98 * s) continue;
      double best = 1e9;
      for (int j = 0; j < m; ++j) best = std::min(best, (q - x[j]).Norm());
      EXPECT_LT(best, 0.02 * d) << "missed an intersection, trial " << k;
    }
  }
  EXPECT_GT(found, 300);
}

TEST(CircleSplat, NoIntersectionWhenTheDiskIsTooSmallOrTheCircleMissesThePlane) {
  const auto c = growth::parentCircle(Point3d(0, 0, 0), Point3d(0.1, 0, 0), 0.1); // radius ~0.0866
  Point3d x[2];
  int r[2];
  // Splat plane z = 0.2: the circle (in the plane x = 0.05) never reaches it.
  EXPECT_EQ(growth::circleSplatIntersections(c, Point3d(0.05, 0, 0.2), Point3d(0, 0, 1), 1.0, x, r), 0);
  // Plane z = 0 meets the circle at y = ±0.0866; a disk of radius 0.05 at the midpoint misses both.
  EXPECT_EQ(growth::circleSplatIntersections(c, Point3d(0.05, 0, 0), Point3d(0, 0, 1), 0.05, x, r), 0);
  // Large enough: both.
  EXPECT_EQ(growth::circleSplatIntersections(c, Point3d(0.05, 0, 0), Point3d(0, 0, 1), 0.09, x, r), 2);
  // Disk around one of them only.
  EXPECT_EQ(growth::circleSplatIntersections(c, Point3d(0.05, 0.08, 0), Point3d(0, 0, 1), 0.02, x, r), 1);
  EXPECT_NEAR(x[0][1], std::sqrt(0.0075), 1e-12);
  // Splat plane containing the axis direction only (normal along the axis): no single point.
  EXPECT_EQ(growth::circleSplatIntersections(c, Point3d(0.05, 0, 0), Point3d(1, 0, 0), 1.0, x, r), 0);
}

TEST(SplatVertexLists, NewestFirst) {
  growth::SplatVertexLists l;
  l.reset(3);
  l.add(1, 10);
  l.add(1, 11);
  l.add(2, 12);
  std::vector<std::uint32_t> got;
  l.forEach(1, [&](std::uint32_t v) { got.push_back(v); });
  EXPECT_EQ(got, (std::vector<std::uint32_t>{11, 10}));
  got.clear();
  l.forEach(0, [&](std::uint32_t v) { got.push_back(v); });
  EXPECT_TRUE(got.empty());
  EXPECT_EQ(l.entries(), 3u);
  // Across chunks, interleaved with other splats: still newest first, each entry once.
  std::vector<std::uint32_t> want0, want2;
  for (std::uint32_t v = 100; v < 140; ++v) {
    l.add(v % 3 == 0 ? 0 : 2, v);
    (v % 3 == 0 ? want0 : want2).insert((v % 3 == 0 ? want0 : want2).begin(), v);
  }
  want2.push_back(12);
  got.clear();
  l.forEach(0, [&](std::uint32_t v) { got.push_back(v); });
  EXPECT_EQ(got, want0);
  got.clear();
  l.forEach(2, [&](std::uint32_t v) { got.push_back(v); });
  EXPECT_EQ(got, want2);
  EXPECT_EQ(l.entries(), 43u);
}

TEST(EnumerateCandidates, MatchesBruteForceOverAllSplats) {
  // A planar patch of splats; vertices placed on it one by one, as the growth would.
  std::vector<Point3d> pts, nrm;
  growth::Random rnd(21);
  for (int i = 0; i < 3000; ++i) {
    pts.emplace_back(rnd.uniform(0, 1), rnd.uniform(0, 1), 0.002 * rnd.uniform(-1, 1));
    nrm.push_back(Point3d(0.05 * rnd.uniform(-1, 1), 0.05 * rnd.uniform(-1, 1), 1).Normalize());
  }
  const double d = 0.1;
  std::vector<float> rad(pts.size(), 0.03f);
  growth::BoxGrid grid;
  grid.build(pts, nrm, d);
  growth::SplatSet splats{&pts, &nrm, &rad};
  growth::SplatVertexLists lists;
  lists.reset(pts.size());
  std::vector<Point3d> verts;
  for (int k = 0; k < 40; ++k) verts.push_back(pts[size_t(k * 71 % 3000)]);

  using Cand = std::tuple<std::uint32_t, std::uint32_t, int>;
  for (std::uint32_t v = 0; v < verts.size(); ++v) {
    std::vector<Cand> got, want;
    growth::enumerateCandidates(v, verts, Point3d(0, 0, 0), d, grid, splats, lists, [&](std::uint32_t u, std::uint32_t s, int root, const Point3d& x) {
      got.emplace_back(u, s, root);
      EXPECT_NEAR((x - verts[v]).Norm(), d, 1e-12);
      EXPECT_NEAR((x - verts[u]).Norm(), d, 1e-12);
    });
    // Sec. 4.4 takes the splats near a vertex from the box containing it (points within d of the
    // box): a splat counts for v when it is in v's box and its disk comes within d of v.
    auto inBoxOf = [&](std::uint32_t w, std::uint32_t s) {
      const int b = grid.boxOf(verts[w]);
      return b >= 0 && std::binary_search(grid.pointsBegin(b), grid.pointsEnd(b), s);
    };
    for (std::uint32_t u = 0; u < v; ++u)
      for (std::uint32_t s = 0; s < pts.size(); ++s) {
        if (growth::squaredDistanceToDisk(verts[v], pts[s], nrm[s], rad[s]) > d * d || !inBoxOf(v, s)) continue;
        if (growth::squaredDistanceToDisk(verts[u], pts[s], nrm[s], rad[s]) > d * d || !inBoxOf(u, s)) continue;
        const auto c = growth::parentCircle(verts[v], verts[u], d);
        Point3d x[2];
        int root[2];
        const int m = growth::circleSplatIntersections(c, pts[s], nrm[s], rad[s], x, root);
        for (int j = 0; j < m; ++j) want.emplace_back(u, s, root[j]);
      }
    std::sort(got.begin(), got.end());
    std::sort(want.begin(), want.end());
    EXPECT_EQ(got, want) << "vertex " << v;
  }
  // Every vertex was registered with the splats within d of it.
  for (std::uint32_t s = 0; s < pts.size(); s += 7) {
    std::vector<std::uint32_t> listed, within;
    lists.forEach(s, [&](std::uint32_t v) { listed.push_back(v); });
    for (std::uint32_t v = 0; v < verts.size(); ++v) {
      const int b = grid.boxOf(verts[v]);
      const bool inBox = b >= 0 && std::binary_search(grid.pointsBegin(b), grid.pointsEnd(b), s);
      if (inBox && growth::squaredDistanceToDisk(verts[v], pts[s], nrm[s], rad[s]) <= d * d) within.push_back(v);
    }
    std::sort(listed.begin(), listed.end());
    EXPECT_EQ(listed, within);
  }
}
