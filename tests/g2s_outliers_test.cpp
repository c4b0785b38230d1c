// Robust G2S on clouds with far points and dense clusters: the spacing it
// measures and logs is growth::meanSpacing (the one mesh_measures and the benchmark use), and
// one point far away changes neither it nor the mesh's holes.
#include "filter_g2s_layer.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>

#include <common/ml_mesh_type.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <vector>

using growth::CloudSpec;
using growth::Shape;
namespace g2s = growth::g2s;

namespace {

struct Run {
  std::vector<growth::Vec3d> points; // as the layer holds them (float), as mesh_measures reads them
  CMeshO mesh;
  g2s::Stat stat;
};

std::unique_ptr<Run> run(const CloudSpec& spec) {
  std::unique_ptr<Run> r(new Run);
  const growth::Cloud cloud = growth::generateCloud(spec);
  CMeshO in;
  growth::toMesh(cloud, in);
  for (const auto& v : in.vert) r->points.push_back(growth::Vec3d::Construct(v.cP()));
  CMeshO none;
  g2s::build(in, r->mesh, g2s::suggestParams(none), r->stat);
  return r;
}

CloudSpec spec(Shape shape, size_t count) {
  CloudSpec s;
  s.shape = shape;
  s.count = count;
  return s;
}

} // namespace

TEST(G2SOutliers, TheLoggedSpacingIsTheMeanSpacingOfTheMeasures) {
  for (Shape shape : {Shape::Sphere, Shape::Patch}) {
    for (size_t far : {size_t(0), size_t(1)}) {
      CloudSpec s = spec(shape, 30000);
      s.farPoints = far;
      const auto r = run(s);
      EXPECT_EQ(r->stat.spacing, growth::meanSpacing(r->points)) << far;
    }
  }
}

TEST(G2SOutliers, OneFarPointChangesNeitherTheSpacingNorTheHoles) {
  for (Shape shape : {Shape::Sphere, Shape::Torus}) {
    const auto clean = run(spec(shape, 50000));
    CloudSpec s = spec(shape, 50000);
    s.farPoints = 1;
    const auto far = run(s);
    EXPECT_EQ(clean->stat.holes, 0u);
    EXPECT_EQ(far->stat.holes, 0u);
    EXPECT_LE(far->stat.unusedPoints, clean->stat.unusedPoints + 1); // the far point alone
    EXPECT_NEAR(far->stat.spacing, clean->stat.spacing, 1e-3 * clean->stat.spacing);
    EXPECT_EQ(far->stat.faces, clean->stat.faces);
  }
}

TEST(G2SOutliers, AFarPointOrADenseClusterCostsTheIndexAtMostHalfAgainTheCleanCloudsWork) {
  // The work is the number of points the index scans for the queries (deterministic, unlike the
  // wall time); the cluster: 1 % of the points within a hundredth of the spacing of one sample.
  for (Shape shape : {Shape::Sphere, Shape::Torus}) {
    const auto clean = run(spec(shape, 50000));
    CloudSpec s = spec(shape, 50000);
    s.farPoints = 1;
    const auto far = run(s);
    s.farPoints = 0;
    s.clusterFraction = 0.01;
    const auto cluster = run(s);
    ASSERT_GT(clean->stat.pointsVisited, 0u);
    EXPECT_LE(double(far->stat.pointsVisited), 1.5 * double(clean->stat.pointsVisited));
    EXPECT_LE(double(cluster->stat.pointsVisited), 1.5 * double(clean->stat.pointsVisited));
    EXPECT_EQ(far->stat.holes, clean->stat.holes);
    // The cluster (a ball of 500 points about a surface sample) is meshed as one point: no hole
    // around it (10 to 13 before the clumps were merged), its other 499 points
    // counted apart, not as unused points.
    EXPECT_EQ(clean->stat.holes, 0u);
    EXPECT_EQ(cluster->stat.holes, 0u);
    EXPECT_EQ(clean->stat.clumps, 0u);
    EXPECT_EQ(cluster->stat.clumps, 1u);
    EXPECT_EQ(cluster->stat.clumpPointsMerged, 499u); // 500, none of them a surface sample
    EXPECT_LE(cluster->stat.unusedPoints, clean->stat.unusedPoints);
  }
}

namespace {

// `cloud` with a clump of `size` points within a hundredth of `spacing` of its point `at`
// (uniform in that ball, drawn from `seed`), appended.
void addClump(growth::Cloud& cloud, size_t at, size_t size, double spacing, std::uint64_t seed) {
  growth::Random rng(seed);
  const growth::Vec3d centre = cloud.points[at];
  for (size_t i = 0; i < size; ++i) {
    cloud.points.push_back(centre + rng.inBall(0.01 * spacing));
    cloud.normals.push_back(cloud.normals[at]);
  }
}

std::unique_ptr<Run> runCloud(const growth::Cloud& cloud) {
  std::unique_ptr<Run> r(new Run);
  CMeshO in;
  growth::toMesh(cloud, in);
  CMeshO none;
  g2s::build(in, r->mesh, g2s::suggestParams(none), r->stat);
  return r;
}

std::vector<std::array<vcg::Point3f, 3>> faces(const CMeshO& m) {
  std::vector<std::array<vcg::Point3f, 3>> f;
  for (const auto& face : m.face) f.push_back({face.cP(0), face.cP(1), face.cP(2)});
  return f;
}

} // namespace

TEST(G2SOutliers, ClumpsOfDifferentSizesAreEachMeshedAsOnePoint) {
  for (Shape shape : {Shape::Sphere, Shape::Torus}) {
    const CloudSpec s = spec(shape, 50000);
    const growth::Cloud clean = growth::generateCloud(s);
    const double spacing = std::sqrt(growth::shapeArea(s) / double(s.count));
    growth::Cloud clumped = clean;
    addClump(clumped, 100, 20, spacing, 7);
    addClump(clumped, 20000, 100, spacing, 8);
    addClump(clumped, 40000, 500, spacing, 9);
    const auto a = runCloud(clean), b = runCloud(clumped);
    EXPECT_EQ(a->stat.clumps, 0u);
    EXPECT_EQ(b->stat.clumps, 3u);
    // Each clump with the surface sample it surrounds: one point of each stays.
    EXPECT_EQ(b->stat.clumpPointsMerged, 620u);
    EXPECT_EQ(b->stat.holes, a->stat.holes);
    EXPECT_EQ(b->stat.holes, 0u);
    EXPECT_EQ(b->stat.unusedPoints, a->stat.unusedPoints);
    EXPECT_EQ(b->stat.vertices + b->stat.unusedPoints + b->stat.clumpPointsMerged, clumped.points.size());
    // The representative is one of the clump's points: the output vertices are input points, and
    // as many as on the clean cloud.
    EXPECT_EQ(b->stat.vertices, a->stat.vertices);
    // Deterministic: the same mesh again.
    const auto c = runCloud(clumped);
    EXPECT_EQ(faces(c->mesh), faces(b->mesh));
  }
}

TEST(G2SOutliers, AClumpOnANoisyCloudLeavesTheHolesOfTheNoisyCloud) {
  CloudSpec s = spec(Shape::Sphere, 50000);
  const double spacing = std::sqrt(growth::shapeArea(s) / double(s.count));
  s.noiseBound = 0.2 * spacing;
  const auto clean = run(s);
  s.clusterFraction = 0.01;
  const auto cluster = run(s);
  EXPECT_EQ(clean->stat.clumps, 0u); // noise makes no clump
  EXPECT_EQ(cluster->stat.clumps, 1u);
  EXPECT_EQ(cluster->stat.clumpPointsMerged, 499u); // 500, none of them a surface sample
  EXPECT_LE(double(cluster->stat.holes), 1.05 * double(clean->stat.holes) + 1.0);
}

TEST(G2SOutliers, TwoSheetsHalfASpacingApartAreNotAClump) {
  // A closed plate whose two faces are half (a fifth of) a spacing apart, the spacing being the
  // sampling's mean nearest-neighbour distance (growth::meanSpacing of a plate sampled alike):
  // every point has points of the other sheet that near, none has eight within a twentieth of a
  // spacing.
  for (double apart : {0.5, 0.2}) {
    CloudSpec s = spec(Shape::Slab, 20000);
    std::vector<growth::Vec3d> sheet;
    for (const auto& p : growth::generateCloud(s).points) sheet.push_back(p);
    s.slabThickness = apart * growth::meanSpacing(sheet);
    const auto r = run(s);
    EXPECT_EQ(r->stat.clumps, 0u) << apart;
    EXPECT_EQ(r->stat.clumpPointsMerged, 0u) << apart;
  }
}
