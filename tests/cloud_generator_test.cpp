#include <growth/meshlab/layer.h>
#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/point_grid.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/import_ply.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numeric>

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
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Patch, Shape::Genus2}) {
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
    const growth::Vec3d q = torus.points[i] + torus.normals[i] * 0.01;
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
  EXPECT_EQ(growth::parseShape("genus2"), Shape::Genus2);
  EXPECT_STREQ(growth::shapeName(Shape::Genus2), "genus2");
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

TEST(CloudGenerator, ExistingCloudsAreUnchanged) {
  // Tests and benchmarks depend on the seeded clouds: first, second and last point (exact, as
  // printed with %.17g) and the coordinate sums of six specs, recorded once: new members and
  // shapes of CloudSpec must leave them as they are.
  struct Ref {
    Shape shape;
    bool nonUniform;
    double noise, gauss, outliers;
    std::uint64_t seed;
    size_t size;
    double first[3], second[3], last[3], sum[3];
  };
  const Ref refs[] = {
      {Shape::Sphere, false, 0, 0, 0, 1, 1000,
       {-0.90641814728350978, -0.11703444272920763, 0.40584366631770097},
       {-0.76723920696330838, 0.62400110592583202, 0.148211400039445},
       {-0.58776622379294552, -0.78972563189031686, 0.17568236252857239},
       {12.869797186342847, -18.779392124066536, -14.575823792809611}},
      {Shape::Torus, false, 0, 0, 0, 7, 1000,
       {2.977229798405574, -0.3552671297571427, -0.057395003303710689},
       {2.5913497315565204, 1.0401794643034719, 0.61010207651690729},
       {1.4347165301760527, 1.4058646245078044, 0.99996217339470561},
       {17.154046313705553, -112.64386892557421, 12.516264838971692}},
      {Shape::Patch, false, 0, 0, 0, 3, 1000,
       {0.38127659023557592, 0.2811620134709214, 0.076609218473403476},
       {0.067923253000907513, -0.15080874427413993, 0.015007161814070026},
       {-0.42092984588385884, 0.9252617309390192, -0.03934572273218441},
       {1.2789037636855278, 36.170677565587887, 0.66374508499047669}},
      {Shape::Sphere, true, 0, 0, 0, 5, 1000,
       {-0.76156294614610942, -0.08027207567395353, 0.64310051541283442},
       {0.36028181993086106, -0.93281106762639587, 0.0077796105950131977},
       {-0.16992153001768565, 0.16274454636513014, 0.97192637903539625},
       {2.3952996376655946, 26.37216047192107, 208.71410784104808}},
      {Shape::Torus, true, 0.01, 0, 0.02, 11, 1020,
       {0.47287499260583199, 2.8130567570160308, 0.51937319882579913},
       {1.3286269649133982, -0.033026574521413408, -0.73262341627601479},
       {-0.71382162093874557, -1.0004148006343816, 0.789734668143665},
       {19.96144856976624, -53.626390356584508, 305.38095235552134}},
      {Shape::Patch, true, 0, 0.003, 0.05, 2, 1050,
       {0.37485216841613589, -0.52944040354670163, 0.06403550845848574},
       {0.9929181884996422, -0.79835689164875878, 0.084057502477251883},
       {0.52892359170629466, -1.0885706343510286, -0.11112156330758319},
       {201.15536920950473, 9.0259960328593642, 29.883902832803745}},
  };
  for (const Ref& r : refs) {
    CloudSpec c = spec(r.shape, 1000, r.seed);
    c.nonUniform = r.nonUniform;
    c.noiseBound = r.noise;
    c.gaussianSigma = r.gauss;
    c.outlierFraction = r.outliers;
    const auto cloud = growth::generateCloud(c);
    ASSERT_EQ(cloud.points.size(), r.size);
    const std::string what = std::string(growth::shapeName(r.shape)) + (r.nonUniform ? " non-uniform" : "");
    double sum[3] = {0, 0, 0};
    for (const auto& p : cloud.points)
      for (int a = 0; a < 3; ++a) sum[a] += p[a];
    for (int a = 0; a < 3; ++a) {
      EXPECT_EQ(cloud.points[0][a], r.first[a]) << what;
      EXPECT_EQ(cloud.points[1][a], r.second[a]) << what;
      EXPECT_EQ(cloud.points.back()[a], r.last[a]) << what;
      EXPECT_NEAR(sum[a], r.sum[a], 1e-9) << what;
    }
  }
}

namespace {
// Density at the top over density at the bottom of a non-uniform sphere: counts in 10 bands of
// equal area (z is uniform on the sphere), a least-squares line through them, its value at the
// top over its value at the bottom.
double sphereDensityRatio(const growth::Cloud& c) {
  const int bins = 10;
  double count[bins] = {};
  for (const auto& p : c.points) count[std::min(bins - 1, int((p[2] + 1.0) * 0.5 * bins))] += 1;
  double st = 0, sc = 0, stt = 0, stc = 0;
  for (int b = 0; b < bins; ++b) {
    const double t = (b + 0.5) / bins;
    st += t, sc += count[b], stt += t * t, stc += t * count[b];
  }
  const double slope = (bins * stc - st * sc) / (bins * stt - st * st), at0 = (sc - slope * st) / bins;
  return (at0 + slope) / at0;
}
} // namespace

TEST(CloudGenerator, DensityRatioIsTheAskedOne) {
  CloudSpec c = spec(Shape::Sphere, 200000, 3);
  c.nonUniform = true;
  EXPECT_NEAR(sphereDensityRatio(growth::generateCloud(c)), 4.0, 0.2); // the default
  c.densityRatio = 5.0;
  EXPECT_NEAR(sphereDensityRatio(growth::generateCloud(c)), 5.0, 0.25);
  c.densityRatio = 1.0; // uniform
  EXPECT_NEAR(sphereDensityRatio(growth::generateCloud(c)), 1.0, 0.05);
  c.densityRatio = 0.5;
  EXPECT_THROW(growth::generateCloud(c), growth::Error);
  c.densityRatio = 5.0;
  c.nonUniform = false; // the ratio is only used by non-uniform clouds
  EXPECT_NEAR(sphereDensityRatio(growth::generateCloud(c)), 1.0, 0.05);
}

TEST(CloudGenerator, ShapeAreas) {
  EXPECT_DOUBLE_EQ(growth::shapeArea(spec(Shape::Sphere, 1)), 4 * M_PI);
  EXPECT_DOUBLE_EQ(growth::shapeArea(spec(Shape::Torus, 1)), 4 * M_PI * M_PI * 2.0);
  // The patch: between the flat square and the square times the largest area element.
  const double patch = growth::shapeArea(spec(Shape::Patch, 1));
  EXPECT_GT(patch, 4.0 * 1.01);
  EXPECT_LT(patch, 4.0 * std::sqrt(1.0 + 2 * 0.225 * 0.225));
  // A midpoint sum on a 2000 x 2000 grid (its own error ~1e-7).
  double sum = 0;
  const int n = 2000;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      const double x = -1 + (i + 0.5) * 2.0 / n, y = -1 + (j + 0.5) * 2.0 / n;
      const double hx = 0.225 * std::cos(1.5 * x) * std::cos(1.2 * y);
      const double hy = -0.18 * std::sin(1.5 * x) * std::sin(1.2 * y);
      sum += std::sqrt(1 + hx * hx + hy * hy);
    }
  EXPECT_NEAR(patch, sum * 4.0 / (double(n) * n), 1e-6);
  // Genus 2: two tori R = 1.2, r = 0.6 (28.42 each) lose their overlap; the far halves x < -c and
  // x > c are plain half tori (14.21 each).
  const double g = growth::shapeArea(spec(Shape::Genus2, 1));
  EXPECT_GT(g, 2 * 2 * M_PI * M_PI * growth::kGenus2Major * growth::kGenus2Minor);
  EXPECT_LT(g, 2 * 4 * M_PI * M_PI * growth::kGenus2Major * growth::kGenus2Minor);
}

TEST(CloudGenerator, Genus2NormalsAreTheGradientOutwardAndOrthogonal) {
  const CloudSpec c = spec(Shape::Genus2, 3000, 4);
  const auto cloud = growth::generateCloud(c);
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    const growth::Vec3d& p = cloud.points[i];
    const growth::Vec3d& n = cloud.normals[i];
    EXPECT_LT(std::abs(growth::genus2Function(p)), 1e-12);
    // The gradient by central differences.
    const double e = 1e-6;
    growth::Vec3d fd;
    for (int a = 0; a < 3; ++a) {
      growth::Vec3d dp(0, 0, 0);
      dp[a] = e;
      fd[a] = (growth::genus2Function(p + dp) - growth::genus2Function(p - dp)) / (2 * e);
    }
    growth::Vec3d g;
    growth::genus2Function(p, &g);
    EXPECT_LT((g - fd).Norm(), 1e-7 * fd.Norm());
    EXPECT_LT((n - fd / fd.Norm()).Norm(), 1e-7);
    // Outward, and orthogonal: a step along the normal moves away from the surface at unit rate.
    EXPECT_GT(growth::genus2Function(p + n * 0.01), 0.0);
    EXPECT_LT(growth::genus2Function(p - n * 0.01), 0.0);
    EXPECT_NEAR(growth::distanceToShape(c, p + n * 0.01), 0.01, 1e-6);
    EXPECT_NEAR(growth::distanceToShape(c, p - n * 0.01), 0.01, 1e-6);
  }
}

TEST(CloudGenerator, Genus2IsUniformByArea) {
  const size_t n = 200000;
  const CloudSpec c = spec(Shape::Genus2, n, 6);
  const auto cloud = growth::generateCloud(c);
  const double R = growth::kGenus2Major, r = growth::kGenus2Minor, cx = growth::kGenus2Offset;
  // The far halves x < -c and x > c are plain half tori: area 2 pi^2 R r each, the rest is the
  // middle with the blend. Counts in proportion to the areas (sigma of a fraction ~0.001).
  const double total = growth::shapeArea(c), half = 2 * M_PI * M_PI * R * r;
  size_t left = 0, right = 0;
  for (const auto& p : cloud.points) left += p[0] < -cx, right += p[0] > cx;
  EXPECT_NEAR(double(left) / n, half / total, 0.004);
  EXPECT_NEAR(double(right) / n, half / total, 0.004);
  EXPECT_NEAR(double(n - left - right) / n, (total - 2 * half) / total, 0.005);
  // Local density: points within eps of probe points (another seed) on the blend (|x| < 0.5)
  // and on the plain tori (|x| > 2), over the ball's area pi eps^2 on the surface. The far
  // probes' density must be n / total, the blend's the same: a sampler that followed the
  // triangulation or the tori instead of the area would be off there.
  const auto probes = growth::generateCloud(spec(Shape::Genus2, 4000, 7));
  const double eps = 0.12;
  double blendCount = 0, farCount = 0;
  int blendProbes = 0, farProbes = 0;
  for (const auto& q : probes.points) {
    const bool blend = std::abs(q[0]) < 0.5, far = std::abs(q[0]) > 2.0;
    if (!(blend && blendProbes < 150) && !(far && farProbes < 150)) continue;
    size_t k = 0;
    for (const auto& p : cloud.points) k += (p - q).SquaredNorm() <= eps * eps;
    (blend ? blendCount : farCount) += double(k);
    ++(blend ? blendProbes : farProbes);
  }
  ASSERT_EQ(blendProbes, 150);
  ASSERT_EQ(farProbes, 150);
  const double want = double(n) / total * M_PI * eps * eps;
  EXPECT_NEAR(farCount / farProbes / want, 1.0, 0.03);
  EXPECT_NEAR(blendCount / blendProbes / want, 1.0, 0.03);
}

TEST(CloudGenerator, Genus2IsOnePieceWithTwoOpenHoles) {
  const CloudSpec c = spec(Shape::Genus2, 20000, 8);
  const auto cloud = growth::generateCloud(c);
  const size_t n = cloud.points.size();
  // Connected: points closer than 0.15 (about 4 mean spacings) joined, one component.
  growth::PointGrid grid;
  grid.build(cloud.points, 0.15);
  std::vector<int> parent(n);
  std::iota(parent.begin(), parent.end(), 0);
  auto find = [&](int i) {
    while (parent[size_t(i)] != i) i = parent[size_t(i)] = parent[size_t(parent[size_t(i)])];
    return i;
  };
  for (size_t i = 0; i < n; ++i)
    grid.forEachInBall(cloud.points[i], 0.15, [&](int j, double) { parent[size_t(find(int(i)))] = find(j); });
  size_t roots = 0;
  for (size_t i = 0; i < n; ++i) roots += find(int(i)) == int(i);
  EXPECT_EQ(roots, 1u);
  // Two holes: no point nearer to the tori's axes than R - r, the middle of the shape is solid
  // (points on both sides of the xy plane around the origin).
  double nearAxis = 1e300;
  size_t above = 0, below = 0;
  for (const auto& p : cloud.points) {
    for (double cx : {-growth::kGenus2Offset, growth::kGenus2Offset})
      nearAxis = std::min(nearAxis, std::hypot(p[0] - cx, p[1]));
    if (std::hypot(p[0], p[1]) < 0.1) (p[2] > 0 ? above : below) += 1;
  }
  EXPECT_NEAR(nearAxis, growth::kGenus2Major - growth::kGenus2Minor, 0.01);
  EXPECT_GT(above, 0u);
  EXPECT_GT(below, 0u);
}

TEST(CloudGenerator, Genus2IsReproducibleAndTakesTheOptions) {
  CloudSpec c = spec(Shape::Genus2, 2000, 9);
  EXPECT_EQ(growth::generateCloud(c).points, growth::generateCloud(c).points);
  c.nonUniform = true;
  c.densityRatio = 5;
  c.noiseBound = 0.02;
  c.outlierFraction = 0.01;
  const auto cloud = growth::generateCloud(c);
  ASSERT_EQ(cloud.points.size(), 2020u);
  size_t up = 0;
  for (size_t i = 0; i < 2000; ++i) {
    EXPECT_LE(growth::distanceToShape(c, cloud.points[i]), 0.02 + 1e-12);
    up += cloud.points[i][2] > 0;
  }
  // Density 0.2 + 0.8 t along z: the upper half holds clearly more (0.5 for a uniform cloud).
  EXPECT_GT(double(up) / 2000, 0.6);
}

TEST(CloudGenerator, LatLongSphereIsTheGridWithItsPoles) {
  CloudSpec c = spec(Shape::LatLongSphere, 1);
  c.latitudeRings = 7;
  c.longitudeSegments = 12;
  const auto cloud = growth::generateCloud(c);
  ASSERT_EQ(cloud.points.size(), size_t(7 * 12 + 2));
  EXPECT_EQ(cloud.points.front(), growth::Vec3d(0, 0, 1));
  EXPECT_EQ(cloud.points.back(), growth::Vec3d(0, 0, -1));
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    EXPECT_LT(growth::distanceToShape(c, cloud.points[i]), 1e-15);
    EXPECT_NEAR((cloud.normals[i] - cloud.points[i]).Norm(), 0.0, 1e-15); // unit sphere: n = p
  }
  // Ring i (1-based) at polar angle pi*i/8, point j at longitude 2*pi*j/12.
  const growth::Vec3d p = cloud.points[1 + 2 * 12 + 3]; // ring 3, point 3
  EXPECT_NEAR(std::acos(p[2]), M_PI * 3 / 8, 1e-12);
  EXPECT_NEAR(std::atan2(p[1], p[0]), 2 * M_PI * 3 / 12, 1e-12);
  EXPECT_DOUBLE_EQ(growth::shapeArea(c), 4 * M_PI);
  // Outliers are a fraction of the grid's points; noise moves them.
  c.outlierFraction = 0.5;
  EXPECT_EQ(growth::generateCloud(c).points.size(), size_t(86 + 43));
  c.nonUniform = true;
  EXPECT_THROW(growth::generateCloud(c), growth::Error);
  EXPECT_EQ(growth::parseShape("latlong"), Shape::LatLongSphere);
}

TEST(CloudGenerator, HollowBallHasBothShellsUniformByAreaWithNormalsOutOfTheMaterial) {
  CloudSpec c = spec(Shape::HollowBall, 20000, 3);
  const auto cloud = growth::generateCloud(c);
  ASSERT_EQ(cloud.points.size(), 20000u);
  size_t inner = 0;
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    const growth::Vec3d& p = cloud.points[i];
    EXPECT_LT(growth::distanceToShape(c, p), 1e-12);
    const bool isInner = p.Norm() < 0.9;
    inner += isInner;
    // Out of the material: away from the centre on the outer shell, towards it on the inner one.
    EXPECT_NEAR((cloud.normals[i] - p / p.Norm() * (isInner ? -1.0 : 1.0)).Norm(), 0.0, 1e-12);
  }
  // Area fraction of the inner shell: 0.64 / 1.64.
  EXPECT_NEAR(double(inner) / 20000.0, 0.64 / 1.64, 0.015);
  EXPECT_DOUBLE_EQ(growth::shapeArea(c), 4 * M_PI * 1.64);
  EXPECT_EQ(growth::parseShape("hollowball"), Shape::HollowBall);
}

TEST(CloudGenerator, SlabIsSampledOnAllSixFacesByArea) {
  CloudSpec c = spec(Shape::Slab, 40000, 2);
  c.slabThickness = 0.1;
  const auto cloud = growth::generateCloud(c);
  ASSERT_EQ(cloud.points.size(), 40000u);
  size_t onSides = 0;
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    const growth::Vec3d& p = cloud.points[i];
    const growth::Vec3d& n = cloud.normals[i];
    EXPECT_LT(growth::distanceToShape(c, p), 1e-15);
    // On its face, with the face's outward normal.
    for (int a = 0; a < 3; ++a) {
      if (n[a] != 0) {
        EXPECT_EQ(p[a], n[a] * (a == 2 ? 0.05 : 1.0));
      }
    }
    onSides += n[2] == 0;
  }
  // The four sides hold 8 h t / (8 h^2 + 8 h t) = 0.1 / 1.1 of the area.
  EXPECT_NEAR(double(onSides) / 40000.0, 0.1 / 1.1, 0.01);
  EXPECT_DOUBLE_EQ(growth::shapeArea(c), 8.0 + 0.8);
  EXPECT_DOUBLE_EQ(growth::distanceToShape(c, growth::Vec3d(0, 0, 0)), 0.05);
  EXPECT_DOUBLE_EQ(growth::distanceToShape(c, growth::Vec3d(0.5, 0, 0.25)), 0.2);
  EXPECT_EQ(growth::parseShape("slab"), Shape::Slab);
}

// The scan-like cloud (the scale benchmark's): several separate parts (the four shapes in turn, scaled,
// turned, set apart), sampled by area, with Gaussian noise, outliers and some flipped normals.
TEST(CloudGenerator, ScanIsSeveralSeparatePartsSampledByArea) {
  CloudSpec c = spec(Shape::Scan, 30000, 3);
  c.scanParts = 6;
  EXPECT_EQ(growth::parseShape("scan"), Shape::Scan);
  EXPECT_STREQ(growth::shapeName(Shape::Scan), "scan");
  const std::vector<growth::ScanPart> parts = growth::scanParts(c);
  ASSERT_EQ(parts.size(), 6u);
  // The parts' balls are kScanGap apart; the shapes go round torus, genus 2, sphere, patch.
  const Shape shapes[4] = {Shape::Torus, Shape::Genus2, Shape::Sphere, Shape::Patch};
  double total = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    total += parts[i].area;
    EXPECT_EQ(parts[i].spec.shape, shapes[i % 4]);
    for (size_t j = 0; j < i; ++j)
      EXPECT_GE((parts[i].offset - parts[j].offset).Norm() - parts[i].radius - parts[j].radius,
                growth::kScanGap - 1e-12) << i << " " << j;
  }
  EXPECT_NEAR(growth::shapeArea(c), total, 1e-9 * total);
  // Without noise: every point on its part's surface, inside its ball; counts by area.
  const auto clean = growth::generateCloud(c);
  ASSERT_EQ(clean.points.size(), 30000u);
  std::vector<size_t> perPart(parts.size(), 0), label(clean.points.size());
  for (size_t i = 0; i < clean.points.size(); ++i) {
    double d = 0;
    const size_t k = label[i] = growth::nearestScanPart(c, parts, clean.points[i], &d);
    ++perPart[k];
    ASSERT_LT(d, 1e-9) << i;
    ASSERT_LE((clean.points[i] - parts[k].offset).Norm(), parts[k].radius + 1e-9) << i;
    ASSERT_NEAR(clean.normals[i].Norm(), 1.0, 1e-12);
  }
  for (size_t k = 0; k < parts.size(); ++k) {
    const double p = parts[k].area / total, expected = p * 30000, sd = std::sqrt(30000 * p * (1 - p));
    EXPECT_NEAR(double(perPart[k]), expected, 5 * sd) << "part " << k;
    EXPECT_GT(perPart[k], 0u);
  }
  // The sphere (part 2): normals outward from its centre.
  for (size_t i = 0; i < clean.points.size(); ++i) {
    if (label[i] == 2) {
      ASSERT_NEAR((clean.normals[i] - (clean.points[i] - parts[2].offset) / (1.5 * parts[2].scale)).Norm(), 0, 1e-9);
    }
  }

  // Scan-like: noise, outliers on top, a share of flipped normals; the same cloud for the same seed.
  c.gaussianSigma = 0.01;
  c.outlierFraction = 0.02;
  c.flippedNormals = 0.05;
  const auto scan = growth::generateCloud(c);
  const auto again = growth::generateCloud(c);
  EXPECT_EQ(scan.points, again.points);
  EXPECT_EQ(scan.normals, again.normals);
  ASSERT_EQ(scan.points.size(), 30600u);
  size_t sphere = 0, flipped = 0;
  for (size_t i = 0; i < 30000; ++i) {
    double d = 0;
    const size_t k = label[i] = growth::nearestScanPart(c, parts, scan.points[i], &d);
    ASSERT_LT(d, 6 * c.gaussianSigma) << i;
    if (k == 2) {
      ++sphere;
      flipped += scan.normals[i] * (scan.points[i] - parts[2].offset) < 0;
    }
  }
  const double share = double(flipped) / double(sphere);
  EXPECT_NEAR(share, 0.05, 5 * std::sqrt(0.05 * 0.95 / double(sphere))) << sphere << " sphere points";
  CloudSpec other = c;
  other.seed = 4;
  EXPECT_NE(growth::generateCloud(other).points, scan.points);
  // Parts of a scan are separate: no two points of different parts closer than the gap less the noise.
  double closest = 1e300;
  for (size_t i = 0; i < 30000; i += 7)
    for (size_t j = 0; j < 30000; j += 5)
      if (label[i] != label[j])
        closest = std::min(closest, (scan.points[i] - scan.points[j]).Norm());
  EXPECT_GT(closest, growth::kScanGap - 12 * c.gaussianSigma);
  // The parts' count is checked.
  c.scanParts = 0;
  EXPECT_THROW(growth::generateCloud(c), growth::Error);
  c.scanParts = 2;
  c.flippedNormals = 1.5;
  EXPECT_THROW(growth::generateCloud(c), growth::Error);
}
