#include "g2s_mesher.h"

#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h> // growth::Random
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>     // growth::robustBox, roughSpacing, trimmedMeanSpacing

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace growth {
namespace g2s {

namespace {
// orientComponents: a piece with a free edge is a sheet, oriented by the layer's normals where it
// has them, when it encloses less than this fraction of the volume of a sphere of its area.
constexpr double kSheetEnclosure = 0.2;
} // namespace


Mesher::Mesher(std::vector<P3> points, const Params& params, double spacing)
    : params_(params), thin_(params.thinPartRules), spacing_(spacing), queue_(std::max(1, params.sizeLevels * params.flatnessLevels)) {
  const size_t given = points.size();
  if (spacing_ > 0) {
    grid_.build(std::move(points), kCellSpacings * spacing_);
  } else {
    // Spacing unknown: build with a guess from the bulk of the cloud (robustBox: one far point
    // would make the bounding box's guess huge), measure the spacing on the grid, and rebuild
    // only when the guess was far off. The robust box is the bulk's box widened by its extent on
    // every side: a third of its diagonal is the bulk's.
    const Box3d bulk = robustBox(points, 4096);
    size_t inside = 0;
    for (const P3& p : points) inside += bulk.IsIn(p) ? 1 : 0;
    const double guess = 0.5 * roughSpacing(bulk, std::max<size_t>(inside, 2)) / 3.0;
    grid_.build(std::move(points), kCellSpacings * guess);
    spacing_ = sampleSpacing();
    const double cellWanted = kCellSpacings * spacing_;
    const double ratio = grid_.cellSize() / cellWanted;
    if (spacing_ > 0 && (ratio < 0.5 || ratio > 2.0)) {
      const std::vector<std::uint32_t> first = grid_.order();
      grid_.build(std::vector<P3>(grid_.points()), cellWanted);
      std::vector<std::uint32_t> composed(given);
      for (size_t i = 0; i < given; ++i) composed[i] = first[grid_.order()[i]];
      grid_.setOrder(std::move(composed));
    }
  }
  if (!(spacing_ > 0)) spacing_ = std::max(grid_.cellSize() / kCellSpacings, 1e-300);
  if (params_.mergeClumps) mergeClumps();
  const size_t n = grid_.size();
  pts_ = grid_.points().data();
  grid_.setVisitCounter(&visited_);
  pem_.reset(n);
  assignHuge(edgeLengthSum_, n, 0.f);
  assignHuge(edgeCount_, n, std::uint16_t(0));
  assignHuge(crossing_, n, std::uint8_t(0));
  assignHuge(freeEdges_, n, std::uint16_t(0));
  assignHuge(faceAt_, n, std::uint32_t(kNoFace));
  assignHuge(onSurface_, n, std::uint8_t(0));
  for (int k = 1; k < params_.flatnessLevels; ++k)
    cosLimit_.push_back(std::cos(3.14159265358979323846 * double(k) / double(params_.flatnessLevels)));
  // A closed surface has 2N − 4 + 4g triangles: room for 2N + 16, made resident at once (an
  // unmeshed part of it costs 12 bytes per point at most, below the output step's peak).
  reserveHuge(tri_, 2 * n + 16, /*populate=*/true);
  // A seed edge joins a point to its nearest neighbour; farther than this it is an isolated
  // point (an outlier), which starts no surface.
  seedMaxEdge_ = 2.0 * std::max(1.0, params_.maxSearchRadiusFactor) * spacing_;
}

double Mesher::sampleSpacing() const {
  // growth::meanSpacing (the trimmed mean of the nearest distances of a fixed stride of the
  // caller's points, the spacing mesh_measures and the benchmark use), measured on this grid: the
  // same samples, the same distances, the same number.
  std::vector<double> d2;
  grid_.nearestOtherSquaredDistances(std::max<size_t>(1, grid_.size() / kMeanSpacingSamples), d2);
  return trimmedMeanSpacing(d2);
}

ManifoldCleanupStat Mesher::removeNonManifoldVertices() {
  assignHuge(alive_, tri_.size(), char(1));
  // With those removed at thin parts before their loops were closed (closeRimLoops).
  ManifoldCleanupStat st = thinCleanup_;
  if (joinedAtVertex_.empty()) return st; // no vertex ever got a second fan
  std::sort(joinedAtVertex_.begin(), joinedAtVertex_.end());
  joinedAtVertex_.erase(std::unique(joinedAtVertex_.begin(), joinedAtVertex_.end()), joinedAtVertex_.end());
  const ManifoldCleanupStat now = growth::removeNonManifoldVertices(tri_, grid_.size(), alive_, &joinedAtVertex_);
  for (size_t f = 0; f < tri_.size(); ++f)
    if (!alive_[f]) pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
  st.nonManifoldVertices += now.nonManifoldVertices;
  st.facesRemoved += now.facesRemoved;
  return st;
}

namespace {
// orientComponents: the component number of a vertex after unionComponents (its root holds
// kRootFlag | the number; every other vertex of a live triangle points at its root).
constexpr std::uint32_t kRootFlag = 1u << 31;
struct ComponentOf {
  const std::vector<std::uint32_t>& parent;
  std::uint32_t operator()(std::uint32_t v) const {
    const std::uint32_t p = parent[v];
    return (p & kRootFlag) != 0 ? p & ~kRootFlag : parent[p] & ~kRootFlag;
  }
};
} // namespace

void Mesher::unionComponents(std::vector<std::uint32_t>& parent) const {
  const size_t n = grid_.size();
  assignHuge(parent, n, 0u);
  for (size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];
      i = parent[i];
    }
    return i;
  };
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!live(f)) continue;
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t r0 = root(tri_[f][0]), r1 = root(tri_[f][k]);
      if (r0 != r1) parent[std::max(r0, r1)] = std::min(r0, r1);
    }
  }
  // Roots are the smallest index of their set, so in increasing order a root is final before the
  // vertices that point at it are compressed.
  for (size_t i = 0; i < n; ++i) parent[i] = root(static_cast<std::uint32_t>(i));
}

size_t Mesher::componentVolumes(std::vector<std::uint32_t>& parent, std::vector<double>& volume) const {
  const ComponentOf component{parent};
  // The components are numbered in the order of their first face, in the same pass that sums the
  // corners (each component's sum in face order, as in a separate pass).
  std::vector<P3> centre;
  std::vector<double> corners;
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    const std::uint32_t v = tri_[f][0];
    if ((parent[v] & kRootFlag) == 0) {
      std::uint32_t& r = parent[parent[v]]; // v's root's entry (v itself when v is the root)
      if ((r & kRootFlag) == 0) {
        r = kRootFlag | static_cast<std::uint32_t>(centre.size());
        centre.push_back(P3(0, 0, 0));
        corners.push_back(0.0);
      }
    }
    const std::uint32_t k = component(v);
    for (std::uint32_t w : tri_[f]) centre[k] += pts_[w];
    corners[k] += 3;
  }
  const size_t components = centre.size();
  volume.assign(components, 0.0);
  for (size_t k = 0; k < components; ++k)
    if (corners[k] > 0) centre[k] /= corners[k];
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    const std::uint32_t k = component(tri_[f][0]);
    const P3 a = pts_[tri_[f][0]] - centre[k], b = pts_[tri_[f][1]] - centre[k], c = pts_[tri_[f][2]] - centre[k];
    volume[k] += a * (b ^ c);
  }
  return components;
}

Mesher::OrientationStat Mesher::orientComponents(const std::vector<P3>* normals) {
  OrientationStat st;
  const size_t n = grid_.size();
  if (alive_.size() != tri_.size()) alive_.assign(tri_.size(), 1);
  // 1. Union–find over the vertices of the live triangles, in the per-point scratch array. After
  //    full compression every vertex points at its root.
  std::vector<std::uint32_t>& parent = scratch_;
  unionComponents(parent);
  // 2. Each component's signed volume about the centroid of its face corners (its roots then
  //    hold kRootFlag | its component's number).
  std::vector<double> volume;
  const size_t components = componentVolumes(parent, volume);
  const ComponentOf component{parent};
  // 3. Each component faces outwards of its own volume (positive signed volume) unless it is a
  //    closed shell nested inside an odd number of other closed shells: then it bounds a cavity
  //    of the material (the inner wall of a hollow ball) and faces into the cavity (negative volume).
  std::vector<signed char> wanted(components, 1);
  nestedShellSigns(component, components, wanted);
  st.components = components;
  for (signed char w : wanted) st.cavities += w < 0;
  std::vector<char> flip(components, 0);
  // 3b. The sheets (pieces with a free edge that enclose little volume: a scan's open surface, a
  //     LiDAR tile's ground), where normals are given: the way the normals point on the whole. A
  //     piece that nearly closes (a scan with holes) keeps the rule of its volume, which estimated
  //     normals oriented the wrong way round could not overturn.
  std::vector<double> agree;
  if (normals != nullptr && normals->size() == n) {
    std::vector<char> open(components, 0);
    for (std::uint32_t v = 0; v < n; ++v)
      if (pem_.degree(v) > 0 && pem_.hasFreeEdge(v)) open[component(v)] = 1;
    agree.assign(components, 0.0);
    std::vector<double> area(components, 0.0);
    for (size_t f = 0; f < tri_.size(); ++f) {
      if (!alive_[f]) continue;
      const Triangle& t = tri_[f];
      const std::uint32_t k = component(t[0]);
      if (!open[k]) continue;
      const P3 fn = (pts_[t[1]] - pts_[t[0]]) ^ (pts_[t[2]] - pts_[t[0]]);
      agree[k] += fn * ((*normals)[t[0]] + (*normals)[t[1]] + (*normals)[t[2]]);
      area[k] += 0.5 * fn.Norm();
    }
    // Enclosed volume against that of a sphere of the same area (1 for a sphere; volume[] is six
    // times the signed volume).
    for (size_t k = 0; k < components; ++k) {
      const double sphere = std::pow(area[k], 1.5) / (6.0 * std::sqrt(3.14159265358979323846));
      if (!(std::abs(volume[k]) / 6.0 < kSheetEnclosure * sphere)) agree[k] = 0;
    }
  }
  bool any = false;
  for (size_t k = 0; k < components; ++k) {
    const bool byNormals = !agree.empty() && agree[k] != 0;
    flip[k] = byNormals ? agree[k] < 0 : volume[k] * double(wanted[k]) < 0;
    st.byNormals += byNormals;
    st.flipped += flip[k];
    any = any || flip[k];
  }
  if (!any) return st;
  // 4. The flipped components' triangles, then their half-edges in the point–edge map: every edge
  //    at a vertex of a flipped component is one of that component's (its triangles are all
  //    flipped), so reversing each such vertex's entries records the flip. A vertex with an edge
  //    carrying a triangle lies on a live triangle, so it has a component.
  for (size_t f = 0; f < tri_.size(); ++f)
    if (alive_[f] && flip[component(tri_[f][0])]) {
      std::swap(tri_[f][1], tri_[f][2]);
      ++st.facesFlipped;
    }
  for (std::uint32_t v = 0; v < n; ++v)
    if (pem_.degree(v) > 0 && flip[component(v)]) pem_.reverseAt(v);
  return st;
}

template <class ComponentOf>
void Mesher::nestedShellSigns(const ComponentOf& component, size_t components, std::vector<signed char>& wanted) const {
  if (components < 2) return;
  // Closed components: no vertex with a boundary half-edge (a used half-edge whose twin is not).
  std::vector<char> open(components, 0);
  for (std::uint32_t v = 0; v < grid_.size(); ++v) {
    bool boundary = false;
    pem_.forEachEdge(v, [&](std::uint32_t, bool out, bool in) { boundary = boundary || (out && !in); });
    if (boundary) open[component(v)] = 1; // a vertex with a used half-edge is on a live triangle
  }
  std::vector<std::uint32_t> closed;
  for (size_t k = 0; k < components; ++k)
    if (!open[k]) closed.push_back(static_cast<std::uint32_t>(k));
  if (closed.size() < 2) return;
  // Their bounding boxes, and their faces grouped by component (a counting sort).
  std::vector<Box3d> box(components);
  std::vector<size_t> faces(components + 1, 0);
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    const std::uint32_t k = component(tri_[f][0]);
    if (open[k]) continue;
    ++faces[k + 1];
    for (std::uint32_t w : tri_[f]) box[k].Add(pts_[w]);
  }
  for (size_t k = 0; k < components; ++k) faces[k + 1] += faces[k];
  std::vector<std::uint32_t> byComponent(faces[components]);
  {
    std::vector<size_t> next(faces.begin(), faces.end() - 1);
    for (size_t f = 0; f < tri_.size(); ++f)
      if (alive_[f] && !open[component(tri_[f][0])])
        byComponent[next[component(tri_[f][0])]++] = static_cast<std::uint32_t>(f);
  }
  // Parity of the crossings of a ray from q with shell j (Möller–Trumbore). The direction is a
  // fixed unit vector off the axes and diagonals, so that a ray through an edge or a vertex of a
  // shell, where a crossing would count twice or not at all, does not occur on real clouds.
  const P3 dir(0.48, 0.6, 0.64);
  auto inside = [&](const P3& q, std::uint32_t j) {
    bool odd = false;
    for (size_t i = faces[j]; i < faces[j + 1]; ++i) {
      const Triangle& t = tri_[byComponent[i]];
      const P3 &A = pts_[t[0]], e1 = pts_[t[1]] - A, e2 = pts_[t[2]] - A;
      const P3 h = dir ^ e2;
      const double det = e1 * h;
      if (det == 0) continue;
      const P3 s = q - A;
      const double u = (s * h) / det;
      if (u < 0 || u > 1) continue;
      const P3 r = s ^ e1;
      const double v = (dir * r) / det;
      if (v < 0 || u + v > 1) continue;
      odd ^= (e2 * r) / det > 0;
    }
    return odd;
  };
  // A shell's depth: the number of other closed shells around one of its vertices. Only shells
  // whose box holds the vertex are tested, so shells side by side cost nothing.
  for (std::uint32_t k : closed) {
    const P3& q = pts_[tri_[byComponent[faces[k]]][0]];
    int depth = 0;
    for (std::uint32_t j : closed)
      if (j != k && box[j].IsIn(q) && inside(q, j)) ++depth;
    wanted[k] = (depth % 2 == 1) ? -1 : 1;
  }
}

void Mesher::releaseGrowthState() {
  holePass_.reset();
  handlePass_.reset();
  grid_.releaseSearch();
  HugeVector<float>().swap(edgeLengthSum_);
  HugeVector<std::uint16_t>().swap(edgeCount_);
  HugeVector<std::uint16_t>().swap(freeEdges_);
  HugeVector<std::uint32_t>().swap(faceAt_);
  HugeVector<std::uint8_t>().swap(crossing_);
  HugeVector<std::uint8_t>().swap(onSurface_);
  queue_ = BucketQueue<FrontEdge, HugeAllocator<FrontEdge>>(queue_.levels());
  near_ = NearList();
  std::vector<Scored>().swap(scored_);
  std::vector<std::uint32_t>().swap(foldHits_);
}

void Mesher::releaseWorkingState() {
  releaseGrowthState();
  pem_.release();
  grid_.releasePoints();
  pts_ = nullptr;
  std::vector<std::uint32_t>().swap(joinedAtVertex_);
}

std::vector<Triangle> Mesher::takeLiveTriangles() {
  if (alive_.size() == tri_.size()) {
    size_t live = 0;
    for (size_t f = 0; f < tri_.size(); ++f)
      if (alive_[f]) tri_[live++] = tri_[f];
    tri_.resize(live);
  }
  std::vector<char>().swap(alive_);
  std::vector<Triangle> live;
  live.swap(tri_);
  return live;
}

size_t Mesher::liveTriangles() const {
  if (alive_.size() != tri_.size()) return tri_.size();
  return static_cast<size_t>(std::count(alive_.begin(), alive_.end(), char(1)));
}

size_t Mesher::boundaryEdges() const {
  size_t n = 0;
  for (std::uint32_t v = 0; v < grid_.size(); ++v)
    pem_.forEachEdge(v, [&](std::uint32_t, bool out, bool in) { n += out && !in; });
  return n;
}

size_t Mesher::boundaryLoops() { return boundary().loops; }

Mesher::BoundaryCount Mesher::boundary() {
  // Each boundary half-edge v→w (used, w→v unused) is followed by a boundary half-edge leaving w;
  // at a manifold vertex there is exactly one, so every walk traces one loop (one hole). One
  // sweep over the points counts the boundary half-edges and starts a walk from each one not yet
  // marked; the marks are then taken off the walked half-edges only (the map is left as it was).
  BoundaryCount count;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> marked;
  for (std::uint32_t v = 0; v < grid_.size(); ++v) {
    bool boundaryHere = false;
    pem_.forEachEdge(v, [&](std::uint32_t, bool out, bool in) {
      const bool b = out && !in;
      count.edges += b;
      boundaryHere = boundaryHere || b;
    });
    if (!boundaryHere) continue;
    std::uint32_t w = 0;
    while (nextBoundaryHalfEdge(v, w)) {
      ++count.loops;
      walkBoundary(v, w, marked, nullptr);
    }
  }
  for (const auto& e : marked) pem_.setMark(e.first, e.second, false);
  return count;
}

size_t Mesher::memoryBytes() const {
  return grid_.memoryBytes() + pem_.memoryBytes() + scratch_.capacity() * sizeof(std::uint32_t) +
         edgeLengthSum_.capacity() * sizeof(float) +
         (edgeCount_.capacity() + freeEdges_.capacity()) * sizeof(std::uint16_t) + faceAt_.capacity() * sizeof(std::uint32_t) +
         tri_.capacity() * sizeof(Triangle) + alive_.capacity() + crossing_.capacity() + onSurface_.capacity() +
         joinedAtVertex_.capacity() * sizeof(std::uint32_t);
}

} // namespace g2s
} // namespace growth
