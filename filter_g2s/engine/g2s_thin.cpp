// Robust G2S: the holes left at the rims of thin closed parts (Mesher::closeRimLoops; not in the
// paper, docs/design/g2s-thin-parts.md). In a file of its own, like g2s_clumps.cpp: it runs once, after the
// growth and only when a thin-part rule of g2s_growth.cpp acted, and keeps out of the growth's
// inlined queries.
//
// Why the rims stay open: a rim of a plate 3 spacings thick is two 90-degree edges 3 spacings
// apart, where the growth leaves loops of 4-10 edges, edges 1-6 spacings long, wrapping round the
// corner of the material. A boundary edge there finds no candidate because the G2S ball of a
// triangle cutting across the corner holds the corner's vertices, or because its search sphere
// (ahead of the edge in the front triangle's plane, out of the material) holds no loop vertex, or
// because the topological tests refuse the loop's vertex (already joined to the edge's end); the
// ear and four-edge closures only close loops of three and four edges. The loops are also tangled with the growth's other leftovers there: triangles
// hanging off a rim by a vertex (non-manifold, taken off by sec. 4.2 later, which opens a hole),
// flaps (a triangle on two consecutive loop edges) and triangles folded over the hole.
//
// So, at a thin part only (kThinFrom), a loop of at most kMaxRimLoopEdges edges is closed, as the
// ear and four-edge closures close theirs, by its triangulation of least area, after taking off
// what blocks it: sec. 4.2's extra fans first, then flaps, stray triangles and up to kMaxUnfolds
// folded triangles; each closure triangle checked like a loop's (no unused point inside, no
// existing edge twice, room at its points) and not folding back on the mesh. Where the least-area
// closure crosses the mesh, the least-area one that crosses nothing; an unused point (or a lone
// seed triangle's) inside the closure is joined to the loop first.
#include "g2s_apart.h"
#include "g2s_mesher.h"

#include <growth/cloud_scale.h>
#include <growth/stopwatch.h>

#include <growth/self_intersections.h>

#include <algorithm>
#include <unordered_map>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <memory>
#include <vector>

namespace growth {
namespace g2s {

namespace {
// Loops of at most this many edges are closed (after the growth, rim loops have 4-10).
constexpr size_t kMaxRimLoopEdges = 16;
// A loop is at a thin part when, from a triangle on one of its edges or at one of its vertices,
// kThinFrom to kThinTo spacings (growth::meanSpacing) along the triangle's normal (either way) and
// within kThinSide spacings of that line, a used point's triangle faces the other way (normals
// more than 120 degrees apart, kFacingApartCos): the other sheet of a part 2-5 spacings thick.
// kThinFrom is g2s_growth.cpp's kFoldGap.
constexpr double kThinFrom = 2.0, kThinTo = 5.0, kThinSide = 2.0;
constexpr double kFacingApartCos = -0.5;
// A triangle of the closure folds by at most about 148 degrees (this cosine) against the mesh
// triangle across its loop edge: at a rim the mesh triangles themselves fold by 90-130 degrees,
// while a closure that would lie back on the mesh is not made.
constexpr double kClosureFoldCos = -0.85;
// Rounds of the pass: taking triangles off (non-manifold fans, flaps, stray triangles) opens or
// changes loops that the next round closes.
constexpr int kRounds = 3;
// At most this many folded triangles are taken off a loop to close it.
constexpr int kMaxUnfolds = 2;
// At most this many free points (unused, or of a lone triangle) are joined to a loop to close it.
constexpr size_t kMaxJoins = 6;
} // namespace

// closeRimLoops' state over one round, and its steps as methods (in the order they run). The
// round's tables are as closeRimLoops kept them: the loops found, the triangles at each point as
// they were then (firstAt, trianglesAt, idAt), each triangle's index now (curOf, kGone once taken
// off) and id (idOf), and the closure triangles added since (added, addedId). Then the loop being
// closed: its closure, the free points joined to it (joins, lonePoints), the triangles being taken
// off (skipIds) and the mesh triangles near it (nearTri, nearId, box lo..hi).
class Mesher::RimPass {
public:
  explicit RimPass(Mesher& m)
      : m_(m), n(m.grid_.size()), pem_(m.pem_), grid_(m.grid_), tri_(m.tri_), pts_(m.pts_), spacing_(m.spacing_) {}
  // One round: sec. 4.2, the loops, the tables, each loop closed at a thin part; true when it
  // changed the mesh.
  bool round();

private:
  static constexpr std::uint32_t kGone = ~0u;
  // Sec. 4.2 first: takes off the extra fans of the non-manifold vertices.
  void removeNonManifoldFans();
  // The boundary loops of 3 to kMaxRimLoopEdges edges, into loops.
  void findLoops();
  // The triangle tables (firstAt, trianglesAt, idAt, curOf, idOf) of tri_ as it is now.
  void makeTables();
  // Triangle t is (a, b, c) in some rotation.
  static bool same(const Triangle& t, std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // The index in tri_ of triangle (a, b, c) (in any rotation), or tri_.size().
  size_t findTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // Takes triangle f off the mesh, keeping the tables.
  void takeOff(size_t f);
  // v has an edge carrying a triangle to a point other than x and y.
  bool hasOtherEdge(std::uint32_t v, std::uint32_t x, std::uint32_t y);
  // One loop, through the steps below: closed where it is at a thin part.
  void closeAtRim(std::vector<std::uint32_t>& loop);
  // The loop's points are distinct and its edges still open.
  bool isOpen(const std::vector<std::uint32_t>& loop);
  // The mesh triangle on the used half-edge from -> to: its third point (false: none found).
  bool thirdPoint(std::uint32_t from, std::uint32_t to, std::uint32_t& third);
  // The thin-part test: another sheet faces the other way 2-5 spacings off a triangle at the loop.
  bool atThinPart(const std::vector<std::uint32_t>& loop);
  // Takes the flaps off the loop (the loop runs across their bases instead).
  void takeOffFlaps(std::vector<std::uint32_t>& loop);
  // A loop of three: takes a stray triangle off; true when the loop is done with.
  bool strayTriangle(const std::vector<std::uint32_t>& loop);
  // Both points of edge u, v are points of lone triangles being taken.
  bool isLoneEdge(std::uint32_t u, std::uint32_t v);
  // The third point of the triangle on loop half-edge from -> to (a join, or a mesh triangle).
  bool thirdOnLoopEdge(std::uint32_t from, std::uint32_t to, std::uint32_t& x);
  // The mesh triangles that a closure triangle of loop l could cross, into nearTri, nearId, lo, hi.
  void gatherNear(const std::vector<std::uint32_t>& l);
  // The near triangles a closure triangle can cross now (not taken off, not skipped, not of a
  // lone triangle being taken, box meeting the loop's), with their boxes, into active/activeBox.
  void collectActive();
  // Triangle c crosses one of active (the cheap tests of g2s_apart.h first, then the exact one).
  bool crossesActive(const Triangle& c);
  // The least-area triangulation of loop (crossing no near triangle with `avoid`), into closure.
  bool triangulate(const std::vector<std::uint32_t>& loop, bool avoid);
  // A triangle of closure crosses another of them, or a near triangle.
  bool crossesMesh();
  // v is a point of a lone triangle (v, x, y).
  bool lonePartners(std::uint32_t v, std::uint32_t& x, std::uint32_t& y);
  // Point i is free: unused, or a point of a lone triangle, and not joined yet.
  bool freePoint(std::uint32_t i);
  // A free point inside triangle (a, b, c), or ~0u.
  std::uint32_t freeInside(std::uint32_t a, std::uint32_t b, std::uint32_t c);
  // Joins free point p to loop l.
  bool join(std::vector<std::uint32_t>& l, std::uint32_t p);
  // Closes loop l (into closure), joining free points first; false: it cannot be closed.
  bool closeLoop(std::vector<std::uint32_t>& l);
  // The unfold step: closes the loop with up to kMaxUnfolds folded triangles taken off.
  bool closeUnfolded(std::vector<std::uint32_t>& loop);
  // Commits the closure of loop: its lone triangles off, its triangles into the mesh.
  void commit(const std::vector<std::uint32_t>& loop);

  Mesher& m_;
  const size_t n;
  PointEdgeMap& pem_;
  MortonGrid& grid_;
  std::vector<Triangle>& tri_;
  const P3* const pts_;
  const double spacing_;
  bool changed = false;
  std::vector<std::vector<std::uint32_t>> loops;
  // The triangles at each point (a copy of each at each of its vertices, as they were when the
  // round's loops were found), and the closure triangles added since: a closure must cross
  // neither (growth::facesIntersect, exact), so that it adds no self-intersection. Each triangle
  // has an id (its index in tri_ when the tables were made; the closures' ids follow) and curOf
  // gives its index in tri_ now, kGone once it is taken off (removeGrownTriangle moves the last
  // triangle into the freed slot). A lookup scans the few triangles at a vertex: a scan of tri_
  // for each would cost seconds on a merged scan, with its thousands of loops.
  std::vector<std::uint32_t> firstAt;
  std::vector<Triangle> trianglesAt;
  std::vector<std::uint32_t> idAt, curOf, idOf;
  std::vector<Triangle> added;
  std::vector<std::uint32_t> addedId;
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> addedAt; // point -> indices into added
  // The loop being closed. The closure's triangles use the loop's half-edges the other way (see
  // triangulate).
  std::vector<std::array<std::uint32_t, 3>> closure;
  // Free points taken into the loop (see closeLoop): each is joined to a loop edge a -> b by the
  // triangle (b, a, p), after which the loop runs a -> p -> b. Lone triangles whose points are
  // taken are taken off when the closure is made (their edges do not count as edges).
  std::vector<std::array<std::uint32_t, 3>> joins;
  std::vector<std::uint32_t> lonePoints, skipIds;
  // The mesh triangles that a triangle of the closure could cross: those with a vertex within
  // reach of the loop (its radius about its centroid, its longest edge and two spacings), and
  // those added this round; gathered once per loop (`near`, with their ids).
  std::vector<Triangle> nearTri;
  std::vector<std::uint32_t> nearId;
  std::vector<Triangle> active;
  std::vector<std::array<double, 6>> activeBox;
  P3 lo, hi;
};

bool Mesher::RimPass::round() {
  removeNonManifoldFans(); // sec. 4.2's extra fans off
  findLoops();             // the short boundary loops
  makeTables();            // the triangles at each point, by id
  for (std::vector<std::uint32_t>& loop : loops) closeAtRim(loop);
  return changed;
}

// Sec. 4.2 first, here rather than after the growth: taking off the extra fans of a
// non-manifold vertex opens a loop, which is then closed below where it is at a thin part.
void Mesher::RimPass::removeNonManifoldFans() {
  if (m_.params_.removeNonManifoldVertices && !m_.joinedAtVertex_.empty()) {
    std::sort(m_.joinedAtVertex_.begin(), m_.joinedAtVertex_.end());
    m_.joinedAtVertex_.erase(std::unique(m_.joinedAtVertex_.begin(), m_.joinedAtVertex_.end()),
                             m_.joinedAtVertex_.end());
    std::vector<char> alive(tri_.size(), 1);
    const ManifoldCleanupStat st = growth::removeNonManifoldVertices(tri_, n, alive, &m_.joinedAtVertex_);
    // From the last: removeGrownTriangle moves the last triangle into the slot it frees.
    for (size_t f = tri_.size(); f-- > 0;)
      if (!alive[f]) m_.removeGrownTriangle(f);
    m_.thinCleanup_.nonManifoldVertices += st.nonManifoldVertices;
    m_.thinCleanup_.facesRemoved += st.facesRemoved;
    changed = st.facesRemoved > 0;
  }
}

// The boundary loops: walks along boundary half-edges (used, twin unused), as in boundary(),
// each walk marking its half-edges; loops through a vertex more than once are left alone.
void Mesher::RimPass::findLoops() {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> marked;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (m_.freeEdges_[v] == 0) continue;
    std::uint32_t w = 0;
    while (m_.nextBoundaryHalfEdge(v, w)) {
      std::vector<std::uint32_t> loop;
      m_.walkBoundary(v, w, marked, &loop);
      // A walk through a vertex twice (two fans meeting there) is split into simple loops.
      std::vector<std::uint32_t> path;
      auto keep = [&](std::vector<std::uint32_t> simple) {
        if (simple.size() >= 3 && simple.size() <= kMaxRimLoopEdges) loops.push_back(std::move(simple));
      };
      for (std::uint32_t u : loop) {
        const auto again = std::find(path.begin(), path.end(), u);
        if (again != path.end()) {
          keep(std::vector<std::uint32_t>(again, path.end()));
          path.erase(again + 1, path.end());
        } else {
          path.push_back(u);
        }
      }
      keep(std::move(path));
    }
  }
  for (const auto& e : marked) pem_.setMark(e.first, e.second, false);
}

void Mesher::RimPass::makeTables() {
  firstAt.assign(n + 1, 0);
  for (const Triangle& t : tri_)
    for (std::uint32_t v : t) ++firstAt[v + 1];
  for (size_t v = 0; v < n; ++v) firstAt[v + 1] += firstAt[v];
  trianglesAt.resize(firstAt[n]);
  idAt.resize(firstAt[n]);
  curOf.resize(tri_.size());
  idOf.resize(tri_.size());
  // The closure triangles of earlier rounds are in the tables now (and their ids were made again).
  added.clear();
  addedId.clear();
  addedAt.clear();
  {
    std::vector<std::uint32_t> next(firstAt.begin(), firstAt.end() - 1);
    for (size_t g = 0; g < tri_.size(); ++g) {
      curOf[g] = idOf[g] = static_cast<std::uint32_t>(g);
      for (std::uint32_t v : tri_[g]) {
        idAt[next[v]] = static_cast<std::uint32_t>(g);
        trianglesAt[next[v]++] = tri_[g];
      }
    }
  }
}

bool Mesher::RimPass::same(const Triangle& t, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  return (t[0] == a && t[1] == b && t[2] == c) || (t[1] == a && t[2] == b && t[0] == c) ||
         (t[2] == a && t[0] == b && t[1] == c);
}

size_t Mesher::RimPass::findTriangle(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  for (std::uint32_t f = firstAt[a]; f < firstAt[a + 1]; ++f)
    if (same(trianglesAt[f], a, b, c) && curOf[idAt[f]] != kGone) return curOf[idAt[f]];
  const auto at = addedAt.find(a);
  if (at != addedAt.end())
    for (size_t j = at->second.size(); j-- > 0;) {
      const size_t k = at->second[j];
      if (same(added[k], a, b, c) && curOf[addedId[k]] != kGone) return curOf[addedId[k]];
    }
  return tri_.size();
}

void Mesher::RimPass::takeOff(size_t f) {
  const size_t last = tri_.size() - 1;
  curOf[idOf[f]] = kGone;
  if (f != last) {
    idOf[f] = idOf[last];
    curOf[idOf[f]] = static_cast<std::uint32_t>(f);
  }
  idOf.pop_back();
  m_.removeGrownTriangle(f);
}

bool Mesher::RimPass::hasOtherEdge(std::uint32_t v, std::uint32_t x, std::uint32_t y) {
  bool other = false;
  pem_.forEachEdge(v, [&](std::uint32_t w, bool, bool) { other = other || (w != x && w != y); });
  return other;
}

void Mesher::RimPass::closeAtRim(std::vector<std::uint32_t>& loop) {
  // (The loop's own state starts empty, as when it was local to the loop.)
  closure.clear();
  joins.clear();
  lonePoints.clear();
  skipIds.clear();
  nearTri.clear();
  nearId.clear();
  if (!isOpen(loop)) return;           // distinct points, still open
  if (!atThinPart(loop)) return;       // the thin-part test
  takeOffFlaps(loop);                  // flaps off
  if (strayTriangle(loop)) return;     // a stray triangle off, or a lone triangle's loop
  bool closed = closeLoop(loop);       // the least-area closure, free points joined
  if (!closed) closed = closeUnfolded(loop); // or with folded triangles off
  if (!closed) return;
  commit(loop);                        // the closure into the mesh
}

bool Mesher::RimPass::isOpen(const std::vector<std::uint32_t>& loop) {
  const size_t loopEdges = loop.size();
  std::vector<std::uint32_t> sorted(loop);
  std::sort(sorted.begin(), sorted.end());
  if (std::adjacent_find(sorted.begin(), sorted.end()) != sorted.end()) return false;
  // Still open (an earlier closure does not touch another loop's edges, but be safe).
  bool open = true;
  for (size_t i = 0; i < loopEdges; ++i)
    open = open && pem_.used(loop[i], loop[(i + 1) % loopEdges]) && !pem_.used(loop[(i + 1) % loopEdges], loop[i]);
  return open;
}

bool Mesher::RimPass::thirdPoint(std::uint32_t from, std::uint32_t to, std::uint32_t& third) {
  bool found = false;
  pem_.forEachEdge(to, [&](std::uint32_t x, bool out, bool) {
    // (from, to, x) is a triangle when its three half-edges are used, unless all three are
    // boundary half-edges (then they can be three triangles' edges, as on a loop of three).
    if (!found && out && x != from && pem_.used(x, from) && (pem_.used(x, to) || pem_.used(from, x))) {
      third = x;
      found = true;
    }
  });
  return found;
}

// At a thin part (kThinFrom): the two sheets of a closed part face apart (or, where it was
// grown inside out, towards each other), both ways antiparallel. A smooth sheet does not
// pass: a triangle tilted by noise sees its own sheet along its normal, facing its own way; a
// triangle flipped within the sheet sees nothing that far off its plane. (Where the growth
// folded a noisy sheet or the layers of merged scans over themselves, the mesh has two
// sheets facing apart, and the loops there are closed too.)
bool Mesher::RimPass::atThinPart(const std::vector<std::uint32_t>& loop) {
  bool apart = false;
  for (size_t s = 0; s < 2 * loop.size() && !apart; ++s) {
    std::array<std::uint32_t, 3> t;
    // The triangles on the loop's edges, and the last triangle at each loop vertex.
    if (s < loop.size()) {
      const std::uint32_t a = loop[s], b = loop[(s + 1) % loop.size()];
      if (!thirdPoint(a, b, t[2])) continue;
      t[0] = a;
      t[1] = b;
    } else if (!m_.triangleAt(loop[s - loop.size()], t)) {
      continue;
    }
    const P3 centre = (pts_[t[0]] + pts_[t[1]] + pts_[t[2]]) / 3.0;
    P3 normal = (pts_[t[1]] - pts_[t[0]]) ^ (pts_[t[2]] - pts_[t[0]]);
    const double len = normal.Norm();
    if (!(len > 0)) continue;
    normal /= len;
    const double from = kThinFrom * spacing_, to = kThinTo * spacing_, side = kThinSide * spacing_;
    const double probe = std::sqrt(0.25 * (to - from) * (to - from) + side * side);
    for (double dir : {1.0, -1.0}) {
      if (apart) break;
      apart = grid_.anyInBall(centre + normal * (dir * 0.5 * (from + to)), probe, [&](std::uint32_t i, double) {
        const P3 d = pts_[i] - centre;
        const double h = d * normal;
        std::array<std::uint32_t, 3> u;
        if (std::abs(h) < from || std::abs(h) > to || (d - normal * h).SquaredNorm() > side * side) return false;
        if (m_.isolated(i) || !m_.triangleAt(i, u)) return false;
        const P3 m = (pts_[u[1]] - pts_[u[0]]) ^ (pts_[u[2]] - pts_[u[0]]);
        return m * normal < kFacingApartCos * m.Norm();
      });
    }
  }
  return apart;
}

// Flaps: a mesh triangle (a, tip, b) on two consecutive loop edges a -> tip -> b whose tip
// has other triangles (a second fan there, which the non-manifold vertex removal of sec. 4.2
// would take it off from later, leaving the loop open). It is taken off now, and the loop
// runs a -> b instead (a -> b is used by the triangle on the other side of the flap's base).
void Mesher::RimPass::takeOffFlaps(std::vector<std::uint32_t>& loop) {
  for (bool again = true; again && loop.size() > 3;) {
    again = false;
    const size_t kk = loop.size();
    for (size_t i = 0; i < kk && !again; ++i) {
      const std::uint32_t a = loop[i], tip = loop[(i + 1) % kk], b = loop[(i + 2) % kk];
      if (!pem_.used(b, a) || !pem_.used(a, b)) continue;
      if (!hasOtherEdge(tip, a, b)) continue;
      const size_t f = findTriangle(a, tip, b);
      if (f == tri_.size()) continue;
      takeOff(f);
      loop.erase(loop.begin() + std::ptrdiff_t((i + 1) % kk));
      again = changed = true;
    }
  }
}

// A stray triangle (all three edges boundary) held to the mesh by its vertices alone: taken
// off (sec. 4.2 would take it off later), which opens the loop of the mesh around it for the
// next round.
bool Mesher::RimPass::strayTriangle(const std::vector<std::uint32_t>& loop) {
  if (loop.size() == 3) {
    const size_t f = findTriangle(loop[0], loop[1], loop[2]);
    if (f < tri_.size() && hasOtherEdge(loop[0], loop[1], loop[2]) && hasOtherEdge(loop[1], loop[2], loop[0]) &&
        hasOtherEdge(loop[2], loop[0], loop[1])) {
      takeOff(f);
      changed = true;
      return true;
    }
    // A lone triangle's own loop: its closure would be the triangle again, reversed.
    if (f < tri_.size()) return true;
  }
  return false;
}

bool Mesher::RimPass::isLoneEdge(std::uint32_t u, std::uint32_t v) {
  return !lonePoints.empty() && std::find(lonePoints.begin(), lonePoints.end(), u) != lonePoints.end() &&
         std::find(lonePoints.begin(), lonePoints.end(), v) != lonePoints.end();
}

// The triangle on loop half-edge from -> to (a join, or a mesh triangle not being taken
// off): its third point. (While triangles are being taken off, by findTriangle: around a
// triangle taken off, the half-edges of its neighbours make its reverse, which thirdPoint
// would take.)
bool Mesher::RimPass::thirdOnLoopEdge(std::uint32_t from, std::uint32_t to, std::uint32_t& x) {
  for (const auto& t : joins)
    for (int e = 0; e < 3; ++e)
      if (t[e] == from && t[(e + 1) % 3] == to) {
        x = t[(e + 2) % 3];
        return true;
      }
  if (skipIds.empty()) return thirdPoint(from, to, x);
  bool found = false;
  pem_.forEachEdge(to, [&](std::uint32_t w, bool out, bool) {
    if (found || !out || w == from) return;
    const size_t f = findTriangle(from, to, w);
    if (f < tri_.size() && std::find(skipIds.begin(), skipIds.end(), idOf[f]) == skipIds.end()) {
      x = w;
      found = true;
    }
  });
  return found;
}

void Mesher::RimPass::gatherNear(const std::vector<std::uint32_t>& l) {
  nearTri.clear();
  nearId.clear();
  P3 centroid(0, 0, 0);
  for (std::uint32_t v : l) centroid += pts_[v];
  centroid /= double(l.size());
  double radius = 0, longest = 0;
  for (size_t i = 0; i < l.size(); ++i) {
    radius = std::max(radius, (pts_[l[i]] - centroid).Norm());
    longest = std::max(longest, (pts_[l[(i + 1) % l.size()]] - pts_[l[i]]).Norm());
  }
  lo = hi = pts_[l[0]];
  for (std::uint32_t v : l)
    for (int a = 0; a < 3; ++a) {
      lo[a] = std::min(lo[a], pts_[v][a]);
      hi[a] = std::max(hi[a], pts_[v][a]);
    }
  // Only triangles whose box meets the loop's: the others are skipped by both users of the list
  // (collectActive), whatever the loop's state.
  auto meetsBox = [&](const Triangle& t) {
    for (int a = 0; a < 3; ++a)
      if (std::max({pts_[t[0]][a], pts_[t[1]][a], pts_[t[2]][a]}) < lo[a] ||
          std::min({pts_[t[0]][a], pts_[t[1]][a], pts_[t[2]][a]}) > hi[a])
        return false;
    return true;
  };
  for (size_t k = 0; k < added.size(); ++k)
    if (meetsBox(added[k])) {
      nearTri.push_back(added[k]);
      nearId.push_back(addedId[k]);
    }
  grid_.forEachInBall(centroid, radius + longest + 2.0 * spacing_, [&](std::uint32_t i, double) {
    for (std::uint32_t f = firstAt[i]; f < firstAt[i + 1]; ++f)
      if (meetsBox(trianglesAt[f])) {
        nearTri.push_back(trianglesAt[f]);
        nearId.push_back(idAt[f]);
      }
  });
}

// The near triangles that count (triangles taken off, skipped ones and lone triangles being taken
// do not; only those whose box meets the loop's), with their boxes.
void Mesher::RimPass::collectActive() {
  active.clear();
  activeBox.clear();
  for (size_t n = 0; n < nearTri.size(); ++n) {
    const Triangle& t = nearTri[n];
    if (curOf[nearId[n]] == kGone ||
        (!skipIds.empty() && std::find(skipIds.begin(), skipIds.end(), nearId[n]) != skipIds.end()))
      continue;
    if (!lonePoints.empty() && isLoneEdge(t[0], t[1]) && isLoneEdge(t[1], t[2])) continue;
    std::array<double, 6> b;
    bool apartBox = false;
    for (int a = 0; a < 3; ++a) {
      b[a] = std::min({pts_[t[0]][a], pts_[t[1]][a], pts_[t[2]][a]});
      b[3 + a] = std::max({pts_[t[0]][a], pts_[t[1]][a], pts_[t[2]][a]});
      apartBox = apartBox || b[3 + a] < lo[a] || b[a] > hi[a];
    }
    if (apartBox) continue;
    active.push_back(t);
    activeBox.push_back(b);
  }
}

// Triangle c crosses one of active: a triangle whose box is apart from c's cannot meet it (the
// same answer as facesIntersect's, without the call), and the cheap sufficient tests of
// g2s_apart.h come before the exact one (they change no decision).
bool Mesher::RimPass::crossesActive(const Triangle& c) {
  double clo[3], chi[3];
  for (int a = 0; a < 3; ++a) {
    clo[a] = std::min({pts_[c[0]][a], pts_[c[1]][a], pts_[c[2]][a]});
    chi[a] = std::max({pts_[c[0]][a], pts_[c[1]][a], pts_[c[2]][a]});
  }
  const std::vector<P3>& pos = grid_.points();
  std::unique_ptr<PlaneOf> plane; // c's, made at the first face whose box meets c's
  for (size_t n = 0; n < active.size(); ++n) {
    const std::array<double, 6>& b = activeBox[n];
    if (b[3] < clo[0] || b[0] > chi[0] || b[4] < clo[1] || b[1] > chi[1] || b[5] < clo[2] || b[2] > chi[2])
      continue;
    if (!plane) plane.reset(new PlaneOf(pos, c));
    const Triangle& t = active[n];
    if (!apartByPlane(pos, *plane, c, t) && !apartByPlane(pos, t, c) && !apartInShadow(pos, *plane, c, t) &&
        facesIntersect(pos, c, t))
      return true;
  }
  return false;
}

// The closure's triangles use the loop's half-edges the other way: polygon q = the loop
// reversed, triangles (q_i, q_m, q_j) for i < m < j. Least total area (dynamic programming over
// the polygon's sub-chains), no diagonal between points that have or had an edge, and no
// triangle folding back onto the mesh triangle across its loop edge; with `avoid`, no
// triangle crossing a mesh triangle near the loop either (see crossesMesh).
bool Mesher::RimPass::triangulate(const std::vector<std::uint32_t>& loop, bool avoid) {
  const double inf = std::numeric_limits<double>::infinity();
  const size_t k = loop.size();
  const std::vector<std::uint32_t> q(loop.rbegin(), loop.rend());
  // Nothing changes while the programme runs, so what its cost asks of the mesh is looked up
  // once: the third point of the triangle on each loop edge q_a -> q_(a+1) (a = k - 1: to
  // q_0), and the near triangles that count (collectActive), with their boxes.
  std::vector<std::uint32_t> third(k, 0);
  std::vector<char> hasThird(k, 0);
  for (size_t a = 0; a < k; ++a)
    hasThird[a] = thirdOnLoopEdge(q[(a + 1) % k], q[a], third[a]) ? 1 : 0;
  if (avoid) collectActive();
  auto cost = [&](size_t i, size_t m, size_t j) {
    const P3 &A = pts_[q[i]], &B = pts_[q[m]], &C = pts_[q[j]];
    const P3 nt = (B - A) ^ (C - A);
    const double len = nt.Norm();
    if (!(len > 0)) return inf;
    // Loop edges of this triangle: (i, m) when m = i + 1, (m, j) when j = m + 1, (j, i) when
    // i = 0 and j = k - 1; each is q_a -> q_b here, used as q_b -> q_a by the mesh.
    const std::pair<size_t, size_t> edges[3] = {{i, m}, {m, j}, {j, i}};
    for (const auto& e : edges) {
      const std::uint32_t u = q[e.first], v = q[e.second];
      const bool loopEdge = (e.second == e.first + 1) || (e.first == k - 1 && e.second == 0);
      if (!loopEdge) {
        if (pem_.hasEntry(u, v) && !isLoneEdge(u, v)) return inf;
        continue;
      }
      if (hasThird[e.first]) {
        const std::uint32_t x = third[e.first];
        const P3 meshNormal = (pts_[u] - pts_[v]) ^ (pts_[x] - pts_[v]);
        const double ml = meshNormal.Norm();
        if (ml > 0 && (meshNormal * nt) < kClosureFoldCos * ml * len) return inf;
      }
    }
    return 0.5 * len;
  };
  std::vector<double> best(k * k, 0.0);
  std::vector<size_t> split(k * k, 0);
  // The triangles (i, m, j) of the closure that `split` gives, from the whole chain down.
  auto forEachTriangle = [&](auto&& f) {
    std::vector<std::pair<size_t, size_t>> stack{{0, k - 1}};
    while (!stack.empty()) {
      const size_t i = stack.back().first, j = stack.back().second;
      stack.pop_back();
      if (j < i + 2) continue;
      const size_t m = split[i * k + j];
      f(i, m, j);
      stack.emplace_back(i, m);
      stack.emplace_back(m, j);
    }
  };
  // For each sub-chain (i, j): the split m of least total cost, the first such m on ties. With
  // `avoid`, a triangle that crosses the mesh costs infinity. That test is the expensive part, so
  // it is made lazily: the programme runs over the triangles not known to cross, the triangles of
  // its result are tested, and those that cross are ruled out for the next run, until a result
  // crosses nothing (or there is none). Every triangle that result uses is tested, and ruling out
  // only lowers no cost, so it is the least-cost closure that crosses nothing, and by the same
  // rule on ties (the first m) the same closure as testing every split.
  std::vector<signed char> crossing(avoid ? k * k * k : 0, -1); // (i, m, j): -1 not tested, 0 no, 1 yes
  auto crosses = [&](size_t i, size_t m, size_t j) { return avoid && crossing[(i * k + m) * k + j] == 1; };
  std::vector<double> costOf(k * k * k, std::numeric_limits<double>::quiet_NaN()); // cost(i, m, j), once each
  for (;;) {
    for (size_t span = 2; span < k; ++span)
      for (size_t i = 0; i + span < k; ++i) {
        const size_t j = i + span;
        double b = inf;
        for (size_t m = i + 1; m < j; ++m) {
          if (!(best[i * k + m] < inf) || !(best[m * k + j] < inf) || crosses(i, m, j)) continue;
          double& t = costOf[(i * k + m) * k + j];
          if (std::isnan(t)) t = cost(i, m, j);
          const double c = best[i * k + m] + best[m * k + j] + t;
          if (c < b) {
            b = c;
            split[i * k + j] = m;
          }
        }
        best[i * k + j] = b;
      }
    if (!avoid || !(best[k - 1] < inf)) break;
    bool ruledOut = false;
    forEachTriangle([&](size_t i, size_t m, size_t j) {
      signed char& x = crossing[(i * k + m) * k + j];
      if (x < 0) x = crossesActive(Triangle{q[i], q[m], q[j]}) ? 1 : 0;
      ruledOut = ruledOut || x == 1;
    });
    if (!ruledOut) break;
  }
  closure.clear();
  if (!(best[k - 1] < inf)) return false;
  forEachTriangle([&](size_t i, size_t m, size_t j) { closure.push_back({q[i], q[m], q[j]}); });
  closure.insert(closure.end(), joins.begin(), joins.end());
  return true;
}

bool Mesher::RimPass::crossesMesh() {
  for (size_t i = 0; i < closure.size(); ++i)
    for (size_t j = i + 1; j < closure.size(); ++j)
      if (facesIntersect(grid_.points(), Triangle{closure[i][0], closure[i][1], closure[i][2]},
                         Triangle{closure[j][0], closure[j][1], closure[j][2]}))
        return true;
  collectActive();
  for (const auto& c : closure)
    if (crossesActive(Triangle{c[0], c[1], c[2]})) return true;
  return false;
}

// A free point: unused, or a point of a lone triangle (a triangle whose points have no other
// edge: a seed that grew nothing, see above).
bool Mesher::RimPass::lonePartners(std::uint32_t v, std::uint32_t& x, std::uint32_t& y) {
  // (x, y: the triangle is (v, x, y), v -> x its half-edge leaving v.)
  int count = 0, outs = 0;
  pem_.forEachEdge(v, [&](std::uint32_t w, bool out, bool) {
    ++count;
    outs += out;
    (out ? x : y) = w;
  });
  return count == 2 && outs == 1 && !hasOtherEdge(x, v, y) && !hasOtherEdge(y, v, x) &&
         findTriangle(v, x, y) < tri_.size();
}

bool Mesher::RimPass::freePoint(std::uint32_t i) {
  std::uint32_t x, y;
  for (const auto& t : joins)
    if (t[2] == i) return false;
  return m_.isolated(i) || lonePartners(i, x, y);
}

// A free point inside triangle (a, b, c) (as in unusedPointInside: projecting inside it, at
// most the radius of its smallest enclosing ball from its plane), or ~0u.
std::uint32_t Mesher::RimPass::freeInside(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const P3 &A = pts_[a], &B = pts_[b], &C = pts_[c];
  const P3 n = (B - A) ^ (C - A);
  const double n2 = n.SquaredNorm();
  std::uint32_t found = ~0u;
  if (!(n2 > 0)) return found;
  Ball ball;
  if (!smallestEnclosingBall(A, B, C, ball)) return found;
  const P3& centre = ball.centre;
  const double r2 = ball.radius2;
  grid_.anyInBall(centre, std::sqrt(2.0 * r2), [&](std::uint32_t i, double) {
    // (The geometric tests first: most points of the ball are used, and freePoint asks the
    // point-edge map; the same point is found.)
    if (i == a || i == b || i == c) return false;
    const P3& X = pts_[i];
    const double h = (X - A) * n;
    if (h * h > r2 * n2) return false;
    if (((B - A) ^ (X - A)) * n > 0 && ((C - B) ^ (X - B)) * n > 0 && ((A - C) ^ (X - C)) * n > 0 &&
        freePoint(i)) {
      found = i;
      return true;
    }
    return false;
  });
  return found;
}

// Joins free point p to the loop edge a -> b whose triangle (b, a, p) has the smallest
// circumradius among those that do not fold back onto the triangle on a -> b.
bool Mesher::RimPass::join(std::vector<std::uint32_t>& l, std::uint32_t p) {
  const double inf = std::numeric_limits<double>::infinity();
  size_t at = l.size();
  double bestR2 = inf;
  for (size_t i = 0; i < l.size(); ++i) {
    const std::uint32_t a = l[i], b = l[(i + 1) % l.size()];
    std::uint32_t x;
    const P3 nt = (pts_[a] - pts_[b]) ^ (pts_[p] - pts_[b]);
    const double len = nt.Norm();
    if (!(len > 0)) continue;
    if (thirdOnLoopEdge(a, b, x)) {
      const P3 meshNormal = (pts_[b] - pts_[a]) ^ (pts_[x] - pts_[a]);
      const double ml = meshNormal.Norm();
      if (ml > 0 && (meshNormal * nt) < kClosureFoldCos * ml * len) continue;
    }
    Ball ball;
    if (!circumBall(pts_[b], pts_[a], pts_[p], ball) || !(ball.radius2 < bestR2)) continue;
    bestR2 = ball.radius2;
    at = i;
  }
  if (at == l.size()) return false;
  joins.push_back({l[(at + 1) % l.size()], l[at], p});
  l.insert(l.begin() + std::ptrdiff_t(at + 1), p);
  return true;
}

// Closes loop l: its least-area triangulation, then (when that crosses the mesh or itself)
// the least-area one among those whose triangles cross no mesh triangle; a free point inside
// a triangle of the closure is joined to the loop first (at most kMaxJoins, with the other
// points of its lone triangle), as the growth grows an edge to an unused point inside a loop.
bool Mesher::RimPass::closeLoop(std::vector<std::uint32_t>& l) {
  const std::vector<std::uint32_t> original(l);
  gatherNear(original); // (the same for both tries: nothing in the mesh changes between them)
  for (bool avoid : {false, true}) {
    l = original;
    joins.clear();
    lonePoints.clear();
    for (;;) {
      if (!triangulate(l, avoid)) break;
      std::uint32_t p = ~0u;
      for (size_t t = 0; t < closure.size() && p == ~0u; ++t) p = freeInside(closure[t][0], closure[t][1], closure[t][2]);
      if (p == ~0u) {
        if (!crossesMesh()) return true;
        break;
      }
      if (joins.size() >= kMaxJoins) break;
      std::uint32_t x, y;
      if (!m_.isolated(p) && lonePartners(p, x, y)) {
        if (joins.size() + 3 > kMaxJoins) break;
        lonePoints.insert(lonePoints.end(), {p, x, y});
        if (!join(l, p) || !join(l, x) || !join(l, y)) break;
      } else if (!join(l, p)) {
        break;
      }
    }
  }
  l = original;
  joins.clear();
  lonePoints.clear();
  return false;
}

// Folded mesh: where the mesh triangle (a, b, x) on loop edge a -> b lies folded over the
// hole, facing with the loop's Newell normal (cosine above -kClosureFoldCos; the mesh around
// a hole faces against it, a hole's boundary running clockwise seen from outside), no
// closure can join it. Up to kMaxUnfolds such triangles, the one facing most with it first,
// are taken off when the loop then runs a -> x -> b and closes.
bool Mesher::RimPass::closeUnfolded(std::vector<std::uint32_t>& loop) {
  bool closed = false;
  std::vector<std::uint32_t> unfolded(loop);
  std::vector<std::array<std::uint32_t, 3>> off;
  for (int unfold = 0; !closed && unfold < kMaxUnfolds; ++unfold) {
    const size_t kk = unfolded.size();
    P3 newell(0, 0, 0);
    for (size_t i = 0; i < kk; ++i) newell += pts_[unfolded[i]] ^ pts_[unfolded[(i + 1) % kk]];
    const double newellNorm = newell.Norm();
    if (!(newellNorm > 0)) break;
    double worst = -kClosureFoldCos;
    size_t at = kk;
    std::uint32_t third = 0;
    for (size_t i = 0; i < kk; ++i) {
      const std::uint32_t a = unfolded[i], b = unfolded[(i + 1) % kk];
      std::uint32_t x;
      if (!thirdPoint(a, b, x) || std::find(unfolded.begin(), unfolded.end(), x) != unfolded.end()) continue;
      if (!pem_.used(a, x) || !pem_.used(x, b) || !hasOtherEdge(x, a, b)) continue;
      const P3 nt = (pts_[b] - pts_[a]) ^ (pts_[x] - pts_[a]);
      const double len = nt.Norm();
      if (!(len > 0)) continue;
      const double c = (nt * newell) / (len * newellNorm);
      if (c > worst) {
        worst = c;
        at = i;
        third = x;
      }
    }
    if (at == kk) break;
    off.push_back({unfolded[at], unfolded[(at + 1) % kk], third});
    unfolded.insert(unfolded.begin() + std::ptrdiff_t(at + 1), third);
    // (The triangles taken off do not count in the crossing test.)
    {
      const size_t f = findTriangle(off.back()[0], off.back()[1], off.back()[2]);
      if (f < tri_.size()) skipIds.push_back(idOf[f]);
    }
    closed = closeLoop(unfolded);
  }
  skipIds.clear();
  if (closed) {
    for (const auto& t : off) {
      const size_t f = findTriangle(t[0], t[1], t[2]);
      if (f < tri_.size()) takeOff(f);
    }
    loop.swap(unfolded);
    changed = true;
  }
  return closed;
}

void Mesher::RimPass::commit(const std::vector<std::uint32_t>& loop) {
  // Every point needs room for the closure's new edges.
  bool clear = true;
  const size_t k = loop.size();
  for (std::uint32_t v : loop) clear = clear && pem_.entries(v) + k <= pem_.capacity();
  if (!clear) return;
  // Every half-edge of the closure must be free in the point-edge map as it will be once the lone
  // triangles are off, and used by one closure triangle only. The programme's checks do not
  // always see it (the joins' edges; a case is kept in fuzz/regressions/ply/): such a closure is
  // not made, and the loop stays open.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> freed, taken;
  for (std::uint32_t v : lonePoints) {
    std::uint32_t x, y;
    if (lonePartners(v, x, y) && findTriangle(v, x, y) < tri_.size())
      freed.insert(freed.end(), {{v, x}, {x, y}, {y, v}});
  }
  for (const auto& t : closure)
    for (int e = 0; e < 3; ++e) {
      const std::pair<std::uint32_t, std::uint32_t> h(t[e], t[(e + 1) % 3]);
      if (h.first == h.second || std::find(taken.begin(), taken.end(), h) != taken.end() ||
          (pem_.used(h.first, h.second) && std::find(freed.begin(), freed.end(), h) == freed.end()))
        return;
      taken.push_back(h);
    }
  for (std::uint32_t v : lonePoints) {
    std::uint32_t x, y;
    if (!lonePartners(v, x, y)) continue;
    const size_t f = findTriangle(v, x, y);
    if (f < tri_.size()) takeOff(f);
  }
  for (const auto& t : closure) {
    m_.addTriangle(t[0], t[1], t[2]);
    for (std::uint32_t v : t) addedAt[v].push_back(static_cast<std::uint32_t>(added.size()));
    added.push_back(Triangle{t[0], t[1], t[2]});
    addedId.push_back(static_cast<std::uint32_t>(curOf.size()));
    idOf.push_back(static_cast<std::uint32_t>(curOf.size()));
    curOf.push_back(static_cast<std::uint32_t>(tri_.size() - 1));
  }
  ++m_.rimLoopsClosed_;
  changed = true;
}

void Mesher::closeRimLoops() {
  Stopwatch watch;
  const size_t before = tri_.size(), removedBefore = rimFacesRemoved_;
  // A few rounds: taking off a stray piece (see strayTriangle) opens the loop of the mesh around it.
  for (int round = 0; round < kRounds; ++round) {
    RimPass pass(*this);
    if (!pass.round()) break;
  }
  // The closures' new edges (the diagonals) were queued by addTriangle and then closed by their
  // second triangle: the queue only drains.
  grow();
  rimFacesAdded_ += tri_.size() + (rimFacesRemoved_ - removedBefore) - before;
  rimSeconds_ += watch.total();
}

} // namespace g2s
} // namespace growth

namespace growth {
namespace g2s {

void Mesher::removeGrownTriangle(size_t f) {
  ++rimFacesRemoved_;
  const Triangle t = tri_[f];
  pem_.removeTriangle(t[0], t[1], t[2]);
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t x = t[k], y = t[(k + 1) % 3];
    // An edge with a triangle on the other side becomes free; a free edge of this triangle goes.
    // (Its entries stay in the point-edge map, and edgeCount_ counts entries.)
    if (pem_.used(y, x)) {
      ++freeEdges_[x];
      ++freeEdges_[y];
    } else {
      --freeEdges_[x];
      --freeEdges_[y];
    }
  }
  for (std::uint32_t v : t) {
    if (faceAt_[v] == f) faceAt_[v] = kNoFace;
    // A point left with no triangle is unused again (isolated).
    bool any = false;
    pem_.forEachEdge(v, [&](std::uint32_t, bool, bool) { any = true; });
    if (!any && edgeCount_[v] != 0) {
      edgeCount_[v] = 0;
      edgeLengthSum_[v] = 0;
      --usedPoints_;
    }
  }
  const size_t last = tri_.size() - 1;
  if (f != last) {
    tri_[f] = tri_[last];
    for (std::uint32_t v : tri_[f])
      if (faceAt_[v] == last) faceAt_[v] = static_cast<std::uint32_t>(f);
  }
  tri_.pop_back();
}

} // namespace g2s
} // namespace growth
