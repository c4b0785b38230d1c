// Robust G2S: small handles cut after the growth (Mesher::removeSmallHandles), and the hole
// pass's wider closure (Mesher::widenHoles); not in the paper (docs/design/g2s-small-handles.md,
// docs/design/g2s-hole-pass.md).
//
// Where two sheets of one surface come within a spacing or two (the rim of a plate 3 spacings
// thick, the overlapping layers of a merged scan), the growth can join them twice and leave a
// tunnel: a handle of the mesh that the surface does not have. On closed slabs 3 spacings thick,
// such a handle lies within two rings of one rim vertex and is cut by a cycle of three mesh edges
// that bounds no face (a non-face 3-cycle): removing the faces on one side of the cycle lowers the
// genus of the two rings around it from 1 to 0. So, as Guskov and Wood's topological noise removal (2001) does
// with its short non-separating cycles, but only for the shortest ones:
//  - the pass runs only where the mesh has a handle: the sum over components of
//    (2 - V + E - F - loops) / 2 is above 0 (a clean sphere stops there without numbering its
//    components), and not on the paper's growth alone (no thin-part rule acted, no repair): its
//    handles are taken as the object's;
//  - an edge (v, a) whose points have more common neighbours than triangles on it gives the
//    candidates (v, a, b), but the link of a point of degree 3 (which bounds its three faces); a
//    cycle is cut when removing the faces on one of its sides (at each of its points, the fan
//    between its next and its previous point) lowers the genus of the region made of the faces
//    within two rings of v (vertices counted once per fan, boundary loops walked in the region):
//    the cycle does not separate the region, hence not the mesh, and the mesh loses one handle;
//  - the cut leaves two loops: the cycle itself (the tunnel's cap: three edges) and the outer edge
//    of the removed faces (one loop, where it runs into a hole that was there); the hole pass
//    (HolePass, g2s_hole_pass.h) closes them with its checks (no crossing, manifold, oriented).
//    The cut is kept only when every loop closed, every point of the region that had no free edge
//    has none after, and every point there has one fan; otherwise it is undone and the other side
//    is tried. The cycle's points keep their faces on the other side, so no point is lost unless
//    all of its faces were on the removed side.
// The wider closure uses the same trial: a loop the hole pass left open loses the faces on its
// edges (then, if that fails, all the faces at its points) and the wider loop is closed. Last,
// where the loop's least-area triangulation (crossings not tested) meets faces of the mesh (the
// blockers: at a plate's rim, triangles left from the front's crossing through the material, a
// fin across the hole), the faces on its edges and the blockers go, then also all the faces at
// the blockers' points off the loop; the loops this leaves are closed as above.
// A handle of the object itself (a torus' tube, a mug's handle) has no cycle of three edges
// around it unless it is sampled by three points across, so it stays.
#include "g2s_hole_pass.h"
#include "g2s_mesher.h"

#include <growth/self_intersections.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <memory>
#include <unordered_map>
#include <vector>

namespace growth {
namespace g2s {

namespace {

// Genus of a set of faces of a manifold, consistently oriented mesh: per connected piece (faces
// joined by edges), 2 - 2g = V - E + F + loops, with V counting each vertex once per fan in the
// set (so that a region pinched at a vertex gives whole numbers). -1 when the set's boundary does
// not walk (an inconsistent orientation).
class RegionGenus {
public:
  int operator()(const std::vector<Triangle>& tri, const std::vector<std::uint32_t>& faces) {
    const size_t nf = faces.size();
    if (nf == 0) return 0;
    half_.clear();
    for (size_t i = 0; i < nf; ++i) {
      const Triangle& t = tri[faces[i]];
      for (int k = 0; k < 3; ++k) half_.push_back({t[k], t[(k + 1) % 3], std::uint32_t(3 * i + k)});
    }
    std::sort(half_.begin(), half_.end());
    corner_.resize(3 * nf);
    for (size_t c = 0; c < corner_.size(); ++c) corner_[c] = std::uint32_t(c);
    face_.resize(nf);
    for (size_t i = 0; i < nf; ++i) face_[i] = std::uint32_t(i);
    size_t edges = 0;
    // Corner c = 3i + k is face i at its k-th point; half-edge 3i + k runs from corner 3i + k to
    // corner 3i + (k + 1) % 3.
    auto to = [](std::uint32_t h) { return h - h % 3 + (h % 3 + 1) % 3; };
    twin_.assign(3 * nf, ~0u);
    for (const Half& h : half_) {
      const Half key{h.b, h.a, 0};
      auto it = std::lower_bound(half_.begin(), half_.end(), key);
      if (it != half_.end() && it->a == h.b && it->b == h.a) {
        twin_[h.id] = it->id;
        if (h.a < h.b) {
          ++edges;
          // h: a→b from corner h.id to to(h.id); twin: b→a from corner it->id to to(it->id).
          join(corner_, h.id, to(it->id));
          join(corner_, to(h.id), it->id);
          join(face_, h.id / 3, it->id / 3);
        }
      } else {
        ++edges;
      }
    }
    size_t vertices = 0, pieces = 0;
    for (size_t c = 0; c < corner_.size(); ++c) vertices += root(corner_, std::uint32_t(c)) == c;
    for (size_t i = 0; i < nf; ++i) pieces += root(face_, std::uint32_t(i)) == i;
    // Boundary loops: the one boundary half-edge leaving each open fan.
    out_.assign(3 * nf, ~0u);
    for (std::uint32_t h = 0; h < 3 * nf; ++h)
      if (twin_[h] == ~0u) {
        const std::uint32_t r = root(corner_, h);
        if (out_[r] != ~0u) return -1;
        out_[r] = h;
      }
    seen_.assign(3 * nf, 0);
    size_t loops = 0;
    for (std::uint32_t h = 0; h < 3 * nf; ++h) {
      if (twin_[h] != ~0u || seen_[h]) continue;
      ++loops;
      std::uint32_t x = h;
      while (!seen_[x]) {
        seen_[x] = 1;
        x = out_[root(corner_, to(x))];
        if (x == ~0u) return -1;
      }
      if (x != h) return -1;
    }
    const long twice = 2 * long(pieces) - (long(vertices) - long(edges) + long(nf)) - long(loops);
    if (twice < 0 || twice % 2 != 0) return -1;
    return int(twice / 2);
  }

private:
  struct Half {
    std::uint32_t a, b, id;
    bool operator<(const Half& o) const { return a != o.a ? a < o.a : b < o.b; }
  };
  static std::uint32_t root(std::vector<std::uint32_t>& p, std::uint32_t i) {
    while (p[i] != i) {
      p[i] = p[p[i]];
      i = p[i];
    }
    return i;
  }
  static void join(std::vector<std::uint32_t>& p, std::uint32_t a, std::uint32_t b) {
    a = root(p, a);
    b = root(p, b);
    if (a != b) p[std::max(a, b)] = std::min(a, b);
  }
  std::vector<Half> half_;
  std::vector<std::uint32_t> corner_, face_, twin_, out_;
  std::vector<char> seen_;
};

} // namespace

size_t Mesher::handleCount(const BoundaryCount& boundary) const {
  // Every component grew from a seed, so where no face was ever taken out (neither by the cleanup
  // nor by the rim pass, which may split a component) there are at most seeds() of them: with that
  // bound, (2 C - V + E - F - loops) / 2 bounds the handles, and a clean closed cloud of genus 0
  // stops here without numbering its components (V: the points used, which the hole pass does not
  // change).
  const bool noneRemoved = foldsRefused_ + otherSheetBalls_ == 0 &&
                           std::find(alive_.begin(), alive_.end(), char(0)) == alive_.end();
  if (noneRemoved && seeds_ > 0) { // (faces put in without a seed, as a test does, are no component's)
    const long faces = long(tri_.size()), edges = (3 * faces + long(boundary.edges)) / 2;
    const long twice = 2 * long(seeds_) - (long(usedPoints_) - edges + faces) - long(boundary.loops);
    if (twice <= 0) return 0;
  }
  const size_t n = grid_.size();
  std::vector<std::uint32_t> parent;
  unionComponents(parent);
  std::vector<char> used(n, 0);
  size_t faces = 0;
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!live(f)) continue;
    ++faces;
    for (std::uint32_t v : tri_[f]) used[v] = 1;
  }
  size_t vertices = 0, pieces = 0;
  for (std::uint32_t v = 0; v < n; ++v) {
    if (!used[v]) continue;
    ++vertices;
    pieces += parent[v] == v;
  }
  const size_t edges = (3 * faces + boundary.edges) / 2;
  const long twice = 2 * long(pieces) - (long(vertices) - long(edges) + long(faces)) - long(boundary.loops);
  return twice > 0 ? size_t(twice / 2) : 0;
}

// removeSmallHandles' state: the faces at each point (the live ones at the start, the ones added
// since by point), the region of the cycle being tried, and the hole pass that closes the cuts.
class Mesher::HandlePass {
public:
  // The regrowth (Widen::Regrow, regrow): the faces at the points within kRegrowBand spacings of
  // the loop are taken out too; the growth runs on the points within kRegrowMargin spacings of
  // the loops' points' centroid beyond the farthest of them (at most kRegrowMaxPoints), and its
  // triangles must keep kRegrowInside spacings inside that ball.
  static constexpr double kRegrowBand = 1.5;
  static constexpr double kRegrowMargin = 4.0;
  static constexpr double kRegrowInside = 1.5;
  static constexpr size_t kRegrowMaxPoints = 8192;
  static constexpr size_t kRegrowPopsPerPoint = 64; // (a bound on the growth's work: measured ~5)
  HandlePass(Mesher& m, int maxHoleEdges) : m_(m), maxHoleEdges_(maxHoleEdges), inRing_(m.grid_.size(), 0), mark_(m.grid_.size(), 0) {
    m_.faceIndex(first_, at_);
    indexed_ = m_.tri_.size();
  }
  // Tries every non-face 3-cycle with v as its smallest point, cutting those that lower the genus.
  void at(std::uint32_t v, HandleStat& st);
  // A loop the hole pass left open, tried again with every face on its edges taken out (the loop
  // then runs through their third points); true when it closed so.
  bool widen(const std::vector<std::uint32_t>& loop, HandleStat& st);
  // One try of widen: the faces on the loop's edges, and (stars) all the faces at its points, or
  // (blockers) the faces in blockers_ (those its least-area triangulation meets), and (blocker
  // stars) all the faces at their points off the loop.
  enum class Widen { Edges, Stars, Blockers, BlockerStars, Regrow };
  bool widenBy(const std::vector<std::uint32_t>& loop, Widen how, HandleStat& st);
  // The faces of cut_'s points that would fall into more than one fan once cut_ is out: those of
  // all but the largest fan join cut_ (sec. 4.2's rule), until each such point has one fan.
  void splitFans();
  // The live faces at x that skip(f) leaves into fan, and their fans: part[i] is the index in fan
  // of the first face of fan[i]'s fan. Returns the number of fans.
  template <class Skip>
  size_t fansAt(std::uint32_t x, Skip&& skip, std::vector<std::uint32_t>& fan, std::vector<std::uint32_t>& part) const;
  // Of fansAt's fans, the one kept (its first face's index in fan): the most faces older than
  // firstNew, then the most faces, then the first.
  static size_t keptFan(const std::vector<std::uint32_t>& fan, const std::vector<std::uint32_t>& part, size_t firstNew);

private:
  template <class F> void forEachFace(std::uint32_t v, F&& f) const {
    for (std::uint32_t k = first_[v]; k < first_[v + 1]; ++k)
      if (m_.alive_[at_[k]]) f(at_[k]);
    if (added_.empty()) return;
    const auto it = added_.find(v);
    if (it != added_.end())
      for (std::uint32_t g : it->second)
        if (m_.alive_[g]) f(g);
  }
  // The live face with half-edge v→w (-1: none).
  std::int64_t faceWith(std::uint32_t v, std::uint32_t w) const {
    std::int64_t found = -1;
    forEachFace(v, [&](std::uint32_t f) {
      const Triangle& t = m_.tri_[f];
      for (int j = 0; j < 3; ++j)
        if (t[j] == v && t[(j + 1) % 3] == w) found = f;
    });
    return found;
  }
  // The faces at x from half-edge x→next round to half-edge x→prev: the cycle's left at x
  // (from the face with x→y to the face with x→(the point before x in it)). False at a boundary.
  bool leftWedge(std::uint32_t prev, std::uint32_t x, std::uint32_t next, std::vector<std::uint32_t>& out) const {
    std::uint32_t y = next;
    for (int guard = 0; guard < 1024; ++guard) {
      if (y == prev) return true;
      const std::int64_t f = faceWith(x, y);
      if (f < 0) return false;
      out.push_back(std::uint32_t(f));
      const Triangle& t = m_.tri_[size_t(f)];
      const int j = t[0] == x ? 0 : t[1] == x ? 1 : 2;
      y = t[(j + 2) % 3];
    }
    return false;
  }
  // The points within two rings of v into ring_ (marked in inRing_), their live faces into region_.
  void gatherRegion(std::uint32_t v);
  // Takes the faces cut_ out and closes the loops through their points; keeps that when every
  // loop closed and every point of the region that had no free edge has none after (or no face:
  // counted lost). Otherwise everything is put back; false.
  bool cutAndClose(HandleStat& st, int maxLoopEdges, bool regrowFirst = false);
  // cutAndClose with regrowFirst: the loops grown into by a G2S growth of their own, on the points
  // near them (the faces there fixed), before the hole pass closes what is left. Adds the new
  // faces (and their points to touched; kept: their number, less those of extra fans taken out
  // again); false when they would cross a face or an edge.
  bool regrow(const std::vector<std::vector<std::uint32_t>>& loops, std::vector<std::uint32_t>& touched,
              size_t& kept);
  // Points of `touched` with more than one fan of live faces.
  bool anyTwoFans(const std::vector<std::uint32_t>& touched) const;

  // The faces added to the mesh since the last call into added_ (dead ones are skipped by
  // forEachFace, so an undone try needs nothing more).
  void indexNewFaces() {
    for (size_t f = indexed_; f < m_.tri_.size(); ++f)
      for (std::uint32_t x : m_.tri_[f]) added_[x].push_back(std::uint32_t(f));
    indexed_ = m_.tri_.size();
  }

  Mesher& m_;
  const int maxHoleEdges_;
  size_t indexed_ = 0; // faces of the mesh known to forEachFace
  std::vector<std::uint32_t> first_, at_;
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> added_;
  RegionGenus genus_;
  std::vector<char> inRing_, mark_;
  std::vector<std::uint32_t> localIndex_; // regrow: the points' places in its local mesher
  std::vector<std::uint8_t> nt_;
  std::vector<std::uint32_t> nv_, ring_, next_, region_, cut_, rest_, outside_, blockers_;
};

void Mesher::HandlePass::gatherRegion(std::uint32_t v) {
  ring_.assign(1, v);
  inRing_[v] = 1;
  size_t from = 0;
  for (int r = 0; r < 2; ++r) {
    const size_t to = ring_.size();
    for (size_t i = from; i < to; ++i)
      m_.pem_.forEachEdge(ring_[i], [&](std::uint32_t w, bool o, bool in) {
        if ((o || in) && !inRing_[w]) {
          inRing_[w] = 1;
          ring_.push_back(w);
        }
      });
    from = to;
  }
  region_.clear();
  for (std::uint32_t x : ring_) forEachFace(x, [&](std::uint32_t f) { region_.push_back(f); });
  std::sort(region_.begin(), region_.end());
  region_.erase(std::unique(region_.begin(), region_.end()), region_.end());
}

bool Mesher::HandlePass::anyTwoFans(const std::vector<std::uint32_t>& touched) const {
  std::vector<std::uint32_t> fan;
  for (std::uint32_t x : touched) {
    fan.clear();
    forEachFace(x, [&](std::uint32_t f) { fan.push_back(f); });
    if (fan.size() < 2) continue;
    // Walk one fan from fan[0] across the edges at x, both ways (once round, if it is closed):
    // all faces reached?
    size_t reached = 1;
    bool closedFan = false;
    for (int dir = 0; dir < 2 && !closedFan; ++dir) {
      std::uint32_t f = fan[0];
      for (size_t guard = 0; guard < fan.size(); ++guard) {
        const Triangle& t = m_.tri_[f];
        const int j = t[0] == x ? 0 : t[1] == x ? 1 : 2;
        // dir 0: across edge (x, next); the face there has half-edge next→x.
        const std::int64_t g = dir == 0 ? faceWith(t[(j + 1) % 3], x) : faceWith(x, t[(j + 2) % 3]);
        if (g < 0) break;
        if (std::uint32_t(g) == fan[0]) {
          closedFan = true;
          break;
        }
        ++reached;
        f = std::uint32_t(g);
      }
    }
    if (reached != fan.size()) return true;
  }
  return false;
}

bool Mesher::HandlePass::cutAndClose(HandleStat& st, int maxLoopEdges, bool regrowFirst) {
  std::vector<char>& alive = m_.alive_;
  const std::vector<Triangle>& tri = m_.tri_;
  PointEdgeMap& pem = m_.pem_;
  const size_t oldFaces = tri.size();
  std::vector<char> wasClosed(ring_.size());
  for (size_t i = 0; i < ring_.size(); ++i) wasClosed[i] = !pem.hasFreeEdge(ring_[i]);
  // (The hole pass indexes the live faces when it is made: before the first cut, so that it
  // finds the faces of a cut that is undone.)
  if (!m_.holePass_) m_.holePass_.reset(new HolePass(m_));
  outside_.clear();
  std::vector<std::uint32_t> touched;
  size_t regrown = 0; // faces a regrowth added (and kept)
  for (std::uint32_t f : cut_) {
    alive[f] = 0;
    pem.removeTriangle(tri[f][0], tri[f][1], tri[f][2]);
    for (std::uint32_t x : tri[f]) touched.push_back(x);
  }
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  bool ok = !anyTwoFans(touched);
  HoleStat hs;
  if (ok) {
    std::vector<std::vector<std::uint32_t>> loops;
    // A loop can run on through a hole that was there before: the faces at its points beyond
    // the region are kept too, in case the closure is undone.
    auto keepBeyond = [&]() {
      for (const auto& loop : loops)
        for (std::uint32_t x : loop)
          if (!inRing_[x]) forEachFace(x, [&](std::uint32_t f) { outside_.push_back(f); });
    };
    // (A regrowth takes loops of any length: those of up to twice the longest closed.)
    m_.boundaryLoops(touched, regrowFirst ? 2 * maxLoopEdges : maxLoopEdges, loops);
    keepBeyond();
    const bool any = !loops.empty();
    if (regrowFirst && any) {
      ok = regrow(loops, touched, regrown);
      if (ok) { // (the loops it left)
        loops.clear();
        m_.boundaryLoops(touched, maxLoopEdges, loops);
        keepBeyond();
      }
    }
    if (ok) {
      for (const auto& loop : loops) m_.holePass_->closeLoop(loop, hs);
      ok = any && hs.closed == loops.size();
    }
  }
  // The new faces are indexed at once (dead ones are skipped if this is undone), so that the
  // checks below see them.
  indexNewFaces();
  // Every point of the region and of the loops with one fan (the hole pass keeps that; checked,
  // as a cut is undone otherwise).
  if (ok) {
    std::vector<std::uint32_t> check(ring_.begin(), ring_.end());
    for (std::uint32_t f : outside_)
      for (std::uint32_t x : tri[f]) check.push_back(x);
    for (size_t f = oldFaces; f < tri.size(); ++f)
      for (std::uint32_t x : tri[f]) check.push_back(x);
    std::sort(check.begin(), check.end());
    check.erase(std::unique(check.begin(), check.end()), check.end());
    ok = !anyTwoFans(check);
    if (!ok) ++st.twoFans;
  }
  for (size_t i = 0; i < ring_.size() && ok; ++i)
    ok = !(wasClosed[i] && pem.hasFreeEdge(ring_[i]));
  // The points left with no face (all had faces): the region's and those of the faces beyond it.
  size_t lost = 0;
  if (ok) {
    std::vector<std::uint32_t> had(ring_.begin(), ring_.end());
    for (std::uint32_t f : outside_)
      for (std::uint32_t x : tri[f]) had.push_back(x);
    std::sort(had.begin(), had.end());
    had.erase(std::unique(had.begin(), had.end()), had.end());
    for (std::uint32_t x : had) lost += pem.isolated(x);
  }
  if (ok) {
    st.facesRemoved += cut_.size() + hs.facesReplaced;
    st.holesClosed += hs.closed;
    st.holeFacesAdded += hs.facesAdded + regrown;
    st.pointsLost += lost;
    return true;
  }
  // Undone: the closures' faces out (they stay in the arrays, dead), then the region's faces back
  // (the cut's and any the hole pass took out: all at the region's points).
  for (size_t f = oldFaces; f < tri.size(); ++f)
    if (alive[f]) {
      alive[f] = 0;
      pem.removeTriangle(tri[f][0], tri[f][1], tri[f][2]);
    }
  // (Only faces that were there before: a regrowth's faces at a loop's points beyond the region
  // are in outside_ too.)
  outside_.insert(outside_.end(), region_.begin(), region_.end());
  for (std::uint32_t f : outside_)
    if (f < oldFaces && !alive[f]) {
      alive[f] = 1;
      pem.addTriangle(tri[f][0], tri[f][1], tri[f][2]);
    }
  ++st.undone;
  return false;
}

void Mesher::HandlePass::at(std::uint32_t v, HandleStat& st) {
  bool again = true;
  while (again) {
    again = false;
    // An edge (v, a) is on a cycle of three edges bounding no face when v and a have more common
    // neighbours than triangles on their edge (the face ones): counted with v's neighbours marked,
    // which on a clean mesh is all the work done at a point. (nv_: v's neighbours, unsorted;
    // nt_: the triangles on each edge.)
    nv_.clear();
    nt_.clear();
    m_.pem_.forEachEdge(v, [&](std::uint32_t w, bool o, bool in) {
      nv_.push_back(w);
      nt_.push_back(std::uint8_t(int(o) + int(in)));
      mark_[w] = 1;
    });
    for (size_t i = 0; i < nv_.size() && !again; ++i) {
      const std::uint32_t a = nv_[i];
      if (a < v) continue;
      int common = 0;
      m_.pem_.forEachEdge(a, [&](std::uint32_t w, bool, bool) { common += mark_[w]; });
      if (common <= nt_[i]) continue;
      for (size_t j = 0; j < nv_.size() && !again; ++j) {
        const std::uint32_t b = nv_[j];
        if (b <= a) continue; // (each cycle once: v < a < b)
        if (!m_.pem_.used(a, b) && !m_.pem_.used(b, a)) continue;
        // A face on the three points (in either turn): the cycle bounds it.
        bool bounds = false;
        forEachFace(v, [&](std::uint32_t f) {
          const Triangle& t = m_.tri_[f];
          bounds = bounds || ((t[0] == a || t[1] == a || t[2] == a) && (t[0] == b || t[1] == b || t[2] == b));
        });
        if (bounds) continue;
        // The link of a point of degree 3 inside it (three faces round a point x): it bounds them.
        bool linkOfThree = false;
        forEachFace(v, [&](std::uint32_t f) {
          const Triangle& t = m_.tri_[f];
          if (linkOfThree || !(t[0] == a || t[1] == a || t[2] == a)) return;
          const std::uint32_t x = t[0] != v && t[0] != a ? t[0] : t[1] != v && t[1] != a ? t[1] : t[2];
          if (m_.pem_.degree(x) != 3) return;
          bool vbx = false, abx = false;
          forEachFace(x, [&](std::uint32_t g) {
            const Triangle& u = m_.tri_[g];
            const bool hasB = u[0] == b || u[1] == b || u[2] == b;
            vbx = vbx || (hasB && (u[0] == v || u[1] == v || u[2] == v));
            abx = abx || (hasB && (u[0] == a || u[1] == a || u[2] == a));
          });
          linkOfThree = vbx && abx;
        });
        if (linkOfThree) continue;
        ++st.candidates;
        gatherRegion(v);
        const int before = genus_(m_.tri_, region_);
        // Each side of the cycle in turn: v→a→b→v (its left), then v→b→a→v.
        for (int side = 0; side < 2 && before > 0 && !again; ++side) {
          const std::uint32_t p = side == 0 ? a : b, q = side == 0 ? b : a;
          cut_.clear();
          if (!leftWedge(q, v, p, cut_) || !leftWedge(v, p, q, cut_) || !leftWedge(p, q, v, cut_)) continue;
          std::sort(cut_.begin(), cut_.end());
          cut_.erase(std::unique(cut_.begin(), cut_.end()), cut_.end());
          if (cut_.empty()) continue;
          rest_.clear();
          std::set_difference(region_.begin(), region_.end(), cut_.begin(), cut_.end(), std::back_inserter(rest_));
          const int after = genus_(m_.tri_, rest_);
          if (after < 0 || after >= before) continue;
          if (cutAndClose(st, maxHoleEdges_)) {
            ++st.handles;
            again = true; // v's neighbours changed
          }
        }
        for (std::uint32_t x : ring_) inRing_[x] = 0;
      }
    }
    for (std::uint32_t x : nv_) mark_[x] = 0;
  }
}

bool Mesher::HandlePass::regrow(const std::vector<std::vector<std::uint32_t>>& loops,
                                std::vector<std::uint32_t>& touched, size_t& kept) {
  const P3* pts = m_.pts_;
  const std::vector<P3>& pos = m_.grid_.points();
  const double sp = m_.spacing_;
  P3 centre(0, 0, 0);
  size_t n = 0;
  for (const auto& loop : loops)
    for (std::uint32_t x : loop) {
      centre += pts[x];
      ++n;
    }
  centre /= double(n);
  double r = 0;
  for (const auto& loop : loops)
    for (std::uint32_t x : loop) r = std::max(r, (pts[x] - centre).Norm());
  const double reach = r + kRegrowMargin * sp;
  std::vector<std::uint32_t> ids;
  m_.grid_.forEachInBall(centre, reach, [&](std::uint32_t i, double) { ids.push_back(i); });
  if (ids.size() < 3 || ids.size() > kRegrowMaxPoints) return false;
  std::sort(ids.begin(), ids.end());
  // With the other points of their faces: every face at a point of the ball is known to the
  // growth (fixed), so that it sees which of their edges are free.
  const size_t inBall = ids.size();
  for (size_t i = 0; i < inBall; ++i)
    forEachFace(ids[i], [&](std::uint32_t f) {
      for (std::uint32_t x : m_.tri_[f]) ids.push_back(x);
    });
  std::sort(ids.begin(), ids.end());
  ids.erase(std::unique(ids.begin(), ids.end()), ids.end());
  // (Each point's place in ids, ~0u for none, until this returns.)
  if (localIndex_.empty()) localIndex_.assign(m_.grid_.size(), ~0u);
  for (size_t i = 0; i < ids.size(); ++i) localIndex_[ids[i]] = std::uint32_t(i);
  struct Unmark {
    std::vector<std::uint32_t>& index;
    const std::vector<std::uint32_t>& ids;
    ~Unmark() {
      for (std::uint32_t g : ids) index[g] = ~0u;
    }
  } unmark{localIndex_, ids};
  auto localOf = [&](std::uint32_t g) -> std::int64_t {
    const std::uint32_t i = localIndex_[g];
    return i != ~0u ? std::int64_t(i) : -1;
  };
  // The live faces with all three points among them are fixed.
  std::vector<std::uint32_t> fixed;
  for (std::uint32_t x : ids)
    forEachFace(x, [&](std::uint32_t f) {
      const Triangle& t = m_.tri_[f];
      if (localOf(t[0]) >= 0 && localOf(t[1]) >= 0 && localOf(t[2]) >= 0) fixed.push_back(f);
    });
  std::sort(fixed.begin(), fixed.end());
  fixed.erase(std::unique(fixed.begin(), fixed.end()), fixed.end());
  std::vector<P3> lp(ids.size());
  for (size_t i = 0; i < ids.size(); ++i) lp[i] = pts[ids[i]];
  Mesher local(std::move(lp), m_.params_, sp);
  const std::vector<std::uint32_t>& order = local.order();
  std::vector<std::uint32_t> inv(ids.size(), ~0u);
  for (size_t i = 0; i < order.size(); ++i) inv[order[i]] = std::uint32_t(i);
  auto toLocal = [&](std::uint32_t g) { return inv[size_t(localOf(g))]; };
  std::vector<Triangle> ft;
  ft.reserve(fixed.size());
  for (std::uint32_t f : fixed) {
    const Triangle& t = m_.tri_[f];
    const Triangle lt{toLocal(t[0]), toLocal(t[1]), toLocal(t[2])};
    if (lt[0] == ~0u || lt[1] == ~0u || lt[2] == ~0u) return false; // (a point merged in a clump)
    ft.push_back(lt);
  }
  if (!local.addFixedTriangles(ft)) return false;
  for (const auto& loop : loops)
    for (size_t i = 0; i < loop.size(); ++i) {
      const std::uint32_t v = loop[i], w = loop[(i + 1) % loop.size()];
      const std::int64_t f = faceWith(v, w);
      if (f < 0) return false;
      const Triangle& t = m_.tri_[size_t(f)];
      const std::uint32_t x = t[0] != v && t[0] != w ? t[0] : t[1] != v && t[1] != w ? t[1] : t[2];
      local.queueFrontEdge(toLocal(v), toLocal(w), toLocal(x));
    }
  local.setGrowBudget(kRegrowPopsPerPoint * ids.size());
  local.grow();
  if (local.growBudgetExhausted()) return false;
  // The new triangles, back in the mesh's points: each must stay inside the region (its points
  // with no face beyond the fixed ones), use no half-edge the mesh has, and cross no face.
  std::vector<Triangle> grown;
  for (size_t k = ft.size(); k < local.triangles().size(); ++k) {
    const Triangle& lt = local.triangles()[k];
    grown.push_back(Triangle{ids[order[lt[0]]], ids[order[lt[1]]], ids[order[lt[2]]]});
  }
  if (grown.empty()) return false;
  PointEdgeMap& pem = m_.pem_;
  for (const Triangle& t : grown) {
    for (int k = 0; k < 3; ++k) {
      if (pem.used(t[k], t[(k + 1) % 3])) return false;
      if ((pts[t[k]] - centre).Norm() > reach - kRegrowInside * sp) return false;
    }
  }
  auto box = [&](const Triangle& t, double lo[3], double hi[3]) {
    for (int d = 0; d < 3; ++d) {
      lo[d] = std::min({pts[t[0]][d], pts[t[1]][d], pts[t[2]][d]});
      hi[d] = std::max({pts[t[0]][d], pts[t[1]][d], pts[t[2]][d]});
    }
  };
  auto apart = [](const double alo[3], const double ahi[3], const double blo[3], const double bhi[3]) {
    for (int d = 0; d < 3; ++d)
      if (ahi[d] < blo[d] || bhi[d] < alo[d]) return true;
    return false;
  };
  // (Boxes made once; the fixed faces apart from all the new ones' box are not looked at.)
  struct Boxed {
    double lo[3], hi[3];
    std::uint32_t f;
  };
  std::vector<Boxed> newBoxes(grown.size()), near;
  Boxed all;
  for (size_t i = 0; i < grown.size(); ++i) {
    box(grown[i], newBoxes[i].lo, newBoxes[i].hi);
    for (int d = 0; d < 3; ++d) {
      all.lo[d] = i == 0 ? newBoxes[i].lo[d] : std::min(all.lo[d], newBoxes[i].lo[d]);
      all.hi[d] = i == 0 ? newBoxes[i].hi[d] : std::max(all.hi[d], newBoxes[i].hi[d]);
    }
  }
  for (std::uint32_t f : fixed) {
    if (!m_.alive_[f]) continue;
    Boxed b;
    box(m_.tri_[f], b.lo, b.hi);
    b.f = f;
    if (!apart(all.lo, all.hi, b.lo, b.hi)) near.push_back(b);
  }
  for (size_t i = 0; i < grown.size(); ++i) {
    const Boxed& a = newBoxes[i];
    for (const Boxed& b : near)
      if (!apart(a.lo, a.hi, b.lo, b.hi) && facesIntersect(pos, grown[i], m_.tri_[b.f])) return false;
    for (size_t j = 0; j < i; ++j)
      if (!apart(a.lo, a.hi, newBoxes[j].lo, newBoxes[j].hi) && facesIntersect(pos, grown[i], grown[j])) return false;
  }
  const size_t firstNew = m_.tri_.size();
  for (const Triangle& t : grown) {
    const auto f = static_cast<std::uint32_t>(m_.tri_.size());
    m_.tri_.push_back(t);
    m_.alive_.push_back(1);
    pem.addTriangle(t[0], t[1], t[2]);
    m_.holePass_->noteAdded(f);
    for (std::uint32_t x : t) touched.push_back(x);
  }
  indexNewFaces();
  std::sort(touched.begin(), touched.end());
  touched.erase(std::unique(touched.begin(), touched.end()), touched.end());
  // A point the growth joined by a vertex alone has two fans (sec. 4.2): the new faces of all but
  // the fan with the most faces there before (then the largest) go; loops left are closed after.
  std::vector<std::uint32_t> fan, part;
  const auto none = [](std::uint32_t) { return false; };
  for (int round = 0; round < 4; ++round) {
    bool removed = false;
    for (std::uint32_t x : touched) {
      if (fansAt(x, none, fan, part) < 2) continue;
      const size_t keep = keptFan(fan, part, firstNew);
      for (size_t i = 0; i < fan.size(); ++i)
        if (part[i] != keep && fan[i] >= firstNew) {
          const Triangle& t = m_.tri_[fan[i]];
          m_.alive_[fan[i]] = 0;
          pem.removeTriangle(t[0], t[1], t[2]);
          removed = true;
        }
    }
    if (!removed) break;
  }
  kept = 0;
  for (size_t f = firstNew; f < m_.tri_.size(); ++f) kept += m_.alive_[f] != 0;
  return true;
}

bool Mesher::HandlePass::widen(const std::vector<std::uint32_t>& loop, HandleStat& st) {
  if (loop.size() > size_t(maxHoleEdges_)) { // (a longer loop: the regrowth alone)
    blockers_.clear();
    return widenBy(loop, Widen::Regrow, st);
  }
  if (widenBy(loop, Widen::Edges, st) || widenBy(loop, Widen::Stars, st)) return true;
  // The blockers, found once for both tries (an undone try leaves the mesh as it was). (The hole
  // pass finds them: its face index holds the faces added since this one's was made.)
  if (!m_.holePass_) m_.holePass_.reset(new HolePass(m_));
  const bool any = m_.holePass_->blockers(loop, blockers_);
  if (any && (widenBy(loop, Widen::Blockers, st) || widenBy(loop, Widen::BlockerStars, st))) return true;
  if (!any) blockers_.clear();
  return widenBy(loop, Widen::Regrow, st);
}

template <class Skip>
size_t Mesher::HandlePass::fansAt(std::uint32_t x, Skip&& skip, std::vector<std::uint32_t>& fan,
                                 std::vector<std::uint32_t>& part) const {
  fan.clear();
  forEachFace(x, [&](std::uint32_t f) {
    if (!skip(f)) fan.push_back(f);
  });
  // Fans by union over the edges at x (few faces: quadratic is fine); part[i]: the fan's first face.
  part.resize(fan.size());
  for (size_t i = 0; i < fan.size(); ++i) part[i] = std::uint32_t(i);
  auto root = [&](std::uint32_t i) {
    while (part[i] != i) i = part[i];
    return i;
  };
  for (size_t i = 0; i < fan.size(); ++i)
    for (size_t j = i + 1; j < fan.size(); ++j) {
      int shared = 0;
      for (std::uint32_t u : m_.tri_[fan[i]])
        for (std::uint32_t w : m_.tri_[fan[j]]) shared += u == w;
      if (shared >= 2) {
        const std::uint32_t a = root(std::uint32_t(i)), b = root(std::uint32_t(j));
        if (a != b) part[std::max(a, b)] = std::min(a, b);
      }
    }
  size_t fans = 0;
  for (size_t i = 0; i < fan.size(); ++i) {
    part[i] = root(std::uint32_t(i));
    fans += part[i] == i;
  }
  return fans;
}

size_t Mesher::HandlePass::keptFan(const std::vector<std::uint32_t>& fan, const std::vector<std::uint32_t>& part,
                                   size_t firstNew) {
  std::vector<size_t> old(fan.size(), 0), size(fan.size(), 0);
  for (size_t i = 0; i < fan.size(); ++i) {
    ++size[part[i]];
    old[part[i]] += fan[i] < firstNew;
  }
  size_t keep = 0;
  for (size_t i = 1; i < fan.size(); ++i)
    if (old[i] > old[keep] || (old[i] == old[keep] && size[i] > size[keep])) keep = i;
  return keep;
}

void Mesher::HandlePass::splitFans() {
  // The points of the cut's faces whose other faces fall into more than one fan: the faces of all
  // but the largest fan go with the cut (sec. 4.2's rule), until every such point has one fan.
  std::vector<std::uint32_t> pts, fan, part;
  for (int round = 0; round < 8; ++round) {
    pts.clear();
    for (std::uint32_t f : cut_)
      for (std::uint32_t x : m_.tri_[f]) pts.push_back(x);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    const size_t before = cut_.size();
    for (std::uint32_t x : pts) {
      const auto inCut = [&](std::uint32_t f) { return std::binary_search(cut_.begin(), cut_.end(), f); };
      if (fansAt(x, inCut, fan, part) < 2) continue;
      const size_t keep = keptFan(fan, part, ~size_t{0});
      for (size_t i = 0; i < fan.size(); ++i)
        if (part[i] != keep) cut_.push_back(fan[i]);
    }
    if (cut_.size() == before) return;
    std::sort(cut_.begin(), cut_.end());
    cut_.erase(std::unique(cut_.begin(), cut_.end()), cut_.end());
  }
}

bool Mesher::HandlePass::widenBy(const std::vector<std::uint32_t>& loop, Widen how, HandleStat& st) {
  const size_t m = loop.size();
  cut_.clear();
  if (how == Widen::Blockers || how == Widen::BlockerStars || how == Widen::Regrow) { // (blockers_: set by widen)
    cut_.assign(blockers_.begin(), blockers_.end());
    if (how != Widen::Blockers)
      for (std::uint32_t f : blockers_)
        for (std::uint32_t x : m_.tri_[f])
          if (std::find(loop.begin(), loop.end(), x) == loop.end()) forEachFace(x, [&](std::uint32_t g) { cut_.push_back(g); });
  }
  for (size_t i = 0; i < m; ++i) {
    const std::int64_t f = faceWith(loop[i], loop[(i + 1) % m]);
    if (f < 0) return false;
    cut_.push_back(std::uint32_t(f));
  }
  if (how == Widen::Regrow) {
    const double band = kRegrowBand * m_.spacing_;
    for (std::uint32_t x : loop)
      m_.grid_.forEachInBall(m_.pts_[x], band, [&](std::uint32_t i, double) { forEachFace(i, [&](std::uint32_t f) { cut_.push_back(f); }); });
  }
  if (how == Widen::Stars || how == Widen::Regrow)
    for (std::uint32_t x : loop) forEachFace(x, [&](std::uint32_t f) { cut_.push_back(f); });
  std::sort(cut_.begin(), cut_.end());
  cut_.erase(std::unique(cut_.begin(), cut_.end()), cut_.end());
  splitFans();
  ring_.clear();
  for (std::uint32_t f : cut_)
    for (std::uint32_t x : m_.tri_[f])
      if (!inRing_[x]) {
        inRing_[x] = 1;
        ring_.push_back(x);
      }
  region_.clear();
  for (std::uint32_t x : ring_) forEachFace(x, [&](std::uint32_t f) { region_.push_back(f); });
  std::sort(region_.begin(), region_.end());
  region_.erase(std::unique(region_.begin(), region_.end()), region_.end());
  // (The wider loop runs through the faces' third points: up to twice as long.)
  const bool closed = cutAndClose(st, 2 * maxHoleEdges_, how == Widen::Regrow);
  st.regrown += closed && how == Widen::Regrow;
  for (std::uint32_t x : ring_) inRing_[x] = 0;
  return closed;
}

size_t Mesher::widenHoles(int maxHoleEdges, HoleStat& hs) {
  if (maxHoleEdges < 3) return 0;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  std::vector<std::uint32_t> seeds;
  boundarySuspects(seeds);
  if (seeds.empty()) return 0;
  std::vector<std::vector<std::uint32_t>> loops;
  boundaryLoops(seeds, 2 * maxHoleEdges, loops);
  if (loops.empty()) return 0;
  if (!handlePass_) handlePass_.reset(new HandlePass(*this, maxHoleEdges));
  HandlePass& pass = *handlePass_;
  HandleStat st;
  size_t closed = 0;
  for (const auto& loop : loops) {
    // (An earlier closure may have closed this loop too: all its half-edges still free?)
    bool open = true;
    for (size_t i = 0; i < loop.size() && open; ++i)
      open = pem_.used(loop[i], loop[(i + 1) % loop.size()]) && !pem_.used(loop[(i + 1) % loop.size()], loop[i]);
    if (open && pass.widen(loop, st)) ++closed;
  }
  hs.closed += closed;
  hs.widened += closed;
  hs.widenedFaces += st.facesRemoved;
  hs.regrown += st.regrown;
  hs.facesAdded += st.holeFacesAdded;
  hs.facesReplaced += st.facesRemoved;
  hs.spikes += st.pointsLost;
  return closed;
}

Mesher::HandleStat Mesher::removeSmallHandles(const BoundaryCount& boundary, int maxHoleEdges) {
  HandleStat st;
  if (alive_.size() != tri_.size()) assignHuge(alive_, tri_.size(), char(1));
  st.handlesBefore = handleCount(boundary);
  if (st.handlesBefore == 0 || maxHoleEdges < 3) return st;
  // The paper's growth alone (no thin-part rule acted, no face taken out, none added by a repair)
  // is not scanned: its handles are taken as the object's. On clean closed clouds the scan cuts
  // nothing and only costs time; the small handles come where the repairs or the thin-part rules
  // acted.
  const bool plainGrowth = foldsRefused_ + otherSheetBalls_ == 0 && tri_.size() == grownTriangles_ &&
                           std::find(alive_.begin(), alive_.end(), char(0)) == alive_.end();
  if (plainGrowth) return st;
  if (!handlePass_) handlePass_.reset(new HandlePass(*this, maxHoleEdges));
  for (std::uint32_t v = 0; v < grid_.size(); ++v) handlePass_->at(v, st);
  return st;
}

void Mesher::PassDeleter::operator()(HolePass* p) const { delete p; }
void Mesher::PassDeleter::operator()(HandlePass* p) const { delete p; }

} // namespace g2s
} // namespace growth
