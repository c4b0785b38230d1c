// A repair after the paper's method (sec. 4.2's cleanup): self-intersecting faces.
//
// Self-intersections. On noisy clouds a triangle that closes a loop of free edges (an ear or a
// quad, Mesher::findCandidate) can overlap the fan of one of its points, and where two fronts grow
// over each other (layers of noisy points) their sheets can cross: the G2S and topological tests
// see points and edges, not faces. Measured on the noisy clouds, every intersecting pair had a
// face that closed a loop, or lay near the boundary (a crossing of two sheets ends at a free edge
// of one of them unless it closes on itself). So the exact test (growth/self_intersections.h)
// takes each loop-closing triangle against the faces at its points and their neighbours, and the
// faces near the vertices that can be on a boundary (boundarySuspects) against each other; faces
// are removed greedily until these have no intersecting pair, the test runs again around what was
// removed (following a crossing inwards) until a round removes nothing, and sec. 4.2 cleans up the
// fans this leaves. A mesh grown without a free edge left (every clean closed cloud) is not
// examined at all. build/mesh_measures counts 0 pairs after it on every noisy cloud measured.

#include "g2s_mesher.h"

#include <growth/self_intersections.h>

#include <algorithm>
#include <cmath>

namespace growth {
namespace g2s {

namespace {
// The exact test runs on the faces with a vertex within this many local spacings of a boundary
// suspect (1: the faces around it; 2 and 3 found no more pairs on the noisy clouds and the bunny).
constexpr double kSuspectReach = 1.0;
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

Mesher::SelfIntersectionStat Mesher::removeSelfIntersections() {
  SelfIntersectionStat st;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  std::vector<std::uint32_t> seeds;
  boundarySuspects(seeds);
  if (seeds.empty()) return st;
  const size_t n = grid_.size(), faces = tri_.size();
  const std::vector<P3>& pos = grid_.points();
  std::vector<char> near(n, 0), sub(faces, 0);
  std::vector<std::uint32_t> marked, region, removedVertices;
  // The triangles that closed a loop, each against the faces at the points near it: the faces
  // meeting one are added to the first round's faces, with it.
  std::vector<std::uint32_t> extra;
  std::vector<std::uint32_t> first, at;
  faceIndex(first, at);
  {
    std::vector<std::uint32_t> ring;
    for (std::uint32_t f : loopFaces_) {
      if (!alive_[f]) continue;
      const Triangle& t = tri_[f];
      double lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        lo[k] = std::min({pts_[t[0]][k], pts_[t[1]][k], pts_[t[2]][k]});
        hi[k] = std::max({pts_[t[0]][k], pts_[t[1]][k], pts_[t[2]][k]});
      }
      // The faces at its points and at their neighbours whose boxes overlap its box.
      ring.assign(t.begin(), t.end());
      for (std::uint32_t v : t) pem_.forEachEdge(v, [&](std::uint32_t w, bool, bool) { ring.push_back(w); });
      std::sort(ring.begin(), ring.end());
      ring.erase(std::unique(ring.begin(), ring.end()), ring.end());
      for (std::uint32_t i : ring)
        for (std::uint32_t k = first[i]; k < first[i + 1]; ++k) {
          const std::uint32_t g = at[k];
          if (g == f) continue;
          const Triangle& u = tri_[g];
          // (A face at two ring points is tested twice: harmless.)
          bool apart = false;
          for (int d = 0; d < 3 && !apart; ++d)
            apart = std::max({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]}) < lo[d] ||
                    std::min({pts_[u[0]][d], pts_[u[1]][d], pts_[u[2]][d]}) > hi[d];
          if (!apart && facesIntersect(pos, t, u)) {
            extra.push_back(f);
            extra.push_back(g);
          }
        }
    }
  }
  while (!seeds.empty() || !extra.empty()) {
    // The points near the seeds, then the live faces with a vertex among them.
    for (std::uint32_t v : seeds) {
      const double reach = kSuspectReach * std::max(localSpacing(v), spacing_);
      grid_.forEachInBall(pts_[v], reach, [&](std::uint32_t i, double) {
        if (!near[i]) {
          near[i] = 1;
          marked.push_back(i);
        }
      });
    }
    region.clear();
    for (std::uint32_t f : extra)
      if (alive_[f] && !sub[f]) {
        sub[f] = 1;
        region.push_back(f);
      }
    extra.clear();
    for (std::uint32_t i : marked)
      for (std::uint32_t k = first[i]; k < first[i + 1]; ++k)
        if (alive_[at[k]] && !sub[at[k]]) {
          sub[at[k]] = 1;
          region.push_back(at[k]);
        }
    for (std::uint32_t i : marked) near[i] = 0;
    marked.clear();
    const size_t removed = growth::removeSelfIntersections(pos, tri_, sub, 1);
    seeds.clear();
    for (std::uint32_t f : region) {
      if (!sub[f]) {
        alive_[f] = 0;
        pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
        for (std::uint32_t v : tri_[f]) seeds.push_back(v);
      }
      sub[f] = 0;
    }
    st.facesRemoved += removed;
    std::sort(seeds.begin(), seeds.end());
    seeds.erase(std::unique(seeds.begin(), seeds.end()), seeds.end());
    removedVertices.insert(removedVertices.end(), seeds.begin(), seeds.end());
  }
  if (st.facesRemoved == 0) return st;
  // The removal can leave a vertex with two fans: sec. 4.2 again, at the removed faces' vertices.
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

} // namespace g2s
} // namespace growth
