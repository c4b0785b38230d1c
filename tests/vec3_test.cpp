// growth::Vec3d and growth::Box3d: vcglib's Point3d and Box3d API, with its order of operations.
#include <growth/vec3.h>

#include <gtest/gtest.h>

#include <cmath>

using growth::Box3d;
using growth::Vec3d;

TEST(Vec3d, OperatorsAreComponentwiseAndLeftToRight) {
  const Vec3d a(0.1, 0.2, 0.3), b(1e16, -1.0, 3.0);
  EXPECT_EQ(a * b, (0.1 * 1e16 + 0.2 * -1.0) + 0.3 * 3.0); // dot, summed left to right
  const Vec3d c = a ^ b;
  EXPECT_EQ(c[0], 0.2 * 3.0 - 0.3 * -1.0);
  EXPECT_EQ(c[1], 0.3 * 1e16 - 0.1 * 3.0);
  EXPECT_EQ(c[2], 0.1 * -1.0 - 0.2 * 1e16);
  EXPECT_EQ((a + b)[1], 0.2 + -1.0);
  EXPECT_EQ((a - b)[2], 0.3 - 3.0);
  EXPECT_EQ((a * 3.0)[0], 0.1 * 3.0);
  EXPECT_EQ((a / 3.0)[0], 0.1 / 3.0);
  EXPECT_EQ(a.SquaredNorm(), (0.1 * 0.1 + 0.2 * 0.2) + 0.3 * 0.3);
  EXPECT_EQ(a.Norm(), std::sqrt(a.SquaredNorm()));
  EXPECT_EQ(a.X(), a[0]);
  EXPECT_EQ(a.Z(), a[2]);
}

TEST(Vec3d, NormalizeDividesByTheNormAndLeavesZeroAlone) {
  Vec3d v(3, 0, 4);
  v.Normalize();
  EXPECT_EQ(v, Vec3d(3.0 / 5.0, 0, 4.0 / 5.0));
  Vec3d z(0, 0, 0);
  z.Normalize();
  EXPECT_EQ(z, Vec3d(0, 0, 0));
}

TEST(Box3d, NullUntilAPointIsAdded) {
  Box3d b;
  EXPECT_TRUE(b.IsNull());
  b.Add(Vec3d(1, 2, 3));
  EXPECT_FALSE(b.IsNull());
  EXPECT_TRUE(b.IsEmpty());
  b.Add(Vec3d(-1, 4, 3));
  EXPECT_EQ(b.min, Vec3d(-1, 2, 3));
  EXPECT_EQ(b.max, Vec3d(1, 4, 3));
  EXPECT_EQ(b.Dim(), Vec3d(2, 2, 0));
  EXPECT_EQ(b.Center(), Vec3d(0, 3, 3));
  EXPECT_EQ(b.Diag(), std::sqrt(8.0));
  EXPECT_TRUE(b.IsIn(Vec3d(1, 4, 3)));
  EXPECT_FALSE(b.IsIn(Vec3d(1, 4.5, 3)));
  b.Offset(1);
  EXPECT_EQ(b.min, Vec3d(-2, 1, 2));
  Box3d other;
  other.Add(b);
  EXPECT_EQ(other.max, b.max);
  b.Add(Box3d()); // a null box adds nothing
  EXPECT_EQ(other.min, b.min);
}
