#pragma once
// The Robust G2S mesh-growing engine (Di Angelo, Di Stefano, Giaccari, sections 3 and 4), working
// on an array of distinct points. g2s.h wraps it for a MeshLab layer; tests drive its parts here.
//
//   seeds (sec. 3.1)  →  front growth by the G2S criterion (sec. 3.2) driven by the priority
//   queue (sec. 4.1), with topological tests on the point–edge map  →  re-seeding until no valid
//   seed is left  →  non-manifold vertex elimination (sec. 4.2, growth/manifold_cleanup.h).
//
// The growth is in g2s_growth.cpp; set-up, sec. 4.2, orientation and the results in g2s_mesher.cpp;
// the passes after the growth in g2s_repair.cpp (crossing faces, holes), g2s_handles.cpp (wider
// closure, regrowth, handles) and g2s_thin.cpp (rims of thin parts).
//
// Everything is flat arrays indexed by point: the points in the spatial hash's cell order
// (MortonGrid, g2s_grid.h), the point–edge map (growth::PointEdgeMap), per-point edge statistics,
// the triangles, and a bucketed queue of free edges (growth::BucketQueue, one FIFO per priority
// index). Point indices are the grid's: order()[i] is the caller's index of point i.
#include "g2s.h"
#include "g2s_geometry.h"
#include "g2s_grid.h"

#include <growth/bucket_queue.h>
#include <growth/huge_pages.h>
#include <growth/manifold_cleanup.h>
#include "point_edge_map.h"
#include <growth/progress.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <vector>

#if defined(__GNUC__)
#define GROWTH_G2S_COLD __attribute__((cold)) // rarely taken: keeps the hot search loop's layout
#else
#define GROWTH_G2S_COLD
#endif

namespace growth {
namespace g2s {

// A free edge in the front queue: half-edge a→b of the front triangle (a, b, c) is used, b→a is
// not; p is the candidate point found for the new triangle (b, a, p) (point indices use at most
// 29 bits, see PointEdgeMap::kMaxPoints, so the top bit carries a flag).
struct FrontEdge {
  static constexpr std::uint32_t kLoop = 1u << 31; // on p: the triangle closes a loop (closesLoop)
  static constexpr std::uint32_t kDeferred = ~0u;  // as p: not searched yet (see Mesher::grow)
  std::uint32_t a, b, c, p;
};

// The outcome of the search for a free edge's reference point (sec. 3.2, steps 4.1–4.2).
struct Candidate {
  std::int64_t point = -1;  // -1: none found up to the maximum radius, the edge is a boundary edge
  int sizeLevel = 0;        // pl_d in [1, n]: the search level at which it was found
  int flatLevel = 0;        // pl_f in [1, m]: flatness class of the angle β
  double cosBeta = 1;       // cos β, β the angle between the front and the new triangle's normals
  bool single = false;      // the only point of its search region, taken without the G2S test
  bool closesLoop = false;  // closes a loop of three free edges (see findCandidate)
  bool valid() const { return point >= 0; }
  int priority(int m) const { return priorityIndex(sizeLevel, flatLevel, m); } // PI, eq. 4.1
};

class Mesher {
public:
  // Grid cells are this many mean spacings wide. The mesher's queries are balls of about 2–3
  // spacings; larger cells scan more points but probe fewer cells, and probes cost more
  // (tools/g2s_grid_bench.cpp times the grid's queries at several cell widths).
  static constexpr double kCellSpacings = 8.0;
  // Dense clumps (a scanner dwelling on a spot; not in the paper): a point with at least
  // kClumpNeighbours others within kClumpRadius spacings is a clump's core point, impossible on a
  // uniform or Poisson sampling of a surface (even a noisy one) and true of every point of a ball
  // of points far denser than the cloud. Each clump (core points joined within that radius, with
  // the points within it of a core point, as in DBSCAN) is meshed as one point: its member nearest
  // the clump's centroid (ties: the lower input index); the others are left out of the mesh.
  static constexpr std::uint32_t kClumpNeighbours = 8;
  static constexpr double kClumpRadius = 0.05;

  // `points`: distinct, finite (at least one). `spacing`: the cloud's mean nearest-neighbour
  // spacing, or <= 0 to measure it on a sample. `params` must be valid (checkParams in g2s.cpp).
  Mesher(std::vector<P3> points, const Params& params, double spacing = 0);

  // Seeds and grows until every point that could start a seed was tried (sec. 3.1, 3.2, 4.1).
  void meshAll(Progress* progress = nullptr);

  // --- The parts, exposed for the unit tests ---

  // Neighbours one point may have (PointEdgeMap::setCapacity; kMaxEntries unless set): tests
  // lower it (before meshAll) to reach the degraded case, where a full point's extra edges stay open.
  void setMaxNeighboursPerPoint(std::uint32_t n) { pem_.setCapacity(n); }

  // Sec. 3.1: from point p (which must be unused), its nearest neighbour q and a third point
  // within k·|pq| of the midpoint: the first triangle, by increasing circumradius, that is a
  // Gabriel 2-simplex and passes the cylinder test. All three points must be unused. The triangle
  // is returned oriented (see orientSeed). False when p starts no valid seed.
  bool findSeedTriangle(std::uint32_t p, std::array<std::uint32_t, 3>& tri);
  // Adds a seed triangle and queues its three edges.
  void addSeed(const std::array<std::uint32_t, 3>& tri);
  // Pops free edges until the queue is empty (sec. 3.2 step 4.3: "the procedure ends when the
  // free edges' queue is empty").
  void grow(Progress* progress = nullptr);

  // Sec. 3.2 steps 4.1–4.2 for the free edge a→b of front triangle (a, b, c), considering only
  // points that pass the topological tests now (topologyAllows). With `ears`, an edge that
  // closes a loop of three free edges takes the loop's third point (closesLoop); grow() checks
  // for an unused point inside the loop (unusedPointInside) before it closes it, and then grows
  // the edge by the ordinary search (ears off) so that the point is not skipped.
  Candidate findCandidate(std::uint32_t a, std::uint32_t b, std::uint32_t c, bool ears = true);
  // For a free edge a→b whose search found nothing, on a loop of four free edges: the point of
  // the diagonal with the better triangles (closesLoop; queued last). Invalid otherwise.
  Candidate quadClosure(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& frontNormal,
                        double frontNorm) const;
  // An unused point inside triangle (a, b, c): projecting inside it, at most the radius of the
  // triangle's smallest enclosing ball from its plane.
  bool unusedPointInside(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;

  // G2S criterion: no point other than a, b, c strictly inside the smallest ball through them.
  bool isGabriel(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  // Cylinder test (sec. 3.1, fig. 1): the points inside the infinite cylinder through the
  // triangle's circumcircle, with axis along its normal, are all on one side of its plane. The
  // cylinder is followed up to 2048 circumradii on each side (a bound on the work per seed).
  bool passesCylinderTest(std::uint32_t a, std::uint32_t b, std::uint32_t c) const;
  // Sec. 3.2 step 4.3 for the new triangle (b, a, p) on the free edge a→b of front triangle
  // (a, b, c): p is a new point; its edges to a and b, where they exist, are traversed in the
  // opposite direction by their one triangle (point–edge map); and p is not an interior vertex
  // (all of its edges already with two triangles), which would make it non-manifold; and the
  // points have room for the new edges (PointEdgeMap::hasRoom).
  bool topologyAllows(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t p) const;

  // Local regrowth (Mesher::HandlePass::regrow): triangles that are already there, added without
  // queueing their edges (false, with nothing more added, at a half-edge used twice: not a
  // consistently oriented manifold); then the free edge a→b of triangle (a, b, c) queued for
  // growth; grow stops after maxPops edges taken from the queue (growBudgetExhausted).
  bool addFixedTriangles(const std::vector<Triangle>& t) {
    for (const Triangle& x : t) {
      if (pem_.used(x[0], x[1]) || pem_.used(x[1], x[2]) || pem_.used(x[2], x[0])) return false;
      addTriangle(x[0], x[1], x[2]);
    }
    queue_.clear();
    joinedAtVertex_.clear();
    return true;
  }
  void queueFrontEdge(std::uint32_t a, std::uint32_t b, std::uint32_t c) { queueEdge(a, b, c); }
  void setGrowBudget(size_t maxPops) { popBudget_ = maxPops; }
  bool growBudgetExhausted() const { return budgetExhausted_; }

  // Sec. 4.2 on the grown triangles (updates the point–edge map); returns the counts. Only the
  // vertices where a triangle was ever joined by a vertex alone can have more than one fan, so
  // only those (and the vertices of removed triangles) are examined.
  ManifoldCleanupStat removeNonManifoldVertices();
  // --- Repairs after sec. 4.2 (g2s_repair.cpp; not in the paper). Both need the growth state
  // (call them before releaseGrowthState) and the cleanup's alive() flags. ---
  struct SelfIntersectionStat {
    size_t facesRemoved = 0;        // faces that intersected others
    size_t nonManifoldVertices = 0; // vertices with two fans after that removal (sec. 4.2 again)
    size_t fanFacesRemoved = 0;     // the faces of their extra fans
  };
  // Removes faces until no two live faces intersect (growth/self_intersections.h, exact) near the
  // boundary of the mesh and the fans sec. 4.2 removed, then the non-manifold vertices this
  // leaves. A mesh grown without a free edge left (a clean closed cloud) is not examined at all.
  SelfIntersectionStat removeSelfIntersections();
  struct HoleStat {
    size_t loops = 0;       // boundary loops of at most maxEdges edges, tried
    size_t closed = 0;      // of them, closed
    size_t facesAdded = 0;
    size_t facesReplaced = 0; // faces at a loop taken out so that it could close (one per loop, two at a spike)
    size_t spikes = 0;        // loop vertices taken out with their one or two faces (left unused)
    size_t widened = 0;       // of the loops closed, those closed wider (widenHoles)
    size_t widenedFaces = 0;  // the faces these took out (counted in facesReplaced too)
    size_t regrown = 0;       // of the widened, those grown into again (G2S on the points around them)
  };
  // Closes the boundary loops of at most maxEdges edges by ear cutting on their vertices; every
  // new triangle keeps each edge at two triangles with consistent orientation, each vertex one fan,
  // and intersects no face (exactly). A loop that cannot be closed whole is tried again with one of
  // its faces taken out (facesReplaced), then at a spike (a loop vertex with only its two loop
  // faces, sharing their third point) with that vertex and both faces out (spikes); one that cannot
  // be closed is left as it was.
  HoleStat closeHoles(int maxEdges);
  // closeHoles on the loops through `seeds` (sorted, unique), adding to st.
  void closeHolesAt(int maxEdges, const std::vector<std::uint32_t>& seeds, HoleStat& st);
  struct BoundaryCount; // (below)
  struct HandleStat {
    size_t handlesBefore = 0;       // handles of the mesh before the pass (sum over its components)
    size_t candidates = 0;          // cycles of three edges bounding no face, tried
    size_t handles = 0;             // of them, cut
    size_t facesRemoved = 0;        // faces on the cut side, and of extra fans this left (sec. 4.2)
    size_t nonManifoldVertices = 0; // points with two fans after a cut
    size_t holesClosed = 0, holeFacesAdded = 0; // the cuts' loops closed
    size_t pointsLost = 0;          // points left with no face by a cut
    size_t undone = 0;              // cuts put back (a loop did not close)
    size_t twoFans = 0;             // of them, because a point had two fans after the closure
    size_t regrown = 0;             // loops closed by a regrowth (widenHoles)
  };
  // Cuts the small handles (g2s_handles.cpp): where the mesh has a handle, each cycle of three
  // edges that bounds no face and does not separate the faces within two rings of its first point
  // loses the faces on one side, and its two loops are closed (closeHolesAt, loops of at most
  // maxHoleEdges edges); where neither side's loops close, the cut is undone. `boundary`: the
  // mesh's boundary now (boundary()). Needs the cleanup's manifold vertices and the
  // growth state (closeHoles).
  HandleStat removeSmallHandles(const BoundaryCount& boundary, int maxHoleEdges);
  // After closeHoles: each loop of at most maxHoleEdges edges it left open is tried again with
  // every face on its edges taken out, then with every face at its points (g2s_handles.cpp), the
  // wider loop closed by the hole pass's means; undone where it does not close or a point inside
  // would be left on a boundary. Adds to hs (closed, widened, faces added, faces replaced, points
  // left out as spikes); returns the loops closed.
  size_t widenHoles(int maxHoleEdges, HoleStat& hs);
  // Handles of the live mesh: the sum over its components of (2 - V + E - F - loops) / 2, given
  // its boundary (boundary()).
  size_t handleCount(const BoundaryCount& boundary) const;
  // Removes the connected pieces of fewer than minFaces live faces but the largest
  // (growth::dropSmallComponents) from the mesh and the point-edge map. Returns the pieces removed;
  // facesDropped gets their faces.
  size_t dropSmallComponents(size_t minFaces, size_t& facesDropped);

  // Orients every connected component so that closed surfaces face out of the material: a
  // component faces outwards of its own volume (positive signed volume about its centroid),
  // except a closed shell inside an odd number of other closed shells (found by the parity of a
  // ray's crossings), which bounds a cavity and faces into it (the inner wall of a hollow ball).
  // Each component was grown with one consistent orientation from its seed; flipping whole
  // components keeps every edge consistent. G2S needs no normals: nesting is all it can go by for
  // a closed shell. A piece that does not close (a sheet: a scan's open surface, a LiDAR tile's
  // ground) has no inside; where the caller gives the layer's normals (in this mesher's point
  // order, zero where a point has none), it faces the way they point on the whole (the sum over
  // its faces of the face normal against its corners' normals), else as its own volume says.
  struct OrientationStat {
    size_t components = 0;      // connected pieces of the live triangles
    size_t flipped = 0;         // of them, turned over
    size_t byNormals = 0;       // sheets oriented by the normals given (flipped or not)
    size_t cavities = 0;        // closed shells nested in an odd number of others (facing into them)
    size_t facesFlipped = 0;    // the triangles of the pieces turned over
  };
  OrientationStat orientComponents(const std::vector<P3>* normals = nullptr);

  // Frees what only the growth uses: the grid's search structure, the per-point edge counters,
  // the queue and the search scratch. No search (seeds, growth, candidates) may follow; the
  // cleanup, orientation and results may. build() calls it after meshAll so that the cleanup's
  // memory does not add up with the growth's.
  void releaseGrowthState();
  // Frees everything but order(), the triangles, alive() and scratch(): releaseGrowthState, the
  // points (size() and points() are then empty) and the point–edge map. Only those four results
  // may be read afterwards; build() calls it before writing the output layer (from the layer's
  // own coordinates) so that the two memory peaks do not add up.
  void releaseWorkingState();

  // Moves the live triangles out, in order (alive() and triangles() are then empty): for the
  // output step, which consumes them.
  std::vector<Triangle> takeLiveTriangles();
  // Frees order() (once the output vertices are written).
  void releaseOrder() { grid_.setOrder(std::vector<std::uint32_t>()); }

  // --- Results ---
  size_t size() const { return grid_.size(); }
  const std::vector<P3>& points() const { return grid_.points(); }
  const std::vector<std::uint32_t>& order() const { return grid_.order(); }
  const std::vector<Triangle>& triangles() const { return tri_; }
  const std::vector<char>& alive() const { return alive_; }
  const PointEdgeMap& edges() const { return pem_; }
  size_t seeds() const { return seeds_; }
  size_t seedAttempts() const { return seedAttempts_; }
  size_t cylinderQueries() const { return cylinderQueries_; } // ball queries of the cylinder tests
  // Front edges left open because a candidate had no room for another edge at one of its points
  // (PointEdgeMap::kMaxEntries): the local degradation that replaces a failure.
  size_t edgesLeftAtFullPoints() const { return edgesLeftAtFullPoints_; }
  // Thin parts (g2s_growth.cpp, kSheetGap): candidates refused as folds across a part, and G2S
  // balls found empty but for points of another sheet.
  size_t foldsRefused() const { return foldsRefused_; }
  size_t otherSheetBalls() const { return otherSheetBalls_; }
  // Loops at the rims of thin parts closed after the growth (closeRimLoops, g2s_thin.cpp).
  size_t rimLoopsClosed() const { return rimLoopsClosed_; }
  // That pass's faces taken out and added, and its time (zero where no thin-part rule acted).
  size_t rimPassFacesRemoved() const { return rimFacesRemoved_; }
  size_t rimPassFacesAdded() const { return rimFacesAdded_; }
  double rimPassSeconds() const { return rimSeconds_; }
  size_t liveTriangles() const;
  size_t boundaryEdges() const;   // edges with one live triangle
  size_t boundaryLoops();         // holes: loops of boundary edges
  // Both at once, in one pass over the point-edge map.
  struct BoundaryCount {
    size_t edges = 0, loops = 0;
  };
  BoundaryCount boundary();
  size_t memoryBytes() const;
  double spacing() const { return spacing_; }
  // Dense clumps merged at construction (see kClumpNeighbours) and the points they left out: the
  // mesher's points are the others (order() maps them to the caller's indices).
  size_t clumps() const { return clumps_; }
  size_t clumpPointsMerged() const { return clumpPointsMerged_; }
  // Points the index scanned for the queries since construction: a deterministic measure of the
  // search work (growth::PointIndex::setVisitCounter).
  std::uint64_t pointsVisited() const { return visited_; }
  std::uint64_t candidateSearches() const { return searches_; }
  // One word per point that callers may use once the mesh is final (saves an allocation).
  std::vector<std::uint32_t>& scratch() { return scratch_; }

private:
  // The first boundary half-edge v→w (used, w→v unused) leaving v that is not marked in the
  // point-edge map, into w; false when there is none (the walk along a boundary loop).
  bool nextBoundaryHalfEdge(std::uint32_t v, std::uint32_t& w) const {
    bool found = false;
    pem_.forEachEdge(v, [&](std::uint32_t x, bool out, bool in) {
      if (!found && out && !in && !pem_.marked(v, x)) {
        w = x;
        found = true;
      }
    });
    return found;
  }
  // Walks a boundary from the boundary half-edge v→w on (nextBoundaryHalfEdge at each point),
  // marking each half-edge in the point-edge map and recording it in `walked` (the caller takes
  // the marks off), the points from v on into *loop when given. Returns the point where the walk
  // stopped: v again where the boundary is manifold. (boundary(), the hole pass, the rim pass.)
  std::uint32_t walkBoundary(std::uint32_t v, std::uint32_t w,
                             std::vector<std::pair<std::uint32_t, std::uint32_t>>& walked,
                             std::vector<std::uint32_t>* loop) {
    std::uint32_t cur = v;
    do {
      pem_.setMark(cur, w, true);
      walked.emplace_back(cur, w);
      if (loop != nullptr) loop->push_back(cur);
      cur = w;
    } while (nextBoundaryHalfEdge(cur, w));
    return cur;
  }
  struct Scored {
    int flatLevel;     // pl_f
    double radius2;    // squared circumradius of the candidate triangle
    std::uint32_t id;
    double cosBeta;
  };

  double sampleSpacing() const;
  // g2s_repair.cpp: the vertices that can lie on a boundary after the cleanup: those with a free
  // edge at the end of the growth, and those of removed triangles. Empty on a closed mesh.
  void boundarySuspects(std::vector<std::uint32_t>& out) const;
  // The live faces at each point: at[first[v]..first[v+1]) (g2s_repair.cpp).
  void faceIndex(std::vector<std::uint32_t>& first, std::vector<std::uint32_t>& at) const;
  // closeHoles: the boundary loops of 3 to maxEdges edges through the seeds (g2s_repair.cpp).
  void boundaryLoops(const std::vector<std::uint32_t>& seeds, int maxEdges,
                     std::vector<std::vector<std::uint32_t>>& loops);
  class HandlePass; // removeSmallHandles' state and steps (g2s_handles.cpp)
  class HolePass; // closeHoles' state and steps (g2s_repair.cpp)
  class CrossingPass; // removeSelfIntersections' state and steps (g2s_repair.cpp)
  // Finds the dense clumps and rebuilds the grid without all but one point of each (constructor).
  void mergeClumps();
  // findCandidate's search by growing spheres (sec. 3.2 steps 4.1–4.2), the ear aside.
  Candidate search(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& dir, const P3& frontNormal,
                   double frontNorm);
  // search, sec. 3.2 step 4.1: the points of a level's search sphere (centre, radius; r2 its
  // exact squared radius) other than the front triangle's, into scored_: gives their number
  // `count` less those of the previous level's sphere, with `found` (all points in it, interior
  // ones too) and seenBefore (a point of the previous sphere that was a candidate there; -1: none).
  size_t spherePoints(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& A, const P3& B, double edge2,
                      const P3& centre, double radius, double r2, const P3& previousCentre, double previousR2,
                      size_t& found, std::int64_t& seenBefore);
  // search, sec. 3.2 step 4.2: the reference point among the `count` candidates of scored_, the
  // first by circumradius that the topological and G2S tests accept (invalid: none).
  Candidate g2sPoint(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& A, const P3& B, size_t count,
                     int level, const P3& dir, const P3& frontNormal, double frontNorm, double radius, double local,
                     double gatherRadius, const P3& gatherCentre);
  // The candidate (b, a, id) found at `level` (its flatness class from the angle with the front).
  Candidate accepted(const P3& A, const P3& B, std::uint32_t id, int level, const P3& frontNormal, double frontNorm,
                     bool single) const;
  void gather(const P3& centre, double radius);     // fills near_ with the points of a ball
  // grid_.anyInBall, over near_ where the ball lies inside the gathered one.
  template <class F> bool anyInBall(const P3& c, double radius, F&& stop) const;
  // Thin parts (see kSheetGap in g2s_growth.cpp). The G2S ball of candidate (b, a, p) holds no
  // point but points far off its plane, of another sheet (a flat candidate only).
  // local: the mean edge length at a and b.
  // inside: a point found inside the ball by emptyBall. gatherRadius, gatherCentre: the ball
  // gathered into near_ (its points are used where it holds the G2S ball).
  GROWTH_G2S_COLD bool emptyButOtherSheet(const Ball& ball, std::uint32_t a, std::uint32_t b, std::uint32_t p,
                                          std::uint32_t inside, const P3& frontNormal, double frontNorm, double local,
                                          double gatherRadius, const P3& gatherCentre);
  // Candidate (b, a, p), far behind the front triangle (a, b, c), folds while its search sphere
  // (of radius `radius` for edge a→b, direction dir) holds a point farther ahead near the front's plane.
  GROWTH_G2S_COLD bool foldsAcrossThePart(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t p,
                                          const P3& dir, const P3& frontNormal, double frontNorm, double radius) const;
  // After a crossing ("after a crossing" at kChildGap in g2s_growth.cpp): a candidate kUnderGap or more
  // behind the front triangle marks its points, and the triangles grown on from marked points for
  // kCrossingMark generations are refused when underASheetAfterCrossing. True: refused.
  bool refusedAfterCrossing(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& frontNormal,
                            double frontNorm) {
    const std::uint8_t generation = std::max(crossing_[a], crossing_[b]);
    if (__builtin_expect((pts_[p] - pts_[a]) * frontNormal <= -kCrossingGap * spacing_ * frontNorm, 0)) {
      crossing_[a] = crossing_[b] = crossing_[p] = kCrossingMark;
      return false;
    }
    if (__builtin_expect(generation == 0, 1)) return false;
    if (underASheetAfterCrossing(a, b, p, frontNormal, frontNorm)) return true;
    if (generation > 1) crossing_[p] = std::max<std::uint8_t>(crossing_[p], std::uint8_t(generation - 1));
    return false;
  }
  // p has kGapSheetPoints other points within kGapSheetReach spacings (a point of a surface, not a
  // stray one), and point i's last triangle faces within acos(kUnderSameWayCos) of n.
  bool onASurface(std::uint32_t p) const;
  bool facesTheSameWay(std::uint32_t i, const P3& n) const;
  // The triangle (b, a, p) lies under a sheet of the mesh facing the same way, beyond an empty layer.
  GROWTH_G2S_COLD bool underASheetAfterCrossing(std::uint32_t a, std::uint32_t b, std::uint32_t p,
                                                const P3& frontNormal, double frontNorm) const;
  static constexpr double kCrossingGap = 0.5;         // = kUnderGap (g2s_growth.cpp)
  static constexpr std::uint8_t kCrossingMark = 4;    // the generations checked after a crossing
  // Candidate (b, a, p), p kUnderGap or more behind the front triangle, would lie in the material
  // under a sheet of the mesh facing the same way (see kUnderGap in g2s_growth.cpp).
  GROWTH_G2S_COLD bool growsUnderASheet(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& frontNormal,
                                        double frontNorm) const;
  // Candidate (b, a, p) folds across a gap of the front's sheet to another sheet parallel to it
  // (p at least kFoldGap behind the front triangle, on such a sheet, and the front's sheet going on
  // flat beyond p).
  GROWTH_G2S_COLD bool foldsAcrossAGap(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& dir,
                                       const P3& frontNormal, double frontNorm) const;
  // After the growth, when a thin-part rule acted: closes the boundary loops of 3 to 16 edges
  // that lie at a thin part (another sheet facing the other way 2-5 spacings off a triangle at
  // the loop) by their triangulation of least area, crossing no triangle, after taking off what
  // blocks them (sec. 4.2's extra fans, flaps, stray and folded triangles; g2s_thin.cpp).
  GROWTH_G2S_COLD void closeRimLoops();
  // closeRimLoops: takes grown triangle f out of the mesh (the last triangle moves into its slot).
  GROWTH_G2S_COLD void removeGrownTriangle(size_t f);
  class RimPass; // closeRimLoops' state over a round and its steps (g2s_thin.cpp)
  // G2S emptiness, using near_ then the grid; when not empty, lastInside_ is a point inside.
  bool emptyBall(const Ball& ball, double gatherRadius, const P3& gatherCentre, std::uint32_t a, std::uint32_t b,
                 std::uint32_t c) const;
  void addTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  void queueEdge(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // The edge's candidate into e.p (with kLoop) and its queue level; false when it has none (a
  // boundary edge).
  bool choose(FrontEdge& e, int& level);
  bool isolated(std::uint32_t v) const { return edgeCount_[v] == 0; }
  // Triangle f is live: every triangle is until the first pass sizes alive_ (the growth removes none).
  bool live(size_t f) const { return alive_.size() != tri_.size() || alive_[f] != 0; }
  // (Both loads and a bitwise and: no branch, the outcome is data-dependent.)
  bool interior(std::uint32_t v) const { return (edgeCount_[v] != 0) & (freeEdges_[v] == 0); }
  // The mean length of v's edges (0 without one). (Defined here, inline: the searches ask it
  // for both points of every edge.)
  double localSpacing(std::uint32_t v) const {
    return edgeCount_[v] > 0 ? double(edgeLengthSum_[v]) / double(edgeCount_[v]) : 0.0;
  }
  int flatnessLevelOfCos(double cosBeta) const {
    // pl_f = 1 + the number of class limits kπ/m (k = 1..m−1) that β reaches; cos is decreasing.
    int level = 1;
    for (double limit : cosLimit_) {
      if (cosBeta > limit) break; // most candidates are flat: one comparison
      ++level;
    }
    return level;
  }
  void orientSeed(std::array<std::uint32_t, 3>& tri) const;
  bool triangleAt(std::uint32_t v, std::array<std::uint32_t, 3>& tri) const;
  // orientComponents, step 1: parent[v], v's root (the smallest vertex of its component over the
  // live triangles; v itself for a vertex on none).
  void unionComponents(std::vector<std::uint32_t>& parent) const;
  // orientComponents, step 2: numbers the components (into their roots' entries of parent) and
  // gives their number, with each one's signed volume about its corners' centroid.
  size_t componentVolumes(std::vector<std::uint32_t>& parent, std::vector<double>& volume) const;
  // orientComponents: sets wanted[k] to -1 for each closed component nested inside an odd number
  // of other closed components (component(v): v's component number, of `components`).
  template <class ComponentOf>
  void nestedShellSigns(const ComponentOf& component, size_t components, std::vector<signed char>& wanted) const;

  Params params_;
  bool thin_ = true; // params_.thinPartRules
  double spacing_ = 0;
  double seedMaxEdge_ = 0;
  size_t clumps_ = 0, clumpPointsMerged_ = 0;
  MortonGrid grid_;
  std::uint64_t visited_ = 0;          // grid_'s visit counter
  std::uint64_t searches_ = 0;         // choose() calls
  const P3* pts_ = nullptr;            // grid_.points().data()
  PointEdgeMap pem_;
  // Per point, during growth: the sum of the lengths of its edges, their number, and how many of
  // them have one triangle only (free edges; an interior vertex has none). Both counts are at most
  // PointEdgeMap::kMaxEntries.
  HugeVector<float> edgeLengthSum_;
  HugeVector<std::uint16_t> edgeCount_;
  HugeVector<std::uint16_t> freeEdges_;
  // Per point, during growth: the last triangle added at it (kNoFace: none yet), for triangleAt.
  static constexpr std::uint32_t kNoFace = ~std::uint32_t{0};
  HugeVector<std::uint32_t> faceAt_;
  // Per point, during growth: generations left to check after a crossing (refusedAfterCrossing).
  HugeVector<std::uint8_t> crossing_;
  static_assert(PointEdgeMap::kMaxEntries <= 65535, "edge counts are 16-bit");
  std::vector<Triangle> tri_;
  std::vector<char> alive_;
  std::vector<std::uint32_t> scratch_;        // per point: union–find in orientComponents
  std::vector<std::uint32_t> joinedAtVertex_; // vertices that got a triangle sharing no edge there
  // Triangles that closed a loop of free edges (g2s_repair.cpp), by their vertices as added: the
  // rim-loop pass (g2s_thin.cpp) moves triangles within tri_, so an index would go stale.
  std::vector<Triangle> loopFaces_;
  BucketQueue<FrontEdge, HugeAllocator<FrontEdge>> queue_;
  size_t usedPoints_ = 0;
  size_t foldedEars_ = 0; // loop-closing triangles folded back over their front triangle (grow)
  size_t popBudget_ = ~size_t{0}; // grow's edges left to take from the queue (setGrowBudget)
  bool budgetExhausted_ = false;
  size_t grownTriangles_ = 0; // triangles at the end of meshAll (the repairs add after them)
  // The hole pass's state, made by the first closeHoles and kept for the wider closures and the
  // handle pass (its face index is built once); and the handle pass's. Freed by releaseGrowthState.
  struct PassDeleter { // (defined in g2s_handles.cpp, where both passes are complete types)
    void operator()(HolePass* p) const;
    void operator()(HandlePass* p) const;
  };
  std::unique_ptr<HolePass, PassDeleter> holePass_;
  std::unique_ptr<HandlePass, PassDeleter> handlePass_;
  size_t seeds_ = 0, seedAttempts_ = 0;
  mutable size_t cylinderQueries_ = 0;
  size_t edgesLeftAtFullPoints_ = 0;
  size_t foldsRefused_ = 0, otherSheetBalls_ = 0, rimLoopsClosed_ = 0;
  size_t rimFacesRemoved_ = 0, rimFacesAdded_ = 0;
  double rimSeconds_ = 0;
  ManifoldCleanupStat thinCleanup_; // sec. 4.2 done early by closeRimLoops
  mutable std::vector<std::uint32_t> foldHits_; // scratch of foldsAcrossThePart
  mutable std::uint32_t lastInside_ = 0;        // see emptyBall
  bool nearFullPoint_ = false;       // some point has fewer than 2 free entries (PointEdgeMap::hasRoom)
  mutable bool roomRefused_ = false; // a candidate passed the topology tests but a point was full
  std::vector<double> cosLimit_;       // cos(kπ/m), k = 1..m−1: flatness class limits (sec. 4.1)
  NearList near_;                      // scratch: points of the last gathered ball
  P3 nearCentre_{0, 0, 0};             // and that ball
  double nearRadius_ = -1;
  mutable HugeVector<std::uint8_t> onSurface_; // onASurface per point: 0 not asked yet, 1 yes, 2 no
  std::vector<Scored> scored_;         // scratch: candidates being ranked
};

} // namespace g2s
} // namespace growth
