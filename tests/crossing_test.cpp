// Crossing check (sec. 3.6, fig. 4b): projected along the normal at the candidate, its new edges
// must not cross existing edges within d in the normal direction.
#include "borders.h"
#include "crossing.h"

#include <gtest/gtest.h>

using Point3d = growth::Vec3d;

TEST(SegmentsCross2D, ProperCrossingsOnly) {
  EXPECT_TRUE(growth::segmentsCross2D(0, 0, 1, 1, 0, 1, 1, 0));
  EXPECT_FALSE(growth::segmentsCross2D(0, 0, 1, 1, 2, 0, 3, 1));     // apart
  EXPECT_FALSE(growth::segmentsCross2D(0, 0, 1, 0, 1, 0, 2, 1));     // touching at an endpoint
  EXPECT_FALSE(growth::segmentsCross2D(0, 0, 1, 0, 0.5, 0, 0.5, 1)); // T-touch
  EXPECT_FALSE(growth::segmentsCross2D(0, 0, 2, 0, 1, 0, 3, 0));     // collinear overlap
  EXPECT_FALSE(growth::segmentsCross2D(0, 0, 1, 1, 0.6, 0.5, 2, 0.5));
}

namespace {
// An existing edge p–q and the two parents a, b of a candidate c.
struct Scene {
  growth::BorderGraph g;
  std::uint32_t a, b, p, q;
  std::vector<std::uint32_t> all;
  Scene(const Point3d& pa, const Point3d& pb, const Point3d& pp, const Point3d& pq) {
    const Point3d up(0, 0, 1);
    a = g.addVertex(pa, up);
    b = g.addVertex(pb, up);
    p = g.addVertex(pp, up);
    q = g.addVertex(pq, up);
    g.addEdge(p, -1, q, -1);
    all = {a, b, p, q};
  }
};
} // namespace

TEST(Crossing, NewEdgeAcrossAnExistingEdgeIsRejected) {
  const double d = 1;
  const Point3d up(0, 0, 1);
  // Candidate at the origin, parents to the left and right-below; an edge crossing c–a.
  Scene s(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, -0.5, 0), Point3d(-0.5, 0.5, 0));
  EXPECT_TRUE(growth::newEdgesCross(s.g, Point3d(0, 0, 0), s.a, s.b, up, d, s.all));
  // The same edge moved away: no crossing.
  Scene t(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, 0.3, 0), Point3d(-0.5, 1.3, 0));
  EXPECT_FALSE(growth::newEdgesCross(t.g, Point3d(0, 0, 0), t.a, t.b, up, d, t.all));
  // Crossing c–b instead.
  Scene u(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(0, -0.6, 0), Point3d(0.6, -0.2, 0));
  EXPECT_TRUE(growth::newEdgesCross(u.g, Point3d(0, 0, 0), u.a, u.b, up, d, u.all));
}

TEST(Crossing, OnlyTheVicinityInNormalDirectionCounts) {
  const double d = 1;
  const Point3d up(0, 0, 1);
  // The crossing edge lies 1.5 d above: another sheet of the surface, ignored.
  Scene s(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, -0.5, 1.5), Point3d(-0.5, 0.5, 1.5));
  EXPECT_FALSE(growth::newEdgesCross(s.g, Point3d(0, 0, 0), s.a, s.b, up, d, s.all));
  // Within d below: counts.
  Scene t(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, -0.5, -0.9), Point3d(-0.5, 0.5, -0.9));
  EXPECT_TRUE(growth::newEdgesCross(t.g, Point3d(0, 0, 0), t.a, t.b, up, d, t.all));
  // One endpoint inside the slab is enough.
  Scene v(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, -0.5, 0.8), Point3d(-0.5, 0.5, 1.4));
  EXPECT_TRUE(growth::newEdgesCross(v.g, Point3d(0, 0, 0), v.a, v.b, up, d, v.all));
}

TEST(Crossing, ProjectionFollowsTheGivenNormal) {
  const double d = 1;
  // Seen along z the edge crosses c–a; seen along x (a plane y–z) it does not.
  Scene s(Point3d(-1, 0, 0), Point3d(0.5, -0.866, 0), Point3d(-0.5, -0.5, 0), Point3d(-0.5, 0.5, 0));
  EXPECT_TRUE(growth::newEdgesCross(s.g, Point3d(0, 0, 0), s.a, s.b, Point3d(0, 0, 1), d, s.all));
  EXPECT_FALSE(growth::newEdgesCross(s.g, Point3d(0, 0, 0), s.a, s.b, Point3d(1, 0, 0), d, s.all));
}

TEST(Crossing, EdgesAtTheParentsOnlyTouch) {
  const double d = 1;
  const Point3d up(0, 0, 1);
  // Existing edges a–p and b–q share an endpoint with the new edges: not crossings.
  growth::BorderGraph g;
  const auto a = g.addVertex(Point3d(-1, 0, 0), up), b = g.addVertex(Point3d(0.5, -0.866, 0), up);
  const auto p = g.addVertex(Point3d(-1, 1, 0), up), q = g.addVertex(Point3d(1.5, -0.866, 0), up);
  g.addEdge(a, -1, p, -1);
  g.addEdge(b, -1, q, -1);
  g.addEdge(a, g.gapOf(a, g.position(b)), b, g.gapOf(b, g.position(a)));
  EXPECT_FALSE(growth::newEdgesCross(g, Point3d(0, 0, 0), a, b, up, d, {a, b, p, q}));
  // But an edge at b that crosses c–a does count.
  const auto r = g.addVertex(Point3d(-0.6, 0.4, 0), up);
  g.addEdge(b, g.gapOf(b, g.position(r)), r, -1);
  EXPECT_TRUE(growth::newEdgesCross(g, Point3d(0, 0, 0), a, b, up, d, {a, b, p, q, r}));
}

TEST(Crossing, SearchRadiusCoversEveryEdgeThatCanCross) {
  // An edge of length d crossing a new edge of length d within the slab has an endpoint within
  // √5·d of c: the worst case, an endpoint at height d and 2d sideways.
  const double d = 1;
  EXPECT_GE(growth::crossingSearchRadius(d), std::sqrt(4.0 + 1.0));
  EXPECT_LT(growth::crossingSearchRadius(d), 2.24);
}
