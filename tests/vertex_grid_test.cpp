// Dynamic vertex hash grid used by the insertion checks (sec. 3.6).
#include <growth/cloud_generator.h>
#include "vertex_grid.h"

#include <gtest/gtest.h>

#include <algorithm>

using Point3d = growth::Vec3d;

TEST(VertexGrid, BallQueriesMatchBruteForceWhileGrowing) {
  growth::VertexGrid g;
  g.reset(Point3d(0, 0, 0), 0.1);
  std::vector<Point3d> pos;
  growth::Random rnd(6);
  for (std::uint32_t i = 0; i < 3000; ++i) {
    // Far from the origin on both sides: coordinates may be negative.
    pos.emplace_back(rnd.uniform(-5, 5), rnd.uniform(-5, 5), rnd.uniform(-0.5, 0.5));
    ASSERT_TRUE(g.insert(i, pos.back()));
    if (i % 100 != 99) continue;
    for (int q = 0; q < 20; ++q) {
      const Point3d c(rnd.uniform(-5, 5), rnd.uniform(-5, 5), rnd.uniform(-0.5, 0.5));
      const double r = rnd.uniform(0.05, 0.4);
      std::vector<std::uint32_t> got, want;
      g.forEachInBall(c, r, pos, [&](std::uint32_t v, double d2) {
        got.push_back(v);
        EXPECT_NEAR(d2, (pos[v] - c).SquaredNorm(), 1e-15);
      });
      for (std::uint32_t v = 0; v <= i; ++v)
        if ((pos[v] - c).Norm() <= r) want.push_back(v);
      std::sort(got.begin(), got.end());
      EXPECT_EQ(got, want);
      // anyCloserThan agrees, with the nearest one skipped.
      if (!want.empty()) {
        const bool strictly = std::any_of(want.begin(), want.end(), [&](std::uint32_t v) { return (pos[v] - c).Norm() < r; });
        EXPECT_EQ(g.anyCloserThan(c, r, pos, ~0u, ~0u), strictly);
        if (want.size() == 1) {
          EXPECT_FALSE(g.anyCloserThan(c, r, pos, want[0], ~0u));
        }
      } else {
        EXPECT_FALSE(g.anyCloserThan(c, r, pos, ~0u, ~0u));
      }
    }
  }
}

TEST(VertexGrid, ExactlyAtTheRadiusIsNotCloser) {
  growth::VertexGrid g;
  g.reset(Point3d(0, 0, 0), 0.25);
  std::vector<Point3d> pos{Point3d(0, 0, 0), Point3d(0.25, 0, 0)};
  g.insert(0, pos[0]);
  g.insert(1, pos[1]);
  EXPECT_FALSE(g.anyCloserThan(Point3d(0.5, 0, 0), 0.25, pos, ~0u, ~0u));
  EXPECT_TRUE(g.anyCloserThan(Point3d(0.49, 0, 0), 0.25, pos, ~0u, ~0u));
  EXPECT_FALSE(g.anyCloserThan(Point3d(0.49, 0, 0), 0.25, pos, 1, ~0u));
}
