#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/manifold_cleanup.h>
#include <growth/self_intersections.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <map>
#include <tuple>
#include <vector>

using growth::Triangle;
using growth::facesIntersect;
using growth::findSelfIntersections;
using growth::removeSelfIntersections;
using Point3d = growth::Vec3d;

namespace {

using Pairs = std::vector<std::pair<std::uint32_t, std::uint32_t>>;

// Two faces 0 = (0, 1, 2) and 1 = (3, 4, 5) with the given corners: do they intersect?
bool meet(const Point3d& a0, const Point3d& a1, const Point3d& a2, const Point3d& b0, const Point3d& b1, const Point3d& b2) {
  const std::vector<Point3d> pos{a0, a1, a2, b0, b1, b2};
  const bool pair = facesIntersect(pos, {0, 1, 2}, {3, 4, 5});
  // The same answer in any order of the faces and of their corners, and from the search.
  EXPECT_EQ(facesIntersect(pos, {3, 4, 5}, {0, 1, 2}), pair);
  EXPECT_EQ(facesIntersect(pos, {1, 2, 0}, {5, 3, 4}), pair);
  EXPECT_EQ(facesIntersect(pos, {2, 1, 0}, {4, 3, 5}), pair);
  EXPECT_EQ(findSelfIntersections(pos, {{0, 1, 2}, {3, 4, 5}}).size(), pair ? 1u : 0u);
  return pair;
}

// Faces (v, a, b) and (v, c, d) sharing the vertex v.
bool meetAtVertex(const Point3d& v, const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
  const std::vector<Point3d> pos{v, a, b, c, d};
  const bool pair = facesIntersect(pos, {0, 1, 2}, {0, 3, 4});
  EXPECT_EQ(facesIntersect(pos, {3, 4, 0}, {2, 0, 1}), pair);
  EXPECT_EQ(facesIntersect(pos, {0, 2, 1}, {4, 0, 3}), pair);
  EXPECT_EQ(findSelfIntersections(pos, {{0, 1, 2}, {0, 3, 4}}).size(), pair ? 1u : 0u);
  return pair;
}

// Faces (u, w, a) and (w, u, b) sharing the edge u–w.
bool meetAtEdge(const Point3d& u, const Point3d& w, const Point3d& a, const Point3d& b) {
  const std::vector<Point3d> pos{u, w, a, b};
  const bool pair = facesIntersect(pos, {0, 1, 2}, {1, 0, 3});
  EXPECT_EQ(facesIntersect(pos, {1, 0, 3}, {2, 0, 1}), pair);
  EXPECT_EQ(facesIntersect(pos, {0, 1, 2}, {0, 1, 3}), pair); // orientation does not matter
  EXPECT_EQ(findSelfIntersections(pos, {{0, 1, 2}, {1, 0, 3}}).size(), pair ? 1u : 0u);
  return pair;
}

// Every pair of taking-part faces through the pair test: the O(n²) reference.
Pairs bruteForce(const std::vector<Point3d>& pos, const std::vector<Triangle>& faces, const std::vector<char>* alive = nullptr) {
  Pairs out;
  for (std::uint32_t i = 0; i < faces.size(); ++i) {
    if (alive && !(*alive)[i]) continue;
    for (std::uint32_t j = i + 1; j < faces.size(); ++j) {
      if (alive && !(*alive)[j]) continue;
      if (facesIntersect(pos, faces[i], faces[j])) out.emplace_back(i, j);
    }
  }
  return out;
}

// The unit icosphere: the icosahedron with every face split in four `levels` times, projected on
// the sphere. Closed, consistently oriented, convex.
void icosphere(int levels, std::vector<Point3d>& pos, std::vector<Triangle>& faces) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  pos = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
         {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  faces = {{0, 11, 5}, {0, 5, 1}, {0, 1, 7}, {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
           {11, 10, 2}, {10, 7, 6}, {7, 1, 8}, {3, 9, 4}, {3, 4, 2}, {3, 2, 6}, {3, 6, 8},
           {3, 8, 9}, {4, 9, 5}, {2, 4, 11}, {6, 2, 10}, {8, 6, 7}, {9, 8, 1}};
  for (auto& p : pos) p.Normalize();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> middle;
    auto mid = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      const auto it = middle.find(key);
      if (it != middle.end()) return it->second;
      pos.push_back((pos[a] + pos[b]).Normalize());
      return middle[key] = std::uint32_t(pos.size() - 1);
    };
    std::vector<Triangle> next;
    for (const Triangle& f : faces) {
      const std::uint32_t ab = mid(f[0], f[1]), bc = mid(f[1], f[2]), ca = mid(f[2], f[0]);
      next.push_back({f[0], ab, ca});
      next.push_back({f[1], bc, ab});
      next.push_back({f[2], ca, bc});
      next.push_back({ab, bc, ca});
    }
    faces = next;
  }
}

} // namespace

// --- Degenerate inputs ---

TEST(SelfIntersections, EmptyAndSingleFace) {
  EXPECT_TRUE(findSelfIntersections({}, {}).empty());
  const std::vector<Point3d> pos{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_TRUE(findSelfIntersections(pos, {{0, 1, 2}}).empty());
  std::vector<char> alive{1};
  EXPECT_EQ(removeSelfIntersections(pos, {{0, 1, 2}}, alive), 0u);
  EXPECT_EQ(alive[0], 1);
}

TEST(SelfIntersections, DeadAndRepeatedVertexFacesTakeNoPart) {
  // Two crossing triangles: found while both are alive and proper, and not otherwise.
  const std::vector<Point3d> pos{{0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {2, 2, 0}};
  const std::vector<Triangle> faces{{0, 1, 2}, {3, 4, 5}};
  EXPECT_EQ(findSelfIntersections(pos, faces), (Pairs{{0, 1}}));
  const std::vector<char> firstDead{0, 1}, bothAlive{1, 1};
  EXPECT_TRUE(findSelfIntersections(pos, faces, &firstDead).empty());
  EXPECT_EQ(findSelfIntersections(pos, faces, &bothAlive), (Pairs{{0, 1}}));
  // A face with a repeated vertex index is no face (even though its corners span the crossing).
  EXPECT_TRUE(findSelfIntersections(pos, {{0, 1, 2}, {3, 4, 4}}).empty());
  EXPECT_TRUE(findSelfIntersections(pos, {{0, 0, 2}, {3, 4, 5}}).empty());
  EXPECT_FALSE(facesIntersect(pos, {0, 1, 1}, {3, 4, 5}));
  // Bad input is refused.
  const std::vector<char> wrongSize{1};
  EXPECT_THROW(findSelfIntersections(pos, faces, &wrongSize), growth::Error);
  EXPECT_THROW(findSelfIntersections(pos, {{0, 1, 6}, {3, 4, 5}}), growth::Error);
  std::vector<char> wrong{1, 1, 1};
  EXPECT_THROW(removeSelfIntersections(pos, faces, wrong), growth::Error);
}

// --- Hand-made cases ---

TEST(SelfIntersections, CrossingTriangles) {
  const Point3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  // An edge through the interior.
  EXPECT_TRUE(meet(a, b, c, {0.5, 0.5, -1}, {0.5, 0.5, 1}, {3, 3, 0.5}));
  // The same triangle lifted above the plane.
  EXPECT_FALSE(meet(a, b, c, {0.5, 0.5, 0.25}, {0.5, 0.5, 1}, {3, 3, 0.5}));
  // Crossing through each other's interiors, no vertex of either inside the other.
  EXPECT_TRUE(meet({-1, 0, 0}, {1, 0, 0}, {0, 2, 0}, {0, 1, -1}, {0, 1, 1}, {0, -1, 0}));
  EXPECT_FALSE(meet({-1, 0, 0}, {1, 0, 0}, {0, 2, 0}, {1.5, 1, -1}, {1.5, 1, 1}, {1.5, -1, 0}));
}

TEST(SelfIntersections, VertexTouchingTheInterior) {
  // T1 in the plane z = fl(0.1); T2 has one corner exactly on it (intersecting, at one point),
  // or one ulp above or below.
  const double z = 0.1;
  const Point3d a(0.3, 0.1, z), b(2.7, 0.3, z), c(0.1, 2.9, z);
  EXPECT_TRUE(meet(a, b, c, {0.7, 0.9, z}, {1.1, 1.3, 1.7}, {0.2, 1.9, 2.3}));
  EXPECT_FALSE(meet(a, b, c, {0.7, 0.9, std::nextafter(z, 1.0)}, {1.1, 1.3, 1.7}, {0.2, 1.9, 2.3}));
  EXPECT_TRUE(meet(a, b, c, {0.7, 0.9, std::nextafter(z, 0.0)}, {1.1, 1.3, 1.7}, {0.2, 1.9, 2.3}));
  // On an edge of T1 and at a corner of T1.
  EXPECT_TRUE(meet({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {1, 0, 0}, {1, 1, 1}, {0.5, -1, 1}));
  EXPECT_TRUE(meet({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {0, 0, 0}, {1, 1, 1}, {0.5, -1, 1}));
  EXPECT_FALSE(meet({0, 0, 0}, {2, 0, 0}, {0, 2, 0}, {-1e-80, 0, 0}, {-1, 1, 1}, {-0.5, -1, 1}));
}

TEST(SelfIntersections, SharedVertex) {
  const Point3d v(0, 0, 0);
  // A fan: the faces only touch at v.
  EXPECT_FALSE(meetAtVertex(v, {1, 0, 0}, {0, 1, 0}, {-1, 0, 0.2}, {0, -1, 0.1}));
  // Sharing v and crossing: an edge of the second face goes through the first.
  EXPECT_TRUE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {1, 0.5, -1}, {1, 0.5, 1}));
  // A corner of the second face at the position of one of the first (a different vertex): they
  // share the segment from v to it.
  EXPECT_TRUE(meetAtVertex(v, {1, 0, 0}, {0, 1, 0}, {1, 0, 0}, {0, 0, 1}));
  // Coplanar: overlapping wedges at v, and wedges on either side of a common ray.
  EXPECT_TRUE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {1, 1, 0}, {2, 1, 0}));
  EXPECT_FALSE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {-1, 1, 0}, {-1, -1, 0}));
  EXPECT_TRUE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {4, 0, 0}, {0, -2, 0}));  // along v–(2,0,0)
  EXPECT_FALSE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {4, -1e-80, 0}, {0, -2, 0}));
  // The planes meet along the x axis: the faces share the segment to (2, 0, 0) when the second
  // one extends along +x (its far edge through that corner, or beyond it), only v along −x.
  EXPECT_TRUE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {2, -1, 1}, {2, 1, -1}));
  EXPECT_TRUE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {2.5, -1, 1}, {2.5, 1, -1}));
  EXPECT_FALSE(meetAtVertex(v, {2, 0, 0}, {0, 2, 0}, {-2, -1, 1}, {-2, 1, -1}));
}

TEST(SelfIntersections, SharedEdge) {
  const Point3d u(0, 0, 0), w(1, 0, 0);
  // Flat, on opposite sides: an ordinary mesh edge.
  EXPECT_FALSE(meetAtEdge(u, w, {0.3, 1, 0}, {0.6, -1, 0}));
  // At a dihedral angle.
  EXPECT_FALSE(meetAtEdge(u, w, {0.3, 1, 0}, {0.6, -1, 0.5}));
  EXPECT_FALSE(meetAtEdge(u, w, {0.3, 1, 0}, {0.6, 1, 0.5}));
  // Folded onto each other (coplanar, same side), including one inside the other and their
  // third corners on the same side far apart.
  EXPECT_TRUE(meetAtEdge(u, w, {0.3, 1, 0}, {0.6, 0.5, 0}));
  EXPECT_TRUE(meetAtEdge(u, w, {0.3, 1, 0}, {0.3, 1, 0}));
  EXPECT_TRUE(meetAtEdge(u, w, {-10, 1, 0}, {11, 1, 0}));
  // One ulp out of the plane: a dihedral angle, no overlap.
  EXPECT_FALSE(meetAtEdge(u, w, {0.3, 1, 0}, {0.6, 0.5, 1e-80}));
  // On an inexact plane: the first face in z = fl(0.1), the second's corner on it or 1 ulp off.
  const double z = 0.1;
  const Point3d u2(0.3, 0.1, z), w2(1.7, 0.3, z);
  EXPECT_TRUE(meetAtEdge(u2, w2, {0.9, 1.1, z}, {1.3, 0.7, z}));
  EXPECT_FALSE(meetAtEdge(u2, w2, {0.9, 1.1, z}, {1.3, 0.7, std::nextafter(z, 1.0)}));
}

TEST(SelfIntersections, FoldsOnInexactPlanesAreDecidedExactly) {
  // f = (a, b, c) with coordinates k·2^-20, |k| < 2^30, and g = (b, a, d) with d = a + 2(b − a) +
  // (c − a) exactly (the same lattice): coplanar, on c's side of the edge, a fold-over. Evaluated
  // in floating point, the plane side of d mostly comes out nonzero; one lattice unit off the plane
  // the faces meet at a dihedral angle and do not intersect.
  growth::Random rng(31);
  const double unit = std::ldexp(1.0, -20);
  auto coord = [&]() { return double(std::int64_t(rng.next() % (std::uint64_t(1) << 30)) - (std::int64_t(1) << 29)) * unit; };
  int roundedOff = 0;
  for (int trial = 0; trial < 2000; ++trial) {
    const Point3d a(coord(), coord(), coord()), b(coord(), coord(), coord()), c(coord(), coord(), coord());
    const Point3d d = a + (b - a) * 2.0 + (c - a); // exact: integers below 2^33 times 2^-20
    const Point3d n = (b - a) ^ (c - a);
    roundedOff += n * (d - a) != 0;
    EXPECT_TRUE(meetAtEdge(a, b, c, d)) << trial;
    EXPECT_FALSE(meetAtEdge(a, b, c, d + Point3d(0, 0, unit))) << trial;
  }
  EXPECT_GT(roundedOff, 1000); // the naive side test would call most of them non-coplanar
}

TEST(SelfIntersections, DuplicateFaces) {
  const std::vector<Point3d> pos{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {5, 5, 5}};
  EXPECT_TRUE(facesIntersect(pos, {0, 1, 2}, {0, 1, 2}));
  EXPECT_TRUE(facesIntersect(pos, {0, 1, 2}, {2, 1, 0}));
  EXPECT_EQ(findSelfIntersections(pos, {{0, 1, 2}, {1, 2, 3}, {1, 0, 2}}), (Pairs{{0, 2}}));
}

TEST(SelfIntersections, Coplanar) {
  const Point3d a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_TRUE(meet(a, b, c, {1, 1, 0}, {3, 1, 0}, {1, 3, 0}));        // corner (1,1) on the hypotenuse
  EXPECT_TRUE(meet(a, b, c, {0.5, 0.5, 0}, {3, 0.5, 0}, {0.5, 3, 0})); // overlapping
  EXPECT_TRUE(meet(a, b, c, {0.2, 0.2, 0}, {0.6, 0.2, 0}, {0.2, 0.6, 0})); // one inside the other
  EXPECT_TRUE(meet(a, b, c, {-1, 0.5, 0}, {3, 0.5, 0}, {1, -1, 0}));  // crossing, no corner inside
  EXPECT_FALSE(meet(a, b, c, {1.1, 1.1, 0}, {3, 1, 0}, {1, 3, 0}));   // just past the hypotenuse
  EXPECT_FALSE(meet(a, b, c, {3, 3, 0}, {4, 3, 0}, {3, 4, 0}));       // disjoint
  // Parallel planes one ulp apart, z = fl(0.1) and the next double: disjoint; at the same z: one
  // inside the other.
  const double z = 0.1, z1 = std::nextafter(z, 1.0);
  const Point3d p(0.3, 0.1, z), q(2.7, 0.3, z), r(0.1, 2.9, z);
  EXPECT_FALSE(meet(p, q, r, {0.5, 0.5, z1}, {1.5, 0.5, z1}, {0.5, 1.5, z1}));
  EXPECT_TRUE(meet(p, q, r, {0.5, 0.5, z}, {1.5, 0.5, z}, {0.5, 1.5, z}));
}

TEST(SelfIntersections, EdgeThroughAVertex) {
  // The second face's edge, vertical at x = y = s, passes exactly through the first face's corner
  // (s = 0), through its interior (s > 0), or beside it (s < 0).
  const Point3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  for (double s : {0.0, 1e-80, -1e-80}) {
    const bool expected = s >= 0;
    EXPECT_EQ(meet(a, b, c, {s, s, -1}, {s, s, 1}, {-2, -3, 0.5}), expected) << s;
  }
  // An edge through the corner along a skew direction.
  EXPECT_TRUE(meet(a, b, c, {-1, -1, -1}, {1, 1, 1}, {-2, 3, 0}));
}

TEST(SelfIntersections, CollinearSlivers) {
  // A zero-area face (0,0,0)–(0.5,0,0)–(x,0,0) is the segment [0, x] on the x axis; the vertical
  // triangle in the plane x = 1 is touched when x reaches 1, not one ulp before.
  const Point3d p(1, -1, -1), q(1, 1, -1), r(1, 0, 1);
  EXPECT_TRUE(meet({0, 0, 0}, {0.5, 0, 0}, {1, 0, 0}, p, q, r));
  EXPECT_TRUE(meet({0, 0, 0}, {2, 0, 0}, {0.5, 0, 0}, p, q, r)); // the middle corner listed last
  EXPECT_FALSE(meet({0, 0, 0}, {0.5, 0, 0}, {std::nextafter(1.0, 0.0), 0, 0}, p, q, r));
  // Two slivers on one line: overlapping, touching at an end, apart.
  EXPECT_TRUE(meet({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {1.5, 1.5, 1.5}, {3, 3, 3}, {4, 4, 4}));
  EXPECT_TRUE(meet({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {2, 2, 2}, {3, 3, 3}, {4, 4, 4}));
  EXPECT_FALSE(meet({0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {2.5, 2.5, 2.5}, {3, 3, 3}, {4, 4, 4}));
  // Crossing slivers, and skew ones.
  EXPECT_TRUE(meet({-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0.5, 0}));
  EXPECT_FALSE(meet({-1, 0, 0}, {0, 0, 0}, {1, 0, 0}, {0, -1, 1e-80}, {0, 1, 1e-80}, {0, 0.5, 1e-80}));
  // A sliver sharing a vertex with a triangle: along its wedge, or outside it.
  EXPECT_TRUE(meetAtVertex({0, 0, 0}, {1, 1, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0}));
  EXPECT_FALSE(meetAtVertex({0, 0, 0}, {-1, -1, 0}, {-2, -2, 0}, {2, 0, 0}, {0, 2, 0}));
  EXPECT_TRUE(meetAtVertex({0, 0, 0}, {-1, -1, 0}, {2, 2, 0}, {2, 0, 0}, {0, 2, 0})); // v inside the sliver
  EXPECT_FALSE(meetAtVertex({0, 0, 0}, {1, 1, 1e-80}, {2, 2, 2e-80}, {2, 0, 0}, {0, 2, 0}));
  // Two slivers sharing a vertex: they meet beyond it when a ray of one is a ray of the other
  // (here each spans a single ray, its other corner sitting at v's position).
  EXPECT_TRUE(meetAtVertex({0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 0}, {2, 0, 0}));
  EXPECT_FALSE(meetAtVertex({0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 0}, {-2, 0, 0}));
  EXPECT_FALSE(meetAtVertex({0, 0, 0}, {1, 0, 0}, {0, 0, 0}, {0, 0, 0}, {2, 1e-80, 0}));
  EXPECT_TRUE(meetAtVertex({0, 0, 0}, {1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {-3, 0, 0}));
  // Slivers sharing an edge with a proper face never overlap it beyond the edge; two slivers on
  // the edge's line do when they stick out at the same end.
  EXPECT_FALSE(meetAtEdge({0, 0, 0}, {1, 0, 0}, {0.3, 1, 0}, {2, 0, 0}));
  EXPECT_TRUE(meetAtEdge({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}));
  EXPECT_FALSE(meetAtEdge({0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {-1, 0, 0}));
  EXPECT_FALSE(meetAtEdge({0, 0, 0}, {1, 0, 0}, {0.5, 0, 0}, {0.7, 0, 0}));
}

// --- An independent reference on lattice points ---
//
// With small integer coordinates every quantity below is an exact 64-bit integer. Two convex
// polytopes (point sets' hulls) are disjoint exactly when the segment between their closest points
// gives a separating direction, and that direction is one of: a face normal, the cross product of
// an edge of each, the perpendicular from a vertex to an edge (e × (e × (v − p))), or the
// difference of two vertices. Taking every pair of points as an "edge" and every pair of edges
// of one set for normals only adds directions, so the separating-axis test over all of them
// decides exactly. Nothing of this shares code or method with the tests under test.

namespace {

struct I3 {
  std::int64_t x, y, z;
};
I3 operator-(const I3& a, const I3& b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
I3 operator+(const I3& a, const I3& b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
I3 cross(const I3& a, const I3& b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
std::int64_t dot(const I3& a, const I3& b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
bool isZero(const I3& a) { return a.x == 0 && a.y == 0 && a.z == 0; }
bool operator==(const I3& a, const I3& b) { return isZero(a - b); }

// The convex hulls of A and B have a point in common.
bool hullsMeet(const std::vector<I3>& A, const std::vector<I3>& B) {
  std::vector<I3> edgesA, edgesB, axes;
  for (size_t i = 0; i < A.size(); ++i)
    for (size_t j = i + 1; j < A.size(); ++j) edgesA.push_back(A[j] - A[i]);
  for (size_t i = 0; i < B.size(); ++i)
    for (size_t j = i + 1; j < B.size(); ++j) edgesB.push_back(B[j] - B[i]);
  for (const auto* edges : {&edgesA, &edgesB})
    for (size_t i = 0; i < edges->size(); ++i)
      for (size_t j = i + 1; j < edges->size(); ++j) axes.push_back(cross((*edges)[i], (*edges)[j]));
  for (const I3& e : edgesA)
    for (const I3& f : edgesB) axes.push_back(cross(e, f));
  for (const I3& a : A)
    for (const I3& b : B) axes.push_back(a - b);
  for (size_t i = 0; i < A.size(); ++i)
    for (size_t j = i + 1; j < A.size(); ++j)
      for (const I3& b : B) axes.push_back(cross(A[j] - A[i], cross(A[j] - A[i], b - A[i])));
  for (size_t i = 0; i < B.size(); ++i)
    for (size_t j = i + 1; j < B.size(); ++j)
      for (const I3& a : A) axes.push_back(cross(B[j] - B[i], cross(B[j] - B[i], a - B[i])));
  for (const I3& axis : axes) {
    if (isZero(axis)) continue;
    std::int64_t loA = dot(axis, A[0]), hiA = loA, loB = dot(axis, B[0]), hiB = loB;
    for (const I3& a : A) {
      loA = std::min(loA, dot(axis, a));
      hiA = std::max(hiA, dot(axis, a));
    }
    for (const I3& b : B) {
      loB = std::min(loB, dot(axis, b));
      hiB = std::max(hiB, dot(axis, b));
    }
    if (hiA < loB || hiB < loA) return false;
  }
  return true;
}

// The part of the face (v, a, b) at least half-way from v, as convex pieces (coordinates doubled,
// so the midpoints are lattice points): it holds the face's edge a–b (or its far ends, for a
// degenerate face) and not v. A common point of two faces sharing v other than v exists exactly
// when a far piece of one meets the other: the farthest common point from v along a shared ray
// lies on a far edge.
std::vector<std::vector<I3>> farPieces(const I3& v, const I3& a, const I3& b) {
  const I3 a2 = a + a, b2 = b + b, ma = v + a, mb = v + b;
  if (!isZero(cross(a - v, b - v))) return {{ma, mb, a2, b2}};
  std::vector<std::vector<I3>> pieces;
  if (!(a == v)) pieces.push_back({ma, a2});
  if (!(b == v)) pieces.push_back({mb, b2});
  return pieces;
}

bool referenceIntersect(const std::vector<I3>& p, const Triangle& f, const Triangle& g) {
  int shared = 0;
  for (std::uint32_t x : f)
    for (std::uint32_t y : g) shared += x == y;
  auto corner = [&](const Triangle& t, int i) { return p[t[size_t(i)]]; };
  if (shared == 3) return true;
  if (shared == 0) return hullsMeet({corner(f, 0), corner(f, 1), corner(f, 2)}, {corner(g, 0), corner(g, 1), corner(g, 2)});
  // Rotate both so the shared corner(s) come first, in f's order.
  int fi = 0, gj = 0;
  if (shared == 1) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j)
        if (f[size_t(i)] == g[size_t(j)]) fi = i, gj = j;
    const I3 v = corner(f, fi), a = corner(f, (fi + 1) % 3), b = corner(f, (fi + 2) % 3);
    const I3 c = corner(g, (gj + 1) % 3), d = corner(g, (gj + 2) % 3);
    const std::vector<I3> F{v + v, a + a, b + b}, G{v + v, c + c, d + d};
    for (const auto& piece : farPieces(v, a, b))
      if (hullsMeet(piece, G)) return true;
    for (const auto& piece : farPieces(v, c, d))
      if (hullsMeet(F, piece)) return true;
    return false;
  }
  // A shared edge u–w; a and b the third corners.
  for (int i = 0; i < 3; ++i)
    if (std::find(g.begin(), g.end(), f[size_t(i)]) == g.end()) fi = i;
  for (int j = 0; j < 3; ++j)
    if (std::find(f.begin(), f.end(), g[size_t(j)]) == f.end()) gj = j;
  const I3 u = corner(f, (fi + 1) % 3), w = corner(f, (fi + 2) % 3), a = corner(f, fi), b = corner(g, gj);
  const I3 na = cross(w - u, a - u), nb = cross(w - u, b - u);
  const bool fProper = !isZero(na), gProper = !isZero(nb);
  if (fProper && gProper) return dot(cross(w - u, a - u), b - u) == 0 && dot(na, nb) > 0;
  if (fProper || gProper) return false;
  if (u == w) return !(a == u) && !(b == u) && isZero(cross(a - u, b - u)) && dot(a - u, b - u) > 0;
  const std::int64_t ta = dot(a - u, w - u), tb = dot(b - u, w - u), len = dot(w - u, w - u);
  return (ta < 0 && tb < 0) || (ta > len && tb > len);
}

// A seeded soup of faces on the lattice [0, side]^3 from a pool of `vertices` points, so that
// faces share vertices and edges, and positions coincide, are collinear and coplanar often.
void latticeSoup(std::uint64_t seed, int side, size_t vertices, size_t faceCount, std::vector<I3>& lattice,
                 std::vector<Point3d>& pos, std::vector<Triangle>& faces) {
  growth::Random rng(seed);
  lattice.clear();
  pos.clear();
  faces.clear();
  auto coord = [&]() { return std::int64_t(rng.next() % std::uint64_t(side + 1)); };
  for (size_t i = 0; i < vertices; ++i) {
    lattice.push_back({coord(), coord(), coord()});
    pos.emplace_back(double(lattice.back().x), double(lattice.back().y), double(lattice.back().z));
  }
  for (size_t f = 0; f < faceCount; ++f) {
    Triangle t;
    for (auto& v : t) v = std::uint32_t(rng.next() % vertices);
    faces.push_back(t);
  }
}

} // namespace

TEST(SelfIntersections, PairTestAgreesWithAnIndependentReference) {
  // Small lattices make every kind of contact common: points on edges, edges through corners,
  // coplanar overlaps, collinear slivers, shared corners and edges in every arrangement.
  size_t tested = 0, intersecting = 0, slivers = 0, sharing = 0;
  for (std::uint64_t seed = 1; seed <= 40; ++seed) {
    std::vector<I3> lattice;
    std::vector<Point3d> pos;
    std::vector<Triangle> faces;
    latticeSoup(seed, seed % 2 ? 2 : 4, 12, 60, lattice, pos, faces);
    std::vector<Point3d> moved(pos);
    for (auto& p : moved) p = p * 0.125 + Point3d(1e6, -3e5, 7e4);
    for (size_t i = 0; i < faces.size(); ++i) {
      const Triangle& f = faces[i];
      if (f[0] == f[1] || f[1] == f[2] || f[2] == f[0]) continue;
      slivers += isZero(cross(lattice[f[1]] - lattice[f[0]], lattice[f[2]] - lattice[f[0]]));
      for (size_t j = i + 1; j < faces.size(); ++j) {
        const Triangle& g = faces[j];
        if (g[0] == g[1] || g[1] == g[2] || g[2] == g[0]) continue;
        const bool expected = referenceIntersect(lattice, f, g);
        ASSERT_EQ(facesIntersect(pos, f, g), expected) << "seed " << seed << " faces " << i << ' ' << j;
        // Scaled by 1/8 and moved far from the origin (both exact here): the same answer, from
        // coordinates whose differences no longer come out exactly in the filters.
        ASSERT_EQ(facesIntersect(moved, f, g), expected) << "seed " << seed << " faces " << i << ' ' << j;
        ++tested;
        intersecting += expected;
        for (std::uint32_t x : f)
          for (std::uint32_t y : g) sharing += x == y;
      }
    }
  }
  // The soups did exercise the cases.
  EXPECT_GT(tested, 30000u);
  EXPECT_GT(intersecting, tested / 10);
  EXPECT_LT(intersecting, tested * 9 / 10);
  EXPECT_GT(slivers, 50u);
  EXPECT_GT(sharing, 3000u);
}

// --- The search against the O(n²) reference ---

namespace {

// A seeded soup of small faces (edges about 0.5) in the box [0, 6]^3, corners on the lattice of
// step 1/4 and shared by index where they coincide (so faces share corners and edges, lie in
// common planes and touch exactly), or with `jitter` moved off it by random amounts; a duplicate
// every 97 faces; some faces with a repeated vertex (where the random offsets are zero); and
// `longFaces` faces from near one corner of the box to near the opposite one.
void soup(std::uint64_t seed, size_t count, size_t longFaces, bool jitter, std::vector<Point3d>& pos,
          std::vector<Triangle>& faces) {
  growth::Random rng(seed);
  pos.clear();
  faces.clear();
  std::map<std::tuple<int, int, int>, std::uint32_t> index;
  auto vertex = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    const auto it = index.find(key);
    if (it != index.end()) return it->second;
    Point3d p(x * 0.25, y * 0.25, z * 0.25);
    if (jitter) p += Point3d(rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1), rng.uniform(-0.1, 0.1));
    pos.push_back(p);
    return index[key] = std::uint32_t(pos.size() - 1);
  };
  auto latticeCoord = [&](int lo, int hi) { return lo + int(rng.next() % std::uint64_t(hi - lo + 1)); };
  for (size_t f = 0; f < count; ++f) {
    const int x = latticeCoord(0, 24), y = latticeCoord(0, 24), z = latticeCoord(0, 24);
    Triangle t;
    t[0] = vertex(x, y, z);
    t[1] = vertex(x + latticeCoord(-2, 2), y + latticeCoord(-2, 2), z + latticeCoord(-2, 2));
    t[2] = vertex(x + latticeCoord(-2, 2), y + latticeCoord(-2, 2), z + latticeCoord(-2, 2));
    faces.push_back(t);
    if (f % 97 == 0) faces.push_back({t[2], t[1], t[0]}); // a duplicate
  }
  // More than 4.5 long along every axis.
  for (size_t f = 0; f < longFaces; ++f)
    faces.push_back({vertex(latticeCoord(0, 3), latticeCoord(0, 3), latticeCoord(0, 3)),
                     vertex(latticeCoord(21, 24), latticeCoord(21, 24), latticeCoord(21, 24)),
                     vertex(latticeCoord(0, 24), latticeCoord(0, 24), latticeCoord(0, 24))});
}

void expectSameAsBruteForce(const std::vector<Point3d>& pos, const std::vector<Triangle>& faces,
                            const std::vector<char>* alive, size_t minPairs) {
  const Pairs reference = bruteForce(pos, faces, alive);
  const Pairs one = findSelfIntersections(pos, faces, alive, 1);
  EXPECT_EQ(one, reference);
  EXPECT_EQ(findSelfIntersections(pos, faces, alive, 2), one);
  EXPECT_EQ(findSelfIntersections(pos, faces, alive, 0), one);
  EXPECT_GE(reference.size(), minPairs);
}

} // namespace

TEST(SelfIntersections, RandomSoupsMatchTheBruteForce) {
  std::vector<Point3d> pos;
  std::vector<Triangle> faces;
  for (std::uint64_t seed : {1, 2, 3}) {
    // On the lattice: touching, coplanar and collinear contacts everywhere.
    soup(seed, 1200, 0, false, pos, faces);
    expectSameAsBruteForce(pos, faces, nullptr, 150);
    // Off the lattice.
    soup(seed + 10, 1200, 0, true, pos, faces);
    expectSameAsBruteForce(pos, faces, nullptr, 150);
  }
  // With dead faces.
  soup(4, 1200, 0, false, pos, faces);
  std::vector<char> alive(faces.size(), 1);
  for (size_t f = 0; f < faces.size(); f += 3) alive[f] = 0;
  expectSameAsBruteForce(pos, faces, &alive, 100);
}

TEST(SelfIntersections, LongFacesMatchTheBruteForce) {
  std::vector<Point3d> pos;
  std::vector<Triangle> faces;
  // A few long faces: tested against every box.
  soup(5, 1200, 5, true, pos, faces);
  expectSameAsBruteForce(pos, faces, nullptr, 300);
  // More long faces than are tested that way: the cells grow.
  soup(6, 1000, 100, true, pos, faces);
  expectSameAsBruteForce(pos, faces, nullptr, 1000);
  // All faces long.
  soup(7, 0, 200, false, pos, faces);
  expectSameAsBruteForce(pos, faces, nullptr, 1000);
}

// --- A closed surface ---

TEST(SelfIntersections, ClosedSphereHasNoPairUntilAVertexIsPushedThrough) {
  std::vector<Point3d> pos;
  std::vector<Triangle> faces;
  icosphere(5, pos, faces); // 20480 faces
  ASSERT_EQ(faces.size(), 20480u);
  EXPECT_TRUE(findSelfIntersections(pos, faces).empty());

  // Vertex 0 (an icosahedron corner, in 5 faces) pushed through the centre to 1.5 beyond the far
  // side: its 5 faces now cross the far side.
  std::vector<std::uint32_t> fan;
  for (std::uint32_t f = 0; f < faces.size(); ++f)
    if (std::find(faces[f].begin(), faces[f].end(), 0u) != faces[f].end()) fan.push_back(f);
  ASSERT_EQ(fan.size(), 5u);
  pos[0] = pos[0] * -1.5;
  const Pairs pairs = findSelfIntersections(pos, faces);
  EXPECT_GT(pairs.size(), 5u);
  for (const auto& p : pairs) // every pair has a fan face in it
    EXPECT_TRUE(std::binary_search(fan.begin(), fan.end(), p.first) || std::binary_search(fan.begin(), fan.end(), p.second));

  std::vector<char> alive(faces.size(), 1);
  EXPECT_EQ(removeSelfIntersections(pos, faces, alive), 5u); // exactly the fan
  for (std::uint32_t f : fan) EXPECT_EQ(alive[f], 0);
  EXPECT_TRUE(findSelfIntersections(pos, faces, &alive).empty());
  EXPECT_EQ(removeSelfIntersections(pos, faces, alive), 0u);
  // The removal left a hole, no non-manifold vertex.
  EXPECT_EQ(growth::countNonManifoldVertices(faces, pos.size(), alive), 0u);
}

TEST(SelfIntersections, SmallSphereWithAPushedVertexMatchesTheBruteForce) {
  std::vector<Point3d> pos;
  std::vector<Triangle> faces;
  icosphere(3, pos, faces); // 1280 faces
  expectSameAsBruteForce(pos, faces, nullptr, 0);
  EXPECT_TRUE(bruteForce(pos, faces).empty());
  pos[7] = pos[7] * -1.2;
  expectSameAsBruteForce(pos, faces, nullptr, 5);
}

TEST(SelfIntersections, RemovalCanLeaveANonManifoldVertex) {
  // A flat hexagonal fan around vertex 0; faces 0 and 3 (opposite) are each pierced by two small
  // vertical triangles. Removing the two fan faces (in two pairs each) clears every pair but
  // splits the fan into two: vertex 0 is non-manifold until removeNonManifoldVertices runs.
  std::vector<Point3d> pos{{0, 0, 0}};
  for (int i = 0; i < 6; ++i) pos.emplace_back(std::cos(M_PI / 3 * i), std::sin(M_PI / 3 * i), 0);
  std::vector<Triangle> faces;
  for (std::uint32_t i = 0; i < 6; ++i) faces.push_back({0, 1 + i, 1 + (i + 1) % 6});
  for (std::uint32_t f : {0u, 3u}) {
    const Point3d centre = (pos[faces[f][0]] + pos[faces[f][1]] + pos[faces[f][2]]) / 3.0;
    for (double dx : {-0.05, 0.05}) {
      const std::uint32_t b = std::uint32_t(pos.size());
      pos.insert(pos.end(), {centre + Point3d(dx, 0, -0.1), centre + Point3d(dx, 0, 0.1), centre + Point3d(dx, 0.03, 0)});
      faces.push_back({b, b + 1, b + 2});
    }
  }
  EXPECT_EQ(findSelfIntersections(pos, faces), (Pairs{{0, 6}, {0, 7}, {3, 8}, {3, 9}}));
  std::vector<char> alive(faces.size(), 1);
  EXPECT_EQ(removeSelfIntersections(pos, faces, alive), 2u);
  EXPECT_EQ(alive[0], 0);
  EXPECT_EQ(alive[3], 0);
  EXPECT_TRUE(findSelfIntersections(pos, faces, &alive).empty());
  EXPECT_EQ(growth::countNonManifoldVertices(faces, pos.size(), alive), 1u);
  const growth::ManifoldCleanupStat st = growth::removeNonManifoldVertices(faces, pos.size(), alive);
  EXPECT_EQ(st.facesRemoved, 2u);
  EXPECT_EQ(growth::countNonManifoldVertices(faces, pos.size(), alive), 0u);
}

TEST(SelfIntersections, GreedyRemovalTakesTheFaceInMostPairsAndTheLowestIndexOnTies) {
  // Face 0 crosses faces 1, 2 and 3 (three disjoint small triangles stacked along its plane's
  // normal... here: three vertical triangles standing through a large horizontal one); faces 4
  // and 5 cross only each other.
  std::vector<Point3d> pos{{0, 0, 0}, {10, 0, 0}, {0, 10, 0}};
  std::vector<Triangle> faces{{0, 1, 2}};
  for (double x : {1.0, 2.0, 3.0}) {
    const std::uint32_t b = std::uint32_t(pos.size());
    pos.insert(pos.end(), {{x, 1, -1}, {x, 1, 1}, {x, 2, 0}});
    faces.push_back({b, b + 1, b + 2});
  }
  const std::uint32_t b = std::uint32_t(pos.size());
  pos.insert(pos.end(), {{20, 0, 0}, {22, 0, 0}, {20, 2, 0}, {20.5, 0.5, -1}, {20.5, 0.5, 1}, {22, 2, 0}});
  faces.push_back({b, b + 1, b + 2});
  faces.push_back({b + 3, b + 4, b + 5});
  EXPECT_EQ(findSelfIntersections(pos, faces), (Pairs{{0, 1}, {0, 2}, {0, 3}, {4, 5}}));
  std::vector<char> alive(faces.size(), 1);
  EXPECT_EQ(removeSelfIntersections(pos, faces, alive), 2u);
  EXPECT_EQ(alive, (std::vector<char>{0, 1, 1, 1, 0, 1}));
}
