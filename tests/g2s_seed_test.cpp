// Robust G2S, sec. 3.1: seed triangles (G2S + cylinder test) and re-seeding.
#include "g2s_mesher.h"

#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <set>
#include <vector>

using namespace growth::g2s;
using growth::CloudSpec;
using growth::Shape;

namespace {

// Internal index (the mesher's grid order) of each input point.
std::vector<std::uint32_t> internalIndex(const Mesher& m) {
  std::vector<std::uint32_t> inv(m.size());
  for (std::uint32_t i = 0; i < m.size(); ++i) inv[m.order()[i]] = i;
  return inv;
}

bool bruteGabriel(const Mesher& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Ball ball;
  if (!circumBall(m.points()[a], m.points()[b], m.points()[c], ball)) return false;
  for (std::uint32_t i = 0; i < m.size(); ++i)
    if (i != a && i != b && i != c && strictlyInside((m.points()[i] - ball.centre).SquaredNorm(), ball.radius2))
      return false;
  return true;
}

bool bruteCylinder(const Mesher& m, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const P3 &A = m.points()[a], &B = m.points()[b], &C = m.points()[c];
  Ball ball;
  if (!circumBall(A, B, C, ball)) return false;
  const P3 n = unitNormal(A, B, C);
  const double eps = 1e-6 * std::sqrt(ball.radius2);
  bool above = false, below = false;
  for (std::uint32_t i = 0; i < m.size(); ++i) {
    if (i == a || i == b || i == c) continue;
    const P3 d = m.points()[i] - ball.centre;
    const double h = d * n;
    if (!strictlyInside(d.SquaredNorm() - h * h, ball.radius2)) continue;
    above = above || h > eps;
    below = below || h < -eps;
  }
  return !(above && below);
}

Params defaults() {
  Params p;
  p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
  return p;
}

} // namespace

TEST(G2SSeed, SeedsOnASphereAreGabrielAndPassTheCylinderTest) {
  CloudSpec spec;
  spec.shape = Shape::Sphere;
  spec.count = 1500;
  Mesher m(growth::generateCloud(spec).points, defaults());
  int found = 0;
  for (std::uint32_t p = 0; p < m.size(); p += 37) {
    std::array<std::uint32_t, 3> t;
    if (!m.findSeedTriangle(p, t)) continue;
    ++found;
    EXPECT_TRUE(t[0] == p || t[1] == p || t[2] == p);
    EXPECT_TRUE(bruteGabriel(m, t[0], t[1], t[2]));
    EXPECT_TRUE(bruteCylinder(m, t[0], t[1], t[2]));
    EXPECT_TRUE(m.isGabriel(t[0], t[1], t[2]));
    EXPECT_TRUE(m.passesCylinderTest(t[0], t[1], t[2]));
    // Step 3.2: the second point is p's nearest neighbour.
    double nn = 1e300;
    std::uint32_t q = 0;
    for (std::uint32_t i = 0; i < m.size(); ++i)
      if (i != p && (m.points()[i] - m.points()[p]).SquaredNorm() < nn) nn = (m.points()[i] - m.points()[p]).SquaredNorm(), q = i;
    EXPECT_TRUE(t[0] == q || t[1] == q || t[2] == q);
    // Oriented outwards (away from the cloud's centre) for a new component.
    const P3 n = (m.points()[t[1]] - m.points()[t[0]]) ^ (m.points()[t[2]] - m.points()[t[0]]);
    EXPECT_GT(n * m.points()[t[0]], 0);
  }
  EXPECT_GT(found, 25); // most points of a clean sphere start a seed (close pairs may not)
}

TEST(G2SSeed, CylinderTestRejectsPointsOnBothSidesEvenFarAway) {
  // Triangle in z = 0 with circumcentre (0.5, 0.5, 0), R = √2/2; the other points are outside its
  // ball, so it is a Gabriel 2-simplex, but inside the infinite cylinder over it.
  std::vector<P3> pts{P3(0, 0, 0), P3(1, 0, 0), P3(0, 1, 0), P3(0.5, 0.5, 2.0), P3(0.6, 0.4, -50.0)};
  Mesher both(pts, defaults());
  const auto in = internalIndex(both);
  EXPECT_TRUE(both.isGabriel(in[0], in[1], in[2]));
  EXPECT_FALSE(both.passesCylinderTest(in[0], in[1], in[2])); // above at 2, below at −50

  pts.pop_back();
  pts.push_back(P3(0.45, 0.55, 7.0)); // both above now
  Mesher above(pts, defaults());
  const auto in2 = internalIndex(above);
  EXPECT_TRUE(above.passesCylinderTest(in2[0], in2[1], in2[2]));

  // Outside the cylinder (beyond R from the axis) a point below does not count.
  pts.push_back(P3(2.0, 2.0, -1.0));
  Mesher outside(pts, defaults());
  const auto in3 = internalIndex(outside);
  EXPECT_TRUE(outside.passesCylinderTest(in3[0], in3[1], in3[2]));
}

// The cylinder walk is bounded by the triangle's size, not by the bounding box.
// Unbounded, a far point 10^6 away along the axis means 7 x 10^5 ball queries for one test, and a
// triangle a few 10^-7 across on a unit sphere 1.4 x 10^7; bounded, at most 1024 per side.
TEST(G2SSeed, TheCylinderWalkIsBoundedByTheTrianglesSize) {
  std::vector<P3> pts;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) pts.push_back(P3(i + 0.01 * ((i * 7 + j * 3) % 5), j + 0.013 * ((i + j * 5) % 7), 0));
  pts.push_back(P3(5.2, 5.3, 1e6)); // far above the patch, inside the cylinders of its middle
  {
    Mesher m(pts, defaults());
    const auto in = internalIndex(m);
    // The triangle of grid points (5, 5), (6, 5), (5, 6): the far point is in its cylinder.
    EXPECT_TRUE(m.passesCylinderTest(in[5 * 12 + 5], in[6 * 12 + 5], in[5 * 12 + 6]));
    EXPECT_GT(m.cylinderQueries(), 1000u); // it does walk towards the far point
    EXPECT_LE(m.cylinderQueries(), 2048u);
  }
  // Three points a few 10^-7 apart at the north pole of a unit sphere.
  CloudSpec spec;
  spec.shape = Shape::Sphere;
  spec.count = 2000;
  std::vector<P3> sphere = growth::generateCloud(spec).points;
  sphere.push_back(P3(0, 0, 1));
  sphere.push_back(P3(3e-7, 0, 1));
  sphere.push_back(P3(0, 3e-7, 1));
  Mesher m(sphere, defaults());
  const auto in = internalIndex(m);
  const size_t n = sphere.size();
  const auto start = std::chrono::steady_clock::now();
  m.passesCylinderTest(in[n - 3], in[n - 2], in[n - 1]);
  EXPECT_LE(m.cylinderQueries(), 2048u);
  // The whole run too: a generous limit (unbounded, this cloud takes minutes).
  m.meshAll();
  EXPECT_LT(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count(), 20.0);
  EXPECT_LE(m.cylinderQueries(), 2048u * m.seedAttempts() + 2048u);
}

// A seed on one sheet of a thin part does not copy the orientation of the
// nearest triangle when that triangle is on the other sheet. Two parallel grids 1.5 apart (unit
// spacing); a triangle on the top one faces up (out of the part); a seed right below it, on the
// bottom sheet, must face down (out of the part), not up like its nearest triangle.
TEST(G2SSeed, ASeedDoesNotCopyTheOrientationOfTheOtherSheet) {
  std::vector<P3> pts;
  for (double z : {0.75, -0.75})
    for (int i = 0; i < 10; ++i)
      for (int j = 0; j < 10; ++j) pts.push_back(P3(i + 0.01 * ((i * 7 + j * 3) % 5), j + 0.013 * ((i + j * 5) % 7), z));
  Mesher m(pts, defaults());
  const auto in = internalIndex(m);
  // Top triangle (4,4), (5,4), (4,5): counter-clockwise seen from above, normal +z.
  const std::uint32_t t0 = in[4 * 10 + 4], t1 = in[5 * 10 + 4], t2 = in[4 * 10 + 5];
  ASSERT_GT((((m.points()[t1] - m.points()[t0]) ^ (m.points()[t2] - m.points()[t0])))[2], 0);
  m.addSeed({t0, t1, t2});
  std::array<std::uint32_t, 3> t;
  ASSERT_TRUE(m.findSeedTriangle(in[100 + 4 * 10 + 4], t));
  for (std::uint32_t v : t) EXPECT_LT(m.points()[v][2], 0) << "the seed is on the bottom sheet";
  const P3 n = (m.points()[t[1]] - m.points()[t[0]]) ^ (m.points()[t[2]] - m.points()[t[0]]);
  EXPECT_LT(n[2], 0);
  // Beside a triangle of its own sheet a seed does agree with it (so that the fronts can join):
  // with a top triangle turned to face down, a seed next to it on the top faces down as well.
  Mesher same(pts, defaults());
  same.addSeed({t0, t2, t1});
  ASSERT_TRUE(same.findSeedTriangle(in[6 * 10 + 4], t));
  for (std::uint32_t v : t) EXPECT_GT(same.points()[v][2], 0);
  const P3 n2 = (same.points()[t[1]] - same.points()[t[0]]) ^ (same.points()[t[2]] - same.points()[t[0]]);
  EXPECT_LT(n2[2], 0);
}

TEST(G2SSeed, CoplanarPointsDoNotFailTheCylinderTest) {
  // A planar grid: every point is on the plane of every seed triangle (height 0).
  std::vector<P3> pts;
  for (int i = 0; i < 12; ++i)
    for (int j = 0; j < 12; ++j) pts.push_back(P3(i + 0.01 * ((i * 7 + j * 3) % 5), j + 0.013 * ((i + j * 5) % 7), 0));
  Mesher m(pts, defaults());
  std::array<std::uint32_t, 3> t;
  ASSERT_TRUE(m.findSeedTriangle(internalIndex(m)[5 * 12 + 5], t));
  EXPECT_TRUE(m.passesCylinderTest(t[0], t[1], t[2]));
}

TEST(G2SSeed, IsolatedPointsStartNoSeed) {
  CloudSpec spec;
  spec.shape = Shape::Sphere;
  spec.count = 800;
  std::vector<P3> pts = growth::generateCloud(spec).points;
  pts.push_back(P3(7, 7, 7)); // an outlier: its nearest neighbour is far beyond any edge length
  Mesher m(pts, defaults());
  std::array<std::uint32_t, 3> t;
  EXPECT_FALSE(m.findSeedTriangle(internalIndex(m)[pts.size() - 1], t));
  // Three close points far from everything are a (tiny) surface of their own: a valid seed.
  pts.push_back(P3(5, 5, 5));
  pts.push_back(P3(5, 5, 5.01));
  pts.push_back(P3(5, 5.01, 5));
  Mesher m2(pts, defaults());
  EXPECT_TRUE(m2.findSeedTriangle(internalIndex(m2)[pts.size() - 3], t));
}

TEST(G2SSeed, ReseedingMeshesEverySeparateComponent) {
  // Two spheres far apart: one front cannot reach the other; a second seed must.
  CloudSpec spec;
  spec.shape = Shape::Sphere;
  spec.count = 1200;
  std::vector<P3> pts = growth::generateCloud(spec).points;
  spec.seed = 2;
  for (const P3& p : growth::generateCloud(spec).points) pts.push_back(p + P3(10, 0, 0));
  Mesher m(pts, defaults());
  m.meshAll();
  EXPECT_GE(m.seeds(), 2u);
  // Every point is used and both spheres are closed: 2 × (2·1200 − 4) triangles.
  EXPECT_EQ(m.liveTriangles(), size_t(2 * (2 * 1200 - 4)));
  EXPECT_EQ(m.boundaryEdges(), 0u);
  size_t left = 0, right = 0;
  for (const auto& t : m.triangles()) (m.points()[t[0]][0] < 5 ? left : right)++;
  EXPECT_EQ(left, right);
}

TEST(G2SSeed, SameRandomSeedSameMeshOtherSeedStillValid) {
  CloudSpec spec;
  spec.shape = Shape::Torus;
  spec.count = 3000;
  const auto pts = growth::generateCloud(spec).points;
  Params p = defaults();
  Mesher a(pts, p), b(pts, p);
  a.meshAll();
  b.meshAll();
  EXPECT_EQ(a.triangles(), b.triangles());
  p.randomSeed = 12345;
  Mesher c(pts, p);
  c.meshAll();
  EXPECT_NE(a.triangles().front(), c.triangles().front()); // another first seed
  EXPECT_EQ(c.liveTriangles(), size_t(2 * 3000));          // still the closed torus (genus 1)
  EXPECT_EQ(c.boundaryEdges(), 0u);
}
