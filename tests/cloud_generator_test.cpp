#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/import_ply.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

using growth::CloudSpec;
using growth::Shape;

namespace {
CloudSpec spec(Shape s, size_t n, std::uint64_t seed = 1) {
  CloudSpec c;
  c.shape = s;
  c.count = n;
  c.seed = seed;
  return c;
}
} // namespace

TEST(CloudGenerator, PointsLieOnTheShapeWithUnitNormals) {
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Patch}) {
    const CloudSpec c = spec(s, 2000);
    const auto cloud = growth::generateCloud(c);
    ASSERT_EQ(cloud.points.size(), 2000u);
    ASSERT_EQ(cloud.normals.size(), 2000u);
    for (size_t i = 0; i < cloud.points.size(); ++i) {
      EXPECT_LT(growth::distanceToShape(c, cloud.points[i]), 1e-12) << growth::shapeName(s);
      EXPECT_NEAR(cloud.normals[i].Norm(), 1.0, 1e-12);
    }
  }
}

TEST(CloudGenerator, NormalsAreOutwardAndOrthogonalToTheSurface) {
  const auto sphere = growth::generateCloud(spec(Shape::Sphere, 500));
  for (size_t i = 0; i < sphere.points.size(); ++i)
    EXPECT_NEAR((sphere.normals[i] - sphere.points[i]).Norm(), 0.0, 1e-12);
  CloudSpec t = spec(Shape::Torus, 500);
  const auto torus = growth::generateCloud(t);
  for (size_t i = 0; i < torus.points.size(); ++i) {
    // Moving along the normal moves away from the tube's centre circle at unit rate.
    const vcg::Point3d q = torus.points[i] + torus.normals[i] * 0.01;
    EXPECT_NEAR(growth::distanceToShape(t, q), 0.01, 1e-9);
  }
}

TEST(CloudGenerator, SameSeedSameCloudOtherSeedOtherCloud) {
  const auto a = growth::generateCloud(spec(Shape::Torus, 1000, 42));
  const auto b = growth::generateCloud(spec(Shape::Torus, 1000, 42));
  const auto c = growth::generateCloud(spec(Shape::Torus, 1000, 43));
  EXPECT_EQ(a.points, b.points);
  EXPECT_NE(a.points, c.points);
}

TEST(CloudGenerator, UniformSphereIsBalancedNonUniformIsNot) {
  auto fractionAbove = [](const growth::Cloud& c) {
    size_t up = 0;
    for (const auto& p : c.points) up += p[2] > 0;
    return double(up) / double(c.points.size());
  };
  CloudSpec u = spec(Shape::Sphere, 20000);
  EXPECT_NEAR(fractionAbove(growth::generateCloud(u)), 0.5, 0.02);
  u.nonUniform = true;
  // Density 0.25 + 0.75 t with t = (z + 1) / 2 uniform on the sphere: the upper half holds
  // (0.125 + 0.28125) / 0.625 = 0.65 of the points.
  EXPECT_NEAR(fractionAbove(growth::generateCloud(u)), 0.65, 0.02);
}

TEST(CloudGenerator, TorusIsUniformByArea) {
  // Area of the outer half (cos v > 0) of the torus R=2, r=1 is (pi R + 2 r)/(2 pi R) of the total.
  const auto t = growth::generateCloud(spec(Shape::Torus, 40000));
  size_t outer = 0;
  for (const auto& p : t.points) outer += std::hypot(p[0], p[1]) > 2.0;
  const double want = (M_PI * 2.0 + 2.0) / (2.0 * M_PI * 2.0);
  EXPECT_NEAR(double(outer) / double(t.points.size()), want, 0.01);
}

TEST(CloudGenerator, BoundedNoiseStaysWithinNu) {
  CloudSpec c = spec(Shape::Sphere, 5000);
  c.noiseBound = 0.03;
  const auto cloud = growth::generateCloud(c);
  double maxDist = 0;
  for (const auto& p : cloud.points) maxDist = std::max(maxDist, growth::distanceToShape(c, p));
  EXPECT_LE(maxDist, 0.03 + 1e-12);
  EXPECT_GT(maxDist, 0.02); // the noise is really there
}

TEST(CloudGenerator, GaussianNoiseHasTheRequestedSigma) {
  CloudSpec c = spec(Shape::Sphere, 20000);
  c.gaussianSigma = 0.01;
  const auto cloud = growth::generateCloud(c);
  double sum2 = 0;
  for (const auto& p : cloud.points) {
    const double r = p.Norm() - 1.0; // radial component of the noise
    sum2 += r * r;
  }
  EXPECT_NEAR(std::sqrt(sum2 / double(cloud.points.size())), 0.01, 0.0005);
}

TEST(CloudGenerator, OutliersAreAddedOnTop) {
  CloudSpec c = spec(Shape::Sphere, 1000);
  c.outlierFraction = 0.05;
  const auto cloud = growth::generateCloud(c);
  EXPECT_EQ(cloud.points.size(), 1050u);
  size_t off = 0;
  for (size_t i = 1000; i < cloud.points.size(); ++i) off += growth::distanceToShape(c, cloud.points[i]) > 0.05;
  EXPECT_GT(off, 25u);
}

TEST(CloudGenerator, RejectsEmptyAndUnknownShape) {
  EXPECT_THROW(growth::generateCloud(spec(Shape::Sphere, 0)), growth::Error);
  EXPECT_THROW(growth::parseShape("cube"), growth::Error);
  EXPECT_EQ(growth::parseShape("torus"), Shape::Torus);
}

TEST(CloudGenerator, PlyRoundTripThroughVcglib) {
  const auto cloud = growth::generateCloud(spec(Shape::Patch, 300, 9));
  const std::string path = ::testing::TempDir() + "growth_cloud_roundtrip.ply";
  growth::writePly(path, cloud);
  CMeshO m;
  int mask = 0;
  ASSERT_EQ(vcg::tri::io::ImporterPLY<CMeshO>::Open(m, path.c_str(), mask), 0);
  ASSERT_EQ(m.vn, 300);
  EXPECT_TRUE(mask & vcg::tri::io::Mask::IOM_VERTNORMAL);
  for (size_t i = 0; i < 300; ++i) {
    for (int a = 0; a < 3; ++a) {
      EXPECT_FLOAT_EQ(m.vert[i].P()[a], float(cloud.points[i][a]));
      EXPECT_FLOAT_EQ(m.vert[i].N()[a], float(cloud.normals[i][a]));
    }
  }
  std::remove(path.c_str());
}

TEST(CloudGenerator, ToMeshCopiesPointsAndNormals) {
  const auto cloud = growth::generateCloud(spec(Shape::Sphere, 100));
  CMeshO m;
  growth::toMesh(cloud, m);
  ASSERT_EQ(m.vn, 100);
  EXPECT_EQ(m.fn, 0);
  EXPECT_FALSE(m.bbox.IsNull());
  EXPECT_FLOAT_EQ(m.vert[7].N()[2], float(cloud.normals[7][2]));
}
