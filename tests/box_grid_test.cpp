// Box grid of the sphere packer (sec. 4.1): hash of occupied boxes of side d referring to the
// points within distance d, the 0.1 normal filter, box normals over a fixed sphere sampling and
// the "d too large" boxes.
#include "box_grid.h"
#include <growth/cloud_generator.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>

using growth::BoxGrid;
using growth::SphereSampling;
using Point3d = growth::Vec3d;

namespace {
std::vector<std::uint32_t> iota(size_t n) {
  std::vector<std::uint32_t> v(n);
  for (size_t i = 0; i < n; ++i) v[i] = std::uint32_t(i);
  return v;
}
} // namespace

TEST(KeyHash, InsertFindGrow) {
  growth::KeyHash h(2);
  for (std::uint64_t k = 0; k < 5000; ++k) EXPECT_EQ(h.findOrInsert(k * 7919 + 3, int(k)), int(k));
  EXPECT_EQ(h.size(), 5000u);
  for (std::uint64_t k = 0; k < 5000; ++k) EXPECT_EQ(h.find(k * 7919 + 3), int(k));
  EXPECT_EQ(h.find(1), -1);
  EXPECT_EQ(h.findOrInsert(3, 99), 0); // existing key keeps its value
  h.set(3, 42);
  EXPECT_EQ(h.find(3), 42);
}

TEST(SphereSampling, DirectionsAreUnitAndSpread) {
  SphereSampling s(3);
  EXPECT_EQ(s.size(), 6u * 64u);
  double worst = 1;
  for (size_t i = 0; i < s.size(); ++i) {
    EXPECT_NEAR(s.direction(i).Norm(), 1.0, 1e-12);
  }
  // Every direction of a fine probe set has a sample within ~12° (cube map of 8x8 per face).
  growth::Random rnd(3);
  for (int k = 0; k < 500; ++k) {
    const Point3d u = rnd.unitVector();
    double best = -1;
    for (size_t i = 0; i < s.size(); ++i) best = std::max(best, u * s.direction(i));
    worst = std::min(worst, best);
  }
  EXPECT_GT(worst, std::cos(12.0 * M_PI / 180.0));
}

TEST(SphereSampling, BranchAndBoundIsExactOverTheSampling) {
  SphereSampling s(4);
  growth::Random rnd(11);
  for (int trial = 0; trial < 60; ++trial) {
    // Normals in a cone of random axis and aperture (up to beyond a hemisphere).
    const Point3d axis = rnd.unitVector();
    const double aperture = rnd.uniform(0.0, 2.2);
    std::vector<Point3d> normals;
    const int n = 1 + int(rnd.uniform(0, 40));
    while (int(normals.size()) < n) {
      const Point3d u = rnd.unitVector();
      if (std::acos(std::max(-1.0, std::min(1.0, u * axis))) <= aperture) normals.push_back(u);
    }
    const auto idx = iota(normals.size());
    double fast = 0, slow = 0;
    const Point3d a = s.maxMinDirection(normals, idx.data(), idx.size(), &fast);
    s.maxMinDirectionBruteForce(normals, idx.data(), idx.size(), &slow);
    EXPECT_NEAR(fast, slow, 1e-12) << "trial " << trial;
    double check = 2;
    for (const auto& m : normals) check = std::min(check, m * a);
    EXPECT_NEAR(check, fast, 1e-12);
  }
}

TEST(SphereSampling, OneNormalGivesItsNearestSample) {
  SphereSampling s(6);
  const std::vector<Point3d> normals{Point3d(0.3, -0.2, 0.9).Normalize()};
  const auto idx = iota(1);
  double m = 0;
  const Point3d a = s.maxMinDirection(normals, idx.data(), 1, &m);
  EXPECT_GT(m, std::cos(1.5 * M_PI / 180.0)); // level 6: samples about 1.4° apart
  EXPECT_NEAR(a * normals[0], m, 1e-12);
}

TEST(SphereSampling, OpposingNormalsHaveNoPositiveDirection) {
  SphereSampling s(5);
  const std::vector<Point3d> normals{Point3d(0, 0, 1), Point3d(0, 0, -1), Point3d(1, 0, 0)};
  const auto idx = iota(3);
  double m = 1;
  s.maxMinDirection(normals, idx.data(), 3, &m);
  EXPECT_LE(m, 0.0);
  EXPECT_GT(m, -0.05); // the best direction is (about) orthogonal to both z normals
}

TEST(BoxNormalFilter, SmallSumKeepsAllLargeSumDropsOpposed) {
  // Sum of the normals shorter than 0.1: all kept, even the opposed ones.
  std::vector<Point3d> n{Point3d(0, 0, 1), Point3d(0, 0, -1), Point3d(1, 0, 0), Point3d(-1, 0, 0)};
  auto idx = iota(n.size());
  EXPECT_EQ(growth::filterBoxNormals(n, idx.data(), idx.size()), 4u);
  n.push_back(Point3d(0.6, 0.8, 0)); // sum (0.6, 0.8, 0): length 1 >= 0.1
  idx = iota(n.size());
  const size_t kept = growth::filterBoxNormals(n, idx.data(), idx.size());
  // <(-1,0,0), sum> = -0.6 < 0 is dropped; the z normals (product 0) stay; order kept.
  ASSERT_EQ(kept, 4u);
  EXPECT_EQ(std::vector<std::uint32_t>(idx.begin(), idx.begin() + 4), (std::vector<std::uint32_t>{0, 1, 2, 4}));
  // Just below / at the threshold.
  std::vector<Point3d> m{Point3d(0, 0, 1), Point3d(0, 0.0995, -0.995).Normalize()};
  idx = iota(2);
  EXPECT_LT((m[0] + m[1]).Norm(), 0.1);
  EXPECT_EQ(growth::filterBoxNormals(m, idx.data(), 2), 2u);
}

TEST(BoxGrid, BoxesReferToExactlyThePointsWithinD) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 4000;
  spec.seed = 5;
  const auto c = growth::generateCloud(spec);
  const double d = 0.23;
  BoxGrid g;
  g.build(c.points, c.normals, d);
  EXPECT_EQ(g.dTooLargeCount(), 0u);
  EXPECT_EQ(g.droppedByFilter(), 0u);
  // Every point is referred to by about 20.6 boxes on average (volume of a box grown by d).
  EXPECT_NEAR(double(g.references()) / double(c.points.size()), 1 + 6 + 3 * M_PI + 4 * M_PI / 3, 1.0);

  growth::Random rnd(9);
  for (int q = 0; q < 300; ++q) {
    const Point3d x(rnd.uniform(-3.3, 3.3), rnd.uniform(-3.3, 3.3), rnd.uniform(-1.3, 1.3));
    growth::KeyHash::Key key;
    ASSERT_TRUE(g.indexer().keyOf(x, key));
    const auto& ix = g.indexer();
    const Point3d lo = ix.corner(ix.coord(x[0], 0), ix.coord(x[1], 1), ix.coord(x[2], 2));
    std::vector<std::uint32_t> expect;
    for (size_t i = 0; i < c.points.size(); ++i)
      if (growth::squaredDistanceToBox(c.points[i], lo, d) <= d * d) expect.push_back(std::uint32_t(i));
    const int box = g.boxOf(x);
    if (expect.empty()) {
      EXPECT_EQ(box, -1);
      continue;
    }
    ASSERT_GE(box, 0);
    const std::vector<std::uint32_t> got(g.pointsBegin(box), g.pointsEnd(box));
    EXPECT_EQ(got, expect);
    // Box normals agree with the torus normals of their points.
    for (auto i : got) EXPECT_GT(c.normals[i] * g.boxNormal(box), 0.0);
  }
}

// Points exactly on box faces (a lattice of step d from the origin of the boxes): rounding can
// put a box two steps away in reach; those points take build()'s general path. Every box refers
// to the points whose reach test (per axis: the boxes from coord(p − d) to coord(p + d), squared
// slab distances summed x, y, z, at most d²) accepts it, in index order, for any number of
// threads. (Not quite brute force: a box at distance exactly d can fall outside that range by
// rounding, as it always could.)
TEST(BoxGrid, PointsOnBoxFacesAreReferredToExactly) {
  const double d = 0.3;
  std::vector<Point3d> pts, nrm;
  growth::Random rnd(14);
  for (int i = 0; i < 40; ++i)
    for (int j = 0; j < 40; ++j) {
      pts.emplace_back(i * d, j * d, 0.0);
      nrm.emplace_back(0, 0, 1);
      pts.emplace_back(rnd.uniform(0, 39 * d), rnd.uniform(0, 39 * d), rnd.uniform(-0.01, 0.01));
      nrm.emplace_back(0, 0, 1);
    }
  BoxGrid one, two;
  one.build(pts, nrm, d, nullptr, 1);
  two.build(pts, nrm, d, nullptr, 2);
  EXPECT_GT(one.pointsAtBoxFaces(), 0u);
  EXPECT_EQ(two.pointsAtBoxFaces(), one.pointsAtBoxFaces());
  ASSERT_EQ(two.boxCount(), one.boxCount());
  const auto& ix = one.indexer();
  std::map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>> expect;
  for (size_t i = 0; i < pts.size(); ++i) {
    const Point3d& p = pts[i];
    std::int64_t lo[3], hi[3];
    double sq[3][8];
    for (int a = 0; a < 3; ++a) {
      lo[a] = ix.coord(p[a] - d, a);
      hi[a] = std::min(ix.coord(p[a] + d, a), lo[a] + 7);
      for (std::int64_t c = lo[a]; c <= hi[a]; ++c) {
        const double l = ix.origin()[a] + double(c) * d;
        const double v = p[a] < l ? l - p[a] : (p[a] > l + d ? p[a] - l - d : 0.0);
        sq[a][c - lo[a]] = v * v;
      }
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          if (!(sq[0][x - lo[0]] + sq[1][y - lo[1]] + sq[2][z - lo[2]] > d * d))
            expect[{x, y, z}].push_back(std::uint32_t(i));
  }
  ASSERT_EQ(one.boxCount(), expect.size());
  for (const auto& e : expect) {
    const Point3d centre = ix.corner(e.first[0], e.first[1], e.first[2]) + Point3d(0.5 * d, 0.5 * d, 0.5 * d);
    for (const BoxGrid* g : {&one, &two}) {
      const int box = g->boxOf(centre);
      ASSERT_GE(box, 0);
      ASSERT_EQ(std::vector<std::uint32_t>(g->pointsBegin(box), g->pointsEnd(box)), e.second);
    }
  }
}

// Splats larger than d (BoxGrid::build's extraReach): such a point is referred to by every box
// within side + its extra reach, the others by the boxes within side, checked against a brute
// force over the boxes around every point (the normal filter drops nothing: one normal for all).
TEST(BoxGrid, LargeSplatsReachFartherBoxes) {
  growth::Random rnd(9);
  std::vector<Point3d> pts, nrm;
  std::vector<float> extra;
  for (int i = 0; i < 3000; ++i) {
    pts.emplace_back(rnd.uniform(0, 2), rnd.uniform(0, 2), 0.05 * rnd.uniform(-1, 1));
    nrm.emplace_back(0, 0, 1);
    extra.push_back(i % 5 == 0 ? float(rnd.uniform(0, 0.5)) : 0.0f);
  }
  extra[7] = 100.0f; // capped at kMaxExtraReach · side
  const double d = 0.1;
  BoxGrid plain, wide;
  plain.build(pts, nrm, d, nullptr, 1);
  wide.build(pts, nrm, d, nullptr, 2, false, nullptr, &extra);
  EXPECT_GT(wide.references(), plain.references());
  const auto& ix = wide.indexer();
  std::map<std::array<std::int64_t, 3>, std::vector<std::uint32_t>> expect;
  for (size_t i = 0; i < pts.size(); ++i) {
    const double reach = d + std::min(double(extra[i]), BoxGrid::kMaxExtraReach * d);
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) lo[a] = ix.coord(pts[i][a] - reach, a), hi[a] = ix.coord(pts[i][a] + reach, a);
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          if (growth::squaredDistanceToBox(pts[i], ix.corner(x, y, z), d) <= reach * reach * (1 - 1e-12))
            expect[{x, y, z}].push_back(std::uint32_t(i));
  }
  size_t checked = 0;
  for (const auto& e : expect) {
    const int box = wide.boxOf(ix.corner(e.first[0], e.first[1], e.first[2]) + Point3d(0.5 * d, 0.5 * d, 0.5 * d));
    ASSERT_GE(box, 0);
    const std::vector<std::uint32_t> got(wide.pointsBegin(box), wide.pointsEnd(box));
    // Every point the brute force finds (up to rounding at the reach) is listed, in index order.
    for (std::uint32_t i : e.second) EXPECT_TRUE(std::binary_search(got.begin(), got.end(), i)) << i;
    EXPECT_TRUE(std::is_sorted(got.begin(), got.end()));
    ++checked;
  }
  EXPECT_GT(checked, 400u);
  // The capped point reaches 7 boxes away, not farther.
  const int far = wide.boxOf(Point3d(pts[7][0] + 8.5 * d, pts[7][1], pts[7][2]));
  if (far >= 0) {
    const std::vector<std::uint32_t> got(wide.pointsBegin(far), wide.pointsEnd(far));
    EXPECT_FALSE(std::binary_search(got.begin(), got.end(), 7u));
  }
}

// Sec. 4.1 before the filter: a thin plate whose sides hold 2:1 points (its normals then sum to
// the denser side, and the filter alone would hide the other) is flagged where d sees both sides,
// not where d is below the plate's thickness.
TEST(BoxGrid, ThinPlateWithTwoToOneSidesIsFlagged) {
  std::vector<Point3d> p, n;
  growth::Random rnd(4);
  for (int i = 0; i < 6000; ++i) {
    const bool top = i % 3 != 0;
    p.emplace_back(rnd.uniform(0, 1), rnd.uniform(0, 1), top ? 0.02 : -0.02);
    n.emplace_back(0, 0, top ? 1 : -1);
  }
  BoxGrid coarse, fine;
  coarse.build(p, n, 0.1);
  fine.build(p, n, 0.01);
  EXPECT_GT(coarse.dTooLargeCount(), coarse.boxCount() / 2);
  EXPECT_EQ(fine.dTooLargeCount(), 0u);
}

// Two-sided boxes (beyond the paper, where its filter drops the smaller side): a box that sees
// both sheets of a thin plate keeps both, as two layers; boxOf() with a normal gives the layer of
// that side, whose points all face it and whose box normal is positive on all of them. The same
// when the sides hold equal shares and the normals cancel (|Σ n| < 0.1: split along their axis).
TEST(BoxGrid, ThinPlateBoxesKeepBothSidesAsLayers) {
  for (const bool equal : {false, true}) {
    SCOPED_TRACE(equal ? "sides of equal size" : "sides 2:1");
    std::vector<Point3d> p, n;
    growth::Random rnd(4);
    if (equal) {
      for (int i = 0; i < 20; ++i)
        for (int j = 0; j < 20; ++j)
          for (const int s : {1, -1}) {
            p.emplace_back(i * 0.02 + 0.001, j * 0.02 + 0.001, s * 0.01);
            n.emplace_back(0, 0, s);
          }
    } else {
      for (int i = 0; i < 6000; ++i) {
        const bool top = i % 3 != 0;
        p.emplace_back(rnd.uniform(0, 1), rnd.uniform(0, 1), top ? 0.02 : -0.02);
        n.emplace_back(0, 0, top ? 1 : -1);
      }
    }
    BoxGrid g;
    g.build(p, n, 0.1);
    EXPECT_GT(g.twoSidedBoxes(), g.boxCount() / 2);
    EXPECT_EQ(g.layerCount(), g.boxCount() + g.twoSidedBoxes());
    size_t checked = 0;
    for (const size_t i : {size_t(0), size_t(1), p.size() / 2, p.size() - 1}) {
      for (const double side : {1.0, -1.0}) {
        const int b = g.boxOf(p[i], Point3d(0, 0, side));
        ASSERT_GE(b, 0);
        ASSERT_GT(g.pointCount(b), 0u);
        for (auto it = g.pointsBegin(b); it != g.pointsEnd(b); ++it) EXPECT_EQ(n[*it][2], side);
        EXPECT_GT(g.boxNormal(b)[2] * side, 0.99);
        EXPECT_GT(g.boxMinDot(b), 0.99);
        ++checked;
      }
      // The layers of one box are two: the other side's layer is not the same box.
      EXPECT_NE(g.boxOf(p[i], Point3d(0, 0, 1)), g.boxOf(p[i], Point3d(0, 0, -1)));
    }
    EXPECT_EQ(checked, 8u);
    // Boxes that see one sheet only (d below the thickness) have one layer.
    BoxGrid fine;
    fine.build(p, n, equal ? 0.005 : 0.01);
    EXPECT_EQ(fine.twoSidedBoxes(), 0u);
  }
}

TEST(BoxGrid, FilterDropsFlippedNormalsOnAPlane) {
  std::vector<Point3d> p, n;
  growth::Random rnd(2);
  for (int i = 0; i < 2000; ++i) {
    p.emplace_back(rnd.uniform(0, 1), rnd.uniform(0, 1), 0);
    n.push_back(i % 17 == 0 ? Point3d(0, 0, -1) : Point3d(0, 0, 1));
  }
  BoxGrid g;
  g.build(p, n, 0.1);
  EXPECT_GT(g.droppedByFilter(), 0u);
  EXPECT_EQ(g.dTooLargeCount(), 0u);
  for (int b = 0; b < int(g.boxCount()); ++b) {
    for (auto it = g.pointsBegin(b); it != g.pointsEnd(b); ++it) EXPECT_EQ(n[*it][2], 1.0);
    EXPECT_GT(g.boxNormal(b)[2], std::cos(1.5 * M_PI / 180));
  }
}

TEST(BoxGrid, ThinPlateWithLargeDIsFlaggedTooLarge) {
  // Two sheets 0.02 apart with opposite normals: with d = 0.1 boxes see both sheets, the sums
  // cancel (< 0.1 in most boxes), nothing is filtered and no direction is positive for all.
  std::vector<Point3d> p, n;
  for (int i = 0; i < 20; ++i)
    for (int j = 0; j < 20; ++j) {
      p.emplace_back(i * 0.02, j * 0.02, 0.01);
      n.emplace_back(0, 0, 1);
      p.emplace_back(i * 0.02, j * 0.02, -0.01);
      n.emplace_back(0, 0, -1);
    }
  BoxGrid g;
  g.build(p, n, 0.1);
  EXPECT_GT(g.dTooLargeCount(), 0u);
  // With d smaller than the gap, no box sees both sheets.
  BoxGrid fine;
  fine.build(p, n, 0.009);
  EXPECT_EQ(fine.dTooLargeCount(), 0u);
}

TEST(BoxGrid, MemoryFollowsThePointsNotTheBoundingBox) {
  std::vector<Point3d> p, n;
  for (int i = 0; i < 50; ++i) {
    p.emplace_back(0.001 * i, 0, 0);
    n.emplace_back(0, 0, 1);
    p.emplace_back(1000.0 + 0.001 * i, 500.0, -700.0);
    n.emplace_back(0, 0, 1);
  }
  BoxGrid g;
  g.build(p, n, 0.01);
  // A dense grid would need 10^15 boxes; the hash holds only boxes near the two clusters.
  EXPECT_LT(g.boxCount(), 2u * 27u * 10u);
  EXPECT_LT(g.memoryBytes(), 200000u);
  EXPECT_EQ(g.boxOf(Point3d(500, 250, -350)), -1);
  EXPECT_GE(g.boxOf(p[1]), 0);
}

TEST(BoxGrid, EmptyInputGivesNoBoxes) {
  BoxGrid g;
  g.build({}, {}, 0.1);
  EXPECT_EQ(g.boxCount(), 0u);
  EXPECT_EQ(g.boxOf(Point3d(0, 0, 0)), -1);
}

// The filter and the box normals run on several threads: the grid is the same, bit for bit, for
// any number of them (noisy normals so that the filter drops points and some boxes are flagged).
// Also: the box normals are those of the sampling whether computed by build() or on first use.
TEST(BoxGrid, SameGridForAnyNumberOfThreads) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 20000;
  spec.seed = 4;
  auto c = growth::generateCloud(spec);
  growth::Random rnd(5);
  for (size_t i = 0; i < c.normals.size(); i += 13) c.normals[i] = rnd.unitVector();
  // A thin two-sided plate above the torus: its boxes are flagged as "d too large".
  for (int k = 0; k < 1000; ++k) {
    const double x = rnd.uniform(-1, 1), y = rnd.uniform(-1, 1);
    for (double side : {1.0, -1.0}) {
      c.points.emplace_back(x, y, 3 + 0.01 * side);
      c.normals.emplace_back(0, 0, side);
    }
  }
  const double d = 0.45;
  BoxGrid one;
  one.build(c.points, c.normals, d, nullptr, 1);
  ASSERT_GT(one.boxCount(), 3 * 256u); // enough for 3 parts (parallelParts: 256 boxes at least per part)
  EXPECT_GT(one.droppedByFilter(), 0u);
  EXPECT_GT(one.dTooLargeCount(), 0u);
  // Box normals (computed by build() or on first use): those of the sampling on the box's points;
  // the flagged boxes are those with a negative minimum and those where the filter dropped a
  // share of the points (the plate's).
  {
    BoxGrid g;
    g.build(c.points, c.normals, d, nullptr, 1);
    const SphereSampling sampling(6);
    size_t flagged = 0;
    for (int b = 0; b < int(g.boxCount()); ++b) {
      double minDot = 0;
      const Point3d n = sampling.maxMinDirection(c.normals, g.pointsBegin(b), g.pointCount(b), &minDot);
      ASSERT_EQ(g.boxNormal(b), n);
      ASSERT_EQ(g.boxMinDot(b), double(float(minDot))); // kept as a float
      if (minDot < 0) {
        EXPECT_TRUE(g.dTooLarge(b));
      }
      flagged += g.dTooLarge(b) ? 1 : 0;
    }
    EXPECT_EQ(g.dTooLargeCount(), flagged);
  }
  for (int threads : {2, 3}) {
    BoxGrid g;
    g.build(c.points, c.normals, d, nullptr, threads);
    ASSERT_EQ(g.boxCount(), one.boxCount());
    EXPECT_EQ(g.references(), one.references());
    EXPECT_EQ(g.droppedByFilter(), one.droppedByFilter());
    EXPECT_EQ(g.dTooLargeCount(), one.dTooLargeCount());
    for (int b = 0; b < int(g.boxCount()); ++b) {
      ASSERT_EQ(std::vector<std::uint32_t>(g.pointsBegin(b), g.pointsEnd(b)),
                std::vector<std::uint32_t>(one.pointsBegin(b), one.pointsEnd(b)));
      ASSERT_EQ(g.boxNormal(b), one.boxNormal(b));
      ASSERT_EQ(g.boxMinDot(b), one.boxMinDot(b));
    }
  }
}

// Deferred box normals, computed on another thread while this one asks for them in another order
// (or with one thread: on first use and in finishNormals()), are those build() computes.
TEST(BoxGrid, DeferredNormalsAreTheSame) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Torus;
  spec.count = 20000;
  spec.seed = 9;
  auto c = growth::generateCloud(spec);
  growth::Random rnd(10);
  for (size_t i = 0; i < c.normals.size(); i += 7) c.normals[i] = (c.normals[i] + rnd.unitVector() * 1.2).Normalize();
  const double d = 0.35;
  BoxGrid ref;
  ref.build(c.points, c.normals, d, nullptr, 1);
  EXPECT_GT(ref.dTooLargeCount(), 0u);
  for (int threads : {1, 2}) {
    BoxGrid g;
    g.build(c.points, c.normals, d, nullptr, threads, /*deferNormals=*/true);
    ASSERT_EQ(g.boxCount(), ref.boxCount());
    g.startNormals(threads, c.points[0]);
    // Ask from the last box down while the other thread goes up.
    for (int b = int(g.boxCount()) - 1; b >= 0; b -= 3) ASSERT_EQ(g.boxNormal(b), ref.boxNormal(b)) << b;
    g.finishNormals();
    EXPECT_EQ(g.dTooLargeCount(), ref.dTooLargeCount()) << threads;
    for (int b = 0; b < int(g.boxCount()); ++b) {
      ASSERT_EQ(g.boxNormal(b), ref.boxNormal(b));
      ASSERT_EQ(g.boxMinDot(b), ref.boxMinDot(b));
    }
  }
  // Dropped while its thread runs: no crash, no leak of the thread.
  BoxGrid dropped;
  dropped.build(c.points, c.normals, d, nullptr, 2, true);
  dropped.startNormals(2, Point3d(0, 0, 0));
}

// Points renumbered (the sphere packer's spatial order) with listOrder giving the original order:
// the same boxes with the same ids, lists of the same points in the same order, the same normals.
TEST(BoxGrid, ListOrderKeepsTheOriginalOrderOfRenumberedPoints) {
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Sphere;
  spec.count = 15000;
  spec.seed = 12;
  auto c = growth::generateCloud(spec);
  growth::Random rnd(13);
  for (size_t i = 0; i < c.normals.size(); i += 5) c.normals[i] = (c.normals[i] + rnd.unitVector()).Normalize();
  const size_t n = c.points.size();
  std::vector<std::uint32_t> orig(n), rank(n); // new -> original, original -> new
  for (size_t i = 0; i < n; ++i) orig[i] = std::uint32_t(i);
  for (size_t i = n - 1; i > 0; --i) std::swap(orig[i], orig[size_t(rnd.uniform(0, double(i + 1))) % (i + 1)]);
  for (size_t i = 0; i < n; ++i) rank[orig[i]] = std::uint32_t(i);
  std::vector<Point3d> pts(n), nrm(n);
  for (size_t i = 0; i < n; ++i) pts[i] = c.points[orig[i]], nrm[i] = c.normals[orig[i]];
  const double d = 0.12;
  BoxGrid a, b;
  a.build(c.points, c.normals, d, nullptr, 2);
  b.build(pts, nrm, d, nullptr, 2, false, &rank);
  ASSERT_EQ(a.boxCount(), b.boxCount());
  EXPECT_EQ(a.dTooLargeCount(), b.dTooLargeCount());
  EXPECT_EQ(a.droppedByFilter(), b.droppedByFilter());
  for (size_t i = 0; i < n; i += 7) {
    const int box = a.boxOf(c.points[i]);
    ASSERT_EQ(b.boxOf(c.points[i]), box);
    std::vector<std::uint32_t> mapped;
    for (const std::uint32_t* it = b.pointsBegin(box); it != b.pointsEnd(box); ++it) mapped.push_back(orig[*it]);
    ASSERT_EQ(mapped, std::vector<std::uint32_t>(a.pointsBegin(box), a.pointsEnd(box)));
    ASSERT_EQ(b.boxNormal(box), a.boxNormal(box));
    ASSERT_EQ(b.boxMinDot(box), a.boxMinDot(box));
  }
}

// Copies of a sampling share its tables and answer like it.
TEST(SphereSampling, ACopyAnswersLikeTheOriginal) {
  const SphereSampling s(5);
  const SphereSampling copy(s);
  growth::Random rnd(8);
  std::vector<Point3d> normals;
  for (int k = 0; k < 40; ++k) normals.push_back((Point3d(0, 0, 1) + rnd.unitVector() * 0.5).Normalize());
  const auto idx = iota(normals.size());
  double a = 0, b = 0;
  EXPECT_EQ(s.maxMinDirection(normals, idx.data(), idx.size(), &a), copy.maxMinDirection(normals, idx.data(), idx.size(), &b));
  EXPECT_EQ(a, b);
}

// The box normals are kept as two-byte codes of S_F's directions: every direction of S_F, and the
// (0, 0, 1) of a box without normals, comes back bit for bit; anything else is refused.
TEST(SphereSampling, DirectionsAreCodedInTwoBytesBitForBit) {
  const SphereSampling s(6);
  for (size_t i = 0; i < s.size(); ++i) {
    const Point3d dir = s.direction(i);
    const std::uint16_t code = s.code(dir);
    ASSERT_NE(code, SphereSampling::kUpCode);
    ASSERT_EQ(s.decode(code), dir) << i;
  }
  EXPECT_EQ(s.code(Point3d(0, 0, 1)), SphereSampling::kUpCode);
  EXPECT_EQ(s.decode(SphereSampling::kUpCode), Point3d(0, 0, 1));
  EXPECT_THROW(s.code(Point3d(0.6, 0.8, 0)), std::logic_error);
}

// The box index in blocks of 4 x 4 x 4 gives the same answers as a hash of the box keys: the same
// value for every key inserted (the first one given), -1 for the others, the same count.
TEST(BoxIdIndex, SameAnswersAsAHashOfTheKeys) {
  growth::BoxIdIndex blocks;
  growth::KeyHash flat;
  blocks.reset(16);
  std::uint64_t s = 12345;
  auto next = [&] { s = s * 6364136223846793005ull + 1442695040888963407ull; return s >> 33; };
  for (int i = 0; i < 20000; ++i) {
    // Clustered coordinates (a surface's boxes) and a few far ones, near the 21-bit limits too.
    const std::int64_t base = (i % 97 == 0) ? growth::BoxIndexer::kMax - 8 : 1000;
    const auto key = growth::BoxIndexer::pack(base + std::int64_t(next() % 40), base + std::int64_t(next() % 40),
                                              std::int64_t(next() % 9));
    ASSERT_EQ(blocks.findOrInsert(key, i), flat.findOrInsert(key, i)) << i;
  }
  EXPECT_EQ(blocks.size(), flat.size());
  for (int i = 0; i < 20000; ++i) {
    const auto key = growth::BoxIndexer::pack(std::int64_t(next() % 1100), std::int64_t(next() % 1100),
                                              std::int64_t(next() % 12));
    ASSERT_EQ(blocks.find(key), flat.find(key)) << i;
  }
}

// A lazy grid (build()'s splatRadius) builds only the boxes the splats' disks meet and gathers the
// others on first use: every box, built or gathered, has the same points in the same order, the
// same layers, box normal, minimum and flags as in the full grid, anywhere near the cloud or far
// from it. On a curved, noisy cloud with flipped normals, a thin two-sided plate, splats larger
// than d and a list order that is not the index order.
TEST(BoxGrid, LazyGridGivesTheSameBoxesAsTheFullGrid) {
  growth::Random rnd(21);
  std::vector<Point3d> p, n;
  std::vector<float> radius, extra;
  const double d = 0.05;
  for (int i = 0; i < 6000; ++i) { // a noisy sphere of radius 0.5, one normal in 20 flipped
    const Point3d u = rnd.unitVector();
    p.push_back(u * (0.5 + 0.004 * rnd.uniform(-1, 1)));
    n.push_back(i % 20 == 0 ? u * -1.0 : u);
  }
  for (int i = 0; i < 3000; ++i) { // a plate 0.02 thick beside it, both sides sampled
    const bool top = i % 2 == 0;
    p.emplace_back(1 + rnd.uniform(0, 0.5), rnd.uniform(0, 0.5), top ? 0.01 : -0.01);
    n.emplace_back(0, 0, top ? 1 : -1);
  }
  for (size_t i = 0; i < p.size(); ++i) {
    radius.push_back(float(d * (i % 13 == 0 ? rnd.uniform(1.0, 3.0) : rnd.uniform(0.2, 1.0))));
    extra.push_back(radius.back() > d ? radius.back() : 0.0f);
  }
  std::vector<std::uint32_t> order = iota(p.size());
  for (size_t i = order.size(); i > 1; --i) std::swap(order[i - 1], order[size_t(rnd.uniform(0, double(i) - 1e-9))]);
  BoxGrid full, lazy;
  full.build(p, n, d, nullptr, 2, false, &order, &extra);
  lazy.build(p, n, d, nullptr, 2, false, &order, &extra, &radius);
  EXPECT_LT(lazy.boxCount(), full.boxCount() / 2);
  EXPECT_LT(lazy.references(), full.references());
  EXPECT_GT(full.twoSidedBoxes(), 0u);
  auto same = [&](const Point3d& q, const Point3d& side) {
    const int a = full.boxOf(q, side), b = lazy.boxOf(q, side);
    ASSERT_EQ(a < 0, b < 0) << q[0] << " " << q[1] << " " << q[2];
    if (a < 0) return;
    ASSERT_EQ(std::vector<std::uint32_t>(full.pointsBegin(a), full.pointsEnd(a)),
              std::vector<std::uint32_t>(lazy.pointsBegin(b), lazy.pointsEnd(b)));
    const Point3d na = full.boxNormal(a), nb = lazy.boxNormal(b);
    EXPECT_TRUE(na[0] == nb[0] && na[1] == nb[1] && na[2] == nb[2]);
    EXPECT_EQ(full.boxMinDot(a), lazy.boxMinDot(b));
    EXPECT_EQ(full.dTooLarge(a), lazy.dTooLarge(b));
  };
  size_t queries = 0;
  for (size_t i = 0; i < p.size(); i += 3)
    for (const double reach : {0.0, 0.5 * d, 1.5 * d, 3 * d, 9 * d}) {
      const Point3d q = p[i] + rnd.unitVector() * (reach * rnd.uniform(0.5, 1.0));
      for (const Point3d& side : {n[i], n[i] * -1.0, Point3d(0, 0, 0)}) same(q, side);
      ++queries;
    }
  EXPECT_GT(queries, 10000u);
  EXPECT_GT(lazy.gatheredBoxes(), 100u);
  // Far from every point: no box in either.
  EXPECT_EQ(lazy.boxOf(Point3d(5, 5, 5)), -1);
}
