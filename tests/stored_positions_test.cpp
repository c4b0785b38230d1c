// Positions rounded as the output layer stores them (filter_spherepack/engine/stored_positions.h).
#include "stored_positions.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

// A loop over many points (the case GCC 12 vectorises, where double(float(x)) was folded to x):
// every coordinate is rounded to float, and double storage leaves it as it is.
TEST(StoredPositions, EveryCoordinateIsRoundedInALongLoop) {
  std::vector<growth::Vec3d> p(200000);
  for (size_t i = 0; i < p.size(); ++i)
    p[i] = growth::Vec3d(-0.014897726704867475 + 1e-9 * double(i), 0.16640705533776953, 1.0 / 3.0);
  const std::vector<growth::Vec3d> f = growth::asStored<float>(p);
  const std::vector<growth::Vec3d> d = growth::asStored<double>(p);
  // A double holds a float value (of normal magnitude) when its 29 lowest mantissa bits are zero;
  // checked on the bits, since a float round trip in the check itself could be folded the same way.
  auto isFloat = [](double x) {
    std::uint64_t bits;
    std::memcpy(&bits, &x, sizeof bits);
    return (bits & ((std::uint64_t(1) << 29) - 1)) == 0;
  };
  size_t unrounded = 0, moved = 0;
  for (size_t i = 0; i < p.size(); ++i)
    for (int a = 0; a < 3; ++a) {
      unrounded += isFloat(f[i][a]) ? 0 : 1;
      moved += std::abs(f[i][a] - p[i][a]) <= 1e-7 * std::abs(p[i][a]) ? 0 : 1;
      ASSERT_EQ(d[i][a], p[i][a]);
    }
  EXPECT_EQ(unrounded, 0u);
  EXPECT_EQ(moved, 0u); // to the nearest float, not elsewhere
  EXPECT_FALSE(isFloat(p[119169][0]));
}
