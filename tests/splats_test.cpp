// Splats (sec. 3.2) and their local sizes (sec. 4.3): rotation onto the tangent plane, Delaunay
// flips of the central fan, farthest Voronoi vertex; global size when switched off.
#include <growth/box_grid.h>
#include <growth/cloud_generator.h>
#include <growth/point_grid.h>
#include <growth/splats.h>

#include <gtest/gtest.h>

#include <algorithm>

using vcg::Point3d;

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
  growth::BoxGrid g;
  g.build(c.points, c.normals, 0.1);
  const auto r = growth::computeSplatRadii(c.points, c.normals, g, 0.07, false);
  ASSERT_EQ(r.size(), c.points.size());
  for (float x : r) EXPECT_EQ(x, 0.07f);
}

TEST(SplatRadii, LocalSizesAreSmallerAndStillCoverTheSphere) {
  const auto c = sphereCloud(10000);
  const double d = 0.1, s = 0.1;
  growth::BoxGrid g;
  g.build(c.points, c.normals, d);
  growth::SplatSizeStats st;
  const auto r = growth::computeSplatRadii(c.points, c.normals, g, s, true, &st);
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
  growth::BoxGrid g;
  g.build(c.points, c.normals, 0.1, nullptr, 1);
  const double s = 0.03;
  growth::SplatSizeStats one;
  const auto r1 = growth::computeSplatRadii(c.points, c.normals, g, s, true, &one, nullptr, 1);
  EXPECT_GT(one.unbounded, 0u);
  EXPECT_GT(one.clamped, 0u);
  for (int threads : {2, 3, 7}) {
    growth::SplatSizeStats st;
    const auto r = growth::computeSplatRadii(c.points, c.normals, g, s, true, &st, nullptr, threads);
    ASSERT_EQ(r, r1) << threads << " threads";
    EXPECT_EQ(st.unbounded, one.unbounded);
    EXPECT_EQ(st.clamped, one.clamped);
    EXPECT_EQ(st.meanRadius, one.meanRadius);
  }
}
