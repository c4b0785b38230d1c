// growth::mortonSpread / mortonCode against a bit-by-bit reference.
#include <growth/morton.h>

#include <gtest/gtest.h>

namespace {

std::uint64_t referenceCode(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  std::uint64_t code = 0;
  for (int i = 0; i < 21; ++i) {
    code |= ((x >> i) & 1u) << (3 * i);
    code |= ((y >> i) & 1u) << (3 * i + 1);
    code |= ((z >> i) & 1u) << (3 * i + 2);
  }
  return code;
}

TEST(Morton, MatchesTheBitByBitInterleave) {
  const std::uint64_t values[] = {0, 1, 2, 3, 5, 0x155555, 0xaaaaa, 0x1fffff, 123456, 2000001};
  for (std::uint64_t x : values)
    for (std::uint64_t y : values)
      for (std::uint64_t z : values) EXPECT_EQ(growth::mortonCode(x, y, z), referenceCode(x, y, z));
}

TEST(Morton, OnlyTheLow21BitsCount) {
  EXPECT_EQ(growth::mortonSpread(std::uint64_t(1) << 21), 0u);
  EXPECT_EQ(growth::mortonSpread((std::uint64_t(1) << 21) | 5), growth::mortonSpread(5));
  EXPECT_EQ(growth::mortonCode(0x1fffff, 0x1fffff, 0x1fffff), (std::uint64_t(1) << 63) - 1);
}

} // namespace
