#include "g2s_near.h"

#include <algorithm>
#include <cstdlib>
#include <cstring>

#if defined(__x86_64__) || defined(__i386__)
#define G2S_NEAR_X86 1
#include <immintrin.h>
#endif

namespace growth {
namespace g2s {

namespace {

// One implementation of the three scans. `n`/`size` and the returned counts are point counts.
struct Kernels {
  std::size_t (*append)(const float* fx, const float* fy, const float* fz, const std::uint32_t* ranges,
                        std::size_t rangeCount, const float* c, float r2, std::uint32_t* oid, float* ox, float* oy,
                        float* oz, std::size_t n);
  std::size_t (*collect)(const std::uint32_t* id, const float* x, const float* y, const float* z, std::size_t size,
                         const float* c, float r2, const std::uint32_t* skip, std::uint32_t* out);
  bool (*border)(const std::uint32_t* id, const float* x, const float* y, const float* z, std::size_t size,
                 const float* c, float inner, float outer, const std::uint32_t* skip, std::uint32_t* out,
                 std::size_t* count);
};

// --- Portable, and SSE2 four lanes at a time (the baseline of x86-64) ---

#if !defined(__SSE2__)
inline float dist2(float x, float y, float z, const float* c) {
  const float dx = x - c[0], dy = y - c[1], dz = z - c[2];
  return (dx * dx + dy * dy) + dz * dz;
}
#endif

std::size_t appendBase(const float* fx, const float* fy, const float* fz, const std::uint32_t* ranges,
                       std::size_t rangeCount, const float* c, float r2, std::uint32_t* oid, float* ox, float* oy,
                       float* oz, std::size_t n) {
#if defined(__SSE2__)
  const __m128 cx = _mm_set1_ps(c[0]), cy = _mm_set1_ps(c[1]), cz = _mm_set1_ps(c[2]), rr = _mm_set1_ps(r2);
  for (std::size_t r = 0; r < rangeCount; ++r)
  for (std::uint32_t i = ranges[2 * r], end = ranges[2 * r + 1]; i < end; i += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(fx + i), cx);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(fy + i), cy);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(fz + i), cz);
    const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    unsigned mask = static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(d2, rr)));
    if (end - i < 4) mask &= (1u << (end - i)) - 1;
    while (mask != 0) {
      const std::uint32_t k = i + static_cast<std::uint32_t>(__builtin_ctz(mask));
      mask &= mask - 1;
      oid[n] = k;
      ox[n] = fx[k];
      oy[n] = fy[k];
      oz[n] = fz[k];
      ++n;
    }
  }
#else
  for (std::size_t r = 0; r < rangeCount; ++r)
  for (std::uint32_t k = ranges[2 * r]; k < ranges[2 * r + 1]; ++k) {
    if (!(dist2(fx[k], fy[k], fz[k], c) <= r2)) continue;
    oid[n] = k;
    ox[n] = fx[k];
    oy[n] = fy[k];
    oz[n] = fz[k];
    ++n;
  }
#endif
  return n;
}

inline bool skipped(std::uint32_t id, const std::uint32_t* skip) {
  return id == skip[0] || id == skip[1] || id == skip[2];
}

std::size_t collectBase(const std::uint32_t* id, const float* x, const float* y, const float* z, std::size_t size,
                        const float* c, float r2, const std::uint32_t* skip, std::uint32_t* out) {
  std::size_t count = 0;
#if defined(__SSE2__)
  const __m128 cx = _mm_set1_ps(c[0]), cy = _mm_set1_ps(c[1]), cz = _mm_set1_ps(c[2]), rr = _mm_set1_ps(r2);
  for (std::size_t k = 0; k < size; k += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(x + k), cx);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(y + k), cy);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(z + k), cz);
    const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    unsigned mask = static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(d2, rr)));
    if (size - k < 4) mask &= (1u << (size - k)) - 1;
    while (mask != 0) {
      const std::size_t j = k + std::size_t(__builtin_ctz(mask));
      mask &= mask - 1;
      if (!skipped(id[j], skip)) out[count++] = id[j];
    }
  }
#else
  for (std::size_t k = 0; k < size; ++k)
    if (dist2(x[k], y[k], z[k], c) <= r2 && !skipped(id[k], skip)) out[count++] = id[k];
#endif
  return count;
}

bool borderBase(const std::uint32_t* id, const float* x, const float* y, const float* z, std::size_t size,
                const float* c, float inner, float outer, const std::uint32_t* skip, std::uint32_t* out,
                std::size_t* count) {
  std::size_t n = 0;
  auto take = [&](std::size_t k, float d2) { // false: inside
    if (skipped(id[k], skip)) return true;
    if (d2 < inner) {
      out[0] = static_cast<std::uint32_t>(k);
      return false;
    }
    out[n++] = static_cast<std::uint32_t>(k);
    return true;
  };
#if defined(__SSE2__)
  const __m128 cx = _mm_set1_ps(c[0]), cy = _mm_set1_ps(c[1]), cz = _mm_set1_ps(c[2]), rr = _mm_set1_ps(outer);
  for (std::size_t k = 0; k < size; k += 4) {
    const __m128 dx = _mm_sub_ps(_mm_loadu_ps(x + k), cx);
    const __m128 dy = _mm_sub_ps(_mm_loadu_ps(y + k), cy);
    const __m128 dz = _mm_sub_ps(_mm_loadu_ps(z + k), cz);
    const __m128 d2 = _mm_add_ps(_mm_add_ps(_mm_mul_ps(dx, dx), _mm_mul_ps(dy, dy)), _mm_mul_ps(dz, dz));
    unsigned mask = static_cast<unsigned>(_mm_movemask_ps(_mm_cmple_ps(d2, rr)));
    if (mask == 0) continue;
    if (size - k < 4) mask &= (1u << (size - k)) - 1;
    alignas(16) float lane[4];
    _mm_store_ps(lane, d2);
    while (mask != 0) {
      const unsigned j = static_cast<unsigned>(__builtin_ctz(mask));
      mask &= mask - 1;
      if (!take(k + j, lane[j])) return true;
    }
  }
#else
  for (std::size_t k = 0; k < size; ++k) {
    const float d2 = dist2(x[k], y[k], z[k], c);
    if (d2 <= outer && !take(k, d2)) return true;
  }
#endif
  *count = n;
  return false;
}

constexpr Kernels kBase{appendBase, collectBase, borderBase};

#if defined(G2S_NEAR_X86)

// --- AVX2, eight lanes; lanes are compressed through a permutation table ---

// For each 8-bit mask, the positions of its set bits in increasing order, one per 4-bit field.
struct CompressTable {
  std::uint32_t entry[256];
  constexpr CompressTable() : entry() {
    for (unsigned m = 0; m < 256; ++m) {
      std::uint32_t e = 0;
      unsigned field = 0;
      for (unsigned j = 0; j < 8; ++j)
        if ((m >> j) & 1u) e |= std::uint32_t(j) << (4 * field++);
      entry[m] = e;
    }
  }
};
constexpr CompressTable kCompress;

__attribute__((target("avx2,popcnt"))) inline __m256i compressIndex(unsigned mask) {
  const __m256i shifts = _mm256_setr_epi32(0, 4, 8, 12, 16, 20, 24, 28);
  return _mm256_and_si256(_mm256_srlv_epi32(_mm256_set1_epi32(int(kCompress.entry[mask])), shifts),
                          _mm256_set1_epi32(7));
}

// Lanes 0..rem-1 (rem may exceed 8).
__attribute__((target("avx2,popcnt"))) inline unsigned validLanes8(std::size_t rem) {
  return (1u << std::min<std::size_t>(rem, 8)) - 1u; // min: a conditional move, not a branch
}

__attribute__((target("avx2,popcnt"))) inline __m256 dist2Avx2(__m256 x, __m256 y, __m256 z, __m256 cx, __m256 cy, __m256 cz) {
  const __m256 dx = _mm256_sub_ps(x, cx), dy = _mm256_sub_ps(y, cy), dz = _mm256_sub_ps(z, cz);
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(dx, dx), _mm256_mul_ps(dy, dy)), _mm256_mul_ps(dz, dz));
}

__attribute__((target("avx2,popcnt"))) std::size_t appendAvx2(const float* fx, const float* fy, const float* fz,
                                                             const std::uint32_t* ranges, std::size_t rangeCount,
                                                             const float* c, float r2, std::uint32_t* oid, float* ox,
                                                             float* oy, float* oz, std::size_t n) {
  const __m256 cx = _mm256_set1_ps(c[0]), cy = _mm256_set1_ps(c[1]), cz = _mm256_set1_ps(c[2]);
  const __m256 rr = _mm256_set1_ps(r2);
  const __m256i iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  for (std::size_t r = 0; r < rangeCount; ++r)
  for (std::uint32_t i = ranges[2 * r], end = ranges[2 * r + 1]; i < end; i += 8) {
    const __m256 x = _mm256_loadu_ps(fx + i), y = _mm256_loadu_ps(fy + i), z = _mm256_loadu_ps(fz + i);
    const unsigned mask =
        unsigned(_mm256_movemask_ps(_mm256_cmp_ps(dist2Avx2(x, y, z, cx, cy, cz), rr, _CMP_LE_OQ))) & validLanes8(end - i);
    const __m256i p = compressIndex(mask);
    _mm256_storeu_ps(ox + n, _mm256_permutevar8x32_ps(x, p));
    _mm256_storeu_ps(oy + n, _mm256_permutevar8x32_ps(y, p));
    _mm256_storeu_ps(oz + n, _mm256_permutevar8x32_ps(z, p));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(oid + n),
                        _mm256_permutevar8x32_epi32(_mm256_add_epi32(iota, _mm256_set1_epi32(int(i))), p));
    n += std::size_t(__builtin_popcount(mask));
  }
  return n;
}

// Lanes whose id is none of skip[0..2].
__attribute__((target("avx2,popcnt"))) inline unsigned keptLanes8(const std::uint32_t* id, __m256i s0, __m256i s1,
                                                                 __m256i s2) {
  const __m256i ids = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(id));
  const __m256i skip = _mm256_or_si256(_mm256_or_si256(_mm256_cmpeq_epi32(ids, s0), _mm256_cmpeq_epi32(ids, s1)),
                                       _mm256_cmpeq_epi32(ids, s2));
  return ~unsigned(_mm256_movemask_ps(_mm256_castsi256_ps(skip))) & 0xffu;
}

__attribute__((target("avx2,popcnt"))) std::size_t collectAvx2(const std::uint32_t* id, const float* x, const float* y,
                                                              const float* z, std::size_t size, const float* c, float r2,
                                                              const std::uint32_t* skip, std::uint32_t* out) {
  const __m256 cx = _mm256_set1_ps(c[0]), cy = _mm256_set1_ps(c[1]), cz = _mm256_set1_ps(c[2]);
  const __m256 rr = _mm256_set1_ps(r2);
  const __m256i s0 = _mm256_set1_epi32(int(skip[0])), s1 = _mm256_set1_epi32(int(skip[1])),
                s2 = _mm256_set1_epi32(int(skip[2]));
  std::size_t count = 0;
  for (std::size_t k = 0; k < size; k += 8) {
    const __m256 d2 = dist2Avx2(_mm256_loadu_ps(x + k), _mm256_loadu_ps(y + k), _mm256_loadu_ps(z + k), cx, cy, cz);
    const unsigned mask = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(d2, rr, _CMP_LE_OQ))) & validLanes8(size - k) &
                          keptLanes8(id + k, s0, s1, s2);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + count),
                        _mm256_permutevar8x32_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(id + k)),
                                                    compressIndex(mask)));
    count += std::size_t(__builtin_popcount(mask));
  }
  return count;
}

__attribute__((target("avx2,popcnt"))) bool borderAvx2(const std::uint32_t* id, const float* x, const float* y,
                                               const float* z, std::size_t size, const float* c, float inner,
                                               float outer, const std::uint32_t* skip, std::uint32_t* out,
                                               std::size_t* count) {
  const __m256 cx = _mm256_set1_ps(c[0]), cy = _mm256_set1_ps(c[1]), cz = _mm256_set1_ps(c[2]);
  const __m256 in = _mm256_set1_ps(inner), on = _mm256_set1_ps(outer);
  const __m256i s0 = _mm256_set1_epi32(int(skip[0])), s1 = _mm256_set1_epi32(int(skip[1])),
                s2 = _mm256_set1_epi32(int(skip[2]));
  const __m256i iota = _mm256_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7);
  std::size_t n = 0;
  for (std::size_t k = 0; k < size; k += 8) {
    const __m256 d2 = dist2Avx2(_mm256_loadu_ps(x + k), _mm256_loadu_ps(y + k), _mm256_loadu_ps(z + k), cx, cy, cz);
    const unsigned keep = keptLanes8(id + k, s0, s1, s2) & validLanes8(size - k);
    const unsigned inside = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(d2, in, _CMP_LT_OQ))) & keep;
    if (inside != 0) {
      out[0] = static_cast<std::uint32_t>(k + unsigned(__builtin_ctz(inside)));
      return true;
    }
    const unsigned near = unsigned(_mm256_movemask_ps(_mm256_cmp_ps(d2, on, _CMP_LE_OQ))) & keep;
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(out + n),
                        _mm256_permutevar8x32_epi32(_mm256_add_epi32(iota, _mm256_set1_epi32(int(k))), compressIndex(near)));
    n += std::size_t(__builtin_popcount(near));
  }
  *count = n;
  return false;
}

constexpr Kernels kAvx2{appendAvx2, collectAvx2, borderAvx2};

// --- AVX-512, sixteen lanes, compressed in registers ---

__attribute__((target("avx512f,popcnt"))) inline __mmask16 validLanes16(std::size_t rem) {
  return __mmask16((1u << std::min<std::size_t>(rem, 16)) - 1u);
}

__attribute__((target("avx512f,popcnt"))) inline __m512 dist2Avx512(__m512 x, __m512 y, __m512 z, __m512 cx, __m512 cy,
                                                            __m512 cz) {
  const __m512 dx = _mm512_sub_ps(x, cx), dy = _mm512_sub_ps(y, cy), dz = _mm512_sub_ps(z, cz);
  return _mm512_add_ps(_mm512_add_ps(_mm512_mul_ps(dx, dx), _mm512_mul_ps(dy, dy)), _mm512_mul_ps(dz, dz));
}

__attribute__((target("avx512f,popcnt"))) std::size_t appendAvx512(const float* fx, const float* fy, const float* fz,
                                                                  const std::uint32_t* ranges, std::size_t rangeCount,
                                                                  const float* c, float r2, std::uint32_t* oid,
                                                                  float* ox, float* oy, float* oz, std::size_t n) {
  const __m512 cx = _mm512_set1_ps(c[0]), cy = _mm512_set1_ps(c[1]), cz = _mm512_set1_ps(c[2]);
  const __m512 rr = _mm512_set1_ps(r2);
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  for (std::size_t r = 0; r < rangeCount; ++r)
  for (std::uint32_t i = ranges[2 * r], end = ranges[2 * r + 1]; i < end; i += 16) {
    const __m512 x = _mm512_loadu_ps(fx + i), y = _mm512_loadu_ps(fy + i), z = _mm512_loadu_ps(fz + i);
    const __mmask16 mask =
        _mm512_mask_cmp_ps_mask(validLanes16(end - i), dist2Avx512(x, y, z, cx, cy, cz), rr, _CMP_LE_OQ);
    _mm512_storeu_ps(ox + n, _mm512_maskz_compress_ps(mask, x));
    _mm512_storeu_ps(oy + n, _mm512_maskz_compress_ps(mask, y));
    _mm512_storeu_ps(oz + n, _mm512_maskz_compress_ps(mask, z));
    _mm512_storeu_si512(oid + n, _mm512_maskz_compress_epi32(mask, _mm512_add_epi32(iota, _mm512_set1_epi32(int(i)))));
    n += std::size_t(__builtin_popcount(unsigned(mask)));
  }
  return n;
}

// Lanes whose id is none of skip[0..2].
__attribute__((target("avx512f,popcnt"))) inline __mmask16 keptLanes16(const std::uint32_t* id, __m512i s0, __m512i s1,
                                                                      __m512i s2) {
  const __m512i ids = _mm512_loadu_si512(id);
  return __mmask16(~(_mm512_cmpeq_epi32_mask(ids, s0) | _mm512_cmpeq_epi32_mask(ids, s1) |
                     _mm512_cmpeq_epi32_mask(ids, s2)));
}

__attribute__((target("avx512f,popcnt"))) std::size_t collectAvx512(const std::uint32_t* id, const float* x,
                                                                   const float* y, const float* z, std::size_t size,
                                                                   const float* c, float r2, const std::uint32_t* skip,
                                                                   std::uint32_t* out) {
  const __m512 cx = _mm512_set1_ps(c[0]), cy = _mm512_set1_ps(c[1]), cz = _mm512_set1_ps(c[2]);
  const __m512 rr = _mm512_set1_ps(r2);
  const __m512i s0 = _mm512_set1_epi32(int(skip[0])), s1 = _mm512_set1_epi32(int(skip[1])),
                s2 = _mm512_set1_epi32(int(skip[2]));
  std::size_t count = 0;
  for (std::size_t k = 0; k < size; k += 16) {
    const __m512 d2 = dist2Avx512(_mm512_loadu_ps(x + k), _mm512_loadu_ps(y + k), _mm512_loadu_ps(z + k), cx, cy, cz);
    const __mmask16 mask =
        _mm512_mask_cmp_ps_mask(__mmask16(validLanes16(size - k) & keptLanes16(id + k, s0, s1, s2)), d2, rr, _CMP_LE_OQ);
    _mm512_storeu_si512(out + count, _mm512_maskz_compress_epi32(mask, _mm512_loadu_si512(id + k)));
    count += std::size_t(__builtin_popcount(unsigned(mask)));
  }
  return count;
}

__attribute__((target("avx512f,popcnt"))) bool borderAvx512(const std::uint32_t* id, const float* x, const float* y,
                                                    const float* z, std::size_t size, const float* c, float inner,
                                                    float outer, const std::uint32_t* skip, std::uint32_t* out,
                                                    std::size_t* count) {
  const __m512 cx = _mm512_set1_ps(c[0]), cy = _mm512_set1_ps(c[1]), cz = _mm512_set1_ps(c[2]);
  const __m512 in = _mm512_set1_ps(inner), on = _mm512_set1_ps(outer);
  const __m512i s0 = _mm512_set1_epi32(int(skip[0])), s1 = _mm512_set1_epi32(int(skip[1])),
                s2 = _mm512_set1_epi32(int(skip[2]));
  const __m512i iota = _mm512_setr_epi32(0, 1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 14, 15);
  std::size_t n = 0;
  for (std::size_t k = 0; k < size; k += 16) {
    const __m512 d2 = dist2Avx512(_mm512_loadu_ps(x + k), _mm512_loadu_ps(y + k), _mm512_loadu_ps(z + k), cx, cy, cz);
    const __mmask16 keep = __mmask16(validLanes16(size - k) & keptLanes16(id + k, s0, s1, s2));
    if (const __mmask16 inside = _mm512_mask_cmp_ps_mask(keep, d2, in, _CMP_LT_OQ)) {
      out[0] = static_cast<std::uint32_t>(k + unsigned(__builtin_ctz(unsigned(inside))));
      return true;
    }
    const __mmask16 near = _mm512_mask_cmp_ps_mask(keep, d2, on, _CMP_LE_OQ);
    _mm512_storeu_si512(out + n, _mm512_maskz_compress_epi32(near, _mm512_add_epi32(iota, _mm512_set1_epi32(int(k)))));
    n += std::size_t(__builtin_popcount(unsigned(near)));
  }
  *count = n;
  return false;
}

constexpr Kernels kAvx512{appendAvx512, collectAvx512, borderAvx512};

#endif // G2S_NEAR_X86

SimdLevel detectBest() {
#if defined(G2S_NEAR_X86)
  __builtin_cpu_init();
  if (!__builtin_cpu_supports("popcnt")) return SimdLevel::kSse2;
  if (__builtin_cpu_supports("avx512f")) return SimdLevel::kAvx512;
  if (__builtin_cpu_supports("avx2")) return SimdLevel::kAvx2;
#endif
  return SimdLevel::kSse2;
}

const Kernels* kernelsOf(SimdLevel level) {
#if defined(G2S_NEAR_X86)
  if (level == SimdLevel::kAvx512) return &kAvx512;
  if (level == SimdLevel::kAvx2) return &kAvx2;
#endif
  (void)level;
  return &kBase;
}

SimdLevel initialLevel() {
  SimdLevel level = detectBest();
  if (const char* env = std::getenv("G2S_SIMD")) {
    SimdLevel wanted = level;
    if (std::strcmp(env, "sse2") == 0) wanted = SimdLevel::kSse2;
    else if (std::strcmp(env, "avx2") == 0) wanted = SimdLevel::kAvx2;
    else if (std::strcmp(env, "avx512") == 0) wanted = SimdLevel::kAvx512;
    if (int(wanted) < int(level)) level = wanted;
  }
  return level;
}

// Constant-initialised to the portable kernels (so a search during static initialisation is still
// right), then switched to the best ones.
SimdLevel gLevel = SimdLevel::kSse2;
const Kernels* gKernels = &kBase;
[[maybe_unused]] const bool gChosen = [] {
  gLevel = initialLevel();
  gKernels = kernelsOf(gLevel);
  return true;
}();

} // namespace

SimdLevel bestSimdLevel() {
  static const SimdLevel best = detectBest();
  return best;
}

SimdLevel simdLevel() { return gLevel; }

void setSimdLevel(SimdLevel level) {
  if (int(level) > int(bestSimdLevel())) level = bestSimdLevel();
  gLevel = level;
  gKernels = kernelsOf(level);
}

const char* simdLevelName(SimdLevel level) {
  switch (level) {
  case SimdLevel::kAvx512: return "avx512";
  case SimdLevel::kAvx2: return "avx2";
  default: return "sse2";
  }
}

void NearList::appendWithin(const float* fx, const float* fy, const float* fz, const std::uint32_t* ranges,
                            std::size_t rangeCount, std::size_t points, const float* c, float r2) {
  reserve(size + points);
  size = gKernels->append(fx, fy, fz, ranges, rangeCount, c, r2, id.data(), x.data(), y.data(), z.data(), size);
}

std::size_t NearList::collectWithin(const float* c, float r2, const std::uint32_t* skip, std::uint32_t* out) const {
  return gKernels->collect(id.data(), x.data(), y.data(), z.data(), size, c, r2, skip, out);
}

bool NearList::insideOrBorderline(const float* c, float inner, float outer, const std::uint32_t* skip,
                                  std::uint32_t* out, std::size_t* count) const {
  return gKernels->border(id.data(), x.data(), y.data(), z.data(), size, c, inner, outer, skip, out, count);
}

} // namespace g2s
} // namespace growth
