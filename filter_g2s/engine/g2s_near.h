#pragma once
// The scans behind the Robust G2S searches (sec. 3.2 steps 4.1–4.2): gathering the points of a
// ball from the grid's cells, and testing the gathered points against a search sphere or a G2S
// ball. They run on float coordinates relative to the grid's box (structure of arrays), many
// points per instruction, and write the points that pass by compressing the vector lanes, so no
// branch depends on which points pass.
//
// Three implementations, chosen once at run time from what the processor supports: AVX-512
// (16 lanes), AVX2 (8 lanes) and SSE2 (4 lanes, every x86-64). All compute the same float
// values (the same operations in the same order, no fused multiply–add), so they pass the same
// points in the same order and the mesh does not depend on the processor.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace growth {
namespace g2s {

// The widest vector of the implementations: arrays that are scanned or written whole vectors at a
// time hold this many entries past their last point.
constexpr std::size_t kNearPad = 16;

// Points gathered around a query: grid indices and float coordinates relative to the grid's box
// (MortonGrid::gatherNear, over growth::PointIndex). Every distance computed from them is within the grid's floatSlack(c, r) of
// the exact one, so a scan decides most points in float and re-checks in double only those within
// the slack of a sphere.
struct NearList {
  std::vector<std::uint32_t> id;
  std::vector<float> x, y, z;
  // Scratch for the positions that collectWithin and insideOrBorderline write, as long as id
  // (mutable: a const search may use it).
  mutable std::vector<std::uint32_t> hit;
  std::size_t size = 0;

  void clear() { size = 0; }
  // Room for `count` points (and kNearPad past them).
  void reserve(std::size_t count) {
    if (count + kNearPad > id.size()) grow(count + kNearPad);
  }
  // Appends the points begin..end-1 of the arrays fx, fy, fz (which hold kNearPad entries past the
  // last point) whose float squared distance to c, ((dx·dx + dy·dy) + dz·dz), is <= r2; their ids
  // are their indices. Calls reserve() itself.
  void appendWithin(const float* fx, const float* fy, const float* fz, std::uint32_t begin, std::uint32_t end,
                    const float* c, float r2) {
    const std::uint32_t range[2] = {begin, end};
    appendWithin(fx, fy, fz, range, 1, end - begin, c, r2);
  }
  // The same for several ranges, ranges[2k]..ranges[2k+1]-1 in turn, holding `points` in all.
  void appendWithin(const float* fx, const float* fy, const float* fz, const std::uint32_t* ranges,
                    std::size_t rangeCount, std::size_t points, const float* c, float r2);
  // Writes to out, in list order, the ids of the points other than skip[0..2] whose float squared
  // distance to c is <= r2 (out must hold size + kNearPad entries); returns how many.
  std::size_t collectWithin(const float* c, float r2, const std::uint32_t* skip, std::uint32_t* out) const;
  // For an emptiness test against a ball of centre c: true when a point other than skip[0..2] has
  // float squared distance < inner (inside, whatever the float error), and then out[0] is the
  // position of such a point; otherwise writes to out the positions of the points other than
  // skip[0..2] with inner <= d2 <= outer (to be decided exactly; out must hold size + kNearPad
  // entries), sets *count, and returns false.
  bool insideOrBorderline(const float* c, float inner, float outer, const std::uint32_t* skip,
                          std::uint32_t* out, std::size_t* count) const;

private:
  void grow(std::size_t n) {
    n = std::max<std::size_t>(n, 2 * id.size());
    if (n < 64) n = 64;
    id.resize(n);
    hit.resize(n);
    x.resize(n, 0.f);
    y.resize(n, 0.f);
    z.resize(n, 0.f);
  }
};

// Which implementation runs. best: what this processor supports; set: force a lower one (tests
// and benchmarks compare them; a level above best() is clamped to it). G2S_SIMD=sse2|avx2|avx512
// in the environment sets the initial choice the same way.
enum class SimdLevel { kSse2 = 0, kAvx2 = 1, kAvx512 = 2 };
SimdLevel bestSimdLevel();
SimdLevel simdLevel();
void setSimdLevel(SimdLevel level);
const char* simdLevelName(SimdLevel level);

} // namespace g2s
} // namespace growth
