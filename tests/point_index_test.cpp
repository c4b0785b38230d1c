#include <growth/point_index.h>

#include <growth/cloud_generator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <limits>
#include <set>
#include <vector>

using MortonGrid = growth::PointIndex;
using Point3d = growth::Vec3d;

namespace {

std::vector<Point3d> torusCloud(size_t n, std::uint64_t seed) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = n;
  spec.seed = seed;
  return growth::generateCloud(spec).points;
}

std::set<std::uint32_t> bruteBall(const MortonGrid& g, const Point3d& c, double r) {
  std::set<std::uint32_t> s;
  for (std::uint32_t i = 0; i < g.size(); ++i)
    if ((g.point(i) - c).SquaredNorm() <= r * r) s.insert(i);
  return s;
}

} // namespace

TEST(PointIndex, MortonCodesInterleaveTheCoordinateBits) {
  EXPECT_EQ(MortonGrid::morton(0, 0, 0), 0u);
  EXPECT_EQ(MortonGrid::morton(1, 0, 0), 1u);
  EXPECT_EQ(MortonGrid::morton(0, 1, 0), 2u);
  EXPECT_EQ(MortonGrid::morton(0, 0, 1), 4u);
  EXPECT_EQ(MortonGrid::morton(3, 0, 0), 9u);
  EXPECT_EQ(MortonGrid::morton(0x1fffff, 0x1fffff, 0x1fffff), (std::uint64_t(1) << 63) - 1);
}

TEST(PointIndex, EmptyAndSinglePoint) {
  MortonGrid g;
  g.build({}, 1.0);
  EXPECT_EQ(g.size(), 0u);
  EXPECT_EQ(g.nearest(Point3d(0, 0, 0)), -1);
  int calls = 0;
  g.forEachInBall(Point3d(0, 0, 0), 10, [&](std::uint32_t, double) { ++calls; });
  EXPECT_EQ(calls, 0);

  g.build({Point3d(1, 2, 3)}, 0.5);
  EXPECT_EQ(g.size(), 1u);
  EXPECT_EQ(g.nearest(Point3d(5, 5, 5)), 0);
  EXPECT_EQ(g.nearest(Point3d(5, 5, 5), 0), -1); // excluded
  EXPECT_EQ(g.nearest(Point3d(5, 5, 5), -1, 1.0), -1); // beyond maxRadius
}

TEST(PointIndex, PointsAreAPermutationInCellOrder) {
  const auto pts = torusCloud(5000, 3);
  MortonGrid g;
  g.build(pts, 0.2);
  ASSERT_EQ(g.size(), pts.size());
  std::vector<std::uint32_t> seen(g.order());
  std::sort(seen.begin(), seen.end());
  for (size_t i = 0; i < seen.size(); ++i) ASSERT_EQ(seen[i], i);
  for (std::uint32_t i = 0; i < g.size(); ++i) ASSERT_TRUE(g.point(i) == pts[g.order()[i]]);
  // Deterministic: the same input gives the same order.
  MortonGrid h;
  h.build(pts, 0.2);
  EXPECT_EQ(g.order(), h.order());
}

TEST(PointIndex, BallQueriesMatchBruteForceAtEveryCellSize) {
  const auto pts = torusCloud(4000, 5);
  growth::Random rng(11);
  bool bricks = false, hash = false; // both ways of looking cells up are exercised
  for (double cell : {0.002, 0.02, 0.1, 0.35, 2.0, 50.0}) { // 0.002: keys beyond 32 bits
    MortonGrid g;
    g.build(pts, cell);
    (g.usesBricks() ? bricks : hash) = true;
    for (int q = 0; q < 60; ++q) {
      const Point3d c = pts[size_t(q) * 61 % pts.size()] + rng.inBall(0.3);
      const double r = rng.uniform(0.0, 0.5);
      std::set<std::uint32_t> got;
      g.forEachInBall(c, r, [&](std::uint32_t i, double d2) {
        EXPECT_NEAR(d2, (g.point(i) - c).SquaredNorm(), 1e-12);
        EXPECT_TRUE(got.insert(i).second) << "point reported twice";
      });
      EXPECT_EQ(got, bruteBall(g, c, r)) << "cell " << cell << " query " << q;
    }
  }
  EXPECT_TRUE(bricks);
  EXPECT_TRUE(hash);
}

TEST(PointIndex, ABrickOfMoreThan65535PointsFallsBackToTheHashTable) {
  // Brick offsets are 16 bits: a cloud whose points all fall into one brick needs the hash table.
  growth::Random rng(5);
  std::vector<Point3d> pts;
  for (int i = 0; i < 70000; ++i) pts.push_back(Point3d(rng.uniform(0, 1), rng.uniform(0, 1), rng.uniform(0, 1)));
  MortonGrid g;
  g.build(pts, 0.3); // 4 cells along each axis: one brick
  EXPECT_FALSE(g.usesBricks());
  for (int q = 0; q < 5; ++q) {
    const Point3d c(0.2 * q, 0.5, 0.9 - 0.15 * q);
    std::set<std::uint32_t> got;
    g.forEachInBall(c, 0.12, [&](std::uint32_t i, double) { got.insert(i); });
    EXPECT_EQ(got, bruteBall(g, c, 0.12));
  }
  g.build(std::vector<Point3d>(pts.begin(), pts.begin() + 60000), 0.3);
  EXPECT_TRUE(g.usesBricks());
  std::set<std::uint32_t> got;
  g.forEachInBall(Point3d(0.5, 0.5, 0.5), 0.2, [&](std::uint32_t i, double) { got.insert(i); });
  EXPECT_EQ(got, bruteBall(g, Point3d(0.5, 0.5, 0.5), 0.2));
}

TEST(PointIndex, PointsExactlyOnTheSphereAreFoundDespiteTheFloatPrefilter) {
  // Far from the origin, where float coordinates round coarsely: the exact double test decides.
  std::vector<Point3d> pts;
  const Point3d o(1e6, -2e6, 3e6);
  for (int i = 0; i < 200; ++i) pts.push_back(o + Point3d(0.001 * i, 0.0007 * (i % 13), 0.0003 * (i % 7)));
  MortonGrid g;
  g.build(pts, 0.01);
  for (std::uint32_t i = 0; i < g.size(); i += 17) {
    const Point3d c = g.point(i);
    for (std::uint32_t j = 0; j < g.size(); j += 23) {
      const double r = (g.point(j) - c).Norm() * (1 + 1e-12); // r² >= d² despite rounding
      bool found = false;
      g.forEachInBall(c, r, [&](std::uint32_t k, double) { found = found || k == j; });
      EXPECT_TRUE(found) << i << " " << j;
    }
  }
}

TEST(PointIndex, AnyInBallStopsAtTheFirstMatch) {
  const auto pts = torusCloud(2000, 9);
  MortonGrid g;
  g.build(pts, 0.3);
  int visits = 0;
  const bool hit = g.anyInBall(g.point(0), 1.0, [&](std::uint32_t, double) {
    ++visits;
    return true;
  });
  EXPECT_TRUE(hit);
  EXPECT_EQ(visits, 1);
  EXPECT_FALSE(g.anyInBall(Point3d(100, 100, 100), 1.0, [](std::uint32_t, double) { return true; }));
}

TEST(PointIndex, NearestMatchesBruteForce) {
  const auto pts = torusCloud(3000, 13);
  growth::Random rng(17);
  for (double cell : {0.03, 0.3, 3.0}) {
    MortonGrid g;
    g.build(pts, cell);
    for (int q = 0; q < 100; ++q) {
      const Point3d c = q % 3 == 0 ? Point3d(rng.uniform(-5, 5), rng.uniform(-5, 5), rng.uniform(-5, 5))
                                   : pts[size_t(q) * 29 % pts.size()] + rng.inBall(0.1);
      const std::int64_t exclude = q % 2 == 0 ? std::int64_t(q) : -1;
      double best = std::numeric_limits<double>::infinity();
      for (std::uint32_t i = 0; i < g.size(); ++i)
        if (std::int64_t(i) != exclude) best = std::min(best, (g.point(i) - c).SquaredNorm());
      double d2 = -1;
      const std::int64_t got = g.nearest(c, exclude, std::numeric_limits<double>::infinity(), &d2);
      ASSERT_GE(got, 0);
      EXPECT_NE(got, exclude);
      EXPECT_DOUBLE_EQ(d2, best);
      EXPECT_DOUBLE_EQ((g.point(std::uint32_t(got)) - c).SquaredNorm(), best);
    }
  }
}

TEST(PointIndex, IdenticalPointsAndFlatClouds) {
  std::vector<Point3d> same(10, Point3d(1, 1, 1));
  MortonGrid g;
  g.build(same, 0.0);
  EXPECT_EQ(g.size(), 10u);
  int n = 0;
  g.forEachInBall(Point3d(1, 1, 1), 0.0, [&](std::uint32_t, double) { ++n; });
  EXPECT_EQ(n, 10);
  // A planar cloud (zero thickness along z).
  std::vector<Point3d> plane;
  for (int i = 0; i < 30; ++i)
    for (int j = 0; j < 30; ++j) plane.push_back(Point3d(i * 0.1, j * 0.1, 0));
  g.build(plane, 0.25);
  EXPECT_EQ(bruteBall(g, Point3d(1, 1, 0), 0.35).size(), size_t([&] {
              int k = 0;
              g.forEachInBall(Point3d(1, 1, 0), 0.35, [&](std::uint32_t, double) { ++k; });
              return k;
            }()));
}

namespace {

// Every query kind against brute force over the caller's points: ball queries (through the
// index's own indices, mapped back by order()) and nearest, at random centres near the points.
void expectMatchesBruteForce(const std::vector<Point3d>& pts, double cell, std::uint64_t seed) {
  MortonGrid g;
  g.build(pts, cell);
  growth::Random rng(seed);
  std::vector<std::uint32_t> finite;
  for (std::uint32_t i = 0; i < pts.size(); ++i)
    if (std::isfinite(pts[i][0]) && std::isfinite(pts[i][1]) && std::isfinite(pts[i][2])) finite.push_back(i);
  ASSERT_EQ(g.size(), finite.size());
  for (int q = 0; q < 80; ++q) {
    const Point3d c = pts[finite[size_t(q) * 37 % finite.size()]] + rng.inBall(q % 4 == 0 ? 0.5 : 0.05);
    const double r = q % 5 == 0 ? rng.uniform(0.0, 0.0005) : rng.uniform(0.0, 0.3);
    std::set<std::uint32_t> got, want;
    g.forEachInBall(c, r, [&](std::uint32_t i, double) { EXPECT_TRUE(got.insert(g.order()[i]).second); });
    for (std::uint32_t i : finite)
      if ((pts[i] - c).SquaredNorm() <= r * r) want.insert(i);
    EXPECT_EQ(got, want) << "query " << q;
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t i : finite) best = std::min(best, (pts[i] - c).SquaredNorm());
    double d2 = -1;
    const std::int64_t i = g.nearest(c, -1, std::numeric_limits<double>::infinity(), &d2);
    ASSERT_GE(i, 0);
    EXPECT_EQ(d2, best) << "query " << q;
  }
  // The far points themselves are found, by ball and by nearest.
  for (std::uint32_t i : finite) {
    if ((pts[i] - pts[finite[0]]).Norm() < 1e3) continue;
    bool found = false;
    g.forEachInBall(pts[i], 0.0, [&](std::uint32_t k, double) { found = found || g.order()[k] == i; });
    EXPECT_TRUE(found) << i;
    double d2 = -1;
    EXPECT_GE(g.nearest(pts[i], -1, std::numeric_limits<double>::infinity(), &d2), 0);
    EXPECT_EQ(d2, 0.0);
  }
}

std::vector<Point3d> withCluster(std::vector<Point3d> pts, size_t count, double radius) {
  growth::Random rng(3);
  const Point3d centre = pts[pts.size() / 2];
  for (size_t i = 0; i < count; ++i) pts.push_back(centre + rng.inBall(radius));
  return pts;
}

} // namespace

TEST(PointIndex, FarPointsDuplicatesClustersAndNonFinitePointsMatchBruteForce) {
  const auto torus = torusCloud(4000, 21);
  const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
  for (double cell : {0.05, 0.3}) {
    SCOPED_TRACE(cell);
    auto far = torus;
    far.push_back(Point3d(3e4, -2e4, 1e4));   // within 2^21 cells: in the cells (hash beside the bricks)
    far.push_back(Point3d(-1e12, 5e11, 0));   // beyond them: the far list
    expectMatchesBruteForce(far, cell, 1);
    auto dup = torus;
    for (size_t i = 0; i < 500; ++i) dup.push_back(torus[i * 7]);
    dup.insert(dup.end(), 300, torus[10]); // 301 copies of one point: a split cell of equal points
    expectMatchesBruteForce(dup, cell, 2);
    expectMatchesBruteForce(withCluster(torus, 2000, 1e-4), cell, 3);
    auto bad = torus;
    bad[5] = Point3d(nan, 0, 0);
    bad[77] = Point3d(0, inf, 0);
    bad.push_back(Point3d(0, 0, -inf));
    expectMatchesBruteForce(bad, cell, 4);
  }
}

TEST(PointIndex, AFarPointChangesNeitherTheCellsNorTheBricks) {
  const auto torus = torusCloud(20000, 23);
  MortonGrid clean, far;
  clean.build(torus, 0.1);
  auto pts = torus;
  pts.push_back(Point3d(1e4, 1e4, 1e4));
  pts.push_back(Point3d(1e30, 0, 0));
  far.build(pts, 0.1);
  EXPECT_EQ(far.cellSize(), clean.cellSize());
  EXPECT_TRUE(clean.usesBricks());
  EXPECT_TRUE(far.usesBricks());
  EXPECT_EQ(far.cellCount(), clean.cellCount() + 1); // the point at 1e4 has a cell of its own
  EXPECT_EQ(far.farPointCount(), 1u);                // the one at 1e30 is kept apart
  EXPECT_LT(far.memoryBytes(), clean.memoryBytes() * 3);
}

TEST(PointIndex, QueriesInADenseClusterScanAboutTheirBallNotTheCell) {
  // 5000 points within 1e-4 of one point of a torus sampled at ~0.05: their cell is split, and a
  // query of a few of their spacings scans a small part of it.
  const auto pts = withCluster(torusCloud(20000, 25), 5000, 1e-4);
  MortonGrid g;
  g.build(pts, 0.3);
  EXPECT_GE(g.splitCellCount(), 1u);
  std::uint64_t visited = 0;
  g.setVisitCounter(&visited);
  size_t found = 0, queries = 0;
  for (size_t i = 20000; i < pts.size(); i += 50, ++queries)
    g.forEachInBall(pts[i], 2e-5, [&](std::uint32_t, double) { ++found; });
  EXPECT_GT(found, queries);
  EXPECT_LT(double(visited) / double(queries), 400.0) << visited; // the cell holds 5000+
}
