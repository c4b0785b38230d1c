#pragma once
// Vertex candidates of the sphere-packing mesher (Lipschütz et al., sec. 3.3, fig. 4c, sec. 4.4).
//
// A vertex candidate is a position at distance exactly d from two existing vertices (its parents)
// that lies on a splat. The positions at distance d from parents a and b form a circle in their
// bisector plane: centre (a + b)/2, radius sqrt(d² − |ab|²/4) (empty when |ab| > 2d). A splat's
// plane cuts that circle in at most two points; those inside the splat's disk are candidates
// (fig. 4c).
//
// Sec. 4.4: for a new vertex v, the splats within distance d of v are found among the splats of
// the box containing v (sec. 4.1), and every splat keeps the list of the vertices within distance
// d of it; the partners of v are read from those lists. enumerateCandidates() does both: it visits
// the splats of v's box within d of v, reports the candidates of v with every vertex already in
// the splat's list, and adds v to the list. (The paper calls the splats near v "a subset of the
// splats associated to the box containing v"; we take it literally: a splat counts for v when its
// point is in v's box and its disk comes within d of v.)
#include "box_grid.h"
#include "splats.h"

#include <growth/vec3.h>

#include <cmath>
#include <algorithm>
#include <cstdint>
#include <memory>
#include <vector>

namespace growth {

// Circle of the points at distance d from both a and b.
struct ParentCircle {
  Vec3d centre{0, 0, 0};
  Vec3d axis{0, 0, 1};   // (b − a)/|b − a|
  double radius = 0;
  bool valid = false;
};

inline ParentCircle parentCircle(const Vec3d& a, const Vec3d& b, double d) {
  ParentCircle c;
  const Vec3d ab = b - a;
  const double len2 = ab.SquaredNorm();
  const double r2 = d * d - 0.25 * len2;
  if (!(len2 > 0) || r2 < 0) return c;
  c.centre = (a + b) * 0.5;
  c.axis = ab / std::sqrt(len2);
  c.radius = std::sqrt(r2);
  c.valid = true;
  return c;
}

// Where the circle meets the plane through p with unit normal n (sec. 4.4, fig. 4c).
// In the circle's plane (orthogonal to the axis u), with w = n − <n,u>u, the line of the splat
// plane is {y : <y, w> = −<centre − p, n>}; its points at distance r from the centre are
// y = α ŵ ± t (u × ŵ), α = −<centre − p, n>/|w|, t = sqrt(r² − α²): base ± t·v. False when the
// circle misses the plane (or lies in it, or is parallel to it).
struct CirclePlaneMeet {
  Vec3d base, v;
  double t = 0;
  Vec3d root(int r) const { return base + v * (r == 0 ? -t : t); } // root 0 takes −t
};
inline bool circleMeetsPlane(const ParentCircle& c, const Vec3d& p, const Vec3d& n, CirclePlaneMeet& m) {
  if (!c.valid) return false;
  const Vec3d w = n - c.axis * (n * c.axis);
  const double wlen = w.Norm();
  if (!(wlen > 1e-12)) return false;
  const Vec3d wh = w / wlen;
  const double alpha = -((c.centre - p) * n) / wlen;
  const double t2 = c.radius * c.radius - alpha * alpha;
  if (t2 < 0) return false;
  m.t = std::sqrt(t2);
  m.v = c.axis ^ wh;
  m.base = c.centre + wh * alpha;
  return true;
}

// One of the (at most two) points where the circle meets the plane through p with unit normal n:
// root 0 or 1. False when there is none, or when the point is farther than s from p (outside the
// splat's disk).
inline bool circleSplatPoint(const ParentCircle& c, const Vec3d& p, const Vec3d& n, double s, int root,
                             Vec3d& out) {
  CirclePlaneMeet m;
  if (!circleMeetsPlane(c, p, n, m)) return false;
  out = m.root(root);
  return (out - p).SquaredNorm() <= s * s;
}

// Both roots; returns how many lie in the disk (written to out/rootOut in root order). A tangent
// circle (t = 0) gives one point. The same values as circleSplatPoint() for root 0 and 1.
inline int circleSplatIntersections(const ParentCircle& c, const Vec3d& p, const Vec3d& n, double s,
                                    Vec3d out[2], int rootOut[2]) {
  CirclePlaneMeet m;
  if (!circleMeetsPlane(c, p, n, m)) return 0;
  const double s2 = s * s;
  int k = 0;
  for (int root = 0; root < 2; ++root) {
    const Vec3d x = m.root(root);
    if (!((x - p).SquaredNorm() <= s2)) continue;
    if (k == 1 && root == 1 && (x - out[0]).SquaredNorm() == 0) break; // tangent: one point
    out[k] = x;
    rootOut[k] = root;
    ++k;
  }
  return k;
}

// Sec. 4.4: for every splat, the vertices within distance d of it, as linked chunks of three
// vertices (16 bytes per chunk, about 5.5 bytes per entry, 4 per splat for its head; no per-splat
// vector) in fixed-size blocks, so growing never copies nor doubles the pool. A chunk is filled
// from its first slot on, the unused slots hold kEmpty; iteration visits the newest first.
// The chunks are written in order: the pages of a block are made resident a run of 64 KiB ahead
// of the writes (one call per run instead of a fault per 4 KiB page, huge_pages.h), so at most
// one run is resident unused.
class SplatVertexLists {
public:
  void reset(size_t splats) {
    assignHuge(head_, splats, std::int32_t(-1));
    blocks_.clear();
    chunks_ = 0;
    entries_ = 0;
  }
  void add(std::uint32_t splat, std::uint32_t vertex) {
    ++entries_;
    const std::int32_t h = head_[splat];
    if (h >= 0) {
      Chunk& c = chunk(size_t(h));
      for (int k = 1; k < kSlots; ++k)
        if (c.vertex[k] == kEmpty) {
          c.vertex[k] = vertex;
          return;
        }
    }
    if ((chunks_ & kRunMask) == 0) {
      if ((chunks_ & kBlockMask) == 0) blocks_.emplace_back(new Chunk[kBlockSize]);
      // The run and the page after it (a block need not start on a page: the run's last,
      // partial page is then covered here too), within the block.
      const size_t left = kBlockSize - (chunks_ & kBlockMask);
      prefault(&chunk(chunks_), std::min(kRunSize + kPageChunks, left) * sizeof(Chunk));
    }
    Chunk& c = chunk(chunks_);
    c.vertex[0] = vertex;
    for (int k = 1; k < kSlots; ++k) c.vertex[k] = kEmpty;
    c.next = h;
    head_[splat] = static_cast<std::int32_t>(chunks_);
    ++chunks_;
  }
  template <class F>
  void forEach(std::uint32_t splat, F&& f) const {
    for (std::int32_t e = head_[splat]; e >= 0;) {
      const Chunk& c = chunk(size_t(e));
      for (int k = kSlots - 1; k >= 0; --k)
        if (c.vertex[k] != kEmpty) f(c.vertex[k]);
      e = c.next;
    }
  }
  bool empty(std::uint32_t splat) const { return head_[splat] < 0; }
  size_t entries() const { return entries_; }
  size_t memoryBytes() const { return head_.capacity() * 4 + blocks_.size() * kBlockSize * sizeof(Chunk); }

private:
  static constexpr int kSlots = 3;
  static constexpr std::uint32_t kEmpty = 0xffffffffu; // never a vertex id (Growth::kNoVertex)
  struct Chunk {
    std::uint32_t vertex[kSlots];
    std::int32_t next;
  };
  static constexpr size_t kBlockBits = 15, kBlockSize = size_t(1) << kBlockBits, kBlockMask = kBlockSize - 1;
  static constexpr size_t kRunSize = size_t(4096), kRunMask = kRunSize - 1; // 64 KiB of chunks
  static constexpr size_t kPageChunks = 4096 / sizeof(Chunk);
  Chunk& chunk(size_t i) { return blocks_[i >> kBlockBits][i & kBlockMask]; }
  const Chunk& chunk(size_t i) const { return blocks_[i >> kBlockBits][i & kBlockMask]; }
  std::vector<std::int32_t> head_;
  std::vector<std::unique_ptr<Chunk[]>> blocks_;
  size_t chunks_ = 0, entries_ = 0;
};

// The splats: centres, unit normals, radii.
struct SplatSet {
  const std::vector<Vec3d>* centre = nullptr;
  const std::vector<Vec3d>* normal = nullptr;
  const std::vector<float>* radius = nullptr;
};

// For the new vertex `v` at x = vertexPos[v] with normal nv: visits the splats of the box
// containing x (of its layer facing nv, when the box is two-sided) that are within distance d of x
// (in box order); for each, calls
//     emit(partner, splat, root, position)
// for every candidate with parents (v, partner), partner taken from the splat's list (vertices
// within d of the splat, added before v), then adds v to the list. Returns the number of splats
// within d of x.
template <class Emit>
size_t enumerateCandidates(std::uint32_t v, const std::vector<Vec3d>& vertexPos, const Vec3d& nv,
                           double d, const BoxGrid& grid, const SplatSet& splats, SplatVertexLists& lists,
                           Emit&& emit) {
  const Vec3d& x = vertexPos[v];
  const int box = grid.boxOf(x, nv);
  if (box < 0) return 0;
  size_t near = 0;
  const double d2 = d * d;
  // The circle of each partner, computed once (a partner is usually listed by many splats): a
  // direct-mapped memo on the partner's id (a collision only recomputes the same circle).
  constexpr std::uint32_t kSlots = 64;
  std::uint32_t cachedId[kSlots];
  ParentCircle cachedCircle[kSlots];
  for (std::uint32_t k = 0; k < kSlots; ++k) cachedId[k] = v; // v is never its own partner
  auto circleOf = [&](std::uint32_t u) -> const ParentCircle& {
    const std::uint32_t k = u & (kSlots - 1);
    if (cachedId[k] != u) {
      cachedId[k] = u;
      cachedCircle[k] = parentCircle(x, vertexPos[u], d);
    }
    return cachedCircle[k];
  };
  for (const std::uint32_t* it = grid.pointsBegin(box); it != grid.pointsEnd(box); ++it) {
    const std::uint32_t s = *it;
    const Vec3d& p = (*splats.centre)[s];
    const Vec3d& n = (*splats.normal)[s];
    const double r = (*splats.radius)[s];
    if (squaredDistanceToDisk(x, p, n, r) > d2) continue;
    ++near;
    lists.forEach(s, [&](std::uint32_t u) {
      const ParentCircle& c = circleOf(u);
      if (!c.valid) return;
      // Quick rejections: a point of the disk on the circle is within r of p, so the disk must
      // reach the circle's plane and come within r of the circle's centre ring.
      const Vec3d pm = p - c.centre;
      const double along = pm * c.axis;
      if (along > r || along < -r) return;
      const double reach = c.radius + r;
      if (pm.SquaredNorm() > reach * reach) return;
      Vec3d pos[2];
      int root[2];
      const int k = circleSplatIntersections(c, p, n, r, pos, root);
      for (int j = 0; j < k; ++j) emit(u, s, root[j], pos[j]);
    });
    lists.add(s, v);
  }
  return near;
}

} // namespace growth
