#pragma once
#include <algorithm>
// The graph G of the sphere packer and the borders of its regions (Lipschütz et al., sec. 3.1,
// 3.4, 3.5, 4.2, figures 3 and 6).
//
// G is stored as a rotation system: around every vertex its edges are kept in counter-clockwise
// order, measured in the plane orthogonal to the vertex normal (the box normal, sec. 4.1). The
// borders of the regions are then the face cycles of this embedding, as oriented half-edge cycles:
//     next(u→v) = v→w, w the neighbour of v just clockwise of u,
// which walks every region with the region on its left (counter-clockwise seen from the normals).
// Degenerate borders come out naturally (fig. 6): a lone vertex is a border of length 0 (no
// half-edge), a single edge a–b the cycle a→b→a of length 2, a path x–v–y the cycle of length 4
// going back and forth.
//
// A corner of a vertex v is an angular gap between two consecutive edges; it belongs to exactly
// one border and is named by its outgoing half-edge (v, k): the gap from neighbour k
// counter-clockwise to neighbour k+1. A new edge v→c enters the corner whose gap contains the
// projected direction of c (sec. 3.5: "the candidate edge is projected to the plane defined by the
// parent vertex and its normal").
//
// Inserting a vertex c with edges to a and b (sec. 3.4, fig. 3) splits one border into two when
// the corners at a and b lie on the same border, and joins two borders into one otherwise; in the
// rotation system both happen by inserting c into the two rotations. Sec. 4.2 bounds the walk that
// tells the two cases apart by the window w: borderDistance() looks at most w steps each way.
#include <growth/vec3.h>

#include <cstdint>
#include <vector>

namespace growth {

struct HalfEdge {
  std::uint32_t v = 0;  // origin
  int slot = 0;         // index of the target in v's rotation
  bool operator==(const HalfEdge& o) const { return v == o.v && slot == o.slot; }
  bool operator!=(const HalfEdge& o) const { return !(*this == o); }
};

class BorderGraph {
public:
  // All edges of G have length d and vertices are at least d apart, so at most 12 neighbours fit
  // around a vertex (the kissing number in 3D).
  static constexpr int kMaxDegree = 12;

  void clear();
  // Frees the rotations and the normals, keeping the positions (vertexCount(), position() and
  // positions() stay; nothing else may be asked afterwards): the regions are triangulated, and the
  // clean-up and the output need the positions only.
  void releaseAdjacency();
  void reserve(size_t vertices);
  std::uint32_t addVertex(const Vec3d& position, const Vec3d& normal);

  size_t vertexCount() const { return pos_.size(); }
  const Vec3d& position(std::uint32_t v) const { return pos_[v]; }
  const Vec3d& normal(std::uint32_t v) const { return nrm_[v]; }
  const std::vector<Vec3d>& positions() const { return pos_; }
  const std::vector<Vec3d>& normals() const { return nrm_; }
  int degree(std::uint32_t v) const { return rot_[v].degree; }
  std::uint32_t neighbour(std::uint32_t v, int k) const { return rot_[v].nb[k]; }
  bool hasEdge(std::uint32_t u, std::uint32_t v) const { return slotOf(u, v) >= 0; }
  size_t edgeCount() const { return edges_; }

  // Angle of the direction from v to x, projected onto the plane orthogonal to normal(v), in
  // v's tangent frame, as a pseudo-angle: a monotonic function of the polar angle in [0, 4) (a
  // full turn is 4), which gives the same cyclic order without the trigonometry.
  double angleAt(std::uint32_t v, const Vec3d& x) const;

  // Corner of v whose gap contains the projected direction towards `target`: the slot k of its
  // outgoing half-edge; 0 for a vertex with one edge (one gap all around); -1 for a lone vertex.
  int gapOf(std::uint32_t v, const Vec3d& target) const;

  // Whether the corner `gap` of v (as returned by gapOf) contains the direction towards `target`
  // when the edges are projected onto the plane orthogonal to another unit normal `n` instead of
  // normal(v). True for vertices with fewer than two edges (one gap all around).
  bool gapContains(std::uint32_t v, int gap, const Vec3d& target, const Vec3d& n) const;

  std::uint32_t target(HalfEdge h) const { return rot_[h.v].nb[h.slot]; }
  HalfEdge next(HalfEdge h) const;
  HalfEdge prev(HalfEdge h) const;

  // Sec. 4.2: number of border edges from the corner (a, gapA) to the corner (b, gapB) when b's
  // corner is reached within w steps along the border, forwards or backwards (the smaller count);
  // 0 when it is not (a join, or a split too far to see, which the window treats as a join).
  // Both vertices must have at least one edge.
  int borderDistance(std::uint32_t a, int gapA, std::uint32_t b, int gapB, int w) const;

  // Adds the edges c–a and c–b for a vertex c without edges, a's edge in corner gapA and b's in
  // gapB (as returned by gapOf). False, with nothing changed, when it cannot be done (a or b full,
  // c not lone, an edge already there, a == b). This is the only change the growth makes.
  bool connect(std::uint32_t c, std::uint32_t a, int gapA, std::uint32_t b, int gapB);
  // A single edge u–v in the corners gapU of u and gapV of v (the building block of connect;
  // also gives the single-edge border of fig. 6). False, with nothing changed, when not possible.
  bool addEdge(std::uint32_t u, int gapU, std::uint32_t v, int gapV);

  // Every border with at least one half-edge, as the sequence of the origins of its half-edges
  // (region on the left), in a deterministic order. Lone vertices are borders of length 0 and are
  // counted by loneVertices().
  std::vector<std::vector<std::uint32_t>> borders() const;
  size_t loneVertices() const;
  size_t memoryBytes() const;

private:
  struct Rotation {
    std::uint32_t nb[kMaxDegree];
    std::uint8_t degree = 0;
  };
  int slotOf(std::uint32_t v, std::uint32_t u) const {
    const Rotation& r = rot_[v];
    for (int k = 0; k < r.degree; ++k)
      if (r.nb[k] == u) return k;
    return -1;
  }
  void insertAt(std::uint32_t v, int pos, std::uint32_t u);

  std::vector<Vec3d> pos_, nrm_;
  std::vector<Rotation> rot_;
  size_t edges_ = 0;
};

// Growth from feature lines (the remesher; the reconstruction with keepFeatures): splits of border
// distance 1 to this (sec. 3.5's least urgent ones) share one level and are taken in the order they
// were found. Sec. 3.5 takes the split of distance 2 before that of distance 1;
// from a straight feature line, or a front that turns by 90°, that order places the vertex that
// completes a square before the apex of a triangle, row after row, and a flat face ends as a
// square lattice (two right triangles of Q_t 0.87 per square) instead of a hexagonal one.
// Splits of larger distance, which close regions off (the seams of sec. 3.5), stay more urgent.
constexpr int kAlikeSplitDistance = 3;
// Sec. 3.5 priorities as levels of a bucket queue (sec. 4.4; level 0 most urgent):
//   0: a parent without edges; 1: a parent with one edge; 2: a join (or a split farther than the
//   window sees); 3 .. 2+w: a split, the larger the distance of the parents along the border the
//   more urgent (distance w at level 3, distance 1 at level 2+w).
// `alike` (the remesher's rule, docs/design/spherepack-remesher.md): splits of distance 1 to
// `alike` share the level of distance `alike`, so they are taken in the order they were found
// (0: sec. 3.5 as written).
struct CandidatePriority {
  static int levels(int w) { return 3 + w; }
  static int level(int degreeA, int degreeB, int borderDistance, int w, int alike = 0) {
    if (degreeA == 0 || degreeB == 0) return 0;
    if (degreeA == 1 || degreeB == 1) return 1;
    if (borderDistance <= 0 || borderDistance > w) return 2;
    if (borderDistance < alike) borderDistance = std::min(alike, w);
    return 3 + (w - borderDistance);
  }
  // The level of a candidate with parents a and b in g, given the corners of a and b it falls into.
  static int of(const BorderGraph& g, std::uint32_t a, std::uint32_t b, int gapA, int gapB, int w, int alike = 0) {
    const int da = g.degree(a), db = g.degree(b);
    if (da <= 1 || db <= 1) return level(da, db, 0, w);
    const int dist = w > 0 ? g.borderDistance(a, gapA, b, gapB, w) : 0;
    return level(da, db, dist, w, alike);
  }
  // The same for a candidate at x.
  static int of(const BorderGraph& g, std::uint32_t a, std::uint32_t b, const Vec3d& x, int w, int alike = 0) {
    const int da = g.degree(a), db = g.degree(b);
    if (da <= 1 || db <= 1) return level(da, db, 0, w);
    return of(g, a, b, g.gapOf(a, x), g.gapOf(b, x), w, alike);
  }
};

} // namespace growth
