#include <growth/cloud_generator.h>
#include <growth/exact_predicates.h>

#include <gtest/gtest.h>

#include <cfloat>
#include <cmath>
#include <cstdint>
#include <vector>

using growth::orient2d;
using growth::orient2dExact;
using growth::orient3d;
using growth::orient3dExact;
using Point3d = growth::Vec3d;

namespace {

__extension__ typedef __int128 Int128;

template <class T>
int signOf(T v) {
  return v > 0 ? 1 : (v < 0 ? -1 : 0);
}

// Integer points (exact in double below 2^53) and their exact orientations in 128-bit integers.
struct IntPoint {
  std::int64_t x, y, z;
};

int orient3dInt(const IntPoint& a, const IntPoint& b, const IntPoint& c, const IntPoint& d) {
  const Int128 adx = a.x - d.x, ady = a.y - d.y, adz = a.z - d.z;
  const Int128 bdx = b.x - d.x, bdy = b.y - d.y, bdz = b.z - d.z;
  const Int128 cdx = c.x - d.x, cdy = c.y - d.y, cdz = c.z - d.z;
  return signOf(adx * (bdy * cdz - bdz * cdy) + bdx * (cdy * adz - cdz * ady) + cdx * (ady * bdz - adz * bdy));
}

int orient2dInt(const IntPoint& a, const IntPoint& b, const IntPoint& c) {
  const Int128 acx = a.x - c.x, acy = a.y - c.y, bcx = b.x - c.x, bcy = b.y - c.y;
  return signOf(acx * bcy - acy * bcx);
}

// The point k·scale (exact: the integers stay below 2^53 and scale is a power of two).
Point3d toDouble(const IntPoint& p, double scale) { return Point3d(double(p.x) * scale, double(p.y) * scale, double(p.z) * scale); }

std::int64_t randomInt(growth::Random& rng, std::int64_t range) {
  return std::int64_t(rng.next() % std::uint64_t(2 * range + 1)) - range;
}

// The naive evaluation the filter starts from, to show the test cases need more than it.
double naiveOrient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  return (ax - cx) * (by - cy) - (ay - cy) * (bx - cx);
}
double naiveOrient3d(const Point3d& a, const Point3d& b, const Point3d& c, const Point3d& d) {
  const Point3d u = a - d, v = b - d, w = c - d;
  return u[0] * (v[1] * w[2] - v[2] * w[1]) + v[0] * (w[1] * u[2] - w[2] * u[1]) + w[0] * (u[1] * v[2] - u[2] * v[1]);
}

} // namespace

TEST(ExactPredicates, SmallLatticeAgreesWithIntegers) {
  // Coordinates in [-3, 3]: a large share of the triples are collinear and of the quadruples
  // coplanar, so the exact zero (which always takes the fallback) is exercised as much as the signs.
  growth::Random rng(11);
  int zeros2 = 0, zeros3 = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    IntPoint p[4];
    for (auto& q : p) q = {randomInt(rng, 3), randomInt(rng, 3), randomInt(rng, 3)};
    Point3d d[4];
    for (int i = 0; i < 4; ++i) d[i] = toDouble(p[i], 1.0);
    const int e2 = orient2dInt(p[0], p[1], p[2]);
    ASSERT_EQ(orient2d(d[0][0], d[0][1], d[1][0], d[1][1], d[2][0], d[2][1]), e2) << trial;
    ASSERT_EQ(orient2dExact(d[0][0], d[0][1], d[1][0], d[1][1], d[2][0], d[2][1]), e2) << trial;
    const int e3 = orient3dInt(p[0], p[1], p[2], p[3]);
    ASSERT_EQ(orient3d(d[0], d[1], d[2], d[3]), e3) << trial;
    ASSERT_EQ(orient3dExact(d[0], d[1], d[2], d[3]), e3) << trial;
    zeros2 += e2 == 0;
    zeros3 += e3 == 0;
  }
  EXPECT_GT(zeros2, 1000);
  EXPECT_GT(zeros3, 1000);
}

TEST(ExactPredicates, NearCoplanarFineLatticeAgreesWithIntegers) {
  // Points k·2^-20 with |k| < 2^31 forming slivers: b = a + B, c = a + λB + e1, d = a + μB + e2
  // with B long and e1, e2 a few lattice units, so that the determinant (B×e1)·e2 is about 2^-30
  // of the products it is made of: far below the naive evaluation's rounding error. Decided
  // against 128-bit integer arithmetic.
  growth::Random rng(12);
  const double scale = std::ldexp(1.0, -20);
  const std::int64_t range = std::int64_t(1) << 29;
  int zeros = 0, naiveWrong = 0;
  for (int trial = 0; trial < 20000; ++trial) {
    const IntPoint a{randomInt(rng, range), randomInt(rng, range), randomInt(rng, range)};
    const IntPoint B{randomInt(rng, range), randomInt(rng, range), randomInt(rng, range)};
    const IntPoint e1{randomInt(rng, 3), randomInt(rng, 3), randomInt(rng, 3)};
    IntPoint e2{randomInt(rng, 3), randomInt(rng, 3), randomInt(rng, 3)};
    if (trial % 3 == 0) e2 = {2 * e1.x, 2 * e1.y, 2 * e1.z}; // coplanar
    const std::int64_t lambda = randomInt(rng, 3), mu = randomInt(rng, 3);
    const IntPoint b{a.x + B.x, a.y + B.y, a.z + B.z};
    const IntPoint c{a.x + lambda * B.x + e1.x, a.y + lambda * B.y + e1.y, a.z + lambda * B.z + e1.z};
    const IntPoint d{a.x + mu * B.x + e2.x, a.y + mu * B.y + e2.y, a.z + mu * B.z + e2.z};
    const Point3d A = toDouble(a, scale), Bp = toDouble(b, scale), C = toDouble(c, scale), D = toDouble(d, scale);
    const int expected = orient3dInt(a, b, c, d);
    ASSERT_EQ(orient3d(A, Bp, C, D), expected) << trial;
    ASSERT_EQ(orient3dExact(A, Bp, C, D), expected) << trial;
    // Any order of the points: the sign of the permutation.
    ASSERT_EQ(orient3d(Bp, A, C, D), -expected) << trial;
    ASSERT_EQ(orient3d(D, Bp, C, A), -expected) << trial;
    ASSERT_EQ(orient3d(Bp, C, A, D), expected) << trial;
    // In the plane: c and d near the line a–b.
    const int expected2 = orient2dInt(a, b, d);
    ASSERT_EQ(orient2d(A[0], A[1], Bp[0], Bp[1], D[0], D[1]), expected2) << trial;
    ASSERT_EQ(orient2dExact(A[0], A[1], Bp[0], Bp[1], D[0], D[1]), expected2) << trial;
    zeros += expected == 0;
    naiveWrong += signOf(naiveOrient3d(A, Bp, C, D)) != expected;
  }
  EXPECT_GT(zeros, 3000);
  EXPECT_GT(naiveWrong, 1000); // the cases are hard: rounding alone decides many of them wrongly
}

TEST(ExactPredicates, OneUlpGridAroundALine) {
  // p = (0.5 + i·2^-53, 0.5 + j·2^-53) against the line y = x through (12, 12) and (24, 24):
  // orient2d(p, (12,12), (24,24)) = 12·(py − px), so its sign is sign(j − i) exactly. The naive
  // evaluation gets a good share of these wrong.
  const double u = std::ldexp(1.0, -53);
  int naiveWrong = 0;
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const double px = 0.5 + i * u, py = 0.5 + j * u;
      const int expected = signOf(j - i);
      ASSERT_EQ(orient2d(px, py, 12, 12, 24, 24), expected) << i << ' ' << j;
      ASSERT_EQ(orient2d(12, 12, 24, 24, px, py), expected) << i << ' ' << j;
      naiveWrong += signOf(naiveOrient2d(px, py, 12, 12, 24, 24)) != expected;
    }
  EXPECT_GT(naiveWrong, 100);

  // The same in 3D, against the vertical plane x = y.
  const Point3d a(12, 12, 0), b(24, 24, 0), c(0, 0, 1);
  const int side = orient3d(a, b, c, Point3d(0, 1, 0)); // y > x
  ASSERT_NE(side, 0);
  for (int i = 0; i < 64; ++i)
    for (int j = 0; j < 64; ++j) {
      const Point3d p(0.5 + i * u, 0.5 + j * u, 0.25);
      ASSERT_EQ(orient3d(a, b, c, p), side * signOf(j - i)) << i << ' ' << j;
    }
}

TEST(ExactPredicates, OneUlpOffAnInexactPlane) {
  // The horizontal plane z = fl(0.1) through three points whose coordinates are not short dyadics;
  // points on it are coplanar, and one ulp above or below it are not.
  const double z = 0.1;
  const Point3d a(0.3, 0.7, z), b(1.9, -0.2, z), c(-0.6, 1.3, z);
  const int above = orient3d(a, b, c, Point3d(0.2, 0.4, 5));
  ASSERT_NE(above, 0);
  for (double x : {0.1, 0.37, 1e3, -7.25})
    for (double y : {0.2, -0.61, 1e-3}) {
      EXPECT_EQ(orient3d(a, b, c, Point3d(x, y, z)), 0);
      EXPECT_EQ(orient3d(a, b, c, Point3d(x, y, std::nextafter(z, 1.0))), above);
      EXPECT_EQ(orient3d(a, b, c, Point3d(x, y, std::nextafter(z, 0.0))), -above);
    }
}

TEST(ExactPredicates, ExtremeExponentsKeepTheSign) {
  // A near-coplanar configuration scaled by 2^±280: every product stays representable, so the
  // sign does not change (scaling by a power of two is exact).
  const Point3d a(0.3, 0.7, 0.1), b(1.9, -0.2, 0.1), c(-0.6, 1.3, 0.1);
  for (int k : {-280, -100, 0, 100, 280}) {
    const double s = std::ldexp(1.0, k);
    const Point3d on(0.25 * s, 0.5 * s, 0.1 * s);
    const Point3d up(0.25 * s, 0.5 * s, std::nextafter(0.1 * s, 1e300));
    EXPECT_EQ(orient3d(a * s, b * s, c * s, on), 0) << k;
    EXPECT_EQ(orient3d(a * s, b * s, c * s, up), orient3d(a, b, c, Point3d(0, 0, 1))) << k;
    EXPECT_EQ(orient2d(0.5 * s, 0.5 * s, 12 * s, 12 * s, 24 * s, 24 * s), 0) << k;
    EXPECT_EQ(orient2d(0.5 * s, std::nextafter(0.5 * s, 1e300), 12 * s, 12 * s, 24 * s, 24 * s), 1) << k;
  }
}

TEST(ExactPredicates, LargeOffsetsCancelExactly) {
  // Coplanar points far from the origin: the differences cancel, the raw products the exact
  // evaluation adds up are 2^90 and more, and still sum to exactly zero.
  const double o = std::ldexp(1.0, 30);
  const Point3d a(o + 1, o + 2, o + 3), b(o + 4, o - 5, o + 6), c(o - 7, o + 8, o + 9);
  const Point3d d = Point3d(o, o, o) + ((b - a) * 3.0 - (c - a) * 2.0) + Point3d(1, 2, 3);
  EXPECT_EQ(orient3dExact(a, b, c, d), 0);
  EXPECT_EQ(orient3d(a, b, c, d), 0);
  EXPECT_EQ(orient3dExact(a, b, c, d + Point3d(0, 0, 1)), orient3dExact(a - Point3d(o, o, o), b - Point3d(o, o, o), c - Point3d(o, o, o), d + Point3d(-o, -o, 1 - o)));
}
