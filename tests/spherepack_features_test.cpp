// Keep features in the reconstruction (Params::keepFeatures, cloud_features.h): crease lines and
// corners detected in the cloud, placed before the growth, no face across a crease.
#include "sphere_packer.h"

#include <growth/cloud_generator.h>
#include <growth/mesh_measures.h>
#include <growth/point_normals.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <functional>
#include <limits>
#include <random>
#include <vector>

namespace {

using growth::Vec3d;
namespace sp = growth::spherepack;

// Uniform in [0, 1) from the raw 64-bit output (the same on every platform).
struct Rng {
  std::mt19937_64 g;
  explicit Rng(std::uint64_t seed) : g(seed) {}
  double uniform() { return double(g() >> 11) * (1.0 / 9007199254740992.0); }
  double symmetric() { return 2 * uniform() - 1; }
};

// A CAD-like solid's sampled surface: `planes` (the faces, each a region of a plane with its
// outward normal) sampled by `sample`, plus uniform noise of at most `noise` per coordinate.
struct Solid {
  std::vector<Vec3d> points, normals;
};

const double kHalf[3] = {1.0, 0.75, 0.5}; // the box's half sizes

Solid boxCloud(size_t n, std::uint64_t seed, double noise) {
  Rng r(seed);
  Solid s;
  const double area[3] = {4 * kHalf[1] * kHalf[2], 4 * kHalf[0] * kHalf[2], 4 * kHalf[0] * kHalf[1]};
  const double total = 2 * (area[0] + area[1] + area[2]);
  for (int f = 0; f < 6; ++f) {
    const int ax = f / 2;
    const double sign = f % 2 ? 1.0 : -1.0;
    const size_t m = size_t(std::lround(double(n) * area[ax] / total));
    for (size_t i = 0; i < m; ++i) {
      Vec3d p(kHalf[0] * r.symmetric(), kHalf[1] * r.symmetric(), kHalf[2] * r.symmetric());
      p[ax] = sign * kHalf[ax];
      Vec3d nn(0, 0, 0);
      nn[ax] = sign;
      for (int k = 0; k < 3; ++k) p[k] += noise * r.symmetric();
      s.points.push_back(p);
      s.normals.push_back(nn);
    }
  }
  return s;
}

// A cylinder of radius 0.6 and height 2 (z from -1 to 1) with its two caps.
Solid cylinderCloud(size_t n, std::uint64_t seed) {
  Rng r(seed);
  Solid s;
  const double R = 0.6, H = 2, pi = 3.14159265358979323846;
  const double side = 2 * pi * R * H, cap = pi * R * R, total = side + 2 * cap;
  for (size_t i = 0; i < size_t(double(n) * side / total); ++i) {
    const double t = 2 * pi * r.uniform(), z = H * (r.uniform() - 0.5);
    s.points.push_back(Vec3d(R * std::cos(t), R * std::sin(t), z));
    s.normals.push_back(Vec3d(std::cos(t), std::sin(t), 0));
  }
  for (int c = 0; c < 2; ++c)
    for (size_t i = 0; i < size_t(double(n) * cap / total); ++i) {
      const double rr = R * std::sqrt(r.uniform()), t = 2 * pi * r.uniform();
      s.points.push_back(Vec3d(rr * std::cos(t), rr * std::sin(t), c ? H / 2 : -H / 2));
      s.normals.push_back(Vec3d(0, 0, c ? 1 : -1));
    }
  return s;
}

// Two unit-wide strips meeting along the y axis (y from -1 to 1): the first in the plane z = 0
// for x in [0, 1], the second turned by `angleDeg` about the y axis (the normals differ by it).
Solid foldCloud(size_t n, std::uint64_t seed, double angleDeg) {
  Rng r(seed);
  Solid s;
  const double a = angleDeg * 3.14159265358979323846 / 180;
  const Vec3d dir(-std::cos(a), 0, std::sin(a)), n2(std::sin(a), 0, std::cos(a));
  for (size_t i = 0; i < n / 2; ++i) {
    s.points.push_back(Vec3d(r.uniform(), r.symmetric(), 0));
    s.normals.push_back(Vec3d(0, 0, 1));
  }
  for (size_t i = 0; i < n / 2; ++i) {
    s.points.push_back(dir * r.uniform() + Vec3d(0, r.symmetric(), 0));
    s.normals.push_back(n2);
  }
  return s;
}

struct Result {
  growth::MeshArrays out;
  sp::Stat st;
};

Result reconstruct(const Solid& s, bool keepFeatures, double d = 0) {
  growth::CloudArrays c;
  c.points = s.points;
  c.normals = s.normals;
  c.floatStorage = false;
  sp::Params p;
  p.keepFeatures = keepFeatures;
  p.sphereDiameter = d;
  p.threads = 2;
  Result r;
  sp::build(std::move(c), r.out, p, r.st);
  return r;
}

double segmentDistance(const Vec3d& x, const Vec3d& a, const Vec3d& b) {
  const Vec3d e = b - a;
  const double t = std::min(1.0, std::max(0.0, ((x - a) * e) / e.SquaredNorm()));
  return (x - (a + e * t)).Norm();
}

// The largest distance from the points of the segment a–b (every d/8) to the output's edges.
// Edges with an end within 3 d of the segment are searched first; a point farther than d from
// all of them searches every edge.
double creaseDistance(const growth::MeshArrays& m, const Vec3d& a, const Vec3d& b, double d, Vec3d* worstAt = nullptr) {
  std::vector<size_t> near;
  for (size_t f = 0; f < m.faces.size(); ++f)
    for (int j = 0; j < 3; ++j)
      if (segmentDistance(m.vertices[m.faces[f][j]], a, b) < 3 * d) {
        near.push_back(f);
        break;
      }
  const int steps = std::max(1, int(std::ceil((b - a).Norm() / (d / 8))));
  double worst = 0;
  for (int k = 0; k <= steps; ++k) {
    const Vec3d x = a + (b - a) * (double(k) / steps);
    double best = std::numeric_limits<double>::infinity();
    for (size_t f : near)
      for (int j = 0; j < 3; ++j)
        best = std::min(best, segmentDistance(x, m.vertices[m.faces[f][j]], m.vertices[m.faces[f][(j + 1) % 3]]));
    if (!(best <= d))
      for (const auto& f : m.faces)
        for (int j = 0; j < 3; ++j)
          best = std::min(best, segmentDistance(x, m.vertices[f[j]], m.vertices[f[(j + 1) % 3]]));
    if (best > worst && worstAt) *worstAt = x;
    worst = std::max(worst, best);
  }
  return worst;
}

double nearestVertex(const growth::MeshArrays& m, const Vec3d& x) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec3d& v : m.vertices) best = std::min(best, (v - x).Norm());
  return best;
}

// Faces with one vertex only on side i and another only on side j != i, where side(v) lists the
// sides a vertex is on (more than one: on a crease).
size_t facesAcross(const growth::MeshArrays& m, const std::function<std::vector<int>(const Vec3d&)>& sides) {
  size_t bad = 0;
  for (const auto& f : m.faces) {
    int only = -1;
    bool across = false;
    for (int k = 0; k < 3; ++k) {
      const std::vector<int> s = sides(m.vertices[f[k]]);
      if (s.size() != 1) continue;
      if (only >= 0 && only != s[0]) across = true;
      only = s[0];
    }
    bad += across ? 1 : 0;
    if (across && bad <= 5 && std::getenv("FEATURE_TEST_DEBUG"))
      for (int k = 0; k < 3; ++k)
        std::printf("  across face %zu: (%.4f %.4f %.4f)\n", bad, m.vertices[f[k]][0], m.vertices[f[k]][1], m.vertices[f[k]][2]);
  }
  return bad;
}

void expectSoundMesh(const Result& r) {
  const double d = r.st.sphereDiameter;
  ASSERT_GT(r.out.faces.size(), 0u);
  EXPECT_EQ(growth::countNonManifoldEdges(r.out), 0u);
  EXPECT_EQ(growth::countNonManifoldVertices(r.out), 0u);
  EXPECT_EQ(growth::countSelfIntersections(r.out), 0u);
  double shortest = std::numeric_limits<double>::infinity();
  for (const auto& f : r.out.faces)
    for (int j = 0; j < 3; ++j) shortest = std::min(shortest, (r.out.vertices[f[j]] - r.out.vertices[f[(j + 1) % 3]]).Norm());
  EXPECT_GE(shortest, d * (1 - 1e-9));
}

// Box side of a vertex: the faces of the box it lies within `tol` of.
std::vector<int> boxSides(const Vec3d& x, double tol) {
  std::vector<int> s;
  for (int ax = 0; ax < 3; ++ax)
    for (int sg = 0; sg < 2; ++sg)
      if (std::abs(x[ax] - (sg ? kHalf[ax] : -kHalf[ax])) < tol) s.push_back(2 * ax + sg);
  return s;
}

// What the box's reconstruction kept of its corners and creases.
struct BoxMeasures {
  double worstCorner = 0, worstCrease = 0; // per d: the farthest corner from a vertex, crease point from an edge
  Vec3d worstCreaseAt{0, 0, 0};
  size_t across = 0;                       // faces across a crease
  size_t boundaryLoops = 0;
};

BoxMeasures measureBox(const Result& r) {
  const double d = r.st.sphereDiameter;
  BoxMeasures m;
  for (int c = 0; c < 8; ++c) {
    const Vec3d x(c & 1 ? kHalf[0] : -kHalf[0], c & 2 ? kHalf[1] : -kHalf[1], c & 4 ? kHalf[2] : -kHalf[2]);
    m.worstCorner = std::max(m.worstCorner, nearestVertex(r.out, x) / d);
    for (int ax = 0; ax < 3; ++ax)
      if (!(c & (1 << ax))) { // the box edge from this corner along +ax
        Vec3d y = x;
        y[ax] = kHalf[ax];
        Vec3d at;
        const double dist = creaseDistance(r.out, x, y, d, &at) / d;
        if (dist > m.worstCrease) m.worstCrease = dist, m.worstCreaseAt = at;
      }
  }
  // A vertex counts as on a face within d/4 of it; vertices nearer two faces are on the crease.
  m.across = facesAcross(r.out, [&](const Vec3d& x) { return boxSides(x, 0.25 * d); });
  m.boundaryLoops = growth::countBoundaryLoops(r.out);
  return m;
}

// extraPatches: patches allowed beyond the box's 6 (with PCA normals a stray crease point can
// split off a small patch: 7 with clang's build at d = 0.038; the geometry is checked below).
void checkBox(const Result& r, double cornerTol, double creaseTol, size_t extraPatches = 0) {
  const double d = r.st.sphereDiameter;
  EXPECT_EQ(r.st.featureCorners, 8u);
  EXPECT_EQ(r.st.featureLines, 12u);
  EXPECT_GE(r.st.featurePatches, 6u);
  EXPECT_LE(r.st.featurePatches, 6u + extraPatches);
  expectSoundMesh(r);
  const BoxMeasures m = measureBox(r);
  EXPECT_LT(m.worstCorner, cornerTol);
  EXPECT_LT(m.worstCrease, creaseTol);
  EXPECT_EQ(m.across, 0u);
  std::printf("box: d %.6g, worst corner %.4f d, worst crease %.4f d at (%.3f %.3f %.3f), %zu vertices, %zu boundary loops\n",
              d, m.worstCorner, m.worstCrease, m.worstCreaseAt[0], m.worstCreaseAt[1], m.worstCreaseAt[2],
              r.out.vertices.size(), m.boundaryLoops);
}

// The box with PCA normals (K = 10), turned outwards only where the propagation flipped a whole
// face, as a user would fix them before the filter.
Solid boxCloudPcaNormals(size_t n, std::uint64_t seed, double noise) {
  Solid s = boxCloud(n, seed, noise);
  s.normals = growth::estimateNormals(s.points, 10);
  for (size_t i = 0; i < s.points.size(); ++i) {
    int ax = 0;
    for (int k = 1; k < 3; ++k)
      if (std::abs(s.points[i][k]) / kHalf[k] > std::abs(s.points[i][ax]) / kHalf[ax]) ax = k;
    if (s.normals[i][ax] * s.points[i][ax] < 0) s.normals[i] = -s.normals[i];
  }
  return s;
}

TEST(SpherePackFeatures, OffByDefault) {
  EXPECT_FALSE(sp::Params().keepFeatures);
  EXPECT_EQ(sp::Params().creaseAngleDeg, 30.0);
}

TEST(SpherePackFeatures, BoxExactNormalsKeepsCornersAndCreases) {
  const Solid s = boxCloud(30000, 1, 0.0005);
  // d given (the default d is about 0.037 here and varies in its last digits with the compiler;
  // other d: BoxExactNormalsAcrossD).
  const Result r = reconstruct(s, true, 0.038);
  checkBox(r, 0.05, 0.05);
  // Without the option the corners are not kept (what the test above measures is the option's).
  const Result plain = reconstruct(s, false);
  double worst = 0;
  for (int c = 0; c < 8; ++c)
    worst = std::max(worst, nearestVertex(plain.out, Vec3d(c & 1 ? kHalf[0] : -kHalf[0], c & 2 ? kHalf[1] : -kHalf[1],
                                                           c & 4 ? kHalf[2] : -kHalf[2])));
  EXPECT_GT(worst, 0.05 * plain.st.sphereDiameter);
}

TEST(SpherePackFeatures, BoxEstimatedNormals) {
  const Solid s = boxCloudPcaNormals(30000, 2, 0.0005);
  const Result r = reconstruct(s, true, 0.038);
  // The crease points of PCA normals' neighbourhoods scatter more than with exact normals.
  checkBox(r, 0.05, 0.1, 1);
}

// The detection is stable across d: the box at d from 0.0305 to 0.0425 (the default is about
// 0.037), with 0.0365, where a crease line once ended at a gap in the crease points and the line
// traced from beyond the gap was dropped, and 0.0370774, clang's default d (gcc's is 0.0370878).
const double kBoxDiameters[] = {0.0305, 0.0335, 0.0365, 0.0370774, 0.0425};

TEST(SpherePackFeatures, BoxExactNormalsAcrossD) {
  const Solid s = boxCloud(30000, 1, 0.0005);
  for (const double d : kBoxDiameters) {
    SCOPED_TRACE(d);
    checkBox(reconstruct(s, true, d), 0.05, 0.1);
  }
}

TEST(SpherePackFeatures, BoxEstimatedNormalsAcrossD) {
  const Solid s = boxCloudPcaNormals(30000, 2, 0.0005);
  for (const double d : kBoxDiameters) {
    SCOPED_TRACE(d);
    checkBox(reconstruct(s, true, d), 0.05, 0.1);
  }
}

// One line per run of the box of `seed` (exact normals; PCA normals on the box of seed + 1) at
// each d, with the stability goal checked: 8 corners, 12 lines, 6 patches, creases within 0.1 d,
// no face across.
void sweepBox(std::uint64_t seed, const std::vector<double>& diameters) {
  const Solid exact = boxCloud(30000, seed, 0.0005), pca = boxCloudPcaNormals(30000, seed + 1, 0.0005);
  for (int pass = 0; pass < 2; ++pass)
    for (const double d : diameters) {
      const Result r = reconstruct(pass ? pca : exact, true, d);
      const BoxMeasures m = measureBox(r);
      std::printf("%-8s %4llu %.4f   %2zu      %2zu    %2zu      %.4f   %.4f   %3zu    %zu      (%.3f %.3f %.3f)\n",
                  pass ? "pca" : "exact", static_cast<unsigned long long>(pass ? seed + 1 : seed), d,
                  r.st.featureCorners, r.st.featureLines, r.st.featurePatches, m.worstCorner, m.worstCrease, m.across,
                  m.boundaryLoops, m.worstCreaseAt[0], m.worstCreaseAt[1], m.worstCreaseAt[2]);
      std::fflush(stdout);
      EXPECT_EQ(r.st.featureCorners, 8u) << d;
      EXPECT_EQ(r.st.featureLines, 12u) << d;
      EXPECT_EQ(r.st.featurePatches, 6u) << d;
      EXPECT_LT(m.worstCrease, 0.1) << d;
      EXPECT_EQ(m.across, 0u) << d;
    }
}

const char* const kSweepHeader =
    "normals  seed d        corners lines patches corner/d crease/d across loops  worst crease at\n";

// The sweeps behind issue 31's stability goal (a minute or two each, not part of the unit tests):
//   build/tests/spherepack_features_test --gtest_also_run_disabled_tests --gtest_filter='*BoxSweep*'
// The box of the tests at d from 0.030 to 0.046 in steps of 0.0005, and boxes of other seeds at
// five d of that range.
TEST(SpherePackFeatures, DISABLED_BoxSweep) {
  std::vector<double> diameters;
  for (int k = 0; k <= 32; ++k) diameters.push_back(0.030 + 0.0005 * k);
  std::printf("%s", kSweepHeader);
  sweepBox(1, diameters);
}

TEST(SpherePackFeatures, DISABLED_BoxSweepOtherSeeds) {
  std::printf("%s", kSweepHeader);
  for (std::uint64_t seed = 11; seed <= 25; seed += 2) sweepBox(seed, {0.030, 0.034, 0.038, 0.042, 0.046});
}

TEST(SpherePackFeatures, CylinderRimsAreClosedLines) {
  const Solid s = cylinderCloud(30000, 3);
  const Result r = reconstruct(s, true);
  const double d = r.st.sphereDiameter;
  EXPECT_EQ(r.st.featureLines, 2u);
  EXPECT_EQ(r.st.featureCorners, 0u);
  EXPECT_EQ(r.st.featurePatches, 3u); // the caps and the mantle
  expectSoundMesh(r);
  double worst = 0;
  for (int c = 0; c < 2; ++c)
    for (int k = 0; k < 64; ++k) {
      const double t = 2 * 3.14159265358979323846 * k / 64;
      const Vec3d a(0.6 * std::cos(t), 0.6 * std::sin(t), c ? 1 : -1);
      worst = std::max(worst, creaseDistance(r.out, a, a, d));
    }
  // A curved crease: the planes fitted to the mantle's curved neighbourhood move the line by up to
  // about a tenth of d.
  EXPECT_LT(worst, 0.15 * d);
  // Sides: the caps (within d/4 of their planes) and the mantle (within d/4 of the radius).
  const auto sides = [&](const Vec3d& x) {
    std::vector<int> s;
    if (std::abs(x[2] + 1) < 0.25 * d) s.push_back(0);
    if (std::abs(x[2] - 1) < 0.25 * d) s.push_back(1);
    if (std::abs(std::hypot(x[0], x[1]) - 0.6) < 0.25 * d) s.push_back(2);
    return s;
  };
  EXPECT_EQ(facesAcross(r.out, sides), 0u);
  std::printf("cylinder: worst rim distance %.4f d\n", worst / d);
}

void checkFold(double angleDeg) {
  const Solid s = foldCloud(20000, 4, angleDeg);
  const Result r = reconstruct(s, true);
  const double d = r.st.sphereDiameter;
  EXPECT_EQ(r.st.featureLines, 1u);
  EXPECT_GE(r.st.featurePatches, 2u);
  expectSoundMesh(r);
  // The crease away from the strips' ends (the samples stop within a spacing or so of the border).
  const double worst = creaseDistance(r.out, Vec3d(0, -1 + 2 * d, 0), Vec3d(0, 1 - 2 * d, 0), d);
  EXPECT_LT(worst, 0.05 * d);
  const double a = angleDeg * 3.14159265358979323846 / 180;
  const Vec3d n2(std::sin(a), 0, std::cos(a));
  const auto sides = [&](const Vec3d& x) {
    std::vector<int> sd;
    if (std::abs(x[2]) < 0.25 * d && x[0] > -0.25 * d) sd.push_back(0);
    if (std::abs(x * n2) < 0.25 * d && x[0] < 0.25 * d) sd.push_back(1);
    return sd;
  };
  EXPECT_EQ(facesAcross(r.out, sides), 0u);
  std::printf("fold %.0f: worst crease distance %.4f d\n", angleDeg, worst / d);
}

TEST(SpherePackFeatures, Fold90) { checkFold(90); }
TEST(SpherePackFeatures, Fold45) { checkFold(45); }

TEST(SpherePackFeatures, Deterministic) {
  const Solid s = boxCloud(20000, 5, 0.0005);
  const Result a = reconstruct(s, true), b = reconstruct(s, true);
  EXPECT_EQ(a.out.vertices.size(), b.out.vertices.size());
  EXPECT_TRUE(a.out.vertices == b.out.vertices);
  EXPECT_TRUE(a.out.faces == b.out.faces);
}

// Smooth surfaces have no crease: nothing is detected and the mesh is the one without the option.
TEST(SpherePackFeatures, SmoothShapesFindNoFeatures) {
  for (const growth::Shape shape : {growth::Shape::Sphere, growth::Shape::Torus}) {
    growth::CloudSpec spec;
    spec.shape = shape;
    spec.count = 30000;
    spec.seed = 6;
    const growth::Cloud c = growth::generateCloud(spec);
    Solid s{c.points, c.normals};
    const Result with = reconstruct(s, true), without = reconstruct(s, false);
    EXPECT_EQ(with.st.featureLines, 0u) << growth::shapeName(shape);
    EXPECT_TRUE(with.out.vertices == without.out.vertices) << growth::shapeName(shape);
    EXPECT_TRUE(with.out.faces == without.out.faces) << growth::shapeName(shape);
  }
}

} // namespace
