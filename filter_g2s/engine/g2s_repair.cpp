// Repairs after the paper's method (sec. 4.2's cleanup): self-intersecting faces, then small holes
// (docs/design/crossing-faces.md, docs/design/g2s-hole-pass.md).
//
// Self-intersections. On noisy clouds a triangle that closes a loop of free edges (an ear or a
// quad, Mesher::findCandidate) can overlap the fan of one of its points, and where two fronts grow
// over each other (layers of noisy points) their sheets can cross: the G2S and topological tests
// see points and edges, not faces. On noisy clouds, an intersecting pair has a face that closed a
// loop, or lies near the boundary (a crossing of two sheets ends at a free edge
// of one of them unless it closes on itself). So the exact test (growth/self_intersections.h)
// takes each loop-closing triangle against the faces at its points and their neighbours, and the
// faces near the vertices that can be on a boundary (boundarySuspects) against each other; faces
// are removed greedily until these have no intersecting pair, the test runs again around what was
// removed (following a crossing inwards) until a round removes nothing, and sec. 4.2 cleans up the
// fans this leaves. A mesh grown without a free edge left (every clean closed cloud) is not
// examined at all.
//
// Holes. A boundary loop of a few edges left by noise (the G2S ball of every triangle that would
// close it holds a point, or sec. 4.2 and the removal above took faces out) is closed by cutting
// ears from it: at each step, among the ears (two consecutive loop edges and the new edge joining
// their ends) the one whose triangle is flattest with its two neighbours is added if the new
// edge does not exist yet, the points have room for it, it folds by less than kMaxFoldDegrees over
// either neighbour, and it intersects no face near it (exactly: the faces at the points within
// kLongEdgeSpacings of the ball around the loop's points, and every face with a longer edge whose
// box meets its box). Every loop vertex is manifold (one open fan) after the cleanup, so filling its loop whole
// closes its fan: no edge gets a third triangle, no vertex a second fan, and the orientation is the
// neighbours' (each new triangle uses the reverse of the loop's half-edges). A loop is closed whole
// or not at all; one that cannot be closed is tried again with one of its faces taken out (in loop
// order, the first that lets it close), when that face's third point is inside the mesh: the point
// joins the loop and leaves it with a closed fan again (on noisy clouds, most loops that fail are
// loops of three whose triangle meets a face nearby). Last, a loop vertex with only the two faces
// on its loop edges, sharing their third point (a spike), is taken out of the mesh with both faces
// and the loop runs through that point; a loop vertex with one face on both its loop edges (a flap)
// goes with that face (one point left unused per spike or flap, at most kMaxSpikes per loop).
#include "g2s_mesher.h"

#include "g2s_apart.h"
#include "g2s_hole_pass.h"

#include <growth/self_intersections.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <unordered_map>

namespace growth {
namespace g2s {

namespace {
bool isZero(const P3& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }
// The exact test runs on the faces with a vertex within this many local spacings of a boundary
// suspect (1: the faces around it; a wider reach finds no more pairs on noisy clouds and merged scans).
constexpr double kSuspectReach = 1.0;
// Hole pass: edges longer than this many mean spacings are few (their faces are tested apart).
constexpr double kLongEdgeSpacings = 3.0;
// A hole triangle may fold over a neighbouring face by at most this angle.
constexpr double kMaxFoldDegrees = 135.0;
// Hole pass: loops of at most this many edges are tried by their least-area triangulation where
// the ears fail (O(n^3) triangles tested).
constexpr size_t kMaxLeastAreaEdges = 48;
// Hole pass: spikes taken out of one loop at most (each leaves a point out of the mesh).
constexpr size_t kMaxSpikes = 4;
} // namespace

void Mesher::boundarySuspects(std::vector<std::uint32_t>& out) const {
  out.clear();
  const size_t n = grid_.size();
  for (std::uint32_t v = 0; v < n; ++v)
    if (freeEdges_[v] != 0) out.push_back(v);
  if (alive_.size() == tri_.size()) {
    bool any = false;
    for (size_t f = 0; f < tri_.size(); ++f)
      if (!alive_[f]) {
        for (std::uint32_t v : tri_[f]) out.push_back(v);
        any = true;
      }
    if (any) {
      std::sort(out.begin(), out.end());
      out.erase(std::unique(out.begin(), out.end()), out.end());
    }
  }
}

void Mesher::faceIndex(std::vector<std::uint32_t>& first, std::vector<std::uint32_t>& at) const {
  const size_t n = grid_.size();
  first.assign(n + 1, 0);
  for (size_t f = 0; f < tri_.size(); ++f)
    if (alive_[f])
      for (std::uint32_t v : tri_[f]) ++first[v + 1];
  for (size_t i = 0; i < n; ++i) first[i + 1] += first[i];
  at.resize(first[n]);
  std::vector<std::uint32_t> next(first.begin(), first.end() - 1);
  for (size_t f = 0; f < tri_.size(); ++f)
    if (alive_[f])
      for (std::uint32_t v : tri_[f]) at[next[v]++] = static_cast<std::uint32_t>(f);
}

// The removal's state over its rounds: the live faces at each point, and per round the faces
// near the seeds (the vertices of the faces removed by the round before).
class Mesher::CrossingPass {
public:
  explicit CrossingPass(Mesher& m)
      : m_(m), pos_(m.grid_.points()), near_(m.grid_.size(), 0), sub_(m.tri_.size(), 0) {
    m_.faceIndex(first_, at_);
  }
  // The triangles that closed a loop, each against the faces at its points: the pairs that meet
  // into extra (checked in the first round, with its faces).
  void loopFaceCrossings(std::vector<std::uint32_t>& extra) const;
  // The round's region: the faces of extra and the live faces with a vertex within kSuspectReach
  // local spacings of a seed, in index order (extra cleared).
  void gatherRegion(const std::vector<std::uint32_t>& seeds, std::vector<std::uint32_t>& extra);
  // The exact test on the region's faces alone, faces removed greedily until no pair intersects;
  // their vertices into seeds (sorted, unique). Gives the number removed.
  size_t removeInRegion(std::vector<std::uint32_t>& seeds);

private:
  Mesher& m_;
  const std::vector<P3>& pos_;
  std::vector<std::uint32_t> first_, at_; // live faces at each point (faceIndex)
  std::vector<char> near_, sub_;          // per point: near a seed; per face: in the region
  std::vector<std::uint32_t> marked_, region_;
  std::vector<Triangle> local_;
  std::vector<char> localAlive_;
};

void Mesher::CrossingPass::loopFaceCrossings(std::vector<std::uint32_t>& extra) const {
  const std::vector<Triangle>& tri = m_.tri_;
  const P3* pts = m_.pts_;
  const std::vector<P3>& pos = pos_;
  for (const Triangle& loopFace : m_.loopFaces_) {
    // Its index now (none when it was taken off since).
    std::uint32_t f = ~0u;
    for (std::uint32_t k = first_[loopFace[0]]; k < first_[loopFace[0] + 1] && f == ~0u; ++k)
      if (tri[at_[k]] == loopFace) f = at_[k];
    if (f == ~0u || !m_.alive_[f]) continue;
    const Triangle& t = tri[f];
    const PlaneOf tPlane(pos, t);
    double lo[3], hi[3];
    for (int k = 0; k < 3; ++k) {
      lo[k] = std::min({pts[t[0]][k], pts[t[1]][k], pts[t[2]][k]});
      hi[k] = std::max({pts[t[0]][k], pts[t[1]][k], pts[t[2]][k]});
    }
    // The faces at its points (a face meeting it away from its points is found in the next
    // round, around the faces removed here, when it meets them too).
    for (std::uint32_t i : t)
      for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k) {
        const std::uint32_t g = at_[k];
        if (g == f) continue;
        const Triangle& u = tri[g];
        // (A face at two ring points is tested twice: harmless.)
        bool apart = false;
        for (int d = 0; d < 3 && !apart; ++d)
          apart = std::max({pts[u[0]][d], pts[u[1]][d], pts[u[2]][d]}) < lo[d] ||
                  std::min({pts[u[0]][d], pts[u[1]][d], pts[u[2]][d]}) > hi[d];
        if (!apart && !apartByPlane(pos, tPlane, t, u) && !apartByPlane(pos, u, t) &&
            !apartInShadow(pos, tPlane, t, u) && facesIntersect(pos, t, u)) {
          extra.push_back(f);
          extra.push_back(g);
        }
      }
  }
}

void Mesher::CrossingPass::gatherRegion(const std::vector<std::uint32_t>& seeds, std::vector<std::uint32_t>& extra) {
  const std::vector<char>& alive = m_.alive_;
  // The points near the seeds, then the live faces with a vertex among them.
  for (std::uint32_t v : seeds) {
    const double reach = kSuspectReach * std::max(m_.localSpacing(v), m_.spacing_);
    m_.grid_.forEachInBall(m_.pts_[v], reach, [&](std::uint32_t i, double) {
      if (!near_[i]) {
        near_[i] = 1;
        marked_.push_back(i);
      }
    });
  }
  region_.clear();
  for (std::uint32_t f : extra)
    if (alive[f] && !sub_[f]) {
      sub_[f] = 1;
      region_.push_back(f);
    }
  extra.clear();
  for (std::uint32_t i : marked_)
    for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k)
      if (alive[at_[k]] && !sub_[at_[k]]) {
        sub_[at_[k]] = 1;
        region_.push_back(at_[k]);
      }
  for (std::uint32_t i : marked_) near_[i] = 0;
  marked_.clear();
  std::sort(region_.begin(), region_.end());
}

size_t Mesher::CrossingPass::removeInRegion(std::vector<std::uint32_t>& seeds) {
  // The region's faces alone, in index order (the same pairs and the same greedy choices as
  // on the whole array with the others dead, without a pass over every face each round).
  local_.clear();
  for (std::uint32_t f : region_) local_.push_back(m_.tri_[f]);
  localAlive_.assign(region_.size(), 1);
  const size_t removed = growth::removeSelfIntersections(pos_, local_, localAlive_, m_.params_.threads);
  for (size_t k = 0; k < region_.size(); ++k) sub_[region_[k]] = localAlive_[k];
  seeds.clear();
  for (std::uint32_t f : region_) {
    if (!sub_[f]) {
      m_.alive_[f] = 0;
      m_.pem_.removeTriangle(m_.tri_[f][0], m_.tri_[f][1], m_.tri_[f][2]);
      for (std::uint32_t v : m_.tri_[f]) seeds.push_back(v);
    }
    sub_[f] = 0;
  }
  std::sort(seeds.begin(), seeds.end());
  seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
  return removed;
}

Mesher::SelfIntersectionStat Mesher::removeSelfIntersections() {
  SelfIntersectionStat st;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  // The vertices that can lie on a boundary: none on a closed mesh. (Where the mesh closed, a
  // loop-closing triangle folded back over its front triangle is the one way found for two faces
  // to cross: step 1 below finds it.)
  std::vector<std::uint32_t> seeds;
  boundarySuspects(seeds);
  if (seeds.empty() && foldedEars_ == 0) return st;
  const size_t n = grid_.size(), faces = tri_.size();
  CrossingPass pass(*this);
  // 1. The loop-closing triangles that meet a face at their points.
  std::vector<std::uint32_t> extra, removedVertices;
  pass.loopFaceCrossings(extra);
  // 2. Rounds: the faces near the seeds (and those of step 1) cleared of intersecting pairs; the
  //    vertices of the faces removed are the next round's seeds, until a round removes nothing.
  while (!seeds.empty() || !extra.empty()) {
    pass.gatherRegion(seeds, extra);
    st.facesRemoved += pass.removeInRegion(seeds);
    removedVertices.insert(removedVertices.end(), seeds.begin(), seeds.end());
  }
  if (st.facesRemoved == 0) return st;
  // 3. The removal can leave a vertex with two fans: sec. 4.2 again, at the removed faces' vertices.
  std::sort(removedVertices.begin(), removedVertices.end());
  removedVertices.erase(std::unique(removedVertices.begin(), removedVertices.end()), removedVertices.end());
  const std::vector<char> before = alive_;
  const ManifoldCleanupStat mc = growth::removeNonManifoldVertices(tri_, n, alive_, &removedVertices);
  st.nonManifoldVertices = mc.nonManifoldVertices;
  st.fanFacesRemoved = mc.facesRemoved;
  for (size_t f = 0; f < faces; ++f)
    if (before[f] && !alive_[f]) pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
  return st;
}

size_t Mesher::dropSmallComponents(size_t minFaces, size_t& facesDropped) {
  facesDropped = 0;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  // One seed grew every face (each new face shares an edge with the mesh) and none was taken out
  // since: one piece, the largest, which stays.
  if (seeds_ == 1 && rimFacesRemoved_ == 0 && std::find(alive_.begin(), alive_.end(), char(0)) == alive_.end())
    return 0;
  const std::vector<char> before(alive_.begin(), alive_.end());
  const size_t dropped = growth::dropSmallComponents(tri_, grid_.size(), alive_, minFaces, facesDropped);
  if (dropped > 0)
    for (size_t f = 0; f < tri_.size(); ++f)
      if (before[f] && !alive_[f]) pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
  return dropped;
}

void Mesher::boundaryLoops(const std::vector<std::uint32_t>& seeds, int maxEdges,
                           std::vector<std::vector<std::uint32_t>>& loops) {
  std::vector<std::pair<std::uint32_t, std::uint32_t>> walked;
  std::vector<std::uint32_t> loop;
  for (std::uint32_t v : seeds) {
    std::uint32_t w = 0;
    while (nextBoundaryHalfEdge(v, w)) {
      loop.clear();
      const std::uint32_t end = walkBoundary(v, w, walked, &loop);
      // A walk ends where it started on a manifold mesh; anything else is left alone.
      if (end == v && loop.size() >= 3 && loop.size() <= size_t(maxEdges)) loops.push_back(loop);
    }
  }
  for (const auto& e : walked) pem_.setMark(e.first, e.second, false);
}

Mesher::HolePass::HolePass(Mesher& m)
    : m_(m), pts_(m.pts_), pos_(m.grid_.points()), longest_(kLongEdgeSpacings * m.spacing_), cell_(4 * longest_),
      origin_(m.grid_.box().min), hasAdded_(m.grid_.size(), 0),
      minCos_(std::cos(kMaxFoldDegrees * 3.14159265358979323846 / 180.0)) {
  m_.faceIndex(first_, at_);
  for (size_t f = 0; f < m_.tri_.size(); ++f)
    if (m_.alive_[f]) addIfLong(static_cast<std::uint32_t>(f));
  inNear_.assign(m_.tri_.size(), 0);
}

long Mesher::HolePass::boxCells(const double boxLo[3], const double boxHi[3], long lo[3], long hi[3]) const {
  long cells = 1;
  for (int d = 0; d < 3; ++d) {
    const double a = boxLo[d] - origin_[d];
    const double b = boxHi[d] - origin_[d];
    // Clamped to ±2^40 cells (a far point or a tiny cell would overflow a long): points beyond
    // share the last cell, which only lists more faces for the exact test.
    auto clampCell = [](double c) {
      constexpr double kFar = 1099511627776.0; // 2^40
      return static_cast<long>(c >= kFar ? kFar : (c >= -kFar ? c : -kFar)); // NaN: -2^40
    };
    lo[d] = clampCell(std::floor(a / cell_));
    hi[d] = clampCell(std::floor(b / cell_));
    cells *= std::min(hi[d] - lo[d] + 1, kMaxCells + 1);
  }
  return cells;
}

long Mesher::HolePass::cellRange(const Triangle& t, long lo[3], long hi[3]) const {
  double boxLo[3], boxHi[3];
  for (int d = 0; d < 3; ++d) {
    boxLo[d] = std::min({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
    boxHi[d] = std::max({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
  }
  return boxCells(boxLo, boxHi, lo, hi);
}

void Mesher::HolePass::addLong(std::uint32_t f) {
  const Triangle& t = m_.tri_[f];
  long lo[3], hi[3];
  if (cellRange(t, lo, hi) > kMaxCells) {
    hugeFaces_.push_back(f);
    return;
  }
  for (long x = lo[0]; x <= hi[0]; ++x)
    for (long y = lo[1]; y <= hi[1]; ++y)
      for (long z = lo[2]; z <= hi[2]; ++z) longCells_[cellKey(x, y, z)].push_back(f);
}

std::int64_t Mesher::HolePass::faceOn(std::uint32_t v, std::uint32_t w) const {
  const std::vector<Triangle>& tri = m_.tri_;
  for (std::uint32_t i = first_[v]; i < first_[v + 1]; ++i) {
    const Triangle& t = tri[at_[i]];
    if (!m_.alive_[at_[i]]) continue;
    for (int k = 0; k < 3; ++k)
      if (t[k] == v && t[(k + 1) % 3] == w) return at_[i];
  }
  const auto it = added_.find(v);
  if (it != added_.end())
    for (std::uint32_t f : it->second)
      if (m_.alive_[f]) // (the handle pass takes back the faces of a cut it undoes)
        for (int k = 0; k < 3; ++k)
          if (tri[f][k] == v && tri[f][(k + 1) % 3] == w) return f;
  return -1;
}

// Any triangle on the points lies in the ball around them and in their box. A face with no edge
// longer than longest_ that meets it has a point within longest/√3 of it (every point of a
// triangle with edges of at most L is within L/√3 of a corner), hence in the ball grown by that
// much; the longer ones are found in longCells_. Only the faces whose box meets the points' box
// are kept (meetsNothing rejects a face whose box misses the triangle's, so the others could never
// count), with their boxes. The live faces are gathered; those taken out later are skipped by
// the tests.
void Mesher::HolePass::gatherNear(const std::vector<std::uint32_t>& points) {
  near_.clear();
  gathered_.assign(points.begin(), points.end());
  std::sort(gathered_.begin(), gathered_.end());
  P3 c(0, 0, 0);
  for (std::uint32_t v : points) c += pts_[v];
  c /= double(points.size());
  double r2 = 0, lo[3], hi[3];
  for (int d = 0; d < 3; ++d) lo[d] = hi[d] = pts_[points[0]][d];
  for (std::uint32_t v : points) {
    r2 = std::max(r2, (pts_[v] - c).SquaredNorm());
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min(lo[d], pts_[v][d]);
      hi[d] = std::max(hi[d], pts_[v][d]);
    }
  }
  // Each face once (inNear_ marks the faces seen, cleared after).
  seen_.clear();
  auto consider = [&](std::uint32_t g) {
    if (g >= inNear_.size()) inNear_.resize(m_.tri_.size(), 0);
    if (inNear_[g]) return;
    inNear_[g] = 1;
    seen_.push_back(g);
    if (!m_.alive_[g]) return;
    const Triangle& u = m_.tri_[g];
    NearFace e;
    for (int d = 0; d < 3; ++d) {
      e.lo[d] = std::min({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]});
      e.hi[d] = std::max({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]});
      if (e.hi[d] < lo[d] || e.lo[d] > hi[d]) return;
    }
    e.g = g;
    near_.push_back(e);
  };
  m_.grid_.forEachInBall(c, (std::sqrt(r2) + 0.58 * longest_) * (1 + 1e-9), [&](std::uint32_t i, double) {
    for (std::uint32_t k = first_[i]; k < first_[i + 1]; ++k) consider(at_[k]);
    if (!hasAdded_[i]) return;
    const auto it = added_.find(i);
    if (it != added_.end())
      for (std::uint32_t g : it->second) consider(g);
  });
  long clo[3], chi[3];
  nearHasLong_ = boxCells(lo, hi, clo, chi) <= kMaxCells;
  if (nearHasLong_) {
    for (std::uint32_t g : hugeFaces_) consider(g);
    for (long x = clo[0]; x <= chi[0]; ++x)
      for (long y = clo[1]; y <= chi[1]; ++y)
        for (long z = clo[2]; z <= chi[2]; ++z) {
          const auto it = longCells_.find(cellKey(x, y, z));
          if (it != longCells_.end())
            for (std::uint32_t g : it->second) consider(g);
        }
  }
  for (std::uint32_t g : seen_) inNear_[g] = 0;
}

template <bool all, class F> bool Mesher::HolePass::anyMeeting(const Triangle& t, F&& stop) const {
  const std::vector<P3>& pos = pos_;
  const PlaneOf tPlane(pos, t);
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
    hi[d] = std::max({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
  }
  // Face u meets t (its box first: most faces near t are beside it).
  auto meetsBeside = [&](const Triangle& u) {
    return !apartByPlane(pos, tPlane, t, u) && !apartByPlane(pos, u, t) && !apartInShadow(pos, tPlane, t, u) &&
           facesIntersect(pos, t, u);
  };
  auto meets = [&](const Triangle& u) {
    for (int d = 0; d < 3; ++d)
      if (std::max({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]}) < lo[d] ||
          std::min({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]}) > hi[d])
        return false;
    return meetsBeside(u);
  };
  auto meetsLong = [&](const std::vector<std::uint32_t>& list) {
    for (std::uint32_t g : list)
      if (m_.alive_[g] && meets(m_.tri_[g]) && stop(g)) return true;
    return false;
  };
  if (!nearHasLong_) {
    if (meetsLong(hugeFaces_)) return true;
    long clo[3], chi[3];
    cellRange(t, clo, chi); // (t is small: a hole's triangle spans few cells)
    for (long x = clo[0]; x <= chi[0]; ++x)
      for (long y = clo[1]; y <= chi[1]; ++y)
        for (long z = clo[2]; z <= chi[2]; ++z) {
          const auto it = longCells_.find(cellKey(x, y, z));
          if (it != longCells_.end() && meetsLong(it->second)) return true;
        }
  }
  for (const NearFace& e : near_)
    if (!(e.hi[0] < lo[0] || e.lo[0] > hi[0] || e.hi[1] < lo[1] || e.lo[1] > hi[1] || e.hi[2] < lo[2] ||
          e.lo[2] > hi[2]) &&
        (all || m_.alive_[e.g]) && meetsBeside(m_.tri_[e.g]) && stop(e.g))
      return true;
  return false;
}

bool Mesher::HolePass::gatheredHolds(const std::vector<std::uint32_t>& points) const {
  for (std::uint32_t v : points)
    if (!std::binary_search(gathered_.begin(), gathered_.end(), v)) return false;
  return true;
}

bool Mesher::HolePass::meetsNoPending(const Triangle& t) const {
  if (pending_.empty()) return true;
  const std::vector<P3>& pos = pos_;
  const PlaneOf tPlane(pos, t);
  double lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = std::min({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
    hi[d] = std::max({pts_[t[0]][d], pts_[t[1]][d], pts_[t[2]][d]});
  }
  for (const Triangle& p : pending_) {
    bool beside = false; // (boxes apart: nothing in common)
    for (int d = 0; d < 3 && !beside; ++d)
      beside = std::max({pts_[p[0]][d], pts_[p[1]][d], pts_[p[2]][d]}) < lo[d] ||
               std::min({pts_[p[0]][d], pts_[p[1]][d], pts_[p[2]][d]}) > hi[d];
    if (!beside && !apartByPlane(pos, tPlane, t, p) && !apartByPlane(pos, p, t) && !apartInShadow(pos, tPlane, t, p) &&
        facesIntersect(pos, t, p))
      return false;
  }
  return true;
}

bool Mesher::HolePass::meetsNothing(const Triangle& t) const { return meetsNoPending(t) && !meetsMesh(t); }

bool Mesher::HolePass::meetsMesh(const Triangle& t) const {
  if (!nearHasLong_) return anyMeeting<false>(t, [](std::uint32_t) { return true; }); // (rare: not kept)
  // Kept per triangle: a face it meets (it meets the mesh while that face is live), or that it
  // meets none, live or not (near_ was gathered with every face that can be live while the loop
  // is closed: faces are only taken out and put back meanwhile).
  Met& known = met_.emplace(t, Met{~0u, false}).first->second;
  if (known.none) return false;
  if (known.face != ~0u && m_.alive_[known.face]) return true;
  bool any = false;
  known.face = ~0u;
  anyMeeting<true>(t, [&](std::uint32_t g) {
    any = true;
    if (!m_.alive_[g]) return false;
    known.face = g;
    return true;
  });
  known.none = !any;
  return known.face != ~0u;
}

// False with pending_ and the point–edge map as before.
bool Mesher::HolePass::close() {
  PointEdgeMap& pem = m_.pem_;
  pending_.clear();
  // Ears by score: the smaller cosine of the new triangle's normal with its two neighbours',
  // then loop order (rank_: each point's place in the loop at the start, which the loop keeps as
  // points leave it). A cut changes the ears at its two neighbours only; an ear that fails a test
  // fails it at every later step (edges, faces pending and points' entries are only added while
  // the loop is closed), so it is dropped.
  rank_.resize(loop_.size());
  for (size_t i = 0; i < rank_.size(); ++i) rank_[i] = static_cast<std::uint32_t>(i);
  auto earAt = [&](size_t i, Ear& e) { // the ear at loop place i, if its score lets it be cut
    const size_t m = loop_.size(), p = (i + m - 1) % m, q = (i + 1) % m;
    const std::uint32_t v0 = loop_[p], v1 = loop_[i], v2 = loop_[q];
    const P3 nt = normal(v1, v0, v2);
    if (isZero(nt)) return false;
    const double c1 = cosBetween(nt, normal(v0, v1, opp_[p]));
    const double c2 = cosBetween(nt, normal(v1, v2, opp_[i]));
    e = Ear{std::min(c1, c2), rank_[i]};
    return e.score >= minCos_;
  };
  auto before = [](const Ear& x, const Ear& y) { return x.score != y.score ? x.score > y.score : x.index < y.index; };
  ears_.clear();
  if (loop_.size() > 3) {
    Ear e;
    for (size_t i = 0; i < loop_.size(); ++i)
      if (earAt(i, e)) ears_.push_back(e);
    std::sort(ears_.begin(), ears_.end(), before);
  }
  bool ok = true;
  while (ok && loop_.size() >= 3) {
    const size_t m = loop_.size();
    if (m == 3) {
      // The last triangle uses the reverse of the three loop edges.
      const Triangle t{loop_[1], loop_[0], loop_[2]};
      ok = !isZero(normal(t[0], t[1], t[2])) && pem.canAddTriangle(t[0], t[1], t[2]);
      for (size_t i = 0; i < 3 && ok; ++i)
        ok = cosBetween(normal(t[0], t[1], t[2]), normal(loop_[i], loop_[(i + 1) % 3], opp_[i])) >= minCos_;
      ok = ok && meetsNothing(t);
      if (ok) {
        pem.addTriangle(t[0], t[1], t[2]);
        pending_.push_back(t);
      }
      break;
    }
    bool cut = false;
    for (size_t k = 0; k < ears_.size() && !cut;) {
      const size_t i = size_t(std::lower_bound(rank_.begin(), rank_.end(), ears_[k].index) - rank_.begin());
      const size_t p = (i + m - 1) % m, q = (i + 1) % m;
      const std::uint32_t v0 = loop_[p], v1 = loop_[i], v2 = loop_[q];
      const Triangle t{v1, v0, v2};
      // The new edge v0–v2 must not exist (it would get a third triangle or join two fans).
      if (pem.triangles(v0, v2) != 0 || !pem.canAddTriangle(t[0], t[1], t[2]) || !meetsNothing(t)) {
        ears_.erase(ears_.begin() + std::ptrdiff_t(k));
        continue;
      }
      // Recorded at once (the loop's later ears see its edges), taken back if the loop fails.
      pem.addTriangle(t[0], t[1], t[2]);
      pending_.push_back(t);
      // v1 leaves the loop; the new loop edge v0→v2 has v1 opposite.
      const std::uint32_t rp = rank_[p], rq = rank_[q];
      opp_[p] = v1;
      loop_.erase(loop_.begin() + std::ptrdiff_t(i));
      opp_.erase(opp_.begin() + std::ptrdiff_t(i));
      rank_.erase(rank_.begin() + std::ptrdiff_t(i));
      ears_.erase(ears_.begin() + std::ptrdiff_t(k));
      cut = true;
      // The ears at v0 and v2 anew.
      ears_.erase(std::remove_if(ears_.begin(), ears_.end(), [&](const Ear& x) { return x.index == rp || x.index == rq; }),
                  ears_.end());
      if (m - 1 > 3) {
        Ear e;
        for (size_t at : {p < i ? p : p - 1, q > i ? q - 1 : q})
          if (earAt(at, e)) ears_.insert(std::lower_bound(ears_.begin(), ears_.end(), e, before), e);
      }
    }
    ok = cut;
  }
  if (!ok)
    for (const Triangle& t : pending_) pem.removeTriangle(t[0], t[1], t[2]);
  return ok;
}

bool Mesher::HolePass::leastArea(bool crossingTest, std::vector<std::array<size_t, 3>>& out) {
  PointEdgeMap& pem = m_.pem_;
  out.clear();
  const size_t n = loop_.size();
  if (n < 3 || n > kMaxLeastAreaEdges) return false;
  // Triangle (i, j, k), i < j < k in loop order, is {loop_[j], loop_[i], loop_[k]}: it uses the
  // reverse of each loop edge among its sides (loop edge i→i+1, and n-1→0 as k→i).
  auto tri = [&](size_t i, size_t j, size_t k) { return Triangle{loop_[j], loop_[i], loop_[k]}; };
  auto loopEdge = [&](size_t a, size_t b) -> std::int64_t { // the loop edge a→b is on (-1: a diagonal)
    if (b == a + 1) return std::int64_t(a);
    if (a == 0 && b == n - 1) return std::int64_t(n - 1);
    return -1;
  };
  // Per triangle: -2 untouched, -1 area known (area_), 0 fails, 1 passes the ears' tests (crossing
  // untested), 2 passes all (area known from -1 on).
  std::vector<signed char>& valid = valid_;
  valid.assign(n * n * n, -2);
  if (area_.size() < n * n * n) area_.resize(n * n * n); // (read only where valid says it was set)
  // The normals of the faces on the loop edges, for the fold tests.
  edgeNormal_.resize(n);
  for (size_t a = 0; a < n; ++a) edgeNormal_[a] = normal(loop_[a], loop_[(a + 1) % n], opp_[a]);
  auto areaOf = [&](size_t i, size_t j, size_t k) {
    const size_t at = (i * n + j) * n + k;
    if (valid[at] == -2) {
      const Triangle t = tri(i, j, k);
      area_[at] = 0.5 * normal(t[0], t[1], t[2]).Norm();
      valid[at] = -1;
    }
    return area_[at];
  };
  auto cheapValid = [&](size_t i, size_t j, size_t k) -> signed char& {
    signed char& v = valid[(i * n + j) * n + k];
    if (v >= 0) return v;
    const Triangle t = tri(i, j, k);
    const P3 nt = normal(t[0], t[1], t[2]);
    bool ok = !isZero(nt) && pem.canAddTriangle(t[0], t[1], t[2]);
    const size_t side[3][2] = {{i, j}, {j, k}, {i, k}};
    for (int s = 0; s < 3 && ok; ++s) {
      const std::int64_t e = loopEdge(side[s][0], side[s][1]);
      if (e < 0) {
        ok = pem.triangles(loop_[side[s][0]], loop_[side[s][1]]) == 0;
      } else {
        ok = cosBetween(nt, edgeNormal_[size_t(e)]) >= minCos_;
      }
    }
    v = ok ? (crossingTest ? 1 : 2) : 0;
    return v;
  };
  auto crossingValid = [&](size_t i, size_t j, size_t k) {
    signed char& v = cheapValid(i, j, k);
    if (v == 1) v = meetsNothing(tri(i, j, k)) ? 2 : 0;
    return v == 2;
  };
  // The crossing test is the costly one, and few triangles fail it: the least area is found with
  // the untested triangles allowed (lazy), and only its triangles are tested; the failing ones
  // are forbidden and the least area found again (for the parts that hold one), until its
  // triangles pass. Every value is then at most the exact one and the optimum's is reached, so
  // the optimum and, for each part, its first best split are the exact ones (sums round
  // monotonically). After kLazyRounds rounds the triangles are tested as they come (eager): the
  // same result.
  constexpr int kLazyRounds = 32;
  const double inf = std::numeric_limits<double>::infinity();
  std::vector<double>& best = best_;
  std::vector<std::uint32_t>& split = bestSplit_;
  best.assign(n * n, inf);
  split.assign(n * n, 0);
  for (size_t i = 0; i + 1 < n; ++i) best[i * n + i + 1] = 0;
  std::vector<std::array<size_t, 2>>& failed = failedParts_; // (i, k) of the triangles that failed
  failed.clear();
  for (int round = 0;; ++round) {
    const bool eager = round >= kLazyRounds;
    for (size_t len = 2; len < n; ++len)
      for (size_t i = 0; i + len < n; ++i) {
        const size_t k = i + len;
        if (round > 0 && !eager) { // (only the parts holding a forbidden triangle change)
          bool holds = false;
          for (const auto& f : failed) holds = holds || (i <= f[0] && f[1] <= k);
          if (!holds) continue;
        }
        double& b = best[i * n + k];
        b = inf;
        split[i * n + k] = 0;
        for (size_t j = i + 1; j < k; ++j) {
          const double sub = best[i * n + j] + best[j * n + k];
          if (!(sub < b)) continue;
          const double cost = sub + areaOf(i, j, k);
          // (The tests only where the triangle would improve the best: the same choice, fewer tests.)
          if (cost < b && (eager ? crossingValid(i, j, k) : cheapValid(i, j, k) != 0)) {
            b = cost;
            split[i * n + k] = std::uint32_t(j);
          }
        }
      }
    if (!(best[n - 1] < inf)) return false;
    // The triangles, outermost first.
    out.clear();
    std::vector<std::array<size_t, 2>> stack{{0, n - 1}};
    while (!stack.empty()) {
      const size_t i = stack.back()[0], k = stack.back()[1];
      stack.pop_back();
      if (k < i + 2) continue;
      const size_t j = split[i * n + k];
      out.push_back({i, j, k});
      stack.push_back({i, j});
      stack.push_back({j, k});
    }
    failed.clear();
    for (const auto& s : out)
      if (!crossingValid(s[0], s[1], s[2])) failed.push_back({s[0], s[2]});
    if (failed.empty()) return true;
  }
}

bool Mesher::HolePass::closeLeastArea() {
  PointEdgeMap& pem = m_.pem_;
  pending_.clear();
  if (loop_.size() < 4 || !leastArea(true, split_)) return false;
  // The triangles, each added at once so that the next is tested against it (meetsNothing looks at
  // pending_) and its diagonal is used in the point–edge map.
  bool ok = true;
  for (const auto& s : split_) {
    const Triangle t{loop_[s[1]], loop_[s[0]], loop_[s[2]]};
    ok = pem.canAddTriangle(t[0], t[1], t[2]) && meetsNoPending(t); // (leastArea tested the mesh's faces)
    // Folds across its diagonals, against the triangles on their other side (added before it or after).
    const P3 nt = normal(t[0], t[1], t[2]);
    for (const Triangle& u : pending_) {
      int shared = 0;
      for (std::uint32_t x : t) shared += x == u[0] || x == u[1] || x == u[2];
      if (shared == 2 && cosBetween(nt, normal(u[0], u[1], u[2])) < minCos_) ok = false;
    }
    if (!ok) break;
    pem.addTriangle(t[0], t[1], t[2]);
    pending_.push_back(t);
  }
  if (!ok) {
    for (const Triangle& t : pending_) pem.removeTriangle(t[0], t[1], t[2]);
    pending_.clear();
  }
  return ok;
}

bool Mesher::HolePass::blockers(const std::vector<std::uint32_t>& original, std::vector<std::uint32_t>& out) {
  out.clear();
  const size_t m = original.size();
  if (m < 3 || m > kMaxLeastAreaEdges) return false;
  face_.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const std::int64_t f = faceOn(original[i], original[(i + 1) % m]);
    if (f < 0) return false;
    face_[i] = static_cast<std::uint32_t>(f);
  }
  loop_ = original;
  opp_.resize(m);
  for (size_t i = 0; i < m; ++i) opp_[i] = thirdPoint(face_[i], original[i], original[(i + 1) % m]);
  pending_.clear();
  gatherNear(loop_);
  if (!leastArea(false, split_)) return false;
  for (const auto& s : split_) {
    const Triangle t{loop_[s[1]], loop_[s[0]], loop_[s[2]]};
    anyMeeting<false>(t, [&](std::uint32_t g) {
      out.push_back(g);
      return false;
    });
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return !out.empty();
}

void Mesher::HolePass::commit(HoleStat& st) {
  for (const Triangle& t : pending_) {
    const auto f = static_cast<std::uint32_t>(m_.tri_.size());
    m_.tri_.push_back(t);
    m_.alive_.push_back(1);
    noteAdded(f);
  }
  ++st.closed;
  st.facesAdded += pending_.size();
}

void Mesher::HolePass::closeLoop(const std::vector<std::uint32_t>& original, HoleStat& st) {
  std::vector<char>& alive = m_.alive_;
  const std::vector<Triangle>& tri = m_.tri_;
  PointEdgeMap& pem = m_.pem_;
  // The faces on the loop's half-edges (a loop without one is left alone).
  const size_t m = original.size();
  face_.resize(m);
  for (size_t i = 0; i < m; ++i) {
    const std::int64_t f = faceOn(original[i], original[(i + 1) % m]);
    if (f < 0) return;
    face_[i] = static_cast<std::uint32_t>(f);
  }
  auto setUp = [&]() {
    loop_ = original;
    opp_.resize(m);
    for (size_t i = 0; i < m; ++i) opp_[i] = thirdPoint(face_[i], original[i], original[(i + 1) % m]);
  };
  // The loop closed as it is: by ears, else by its least-area triangulation. (The mesh's answers
  // are kept for the loop's tries: faces are only taken out and put back until it is closed.)
  met_.clear();
  setUp();
  gatherNear(loop_);
  bool closed = close();
  if (!closed) {
    setUp();
    closed = closeLeastArea();
  }
  // Where it cannot be closed, the loop with one of its faces taken out (in loop order, the
  // first that lets it close): the face's third point must be inside the mesh (its fan closed),
  // so that it joins the loop and leaves with a closed fan again.
  bool widerGathered = false;
  for (size_t i = 0; i < m && !closed; ++i) {
    const std::uint32_t f = face_[i], v = original[i], w = original[(i + 1) % m];
    const std::uint32_t o = thirdPoint(f, v, w);
    if (!alive[f] || !pem.closed(o)) continue;
    if (!widerGathered) { // (once for every try, before a face is taken out: the loop and all the third points)
      tryPoints_.assign(original.begin(), original.end());
      for (size_t j = 0; j < m; ++j) tryPoints_.push_back(thirdPoint(face_[j], original[j], original[(j + 1) % m]));
      gatherNear(tryPoints_);
      widerGathered = true;
    }
    alive[f] = 0;
    pem.removeTriangle(tri[f][0], tri[f][1], tri[f][2]);
    setUp();
    const std::int64_t f1 = faceOn(v, o), f2 = faceOn(o, w);
    if (f1 >= 0 && f2 >= 0) {
      loop_.insert(loop_.begin() + std::ptrdiff_t(i + 1), o);
      opp_[i] = thirdPoint(static_cast<std::uint32_t>(f1), v, o);
      opp_.insert(opp_.begin() + std::ptrdiff_t(i + 1), thirdPoint(static_cast<std::uint32_t>(f2), o, w));
      closed = close();
    }
    if (closed) {
      ++st.facesReplaced;
    } else {
      alive[f] = 1;
      pem.addTriangle(tri[f][0], tri[f][1], tri[f][2]);
    }
  }
  // Spikes: a loop vertex whose only faces are the two on its loop edges, with the same third point
  // inside the mesh (a point the growth joined by two triangles at a corner, whose one closing
  // triangle folds back). Both faces are taken out, the vertex leaves the mesh, and the loop runs
  // through the third point instead, which leaves with a closed fan again. Spikes are taken out one
  // after another (at most kMaxSpikes per loop), the loop tried after each; all are put back if it
  // never closes.
  if (!closed) {
    std::vector<std::uint32_t> cur = original, removed;
    size_t spikes = 0;
    while (!closed && spikes < kMaxSpikes) {
      const size_t mc = cur.size();
      bool found = false;
      for (size_t i = 0; i < mc && !found; ++i) {
        const size_t h = (i + mc - 1) % mc;
        const std::uint32_t u = cur[h], v = cur[i], w = cur[(i + 1) % mc];
        const std::int64_t f0 = faceOn(u, v), f1 = faceOn(v, w);
        if (f0 >= 0 && f0 == f1 && mc > 3 && pem.degree(v) == 2 && faceOn(u, w) >= 0) {
          // A flap: v's one face lies on both its loop edges; it goes with v, and the loop runs
          // u -> w over the face on the other side of that edge.
          alive[std::size_t(f0)] = 0;
          const Triangle& t = tri[std::size_t(f0)];
          pem.removeTriangle(t[0], t[1], t[2]);
          removed.push_back(static_cast<std::uint32_t>(f0));
          cur.erase(cur.begin() + std::ptrdiff_t(i));
          ++spikes;
          found = true;
          continue;
        }
        if (f0 < 0 || f1 < 0 || f0 == f1 || pem.degree(v) != 3) continue;
        const std::uint32_t o = thirdPoint(static_cast<std::uint32_t>(f0), u, v);
        if (o != thirdPoint(static_cast<std::uint32_t>(f1), v, w) || !pem.closed(o) ||
            std::find(cur.begin(), cur.end(), o) != cur.end())
          continue;
        for (std::int64_t f : {f0, f1}) {
          alive[std::size_t(f)] = 0;
          const Triangle& t = tri[std::size_t(f)];
          pem.removeTriangle(t[0], t[1], t[2]);
          removed.push_back(static_cast<std::uint32_t>(f));
        }
        cur[i] = o;
        ++spikes;
        found = true;
      }
      if (!found) break;
      // The loop through the third points, with the faces on its half-edges.
      const size_t mk = cur.size();
      loop_ = cur;
      opp_.resize(mk);
      bool complete = true;
      for (size_t i = 0; i < mk && complete; ++i) {
        const std::int64_t f = faceOn(cur[i], cur[(i + 1) % mk]);
        complete = f >= 0;
        if (complete) opp_[i] = thirdPoint(static_cast<std::uint32_t>(f), cur[i], cur[(i + 1) % mk]);
      }
      if (!complete) break;
      if (!gatheredHolds(loop_)) gatherNear(loop_);
      closed = close();
    }
    if (closed) {
      st.facesReplaced += removed.size();
      st.spikes += spikes;
    } else {
      for (std::uint32_t f : removed) {
        alive[f] = 1;
        pem.addTriangle(tri[f][0], tri[f][1], tri[f][2]);
      }
    }
  }
  if (closed) commit(st);
}

Mesher::HoleStat Mesher::closeHoles(int maxEdges) {
  HoleStat st;
  if (maxEdges < 3) return st;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  std::vector<std::uint32_t> seeds;
  boundarySuspects(seeds);
  if (seeds.empty()) return st;
  closeHolesAt(maxEdges, seeds, st);
  return st;
}

void Mesher::closeHolesAt(int maxEdges, const std::vector<std::uint32_t>& seeds, HoleStat& st) {
  // 1. The boundary loops of at most maxEdges edges (v0→v1→…: half-edges used by one face each).
  std::vector<std::vector<std::uint32_t>> loops;
  boundaryLoops(seeds, maxEdges, loops);
  st.loops += loops.size();
  if (loops.empty()) return;
  // 2. The faces at each point and the long faces by cells, for the exact tests (once: the pass
  //    follows the faces taken out through alive() and keeps those it adds).
  if (!holePass_) holePass_.reset(new HolePass(*this));
  // 3. Each loop closed by ears, whole or not at all.
  for (const std::vector<std::uint32_t>& original : loops) holePass_->closeLoop(original, st);
}

} // namespace g2s
} // namespace growth
