#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/input_cloud.h>

#include <common/ml_mesh_type.h>

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

using growth::CloudCheck;

namespace {
void addPoint(CMeshO& m, float x, float y, float z, float nx = 0, float ny = 0, float nz = 1) {
  auto v = vcg::tri::Allocator<CMeshO>::AddVertices(m, 1);
  v->P() = vcg::Point3f(x, y, z);
  v->N() = vcg::Point3f(nx, ny, nz);
}

// The message of the growth::Error thrown by readCloud, or "" when it does not throw.
std::string errorOf(const CMeshO& m, CloudCheck check) {
  try {
    growth::readCloud(m, check);
  } catch (const growth::Error& e) {
    return e.what();
  }
  return "";
}

void sphereMesh(CMeshO& m, size_t n) {
  growth::CloudSpec s;
  s.count = n;
  growth::toMesh(growth::generateCloud(s), m);
}
} // namespace

TEST(InputCloud, EmptyLayerIsRefused) {
  CMeshO m;
  EXPECT_NE(errorOf(m, {}).find("no vertices"), std::string::npos);
}

TEST(InputCloud, GoodCloudIsCopiedInDouble) {
  CMeshO m;
  sphereMesh(m, 500);
  CloudCheck check;
  check.needNormals = true;
  const auto c = growth::readCloud(m, check);
  ASSERT_EQ(c.points.size(), 500u);
  ASSERT_EQ(c.normals.size(), 500u);
  EXPECT_EQ(c.duplicatesDropped, 0u);
  EXPECT_EQ(c.vertexIndex[499], 499);
  EXPECT_NEAR(c.box.Diag(), 2 * std::sqrt(3.0), 0.2);
  EXPECT_DOUBLE_EQ(c.points[3][1], double(m.vert[3].P()[1]));
}

TEST(InputCloud, NonFiniteCoordinatesAreRefusedWithTheirCount) {
  CMeshO m;
  sphereMesh(m, 100);
  m.vert[5].P()[0] = std::numeric_limits<float>::quiet_NaN();
  m.vert[6].P()[2] = std::numeric_limits<float>::infinity();
  const std::string e = errorOf(m, {});
  EXPECT_NE(e.find("2 of 100 vertices have NaN or infinite"), std::string::npos) << e;
}

// A cloud 1e38 across (fuzz/regressions/cloud/torus_1e38_g2s_nan_centre) would overflow G2S's
// sums of edge lengths into a NaN search centre. Such coordinates are refused, with a count.
TEST(InputCloud, HugeCoordinatesAreRefusedWithTheirCount) {
  CMeshO m;
  sphereMesh(m, 100);
  m.vert[7].P()[1] = 2e15f;
  m.vert[8].P()[0] = -1e38f;
  m.vert[9].P()[2] = 9e14f; // within the bound
  const std::string e = errorOf(m, {});
  EXPECT_NE(e.find("2 of 100 vertices have a coordinate beyond"), std::string::npos) << e;
  m.vert[7].P()[1] = 0;
  m.vert[8].P()[0] = 0;
  EXPECT_EQ(errorOf(m, {}).find("beyond"), std::string::npos);
}

TEST(InputCloud, MissingNormalsSayHowToComputeThem) {
  CMeshO m;
  for (int i = 0; i < 10; ++i) addPoint(m, float(i), float(i * i % 7), 0, 0, 0, 0);
  CloudCheck check;
  check.needNormals = true;
  const std::string e = errorOf(m, check);
  EXPECT_NE(e.find("Compute normals for point sets"), std::string::npos) << e;
  check.needNormals = false;
  EXPECT_EQ(errorOf(m, check), "");
}

TEST(InputCloud, SomeBadNormalsAreCounted) {
  CMeshO m;
  sphereMesh(m, 50);
  m.vert[0].N() = vcg::Point3f(0, 0, 0);
  CloudCheck check;
  check.needNormals = true;
  EXPECT_NE(errorOf(m, check).find("1 of 50 vertices have a zero or invalid normal"), std::string::npos);
}

TEST(InputCloud, DuplicatesAreDroppedKeepingTheFirst) {
  CMeshO m;
  addPoint(m, 0, 0, 0);
  addPoint(m, 1, 0, 0);
  addPoint(m, 0, 0, 0);
  addPoint(m, 0, 1, 0);
  addPoint(m, 1, 0, 0);
  const auto c = growth::readCloud(m, {});
  EXPECT_EQ(c.points.size(), 3u);
  EXPECT_EQ(c.duplicatesDropped, 2u);
  EXPECT_EQ(c.vertexIndex, (std::vector<int>{0, 1, 3}));
}

TEST(InputCloud, AllIdenticalPointsAreRefused) {
  CMeshO m;
  for (int i = 0; i < 20; ++i) addPoint(m, 1, 2, 3);
  EXPECT_NE(errorOf(m, {}).find("identical"), std::string::npos);
}

TEST(InputCloud, TooFewAndCollinearPointsAreRefused) {
  CMeshO two;
  addPoint(two, 0, 0, 0);
  addPoint(two, 1, 0, 0);
  EXPECT_NE(errorOf(two, {}).find("only 2 distinct points"), std::string::npos);
  CMeshO line;
  for (int i = 0; i < 10; ++i) addPoint(line, float(i), float(2 * i), 0);
  EXPECT_NE(errorOf(line, {}).find("one straight line"), std::string::npos);
  CMeshO one;
  addPoint(one, 1, 2, 3);
  EXPECT_NE(errorOf(one, {}).find("only 1 point;"), std::string::npos) << errorOf(one, {});
}

// A line written in float is off the line by rounding (half a unit in the last place): still a
// line. A cloud as thin as a few units in the last place of its coordinates is not.
TEST(InputCloud, ALineInFloatIsALine) {
  CMeshO line;
  for (int i = 0; i < 200; ++i) addPoint(line, 0.01f * float(i), 0.02f * float(i), -0.03f * float(i));
  bool offLine = false; // the float points are not exactly on one line in double
  const growth::Vec3d a = growth::Vec3d::Construct(line.vert[0].P()), b = growth::Vec3d::Construct(line.vert[199].P());
  for (const auto& v : line.vert)
    offLine |= ((growth::Vec3d::Construct(v.P()) - a) ^ (b - a)).Norm() > 1e-9 * (b - a).SquaredNorm();
  EXPECT_TRUE(offLine);
  EXPECT_NE(errorOf(line, {}).find("one straight line"), std::string::npos);
  // Far from the origin (a geo-referenced line): the same.
  CMeshO far;
  for (int i = 0; i < 200; ++i) addPoint(far, 1e6f + 0.37f * float(i), 1e6f + 0.71f * float(i), 1e6f - 0.13f * float(i));
  EXPECT_NE(errorOf(far, {}).find("one straight line"), std::string::npos);
  // A strip 1e-3 wide next to the line: a (thin) surface, accepted.
  CMeshO strip;
  for (int i = 0; i < 200; ++i) addPoint(strip, 0.01f * float(i), 0.001f * float(i % 2), 0);
  EXPECT_EQ(errorOf(strip, {}), "");
}

TEST(InputCloud, DeletedVerticesAreIgnored) {
  CMeshO m;
  sphereMesh(m, 30);
  vcg::tri::Allocator<CMeshO>::DeleteVertex(m, m.vert[0]);
  const auto c = growth::readCloud(m, {});
  EXPECT_EQ(c.points.size(), 29u);
  EXPECT_EQ(c.vertexIndex[0], 1);
}

TEST(InputCloud, AMeshIsRefusedUnlessAllowed) {
  CMeshO m;
  sphereMesh(m, 10);
  vcg::tri::Allocator<CMeshO>::AddFace(m, 0, 1, 2);
  const std::string e = errorOf(m, {});
  EXPECT_NE(e.find("is a mesh (1 faces)"), std::string::npos) << e;
  CloudCheck allow;
  allow.allowFaces = true;
  EXPECT_EQ(errorOf(m, allow), "");
}

TEST(InputCloud, MeanSpacingOfAGrid) {
  std::vector<growth::Vec3d> pts;
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) pts.emplace_back(0.5 * i, 0.5 * j, 0);
  EXPECT_NEAR(growth::meanSpacing(pts), 0.5, 1e-12);
  EXPECT_EQ(growth::meanSpacing({growth::Vec3d(0, 0, 0)}), 0.0);
}

// The mean spacing is robust: one point far away, or 1 % of outliers scattered in a box around
// the cloud, leave it as it is (within 1 %), and the clean cloud's value is the plain mean of its
// samples' nearest distances (no sample of a clean sampling is beyond 5 times their median).
TEST(InputCloud, MeanSpacingIgnoresFarPointsAndOutliers) {
  growth::CloudSpec spec;
  spec.count = 20000; // every point a sample (kMeanSpacingSamples)
  spec.seed = 4;
  const growth::Cloud clean = growth::generateCloud(spec);
  const double s0 = growth::meanSpacing(clean.points);
  // The plain mean, by brute force.
  double sum = 0;
  size_t n = 0;
  for (size_t i = 0; i < clean.points.size(); ++i, ++n) {
    double best = std::numeric_limits<double>::infinity();
    for (size_t j = 0; j < clean.points.size(); ++j)
      if (j != i) best = std::min(best, (clean.points[j] - clean.points[i]).SquaredNorm());
    sum += std::sqrt(best);
  }
  EXPECT_NEAR(s0, sum / double(n), 1e-12 * s0);

  std::vector<growth::Vec3d> far = clean.points;
  far.push_back(growth::Vec3d(1e4, 0, 0)); // the same samples, and one more: the far point
  EXPECT_NEAR(growth::meanSpacing(far), s0, 1e-12 * s0);
  growth::CloudSpec noisy = spec;
  noisy.outlierFraction = 0.01;
  EXPECT_NEAR(growth::meanSpacing(growth::generateCloud(noisy).points), s0, 0.01 * s0);
  // The robust box holds the cloud, not the far point.
  const growth::Box3d box = growth::robustBox(far);
  EXPECT_TRUE(box.IsIn(growth::Vec3d(0.99, 0, 0)));
  EXPECT_FALSE(box.IsIn(growth::Vec3d(1e4, 0, 0)));
}
