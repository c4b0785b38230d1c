// Sec. 3.4-3.6 on every part of the cloud, sec. 3.3 starting each (packer_steps.h).
#include "packer_growth.h"

#include "cloud_features.h"
#include "feature_lines.h"

namespace growth {
namespace spherepack {
namespace detail {

// Sec. 3.4–3.6: the disk growing from the first pair; then sec. 3.3 again on every further part of
// the cloud. When the growth has stopped and points are left that no vertex reached, a new
// starting pair on the first of them in input order (every point is tried once, so the scan is
// linear), at least kStartClearancePerD·d from every vertex placed so far: a point with a vertex
// between d and that far lies on a surface already meshed there (a misregistered second scan
// layer, or the rim of a gap the growth left), and a start on it would only grow a separate sheet
// over or beside the mesh (docs/design/spherepack-every-part.md).
void growEveryPart(Growth& growth, const StartPair& first, const InputCloud& in, const std::vector<float>& radius,
                   const BoxGrid& grid, const Renumbering& order, double d, Stat& st) {
  // (With features placed first, the first pair is used only where no vertex is closer than d.)
  if (!growth.anyVertexCloserThan(first.s1, d) && !growth.anyVertexCloserThan(first.s2, d)) {
    growth.start(first.s1, first.splat1, first.s2, first.splat2);
    growth.run();
    st.componentsStarted = 1;
  }
  bool nearMesh = false;
  auto farFromVertices = [&](const Vec3d& x) {
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

// Keep features, sec. 3.3 with more than two starting vertices, as the remesher places the creases
// of its input: the corners as vertices, then every crease line sampled at a chord spacing s >= d
// that ends exactly at its far end (sampleLine), joined by edges; then their candidates and the
// growth from them. A feature vertex closer than d to one placed before is left out (with its
// edges; neighbours across it are joined when at most 2.2 d apart, the longest edge the crossing
// check sees, sec. 3.6).
void placeCloudFeatures(Growth& growth, const CloudFeatures& f, const std::vector<Vec3d>& points, double d, Stat& st) {
  std::vector<std::uint32_t> cornerVertex(f.corners.size(), std::uint32_t(Growth::kNoVertex)), placed;
  auto place = [&](const Vec3d& x, const Vec3d& n, const Vec3d* t = nullptr) {
    const std::uint32_t id =
        t != nullptr ? growth.addFeatureVertex(x, n, f.sidesAt(x, *t, points), *t) : growth.addFeatureVertex(x, n);
    if (id != Growth::kNoVertex) placed.push_back(id);
    return id;
  };
  for (size_t c = 0; c < f.corners.size(); ++c) cornerVertex[c] = place(f.corners[c], f.cornerNormals[c]);
  auto join = [&](std::uint32_t u, std::uint32_t v) {
    if (u != Growth::kNoVertex && v != Growth::kNoVertex && u != v &&
        (growth.graph().position(u) - growth.graph().position(v)).SquaredNorm() <= 2.2 * 2.2 * d * d)
      growth.addFeatureEdge(u, v);
  };
  for (const CloudFeatures::Line& line : f.lines) {
    std::uint32_t from = line.front >= 0 ? cornerVertex[size_t(line.front)] : Growth::kNoVertex;
    auto direction = [&](size_t seg) {
      Vec3d t = line.p[std::min(seg + 1, line.p.size() - 1)] - line.p[seg];
      if (t.Norm() > 0) t.Normalize();
      return t;
    };
    if (line.front < 0) {
      const Vec3d t = direction(0);
      from = place(line.p.front(), line.n.front(), &t);
    }
    const std::uint32_t to = line.closed ? from : line.back >= 0 ? cornerVertex[size_t(line.back)] : Growth::kNoVertex;
    std::uint32_t prev = from;
    for (const LinePoint& q : sampleLine(line.p, d)) {
      const Vec3d t = direction(q.seg);
      const std::uint32_t id = place(q.p, line.n[q.seg], &t);
      if (id == Growth::kNoVertex) continue;
      join(prev, id);
      prev = id;
    }
    join(prev, to);
  }
  st.featureLines = f.lines.size();
  st.featureCorners = f.corners.size();
  st.featureVertices = placed.size();
  for (const std::uint32_t v : placed) growth.enumerateFeature(v);
  growth.run();
}

// Input points no vertex came within d of.
size_t unreachedPoints(const Growth& growth, size_t points) {
  size_t unreached = 0;
  for (std::uint32_t i = 0; i < points; ++i) {
    unreached += growth.lists().empty(i) ? 1 : 0;
  }
  return unreached;
}

} // namespace detail
} // namespace spherepack
} // namespace growth
