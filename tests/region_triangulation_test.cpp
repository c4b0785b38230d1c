// Region triangulation (sec. 3.7): smallest inner angle first, angles in the projection onto the
// vertex normal's plane, regions longer than ∂max stay holes.
#include "region_triangulation.h"

#include <gtest/gtest.h>

#include <cmath>
#include <set>

using Point3d = growth::Vec3d;
using growth::Triangle;

namespace {
const Point3d kUp(0, 0, 1);

double area2(const std::vector<Point3d>& p, const Triangle& t) {
  const Point3d a = p[t[0]], b = p[t[1]], c = p[t[2]];
  return ((b - a) ^ (c - a)) * kUp; // twice the signed area seen from +z
}
double polygonArea2(const std::vector<Point3d>& p, const std::vector<std::uint32_t>& loop) {
  double a = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const Point3d &u = p[loop[i]], &v = p[loop[(i + 1) % loop.size()]];
    a += u[0] * v[1] - u[1] * v[0];
  }
  return a;
}
// Triangulates a planar loop; checks the standard properties of a polygon triangulation.
std::vector<Triangle> triangulate(const std::vector<Point3d>& p, const std::vector<std::uint32_t>& loop) {
  std::vector<Point3d> n(p.size(), kUp);
  growth::EdgeSet edges;
  for (size_t i = 0; i < loop.size(); ++i) edges.insert(loop[i], loop[(i + 1) % loop.size()]);
  std::vector<Triangle> faces;
  EXPECT_TRUE(growth::triangulateLoop(loop, p, n, edges, faces));
  EXPECT_EQ(faces.size(), loop.size() - 2);
  double sum = 0;
  for (const auto& t : faces) {
    EXPECT_GT(area2(p, t), 0) << "every face counter-clockwise (normal along the vertex normals)";
    sum += area2(p, t);
  }
  EXPECT_NEAR(sum, polygonArea2(p, loop), 1e-9) << "faces tile the region without overlap";
  return faces;
}
} // namespace

TEST(InnerAngle, CounterClockwiseFromOutgoingToIncoming) {
  // Region on the left of u→v→w: at v = origin, u = (1,0) incoming... the region lies
  // counter-clockwise from the direction to w to the direction to u.
  EXPECT_NEAR(growth::innerAngle(Point3d(1, 0, 0), Point3d(0, 0, 0), Point3d(0, 1, 0), kUp), 1.5 * M_PI, 1e-12);
  EXPECT_NEAR(growth::innerAngle(Point3d(0, 1, 0), Point3d(0, 0, 0), Point3d(1, 0, 0), kUp), 0.5 * M_PI, 1e-12);
  // Measured in the plane of the normal: a tilted normal sees the projected angle.
  const Point3d n = Point3d(0, 1, 1).Normalize();
  const double a = growth::innerAngle(Point3d(0, 1, 0), Point3d(0, 0, 0), Point3d(1, 0, 0), n);
  EXPECT_NEAR(a, 0.5 * M_PI, 1e-12); // x stays, y shrinks by cos 45°: still a right angle
  const double b = growth::innerAngle(Point3d(0, 1, 0), Point3d(0, 0, 0), Point3d(1, 1, 0), n);
  // Projections (1, 0.5, −0.5) and (0, 0.5, −0.5): cos = 0.5 / (√1.5 · √0.5) = 1/√3.
  EXPECT_NEAR(b, std::acos(1 / std::sqrt(3.0)), 1e-12);
}

TEST(RegionTriangulation, RhombusIsCutAtItsSixtyDegreeCorner) {
  const double h = std::sqrt(0.75);
  // Rhombus 0 (0,0), 1 (1,0), 2 (1.5,h), 3 (0.5,h): 60° at 0 and 2, 120° at 1 and 3.
  const std::vector<Point3d> p{Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1.5, h, 0), Point3d(0.5, h, 0)};
  const auto f = triangulate(p, {0, 1, 2, 3});
  ASSERT_EQ(f.size(), 2u);
  // The diagonal is the short one (1–3): two equilateral triangles.
  for (const auto& t : f) {
    const std::set<std::uint32_t> vs(t.begin(), t.end());
    EXPECT_TRUE(vs == (std::set<std::uint32_t>{0, 1, 3}) || vs == (std::set<std::uint32_t>{1, 2, 3}));
  }
}

TEST(RegionTriangulation, NonConvexRegionGivesAValidTriangulation) {
  // An arrow-shaped loop with a reflex corner (angle > 180° at vertex 3).
  const std::vector<Point3d> p{Point3d(0, 0, 0), Point3d(4, 0, 0), Point3d(4, 3, 0), Point3d(2, 1, 0), Point3d(0, 3, 0)};
  const auto f = triangulate(p, {0, 1, 2, 3, 4});
  EXPECT_NE(f[0][1], 3u) << "never cut at the reflex corner";
  // A longer, zig-zag loop.
  std::vector<Point3d> z;
  std::vector<std::uint32_t> loop;
  for (int i = 0; i <= 6; ++i) z.emplace_back(i, (i % 2) ? 0.8 : 0.0, 0);
  for (int i = 6; i >= 0; --i) z.emplace_back(i, 2.0 + ((i % 2) ? 0.6 : 0.0), 0);
  for (std::uint32_t i = 0; i < z.size(); ++i) loop.push_back(i);
  triangulate(z, loop);
}

TEST(RegionTriangulation, SmallestAngleIsCutFirst) {
  // A pentagon with one sharp corner (at vertex 0): the first face is the ear at 0.
  const std::vector<Point3d> p{Point3d(0, 0, 0), Point3d(3, 0.5, 0), Point3d(3.5, 1.5, 0), Point3d(2, 2.5, 0), Point3d(3, 1, 0)};
  std::vector<Point3d> n(p.size(), kUp);
  // Reorder into a simple counter-clockwise loop: 0, 1, 2, 3 then back; vertex 4 unused.
  const std::vector<std::uint32_t> loop{0, 1, 2, 3};
  growth::EdgeSet edges;
  std::vector<Triangle> faces;
  ASSERT_TRUE(growth::triangulateLoop(loop, p, n, edges, faces));
  double best = 10;
  std::uint32_t bestV = 0;
  for (size_t i = 0; i < loop.size(); ++i) {
    const double a = growth::innerAngle(p[loop[(i + 3) % 4]], p[loop[i]], p[loop[(i + 1) % 4]], kUp);
    if (a < best) best = a, bestV = loop[i];
  }
  EXPECT_EQ(faces[0][1], bestV);
}

TEST(RegionTriangulation, ExistingDiagonalIsNotAddedTwice) {
  const double h = std::sqrt(0.75);
  const std::vector<Point3d> p{Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1.5, h, 0), Point3d(0.5, h, 0)};
  std::vector<Point3d> n(p.size(), kUp);
  growth::EdgeSet edges;
  edges.insert(1, 3); // the short diagonal exists elsewhere already
  std::vector<Triangle> faces;
  ASSERT_TRUE(growth::triangulateLoop({0, 1, 2, 3}, p, n, edges, faces));
  ASSERT_EQ(faces.size(), 2u);
  EXPECT_EQ(faces[0], (Triangle{0, 1, 2})); // cut at 1 (120°) instead: diagonal 0–2
}

TEST(RegionTriangulation, PinchedBorderIsSplitIntoSimpleLoops) {
  const auto loops = growth::splitAtRepeatedVertices({0, 1, 2, 0, 3, 4});
  ASSERT_EQ(loops.size(), 2u);
  EXPECT_EQ(loops[0], (std::vector<std::uint32_t>{0, 1, 2}));
  EXPECT_EQ(loops[1], (std::vector<std::uint32_t>{0, 3, 4}));
  // A spike (dangling edge 2–5) inside a square region.
  const auto s = growth::splitAtRepeatedVertices({0, 1, 2, 5, 2, 3});
  ASSERT_EQ(s.size(), 2u);
  EXPECT_EQ(s[0], (std::vector<std::uint32_t>{2, 5}));
  EXPECT_EQ(s[1], (std::vector<std::uint32_t>{0, 1, 2, 3}));
  // The path border of fig. 6b (back and forth) has no region to fill.
  const auto path = growth::splitAtRepeatedVertices({0, 1, 2, 1});
  for (const auto& l : path) EXPECT_LT(l.size(), 3u);
}

TEST(RegionTriangulation, BordersLongerThanTheLimitStayHoles) {
  // Two borders of a ring of 12 vertices: the inner and the outer one (both length 12).
  std::vector<Point3d> p;
  std::vector<std::uint32_t> inner, outer;
  for (int i = 0; i < 12; ++i) p.emplace_back(std::cos(2 * M_PI * i / 12), std::sin(2 * M_PI * i / 12), 0);
  for (std::uint32_t i = 0; i < 12; ++i) inner.push_back(i), outer.push_back(11 - i);
  std::vector<Point3d> n(p.size(), kUp);
  for (int limit : {11, 12}) {
    growth::EdgeSet edges;
    for (std::uint32_t i = 0; i < 12; ++i) edges.insert(i, (i + 1) % 12);
    std::vector<Triangle> faces;
    const auto st = growth::triangulateRegions({inner, outer}, p, n, limit, edges, faces);
    EXPECT_EQ(st.borders, 2u);
    EXPECT_EQ(st.longestBorder, 12u);
    if (limit == 11) {
      EXPECT_EQ(st.holes, 2u);
      EXPECT_TRUE(faces.empty());
    } else {
      // The inner region is a convex polygon: filled. The outer one, seen from the same normals,
      // has only reflex angles: nothing to cut, it stays open.
      EXPECT_EQ(st.triangulated, 1u);
      EXPECT_EQ(st.holes, 1u);
      EXPECT_EQ(faces.size(), 10u);
    }
  }
}

// A face is too flat to output when its largest angle exceeds 179° (or two vertices coincide):
// a face with edges d, d, 2d has 180°.
TEST(RegionTriangulation, NearlyCollinearFacesAreRecognised) {
  const growth::Vec3d a(0, 0, 0), c(2, 0, 0);
  EXPECT_TRUE(growth::nearlyCollinear(a, growth::Vec3d(1, 0, 0), c));
  EXPECT_TRUE(growth::nearlyCollinear(a, a, c));
  // Middle vertex 0.005 off the line: 179.43°; 0.02 off: 177.7°.
  EXPECT_TRUE(growth::nearlyCollinear(a, growth::Vec3d(1, 0.005, 0), c));
  EXPECT_FALSE(growth::nearlyCollinear(a, growth::Vec3d(1, 0.02, 0), c));
  EXPECT_FALSE(growth::nearlyCollinear(a, growth::Vec3d(1, std::sqrt(3.0), 0), c));
  // The same at 10^6 from the origin (the test works on differences).
  const growth::Vec3d o(1e6, 1e6, 1e6);
  EXPECT_TRUE(growth::nearlyCollinear(a + o, growth::Vec3d(1, 0.005, 0) + o, c + o));
  EXPECT_FALSE(growth::nearlyCollinear(a + o, growth::Vec3d(1, 0.02, 0) + o, c + o));
}
