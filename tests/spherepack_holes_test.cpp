// The sphere packer's hole pass (Params::closeHoles, docs/design/spherepack-holes.md): clean closed
// clouds with the normals a MeshLab user estimates (growth/point_normals.h, K = 10) give closed
// meshes across the range of d, with every guarantee kept; open surfaces keep their boundaries.
#include "filter_spherepack_layer.h"

#include <growth/cloud_generator.h>
#include <growth/cloud_scale.h>
#include <growth/mesh_measures.h>
#include <growth/meshlab/layer.h>
#include <growth/point_normals.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/allocate.h>

#include <gtest/gtest.h>

#include <cmath>
#include <string>

namespace sp = growth::spherepack;

namespace {

// A generated cloud with the normals estimated from its points (MeshLab's K = 10), optionally
// with the points below z = cutBelow removed (an open surface).
growth::Cloud estimatedCloud(const growth::CloudSpec& spec, double cutBelow = -1e300) {
  growth::Cloud c = growth::generateCloud(spec);
  growth::Cloud kept;
  for (size_t i = 0; i < c.points.size(); ++i)
    if (c.points[i][2] >= cutBelow) kept.points.push_back(c.points[i]);
  kept.normals = growth::estimateNormals(kept.points, 10);
  return kept;
}

struct Result {
  CMeshO mesh;
  sp::Stat stat;
  growth::MeshMeasures m;
};

// d = `spacings` mean spacings (growth::meanSpacing, as spherepack_run --d-spacings).
void run(const growth::Cloud& cloud, double spacings, bool closeHoles, Result& r) {
  CMeshO in;
  growth::toMesh(cloud, in);
  sp::Params p;
  p.sphereDiameter = spacings * growth::meanSpacing(cloud.points);
  p.closeHoles = closeHoles;
  sp::build(in, r.mesh, p, r.stat);
  r.m = growth::measure(r.mesh);
}

// The guarantees: every edge and vertex pair at least d (float storage: relative 1e-5), manifold,
// consistently oriented, no intersecting faces, Stat in agreement with the mesh.
void expectGuarantees(const Result& r, const std::string& what) {
  const double d = r.stat.sphereDiameter;
  EXPECT_GE(r.m.edgeMin, d * (1 - 1e-5)) << what;
  EXPECT_GE(r.m.minVertexDistance, d * (1 - 1e-5)) << what;
  EXPECT_EQ(r.m.nonManifoldEdges, 0u) << what;
  EXPECT_EQ(r.m.nonManifoldVertices, 0u) << what;
  EXPECT_EQ(r.m.inconsistentEdges, 0u) << what;
  EXPECT_EQ(r.m.selfIntersectingPairs, 0u) << what;
  EXPECT_EQ(r.m.degenerateFaces, 0u) << what;
  EXPECT_EQ(r.m.duplicateFaces, 0u) << what;
  EXPECT_EQ(r.m.unreferencedVertices, 0u) << what;
  EXPECT_EQ(r.stat.faces, r.m.faces) << what;
  EXPECT_EQ(r.stat.boundaryLoops, r.m.boundaryLoops) << what;
  EXPECT_EQ(r.stat.holes, r.m.boundaryLoops) << what;
}

// A closed cloud at d = `spacings` mean spacings: holes without the pass (the cell tests the
// pass), none with it, a closed mesh of the shape's topology, with every guarantee.
void expectCloses(const growth::Cloud& cloud, double spacings, int euler, const std::string& what) {
  Result off, on;
  run(cloud, spacings, false, off);
  run(cloud, spacings, true, on);
  EXPECT_GT(off.m.boundaryLoops, 0u) << what << ": the cell has no holes to close";
  expectGuarantees(on, what);
  EXPECT_EQ(on.m.boundaryLoops, 0u) << what;
  EXPECT_EQ(on.m.boundaryEdges, 0u) << what;
  EXPECT_EQ(on.stat.holes, 0u) << what;
  EXPECT_EQ(on.m.components, 1u) << what;
  EXPECT_EQ(on.m.eulerCharacteristic, euler) << what;
  EXPECT_GE(on.stat.holesClosed, off.m.boundaryLoops) << what;
  // The closures replace little of the mesh.
  EXPECT_LT(double(on.stat.holeFacesAdded + on.stat.holeFacesRemoved), 0.02 * double(on.m.faces)) << what;
  EXPECT_GE(on.m.qualityMean, 0.9) << what;
}

growth::CloudSpec slabSpec() {
  // A box with sharp edges (0.4 thick, 2 wide), 20,000 points: its creases leave holes.
  growth::CloudSpec s;
  s.shape = growth::Shape::Slab;
  s.slabThickness = 0.4;
  s.count = 20000;
  s.seed = 1;
  return s;
}

} // namespace

TEST(SpherePackHoles, BoxWithEstimatedNormalsClosesAcrossD) {
  const growth::Cloud cloud = estimatedCloud(slabSpec());
  for (double spacings : {2.0, 3.0})
    expectCloses(cloud, spacings, 2, "slab 0.4 at " + std::to_string(spacings) + " spacings");
}

TEST(SpherePackHoles, BoxWithEstimatedNormalsIsClosedAtLargeD) {
  // At 6 and 10 spacings the growth leaves no hole here; the pass must keep it so.
  const growth::Cloud cloud = estimatedCloud(slabSpec());
  for (double spacings : {6.0, 10.0}) {
    const std::string what = "slab 0.4 at " + std::to_string(spacings) + " spacings";
    Result r;
    run(cloud, spacings, true, r);
    expectGuarantees(r, what);
    EXPECT_EQ(r.m.boundaryLoops, 0u) << what;
    EXPECT_EQ(r.m.components, 1u) << what;
    EXPECT_EQ(r.m.eulerCharacteristic, 2) << what;
  }
}

TEST(SpherePackHoles, SparseSamplingWithEstimatedNormalsCloses) {
  // Density 10:1 to 16:1 along z: the sparse side holds regions the splats barely cover.
  growth::CloudSpec g;
  g.shape = growth::Shape::Genus2;
  g.count = 8000;
  g.nonUniform = true;
  g.densityRatio = 16;
  g.seed = 1;
  expectCloses(estimatedCloud(g), 2.5, -2, "genus 2, 16:1, at 2.5 spacings");
  growth::CloudSpec b = g;
  b.shape = growth::Shape::Genus2;
  b.densityRatio = 10;
  expectCloses(estimatedCloud(b), 1.5, -2, "genus 2, 10:1, at 1.5 spacings");
}

TEST(SpherePackHoles, PoleIslandIsDroppedAndTheHoleClosed) {
  // A sphere sampled on a latitude-longitude grid (a turntable scan): at a pole the estimated
  // normals leave a cap apart from the rest, a disk over the hole the rest leaves there.
  growth::CloudSpec s;
  s.shape = growth::Shape::LatLongSphere; // 300 rings of 600 points
  s.seed = 1;
  const growth::Cloud cloud = estimatedCloud(s);
  Result off, on;
  run(cloud, 4.0, false, off);
  run(cloud, 4.0, true, on);
  EXPECT_GT(off.m.boundaryLoops, 0u);
  expectGuarantees(on, "latlong at 4 spacings");
  EXPECT_EQ(on.m.boundaryLoops, 0u);
  EXPECT_EQ(on.m.components, 1u);
  EXPECT_EQ(on.m.eulerCharacteristic, 2);
  EXPECT_EQ(on.stat.holeIslandsDropped, off.m.components - 1);
}

TEST(SpherePackHoles, SameMeshEveryRun) {
  const growth::Cloud cloud = estimatedCloud(slabSpec());
  Result a, b;
  run(cloud, 2.5, true, a);
  run(cloud, 2.5, true, b);
  ASSERT_GT(a.stat.holesClosed, 0u);
  EXPECT_EQ(a.m.boundaryLoops, 0u);
  expectGuarantees(a, "slab 0.4 at 2.5 spacings");
  ASSERT_EQ(a.mesh.vert.size(), b.mesh.vert.size());
  ASSERT_EQ(a.mesh.face.size(), b.mesh.face.size());
  for (size_t i = 0; i < a.mesh.vert.size(); ++i) ASSERT_EQ(a.mesh.vert[i].cP(), b.mesh.vert[i].cP());
  for (size_t i = 0; i < a.mesh.face.size(); ++i)
    for (int k = 0; k < 3; ++k)
      ASSERT_EQ(vcg::tri::Index(a.mesh, a.mesh.face[i].cV(k)), vcg::tri::Index(b.mesh, b.mesh.face[i].cV(k)));
}

TEST(SpherePackHoles, OpenSurfacesKeepTheirBoundaries) {
  // A sphere with its bottom cap cut off (z < -0.3): one boundary, not covered by the cloud.
  growth::CloudSpec s;
  s.shape = growth::Shape::Sphere;
  s.count = 30000;
  s.seed = 2;
  const growth::Cloud cap = estimatedCloud(s, -0.3);
  for (double spacings : {1.5, 2.5, 4.0}) {
    const std::string what = "cut sphere at " + std::to_string(spacings) + " spacings";
    Result r;
    run(cap, spacings, true, r);
    expectGuarantees(r, what);
    EXPECT_EQ(r.m.boundaryLoops, 1u) << what;
    EXPECT_EQ(r.m.eulerCharacteristic, 1) << what; // a disk
    EXPECT_EQ(r.stat.holesNotCovered, 1u) << what; // the pass tried and the cloud said no
    // Nothing across the cut: no face in the disk the cap was (a closure's faces would lie there,
    // near the z axis; the sphere's own faces near z = -0.3 are about 0.95 from it).
    size_t across = 0;
    for (const auto& f : r.mesh.face) {
      const auto c = (f.cP(0) + f.cP(1) + f.cP(2)) / 3;
      across += c[2] < 0 && std::hypot(double(c[0]), double(c[1])) < 0.5 ? 1 : 0;
    }
    EXPECT_EQ(across, 0u) << what;
  }
  // A torus with a band cut out across its tube (|angle| < 0.6 around the z axis): two loops.
  growth::CloudSpec t;
  t.shape = growth::Shape::Torus;
  t.count = 30000;
  t.seed = 2;
  growth::Cloud full = growth::generateCloud(t), band;
  for (size_t i = 0; i < full.points.size(); ++i)
    if (std::abs(std::atan2(full.points[i][1], full.points[i][0])) >= 0.6) band.points.push_back(full.points[i]);
  band.normals = growth::estimateNormals(band.points, 10);
  for (double spacings : {1.5, 2.5, 4.0}) {
    const std::string what = "cut torus at " + std::to_string(spacings) + " spacings";
    Result r;
    run(band, spacings, true, r);
    expectGuarantees(r, what);
    EXPECT_EQ(r.m.boundaryLoops, 2u) << what;
    EXPECT_EQ(r.m.eulerCharacteristic, 0) << what; // a tube
    EXPECT_EQ(r.stat.holesNotCovered, 2u) << what;
  }
}
