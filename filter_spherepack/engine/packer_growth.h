#pragma once
// The sphere packer's disk growing, sec. 3.4-3.6 (sec. 3.3 places its starting vertices): one
// vertex candidate after the other by priority, each checked and inserted or dropped.
#include "packer_steps.h"

#include "candidates.h"
#include "crossing.h"
#include <growth/bucket_queue.h>
#include <growth/error.h>
#include "vertex_grid.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

namespace growth {
namespace spherepack {
namespace detail {

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
    // Reserve for the estimate and a quarter more, so that the arrays are not copied as they grow
    // (a reserve beyond what is used is address space, never written).
    const size_t reserve = std::min<size_t>(expected_ + expected_ / 4, p.maxOutputVertices);
    vgrid_.reset(grid.indexer().origin(), crossingSearchRadius(d), reserve);
    graph_.reserve(reserve);
  }

  const BorderGraph& graph() const { return graph_; }
  // Frees the graph's rotations and normals (after the regions are triangulated), then the graph.
  void releaseAdjacency() { graph_.releaseAdjacency(); }
  void releaseGraph() { graph_ = BorderGraph(); }
  bool anyVertexCloserThan(const Vec3d& x, double r) const {
    return vgrid_.anyCloserThan(x, r, graph_.positions(), kNoVertex, kNoVertex);
  }
  const SplatVertexLists& lists() const { return lists_; }
  // Frees what only the growth uses (vertex grid, splat vertex lists, queue): the graph G stays.
  void releaseSearch() {
    vgrid_ = VertexGrid();
    lists_ = SplatVertexLists();
    queue_.release();
    std::vector<std::uint32_t>().swap(near_);
    std::vector<Found>().swap(found_);
  }
  // Bytes of the growth's arrays (graph, vertex grid, splat vertex lists, candidate queue).
  size_t memoryBytes() const {
    return graph_.memoryBytes() + vgrid_.memoryBytes() + lists_.memoryBytes() + queue_.memoryBytes();
  }

  // Keep features (Params::keepFeatures): the patch of every splat (cloud_features.h; kNoVertex:
  // every patch, away from the creases). A vertex takes its splat's patch, a feature vertex none
  // (it belongs to every patch); a candidate is
  // taken only when each parent is on its splat's patch or a feature vertex, so no face joins two
  // sides of a crease, and the crossing check leaves out the edges of other patches (seen
  // edge-on across the crease), as the remesher does. Null (the default): no patches.
  void setPatches(const std::vector<std::uint32_t>* patch) { patch_ = patch; }
  // Sec. 3.3 with more than two starting vertices: a feature vertex at x with normal n, unless a
  // vertex is closer than d (then kNoVertex). Its candidates are enumerated by enumerateFeature()
  // once all feature vertices and edges are in.
  // `sides`: per patch, the direction across the crease into it (CloudFeatures::sidesAt), the
  // crease running along the unit vector t there; a candidate of a listed patch with this vertex as
  // a parent must lie on that side of it: its offset from the vertex, without its part along t,
  // within 60 degrees of the side's direction (a splat tilted across the crease, as estimated
  // normals are there, runs past it out of the side's plane).
  std::uint32_t addFeatureVertex(const Vec3d& x, const Vec3d& n,
                                 std::vector<std::pair<std::uint32_t, Vec3d>> sides = {},
                                 const Vec3d& t = Vec3d(0, 0, 0)) {
    if (anyVertexCloserThan(x, d_)) return kNoVertex;
    const std::uint32_t v = insertVertex(x, 0, &n, /*enumerateLater=*/true, /*feature=*/true);
    if (!sides.empty()) {
      if (featureSides_.size() <= v) featureSides_.resize(v + 1), featureDirs_.resize(v + 1, Vec3d(0, 0, 0));
      featureSides_[v] = std::move(sides);
      featureDirs_[v] = t;
    }
    return v;
  }
  // An edge of a crease line between two feature vertices.
  bool addFeatureEdge(std::uint32_t u, std::uint32_t v) {
    const auto& pos = graph_.positions();
    return graph_.addEdge(u, graph_.gapOf(u, pos[v]), v, graph_.gapOf(v, pos[u]));
  }
  void enumerateFeature(std::uint32_t v) { enumerate(v); }

  // Sec. 3.3: the two starting vertices (already projected onto their splats).
  void start(const Vec3d& s1, std::uint32_t splat1, const Vec3d& s2, std::uint32_t splat2) {
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

      Vec3d x;
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
      const std::uint32_t patch = patch_ != nullptr ? (*patch_)[cd.splat] : kNoVertex;
      if (patch_ != nullptr && (!onPatch(cd.a, patch) || !onPatch(cd.b, patch))) continue;
      // Sec. 3.6, fig. 4b: projected along the approximated surface normal, the new edges must not
      // cross existing edges within d in normal direction.
      const Vec3d n = normalAt(x, cd.splat);
      // One look-up for the crossing check and, when x is inserted, its candidates (enumerate()
      // needs the vertices within 2d, inside the crossing radius).
      nearby.clear();
      nearbyD2.clear();
      vgrid_.forEachInBall(x, crossingSearchRadius(d_), pos, [&](std::uint32_t v, double d2) {
        nearby.push_back(v);
        nearbyD2.push_back(d2);
      });
      const auto samePatch = [&](std::uint32_t u) { return onPatch(u, patch); };
      if (patch_ != nullptr ? newEdgesCrossIf(graph_, x, cd.a, cd.b, n, d_, nearby,
                                              [&](std::uint32_t u, std::uint32_t w) { return samePatch(u) && samePatch(w); })
                            : newEdgesCross(graph_, x, cd.a, cd.b, n, d_, nearby)) {
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
  // all vertices lying in b_j"; in a two-sided box, of the layer the splat's side is in), or the
  // splat normal when that box refers to no point.
  Vec3d normalAt(const Vec3d& x, std::uint32_t splat) const {
    const int box = grid_.boxOf(x, in_.normals[splat]);
    return box >= 0 ? grid_.boxNormal(box) : in_.normals[splat];
  }

  std::uint32_t insertVertex(const Vec3d& x, std::uint32_t splat, const Vec3d* normal = nullptr,
                             bool enumerateLater = false, bool feature = false) {
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
    if (patch_ != nullptr) vpatch_.push_back(feature ? std::uint32_t(kNoVertex) : (*patch_)[splat]);
    if (!enumerateLater) enumerate(v);
    return v;
  }

  // Sec. 3.5 priority of a candidate at x with parents a and b, from the current graph.
  // With feature lines (keepFeatures found some) the splits of distance 1 to kAlikeSplitDistance are
  // alike.
  int levelOf(std::uint32_t a, std::uint32_t b, const Vec3d& x) const {
    return CandidatePriority::of(graph_, a, b, x, w_, alike());
  }
  // The same, given the corners of a and b that x falls into.
  int levelOf(std::uint32_t a, std::uint32_t b, int gapA, int gapB) const {
    return CandidatePriority::of(graph_, a, b, gapA, gapB, w_, alike());
  }
  int alike() const { return patch_ != nullptr ? kAlikeSplitDistance : 0; }

  // Sec. 3.4/4.4: new candidates with v as a parent, from the splats near v and their vertex lists.
  // near_: the vertices within 2d of v when nearKnown (a superset does as well), else looked up.
  void enumerate(std::uint32_t v, bool nearKnown = false) {
    const auto& pos = graph_.positions();
    const Vec3d x = pos[v];
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
    const Vec3d& nv = graph_.normal(v);
    enumerateCandidates(v, pos, nv, d_, grid_, splats_, lists_,
                        [&](std::uint32_t u, std::uint32_t s, int root, const Vec3d& y) {
                          if (patch_ != nullptr && (!onPatch(v, (*patch_)[s]) || !onPatch(u, (*patch_)[s]) ||
                                                    !onSide(v, (*patch_)[s], y) || !onSide(u, (*patch_)[s], y)))
                            return;
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
    Vec3d y;
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
  const std::vector<std::uint32_t>* patch_ = nullptr;
  std::vector<std::uint32_t> vpatch_; // with patches: per vertex its patch, kNoVertex for a feature vertex
  // kNoVertex as a patch: every patch (a splat away from the creases, a feature vertex).
  bool onPatch(std::uint32_t v, std::uint32_t patch) const {
    return patch == kNoVertex || vpatch_[v] == kNoVertex || vpatch_[v] == patch;
  }
  std::vector<std::vector<std::pair<std::uint32_t, Vec3d>>> featureSides_; // per feature vertex (addFeatureVertex)
  std::vector<Vec3d> featureDirs_;                                          // and the crease's direction there
  bool onSide(std::uint32_t v, std::uint32_t patch, const Vec3d& y) const {
    if (v >= featureSides_.size()) return true;
    Vec3d o = y - graph_.position(v);
    o -= featureDirs_[v] * (o * featureDirs_[v]);
    for (const auto& e : featureSides_[v])
      if (e.first == patch) return o * e.second > 0.5 * o.Norm();
    return true;
  }
  Progress& progress_;
  const size_t expected_;
  SplatSet splats_;
  SplatVertexLists lists_;
  VertexGrid vgrid_;
  BorderGraph graph_;
  BucketQueue<Candidate> queue_;
  std::vector<std::uint32_t> near_;
};

} // namespace detail
} // namespace spherepack
} // namespace growth
