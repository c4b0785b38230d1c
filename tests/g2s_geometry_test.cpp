#include "g2s_geometry.h"

#include <gtest/gtest.h>

#include <cmath>

using namespace growth::g2s;

namespace {
const double kPi = 3.14159265358979323846;
}

TEST(G2SGeometry, CircumBallOfARightTriangleIsCentredOnTheHypotenuse) {
  Ball b;
  ASSERT_TRUE(circumBall(P3(0, 0, 0), P3(2, 0, 0), P3(0, 2, 0), b));
  EXPECT_NEAR(b.centre[0], 1, 1e-12);
  EXPECT_NEAR(b.centre[1], 1, 1e-12);
  EXPECT_NEAR(b.centre[2], 0, 1e-12);
  EXPECT_NEAR(b.radius2, 2, 1e-12);
}

TEST(G2SGeometry, CircumBallLiesInTheTrianglePlaneAndPassesThroughTheVertices) {
  const P3 a(0.3, -1.2, 2.0), b(1.7, 0.4, 2.5), c(-0.5, 0.9, 1.1);
  Ball ball;
  ASSERT_TRUE(circumBall(a, b, c, ball));
  for (const P3& p : {a, b, c}) EXPECT_NEAR((p - ball.centre).SquaredNorm(), ball.radius2, 1e-12);
  const P3 n = (b - a) ^ (c - a);
  EXPECT_NEAR((ball.centre - a) * n, 0, 1e-12); // smallest ball: centre in the plane
  // Equilateral triangle of side s: R = s/√3.
  ASSERT_TRUE(circumBall(P3(0, 0, 0), P3(1, 0, 0), P3(0.5, std::sqrt(3.0) / 2, 0), ball));
  EXPECT_NEAR(ball.radius2, 1.0 / 3.0, 1e-12);
}

TEST(G2SGeometry, CollinearPointsHaveNoCircumBall) {
  Ball b;
  EXPECT_FALSE(circumBall(P3(0, 0, 0), P3(1, 1, 1), P3(2, 2, 2), b));
  EXPECT_FALSE(circumBall(P3(0, 0, 0), P3(0, 0, 0), P3(1, 0, 0), b));
  EXPECT_TRUE(circumBall(P3(0, 0, 0), P3(1, 0, 0), P3(0.5, 1e-6, 0), b)); // thin but proper
}

TEST(G2SGeometry, PointsOnTheSphereAreNotInside) {
  EXPECT_TRUE(strictlyInside(0.99, 1.0));
  EXPECT_FALSE(strictlyInside(1.0, 1.0));
  EXPECT_FALSE(strictlyInside(1.0 - 1e-13, 1.0)); // cocircular up to rounding
  EXPECT_FALSE(strictlyInside(1.1, 1.0));
}

TEST(G2SGeometry, GrowingDirectionIsInThePlaneAwayFromTheThirdVertex) {
  const P3 a(0, 0, 0), b(1, 0, 0), c(0.4, 0.8, 0);
  const P3 d = growingDirection(a, b, c);
  EXPECT_NEAR(d.Norm(), 1, 1e-12);
  EXPECT_NEAR(d * (b - a), 0, 1e-12);
  EXPECT_NEAR(d[2], 0, 1e-12);
  EXPECT_LT(d * (c - (a + b) * 0.5), 0);
  // Tilted triangle: still in its plane, orthogonal to the edge, away from c.
  const P3 c2(0.5, 0.3, 0.7);
  const P3 d2 = growingDirection(a, b, c2);
  EXPECT_NEAR(d2 * ((b - a) ^ (c2 - a)), 0, 1e-12);
  EXPECT_NEAR(d2 * (b - a), 0, 1e-12);
  EXPECT_LT(d2 * (c2 - a), 0);
  EXPECT_TRUE(growingDirection(a, b, P3(2, 0, 0)) == P3(0, 0, 0)); // degenerate front triangle
}

TEST(G2SGeometry, SearchSpheresPassThroughTheEdgeEndsAndAreNestedAhead) {
  const P3 a(0, 0, 0), b(1, 0, 0), dir(0, -1, 0);
  // First radius |ab|: centred on the apex of the equilateral triangle over ab.
  const P3 c1 = searchCentre(a, b, dir, 1.0);
  EXPECT_NEAR(c1[0], 0.5, 1e-12);
  EXPECT_NEAR(c1[1], -std::sqrt(3.0) / 2, 1e-12);
  for (double r : {0.5, 1.0, 1.5, 2.5}) {
    const P3 c = searchCentre(a, b, dir, r);
    EXPECT_NEAR((a - c).Norm(), r, 1e-12);
    EXPECT_NEAR((b - c).Norm(), r, 1e-12);
  }
  // A point ahead of the edge, once inside a search sphere, is inside every larger one.
  const P3 ahead(0.2, -0.4, 0.05);
  bool inside = false;
  for (double r : {1.0, 1.5, 2.0, 3.0}) {
    const bool now = (ahead - searchCentre(a, b, dir, r)).Norm() <= r;
    EXPECT_TRUE(!inside || now) << "left the search region when it grew to " << r;
    inside = now;
  }
  EXPECT_TRUE(inside);
  // Behind the edge, a point is never inside (for r >= |ab|) unless very close to the edge.
  EXPECT_GT((P3(0.5, 0.3, 0) - searchCentre(a, b, dir, 1.0)).Norm(), 1.0);
}

TEST(G2SGeometry, SearchRadiiStepFromTheEdgeLengthToTheMaximum) {
  EXPECT_DOUBLE_EQ(searchRadius(1, 4, 1.0, 2.5), 1.0);
  EXPECT_DOUBLE_EQ(searchRadius(2, 4, 1.0, 2.5), 1.5);
  EXPECT_DOUBLE_EQ(searchRadius(4, 4, 1.0, 2.5), 2.5);
  EXPECT_DOUBLE_EQ(searchRadius(3, 4, 2.0, 1.0), 2.0); // maximum below the edge: the edge length
  EXPECT_DOUBLE_EQ(searchRadius(1, 1, 1.0, 2.5), 2.5); // one level: the maximum
}

TEST(G2SGeometry, FlatnessLevelsAndPriorityIndex) {
  // m = 8 classes of 22.5°: β = 0 → 1, β = 180° → 8.
  EXPECT_EQ(flatnessLevel(0.0, 8), 1);
  EXPECT_EQ(flatnessLevel(kPi / 8 - 1e-9, 8), 1);
  EXPECT_EQ(flatnessLevel(kPi / 8 + 1e-9, 8), 2);
  EXPECT_EQ(flatnessLevel(kPi / 4 + 1e-9, 8), 3);
  EXPECT_EQ(flatnessLevel(kPi, 8), 8);
  EXPECT_EQ(flatnessLevel(kPi / 2, 1), 1);
  // Eq. 4.1: PI = m·(pl_d − 1) + pl_f; a tighter size level always beats any flatness.
  EXPECT_EQ(priorityIndex(1, 1, 8), 1);
  EXPECT_EQ(priorityIndex(1, 8, 8), 8);
  EXPECT_EQ(priorityIndex(2, 1, 8), 9);
  EXPECT_EQ(priorityIndex(4, 8, 8), 32);
  EXPECT_LT(priorityIndex(1, 8, 8), priorityIndex(2, 1, 8));
}

TEST(G2SGeometry, AngleBetweenNormals) {
  EXPECT_NEAR(angleBetween(P3(0, 0, 1), P3(0, 0, 3)), 0, 1e-12);
  EXPECT_NEAR(angleBetween(P3(0, 0, 1), P3(0, 1, 0)), kPi / 2, 1e-12);
  EXPECT_NEAR(angleBetween(P3(0, 0, 1), P3(0, 0, -1)), kPi, 1e-12);
}
