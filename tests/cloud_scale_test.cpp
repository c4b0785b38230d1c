#include <growth/cloud_generator.h>
#include <growth/cloud_scale.h>
#include <growth/input_cloud.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <vector>

using growth::CloudSpec;
using growth::SamplingEstimate;
using growth::Shape;
using Point3d = growth::Vec3d;

namespace {
CloudSpec spec(Shape s, size_t n, std::uint64_t seed = 1) {
  CloudSpec c;
  c.shape = s;
  c.count = n;
  c.seed = seed;
  return c;
}

// Median nearest-neighbour distance of a Poisson sample of the plane with area a per point:
// sqrt(a ln 2 / pi).
double poissonMedianSpacing(double areaPerPoint) { return std::sqrt(areaPerPoint * std::log(2.0) / M_PI); }

void expectAllZero(const SamplingEstimate& e) {
  EXPECT_EQ(e.medianSpacing, 0.0);
  EXPECT_EQ(e.areaPerPoint, 0.0);
  EXPECT_EQ(e.noiseSigma, 0.0);
  EXPECT_EQ(e.noise, 0.0);
}

void expectFiniteSane(const SamplingEstimate& e) {
  EXPECT_TRUE(std::isfinite(e.medianSpacing) && e.medianSpacing >= 0);
  EXPECT_TRUE(std::isfinite(e.areaPerPoint) && e.areaPerPoint >= 0);
  EXPECT_TRUE(std::isfinite(e.noiseSigma) && e.noiseSigma >= 0);
  EXPECT_TRUE(std::isfinite(e.noise) && e.noise >= 0);
}

bool sameEstimate(const SamplingEstimate& a, const SamplingEstimate& b) {
  return a.spacing == b.spacing && a.areaPerPoint == b.areaPerPoint && a.noiseSigma == b.noiseSigma &&
         a.noise == b.noise && a.samples == b.samples && a.isolated == b.isolated && a.noiseSamples == b.noiseSamples;
}
} // namespace

TEST(CloudScale, EmptyOneAndTwoPoints) {
  expectAllZero(growth::estimateSampling({}));
  expectAllZero(growth::estimateSampling({Point3d(1, 2, 3)}));
  const SamplingEstimate two = growth::estimateSampling({Point3d(0, 0, 0), Point3d(0.3, 0.4, 0)});
  EXPECT_DOUBLE_EQ(two.spacing, 0.5);
  EXPECT_NEAR(two.areaPerPoint, M_PI * 0.25 / (1 - 1.0 / 3), 1e-12); // k = 1: the only other point
  EXPECT_EQ(two.noise, 0.0);                                          // no surface to fit
  EXPECT_EQ(two.samples, 2u);
}

TEST(CloudScale, IdenticalCollinearAndNonFinitePoints) {
  const SamplingEstimate same = growth::estimateSampling(std::vector<Point3d>(1000, Point3d(1, 1, 1)));
  expectAllZero(same); // the spacing of duplicates is 0; no surface
  EXPECT_EQ(same.samples, 1000u);
  expectAllZero(growth::estimateSampling(std::vector<Point3d>(1000, Point3d(std::nan(""), 0, 0))));
  std::vector<Point3d> line;
  for (int i = 0; i < 1000; ++i) line.emplace_back(0.01 * i, 0.02 * i, -0.02 * i); // spacing 0.03
  const SamplingEstimate e = growth::estimateSampling(line);
  expectFiniteSane(e);
  EXPECT_NEAR(e.medianSpacing, 0.03, 1e-12);
  EXPECT_EQ(e.noise, 0.0); // no plane: every local fit is degenerate
  EXPECT_EQ(e.noiseSamples, 0u);
  // Six points: too few for the quadric fit (six terms), no noise, spacing still measured.
  std::vector<Point3d> six;
  for (int i = 0; i < 6; ++i) six.emplace_back(std::cos(i), std::sin(i), 0.1 * i);
  const SamplingEstimate s = growth::estimateSampling(six);
  expectFiniteSane(s);
  EXPECT_GT(s.spacing, 0.0);
  EXPECT_EQ(s.noiseSamples, 0u);
  // Non-finite points are ignored: the same estimate as without them (small cloud: every point
  // is a sample).
  auto cloud = growth::generateCloud(spec(Shape::Sphere, 3000)).points;
  const SamplingEstimate clean = growth::estimateSampling(cloud);
  cloud.insert(cloud.begin() + 100, Point3d(std::numeric_limits<double>::infinity(), 0, 0));
  cloud.insert(cloud.begin() + 2000, Point3d(0, std::nan(""), 0));
  EXPECT_TRUE(sameEstimate(growth::estimateSampling(cloud), clean));
}

TEST(CloudScale, MostlyDuplicatesFinishQuickly) {
  // Half of 200k points on one spot: searches in the cluster stop at the visit limit.
  auto cloud = growth::generateCloud(spec(Shape::Sphere, 100000)).points;
  cloud.resize(200000, Point3d(0.3, 0.2, 0.1));
  const auto t0 = std::chrono::steady_clock::now();
  const SamplingEstimate e = growth::estimateSampling(cloud, 1);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  expectFiniteSane(e);
  // The sanitizer build (scripts/sanitize.sh) runs this code several times slower; a search
  // without the visit limit takes minutes in either.
#ifdef GROWTH_SANITIZED
  EXPECT_LT(seconds, 20.0);
#else
  EXPECT_LT(seconds, 2.0);
#endif
}

TEST(CloudScale, SpacingAndAreaOfTheGeneratedShapes) {
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Patch, Shape::Genus2})
    for (size_t n : {10000u, 100000u}) {
      const CloudSpec c = spec(s, n, 3);
      const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(c).points);
      const double a = growth::shapeArea(c) / double(n);
      const std::string what = std::string(growth::shapeName(s)) + " " + std::to_string(n);
      EXPECT_NEAR(e.areaPerPoint / a, 1.0, 0.03) << what;
      EXPECT_NEAR(e.medianSpacing / poissonMedianSpacing(a), 1.0, 0.03) << what;
      EXPECT_EQ(e.samples + e.isolated, std::min<size_t>(n, 20000)) << what;
      EXPECT_EQ(e.isolated, 0u) << what;
    }
}

TEST(CloudScale, OneFarPointChangesNothing) {
  const auto cloud = growth::generateCloud(spec(Shape::Sphere, 50000)).points;
  const SamplingEstimate clean = growth::estimateSampling(cloud);
  // Appended (the samples stay the same, stride 3): bit for bit the same estimate, the far point,
  // when it is a sample, counted as isolated. It enters neither the grid nor its cell size.
  auto appended = cloud;
  appended.emplace_back(2e4, -3e4, 1e4); // index 50000: not a sample
  EXPECT_TRUE(sameEstimate(growth::estimateSampling(appended), clean));
  appended.emplace_back(-2e4, 3e4, 1e4); // index 50001: a sample
  SamplingEstimate e = growth::estimateSampling(appended);
  EXPECT_EQ(e.isolated, clean.isolated + 1);
  e.isolated = clean.isolated;
  EXPECT_TRUE(sameEstimate(e, clean));
  // Inserted before the others (all samples change): within 3 %.
  for (size_t at : {size_t(0), size_t(25000), size_t(50000)}) { // sampled or not, first or last
    auto far = cloud;
    far.insert(far.begin() + std::ptrdiff_t(at), Point3d(2e4, -3e4, 1e4)); // 10^4 x the cloud's size
    const SamplingEstimate e = growth::estimateSampling(far);
    EXPECT_NEAR(e.medianSpacing / clean.medianSpacing, 1.0, 0.03) << at;
    EXPECT_NEAR(e.areaPerPoint / clean.areaPerPoint, 1.0, 0.03) << at;
    EXPECT_NEAR(2.5 * e.medianSpacing / (2.5 * clean.medianSpacing), 1.0, 0.03) << at; // d = 2.5 spacings
    EXPECT_NEAR(e.noise, clean.noise, 0.01 * clean.medianSpacing) << at;
  }
  // The mean spacing is robust too (a far point among its samples must not give its grid one
  // cell for the whole sphere).
  auto small = growth::generateCloud(spec(Shape::Sphere, 5000)).points;
  const double mean = growth::meanSpacing(small);
  small.insert(small.begin(), Point3d(2e4, -3e4, 1e4));
  EXPECT_NEAR(growth::meanSpacing(small) / mean, 1.0, 0.01);
}

TEST(CloudScale, OnePercentOutliersBarelyMoveTheEstimates) {
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Genus2}) {
    CloudSpec c = spec(s, 50000, 5);
    const SamplingEstimate clean = growth::estimateSampling(growth::generateCloud(c).points);
    c.outlierFraction = 0.01;
    const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(c).points);
    EXPECT_NEAR(e.medianSpacing / clean.medianSpacing, 1.0, 0.03) << growth::shapeName(s);
    EXPECT_NEAR(e.areaPerPoint / clean.areaPerPoint, 1.0, 0.03) << growth::shapeName(s);
    EXPECT_LT(e.noise, 0.15 * e.medianSpacing) << growth::shapeName(s);
    // With noise as well: the noise estimate keeps within its tolerance.
    c.noiseBound = 0.5 * clean.medianSpacing;
    const SamplingEstimate noisy = growth::estimateSampling(growth::generateCloud(c).points);
    EXPECT_NEAR(noisy.noise / c.noiseBound, 1.0, 0.25) << growth::shapeName(s);
  }
}

TEST(CloudScale, BoundedNoiseIsFound) {
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Patch, Shape::Genus2}) {
    CloudSpec c = spec(s, 20000, 7);
    const SamplingEstimate clean = growth::estimateSampling(growth::generateCloud(c).points);
    for (double nu : {0.25, 0.5, 1.0}) {
      c.noiseBound = nu * clean.medianSpacing;
      const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(c).points);
      EXPECT_NEAR(e.noise / c.noiseBound, 1.0, 0.25) << growth::shapeName(s) << " nu " << nu;
      EXPECT_NEAR(e.noiseSigma, e.noise / std::sqrt(5.0), 1e-12 * e.noise);
    }
  }
}

TEST(CloudScale, CleanCloudsHaveLittleNoise) {
  // The quadric takes up the curvature: what is left is far below the spacing, from the small
  // clouds (large neighbourhoods on curved surfaces) up.
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Patch, Shape::Genus2})
    for (size_t n : {2000u, 10000u, 200000u}) {
      const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(spec(s, n, 9)).points);
      EXPECT_LT(e.noise, 0.15 * e.medianSpacing) << growth::shapeName(s) << " " << n;
    }
}

TEST(CloudScale, GaussianNoiseSigmaIsFound) {
  for (Shape s : {Shape::Sphere, Shape::Torus, Shape::Genus2}) {
    CloudSpec c = spec(s, 20000, 11);
    const SamplingEstimate clean = growth::estimateSampling(growth::generateCloud(c).points);
    for (double sigma : {0.1, 0.3}) {
      c.gaussianSigma = sigma * clean.medianSpacing;
      const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(c).points);
      EXPECT_NEAR(e.noiseSigma / c.gaussianSigma, 1.0, 0.25) << growth::shapeName(s) << " sigma " << sigma;
    }
  }
}

TEST(CloudScale, RegularLatticesAndLatLongSampling) {
  // A square and a triangular lattice of side h in a tilted plane: spacing h exactly, the area
  // per point within 10 % (k = 16: 1.002 h^2 and 0.926 of sqrt(3)/2 h^2), no noise.
  const double h = 0.01;
  const Point3d e1 = Point3d(1, 2, 2) / 3.0, e2 = Point3d(2, 1, -2) / 3.0; // orthonormal
  std::vector<Point3d> square, triangular;
  for (int i = 0; i < 300; ++i)
    for (int j = 0; j < 300; ++j) {
      square.push_back(e1 * (i * h) + e2 * (j * h));
      triangular.push_back(e1 * ((i + 0.5 * (j % 2)) * h) + e2 * (j * h * std::sqrt(3.0) / 2));
    }
  const SamplingEstimate sq = growth::estimateSampling(square);
  EXPECT_NEAR(sq.spacing, h, 1e-9);
  EXPECT_NEAR(sq.areaPerPoint / (h * h), 1.0, 0.1);
  EXPECT_LT(sq.noise, 1e-6 * h);
  const SamplingEstimate tri = growth::estimateSampling(triangular);
  EXPECT_NEAR(tri.spacing, h, 1e-9);
  EXPECT_NEAR(tri.areaPerPoint / (h * h * std::sqrt(3.0) / 2), 1.0, 0.1);
  EXPECT_LT(tri.noise, 1e-6 * h);
  // A latitude-longitude sampling of the unit sphere (rows crowd at the poles): sane values, the
  // spacing of the rows at the equator at most, little noise.
  std::vector<Point3d> latLong;
  const int rows = 150, columns = 300;
  for (int i = 1; i < rows; ++i)
    for (int j = 0; j < columns; ++j) {
      const double theta = M_PI * i / rows, phi = 2 * M_PI * j / columns;
      latLong.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
    }
  const SamplingEstimate ll = growth::estimateSampling(latLong);
  expectFiniteSane(ll);
  EXPECT_GT(ll.spacing, 0.0);
  EXPECT_LE(ll.spacing, M_PI / rows + 1e-9);
  EXPECT_GT(ll.areaPerPoint, 0.0);
  EXPECT_LT(ll.areaPerPoint, 4 * M_PI / double(latLong.size()) * 2);
  EXPECT_LT(ll.noise, 0.15 * ll.spacing);
}

TEST(CloudScale, SameResultForAnyThreadCount) {
  CloudSpec c = spec(Shape::Torus, 60000, 13);
  c.noiseBound = 0.01;
  c.outlierFraction = 0.01;
  const auto cloud = growth::generateCloud(c).points;
  const SamplingEstimate one = growth::estimateSampling(cloud, 1);
  for (int threads : {2, 3, 8, 0}) EXPECT_TRUE(sameEstimate(growth::estimateSampling(cloud, threads), one)) << threads;
}

TEST(CloudScale, IsolatedSamplesAreCountedNotUsed) {
  // Every 10th point moved far off a dense patch (inside the robust box): those samples find no
  // 16 neighbours within the search cap.
  auto cloud = growth::generateCloud(spec(Shape::Patch, 20000, 15)).points;
  growth::Random rng(3);
  size_t moved = 0;
  for (size_t i = 0; i < cloud.size(); i += 100, ++moved) cloud[i][2] += 0.3 + rng.uniform(0, 0.3);
  const SamplingEstimate e = growth::estimateSampling(cloud);
  EXPECT_GE(e.isolated, moved * 9 / 10);
  EXPECT_EQ(e.samples + e.isolated, cloud.size());
}

TEST(CloudScale, NonUniformDensity) {
  // 5:1 density along z: the medians sit between the sparse and the dense ends.
  CloudSpec c = spec(Shape::Sphere, 50000, 17);
  c.nonUniform = true;
  c.densityRatio = 5;
  const SamplingEstimate e = growth::estimateSampling(growth::generateCloud(c).points);
  const double mean = growth::shapeArea(c) / double(c.count);
  EXPECT_GT(e.areaPerPoint, 0.5 * mean);
  EXPECT_LT(e.areaPerPoint, 1.5 * mean);
  EXPECT_EQ(e.isolated, 0u);
  EXPECT_LT(e.noise, 0.15 * e.medianSpacing);
}

// With the normals (SamplingOptions::normals), a closed plate 2.6 median spacings thick reads as
// two sheets, not as one noisy surface sampled twice as densely: the plate's area per point, the
// noise of one sheet (that of a plate 20 times thicker), and the thickness as the sheets' gap. The
// neighbours whose normals are flipped but lie along the tangent plane (inconsistently oriented
// normals on one sheet) are kept: a plane with every other normal flipped measures as a plane.
TEST(CloudScale, NormalsSeparateTheSheetsOfAThinPlate) {
  CloudSpec thin = spec(Shape::Slab, 50000, 3), thick = thin;
  thin.slabThickness = 0.0165;
  thick.slabThickness = 0.33;
  const growth::Cloud a = growth::generateCloud(thin), b = growth::generateCloud(thick);
  growth::SamplingOptions withNormals;
  withNormals.normals = &a.normals;
  const SamplingEstimate blind = growth::estimateSampling(a.points), sheets = growth::estimateSampling(a.points, withNormals);
  withNormals.normals = &b.normals;
  const SamplingEstimate reference = growth::estimateSampling(b.points, withNormals);
  EXPECT_LT(thin.slabThickness / sheets.spacing, 3.0);
  const double areaPerPoint = growth::shapeArea(thin) / double(thin.count);
  // Without the normals: about half the area per point, and the gap read as noise.
  EXPECT_LT(blind.areaPerPoint, 0.7 * areaPerPoint);
  EXPECT_GT(blind.noise, 0.2 * thin.slabThickness);
  // With them: the plate's, and one sheet's noise.
  EXPECT_NEAR(sheets.areaPerPoint, areaPerPoint, 0.05 * areaPerPoint);
  EXPECT_LT(sheets.noise, 0.02 * thin.slabThickness);
  EXPECT_LE(sheets.noise, reference.noise + 0.002 * thin.slabThickness);
  EXPECT_GT(sheets.sheetGaps.size(), sheets.samples * 9 / 10);
  std::vector<float> gaps = sheets.sheetGaps;
  std::nth_element(gaps.begin(), gaps.begin() + std::ptrdiff_t(gaps.size() / 2), gaps.end());
  EXPECT_NEAR(gaps[gaps.size() / 2], thin.slabThickness, 0.02 * thin.slabThickness);
  EXPECT_LT(reference.sheetGaps.size(), reference.samples / 50); // the thick plate's rims only

  // One sheet, every other normal flipped: all neighbours kept.
  const growth::Cloud plane = growth::generateCloud(spec(Shape::Patch, 20000, 5));
  std::vector<Point3d> flipped = plane.normals;
  for (size_t i = 0; i < flipped.size(); i += 2) flipped[i] = -flipped[i];
  growth::SamplingOptions mixed;
  mixed.normals = &flipped;
  const SamplingEstimate p0 = growth::estimateSampling(plane.points), p1 = growth::estimateSampling(plane.points, mixed);
  EXPECT_EQ(p1.areaPerPoint, p0.areaPerPoint);
  EXPECT_EQ(p1.noise, p0.noise);
  EXPECT_TRUE(p1.sheetGaps.empty());
}
