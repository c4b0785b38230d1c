#include "sphere_packer.h"

#include "borders.h"
#include "box_grid.h"
#include <growth/bucket_queue.h>
#include "candidates.h"
#include <growth/cloud_scale.h>
#include "crossing.h"
#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/manifold_cleanup.h>
#include <growth/mesh_measures.h>
#include <growth/mesh_normals.h>
#include <growth/morton.h>
#include <growth/parallel.h>
#include <growth/point_grid.h>
#include <growth/progress.h>
#include <growth/radix_order.h>
#include <growth/self_intersections.h>
#include "region_triangulation.h"
#include "splats.h"
#include <growth/stopwatch.h>
#include "stored_positions.h"
#include "vertex_grid.h"

#include <common/ml_mesh_type.h>
#include <vcg/complex/allocate.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

namespace growth {
namespace spherepack {

namespace {

// First neighbourhood of the local splat radii (splats.h): twice a typical Voronoi radius.
constexpr double kSplatFirstReachPerAreaSpacing = 2.5;
// Splats with a radius above this many d are referred to by the boxes their disk comes near
// (BoxGrid::build's extraReach); smaller ones by the boxes their centre is within d of, as in the
// paper (a location on the surface is nearly always covered by a nearby point's splat as well).
constexpr double kLargeSplatPerD = 1.0;
// A start after the first (sec. 3.3 again) keeps this many d from every vertex: two spacings or
// so more than the d that any vertex keeps, so that no start lands on a second layer of a surface
// already meshed (the flaps on the bunny's misregistered scans lie 0.4-2 d off the mesh, median 0.84 d).
constexpr double kStartClearancePerD = 2.0;
constexpr double kTriangleAreaFactor = 0.86602540378443864676; // √3/2: area per vertex of a d-lattice is (√3/2)·d²

// Unoriented normals (a sign that changes from point to point) are told from thin parts and folds,
// which also make boxes see two sides (BoxGrid's d-too-large count), by the points' nearest
// neighbours: their normals point to opposite sides for about half of the points when the signs
// are random, and for almost none on an oriented cloud (the nearest neighbour of a point of a thin
// part lies on the same side). Checked when at least kTwoSidedBoxShareToCheck of the boxes see two
// sides; the normals look unoriented when at least kOppositeNeighbourShare of the points have an
// opposite nearest neighbour.
constexpr double kTwoSidedBoxShareToCheck = 0.1;
constexpr double kOppositeNeighbourShare = 0.2;
constexpr size_t kOrientationSamples = 4096;

// Share of the sampled points (a fixed stride) whose nearest other point has a normal with a
// negative product with theirs. `cell`: the grid's cell size (about the spacing).
double oppositeNeighbourShare(const std::vector<vcg::Point3d>& points, const std::vector<vcg::Point3d>& normals,
                              double cell) {
  if (points.size() < 2 || !(cell > 0)) return 0;
  PointGrid grid;
  grid.build(points, cell);
  const size_t stride = std::max<size_t>(1, points.size() / kOrientationSamples);
  size_t sampled = 0, opposite = 0;
  for (size_t i = 0; i < points.size(); i += stride) {
    const int j = grid.nearest(points[i], nullptr, int(i));
    if (j < 0) continue;
    ++sampled;
    opposite += normals[i] * normals[size_t(j)] < 0 ? 1 : 0;
  }
  return sampled > 0 ? double(opposite) / double(sampled) : 0;
}

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

// A queued vertex candidate: its parents (a made it when it was inserted), the splat it lies on
// and which of the two circle–plane intersections it is. The position is recomputed bit for bit
// when it is popped (candidates.h), so an entry takes 16 bytes instead of 40.
struct Candidate {
  std::uint32_t a, b, splat;
  std::uint8_t root;
};

// The disk growing of sec. 3.3–3.6 on prepared splats and box grid.
class Growth {
public:
  static constexpr std::uint32_t kNoVertex = 0xffffffffu;
  Growth(const InputCloud& in, const BoxGrid& grid, const std::vector<float>& radius, double d, const Params& p,
         Stat& st, Progress& progress, size_t expectedVertices)
      : in_(in), grid_(grid), radius_(radius), d_(d), d2_(d * d), w_(p.windowSize), params_(p), st_(st),
        progress_(progress), expected_(std::max<size_t>(expectedVertices, 16)),
        queue_(CandidatePriority::levels(p.windowSize)) {
    splats_ = SplatSet{&in.points, &in.normals, &radius};
    lists_.reset(in.points.size());
    // Cells of the crossing check's radius (√5·d): its ball then meets at most 3 × 3 × 3 cells
    // (at most 4 × 4 × 4 with cells of 2d), and the ball of radius d of the distance check
    // (sec. 3.6), the most frequent query, at most 2 × 2 × 2.
    // Reserve for the estimate, within reason (the estimate can be high on noisy clouds).
    const size_t reserve = std::min<size_t>(expected_ + expected_ / 4, size_t(1) << 21);
    vgrid_.reset(grid.indexer().origin(), crossingSearchRadius(d), reserve);
    graph_.reserve(reserve);
  }

  const BorderGraph& graph() const { return graph_; }
  bool anyVertexCloserThan(const vcg::Point3d& x, double r) const {
    return vgrid_.anyCloserThan(x, r, graph_.positions(), kNoVertex, kNoVertex);
  }
  const SplatVertexLists& lists() const { return lists_; }

  // Sec. 3.3: the two starting vertices (already projected onto their splats).
  void start(const vcg::Point3d& s1, std::uint32_t splat1, const vcg::Point3d& s2, std::uint32_t splat2) {
    insertVertex(s1, splat1);
    insertVertex(s2, splat2);
  }

  // Sec. 3.4–3.6: pop candidates by priority until none is left.
  void run() {
    size_t pops = 0;
    std::vector<std::uint32_t> nearby;
    std::vector<double> nearbyD2;
    while (!queue_.empty()) {
      int popped = 0;
      const Candidate cd = queue_.pop(&popped);
      if ((++pops & 31) == 0)
        progress_.update(std::min(0.99, double(graph_.vertexCount()) / double(expected_)));

      vcg::Point3d x;
      const auto& pos = graph_.positions();
      const ParentCircle circle = parentCircle(pos[cd.a], pos[cd.b], d_);
      if (!circleSplatPoint(circle, in_.points[cd.splat], in_.normals[cd.splat], radius_[cd.splat], cd.root, x))
        continue; // cannot happen: the same computation succeeded when it was queued

      // Sec. 3.6: no vertex closer than d.
      if (vgrid_.anyCloserThan(x, d_, pos, cd.a, cd.b)) {
        ++st_.rejectedTooClose;
        continue;
      }
      // Sec. 3.6: a candidate whose priority got worse since it was queued goes to its new level.
      // (The corners of the parents the new edges go into, from the graph as it is now: the
      // priority's and the insertion's.)
      const int gapA = graph_.gapOf(cd.a, x), gapB = graph_.gapOf(cd.b, x);
      const int level = levelOf(cd.a, cd.b, gapA, gapB);
      if (level > popped) {
        queue_.push(level, cd);
        ++st_.requeued;
        ++st_.candidates;
        continue;
      }
      if (graph_.degree(cd.a) >= BorderGraph::kMaxDegree || graph_.degree(cd.b) >= BorderGraph::kMaxDegree) continue;
      // Sec. 3.6, fig. 4b: projected along the approximated surface normal, the new edges must not
      // cross existing edges within d in normal direction.
      const vcg::Point3d n = normalAt(x, cd.splat);
      // One look-up for the crossing check and, when x is inserted, its candidates (enumerate()
      // needs the vertices within 2d, inside the crossing radius).
      nearby.clear();
      nearbyD2.clear();
      vgrid_.forEachInBall(x, crossingSearchRadius(d_), pos, [&](std::uint32_t v, double d2) {
        nearby.push_back(v);
        nearbyD2.push_back(d2);
      });
      if (newEdgesCross(graph_, x, cd.a, cd.b, n, d_, nearby)) {
        ++st_.rejectedCrossing;
        continue;
      }
      // The corners chosen at the parents (in their own planes, sec. 3.5) must also hold the new
      // edges in the projection along n used for the crossing check; when they do not, the edge
      // is too steep for the local normals to tell its side, and inserting it would twist the
      // borders (a choice where the paper is silent, for the manifold guarantee of sec. 3.1).
      if (params_.rejectTwisted && (!graph_.gapContains(cd.a, gapA, x, n) || !graph_.gapContains(cd.b, gapB, x, n))) {
        ++st_.rejectedInconsistent;
        continue;
      }
      const std::uint32_t c = insertVertex(x, cd.splat, &n, /*enumerateLater=*/true);
      if (!graph_.connect(c, cd.a, gapA, cd.b, gapB))
        throw std::logic_error("sphere packing: could not connect a new vertex"); // degrees checked above
      if (params_.checkInvariants) checkInvariants(c, cd.a, cd.b);
      near_.clear();
      for (size_t k = 0; k < nearby.size(); ++k)
        if (nearbyD2[k] <= 4 * d2_) near_.push_back(nearby[k]);
      enumerate(c, /*nearKnown=*/true);
    }
  }

private:
  // Vertex normal: the box normal of the box containing x (sec. 4.1: "used as vertex normal for
  // all vertices lying in b_j"), or the splat normal when that box refers to no point.
  vcg::Point3d normalAt(const vcg::Point3d& x, std::uint32_t splat) const {
    const int box = grid_.boxOf(x);
    return box >= 0 ? grid_.boxNormal(box) : in_.normals[splat];
  }

  std::uint32_t insertVertex(const vcg::Point3d& x, std::uint32_t splat, const vcg::Point3d* normal = nullptr,
                             bool enumerateLater = false) {
    // The limit checked before the growth bounds the surface area estimated from the points; the
    // splats can cover more (large splats on a noisy or thick cloud: a fuzz input estimated at
    // under 10,000 vertices grew 51,000), so it is enforced here too.
    if (graph_.vertexCount() >= params_.maxOutputVertices)
      throw Error("The mesh grew past the limit of " + std::to_string(params_.maxOutputVertices) +
                  " vertices (the estimate from the cloud's surface area was about " + fmt(double(expected_)) +
                  "): the splats cover more than the points' surface. Use a larger sphere diameter d or a "
                  "smaller splat size.");
    const std::uint32_t v = graph_.addVertex(x, normal != nullptr ? *normal : normalAt(x, splat));
    vgrid_.insert(v, x);
    if (!enumerateLater) enumerate(v);
    return v;
  }

  // Sec. 3.5 priority of a candidate at x with parents a and b, from the current graph.
  int levelOf(std::uint32_t a, std::uint32_t b, const vcg::Point3d& x) const {
    const int da = graph_.degree(a), db = graph_.degree(b);
    if (da <= 1 || db <= 1) return CandidatePriority::level(da, db, 0, w_);
    return levelOf(a, b, graph_.gapOf(a, x), graph_.gapOf(b, x));
  }
  // The same, given the corners of a and b that x falls into.
  int levelOf(std::uint32_t a, std::uint32_t b, int gapA, int gapB) const {
    const int da = graph_.degree(a), db = graph_.degree(b);
    if (da <= 1 || db <= 1) return CandidatePriority::level(da, db, 0, w_);
    const int dist = w_ > 0 ? graph_.borderDistance(a, gapA, b, gapB, w_) : 0;
    return CandidatePriority::level(da, db, dist, w_);
  }

  // Sec. 3.4/4.4: new candidates with v as a parent, from the splats near v and their vertex lists.
  // near_: the vertices within 2d of v when nearKnown (a superset does as well), else looked up.
  void enumerate(std::uint32_t v, bool nearKnown = false) {
    const auto& pos = graph_.positions();
    const vcg::Point3d x = pos[v];
    if (!nearKnown) {
      near_.clear();
      vgrid_.forEachInBall(x, 2 * d_, pos, [&](std::uint32_t u, double) { near_.push_back(u); });
    }
    // The circle of v and a partner u crosses the surface about twice, once on each side of the
    // edge v–u; where splats overlap, several of them give a candidate at nearly the same place.
    // Of those (same partner, same side, within d/2 of each other), the one nearest to its
    // splat's point is queued: the splat is the best approximation of the surface there, and the
    // queue does not carry the others only to drop them as too close when popped.
    found_.clear();
    const vcg::Point3d& nv = graph_.normal(v);
    enumerateCandidates(v, pos, d_, grid_, splats_, lists_,
                        [&](std::uint32_t u, std::uint32_t s, int root, const vcg::Point3d& y) {
                          // A candidate already closer than d to a vertex can never be inserted
                          // (vertices are never removed): drop it now instead of when popped.
                          for (std::uint32_t w : near_)
                            if (w != v && w != u && (pos[w] - y).SquaredNorm() < d2_) return;
                          const double score = (y - in_.points[s]).SquaredNorm();
                          const bool side = (((pos[u] - x) ^ (y - x)) * nv) >= 0;
                          for (Found& f : found_)
                            if (f.u == u && f.side == side && (f.y - y).SquaredNorm() < 0.25 * d2_) {
                              if (score < f.score) f = Found{y, score, u, s, std::uint8_t(root), side};
                              return;
                            }
                          found_.push_back(Found{y, score, u, s, std::uint8_t(root), side});
                        });
    for (const Found& f : found_) {
      queue_.push(levelOf(v, f.u, f.y), Candidate{v, f.u, f.splat, f.root});
      ++st_.candidates;
    }
  }
  struct Found {
    vcg::Point3d y;
    double score;
    std::uint32_t u, splat;
    std::uint8_t root;
    bool side;
  };
  std::vector<Found> found_;

  // The positions are doubles: a distance between two of them is exact only to a few units in the
  // last place of their coordinates, which on far-off clouds (geo-referenced, or 7e13 from the
  // origin with d = 1.6e10, fuzz/regressions/cloud/spherepack_invariant_1e10) is more than a
  // relative 1e-12 of d. The tolerances add 16 such units of the largest coordinate involved.
  void checkInvariants(std::uint32_t c, std::uint32_t a, std::uint32_t b) const {
    const auto& pos = graph_.positions();
    const auto ulps = [&](std::uint32_t v) {
      double m = 0;
      for (std::uint32_t u : {v, c})
        for (int k = 0; k < 3; ++k) m = std::max(m, std::abs(pos[u][k]));
      return 16 * std::numeric_limits<double>::epsilon() * m;
    };
    for (std::uint32_t v = 0; v < c; ++v) {
      const double dist = (pos[v] - pos[c]).Norm();
      if (dist < d_ * (1 - 1e-12) - ulps(v))
        throw std::logic_error("sphere packing invariant: vertices " + std::to_string(v) + " and " +
                               std::to_string(c) + " are " + fmt(dist) + " < d apart");
    }
    for (std::uint32_t p : {a, b}) {
      const double len = (pos[p] - pos[c]).Norm();
      if (std::abs(len - d_) > 1e-9 * d_ + ulps(p))
        throw std::logic_error("sphere packing invariant: edge of length " + fmt(len) + " != d");
    }
  }

  const InputCloud& in_;
  const BoxGrid& grid_;
  const std::vector<float>& radius_;
  const double d_, d2_;
  const int w_;
  const Params& params_;
  Stat& st_;
  Progress& progress_;
  const size_t expected_;
  SplatSet splats_;
  SplatVertexLists lists_;
  VertexGrid vgrid_;
  BorderGraph graph_;
  BucketQueue<Candidate> queue_;
  std::vector<std::uint32_t> near_;
};

// The points renumbered in a spatial order, for memory locality on large clouds: by the Morton
// code of their boxes of side d, equal codes in input order. Everything the method does in an
// order of the points keeps the input order through these maps (box lists, ties of neighbours
// and of the starting vertex), so the mesh is the same as without renumbering. Small clouds fit
// in the caches and are not renumbered (orig/rank stay empty: identity): Params::spatialOrderMinPoints,
// 20,000 by default (torus, 2 threads: 10k and 20k the same time either way, 30k -4 %, 100k -7 %,
// 1M -12 %).
struct Renumbering {
  std::vector<std::uint32_t> orig; // new index -> input index (until the starting vertices)
  std::vector<std::uint32_t> rank; // input index -> new index (for the box grid)
  std::uint32_t origOf(std::uint32_t i) const { return orig.empty() ? i : orig[i]; }
  std::uint32_t rankOf(std::uint32_t k) const { return rank.empty() ? k : rank[k]; }
};

Renumbering spatialOrder(InputCloud& in, double d, size_t minPoints) {
  Renumbering r;
  const size_t n = in.points.size();
  if (n < std::max<size_t>(minPoints, 2)) return r;
  // Box coordinates (at most 21 bits each, as the box grid's), interleaved.
  HugeVector<std::uint64_t> code(n);
  std::uint64_t maxCode = 0;
  for (size_t i = 0; i < n; ++i) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::min<std::uint64_t>(std::uint64_t(std::max(0.0, std::floor((in.points[i][a] - in.box.min[a]) / d))),
                                     (std::uint64_t(1) << 21) - 1);
    code[i] = mortonCode(c[0], c[1], c[2]);
    maxCode = std::max(maxCode, code[i]);
  }
  // Stable order of the codes (equal codes in input order).
  int bits = 0;
  while (bits < 64 && (maxCode >> bits) != 0) ++bits;
  reserveHuge(r.orig, n, /*populate=*/true); // written whole: resident in one call (huge_pages.h)
  stableRadixOrder(code.data(), n, bits, r.orig);
  reserveHuge(r.rank, n, /*populate=*/true);
  r.rank.resize(n);
  for (size_t i = 0; i < n; ++i) r.rank[r.orig[i]] = static_cast<std::uint32_t>(i);
  // Permute the arrays in place, cycle by cycle (no second copy of them: the peak memory).
  std::vector<bool> done(n, false);
  for (size_t start = 0; start < n; ++start) {
    if (done[start]) continue;
    const vcg::Point3d p0 = in.points[start], n0 = in.normals[start];
    size_t i = start;
    for (;;) {
      done[i] = true;
      const size_t from = r.orig[i];
      if (from == start) break;
      in.points[i] = in.points[from];
      in.normals[i] = in.normals[from];
      i = from;
    }
    in.points[i] = p0;
    in.normals[i] = n0;
  }
  return r;
}

// Closest splat to x (smallest distance to its disk) and the projection of x onto it (sec. 3.3).
// The splats of the box containing x (all points within d of it) are searched; when x is farther
// than d from every point, all splats are when `searchAll` (user-given points), none otherwise.
bool projectOntoClosestSplat(const vcg::Point3d& x, const InputCloud& in, const std::vector<float>& radius,
                             const BoxGrid& grid, const Renumbering& order, bool searchAll, vcg::Point3d& proj,
                             std::uint32_t& splat) {
  double best = std::numeric_limits<double>::infinity();
  std::int64_t bestIdx = -1;
  auto consider = [&](std::uint32_t i) {
    const double dd = squaredDistanceToDisk(x, in.points[i], in.normals[i], radius[i]);
    if (dd < best) best = dd, bestIdx = i;
  };
  const int box = grid.boxOf(x);
  if (box >= 0) {
    for (const std::uint32_t* it = grid.pointsBegin(box); it != grid.pointsEnd(box); ++it) consider(*it);
  }
  if (bestIdx < 0 && searchAll) // all points: of equally close ones, the first in input order
    for (std::uint32_t i = 0; i < in.points.size(); ++i) {
      const double dd = squaredDistanceToDisk(x, in.points[i], in.normals[i], radius[i]);
      if (dd < best || (dd == best && bestIdx >= 0 && order.origOf(i) < order.origOf(std::uint32_t(bestIdx))))
        best = dd, bestIdx = i;
    }
  if (bestIdx < 0) return false;
  splat = static_cast<std::uint32_t>(bestIdx);
  proj = projectOntoDisk(x, in.points[splat], in.normals[splat], radius[splat]);
  return true;
}

// A starting pair (sec. 3.3): two positions on splats, between d and 2d apart.
struct StartPair {
  vcg::Point3d s1, s2;
  std::uint32_t splat1 = 0, splat2 = 0;
};

// Sec. 3.3 at input point i: s1 = p_i on its own splat, s2 the projection onto the closest splat
// of a point 1.5·d away in p_i's tangent plane (12 directions tried in turn), between d and 2d
// from s1. Both must pass `free` (no vertex closer than d). False when p_i is isolated (fewer
// than 3 other points within d: no part that can hold a triangle) or no direction works.
template <class Free>
bool startPairAt(std::uint32_t i, const InputCloud& in, const std::vector<float>& radius, const BoxGrid& grid,
                 const Renumbering& order, double d, Free&& free, StartPair& out) {
  const vcg::Point3d& p = in.points[i];
  const int box = grid.boxOf(p);
  if (box < 0) return false;
  int around = 0;
  for (const std::uint32_t* it = grid.pointsBegin(box); it != grid.pointsEnd(box) && around < 4; ++it)
    around += (in.points[*it] - p).SquaredNorm() <= d * d ? 1 : 0;
  if (around < 4 || !free(p)) return false;
  vcg::Point3d e1, e2;
  tangentFrame(in.normals[i], e1, e2);
  for (int k = 0; k < 12; ++k) {
    const double phi = 2 * 3.14159265358979323846 * k / 12;
    const vcg::Point3d target = p + (e1 * std::cos(phi) + e2 * std::sin(phi)) * (1.5 * d);
    vcg::Point3d q;
    std::uint32_t sq = 0;
    if (!projectOntoClosestSplat(target, in, radius, grid, order, false, q, sq)) continue;
    const double dist = (q - p).Norm();
    if (dist >= d && dist <= 2 * d && free(q)) {
      out = StartPair{p, q, i, sq};
      return true;
    }
  }
  return false;
}

// Drops the connected pieces of `faces` with fewer than minFaces faces, except the largest (the
// first of equal ones). Pieces are joined through shared vertices: after the manifold clean-up
// every vertex has one fan of faces, so these are the edge-connected pieces (mesh_measures.h).
// The order of the faces kept is unchanged. Returns the number of pieces dropped.
size_t dropSmallComponents(std::vector<Triangle>& faces, size_t vertexCount, size_t minFaces,
                           size_t& facesDropped) {
  facesDropped = 0;
  if (minFaces <= 1 || faces.empty()) return 0;
  std::vector<std::uint32_t> parent(vertexCount);
  for (std::uint32_t v = 0; v < vertexCount; ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  auto unite = [&](std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  for (const Triangle& f : faces) unite(f[0], f[1]), unite(f[1], f[2]);
  std::vector<std::uint32_t> count(vertexCount, 0);
  std::uint32_t largest = find(faces[0][0]);
  for (const Triangle& f : faces) {
    const std::uint32_t r = find(f[0]);
    if (++count[r] > count[largest]) largest = r;
  }
  size_t dropped = 0;
  for (std::uint32_t v = 0; v < vertexCount; ++v)
    dropped += parent[v] == v && count[v] > 0 && count[v] < minFaces && v != largest ? 1 : 0;
  if (dropped == 0) return 0;
  size_t w = 0;
  for (const Triangle& f : faces) {
    const std::uint32_t r = find(f[0]);
    if (count[r] >= minFaces || r == largest) faces[w++] = f;
  }
  facesDropped = faces.size() - w;
  faces.resize(w);
  return dropped;
}

} // namespace

CloudScale cloudScale(const std::vector<vcg::Point3d>& points, int threads) {
  CloudScale sc;
  // 8,000 samples (3,000 of them with a local fit) are enough for medians within about 1 %
  // (docs/sampling-estimate.md); more only cost time (the default 20,000 were 8 % of a 30k run).
  SamplingOptions options;
  options.maxSamples = 8000;
  options.maxNoiseSamples = 3000;
  const SamplingEstimate e = estimateSampling(points, options, threads);
  if (!(e.areaPerPoint > 0) || !std::isfinite(e.areaPerPoint)) return sc;
  sc.spacing = e.spacing;
  sc.meanSpacing = e.meanSpacing;
  sc.areaSpacing = std::sqrt(e.areaPerPoint);
  sc.area = e.areaPerPoint * double(points.size());
  sc.noise = std::isfinite(e.noise) ? e.noise : 0.0;
  return sc;
}

double defaultDiameter(const CloudScale& scale) {
  return std::max(kDefaultDiameterPerAreaSpacing * scale.areaSpacing, kDefaultDiameterPerNoise * scale.noise);
}

std::string defaultDiameterReason(const CloudScale& scale) {
  if (kDefaultDiameterPerNoise * scale.noise > kDefaultDiameterPerAreaSpacing * scale.areaSpacing)
    return "from the noise: 3 x the estimated noise bound (at least 2x, sec. 5.3; larger than the sampling's " +
           fmt(kDefaultDiameterPerAreaSpacing * scale.areaSpacing) + ")";
  return "from the sampling: 1.8 x sqrt(area per point) (the noise asks for at least " +
         fmt(kDefaultDiameterPerNoise * scale.noise) + ")";
}

double defaultSplatSize(const CloudScale& scale, double d) {
  const double s = kDefaultSplatPerAreaSpacing * scale.areaSpacing;
  return s > 0 ? s : d;
}

Params suggestParams(const CMeshO& cloud) {
  Params p;
  try {
    CloudCheck check;
    check.needNormals = false;
    check.allowFaces = true;
    InputCloud in = readCloud(cloud, check);
    const CloudScale sc = cloudScale(in.points);
    if (sc.areaSpacing > 0 && std::isfinite(sc.areaSpacing)) {
      p.sphereDiameter = defaultDiameter(sc);
      p.splatSize = defaultSplatSize(sc, p.sphereDiameter);
    }
  } catch (const std::exception&) {
    // An unusable cloud: keep the static defaults; build() will explain what is wrong.
  }
  return p;
}

namespace {

// The phases of build(), in the order of the paper's method.

// The sizes the method runs at.
struct Sizes {
  CloudScale scale;    // the cloud's sampling and noise
  double d = 0;        // sphere diameter: the edge length
  double s = 0;        // splat size (sec. 4.3)
  double expected = 0; // vertices expected: the surface area over the area per vertex of a d-lattice
};

// Input: the cloud's points and normals, checked (what sec. 3.1 assumes of the input).
InputCloud readInput(const CMeshO& cloud, Stat& st) {
  CloudCheck check;
  check.needNormals = true;
  check.allowFaces = false;
  check.minPoints = 3;
  InputCloud in = readCloud(cloud, check);
  st.inputPoints = static_cast<size_t>(cloud.vn);
  st.duplicatesDropped = in.duplicatesDropped;
  return in;
}

// Sec. 3.1, 4.3 and 5.3: the parameters checked, the sphere diameter d (given, or from the sampling
// and the noise), the splat size s, and the vertices expected within Params::maxOutputVertices.
Sizes chooseSizes(const InputCloud& in, const Params& params, Stat& st) {
  if (params.windowSize < 0 || params.windowSize > 1000)
    throw Error("The window size w must be between 0 and 1000 (the paper uses 8).");
  if (params.minComponentFaces < 0)
    throw Error("The smallest piece to keep must be 0 faces (keep all) or more.");
  if (params.maxBorderLength < 3)
    throw Error("The border limit must be at least 3 (a triangle); the paper uses 40.");
  Sizes z;
  z.scale = cloudScale(in.points, params.threads);
  const CloudScale& scale = z.scale;
  const double diag = in.box.Diag();
  st.scale = scale;
  double d = params.sphereDiameter;
  st.diameterReason = "given";
  if (!(d > 0)) {
    d = defaultDiameter(scale);
    st.diameterReason = defaultDiameterReason(scale);
    if (!(d > 0) || !std::isfinite(d))
      throw Error("Could not estimate the point spacing of this cloud (too few points with neighbours around "
                  "them): give the sphere diameter d by hand.");
  }
  if (!std::isfinite(d) || !(d > 0)) throw Error("The sphere diameter d must be a positive number.");
  if (d > 0.5 * diag) {
    const double automatic = defaultDiameter(scale);
    if (!(params.sphereDiameter > 0) || !(automatic <= 0.5 * diag))
      // The cloud's own sampling asks for edges longer than the cloud.
      throw Error("Too few points, or too sparse, for a mesh: the automatic sphere diameter d = " + fmt(automatic) +
                  " (from the spacing of the " + std::to_string(in.points.size()) + " points) is larger than "
                  "the cloud (bounding box diagonal " + fmt(diag) + "). Give a d below " + fmt(0.5 * diag) +
                  " by hand, or use a denser cloud.");
    throw Error("The sphere diameter d = " + fmt(d) + " is larger than the cloud (bounding box diagonal " +
                fmt(diag) + "): no mesh with edges that long fits on it. Use a smaller d, e.g. the default " +
                fmt(automatic) + ".");
  }
  double s = params.splatSize;
  if (!(s > 0)) s = defaultSplatSize(scale, d);
  if (!std::isfinite(s)) throw Error("The splat radius s must be a positive number.");
  st.sphereDiameter = d;
  st.splatSize = s;

  const double area = scale.area;
  const double expected = area / (d * d * kTriangleAreaFactor);
  if (expected > double(params.maxOutputVertices)) {
    const double dMin = std::sqrt(area / (double(params.maxOutputVertices) * kTriangleAreaFactor));
    throw Error("The sphere diameter d = " + fmt(d) + " is too small for this cloud: the mesh would have about " +
                fmt(expected) + " vertices (surface area about " + fmt(area) + " / (d²·√3/2)), more than the limit of " +
                std::to_string(params.maxOutputVertices) + ". Use a larger d (at least about " + fmt(dMin) +
                "; the default for this cloud is " + fmt(defaultDiameter(scale)) + ").");
  }
  z.d = d;
  z.s = s;
  z.expected = expected;
  return z;
}

// Sec. 4.3: the splat radii, from the points' own neighbourhoods (independent of d).
std::vector<float> splatRadii(const InputCloud& in, const Sizes& z, const Params& params, const Renumbering& order,
                              Stat& st, Progress& progress) {
  SplatSizeStats splatStats;
  std::vector<float> radius =
      computeSplatRadii(in.points, in.normals, z.s, kSplatFirstReachPerAreaSpacing * z.scale.areaSpacing,
                        params.localSplatSizes, &splatStats, &progress, params.threads,
                        order.orig.empty() ? nullptr : &order.orig);
  st.meanSplatRadius = splatStats.meanRadius;
  st.splatsUnbounded = splatStats.unbounded;
  st.splatsClamped = splatStats.clamped;
  return radius;
}

// Sec. 4.1: the box grid, normal filter and box normals. A splat larger than d is referred to by
// every box it comes within d of (sec. 4.4 needs all splats within d of a vertex), not only by
// those its centre is within d of. The normals of the boxes holding input points are deferred:
// computed on another thread while the growth (one thread) runs, which asks for them as it goes
// (BoxGrid::startNormals).
void buildBoxGrid(BoxGrid& grid, const InputCloud& in, const std::vector<float>& radius, double d,
                  const Params& params, const Renumbering& order, Stat& st, Progress& progress) {
  std::vector<float> extraReach;
  {
    size_t large = 0;
    for (float r : radius) large += r > kLargeSplatPerD * d ? 1 : 0;
    if (large > 0) {
      extraReach.assign(radius.size(), 0.0f);
      for (size_t i = 0; i < radius.size(); ++i)
        if (radius[i] > kLargeSplatPerD * d) extraReach[i] = radius[i];
    }
  }
  grid.build(in.points, in.normals, d, &progress, params.threads, /*deferNormals=*/true,
             order.rank.empty() ? nullptr : &order.rank, extraReach.empty() ? nullptr : &extraReach);
  std::vector<float>().swap(extraReach);
  st.boxes = grid.boxCount();
}

// Sec. 3.3: the first starting pair, projected onto their closest splats, between d and 2d apart:
// the user's two points, or "around the maximum z-coordinate of the input".
StartPair firstStartPair(const InputCloud& in, const std::vector<float>& radius, const BoxGrid& grid,
                         const Renumbering& order, double d, double s, const Params& params) {
  StartPair first;
  bool haveFirst = false;
  auto noVertexYet = [](const vcg::Point3d&) { return true; };
  if (params.useStartPoints) {
    for (const auto& q : params.startPoint)
      if (!std::isfinite(q[0]) || !std::isfinite(q[1]) || !std::isfinite(q[2]))
        throw Error("The starting points must have finite coordinates.");
    projectOntoClosestSplat(params.startPoint[0], in, radius, grid, order, true, first.s1, first.splat1);
    projectOntoClosestSplat(params.startPoint[1], in, radius, grid, order, true, first.s2, first.splat2);
    const double dist = (first.s1 - first.s2).Norm();
    if (dist < d || dist > 2 * d)
      throw Error("The two starting points, projected onto their closest splats, are " + fmt(dist) +
                  " apart; they must be between d = " + fmt(d) + " and 2d = " + fmt(2 * d) +
                  " apart (paper, section 3.3). Move them, or let the filter choose them.");
    haveFirst = true;
  } else {
    // Automatic: the highest points in turn; when none of the 64 highest can start, the first
    // usable point in input order.
    std::vector<std::uint32_t> highest;
    reserveHuge(highest, in.points.size(), /*populate=*/true);
    highest.resize(in.points.size());
    for (std::uint32_t i = 0; i < highest.size(); ++i) highest[i] = i;
    const size_t tries = std::min<size_t>(highest.size(), 64);
    std::partial_sort(highest.begin(), highest.begin() + std::ptrdiff_t(tries), highest.end(),
                      [&](std::uint32_t a, std::uint32_t b) {
                        return in.points[a][2] != in.points[b][2] ? in.points[a][2] > in.points[b][2]
                                                                  : order.origOf(a) < order.origOf(b);
                      });
    for (size_t t = 0; t < tries && !haveFirst; ++t)
      haveFirst = startPairAt(highest[t], in, radius, grid, order, d, noVertexYet, first);
    for (std::uint32_t k = 0; k < in.points.size() && !haveFirst; ++k)
      haveFirst = startPairAt(order.rankOf(k), in, radius, grid, order, d, noVertexYet, first);
    if (!haveFirst)
      throw Error("Could not place two starting vertices between d and 2d apart anywhere on the cloud: d = " +
                  fmt(d) + " is probably too large for it, or the splats too small (s = " + fmt(s) +
                  "). Try the default d, or give the starting points by hand.");
  }
  return first;
}

// Sec. 3.4–3.6: the disk growing from the first pair; then sec. 3.3 again on every further part of
// the cloud. When the growth has stopped and points are left that no vertex reached, a new
// starting pair on the first of them in input order (every point is tried once, so the scan is
// linear), at least kStartClearancePerD·d from every vertex placed so far: a point with a vertex
// between d and that far lies on a surface already meshed there (a misregistered second scan
// layer, or the rim of a gap the growth left), and a start on it would only grow a separate sheet
// over or beside the mesh (docs/spherepack-components.md).
void growEveryPart(Growth& growth, const StartPair& first, const InputCloud& in, const std::vector<float>& radius,
                   const BoxGrid& grid, const Renumbering& order, double d, Stat& st) {
  growth.start(first.s1, first.splat1, first.s2, first.splat2);
  growth.run();
  st.componentsStarted = 1;
  bool nearMesh = false;
  auto farFromVertices = [&](const vcg::Point3d& x) {
    if (growth.anyVertexCloserThan(x, d)) return false;
    if (!growth.anyVertexCloserThan(x, kStartClearancePerD * d)) return true;
    nearMesh = true;
    return false;
  };
  for (std::uint32_t k = 0; k < in.points.size(); ++k) {
    const std::uint32_t i = order.rankOf(k);
    if (!growth.lists().empty(i)) continue;
    StartPair pair;
    nearMesh = false;
    if (!startPairAt(i, in, radius, grid, order, d, farFromVertices, pair)) {
      st.startsRefusedNearMesh += nearMesh ? 1 : 0;
      continue;
    }
    growth.start(pair.s1, pair.splat1, pair.s2, pair.splat2);
    growth.run();
    ++st.componentsStarted;
  }
}

// Sec. 3.7: the regions the borders enclose, triangulated (up to Params::maxBorderLength edges;
// longer borders are left as holes).
std::vector<Triangle> triangulate(const BorderGraph& g, const Params& params, Stat& st) {
  EdgeSet edges(g.edgeCount() * 2 + 16);
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    for (int k = 0; k < g.degree(v); ++k)
      if (v < g.neighbour(v, k)) edges.insert(v, g.neighbour(v, k));
  std::vector<Triangle> faces;
  faces.reserve(2 * g.vertexCount() + 16);
  const RegionStats rs = triangulateRegions(g.borders(), g.positions(), g.normals(), params.maxBorderLength, edges, faces);
  st.holes = rs.holes;
  st.longestBorder = rs.longestBorder;
  st.meanBorderLength = rs.borders > 0 ? double(rs.borderEdges) / double(rs.borders) : 0;
  return faces;
}

// Sec. 3.1's manifold guarantee made unconditional: it holds for a suitable d on a cloud sampling a
// manifold; elsewhere (noise beyond d/2, thin parts, misregistered scans, flipped normals) the
// growth's checks and the ear cut of sec. 3.7 can leave a vertex with two fans of faces or an edge
// with three. The fewest faces are removed: the extra fans of every non-manifold vertex (Robust
// G2S, sec. 4.2: growth/manifold_cleanup.h), which removes every face beyond two at an edge too.
// Every edge left is still an edge of the packing (>= d). Then no two faces may intersect (two
// sheets of a thin part or of misregistered scans meshed through each other, a fold of the ear
// cut): of each intersecting pair, faces are removed greedily (the one in most pairs first,
// growth/self_intersections.h), and the fans that this leaves at a vertex are cleaned up again.
void makeManifold(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, Stat& st) {
  std::vector<char> alive(faces.size(), 1);
  ManifoldCleanupStat mc = removeNonManifoldVertices(faces, g.vertexCount(), alive);
  st.nonManifoldVerticesRemoved = mc.nonManifoldVertices;
  st.facesRemoved = mc.facesRemoved;
  // On the positions as the output stores them (float in MeshLab 2020.09): rounding must not make
  // faces that nearly touch intersect.
  st.selfIntersectionFacesRemoved =
      removeSelfIntersections(asStored<CMeshO::ScalarType>(g.positions()), faces, alive, params.threads);
  if (st.selfIntersectionFacesRemoved > 0) {
    mc = removeNonManifoldVertices(faces, g.vertexCount(), alive);
    st.nonManifoldVerticesRemoved += mc.nonManifoldVertices;
    st.facesRemoved += mc.facesRemoved + st.selfIntersectionFacesRemoved;
  }
  if (st.facesRemoved > 0) {
    size_t w = 0;
    for (size_t f = 0; f < faces.size(); ++f)
      if (alive[f]) faces[w++] = faces[f];
    faces.resize(w);
  }
}

// Pieces too small to be a part of the surface: flaps grown onto a misregistered second scan
// layer, cut off from the mesh by the regions left open between the layers, and bits of stray
// points (docs/spherepack-components.md). Whole pieces go, so the rest keeps every guarantee.
void dropSmallPieces(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, Stat& st) {
  if (params.minComponentFaces > 1)
    st.componentsDropped = dropSmallComponents(faces, g.vertexCount(), size_t(params.minComponentFaces),
                                               st.componentFacesDropped);
}

// Input points no vertex came within d of.
size_t unreachedPoints(const Growth& growth, size_t points) {
  size_t unreached = 0;
  for (std::uint32_t i = 0; i < points; ++i) {
    unreached += growth.lists().empty(i) ? 1 : 0;
  }
  return unreached;
}

// Output: referenced vertices only (in the order of creation), the mesh's own normals, the
// triangle quality Q_t of sec. 5 per face; its topology measured.
void writeMesh(const std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, CMeshO& out,
               Stat& st) {
  std::vector<std::int32_t> remap;
  assignHuge(remap, g.vertexCount(), std::int32_t(-1));
  std::vector<std::uint32_t> used;
  reserveHuge(used, g.vertexCount(), /*populate=*/true); // all of it but unreferenced vertices
  for (const auto& f : faces)
    for (std::uint32_t v : f)
      if (remap[v] < 0) {
        remap[v] = static_cast<std::int32_t>(used.size());
        used.push_back(v);
      }
  // Deterministic vertex order: by the order of creation.
  std::sort(used.begin(), used.end());
  for (size_t i = 0; i < used.size(); ++i) remap[used[i]] = static_cast<std::int32_t>(i);

  if (!faces.empty()) {
    // Exact sizes reserved first: the vectors are allocated once and made resident in one call.
    reserveHuge(out.vert, used.size(), /*populate=*/true);
    auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(out, used.size());
    for (size_t i = 0; i < used.size(); ++i, ++vi) vi->P() = CMeshO::CoordType::Construct(g.position(used[i]));
    out.face.EnableQuality();
    reserveHuge(out.face, faces.size(), /*populate=*/true); // (vcglib's reserve reserves the quality vector too)
    prefault(out.face.QV.data(), faces.size() * sizeof(out.face.QV[0]));
    auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(out, faces.size());
    double qsum = 0, minEdge = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < faces.size(); ++k, ++fi) {
      const auto& f = faces[k];
      for (int j = 0; j < 3; ++j) fi->V(j) = &out.vert[size_t(remap[f[j]])];
      const vcg::Point3d a = g.position(f[0]), b = g.position(f[1]), c = g.position(f[2]);
      const double l1 = (b - a).SquaredNorm(), l2 = (c - b).SquaredNorm(), l3 = (a - c).SquaredNorm();
      const double area2 = ((b - a) ^ (c - a)).Norm();
      const double q = (l1 + l2 + l3) > 0 ? 2 * std::sqrt(3.0) * area2 / (l1 + l2 + l3) : 0;
      fi->Q() = static_cast<CMeshO::ScalarType>(q);
      qsum += q;
      minEdge = std::min(minEdge, std::sqrt(std::min(l1, std::min(l2, l3))));
    }
    // Face and vertex normals of the mesh itself (angle-weighted), so that it shades as it comes
    // out; the box normals stay the growth's.
    // (With the topology check, which only reads the faces' vertices, on a second thread.)
    MeshTopology topo;
    parallelFor(2, parallelParts(2, params.threads, 1), [&](size_t t0, size_t t1, int) {
      for (size_t t = t0; t < t1; ++t) {
        if (t == 0) updateNormals(out);
        else topo = measureTopology(out);
      }
    });
    st.qualityAvg = qsum / double(faces.size());
    st.smallestEdge = minEdge;
    st.nonManifoldVertices = topo.nonManifoldVertices;
    st.nonManifoldEdges = topo.nonManifoldEdges;
    st.boundaryLoops = topo.boundaryLoops;
  }
  st.vertices = used.size();
  st.faces = faces.size();
}

// The report: warnings on what the cloud made the method do (unoriented normals, d too large for
// sec. 4.1's normal filter, faces removed, points unreached), and the errors of a non-manifold or
// empty result.
void report(const InputCloud& in, const CloudScale& scale, double d, double s, const BorderGraph& g,
            bool noFaces, Stat& st) {
  const double opposite = double(st.boxesDTooLarge) >= kTwoSidedBoxShareToCheck * double(st.boxes)
                              ? oppositeNeighbourShare(in.points, in.normals, scale.spacing)
                              : 0.0;
  if (opposite >= kOppositeNeighbourShare)
    st.warnings.push_back("The normals look unoriented: for " + fmt(100 * opposite) + " % of the points the "
                          "nearest point's normal points to the other side, and in " +
                          std::to_string(st.boxesDTooLarge) + " of " + std::to_string(st.boxes) + " boxes the "
                          "normals within d disagree, so the mesh has holes there. Orient them consistently "
                          "(Filters > Normals, Curvatures and Orientation > Compute normals for point sets "
                          "propagates one orientation) and run the filter again.");
  else if (st.boxesDTooLarge > 0)
    st.warnings.push_back("In " + std::to_string(st.boxesDTooLarge) + " of " + std::to_string(st.boxes) +
                          " boxes the point normals within d disagree (the box sees two sides of the surface): "
                          "d = " + fmt(d) + " is too large there for the paper's manifold guarantee (section 4.1): "
                          "thin parts, folds, or normals not consistently oriented. Try a smaller d, or "
                          "re-orient the normals.");
  if (st.facesRemoved > 0)
    st.warnings.push_back("The packing was not manifold at " + std::to_string(st.nonManifoldVerticesRemoved) +
                          " vertices and had " + std::to_string(st.selfIntersectionFacesRemoved) +
                          " faces through others; " + std::to_string(st.facesRemoved) + " faces were removed "
                          "there (the fewest that make it manifold and free of intersections), leaving holes. "
                          "Usual causes: noise beyond d/2 (paper, section 5.3: use a larger d), thin parts (a "
                          "smaller d), misregistered scans.");
  if (st.nonManifoldVertices > 0 || st.nonManifoldEdges > 0) // cannot happen: makeManifold
    throw std::logic_error("sphere packing: the output is not manifold after the clean-up");
  if (st.unreachedPoints * 100 > in.points.size())
    st.warnings.push_back(fmt(100.0 * double(st.unreachedPoints) / double(in.points.size())) +
                          " % of the points have no vertex within d: parts too small or too sparse to hold a "
                          "triangle of side d (a growth was started on every part that could), or the growth "
                          "was stopped by a defect there.");
  if (noFaces)
    throw Error("No triangle could be built: the growth stopped after " + std::to_string(g.vertexCount()) +
                " vertices. d = " + fmt(d) + " and s = " + fmt(s) + " do not fit this cloud: the splats must cover "
                "the surface, and the noise must stay below d/2 (paper, section 5.3). Try the defaults, or a larger d.");
}

} // namespace

// The method's phases in the paper's order; each phase's time goes to its Stat::seconds* field.
void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& st, vcg::CallBackPos* cb) {
  Stopwatch watch;
  out.Clear();
  st = Stat();
  Progress progress(cb);

  // Input and sizes; the points renumbered in a spatial order (the same mesh, faster).
  progress.phase("Sphere packing: reading the cloud", 0, 2);
  InputCloud in = readInput(cloud, st);
  const Sizes sizes = chooseSizes(in, params, st);
  const CloudScale& scale = sizes.scale;
  const double d = sizes.d, s = sizes.s, expected = sizes.expected;
  std::vector<int>().swap(in.vertexIndex); // not needed here
  Renumbering order = spatialOrder(in, d, params.spatialOrderMinPoints);

  // Sec. 4.3: splat radii.
  progress.phase("Sphere packing: splat sizes", 2, 10);
  st.secondsInput = watch.lap();
  const std::vector<float> radius = splatRadii(in, sizes, params, order, st, progress);
  st.secondsSplats = watch.lap();

  // Sec. 4.1: box grid.
  progress.phase("Sphere packing: box grid", 10, 20);
  BoxGrid grid;
  buildBoxGrid(grid, in, radius, d, params, order, st, progress);
  st.secondsBoxGrid = watch.lap();

  // Sec. 3.3: start.
  progress.phase("Sphere packing: starting vertices", 20, 21);
  const StartPair first = firstStartPair(in, radius, grid, order, d, s, params);

  // Sec. 3.4-3.6: growth of the front, on every part of the cloud; meanwhile the deferred box
  // normals (sec. 4.1) on another thread, those near the start first (the growth spreads from there).
  grid.startNormals(params.threads, first.s1);
  progress.phase("Sphere packing: growing", 21, 92);
  Growth growth(in, grid, radius, d, params, st, progress, static_cast<size_t>(expected));
  growEveryPart(growth, first, in, radius, grid, order, d, st);
  std::vector<std::uint32_t>().swap(order.orig);
  std::vector<std::uint32_t>().swap(order.rank);
  const BorderGraph& g = growth.graph();
  grid.finishNormals();
  st.boxesDTooLarge = grid.dTooLargeCount();
  st.secondsGrowth = watch.lap();

  // Sec. 3.7: region triangulation.
  progress.phase("Sphere packing: triangulating the regions", 92, 97);
  std::vector<Triangle> faces = triangulate(g, params, st);
  st.secondsTriangulation = watch.lap();

  // Clean-up: manifold and free of self-intersections (sec. 3.1's guarantee on any input), no small pieces.
  makeManifold(faces, g, params, st);
  dropSmallPieces(faces, g, params, st);
  st.secondsCleanup = watch.lap();

  // Output and report.
  progress.phase("Sphere packing: writing the mesh", 97, 100);
  st.unreachedPoints = unreachedPoints(growth, in.points.size());
  writeMesh(faces, g, params, out, st);
  report(in, scale, d, s, g, faces.empty(), st);
  st.secondsOutput = watch.lap();
  st.seconds = watch.total();
}

} // namespace spherepack
} // namespace growth
