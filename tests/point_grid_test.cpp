#include <growth/cloud_generator.h>
#include <growth/point_grid.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

using growth::PointGrid;
using Point3d = growth::Vec3d;

namespace {
// Brute-force references.
int bruteNearest(const std::vector<Point3d>& pts, const Point3d& c, int exclude) {
  int best = -1;
  double bd = std::numeric_limits<double>::infinity();
  for (size_t i = 0; i < pts.size(); ++i) {
    if (int(i) == exclude) continue;
    const double d = (pts[i] - c).SquaredNorm();
    if (d < bd) bd = d, best = int(i);
  }
  return best;
}
} // namespace

TEST(PointGrid, EmptyGridAnswersNothing) {
  PointGrid g;
  g.build({}, 0.1);
  EXPECT_EQ(g.nearest(Point3d(0, 0, 0)), -1);
  int calls = 0;
  g.forEachInBall(Point3d(0, 0, 0), 10, [&](int, double) { ++calls; });
  EXPECT_EQ(calls, 0);
}

TEST(PointGrid, SinglePointAndExclusion) {
  PointGrid g;
  std::vector<Point3d> pts{Point3d(1, 2, 3)};
  g.build(pts, 0.5);
  double d2 = -1;
  EXPECT_EQ(g.nearest(Point3d(10, 10, 10), &d2), 0);
  EXPECT_NEAR(d2, (Point3d(10, 10, 10) - pts[0]).SquaredNorm(), 1e-12);
  EXPECT_EQ(g.nearest(pts[0], nullptr, 0), -1);
}

TEST(PointGrid, NonFinitePointsAreSkipped) {
  PointGrid g;
  std::vector<Point3d> pts{Point3d(0, 0, 0), Point3d(std::nan(""), 0, 0), Point3d(1, 0, 0)};
  g.build(pts, 0.5);
  EXPECT_EQ(g.pointCount(), 2u);
  int visits = 0;
  g.forEachInBall(Point3d(0.5, 0, 0), 10, [&](int i, double) { EXPECT_NE(i, 1); ++visits; });
  EXPECT_EQ(visits, 2);
}

TEST(PointGrid, NearestMatchesBruteForce) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 3000;
  spec.seed = 7;
  const auto cloud = growth::generateCloud(spec);
  for (double cell : {0.01, 0.1, 0.7, 5.0}) {
    PointGrid g;
    g.build(cloud.points, cell);
    growth::Random rng(3);
    for (int q = 0; q < 300; ++q) {
      const Point3d c(rng.uniform(-4, 4), rng.uniform(-4, 4), rng.uniform(-2, 2));
      const int exclude = q % 2 == 0 ? -1 : q;
      const int got = g.nearest(c, nullptr, exclude);
      const int want = bruteNearest(cloud.points, c, exclude);
      ASSERT_GE(got, 0);
      EXPECT_DOUBLE_EQ((cloud.points[size_t(got)] - c).SquaredNorm(), (cloud.points[size_t(want)] - c).SquaredNorm())
          << "cell " << cell << " query " << q;
    }
  }
}

TEST(PointGrid, BallQueryMatchesBruteForce) {
  growth::CloudSpec spec;
  spec.count = 2000;
  spec.seed = 11;
  const auto cloud = growth::generateCloud(spec);
  PointGrid g;
  g.build(cloud.points, 0.05);
  growth::Random rng(5);
  for (int q = 0; q < 100; ++q) {
    const Point3d c = rng.unitVector() * rng.uniform(0.5, 1.5);
    const double r = rng.uniform(0.0, 0.4);
    std::vector<int> got;
    g.forEachInBall(c, r, [&](int i, double d2) {
      EXPECT_NEAR(d2, (cloud.points[size_t(i)] - c).SquaredNorm(), 1e-12);
      got.push_back(i);
    });
    std::sort(got.begin(), got.end());
    std::vector<int> want;
    for (size_t i = 0; i < cloud.points.size(); ++i)
      if ((cloud.points[i] - c).SquaredNorm() <= r * r) want.push_back(int(i));
    EXPECT_EQ(got, want);
  }
}

TEST(PointGrid, BallQueryStopsWhenAsked) {
  std::vector<Point3d> pts;
  for (int i = 0; i < 1000; ++i) pts.emplace_back(0, 0, 0); // one dense cluster
  pts.emplace_back(0.5, 0, 0);
  PointGrid g;
  g.build(pts, 0.1);
  std::vector<int> all, first;
  EXPECT_TRUE(g.forEachInBallWhile(Point3d(0, 0, 0), 1.0, [&](int i, double) {
    all.push_back(i);
    return true;
  }));
  EXPECT_EQ(all.size(), 1001u);
  EXPECT_FALSE(g.forEachInBallWhile(Point3d(0, 0, 0), 1.0, [&](int i, double) {
    first.push_back(i);
    return first.size() < 10;
  }));
  ASSERT_EQ(first.size(), 10u);
  EXPECT_TRUE(std::equal(first.begin(), first.end(), all.begin())); // the same order, cut short
}

TEST(PointGrid, NearestRespectsMaxRadius) {
  PointGrid g;
  std::vector<Point3d> pts{Point3d(0, 0, 0), Point3d(1, 0, 0)};
  g.build(pts, 0.1);
  EXPECT_EQ(g.nearest(Point3d(0.5, 0.6, 0), nullptr, -1, 0.5), -1);
  EXPECT_GE(g.nearest(Point3d(0.5, 0.6, 0), nullptr, -1, 0.8), 0);
}

// The cell-batched nearest distances give exactly nearest()'s values, whatever the cell size
// (small cells: most answers beyond the 27 cells, large ones: many points per cell), the stride,
// the number of threads, and with duplicate points.
TEST(PointGrid, BatchedNearestDistancesAreThoseOfNearest) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 5000;
  spec.seed = 3;
  spec.nonUniform = true;
  auto pts = growth::generateCloud(spec).points;
  pts.push_back(pts[17]); // a duplicate: distance 0
  pts.push_back(Point3d(40, 0, 0)); // far away: found by the full search only
  for (double cell : {0.04, 0.15, 0.6, 4.0}) // spacing ~0.13: from "beyond the 27 cells" to "all in a few"
    for (size_t stride : {1u, 7u}) {
      PointGrid g;
      g.build(pts, cell);
      std::vector<double> expect((pts.size() - 1) / stride + 1, -1.0);
      for (size_t i = 0; i < pts.size(); i += stride) {
        double d2 = -1;
        if (g.nearest(pts[i], &d2, int(i)) >= 0) expect[i / stride] = d2;
      }
      for (int threads : {1, 2, 3}) {
        std::vector<double> got;
        g.nearestOtherSquaredDistances(stride, got, threads);
        ASSERT_EQ(got.size(), expect.size());
        for (size_t k = 0; k < got.size(); ++k)
          ASSERT_EQ(got[k], expect[k]) << "cell " << cell << " stride " << stride << " threads " << threads
                                       << " sample " << k;
      }
    }
  PointGrid one;
  one.build({Point3d(1, 1, 1)}, 0.5);
  std::vector<double> got;
  one.nearestOtherSquaredDistances(1, got);
  ASSERT_EQ(got.size(), 1u);
  EXPECT_EQ(got[0], -1.0); // no other point
}

// Points of one cell are visited in input order (the cell sort is stable), also when the cell
// coordinates need several radix passes (cells far finer than the cloud).
TEST(PointGrid, PointsOfACellAreVisitedInInputOrder) {
  growth::Random rnd(12);
  // The origin point makes the grid's cells [0.005 k, 0.005 (k + 1)); each cluster keeps 0.0005
  // away from their faces, so the test knows which points share a cell.
  std::vector<Point3d> pts{Point3d(0, 0, 0)};
  for (int i = 0; i < 6000; ++i) {
    // Clusters of points sharing a cell, spread over a large extent along all three axes.
    const Point3d c(std::floor(rnd.uniform(0, 3000)), std::floor(rnd.uniform(0, 3000)), std::floor(rnd.uniform(0, 50)));
    pts.push_back(c * 0.01 + Point3d(0.0005, 0.0005, 0.0005) +
                  Point3d(rnd.uniform(0, 0.004), rnd.uniform(0, 0.004), rnd.uniform(0, 0.004)));
  }
  for (int i = 0; i < 200; ++i) pts.push_back(pts[size_t(i) * 7]); // exact repeats land in the same cell
  PointGrid g;
  g.build(pts, 0.005);
  for (int q = 0; q < 300; ++q) {
    const Point3d c = pts[size_t(rnd.uniform(0, double(pts.size())))];
    std::vector<int> seen;
    g.forEachInBall(c, 0.004, [&](int i, double) { seen.push_back(i); });
    // Brute force: the same set.
    std::vector<int> expect;
    for (size_t i = 0; i < pts.size(); ++i)
      if ((pts[i] - c).SquaredNorm() <= 0.004 * 0.004) expect.push_back(int(i));
    std::vector<int> sorted = seen;
    std::sort(sorted.begin(), sorted.end());
    ASSERT_EQ(sorted, expect);
    // Within one cell (consecutive visits of points with the same cell), increasing indices.
    for (size_t k = 1; k < seen.size(); ++k) {
      const Point3d &a = pts[size_t(seen[k - 1])], &b = pts[size_t(seen[k])];
      bool sameCell = true;
      for (int ax = 0; ax < 3; ++ax) sameCell = sameCell && std::floor(a[ax] / 0.005) == std::floor(b[ax] / 0.005);
      if (sameCell) {
        EXPECT_LT(seen[k - 1], seen[k]);
      }
    }
  }
}
