// Robust G2S's repairs after the paper's method (filter_g2s/engine/g2s_repair.cpp): on noisy clouds
// the output has no intersecting face pairs, and the hole pass closes small holes while keeping the
// mesh manifold, consistently oriented and free of intersections; both are deterministic, and a
// clean closed cloud is left exactly as the paper's method meshes it.
#include "filter_g2s_layer.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>

#include <common/ml_mesh_type.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <functional>
#include <memory>
#include <string>

using growth::CloudSpec;
using growth::Shape;
namespace g2s = growth::g2s;

namespace {

using Mesh = std::unique_ptr<CMeshO>;

// Gaussian noise (sigma in mean spacings of the clean cloud) and outliers (a fraction of the
// points), as the benchmark's noisy clouds; seeded.
Mesh noisyCloud(Shape shape, size_t n, double sigmaSpacings, double outliers, std::uint64_t seed) {
  CloudSpec spec;
  spec.shape = shape;
  spec.count = n;
  spec.seed = seed;
  const double mu = growth::meanSpacing(growth::generateCloud(spec).points);
  spec.gaussianSigma = sigmaSpacings * mu;
  spec.outlierFraction = outliers;
  Mesh m(new CMeshO);
  growth::toMesh(growth::generateCloud(spec), *m);
  return m;
}

struct Run {
  CMeshO mesh;
  g2s::Stat stat;
};

// (The handle pass, which closes the loops of its cuts with the hole pass's means, is off unless
// asked: the hole pass's counts are checked alone.)
std::unique_ptr<Run> run(const CMeshO& cloud, int maxHoleEdges, bool handles = false) {
  CMeshO none;
  g2s::Params p = g2s::suggestParams(none);
  p.maxHoleEdges = maxHoleEdges;
  p.removeSmallHandles = handles;
  std::unique_ptr<Run> r(new Run);
  g2s::build(cloud, r->mesh, p, r->stat);
  return r;
}

bool sameMesh(const CMeshO& a, const CMeshO& b) {
  if (a.vn != b.vn || a.fn != b.fn) return false;
  for (size_t i = 0; i < a.vert.size(); ++i)
    if (!(a.vert[i].cP() == b.vert[i].cP())) return false;
  for (size_t f = 0; f < a.face.size(); ++f)
    for (int k = 0; k < 3; ++k)
      if (vcg::tri::Index(a, a.face[f].cV(k)) != vcg::tri::Index(b, b.face[f].cV(k))) return false;
  return true;
}

struct Case {
  const char* name;
  Shape shape;
  double sigma, outliers;
  std::uint64_t seed;
};

const Case kNoisy[] = {
    {"sphere gauss 0.25", Shape::Sphere, 0.25, 0, 1},  {"sphere gauss 0.5", Shape::Sphere, 0.5, 0, 2},
    {"torus gauss 0.5", Shape::Torus, 0.5, 0, 3},      {"patch gauss 0.5", Shape::Patch, 0.5, 0, 4},
    {"sphere outliers 0.1", Shape::Sphere, 0, 0.1, 5}, {"torus outliers 0.1", Shape::Torus, 0, 0.1, 6},
};

} // namespace

// Without the removal, noisy clouds like these give intersecting pairs
// (docs/design/crossing-faces.md).
TEST(G2SRepair, NoisyCloudsGiveNoIntersectingFacesNoDefectsAndTheSameMeshTwice) {
  size_t removed = 0, closed = 0;
  for (const Case& c : kNoisy) {
    SCOPED_TRACE(c.name);
    const Mesh cloud = noisyCloud(c.shape, 12000, c.sigma, c.outliers, c.seed);
    for (int holes : {0, 20}) {
      SCOPED_TRACE(holes);
      const auto r = run(*cloud, holes);
      ASSERT_GT(r->stat.faces, 10000u);
      EXPECT_EQ(growth::countSelfIntersections(r->mesh), 0u);
      const growth::MeshTopology t = growth::measureTopology(r->mesh);
      EXPECT_EQ(t.nonManifoldVertices, 0u);
      EXPECT_EQ(t.nonManifoldEdges, 0u);
      EXPECT_EQ(t.inconsistentEdges, 0u); // orientation consistent across every edge
      EXPECT_EQ(t.duplicateFaces, 0u);
      EXPECT_EQ(t.boundaryLoops, r->stat.holes);
      EXPECT_EQ(t.boundaryEdges, r->stat.boundaryEdges);
      removed += r->stat.selfIntersectionFacesRemoved;
      closed += r->stat.holesClosed;
      const auto again = run(*cloud, holes);
      EXPECT_TRUE(sameMesh(r->mesh, again->mesh));
      EXPECT_EQ(again->stat.holesClosed, r->stat.holesClosed);
    }
  }
  EXPECT_GT(removed, 0u); // the removal was needed on these clouds
  EXPECT_GT(closed, 0u);
}

// Closed noisy clouds: where the growth closes without a free edge, the removal of intersecting
// faces, which starts from the boundary, has nowhere to start, yet an ear (a loop of three free
// edges closed, G2S or not) folded back over its front triangle can lie across the faces at its
// points. Such an ear makes the removal look: it takes it out and the hole pass closes the hole.
TEST(G2SRepair, FoldedEarsOfClosedNoisyCloudsAreFound) {
  struct Closed {
    Shape shape;
    size_t n;
    double sigma;
    std::uint64_t seed;
  };
  size_t removed = 0;
  for (const Closed& c : {Closed{Shape::Sphere, 2000, 0.1, 9}, Closed{Shape::Torus, 2000, 0.1, 2},
                          Closed{Shape::Torus, 2000, 0.25, 9}, Closed{Shape::Sphere, 5000, 0.1, 8},
                          Closed{Shape::Genus2, 2000, 0.25, 1}}) {
    SCOPED_TRACE(testing::Message() << int(c.shape) << " " << c.n << " sigma " << c.sigma << " seed " << c.seed);
    const Mesh cloud = noisyCloud(c.shape, c.n, c.sigma, 0, c.seed);
    const auto r = run(*cloud, 20);
    EXPECT_EQ(growth::countSelfIntersections(r->mesh), 0u);
    const growth::MeshTopology t = growth::measureTopology(r->mesh);
    EXPECT_EQ(t.nonManifoldVertices + t.nonManifoldEdges + t.inconsistentEdges, 0u);
    EXPECT_EQ(r->stat.holes, 0u);
    EXPECT_LE(r->stat.unusedPoints, 5u);
    removed += r->stat.selfIntersectionFacesRemoved;
  }
  EXPECT_GE(removed, 5u);
}

// The handle pass (g2s_handles.cpp) on the noisy clouds: it only cuts handles (each cut one handle
// fewer), keeps the mesh manifold, consistently oriented and free of intersecting faces, leaves no
// more holes than before, and its faces add up; the same mesh twice.
TEST(G2SRepair, HandlePassCutsHandlesAndKeepsTheMeshValid) {
  size_t cut = 0;
  for (const Case& c : kNoisy) {
    SCOPED_TRACE(c.name);
    const Mesh cloud = noisyCloud(c.shape, 30000, c.sigma, c.outliers, c.seed);
    const auto off = run(*cloud, 20, false), on = run(*cloud, 20, true);
    EXPECT_EQ(off->stat.handlesCut, 0u);
    EXPECT_EQ(on->stat.handles + on->stat.handlesCut, off->stat.handles);
    EXPECT_EQ(on->stat.faces, off->stat.faces + on->stat.handleFacesAdded - on->stat.handleFacesRemoved);
    EXPECT_LE(on->stat.holes, off->stat.holes);
    EXPECT_EQ(growth::countSelfIntersections(on->mesh), 0u);
    const growth::MeshTopology t = growth::measureTopology(on->mesh);
    EXPECT_EQ(t.nonManifoldVertices + t.nonManifoldEdges + t.inconsistentEdges + t.duplicateFaces, 0u);
    EXPECT_EQ(t.boundaryLoops, on->stat.holes);
    EXPECT_EQ(t.components, growth::measureTopology(off->mesh).components); // a cut separates nothing
    const auto again = run(*cloud, 20, true);
    EXPECT_TRUE(sameMesh(on->mesh, again->mesh));
    cut += on->stat.handlesCut;
  }
  EXPECT_GT(cut, 0u); // the noisy clouds have small handles
}

// The hole pass adds faces to the mesh the paper's method (and the removal) gave, on the same points
// (taking out at most one face per loop it closes, or a spike vertex with its two faces); each loop
// it closes is one hole fewer.
TEST(G2SRepair, HolePassOnlyAddsFacesAndLeavesFewerHoles) {
  size_t spikes = 0;
  for (const Case& c : kNoisy) {
    SCOPED_TRACE(c.name);
    const Mesh cloud = noisyCloud(c.shape, 12000, c.sigma, c.outliers, c.seed);
    const auto off = run(*cloud, 0), on = run(*cloud, 20);
    EXPECT_EQ(off->stat.holesClosed, 0u);
    EXPECT_EQ(on->stat.faces, off->stat.faces + on->stat.holeFacesAdded - on->stat.holeFacesReplaced);
    // One face per loop, or two at a spike (whose vertex then leaves the mesh), but for the loops
    // closed wider (every face on their edges, or at their points, taken out first).
    EXPECT_LE(on->stat.holeFacesReplaced - on->stat.holeFacesWidened, on->stat.holesClosed + on->stat.holeSpikes);
    EXPECT_LE(on->stat.holesWidened, on->stat.holesClosed);
    EXPECT_LE(on->stat.holeFacesWidened, on->stat.holeFacesReplaced);
    EXPECT_LE(on->stat.holeSpikes, on->stat.holesClosed);
    EXPECT_EQ(on->stat.holes + on->stat.holesClosed, off->stat.holes);
    EXPECT_LE(on->stat.boundaryEdges, off->stat.boundaryEdges);
    // No point added (loops close on their own points); a spike's vertex is taken out.
    EXPECT_EQ(on->stat.vertices + on->stat.holeSpikes, off->stat.vertices);
    if (c.sigma >= 0.5) {
      EXPECT_GT(on->stat.holesClosed, 0u);
    }
    spikes += on->stat.holeSpikes;
  }
  EXPECT_GT(spikes, 0u); // the spike step was reached on these clouds
}

// A clean closed cloud: no free edge is left by the growth, so neither repair looks at the mesh:
// the same mesh with the hole pass on or off.
TEST(G2SRepair, CleanClosedCloudIsLeftAlone) {
  for (Shape shape : {Shape::Sphere, Shape::Torus}) {
    const Mesh cloud = noisyCloud(shape, 20000, 0, 0, 1);
    const auto on = run(*cloud, 20), off = run(*cloud, 0);
    EXPECT_EQ(on->stat.holes, 0u);
    EXPECT_EQ(on->stat.selfIntersectionFacesRemoved, 0u);
    EXPECT_EQ(on->stat.holesClosed, 0u);
    EXPECT_TRUE(sameMesh(on->mesh, off->mesh));
  }
}

// The patch's border (a loop of hundreds of edges) is no small hole: left open.
TEST(G2SRepair, LongBorderStaysOpen) {
  const Mesh cloud = noisyCloud(Shape::Patch, 20000, 0, 0, 1);
  const auto r = run(*cloud, 20);
  EXPECT_EQ(r->stat.holes, 1u);
  EXPECT_EQ(r->stat.holesClosed, 0u);
}

// Triangles among the outliers form small pieces apart from the surface: with minComponentFaces
// they are dropped, every piece left but the largest has at least that many faces, and the rest
// of the mesh is the one the pass off gives (the same faces in the same order, on fewer vertices;
// compared with the hole pass off, which would otherwise also close loops of the small pieces).
TEST(G2SRepair, SmallPiecesAmongOutliersAreDroppedAndNothingElse) {
  const Mesh cloud = noisyCloud(Shape::Patch, 20000, 0, 0.2, 7);
  CMeshO none;
  g2s::Params p = g2s::suggestParams(none);
  ASSERT_EQ(p.minComponentFaces, 50);
  p.minComponentFaces = 0;
  p.maxHoleEdges = 0;
  g2s::Stat offStat, onStat;
  CMeshO off, on;
  g2s::build(*cloud, off, p, offStat);
  EXPECT_EQ(offStat.componentsDropped, 0u);
  const growth::MeshTopology offTop = growth::measureTopology(off);
  ASSERT_GT(offTop.components, 5u); // the outliers gave pieces (checked: 23 with this cloud)
  p.minComponentFaces = 50;
  g2s::build(*cloud, on, p, onStat);
  const growth::MeshTopology t = growth::measureTopology(on);
  EXPECT_GT(onStat.componentsDropped, 0u);
  EXPECT_EQ(t.components + onStat.componentsDropped, offTop.components);
  EXPECT_EQ(size_t(on.fn) + onStat.componentFacesDropped, size_t(off.fn));
  EXPECT_EQ(t.boundaryLoops, onStat.holes);
  EXPECT_LT(onStat.holes, offStat.holes);
  EXPECT_EQ(t.nonManifoldVertices, 0u);
  EXPECT_EQ(t.nonManifoldEdges, 0u);
  EXPECT_EQ(t.inconsistentEdges, 0u);
  EXPECT_EQ(growth::countSelfIntersections(on), 0u);
  // Each face of `on` is a face of `off` with the same points in the same order (the pass only
  // takes faces out, and keeps the orientation).
  std::vector<std::array<vcg::Point3<CMeshO::ScalarType>, 3>> offFaces, onFaces;
  for (const auto& f : off.face) offFaces.push_back({f.cP(0), f.cP(1), f.cP(2)});
  for (const auto& f : on.face) onFaces.push_back({f.cP(0), f.cP(1), f.cP(2)});
  size_t j = 0;
  for (const auto& f : onFaces) {
    while (j < offFaces.size() && offFaces[j] != f) ++j;
    ASSERT_LT(j, offFaces.size()) << "a face of the mesh with the pass is not in the mesh without it, in order";
    ++j;
  }
  // Every piece but the largest has at least 50 faces.
  std::vector<size_t> parent(size_t(on.vn)), count(size_t(on.vn), 0);
  for (size_t v = 0; v < parent.size(); ++v) parent[v] = v;
  auto find = [&](size_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  for (const auto& f : on.face)
    for (int k = 1; k < 3; ++k) parent[find(vcg::tri::Index(on, f.cV(k)))] = find(vcg::tri::Index(on, f.cV(0)));
  for (const auto& f : on.face) ++count[find(vcg::tri::Index(on, f.cV(0)))];
  std::sort(count.begin(), count.end(), std::greater<size_t>());
  ASSERT_GT(count[0], 10000u);
  for (size_t k = 1; k < count.size() && count[k] > 0; ++k) EXPECT_GE(count[k], 50u);
  // With the defaults (the hole pass on): fewer holes than without the drop, no defects, and the
  // same mesh twice.
  p = g2s::suggestParams(none);
  CMeshO full, again, keep;
  g2s::Stat fullStat, againStat, keepStat;
  g2s::build(*cloud, full, p, fullStat);
  g2s::build(*cloud, again, p, againStat);
  EXPECT_TRUE(sameMesh(full, again));
  const growth::MeshTopology ft = growth::measureTopology(full);
  EXPECT_EQ(ft.nonManifoldVertices + ft.nonManifoldEdges + ft.inconsistentEdges, 0u);
  EXPECT_EQ(growth::countSelfIntersections(full), 0u);
  p.minComponentFaces = 0;
  g2s::build(*cloud, keep, p, keepStat);
  EXPECT_LT(fullStat.holes, keepStat.holes);
}
