#pragma once
// Morton (Z-order) codes of integer cell coordinates: visiting cells by increasing code keeps
// nearby cells close in memory. Coordinates use their low 21 bits (a 63-bit code).
#include <cstdint>

namespace growth {

// Spreads the low 21 bits of v to every third bit: bit i goes to bit 3i.
inline std::uint64_t mortonSpread(std::uint64_t v) {
  v &= 0x1fffff;
  v = (v | v << 32) & 0x1f00000000ffffull;
  v = (v | v << 16) & 0x1f0000ff0000ffull;
  v = (v | v << 8) & 0x100f00f00f00f00full;
  v = (v | v << 4) & 0x10c30c30c30c30c3ull;
  v = (v | v << 2) & 0x1249249249249249ull;
  return v;
}

// Interleaves x, y, z (x in the lowest bit).
inline std::uint64_t mortonCode(std::uint64_t x, std::uint64_t y, std::uint64_t z) {
  return mortonSpread(x) | mortonSpread(y) << 1 | mortonSpread(z) << 2;
}

} // namespace growth
