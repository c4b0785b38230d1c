// The sphere-packing mesher end to end (sections 3 and 4 of the paper; section 5.2 for the test
// clouds): the guarantees on generated clouds, determinism, noise, open surfaces, bad input,
// progress and cancel.
#include "filter_spherepack_layer.h"
#include "region_triangulation.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>
#include <growth/mesh_normals.h>
#include <growth/point_grid.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/allocate.h>
#include <vcg/complex/append.h>

#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <memory>
#include <stdexcept>

namespace sp = growth::spherepack;
using Point3d = growth::Vec3d;

namespace {

growth::CloudSpec sphereSpec() {
  growth::CloudSpec s;
  s.shape = growth::Shape::Sphere;
  s.count = 10000; // sec. 5.2
  s.seed = 1;
  return s;
}

growth::CloudSpec torusSpec() {
  growth::CloudSpec s;
  s.shape = growth::Shape::Torus;
  s.count = 60000; // sec. 5.2: R = 2, r = 1
  s.seed = 1;
  return s;
}

struct Run {
  growth::CloudSpec spec;
  CMeshO cloud, mesh;
  sp::Params params;
  sp::Stat stat;
  growth::MeshMeasures m;
};

// Builds (once per distinct key) and measures.
std::shared_ptr<Run> build(const std::string& key, const growth::CloudSpec& spec, const sp::Params& params) {
  static std::map<std::string, std::shared_ptr<Run>> cache;
  auto it = cache.find(key);
  if (it != cache.end()) return it->second;
  auto r = std::make_shared<Run>();
  r->spec = spec;
  r->params = params;
  growth::toMesh(growth::generateCloud(spec), r->cloud);
  sp::build(r->cloud, r->mesh, params, r->stat);
  r->m = growth::measure(r->mesh);
  cache[key] = r;
  return r;
}

sp::Params paperParams() {
  sp::Params p;
  p.sphereDiameter = 0.1; // sec. 5.2
  p.checkInvariants = true;
  return p;
}

// The guarantees every closed-surface run must show.
void expectClosedManifoldMesh(const Run& r, int euler) {
  const double d = r.stat.sphereDiameter;
  const auto& m = r.m;
  EXPECT_EQ(m.selfIntersectingPairs, 0u);
  EXPECT_GT(m.faces, 1000u);
  // Every edge and every pair of vertices at least d apart (float storage: relative 1e-5).
  EXPECT_GE(m.edgeMin, d * (1 - 1e-5));
  EXPECT_GE(m.minVertexDistance, d * (1 - 1e-5));
  // Manifold, consistently oriented, closed, one piece, of the right topology.
  EXPECT_EQ(m.nonManifoldEdges, 0u);
  EXPECT_EQ(m.nonManifoldVertices, 0u);
  EXPECT_EQ(m.inconsistentEdges, 0u);
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_EQ(m.components, 1u);
  EXPECT_EQ(m.eulerCharacteristic, euler);
  EXPECT_EQ(m.unreferencedVertices, 0u);
  EXPECT_EQ(m.degenerateFaces, 0u);
  EXPECT_EQ(m.duplicateFaces, 0u);
  // Quality in the range the paper reports (Q_avg 0.945–0.958, E_RMS 11–16 %).
  EXPECT_GE(m.qualityMean, 0.94);
  EXPECT_LE(m.edgeRmsPercent, 16.0);
  // Stat agrees with the mesh.
  EXPECT_EQ(r.stat.vertices, m.vertices);
  EXPECT_EQ(r.stat.faces, m.faces);
  EXPECT_NEAR(r.stat.qualityAvg, m.qualityMean, 1e-5);
  EXPECT_NEAR(r.stat.smallestEdge, m.edgeMin, 1e-5 * d);
  EXPECT_EQ(r.stat.holes, 0u);
  EXPECT_EQ(r.stat.nonManifoldVertices, 0u);
  EXPECT_EQ(r.stat.boxesDTooLarge, 0u);
  EXPECT_TRUE(r.stat.warnings.empty()) << r.stat.warnings.front();
  // Every vertex on (or within 0.01 of) the true surface (sec. 5.2, covering splat size).
  double worst = 0;
  for (const auto& v : r.mesh.vert) worst = std::max(worst, growth::distanceToShape(r.spec, Point3d::Construct(v.cP())));
  EXPECT_LE(worst, 0.01);
}

// The same mesh, bit for bit: vertices (positions, normals), faces (quality, vertex indices).
void expectSameMesh(const CMeshO& a, const CMeshO& b) {
  ASSERT_EQ(a.vert.size(), b.vert.size());
  ASSERT_EQ(a.face.size(), b.face.size());
  for (size_t i = 0; i < a.vert.size(); ++i) {
    ASSERT_EQ(a.vert[i].cP(), b.vert[i].cP());
    ASSERT_EQ(a.vert[i].cN(), b.vert[i].cN());
  }
  for (size_t i = 0; i < a.face.size(); ++i) {
    ASSERT_EQ(a.face[i].cQ(), b.face[i].cQ());
    for (int k = 0; k < 3; ++k) ASSERT_EQ(vcg::tri::Index(a, a.face[i].cV(k)), vcg::tri::Index(b, b.face[i].cV(k)));
  }
}

} // namespace

TEST(SpherePacker, UnitSphereOfSection52) {
  const auto r = build("sphere", sphereSpec(), paperParams());
  expectClosedManifoldMesh(*r, 2);
  // Each new vertex brings two edges, so G has ~2V edges and its regions ~4 border edges on
  // average (sec. 3.7); none is long.
  EXPECT_GT(r->stat.meanBorderLength, 3.5);
  EXPECT_LT(r->stat.meanBorderLength, 4.5);
  EXPECT_LE(r->stat.longestBorder, 15u);
  // About area / (√3/2 · d²) vertices, a little less since edges are at least d.
  EXPECT_GT(r->m.vertices, 1000u);
  EXPECT_LT(r->m.vertices, size_t(4 * M_PI / (0.8660254 * 0.01)));
}

TEST(SpherePacker, TorusOfSection52) {
  const auto r = build("torus", torusSpec(), paperParams());
  expectClosedManifoldMesh(*r, 0); // genus 1
}

TEST(SpherePacker, FacesAreOrientedLikeTheNormalsAndCarryQt) {
  const auto r = build("sphere", sphereSpec(), paperParams());
  ASSERT_TRUE(r->mesh.face.IsQualityEnabled());
  for (const auto& f : r->mesh.face) {
    const Point3d a = Point3d::Construct(f.cP(0)), b = Point3d::Construct(f.cP(1)), c = Point3d::Construct(f.cP(2));
    const Point3d n = (b - a) ^ (c - a);
    // Outward like the sphere's normals, and like the vertex normals.
    EXPECT_GT(n * (a + b + c), 0);
    for (int k = 0; k < 3; ++k) EXPECT_GT(n * Point3d::Construct(f.cV(k)->cN()), 0);
    EXPECT_NEAR(f.cQ(), growth::triangleQuality(a, b, c), 1e-5);
  }
  for (const auto& v : r->mesh.vert) {
    EXPECT_NEAR(Point3d::Construct(v.cN()).Norm(), 1.0, 1e-5);
    EXPECT_GT(Point3d::Construct(v.cN()) * Point3d::Construct(v.cP()).Normalize(), 0.95);
  }
  // The output's normals are the mesh's own (angle-weighted vertex normals, unit face normals),
  // not the box normals: recomputing them on a copy changes nothing.
  CMeshO copy;
  vcg::tri::Append<CMeshO, CMeshO>::MeshCopy(copy, r->mesh);
  growth::updateNormals(copy);
  for (size_t i = 0; i < copy.vert.size(); ++i)
    EXPECT_LT((Point3d::Construct(copy.vert[i].cN()) - Point3d::Construct(r->mesh.vert[i].cN())).Norm(), 1e-6);
  for (size_t i = 0; i < copy.face.size(); ++i)
    EXPECT_LT((Point3d::Construct(copy.face[i].cN()) - Point3d::Construct(r->mesh.face[i].cN())).Norm(), 1e-6);
}

// The packer follows the input normals, which point out of the material, so
// the inner wall of a hollow ball faces the hollow; a thin closed plate (0.05 thick, about 1.7 d)
// faces out on both large faces.
TEST(SpherePacker, HollowBallAndThinSlabFaceOutOfTheMaterial) {
  growth::CloudSpec hollow;
  hollow.shape = growth::Shape::HollowBall;
  hollow.count = 20000;
  const auto r = build("hollowball", hollow, sp::Params());
  EXPECT_EQ(r->stat.holes, 0u);
  EXPECT_EQ(r->m.components, 2u);
  EXPECT_EQ(r->m.nonManifoldVertices + r->m.nonManifoldEdges, 0u);
  size_t inner = 0, wrong = 0;
  for (const auto& f : r->mesh.face) {
    const Point3d a = Point3d::Construct(f.cP(0)), b = Point3d::Construct(f.cP(1)), c = Point3d::Construct(f.cP(2));
    const Point3d g = (a + b + c) / 3.0;
    const bool isInner = g.Norm() < 0.9;
    inner += isInner;
    wrong += (((b - a) ^ (c - a)) * g > 0) == isInner;
  }
  EXPECT_GT(inner, 1000u);
  EXPECT_EQ(wrong, 0u);

  growth::CloudSpec slab;
  slab.shape = growth::Shape::Slab;
  slab.count = 30000;
  const auto s = build("slab", slab, sp::Params());
  EXPECT_EQ(s->m.nonManifoldVertices + s->m.nonManifoldEdges, 0u);
  EXPECT_EQ(s->m.inconsistentEdges, 0u);
  size_t top = 0, bottom = 0, flipped = 0;
  for (const auto& f : s->mesh.face) {
    const Point3d a = Point3d::Construct(f.cP(0)), b = Point3d::Construct(f.cP(1)), c = Point3d::Construct(f.cP(2));
    const Point3d n = ((b - a) ^ (c - a)).Normalize();
    if (std::abs(n[2]) < 0.9) continue;
    const bool up = (a[2] + b[2] + c[2]) > 0;
    (up ? top : bottom) += 1;
    flipped += (n[2] > 0) != up;
  }
  EXPECT_GT(top, 5000u);
  EXPECT_GT(bottom, 5000u);
  EXPECT_LE(flipped, 10u); // stray faces across the rim
}

// Closed plates about three mean spacings thick (as Robust G2S's thin-plate tests) at the automatic
// d (docs/design/spherepack-thin-parts.md). The noise estimate leaves out the neighbours on the
// other sheet, so that it does not read the two sheets as one noisy surface: d follows the plate's
// thickness (thickness / 1.2), and the boxes that see both sides keep both as two layers, so both
// sides are meshed, facing out of the plate. The rims keep a few holes where two 90-degree edges
// lie 1.2 d apart; the smaller splats (s = 0.9 × the thickness) keep their overhangs past the rim
// from meeting.
TEST(SpherePacker, ThinPlatesAboutThreeSpacingsThickAreMeshedOnBothSides) {
  for (const auto& c : {std::make_pair(0.025, 30000), std::make_pair(0.02, 50000)}) {
    SCOPED_TRACE(testing::Message() << "thickness " << c.first << ", " << c.second << " points");
    growth::CloudSpec slab;
    slab.shape = growth::Shape::Slab;
    slab.count = size_t(c.second);
    slab.slabThickness = c.first;
    const auto s = build("thinslab" + std::to_string(c.second), slab, sp::Params());
    EXPECT_EQ(s->m.nonManifoldVertices + s->m.nonManifoldEdges, 0u);
    EXPECT_EQ(s->m.inconsistentEdges, 0u);
    EXPECT_EQ(s->m.selfIntersectingPairs, 0u);
    EXPECT_EQ(s->m.components, 1u);
    EXPECT_GE(s->m.edgeMin, s->stat.sphereDiameter * (1 - 1e-5));
    // d from the thickness: the estimate saw the plate nearly everywhere.
    EXPECT_GT(s->stat.scale.thinShare, 0.9);
    EXPECT_NEAR(s->stat.scale.sheetGap, c.first, 0.05 * c.first);
    EXPECT_NEAR(s->stat.sphereDiameter, c.first / sp::kThinGapPerD, 0.05 * c.first);
    EXPECT_NE(s->stat.diameterReason.find("thin parts"), std::string::npos) << s->stat.diameterReason;
    EXPECT_NEAR(s->stat.splatSize, sp::kThinSplatPerGap * c.first, 0.05 * c.first);
    EXPECT_LE(s->stat.holes, 20u);
    EXPECT_LE(s->m.boundaryLoops, 40u); // the rims' loops, with those of the faces the clean-up removed
    EXPECT_EQ(s->stat.boundaryLoops, s->m.boundaryLoops);
    double top = 0, bottom = 0, wrong = 0;
    for (const auto& f : s->mesh.face) {
      const Point3d a = Point3d::Construct(f.cP(0)), b = Point3d::Construct(f.cP(1)), e = Point3d::Construct(f.cP(2));
      const Point3d cross = (b - a) ^ (e - a);
      const double area = 0.5 * cross.Norm();
      const double nz = cross[2] / (2 * area);
      if (std::abs(nz) < 0.9) continue;
      const bool up = (a[2] + b[2] + e[2]) > 0;
      if ((nz > 0) != up) wrong += area;
      else (up ? top : bottom) += area;
    }
    const double side = 4 * slab.slabHalfSize * slab.slabHalfSize;
    EXPECT_GT(top, 0.95 * side);
    EXPECT_GT(bottom, 0.95 * side);
    EXPECT_LT(wrong, 0.002 * side);
  }
}

TEST(SpherePacker, SameInputSameOutput) {
  const auto r = build("sphere", sphereSpec(), paperParams());
  CMeshO again;
  sp::Stat st;
  sp::build(r->cloud, again, r->params, st);
  ASSERT_EQ(again.vert.size(), r->mesh.vert.size());
  ASSERT_EQ(again.face.size(), r->mesh.face.size());
  for (size_t i = 0; i < again.vert.size(); ++i) EXPECT_EQ(again.vert[i].cP(), r->mesh.vert[i].cP());
  for (size_t i = 0; i < again.face.size(); ++i)
    for (int k = 0; k < 3; ++k)
      EXPECT_EQ(vcg::tri::Index(again, again.face[i].cV(k)), vcg::tri::Index(r->mesh, r->mesh.face[i].cV(k)));
}

// The per-box and per-point phases run on several threads: the mesh is the same, bit for bit,
// for any number of them (default parameters: d from the mean spacing, local splat sizes).
TEST(SpherePacker, SameOutputForAnyNumberOfThreads) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 20000;
  spec.seed = 2;
  spec.noiseBound = 0.01;
  CMeshO cloud;
  growth::toMesh(growth::generateCloud(spec), cloud);
  sp::Params p;
  p.threads = 1;
  CMeshO one;
  sp::Stat st1;
  sp::build(cloud, one, p, st1);
  ASSERT_GT(one.face.size(), 1000u);
  for (int threads : {2, 3}) {
    p.threads = threads;
    CMeshO mesh;
    sp::Stat st;
    sp::build(cloud, mesh, p, st);
    EXPECT_EQ(st.sphereDiameter, st1.sphereDiameter);
    EXPECT_EQ(st.splatSize, st1.splatSize);
    EXPECT_EQ(st.meanSplatRadius, st1.meanSplatRadius);
    EXPECT_EQ(st.boxes, st1.boxes);
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(mesh, one)) << threads << " threads";
  }
}

// Large clouds are processed in a spatial order of their points; every order the method depends
// on stays that of the input, so the mesh is the same as without (forced on and off here).
TEST(SpherePacker, SameOutputInSpatialOrder) {
  for (growth::Shape shape : {growth::Shape::Torus, growth::Shape::Patch}) {
    growth::CloudSpec spec;
    spec.shape = shape;
    spec.count = 20000;
    spec.seed = 5;
    spec.nonUniform = shape == growth::Shape::Patch;
    spec.noiseBound = 0.005;
    CMeshO cloud;
    growth::toMesh(growth::generateCloud(spec), cloud);
    sp::Params p;
    p.spatialOrderMinPoints = size_t(1) << 40; // never
    CMeshO plain, sorted;
    sp::Stat st1, st2;
    sp::build(cloud, plain, p, st1);
    p.spatialOrderMinPoints = 0; // always
    sp::build(cloud, sorted, p, st2);
    ASSERT_GT(plain.face.size(), 1000u);
    EXPECT_EQ(st2.meanSplatRadius, st1.meanSplatRadius);
    EXPECT_EQ(st2.boxesDTooLarge, st1.boxesDTooLarge);
    EXPECT_EQ(st2.unreachedPoints, st1.unreachedPoints);
    ASSERT_NO_FATAL_FAILURE(expectSameMesh(sorted, plain));
  }
}

TEST(SpherePacker, ManifoldWithNoiseUpToAThirdOfD) {
  growth::CloudSpec spec = sphereSpec();
  spec.noiseBound = 0.3 * 0.1; // sec. 5.3: each point moved by a random vector of length <= ν
  const auto r = build("sphere-noise-0.3d", spec, paperParams());
  const auto& m = r->m;
  EXPECT_EQ(m.nonManifoldEdges, 0u);
  EXPECT_EQ(m.nonManifoldVertices, 0u);
  EXPECT_EQ(m.inconsistentEdges, 0u);
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_EQ(m.eulerCharacteristic, 2);
  EXPECT_GE(m.edgeMin, 0.1 * (1 - 1e-5));
  EXPECT_GE(m.minVertexDistance, 0.1 * (1 - 1e-5));
}

// Noise beyond d/2: the packing is not manifold at some vertices (sec. 5.3); the fewest faces are
// removed so that the output is, with a warning that says so.
TEST(SpherePacker, NoiseFarBeyondHalfDIsMadeManifoldWithAWarning) {
  growth::CloudSpec spec = sphereSpec();
  spec.noiseBound = 1.0 * 0.1; // 2ν = 2d, far beyond the paper's d >= 2ν
  const auto r = build("sphere-noise-1d", spec, paperParams());
  ASSERT_FALSE(r->stat.warnings.empty());
  EXPECT_GT(r->stat.nonManifoldVerticesRemoved, 0u); // the packing itself was not manifold here
  EXPECT_GT(r->stat.facesRemoved, 0u);
  EXPECT_GT(r->stat.selfIntersectionFacesRemoved, 0u); // and faces through others
  EXPECT_EQ(r->m.selfIntersectingPairs, 0u);
  bool mentionsNoise = false;
  for (const auto& w : r->stat.warnings) mentionsNoise = mentionsNoise || w.find("noise") != std::string::npos;
  EXPECT_TRUE(mentionsNoise);
  // The guarantees hold whatever the input: manifold, every edge and vertex distance >= d.
  EXPECT_GE(r->m.edgeMin, 0.1 * (1 - 1e-5));
  EXPECT_GE(r->m.minVertexDistance, 0.1 * (1 - 1e-5));
  EXPECT_EQ(r->m.nonManifoldEdges, 0u);
  EXPECT_EQ(r->m.nonManifoldVertices, 0u);
  EXPECT_EQ(r->m.inconsistentEdges, 0u);
  // So much noise that no triangle fits: a clear error, no crash.
  spec.noiseBound = 3.0 * 0.1;
  CMeshO cloud, out;
  growth::toMesh(growth::generateCloud(spec), cloud);
  sp::Stat st;
  try {
    sp::build(cloud, out, paperParams(), st);
    EXPECT_FALSE(st.warnings.empty());
  } catch (const growth::Error& e) {
    EXPECT_NE(std::string(e.what()).find("noise"), std::string::npos) << e.what();
    EXPECT_EQ(out.vn, 0);
  }
}

TEST(SpherePacker, OpenPatchKeepsItsBoundaryAsAHole) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Patch;
  spec.count = 20000;
  spec.seed = 3;
  sp::Params p;
  p.checkInvariants = true;
  const auto r = build("patch", spec, p);
  const auto& m = r->m;
  EXPECT_EQ(m.nonManifoldEdges, 0u);
  EXPECT_EQ(m.nonManifoldVertices, 0u);
  EXPECT_EQ(m.inconsistentEdges, 0u);
  EXPECT_EQ(m.boundaryLoops, 1u); // the outer border, longer than ∂max, stays open
  EXPECT_EQ(r->stat.holes, 1u);
  EXPECT_GT(r->stat.longestBorder, size_t(p.maxBorderLength));
  EXPECT_EQ(m.eulerCharacteristic, 1); // a disk
  EXPECT_GE(m.qualityMean, 0.94);
  double worst = 0;
  for (const auto& v : r->mesh.vert) worst = std::max(worst, growth::distanceToShape(spec, Point3d::Construct(v.cP())));
  EXPECT_LE(worst, 0.01);
  // The limit decides sec. 3.7: with ∂max = 3 only the triangular regions are filled, the
  // quadrilaterals (the most common regions, sec. 3.7) stay open too (without the hole pass, which
  // would close them: the cloud covers them).
  sp::Params tight = p;
  tight.maxBorderLength = 3;
  tight.closeHoles = false;
  const auto t = build("patch-border-3", spec, tight);
  EXPECT_GT(t->stat.regionsLeftOpen, 100u);
  EXPECT_LT(t->m.faces, r->m.faces / 2);
  EXPECT_EQ(t->m.vertices > 0, true);
}

TEST(SpherePacker, WindowZeroIsBreadthFirstAndStillManifold) {
  sp::Params p = paperParams();
  p.windowSize = 0;
  p.maxBorderLength = 100; // its seams are longer than the default 40
  const auto r = build("torus-w0", torusSpec(), p);
  EXPECT_EQ(r->m.nonManifoldVertices, 0u);
  EXPECT_EQ(r->m.boundaryEdges, 0u);
  EXPECT_GE(r->m.edgeMin, 0.1 * (1 - 1e-5));
  // A different growth order (sec. 4.2: w = 0 is the breadth-first strategy): a different mesh,
  // with the long borders of the seams of fig. 7 (on the larger torus: on the 10k sphere the
  // longest border is only 1.8 times that of w = 8).
  const auto ref = build("torus", torusSpec(), paperParams());
  EXPECT_GT(r->stat.longestBorder, 2 * ref->stat.longestBorder);
  bool differs = r->mesh.vert.size() != ref->mesh.vert.size();
  for (size_t i = 0; !differs && i < r->mesh.vert.size(); ++i) differs = r->mesh.vert[i].cP() != ref->mesh.vert[i].cP();
  EXPECT_TRUE(differs);
}

TEST(SpherePacker, GlobalSplatSizeAtTheCoveringSize) {
  // Sec. 5.2: a global splat size just large enough to cover the sphere keeps the vertices on it.
  sp::Params p = paperParams();
  p.localSplatSizes = false;
  p.splatSize = 0.05;
  const auto r = build("sphere-global-0.05", sphereSpec(), p);
  expectClosedManifoldMesh(*r, 2);
  EXPECT_NEAR(r->stat.meanSplatRadius, 0.05, 1e-9);
  // Splats too small to cover: the growth stops early (sec. 5.2), with a warning.
  p.splatSize = 0.005;
  CMeshO out;
  sp::Stat st;
  try {
    sp::build(build("sphere", sphereSpec(), paperParams())->cloud, out, p, st);
    EXPECT_LT(st.vertices, r->stat.vertices / 2);
    EXPECT_FALSE(st.warnings.empty());
  } catch (const growth::Error& e) {
    EXPECT_EQ(out.vn, 0) << e.what();
  }
}

TEST(SpherePacker, StartingPointsGivenByTheUser) {
  const auto ref = build("sphere", sphereSpec(), paperParams());
  sp::Params p = paperParams();
  p.useStartPoints = true;
  p.startPoint[0] = Point3d(0, 0, -1.2); // projected onto the closest splats (bottom of the sphere)
  p.startPoint[1] = Point3d(0.15, 0, -1.2);
  CMeshO out;
  sp::Stat st;
  sp::build(ref->cloud, out, p, st);
  const auto m = growth::measure(out);
  EXPECT_EQ(m.nonManifoldVertices, 0u);
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_GE(m.qualityMean, 0.94);
  // The output hardly depends on the start (sec. 5.2: 0.9499–0.9504 over eight starts).
  EXPECT_NEAR(m.qualityMean, ref->m.qualityMean, 0.01);
  EXPECT_NEAR(double(m.vertices), double(ref->m.vertices), 0.03 * double(ref->m.vertices));
  // Projections not between d and 2d apart: refused with the reason.
  p.startPoint[1] = Point3d(0.02, 0, -1.2);
  CMeshO none;
  try {
    sp::build(ref->cloud, none, p, st);
    FAIL() << "starting points too close were accepted";
  } catch (const growth::Error& e) {
    EXPECT_NE(std::string(e.what()).find("between d"), std::string::npos) << e.what();
  }
  EXPECT_EQ(none.vn, 0);
}

TEST(SpherePacker, SuggestedParametersComeFromTheSampling) {
  const auto ref = build("sphere", sphereSpec(), paperParams());
  const sp::Params p = sp::suggestParams(ref->cloud);
  // d = 1.8 sqrt(area per point) on a clean cloud (the sphere's area per point is 4π / 10,000).
  const double areaSpacing = std::sqrt(4 * M_PI / 10000);
  EXPECT_NEAR(p.sphereDiameter, sp::kDefaultDiameterPerAreaSpacing * areaSpacing, 0.03 * p.sphereDiameter);
  EXPECT_NEAR(p.splatSize, sp::kDefaultSplatPerAreaSpacing * areaSpacing, 0.03 * p.splatSize);
  EXPECT_EQ(p.windowSize, 8);
  EXPECT_EQ(p.maxBorderLength, 40);
  // The defaults work without tuning, at the scan's resolution (at least 0.2 vertices per point).
  CMeshO out;
  sp::Stat st;
  sp::build(ref->cloud, out, sp::Params(), st);
  EXPECT_EQ(st.sphereDiameter, p.sphereDiameter);
  const auto m = growth::measure(out);
  EXPECT_EQ(m.nonManifoldVertices, 0u);
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_GE(m.qualityMean, 0.94);
  EXPECT_GE(double(m.vertices), 0.2 * 10000);
  EXPECT_NE(st.diameterReason.find("sampling"), std::string::npos) << st.diameterReason;
  // An unusable layer gives the static defaults, without throwing.
  CMeshO empty;
  const sp::Params q = sp::suggestParams(empty);
  EXPECT_EQ(q.sphereDiameter, 0);
}

// Sec. 5.3: d >= 2ν for an estimated noise ν. Noise of 1.2 sqrt(area per point) (2.5 median
// spacings) makes the default follow the noise, at 3ν; the result is manifold and closed.
TEST(SpherePacker, DefaultDiameterFollowsTheNoise) {
  growth::CloudSpec spec = sphereSpec();
  spec.count = 20000;
  const double nu = 1.2 * std::sqrt(4 * M_PI / 20000);
  spec.noiseBound = nu;
  CMeshO cloud, out;
  growth::toMesh(growth::generateCloud(spec), cloud);
  sp::Stat st;
  sp::build(cloud, out, sp::Params(), st);
  EXPECT_NEAR(st.scale.noise, nu, 0.25 * nu);
  EXPECT_NEAR(st.sphereDiameter, sp::kDefaultDiameterPerNoise * st.scale.noise, 1e-12);
  // The spacing it logs is growth::meanSpacing's estimator (the trimmed mean) on the estimate's
  // 8,000 samples: within sampling error of the number Robust G2S and mesh_measures report from
  // 20,000 (one spacing estimator for both filters and the measures).
  std::vector<Point3d> layer;
  for (const auto& v : cloud.vert) layer.push_back(Point3d::Construct(v.cP()));
  const double reference = growth::meanSpacing(layer);
  EXPECT_NEAR(st.scale.spacing, reference, 0.02 * reference);
  EXPECT_GT(st.scale.spacing, 0.0);
  EXPECT_NE(st.diameterReason.find("noise"), std::string::npos) << st.diameterReason;
  const auto m = growth::measure(out);
  EXPECT_TRUE(m.manifold());
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_GE(m.edgeMin, st.sphereDiameter * (1 - 1e-5));
}

// The default d is robust: one point far away, or 1 % of outliers scattered around the cloud,
// change it by less than 5 %.
TEST(SpherePacker, DefaultDiameterIgnoresFarPointsAndOutliers) {
  growth::CloudSpec spec = sphereSpec();
  spec.count = 50000;
  const growth::Cloud clean = growth::generateCloud(spec);
  auto defaultD = [](const growth::Cloud& c) {
    CMeshO m;
    growth::toMesh(c, m);
    return sp::suggestParams(m).sphereDiameter;
  };
  const double d0 = defaultD(clean);
  ASSERT_GT(d0, 0);
  growth::Cloud far = clean;
  far.points.insert(far.points.begin() + 1234, Point3d(1e4, 0, 0));
  far.normals.insert(far.normals.begin() + 1234, Point3d(1, 0, 0));
  EXPECT_NEAR(defaultD(far), d0, 0.05 * d0);
  growth::CloudSpec noisy = spec;
  noisy.outlierFraction = 0.01;
  EXPECT_NEAR(defaultD(growth::generateCloud(noisy)), d0, 0.05 * d0);
}

// Sec. 4.3 / 5.2: with the default splat radii, the clean closed clouds of 100k points (sphere,
// torus, genus 2, 5:1 non-uniform) are meshed closed and manifold at every d from 1.5 to 10 mean
// spacings, and every input point has a vertex within d.
TEST(SpherePackerCoverage, ClosedAtEveryDFromOneAndAHalfToTenSpacings) {
  std::vector<growth::CloudSpec> specs(4);
  specs[0].shape = growth::Shape::Sphere;
  specs[1].shape = growth::Shape::Torus;
  specs[2].shape = growth::Shape::Genus2;
  specs[3].shape = growth::Shape::Torus;
  specs[3].nonUniform = true;
  specs[3].densityRatio = 5;
  const int eulers[4] = {2, 0, -2, 0};
  // 100k points; 30k in the sanitizer build (scripts/sanitize.sh), where 100k took 6 minutes.
#ifdef GROWTH_SANITIZED
  const size_t count = 30000;
#else
  const size_t count = 100000;
#endif
  for (size_t k = 0; k < specs.size(); ++k) {
    specs[k].count = count;
    specs[k].seed = 5;
    const growth::Cloud c = growth::generateCloud(specs[k]);
    CMeshO cloud;
    growth::toMesh(c, cloud);
    const double spacing = growth::meanSpacing(c.points);
    for (double spacings : {1.5, 2.5, 5.0, 10.0}) {
      sp::Params p;
      p.sphereDiameter = spacings * spacing;
      CMeshO mesh;
      sp::Stat st;
      sp::build(cloud, mesh, p, st);
      const growth::MeshTopology t = growth::measureTopology(mesh);
      const std::string what = std::string(growth::shapeName(specs[k].shape)) + (specs[k].nonUniform ? " 5:1" : "") +
                               " at " + std::to_string(spacings) + " spacings";
      EXPECT_EQ(st.holes, 0u) << what;
      EXPECT_EQ(t.boundaryEdges, 0u) << what;
      EXPECT_EQ(t.nonManifoldVertices + t.nonManifoldEdges, 0u) << what;
      EXPECT_EQ(t.components, 1u) << what;
      EXPECT_EQ(int(mesh.vn) - int(t.edges) + mesh.fn, eulers[k]) << what;
      EXPECT_EQ(st.facesRemoved, 0u) << what;
      // Every input point has a vertex within d.
      growth::PointGrid vertices;
      std::vector<Point3d> vp;
      for (const auto& v : mesh.vert) vp.push_back(Point3d::Construct(v.cP()));
      vertices.build(vp, p.sphereDiameter);
      size_t far = 0;
      for (const auto& q : c.points) {
        double d2 = 0;
        far += vertices.nearest(q, &d2, -1, p.sphereDiameter) < 0 ? 1 : 0;
      }
      EXPECT_EQ(far, 0u) << what;
    }
  }
}

// Sec. 4.1: a fold (two sheets meeting at a sharp angle, normals on their outer sides) makes the
// boxes at the crease see opposed normals once d reaches across it: the warning fires there, and
// not at a d well below the fold's width.
TEST(SpherePackerBadInput, DTooLargeAtAFoldIsWarnedAbout) {
  growth::Cloud c;
  growth::Random rnd(21);
  const double half = 10 * M_PI / 180; // a 20° wedge: the sheets z = ±tan(10°)·x, x in [0, 1]
  for (int i = 0; i < 40000; ++i) {
    const double x = rnd.uniform(0, 1), y = rnd.uniform(0, 1);
    const double side = i % 2 ? 1.0 : -1.0;
    c.points.emplace_back(x, y, side * std::tan(half) * x);
    c.normals.push_back(Point3d(-std::sin(half), 0, side * std::cos(half)));
  }
  CMeshO cloud;
  growth::toMesh(c, cloud);
  auto warned = [&](double d) {
    sp::Params p;
    p.sphereDiameter = d;
    CMeshO out;
    sp::Stat st;
    try {
      sp::build(cloud, out, p, st);
    } catch (const growth::Error&) {
    }
    bool w = false;
    for (const auto& s : st.warnings) w = w || s.find("too large") != std::string::npos;
    return std::make_pair(w, double(st.boxesDTooLarge) / double(std::max<size_t>(st.boxes, 1)));
  };
  const auto coarse = warned(0.1), fine = warned(0.02);
  EXPECT_TRUE(coarse.first);
  EXPECT_GT(coarse.second, 0.0);
  // The boxes that see both sides lie where the sheets are closer than about 2d (x < ~6d here):
  // at d = 0.02 a far smaller share of the boxes than at d = 0.1.
  EXPECT_LT(fine.second, 0.5 * coarse.second);
}

namespace {
// Appends `c`, moved by `offset`, to `into`.
void append(growth::Cloud& into, const growth::Cloud& c, const Point3d& offset) {
  for (size_t i = 0; i < c.points.size(); ++i) {
    into.points.push_back(c.points[i] + offset);
    into.normals.push_back(c.normals[i]);
  }
}
} // namespace

// Sec. 3.3 again for every part the growth did not reach: a sphere, a small sphere (1 % of the
// points) beside it and a few stray points give two closed components; the strays stay unreached.
TEST(SpherePacker, EveryComponentIsMeshed) {
  growth::CloudSpec big = sphereSpec();
  big.count = 20000;
  growth::CloudSpec small = big;
  small.count = 200;
  small.sphereRadius = 0.1; // the same density
  small.seed = 2;
  growth::Cloud c = growth::generateCloud(big);
  append(c, growth::generateCloud(small), Point3d(1.6, 0, 0));
  for (int k = 0; k < 5; ++k) {
    c.points.push_back(Point3d(-3.0 - 0.7 * k, 0.5 * k, 1.0));
    c.normals.push_back(Point3d(0, 0, 1));
  }
  CMeshO cloud, mesh;
  growth::toMesh(c, cloud);
  sp::Params p;
  p.sphereDiameter = 0.03; // 2.4 mean spacings
  sp::Stat st;
  sp::build(cloud, mesh, p, st);
  const growth::MeshMeasures m = growth::measure(mesh);
  EXPECT_EQ(st.componentsStarted, 2u);
  EXPECT_EQ(m.components, 2u);
  EXPECT_EQ(m.boundaryEdges, 0u);
  EXPECT_TRUE(m.manifold());
  EXPECT_GE(m.edgeMin, 0.03 * (1 - 1e-5));
  EXPECT_EQ(st.unreachedPoints, 5u);
  size_t onSmall = 0;
  for (const auto& v : mesh.vert) onSmall += (Point3d::Construct(v.cP()) - Point3d(1.6, 0, 0)).Norm() < 0.2 ? 1 : 0;
  EXPECT_GT(onSmall, 20u);
}

namespace {
// A sphere of 20,000 points (mean spacing about 0.0125) and, over its cap z > 0.5, a second scan
// layer of the same density `offset` further out: a misregistered scan (docs/design/spherepack-every-part.md).
growth::Cloud sphereWithSecondLayer(double offset) {
  growth::CloudSpec big = sphereSpec();
  big.count = 20000;
  growth::Cloud c = growth::generateCloud(big);
  growth::CloudSpec outer = big;
  outer.seed = 2;
  outer.sphereRadius = 1 + offset;
  const growth::Cloud layer = growth::generateCloud(outer);
  for (size_t i = 0; i < layer.points.size(); ++i)
    if (layer.normals[i][2] > 0.5) {
      c.points.push_back(layer.points[i]);
      c.normals.push_back(layer.normals[i]);
    }
  return c;
}

struct Meshed {
  CMeshO mesh;
  sp::Stat st;
  growth::MeshMeasures m;
};
std::unique_ptr<Meshed> mesh(const growth::Cloud& c, const sp::Params& p) {
  auto r = std::make_unique<Meshed>();
  CMeshO cloud;
  growth::toMesh(c, cloud);
  sp::build(cloud, r->mesh, p, r->st);
  r->m = growth::measure(r->mesh);
  return r;
}
} // namespace

// A second layer d over part of the surface: the growth stopped on it at many places, and every
// unreached point with no vertex within d got a start of its own (276 starts, 41 pieces before).
// Now no start is placed within 2d of a vertex, and what grew across onto the layer in small
// flaps is dropped: one piece, manifold, every edge at least d.
TEST(SpherePackerComponents, SecondScanLayerOneSpacingOffGivesOnePiece) {
  sp::Params p;
  p.sphereDiameter = 0.03; // 2.4 mean spacings; the layer lies 1 d out
  const auto r = mesh(sphereWithSecondLayer(0.03), p);
  EXPECT_EQ(r->m.components, 1u);
  EXPECT_LE(r->st.componentsStarted, 2u);
  EXPECT_GT(r->st.startsRefusedNearMesh, 0u);
  EXPECT_TRUE(r->m.manifold());
  EXPECT_EQ(r->m.selfIntersectingPairs, 0u);
  EXPECT_GE(r->m.edgeMin, 0.03 * (1 - 1e-5));
  EXPECT_GE(r->m.minVertexDistance, 0.03 * (1 - 1e-5));
  EXPECT_GT(r->m.faces, 25000u); // the sphere, about 29,000 faces
  EXPECT_LE(r->m.boundaryEdges, 200u);
}

// Small clumps of stray points each hold a start and a triangle or a few: dropped, counted in
// the Stat, and kept with minComponentFaces = 0.
TEST(SpherePackerComponents, StrayClumpsAreDroppedAndCounted) {
  growth::CloudSpec big = sphereSpec();
  big.count = 20000;
  growth::Cloud c = growth::generateCloud(big);
  growth::Random rnd(7);
  const int clumps = 6;
  for (int k = 0; k < clumps; ++k) {
    const Point3d centre(3.0 + 0.5 * k, 0.3 * k, -1.0); // far from the sphere and from each other
    for (int j = 0; j < 6; ++j) {
      const double a = 2 * 3.14159265358979 * rnd.uniform(), r = 0.02 * std::sqrt(rnd.uniform());
      c.points.push_back(centre + Point3d(r * std::cos(a), r * std::sin(a), 0));
      c.normals.push_back(Point3d(0, 0, 1));
    }
  }
  sp::Params p;
  p.sphereDiameter = 0.03;
  p.minComponentFaces = 0;
  const auto kept = mesh(c, p);
  EXPECT_EQ(kept->st.componentsDropped, 0u);
  ASSERT_GT(kept->m.components, 1u); // the clumps made faces
  const size_t clumpPieces = kept->m.components - 1;
  p.minComponentFaces = 50;
  const auto dropped = mesh(c, p);
  EXPECT_EQ(dropped->m.components, 1u);
  EXPECT_EQ(dropped->st.componentsDropped, clumpPieces);
  EXPECT_EQ(dropped->st.componentFacesDropped, kept->m.faces - dropped->m.faces);
  EXPECT_EQ(dropped->st.faces, dropped->m.faces);
  EXPECT_EQ(dropped->m.boundaryEdges, 0u);
  EXPECT_TRUE(dropped->m.manifold());
  EXPECT_GE(dropped->m.edgeMin, 0.03 * (1 - 1e-5));
  for (const auto& v : dropped->mesh.vert) EXPECT_LT(Point3d::Construct(v.cP()).Norm(), 1.1);
}

// The largest piece stays whatever the minimum; a negative minimum is refused.
TEST(SpherePackerComponents, TheLargestPieceAlwaysStays) {
  growth::CloudSpec s = sphereSpec();
  s.count = 2000;
  sp::Params p;
  p.minComponentFaces = 1000000;
  const auto r = mesh(growth::generateCloud(s), p);
  EXPECT_EQ(r->m.components, 1u);
  EXPECT_EQ(r->st.componentsDropped, 0u);
  EXPECT_GT(r->m.faces, 100u);
  p.minComponentFaces = -1;
  EXPECT_THROW(mesh(growth::generateCloud(s), p), growth::Error);
}

namespace {
// Runs build on `cloud` and returns the growth::Error message ("" when it did not throw).
std::string errorOf(const CMeshO& cloud, const sp::Params& p = sp::Params()) {
  CMeshO out;
  sp::Stat st;
  try {
    sp::build(cloud, out, p, st);
  } catch (const growth::Error& e) {
    EXPECT_EQ(out.vn, 0);
    EXPECT_EQ(out.fn, 0);
    return e.what();
  }
  return "";
}

void smallSphere(CMeshO& m, size_t n = 2000) {
  growth::CloudSpec s = sphereSpec();
  s.count = n;
  growth::toMesh(growth::generateCloud(s), m);
}
} // namespace

TEST(SpherePackerBadInput, EmptyLayer) {
  CMeshO m;
  EXPECT_NE(errorOf(m).find("no vertices"), std::string::npos);
}

TEST(SpherePackerBadInput, NoNormalsSaysHowToComputeThem) {
  CMeshO m;
  smallSphere(m);
  for (auto& v : m.vert) v.N() = CMeshO::CoordType(0, 0, 0);
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("Compute normals for point sets"), std::string::npos) << e;
}

TEST(SpherePackerBadInput, NaNCoordinates) {
  CMeshO m;
  smallSphere(m);
  m.vert[7].P()[1] = std::nanf("");
  EXPECT_NE(errorOf(m).find("NaN"), std::string::npos);
}

TEST(SpherePackerBadInput, AllPointsIdentical) {
  CMeshO m;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 50);
  for (auto& v : m.vert) v.P() = CMeshO::CoordType(1, 2, 3), v.N() = CMeshO::CoordType(0, 0, 1);
  EXPECT_NE(errorOf(m).find("identical"), std::string::npos);
}

TEST(SpherePackerBadInput, DLargerThanTheCloud) {
  CMeshO m;
  smallSphere(m);
  sp::Params p;
  p.sphereDiameter = 5.0; // the unit sphere's box diagonal is 3.46
  const std::string e = errorOf(m, p);
  EXPECT_NE(e.find("larger than the cloud"), std::string::npos) << e;
}

// Three points: the automatic d (from their spacing) is larger than the cloud; the message says
// the cloud is too sparse, and does not offer that same d as the way out.
TEST(SpherePackerBadInput, TooFewPointsForTheAutomaticD) {
  CMeshO m;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 3);
  m.vert[0].P() = CMeshO::CoordType(0, 0, 0);
  m.vert[1].P() = CMeshO::CoordType(1, 0, 0);
  m.vert[2].P() = CMeshO::CoordType(0, 1, 0);
  for (auto& v : m.vert) v.N() = CMeshO::CoordType(0, 0, 1);
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("Too few points, or too sparse"), std::string::npos) << e;
  EXPECT_NE(e.find("Give a d below 0.7071"), std::string::npos) << e;
  EXPECT_EQ(e.find("the default"), std::string::npos) << e;
}

// Normals whose sign changes from point to point: a mesh with holes (never a non-manifold one)
// and a warning that names the cause and the MeshLab filter that orients them.
TEST(SpherePackerBadInput, UnorientedNormalsAreNamedInTheWarning) {
  CMeshO m;
  smallSphere(m, 3000);
  growth::Random rnd(3);
  for (auto& v : m.vert)
    if (rnd.uniform(0, 1) < 0.5) v.N() = -v.N();
  CMeshO out;
  sp::Stat st;
  sp::build(m, out, sp::Params(), st);
  EXPECT_GT(st.faces, 0u);
  EXPECT_EQ(st.nonManifoldVertices, 0u);
  EXPECT_EQ(st.nonManifoldEdges, 0u);
  std::string warning;
  for (const auto& w : st.warnings)
    if (w.find("look unoriented") != std::string::npos) warning = w;
  EXPECT_NE(warning.find("Compute normals for point sets"), std::string::npos) << warning;
}

TEST(SpherePackerBadInput, DSoSmallThatTheOutputWouldExplode) {
  CMeshO m;
  smallSphere(m);
  sp::Params p;
  p.sphereDiameter = 1e-4; // 4π / (0.866e-8) ≈ 1.5e9 vertices
  const std::string e = errorOf(m, p);
  EXPECT_NE(e.find("too small"), std::string::npos) << e;
  EXPECT_NE(e.find("vertices"), std::string::npos) << e;
  // The limit is a parameter.
  p.sphereDiameter = 0.05;
  p.maxOutputVertices = 1000; // ~5800 needed
  EXPECT_NE(errorOf(m, p).find("too small"), std::string::npos);
}

TEST(SpherePackerBadInput, AMeshInsteadOfACloud) {
  CMeshO m;
  smallSphere(m, 100);
  vcg::tri::Allocator<CMeshO>::AddFace(m, &m.vert[0], &m.vert[1], &m.vert[2]);
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("is a mesh"), std::string::npos) << e;
}

TEST(SpherePackerBadInput, BadWindowOrBorderLimit) {
  CMeshO m;
  smallSphere(m);
  sp::Params p;
  p.windowSize = -1;
  EXPECT_NE(errorOf(m, p).find("window"), std::string::npos);
  p = sp::Params();
  p.maxBorderLength = 2;
  EXPECT_NE(errorOf(m, p).find("border limit"), std::string::npos);
}

TEST(SpherePackerBadInput, DTooLargeForAThinPlateIsWarnedAbout) {
  // Two sheets 0.05 apart with opposite normals (a thin plate); d = 0.2 sees both in its boxes.
  CMeshO m;
  const int n = 60;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 2 * n * n);
  size_t k = 0;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j)
      for (int side = 0; side < 2; ++side, ++k) {
        m.vert[k].P() = CMeshO::CoordType(i * 0.02f + 0.007f * side, j * 0.02f, side ? -0.025f : 0.025f);
        m.vert[k].N() = CMeshO::CoordType(0, 0, side ? -1.0f : 1.0f);
      }
  sp::Params p;
  p.sphereDiameter = 0.2;
  CMeshO out;
  sp::Stat st;
  try {
    sp::build(m, out, p, st);
  } catch (const growth::Error&) {
  }
  EXPECT_GT(st.boxesDTooLarge, 0u);
  bool warned = false, unoriented = false;
  for (const auto& w : st.warnings) warned = warned || w.find("too large") != std::string::npos;
  for (const auto& w : st.warnings) unoriented = unoriented || w.find("unoriented") != std::string::npos;
  EXPECT_TRUE(warned);
  EXPECT_FALSE(unoriented); // the normals are oriented: the plate is thin
}

namespace {
int g_calls = 0, g_cancelAt = -1, g_lastPercent = -1;
bool g_monotonic = true;
bool countingCallback(const int pos, const char*) {
  ++g_calls;
  if (pos < g_lastPercent) g_monotonic = false;
  g_lastPercent = pos;
  return g_cancelAt < 0 || g_calls < g_cancelAt;
}
} // namespace

TEST(SpherePackerProgress, AFewHundredUpdatesAtMost) {
  const auto ref = build("sphere", sphereSpec(), paperParams());
  g_calls = 0;
  g_cancelAt = -1;
  g_lastPercent = -1;
  g_monotonic = true;
  CMeshO out;
  sp::Stat st;
  sp::build(ref->cloud, out, paperParams(), st, countingCallback);
  EXPECT_GE(g_calls, 10);
  EXPECT_LE(g_calls, 400);
  EXPECT_TRUE(g_monotonic);
  EXPECT_GT(out.fn, 0);
}

// The progress callbacks are the same sequence for any number of threads (the phases that share
// work between threads report every percentage they pass), so a cancel at the k-th callback is
// reproducible.
TEST(SpherePackerProgress, SameCallbacksForAnyNumberOfThreads) {
  const auto ref = build("sphere", sphereSpec(), paperParams());
  static std::vector<int> seen;
  auto record = [](const int pos, const char*) {
    seen.push_back(pos);
    return true;
  };
  std::vector<int> first;
  for (int threads : {1, 2, 3, 2}) {
    sp::Params p = paperParams();
    p.checkInvariants = false;
    p.threads = threads;
    seen.clear();
    CMeshO out;
    sp::Stat st;
    sp::build(ref->cloud, out, p, st, record);
    if (first.empty()) first = seen;
    EXPECT_EQ(seen, first) << threads << " threads";
  }
  EXPECT_GE(first.size(), 50u);
}

TEST(SpherePackerProgress, CancelLeavesNothing) {
  const auto ref = build("sphere", sphereSpec(), paperParams());
  g_calls = 0;
  g_cancelAt = -1;
  CMeshO all;
  sp::Stat st0;
  sp::build(ref->cloud, all, paperParams(), st0, countingCallback);
  const int total = g_calls;
  ASSERT_GE(total, 10);
  // Cancel in every phase: reading, box grid, splats, growth (several times), triangulation.
  for (int at : {1, 3, 8, total / 3, total / 2, (2 * total) / 3, total - 1}) {
    g_calls = 0;
    g_cancelAt = at;
    g_lastPercent = -1;
    CMeshO out;
    sp::Stat st;
    EXPECT_THROW(sp::build(ref->cloud, out, paperParams(), st, countingCallback), growth::Cancelled) << at;
    EXPECT_EQ(out.vn, 0);
    EXPECT_EQ(out.fn, 0);
  }
  g_cancelAt = -1;
}

// The limit on the output is checked again while the mesh grows: the estimate before the growth
// comes from the points' surface area, and large splats on a thick noisy cloud cover more
// (fuzz/regressions/cloud/spherepack_output_past_estimate grows far past its estimate).
TEST(SpherePackerBadInput, OutputPastTheEstimateStopsWithAClearError) {
  growth::CloudSpec s = sphereSpec();
  s.count = 2000;
  s.gaussianSigma = 0.05;
  CMeshO m;
  growth::toMesh(growth::generateCloud(s), m);
  sp::Params p;
  p.sphereDiameter = 0.04;
  p.splatSize = 0.3;
  CMeshO out;
  sp::Stat st;
  sp::build(m, out, p, st); // 18,500 vertices where the area estimate says 10,400
  const double estimate = st.scale.area / (p.sphereDiameter * p.sphereDiameter * std::sqrt(3.0) / 2);
  ASSERT_GT(double(st.vertices), 1.5 * estimate);
  p.maxOutputVertices = size_t(1.25 * estimate); // passes the check before the growth
  const std::string e = errorOf(m, p);
  EXPECT_NE(e.find("grew past the limit of " + std::to_string(p.maxOutputVertices) + " vertices"), std::string::npos)
      << e;
  EXPECT_NE(e.find("larger sphere diameter"), std::string::npos) << e;
}

// One stray point a million units away would make the extent exceed the box grid's 2^21 boxes of
// side d per axis, and the whole cloud be refused ("use a larger d"): the far point is left out of
// the packing, counted and warned about, and the sphere is meshed closed
// (docs/design/spherepack-far-points.md).
TEST(SpherePackerFarPoints, OneStrayPointFarAwayIsLeftOut) {
  growth::CloudSpec spec = sphereSpec();
  spec.count = 20000;
  growth::Cloud c = growth::generateCloud(spec);
  c.points.insert(c.points.begin() + 777, Point3d(1e6, 0, 0));
  c.normals.insert(c.normals.begin() + 777, Point3d(1, 0, 0));
  std::unique_ptr<Meshed> r;
  ASSERT_NO_THROW(r = mesh(c, sp::Params()));
  EXPECT_EQ(r->st.farPointsLeftOut, 1u);
  EXPECT_GT(r->st.farPointsGap, 1e5);
  EXPECT_EQ(r->m.components, 1u);
  EXPECT_EQ(r->m.boundaryEdges, 0u);
  EXPECT_TRUE(r->m.manifold());
  EXPECT_EQ(r->m.eulerCharacteristic, 2);
  EXPECT_GE(r->m.edgeMin, r->st.sphereDiameter * (1 - 1e-5));
  ASSERT_EQ(r->st.warnings.size(), 1u);
  EXPECT_NE(r->st.warnings[0].find("1 point lies"), std::string::npos) << r->st.warnings[0];
  EXPECT_NE(r->st.warnings[0].find("left out of the mesh"), std::string::npos) << r->st.warnings[0];
}

// Two separate spheres of 20,000 points each: 10^4 apart both are meshed (the grid reaches that
// far at their d); 10^6 apart the cloud is refused with a message that says why and what to do
// (the parts are the bulk of the cloud, not stray points: nothing is left out silently).
TEST(SpherePackerFarPoints, TwoPartsFarApartAreBothMeshedOrRefusedClearly) {
  growth::CloudSpec a = sphereSpec();
  a.count = 20000;
  growth::CloudSpec b = a;
  b.seed = 2;
  const growth::Cloud ca = growth::generateCloud(a), cb = growth::generateCloud(b);
  growth::Cloud near = ca;
  append(near, cb, Point3d(1e4, 0, 0));
  std::unique_ptr<Meshed> r;
  ASSERT_NO_THROW(r = mesh(near, sp::Params()));
  EXPECT_EQ(r->st.farPointsLeftOut, 0u);
  EXPECT_EQ(r->m.components, 2u);
  EXPECT_EQ(r->m.boundaryEdges, 0u);
  EXPECT_TRUE(r->m.manifold());
  size_t onSecond = 0;
  for (const auto& v : r->mesh.vert) onSecond += v.cP()[0] > 5e3 ? 1 : 0;
  EXPECT_GT(onSecond, r->m.vertices / 3);

  growth::Cloud far = ca;
  append(far, cb, Point3d(1e6, 0, 0));
  CMeshO cloud;
  growth::toMesh(far, cloud);
  const std::string e = errorOf(cloud, sp::Params());
  EXPECT_NE(e.find("along x its bulk"), std::string::npos) << e;
  EXPECT_NE(e.find("mesh them one at a time"), std::string::npos) << e;
  EXPECT_NE(e.find("a d of at least"), std::string::npos) << e;
}

// A sphere of 20,000 points and a small one (`count` points, `radius`, `seed`) moved by `offset`.
growth::Cloud sphereAndSmallPart(size_t count, double radius, std::uint64_t seed, const Point3d& offset) {
  growth::CloudSpec big = sphereSpec();
  big.count = 20000;
  growth::CloudSpec small = big;
  small.count = count;
  small.sphereRadius = radius;
  small.seed = seed;
  growth::Cloud c = growth::generateCloud(big);
  append(c, growth::generateCloud(small), offset);
  return c;
}

// A small separate part (0.5 % of the points) 10^6 away: beyond the grid's reach, left out and
// named in the warning (a part that small is not the bulk of the cloud).
TEST(SpherePackerFarPoints, ASmallPartFarAwayIsLeftOutWithAWarning) {
  growth::Cloud c = sphereAndSmallPart(100, 0.07, 3, Point3d(0, -1e6, 0));
  std::unique_ptr<Meshed> r;
  ASSERT_NO_THROW(r = mesh(c, sp::Params()));
  EXPECT_EQ(r->st.farPointsLeftOut, 100u);
  EXPECT_EQ(r->m.components, 1u);
  EXPECT_EQ(r->m.boundaryEdges, 0u);
  ASSERT_FALSE(r->st.warnings.empty());
  EXPECT_NE(r->st.warnings[0].find("100 points lie"), std::string::npos) << r->st.warnings[0];
  EXPECT_NE(r->st.warnings[0].find("mesh it on its own"), std::string::npos) << r->st.warnings[0];
}

// A vertex placed at the midpoint of an edge of length 2d can give a face with three collinear
// vertices (edges d, d, 2d: zero area), as on this torus with 10 % outliers. No face with an angle
// above 179° is written; the mesh stays manifold, the three edges a hole.
TEST(SpherePackerFlatFaces, NoFaceWithCollinearVertices) {
  growth::CloudSpec s = torusSpec();
  s.count = 5000;
  s.outlierFraction = 0.1;
  s.seed = 2;
  auto r = mesh(growth::generateCloud(s), sp::Params());
  EXPECT_EQ(r->m.degenerateFaces, 0u);
  EXPECT_GE(r->st.flatFacesRemoved, 1u);
  EXPECT_TRUE(r->m.manifold());
  EXPECT_EQ(r->m.nonManifoldEdges, 0u);
  EXPECT_EQ(r->m.nonManifoldVertices, 0u);
  EXPECT_EQ(r->m.selfIntersectingPairs, 0u);
  size_t flat = 0;
  for (const auto& f : r->mesh.face)
    flat += growth::nearlyCollinear(Point3d::Construct(f.cP(0)), Point3d::Construct(f.cP(1)),
                                    Point3d::Construct(f.cP(2)))
                ? 1
                : 0;
  EXPECT_EQ(flat, 0u);
}

// A torus 300 across, 10^6 from the origin. The engine keeps every edge at
// least d in double, but MeshLab 2020.09 stores float, whose steps are 0.0625 there. The smallest
// edge reported is the one of the stored mesh, and a warning says why it is below d.
TEST(SpherePackerStoredPrecision, SmallestEdgeIsMeasuredAsStored) {
  growth::CloudSpec s = torusSpec();
  s.count = 20000;
  s.torusMajor = 100;
  s.torusMinor = 50;
  growth::Cloud c = growth::generateCloud(s);
  for (auto& p : c.points) p += Point3d(1e6, 1e6, 1e6);
  auto r = mesh(c, sp::Params());
  const double d = r->st.sphereDiameter;
  EXPECT_TRUE(r->m.manifold());
  EXPECT_NEAR(r->st.smallestEdge, r->m.edgeMin, 1e-9 * d);
  bool warned = false;
  for (const auto& w : r->st.warnings) warned = warned || w.find("below d") != std::string::npos;
  if (sizeof(CMeshO::ScalarType) == sizeof(float)) {
    EXPECT_LT(r->m.edgeMin, d * (1 - sp::kSmallestEdgeTolerance)); // float storage shortens some edge below d
    EXPECT_TRUE(warned);
  } else {
    EXPECT_GE(r->m.edgeMin, d * (1 - sp::kSmallestEdgeTolerance));
    EXPECT_FALSE(warned);
  }
}

// Only what the grid cannot reach is left out: a small part 2 units off the sphere (far more than
// 8 d, but within reach) stays and is meshed when a stray point 10^6 away is left out.
TEST(SpherePackerFarPoints, ANearSmallPartStaysWhenAFarPointIsLeftOut) {
  growth::Cloud c = sphereAndSmallPart(200, 0.1, 2, Point3d(0, 3, 0));
  c.points.push_back(Point3d(1e6, 0, 0));
  c.normals.push_back(Point3d(1, 0, 0));
  sp::Params p;
  p.sphereDiameter = 0.03;
  std::unique_ptr<Meshed> r;
  ASSERT_NO_THROW(r = mesh(c, p));
  EXPECT_EQ(r->st.farPointsLeftOut, 1u);
  EXPECT_EQ(r->m.components, 2u);
  EXPECT_EQ(r->m.boundaryEdges, 0u);
  size_t onSmall = 0;
  for (const auto& v : r->mesh.vert) onSmall += (Point3d::Construct(v.cP()) - Point3d(0, 3, 0)).Norm() < 0.2 ? 1 : 0;
  EXPECT_GT(onSmall, 20u);
}

// The engine's memory (Stat::memory): each part counted, the peak at least what is held at once at
// the end of the growth and at the output, and within the budget per input point at d = 2.5 mean
// spacings (about 0.66 output vertices per point).
TEST(SpherePackerMemory, PeakAndItsPartsAreReportedWithinTheBudget) {
  growth::CloudSpec spec = torusSpec();
  spec.count = 200000;
  const growth::CloudArrays cloud = growth::toArrays(growth::generateCloud(spec));
  sp::Params p;
  p.sphereDiameter = 2.5 * growth::meanSpacing(cloud.points);
  growth::MeshArrays out;
  sp::Stat st;
  sp::build(cloud, out, p, st);
  const sp::Stat::Memory& m = st.memory;
  const size_t n = spec.count;
  EXPECT_GE(m.input, 2 * 24 * n + 4 * n); // positions and normals in double, radii in float
  EXPECT_GE(m.boxGrid, 4 * n);            // at least one reference per point
  EXPECT_GE(m.growth, st.vertices * (24 + 24)); // positions and normals of G
  EXPECT_GE(m.faces, 12 * st.faces);
  EXPECT_GE(m.output, 24 * st.vertices + 12 * st.faces);
  EXPECT_GE(m.peak, m.input + m.boxGrid + m.growth);
  EXPECT_GE(m.peak, m.faces + m.output);
  EXPECT_LE(double(m.peak) / double(n), 550.0) << "bytes per point";
}

// The peak estimated before the box grid (Stat::memory.estimate) is within a fifth of the peak at
// small, usual and large d; a run whose estimate exceeds Params::maxMemoryBytes is refused before
// the box grid, with the estimate in the message, and leaves nothing.
TEST(SpherePackerMemory, TheEstimateIsCloseAndALimitRefusesBeforeTheWork) {
  growth::CloudSpec spec = torusSpec();
  spec.count = 100000;
  const growth::CloudArrays cloud = growth::toArrays(growth::generateCloud(spec));
  const double spacing = growth::meanSpacing(cloud.points);
  for (double k : {1.5, 2.5, 5.0}) {
    sp::Params p;
    p.sphereDiameter = k * spacing;
    growth::MeshArrays out;
    sp::Stat st;
    sp::build(cloud, out, p, st);
    EXPECT_GT(st.memory.limit, 0u) << "the machine's available memory";
    const double ratio = double(st.memory.estimate) / double(st.memory.peak);
    EXPECT_GT(ratio, 0.8) << k << " spacings";
    EXPECT_LT(ratio, 1.25) << k << " spacings";
  }
  sp::Params p;
  p.sphereDiameter = 2.5 * spacing;
  p.maxMemoryBytes = 8u << 20; // 8 MiB: less than the input alone
  growth::MeshArrays out;
  out.faces.push_back({0, 1, 2});
  sp::Stat st;
  try {
    sp::build(cloud, out, p, st);
    FAIL() << "not refused";
  } catch (const growth::Error& e) {
    EXPECT_NE(std::string(e.what()).find("GiB of memory"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("larger d"), std::string::npos) << e.what();
  }
  EXPECT_TRUE(out.faces.empty() && out.vertices.empty());
  EXPECT_EQ(st.memory.limit, p.maxMemoryBytes);
  EXPECT_EQ(st.secondsBoxGrid, 0.0) << "refused before the box grid";
}

// The guarantees at a million points (the benchmark checks them at ten million): a scan-like cloud
// of six separate parts with noise, 2 % stray points and 1 % flipped normals, at the automatic
// parameters: every edge and every pair of vertices at least d (double output), manifold, no
// intersecting faces, each part meshed.
TEST(SpherePackerScale, AMillionPointScanKeepsEveryGuarantee) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Scan;
  spec.scanParts = 6;
  spec.count = 980392; // with the 2 % outliers: 1,000,000 points
  spec.seed = 1;
  spec.gaussianSigma = 0.1 * std::sqrt(growth::shapeArea(spec) / double(spec.count));
  spec.outlierFraction = 0.02;
  spec.flippedNormals = 0.01;
  const growth::CloudArrays cloud = growth::toArrays(growth::generateCloud(spec));
  ASSERT_EQ(cloud.points.size(), 1000000u);
  growth::MeshArrays out;
  sp::Stat st;
  sp::build(cloud, out, sp::Params(), st);
  const double d = st.sphereDiameter;
  const growth::MeshMeasures m = growth::measure(out);
  EXPECT_GT(m.faces, 500000u);
  EXPECT_GE(m.edgeMin, d * (1 - 1e-12));
  EXPECT_GE(m.minVertexDistance, d * (1 - 1e-12));
  EXPECT_TRUE(m.manifold()) << m.nonManifoldEdges << " edges, " << m.nonManifoldVertices << " vertices";
  EXPECT_TRUE(m.consistentlyOriented());
  EXPECT_EQ(m.selfIntersectingPairs, 0u);
  EXPECT_EQ(m.components, 6u) << "one piece per part";
  EXPECT_EQ(st.vertices, m.vertices);
  EXPECT_LE(double(st.memory.peak) / 1e6, 600.0) << "MB";
}
