// Borders of the regions of G as oriented half-edge cycles (sec. 3.4, 4.2, figures 3 and 6):
// lone vertices, single edges, split and join on insertion, cyclic order in the plane orthogonal
// to the vertex normal, the window walk, and the priority levels of sec. 3.5.
#include "borders.h"
#include <growth/cloud_generator.h>
#include "splats.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <map>

using growth::BorderGraph;
using growth::HalfEdge;
using Point3d = growth::Vec3d;

namespace {
const Point3d kUp(0, 0, 1);

std::vector<size_t> lengths(const BorderGraph& g) {
  std::vector<size_t> l;
  for (const auto& c : g.borders()) l.push_back(c.size());
  std::sort(l.begin(), l.end());
  return l;
}
size_t borderCount(const BorderGraph& g) { return g.borders().size() + g.loneVertices(); }

// Inserts c with edges to a and b in the gaps their directions fall into.
bool grow(BorderGraph& g, std::uint32_t c, std::uint32_t a, std::uint32_t b) {
  return g.connect(c, a, g.gapOf(a, g.position(c)), b, g.gapOf(b, g.position(c)));
}

// gapOf() from scratch: the neighbours' angles computed now with angleAt() (the graph keeps them
// from the insertions), the same rule otherwise.
int referenceGapOf(const BorderGraph& g, std::uint32_t v, const Point3d& target) {
  const int deg = g.degree(v);
  if (deg == 0) return -1;
  if (deg == 1) return 0;
  const double twoPi = 4; // angleAt: a pseudo-angle, a full turn is 4
  auto ccw = [&](double a, double b) {
    double t = b - a;
    while (t < 0) t += twoPi;
    while (t >= twoPi) t -= twoPi;
    return t;
  };
  const double th = g.angleAt(v, target);
  int best = 0;
  double bestSlack = -twoPi - 1;
  for (int k = 0; k < deg; ++k) {
    const double a0 = g.angleAt(v, g.position(g.neighbour(v, k)));
    const double a1 = g.angleAt(v, g.position(g.neighbour(v, (k + 1) % deg)));
    const double span = ccw(a0, a1), into = ccw(a0, th);
    if (into < span) return k;
    if (span - into > bestSlack) bestSlack = span - into, best = k;
  }
  return best;
}

// Signed area of a cycle projected along kUp.
double signedArea(const BorderGraph& g, const std::vector<std::uint32_t>& c) {
  double a = 0;
  for (size_t i = 0; i < c.size(); ++i) {
    const Point3d &p = g.position(c[i]), &q = g.position(c[(i + 1) % c.size()]);
    a += p[0] * q[1] - p[1] * q[0];
  }
  return 0.5 * a;
}
} // namespace

TEST(Borders, LoneVertexIsABorderOfLengthZero) {
  BorderGraph g;
  g.addVertex(Point3d(0, 0, 0), kUp);
  g.addVertex(Point3d(1, 0, 0), kUp);
  EXPECT_TRUE(g.borders().empty());
  EXPECT_EQ(g.loneVertices(), 2u);
  EXPECT_EQ(g.gapOf(0, Point3d(1, 1, 0)), -1);
}

TEST(Borders, SingleEdgeIsABorderOfLengthTwo) {
  BorderGraph g;
  g.addVertex(Point3d(0, 0, 0), kUp);
  g.addVertex(Point3d(1, 0, 0), kUp);
  ASSERT_TRUE(g.addEdge(0, -1, 1, -1));
  EXPECT_EQ(lengths(g), (std::vector<size_t>{2}));
  EXPECT_EQ(g.gapOf(0, Point3d(-1, 3, 0)), 0); // one gap all around
  const HalfEdge h{0, 0};
  EXPECT_EQ(g.next(h), (HalfEdge{1, 0}));
  EXPECT_EQ(g.next(g.next(h)), h);
  EXPECT_FALSE(g.addEdge(0, 0, 1, 0)); // no double edge
}

TEST(Borders, FirstInsertionJoinsTwoLoneVerticesIntoABorderOfLengthFour) {
  BorderGraph g;
  g.addVertex(Point3d(0, 0, 0), kUp);
  g.addVertex(Point3d(1.5, 0, 0), kUp);
  const auto c = g.addVertex(Point3d(0.75, 0.66, 0), kUp);
  EXPECT_EQ(borderCount(g), 3u);
  ASSERT_TRUE(grow(g, c, 0, 1));
  EXPECT_EQ(borderCount(g), 1u); // two borders joined (fig. 6b: back and forth)
  EXPECT_EQ(lengths(g), (std::vector<size_t>{4}));
}

TEST(Borders, InsertionSplitsOneBorderIntoTwoWithTheRegionOnTheLeft) {
  BorderGraph g;
  g.addVertex(Point3d(0, 0, 0), kUp);
  g.addVertex(Point3d(1, 0, 0), kUp);
  const auto c = g.addVertex(Point3d(0.5, std::sqrt(0.75), 0), kUp);
  ASSERT_TRUE(grow(g, c, 0, 1)); // path 0 - c - 1
  // Close the triangle on the other side... the vertex below the edge 0–1 does not exist, so put
  // a vertex connected to 0 and c: a triangle 0, c, x.
  const auto x = g.addVertex(Point3d(-0.5, std::sqrt(0.75), 0), kUp);
  // Corners of 0 and c toward x are on the same (only) border: their distance along it is 1.
  EXPECT_EQ(g.borderDistance(0, g.gapOf(0, g.position(x)), c, g.gapOf(c, g.position(x)), 8), 1);
  ASSERT_TRUE(grow(g, x, 0, c));
  EXPECT_EQ(borderCount(g), 2u);
  EXPECT_EQ(lengths(g), (std::vector<size_t>{3, 5}));
  for (const auto& cyc : g.borders()) {
    if (cyc.size() == 3) {
      EXPECT_GT(signedArea(g, cyc), 0); // inner region: counter-clockwise
    }
  }
}

TEST(Borders, ConnectingTwoComponentsJoinsTheirBorders) {
  BorderGraph g;
  // Two paths, far apart.
  for (double x0 : {0.0, 3.0}) {
    const auto a = g.addVertex(Point3d(x0, 0, 0), kUp);
    const auto b = g.addVertex(Point3d(x0 + 1, 0, 0), kUp);
    const auto c = g.addVertex(Point3d(x0 + 0.5, 0.8, 0), kUp);
    ASSERT_TRUE(grow(g, c, a, b));
  }
  EXPECT_EQ(borderCount(g), 2u);
  const auto j = g.addVertex(Point3d(2, 0.5, 0), kUp);
  // Vertices 1 (x = 1) and 3 (x = 3) are on different borders: distance 0 = join.
  EXPECT_EQ(g.borderDistance(1, g.gapOf(1, g.position(j)), 3, g.gapOf(3, g.position(j)), 100), 0);
  ASSERT_TRUE(grow(g, j, 1, 3));
  EXPECT_EQ(borderCount(g), 1u);
  EXPECT_EQ(lengths(g), (std::vector<size_t>{12}));
}

TEST(Borders, CyclicOrderIsMeasuredInThePlaneOfTheVertexNormal) {
  // A centre with a tilted normal; neighbours inserted in a scrambled order end up sorted
  // counter-clockwise around the normal.
  const Point3d n = Point3d(0.3, -0.2, 1).Normalize();
  Point3d e1, e2;
  growth::tangentFrame(n, e1, e2);
  BorderGraph g;
  const auto centre = g.addVertex(Point3d(0, 0, 0), n);
  std::vector<double> angles{0.1, 2.0, 4.0, 1.0, 5.5, 3.0};
  // Neighbours come with edges to the centre only, as single edges.
  for (double a : angles) {
    const Point3d p = (e1 * std::cos(a) + e2 * std::sin(a)) + n * 0.3; // off the plane too
    const auto v = g.addVertex(p, n);
    ASSERT_TRUE(g.addEdge(centre, g.gapOf(centre, p), v, -1));
  }
  std::vector<double> got;
  for (int k = 0; k < g.degree(centre); ++k) got.push_back(g.angleAt(centre, g.position(g.neighbour(centre, k))));
  // Cyclically increasing.
  int descents = 0;
  for (size_t k = 0; k < got.size(); ++k) descents += got[(k + 1) % got.size()] < got[k] ? 1 : 0;
  EXPECT_EQ(descents, 1);
  // A direction at angle 1.5 falls between the neighbours at 1.0 and 2.0.
  const int gap = g.gapOf(centre, e1 * std::cos(1.5) + e2 * std::sin(1.5));
  auto at = [&](double a) { return g.angleAt(centre, e1 * std::cos(a) + e2 * std::sin(a)); };
  EXPECT_NEAR(g.angleAt(centre, g.position(g.neighbour(centre, gap))), at(1.0), 1e-12);
  EXPECT_NEAR(g.angleAt(centre, g.position(g.neighbour(centre, (gap + 1) % g.degree(centre)))), at(2.0), 1e-12);
}

TEST(Borders, WindowBoundsTheWalkAlongTheBorder) {
  // A ring of 20 vertices (a cycle: inner and outer border of length 20).
  BorderGraph g;
  const int n = 20;
  for (int i = 0; i < n; ++i) g.addVertex(Point3d(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), 0), kUp);
  for (int i = 0; i < n; ++i) {
    const int j = (i + 1) % n;
    ASSERT_TRUE(g.addEdge(i, g.gapOf(i, g.position(j)), j, g.gapOf(j, g.position(i))));
  }
  EXPECT_EQ(lengths(g), (std::vector<size_t>{20, 20}));
  // Corners facing the centre: distances along the inner border.
  const Point3d centre(0, 0, 0);
  for (int k = 1; k < n; ++k) {
    const int along = std::min(k, n - k);
    EXPECT_EQ(g.borderDistance(0, g.gapOf(0, centre), k, g.gapOf(k, centre), 8), along <= 8 ? along : 0) << k;
    EXPECT_EQ(g.borderDistance(0, g.gapOf(0, centre), k, g.gapOf(k, centre), 100), along);
    EXPECT_EQ(g.borderDistance(0, g.gapOf(0, centre), k, g.gapOf(k, centre), 0), 0); // w = 0: never a split
  }
  // An inner corner and an outer corner are on different borders.
  EXPECT_EQ(g.borderDistance(0, g.gapOf(0, centre), 1, g.gapOf(1, Point3d(5, 5, 0)), 100), 0);
}

TEST(Borders, GrowthOnALatticeKeepsAPlanarEmbedding) {
  // Vertices of a triangular lattice inserted in a scrambled order, each connected to two of its
  // lattice neighbours already present; the edges never cross, so the rotation system must stay
  // planar: V − E + (borders + lone vertices) = 2 · components, and every insertion splits (+1)
  // or joins (−1). next/prev are inverse and every border has its region on the left.
  BorderGraph g;
  const int R = 6;
  std::map<std::pair<int, int>, std::uint32_t> id;
  std::vector<std::pair<int, int>> cells;
  for (int i = -R; i <= R; ++i)
    for (int j = -R; j <= R; ++j)
      if (std::abs(i + j) <= R) cells.emplace_back(i, j);
  auto pos = [](int i, int j) { return Point3d(i + 0.5 * j, std::sqrt(0.75) * j, 0.0); };
  // Breadth-first from the centre with a seeded shuffle inside each ring.
  std::sort(cells.begin(), cells.end(), [](auto a, auto b) {
    const int ra = std::max({std::abs(a.first), std::abs(a.second), std::abs(a.first + a.second)});
    const int rb = std::max({std::abs(b.first), std::abs(b.second), std::abs(b.first + b.second)});
    return ra != rb ? ra < rb : a < b;
  });
  const int dirs[6][2] = {{1, 0}, {0, 1}, {-1, 1}, {-1, 0}, {0, -1}, {1, -1}};
  growth::Random rnd(5);
  id[{0, 0}] = g.addVertex(pos(0, 0), kUp);
  id[{1, 0}] = g.addVertex(pos(1, 0), kUp);
  // Inserts the lattice cell c when two of its neighbours are there; false otherwise.
  auto tryInsert = [&](const std::pair<int, int>& c) {
    std::vector<std::uint32_t> nb;
    for (const auto& d : dirs) {
      auto it = id.find({c.first + d[0], c.second + d[1]});
      if (it != id.end()) nb.push_back(it->second);
    }
    if (nb.size() < 2) return false;
    const size_t a = size_t(rnd.uniform(0, double(nb.size())));
    size_t b = size_t(rnd.uniform(0, double(nb.size() - 1)));
    if (b >= a) ++b;
    const auto v = g.addVertex(pos(c.first, c.second), kUp);
    const size_t before = borderCount(g) - 1; // v itself is still a lone vertex
    const int dist = g.degree(nb[a]) > 0 && g.degree(nb[b]) > 0
                         ? g.borderDistance(nb[a], g.gapOf(nb[a], g.position(v)), nb[b],
                                            g.gapOf(nb[b], g.position(v)), 1000)
                         : 0;
    EXPECT_TRUE(grow(g, v, nb[a], nb[b]));
    id[c] = v;
    const size_t after = borderCount(g);
    EXPECT_EQ(after, dist > 0 ? before + 1 : before - 1) << "split iff the parents share a border";
    EXPECT_EQ(long(g.vertexCount()) - long(g.edgeCount()) + long(after), 2) << "Euler characteristic";
    return true;
  };
  size_t inserted = 0;
  for (bool progress = true; progress;) {
    progress = false;
    for (const auto& c : cells)
      if (!id.count(c) && tryInsert(c)) ++inserted, progress = true;
  }
  EXPECT_EQ(inserted + 2, cells.size());
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    for (int k = 0; k < g.degree(v); ++k) {
      const HalfEdge h{v, k};
      EXPECT_EQ(g.prev(g.next(h)), h);
      EXPECT_EQ(g.next(g.prev(h)), h);
    }
  // The corners found from the angles kept per edge are those computed from scratch.
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    for (int t = 0; t < 16; ++t) {
      const Point3d target = g.position(v) + rnd.unitVector();
      ASSERT_EQ(g.gapOf(v, target), referenceGapOf(g, v, target));
    }
  // Exactly one border (the outer one) runs clockwise.
  int clockwise = 0;
  for (const auto& cyc : g.borders())
    if (cyc.size() >= 3 && signedArea(g, cyc) < 0) ++clockwise;
  EXPECT_EQ(clockwise, 1);
}

TEST(CandidatePriority, LevelsFollowSection35) {
  const int w = 8;
  EXPECT_EQ(growth::CandidatePriority::levels(w), 11);
  EXPECT_EQ(growth::CandidatePriority::level(0, 3, 5, w), 0); // parent without edges
  EXPECT_EQ(growth::CandidatePriority::level(4, 1, 5, w), 1); // parent with one edge
  EXPECT_EQ(growth::CandidatePriority::level(2, 3, 0, w), 2); // join
  EXPECT_EQ(growth::CandidatePriority::level(2, 3, 8, w), 3); // split, largest distance first
  EXPECT_EQ(growth::CandidatePriority::level(2, 3, 1, w), 10);
  for (int dist = 1; dist < w; ++dist)
    EXPECT_LT(growth::CandidatePriority::level(2, 2, dist + 1, w), growth::CandidatePriority::level(2, 2, dist, w));
  EXPECT_EQ(growth::CandidatePriority::levels(0), 3);          // w = 0: breadth-first after the start
  EXPECT_EQ(growth::CandidatePriority::level(2, 2, 0, 0), 2);
}

TEST(Borders, GapSeenAlongAnotherNormal) {
  // Centre with neighbours at 0°, 90°, 180° (tangent plane z = 0). A direction at 45° lies in the
  // gap (0°, 90°); seen along a normal tilted towards it nothing changes, but a steep target right
  // above the centre, slightly to one side, flips to another gap when the projection axis tilts.
  BorderGraph g;
  const auto c = g.addVertex(Point3d(0, 0, 0), kUp);
  for (const Point3d& p : {Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(-1, 0, 0)}) {
    const auto v = g.addVertex(p, kUp);
    ASSERT_TRUE(g.addEdge(c, g.gapOf(c, p), v, -1));
  }
  const Point3d flat(1, 1, 0);
  const int gap = g.gapOf(c, flat);
  EXPECT_TRUE(g.gapContains(c, gap, flat, kUp));
  EXPECT_TRUE(g.gapContains(c, gap, flat, Point3d(0.2, 0.1, 1).Normalize()));
  const Point3d steep(0.05, 0.05, 1); // nearly along the normal, at 45° in the plane
  const int g2 = g.gapOf(c, steep);
  EXPECT_EQ(g2, gap);
  EXPECT_FALSE(g.gapContains(c, g2, steep, Point3d(0.3, 0, 1).Normalize())); // now seen at ~180°
  // A vertex with one edge has one gap all around: it holds every direction.
  ASSERT_EQ(g.degree(1), 1);
  EXPECT_TRUE(g.gapContains(1, 0, Point3d(5, -3, 2), Point3d(1, 0, 0)));
}
