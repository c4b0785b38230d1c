// The vector scans of Robust G2S's searches (g2s_near.h): every implementation this processor
// runs passes exactly the points a plain float loop passes, in the same order, and the mesher
// builds the same mesh with each of them.
#include "g2s_grid.h"
#include "g2s_mesher.h"
#include "g2s_near.h"

#include <growth/cloud_generator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <vector>

using namespace growth::g2s;

namespace {

std::vector<SimdLevel> levels() {
  std::vector<SimdLevel> all;
  for (int l = 0; l <= int(bestSimdLevel()); ++l) all.push_back(SimdLevel(l));
  return all;
}

// Restores the level chosen at start-up when a test ends.
struct LevelGuard {
  SimdLevel saved = simdLevel();
  ~LevelGuard() { setSimdLevel(saved); }
};

float dist2(float x, float y, float z, const float* c) {
  const float dx = x - c[0], dy = y - c[1], dz = z - c[2];
  return (dx * dx + dy * dy) + dz * dz;
}

// Coordinates in [0, 1) with kNearPad entries of padding, as the grid stores them.
struct Cloud {
  std::vector<float> x, y, z;
  explicit Cloud(size_t n, unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (size_t i = 0; i < n; ++i) {
      x.push_back(u(rng));
      y.push_back(u(rng));
      z.push_back(u(rng));
    }
    for (size_t i = 0; i < kNearPad; ++i) {
      x.push_back(0.5f); // inside every test ball: padding must never be taken
      y.push_back(0.5f);
      z.push_back(0.5f);
    }
  }
};

} // namespace

TEST(G2SNear, TheLevelCanBeLoweredButNotRaisedAboveTheProcessors) {
  LevelGuard guard;
  setSimdLevel(SimdLevel::kSse2);
  EXPECT_EQ(simdLevel(), SimdLevel::kSse2);
  setSimdLevel(SimdLevel::kAvx512);
  EXPECT_EQ(simdLevel(), bestSimdLevel());
  EXPECT_STREQ(simdLevelName(SimdLevel::kAvx2), "avx2");
}

TEST(G2SNear, AppendWithinPassesWhatAPlainLoopPasses) {
  LevelGuard guard;
  const Cloud cloud(200, 1);
  const float c[3] = {0.5f, 0.5f, 0.5f};
  const float r2 = 0.12f;
  // Every range length from 0 to 40 at several offsets: whole vectors, partial ones, empty ranges.
  for (SimdLevel level : levels()) {
    setSimdLevel(level);
    for (std::uint32_t begin = 0; begin < 23; begin += 7)
      for (std::uint32_t len = 0; len <= 40; ++len) {
        NearList near;
        near.appendWithin(cloud.x.data(), cloud.y.data(), cloud.z.data(), begin, begin + len, c, r2);
        // Appending a second range continues the list.
        near.appendWithin(cloud.x.data(), cloud.y.data(), cloud.z.data(), 150, 150 + len, c, r2);
        std::vector<std::uint32_t> want;
        for (std::uint32_t k = begin; k < begin + len; ++k)
          if (dist2(cloud.x[k], cloud.y[k], cloud.z[k], c) <= r2) want.push_back(k);
        for (std::uint32_t k = 150; k < 150 + len; ++k)
          if (dist2(cloud.x[k], cloud.y[k], cloud.z[k], c) <= r2) want.push_back(k);
        ASSERT_EQ(near.size, want.size()) << simdLevelName(level) << " begin " << begin << " len " << len;
        for (size_t i = 0; i < want.size(); ++i) {
          ASSERT_EQ(near.id[i], want[i]) << simdLevelName(level);
          EXPECT_EQ(near.x[i], cloud.x[want[i]]);
          EXPECT_EQ(near.y[i], cloud.y[want[i]]);
          EXPECT_EQ(near.z[i], cloud.z[want[i]]);
        }
      }
  }
}

TEST(G2SNear, CollectWithinAndTheEmptinessScanAgreeWithAPlainLoop) {
  LevelGuard guard;
  const Cloud cloud(120, 2);
  for (SimdLevel level : levels()) {
    setSimdLevel(level);
    for (std::uint32_t len = 0; len <= 40; ++len) {
      NearList near;
      near.appendWithin(cloud.x.data(), cloud.y.data(), cloud.z.data(), 0, len, std::vector<float>{0, 0, 0}.data(), 10.f);
      ASSERT_EQ(near.size, len); // all taken
      const float c[3] = {0.4f, 0.6f, 0.5f};
      std::vector<std::uint32_t> out(near.size + kNearPad);
      const std::uint32_t skipNone[3] = {~0u, ~0u, ~0u}, skipSome[3] = {2, 3, 17};
      std::vector<std::uint32_t> want;
      for (std::uint32_t k = 0; k < len; ++k)
        if (dist2(near.x[k], near.y[k], near.z[k], c) <= 0.1f) want.push_back(k);
      size_t hits = near.collectWithin(c, 0.1f, skipNone, out.data());
      ASSERT_EQ(hits, want.size()) << simdLevelName(level);
      for (size_t i = 0; i < hits; ++i) EXPECT_EQ(out[i], want[i]);
      // Skipped ids are left out (ids are the positions here: all points were appended in order).
      want.erase(std::remove_if(want.begin(), want.end(), [](std::uint32_t k) { return k == 2 || k == 3 || k == 17; }),
                 want.end());
      hits = near.collectWithin(c, 0.1f, skipSome, out.data());
      ASSERT_EQ(hits, want.size()) << simdLevelName(level);
      for (size_t i = 0; i < hits; ++i) EXPECT_EQ(out[i], want[i]);

      // Emptiness: skipped ids are ignored; a point below `inner` answers at once, its position in
      // out[0]; the points between inner and outer are listed for the exact test.
      for (float inner : {0.f, 0.01f, 0.05f}) {
        const float outer = 0.08f;
        const std::uint32_t skip[3] = {1, 5, 9};
        size_t count = 99;
        const bool inside = near.insideOrBorderline(c, inner, outer, skip, out.data(), &count);
        bool wantInside = false;
        std::vector<std::uint32_t> border;
        for (std::uint32_t k = 0; k < len; ++k) {
          if (k == 1 || k == 5 || k == 9) continue;
          const float d2 = dist2(near.x[k], near.y[k], near.z[k], c);
          if (d2 < inner) wantInside = true;
          else if (d2 <= outer) border.push_back(k);
        }
        ASSERT_EQ(inside, wantInside) << simdLevelName(level) << " len " << len << " inner " << inner;
        if (inside) {
          ASSERT_LT(out[0], len);
          EXPECT_TRUE(out[0] != 1 && out[0] != 5 && out[0] != 9) << out[0];
          EXPECT_LT(dist2(near.x[out[0]], near.y[out[0]], near.z[out[0]], c), inner) << simdLevelName(level);
          continue;
        }
        ASSERT_EQ(count, border.size());
        for (size_t i = 0; i < count; ++i) EXPECT_EQ(out[i], border[i]);
      }
    }
  }
}

TEST(G2SNear, GatherNearVisitsWhatForEachNearBallVisits) {
  LevelGuard guard;
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 4000;
  MortonGrid g;
  g.build(growth::generateCloud(spec).points, 0.08);
  for (SimdLevel level : levels()) {
    setSimdLevel(level);
    NearList near;
    for (std::uint32_t i = 0; i < g.size(); i += 97)
      for (double r : {0.0, 0.03, 0.1, 0.4}) {
        std::vector<std::uint32_t> want;
        g.forEachNearBall(g.point(i), r, [&](std::uint32_t k) { want.push_back(k); });
        g.gatherNear(g.point(i), r, near);
        ASSERT_EQ(near.size, want.size()) << simdLevelName(level);
        for (size_t k = 0; k < want.size(); ++k) {
          ASSERT_EQ(near.id[k], want[k]);
          EXPECT_EQ(near.x[k], g.fx(want[k]));
          EXPECT_EQ(near.z[k], g.fz(want[k]));
        }
      }
  }
}

TEST(G2SNear, TheMeshDoesNotDependOnTheVectorScans) {
  LevelGuard guard;
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Sphere;
  spec.count = 6000;
  spec.gaussianSigma = 0.004; // noisy: many G2S tests, larger search levels and grid fallbacks
  const std::vector<P3> pts = growth::generateCloud(spec).points;
  Params p;
  p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
  std::vector<growth::Triangle> first;
  for (SimdLevel level : levels()) {
    setSimdLevel(level);
    Mesher m(pts, p);
    m.meshAll();
    ASSERT_GT(m.triangles().size(), 2 * pts.size() / 3);
    if (first.empty()) first = m.triangles();
    else EXPECT_EQ(m.triangles(), first) << simdLevelName(level);
  }
}
