#include <growth/manifold_cleanup.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <vector>

using growth::ManifoldCleanupStat;
using growth::Triangle;
using growth::countNonManifoldVertices;
using growth::removeNonManifoldVertices;

namespace {

size_t alive(const std::vector<char>& a) { return size_t(std::count(a.begin(), a.end(), char(1))); }

// Closed fan of k triangles around `centre` with rim vertices first..first+k-1.
void closedFan(std::vector<Triangle>& f, std::uint32_t centre, std::uint32_t first, std::uint32_t k) {
  for (std::uint32_t i = 0; i < k; ++i) f.push_back({centre, first + i, first + (i + 1) % k});
}

} // namespace

TEST(ManifoldCleanup, ManifoldMeshesAreLeftAlone) {
  // One triangle, a closed tetrahedron, an open fan.
  std::vector<Triangle> tri{{0, 1, 2}};
  std::vector<char> a;
  ManifoldCleanupStat st = removeNonManifoldVertices(tri, 3, a);
  EXPECT_EQ(st.nonManifoldVertices, 0u);
  EXPECT_EQ(alive(a), 1u);

  std::vector<Triangle> tet{{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  a.clear();
  st = removeNonManifoldVertices(tet, 4, a);
  EXPECT_EQ(st.facesRemoved, 0u);
  EXPECT_EQ(alive(a), 4u);

  std::vector<Triangle> fan;
  for (std::uint32_t i = 1; i < 6; ++i) fan.push_back({0, i, i + 1});
  a.clear();
  st = removeNonManifoldVertices(fan, 7, a);
  EXPECT_EQ(st.facesRemoved, 0u);
  EXPECT_EQ(countNonManifoldVertices(fan, 7, a), 0u);
}

TEST(ManifoldCleanup, BowTieLosesOneTriangle) {
  // Two triangles touching only at vertex 0 (fig. 5, left).
  std::vector<Triangle> tri{{0, 1, 2}, {0, 3, 4}};
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 5, a), 1u);
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 5, a);
  EXPECT_EQ(st.nonManifoldVertices, 1u);
  EXPECT_EQ(st.facesRemoved, 1u);
  EXPECT_EQ(a[0], 1); // equal open fans: the one with the lower triangle index stays
  EXPECT_EQ(a[1], 0);
  EXPECT_EQ(countNonManifoldVertices(tri, 5, a), 0u);
}

TEST(ManifoldCleanup, ClosedFanIsKeptOverALargerOpenOne) {
  // Vertex 0: a closed fan of 4 triangles and an open fan of 5.
  std::vector<Triangle> tri;
  closedFan(tri, 0, 1, 4);
  for (std::uint32_t i = 0; i < 5; ++i) tri.push_back({0, 10 + i, 11 + i});
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 16, a), 1u);
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 16, a);
  EXPECT_EQ(st.facesRemoved, 5u);
  for (size_t f = 0; f < 4; ++f) EXPECT_EQ(a[f], 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 16, a), 0u);
}

TEST(ManifoldCleanup, LargerOfTwoOpenFansIsKept) {
  std::vector<Triangle> tri{{0, 1, 2}, {0, 5, 6}, {0, 6, 7}, {0, 7, 8}};
  std::vector<char> a(tri.size(), 1);
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 9, a);
  EXPECT_EQ(st.facesRemoved, 1u);
  EXPECT_EQ(a[0], 0);
  EXPECT_EQ(alive(a), 3u);
}

TEST(ManifoldCleanup, TwoClosedConesAtOneApex) {
  // Fig. 5, right: two closed fans share the apex; one cone goes.
  std::vector<Triangle> tri;
  closedFan(tri, 0, 1, 5);
  closedFan(tri, 0, 10, 4);
  std::vector<char> a(tri.size(), 1);
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 14, a);
  EXPECT_EQ(st.nonManifoldVertices, 1u);
  EXPECT_EQ(st.facesRemoved, 4u);
  EXPECT_EQ(alive(a), 5u);
  EXPECT_EQ(countNonManifoldVertices(tri, 14, a), 0u);
}

TEST(ManifoldCleanup, RemovalThatSplitsANeighboursFanIsFollowedUp) {
  // Vertex 0: closed fan of 4 (rim 1..4) and an open fan of two triangles sharing edge {0,6}.
  // Vertex 6's fan runs (6,5,8) – (0,5,6) – (0,6,7) – (7,6,9): removing vertex 0's small fan
  // cuts it in two, so vertex 6 becomes non-manifold and loses one of the halves.
  std::vector<Triangle> tri;
  closedFan(tri, 0, 1, 4);            // faces 0..3
  tri.push_back({0, 5, 6});           // 4
  tri.push_back({0, 6, 7});           // 5
  tri.push_back({6, 5, 8});           // 6
  tri.push_back({7, 6, 9});           // 7
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 10, a), 1u);
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 10, a);
  EXPECT_EQ(st.nonManifoldVertices, 2u); // 0, then 6
  EXPECT_EQ(st.facesRemoved, 3u);
  EXPECT_EQ(a[4], 0);
  EXPECT_EQ(a[5], 0);
  EXPECT_EQ(a[6] + a[7], 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 10, a), 0u);
}

TEST(ManifoldCleanup, ChainOfBowTiesKeepsEveryOtherTriangle) {
  // Triangles t_i = (s_{i-1}, x_i, s_i) touching their neighbours only at the s vertices: every
  // shared vertex is a bow-tie. Resolving s_0 removes t_1, which resolves s_1, and so on.
  const std::uint32_t k = 9;
  std::vector<Triangle> tri;
  // Shared vertices s_i = i (0..k-2), private ones from 100, the first vertex of t_0 is 99.
  for (std::uint32_t i = 0; i < k; ++i) {
    const std::uint32_t prev = i == 0 ? 99 : i - 1, next = i + 1 == k ? 98 : i;
    tri.push_back({prev, 100 + i, next});
  }
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 200, a), size_t(k - 1));
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 200, a);
  EXPECT_EQ(countNonManifoldVertices(tri, 200, a), 0u);
  EXPECT_EQ(alive(a), size_t((k + 1) / 2));
  EXPECT_EQ(st.facesRemoved, size_t(k / 2));
  for (std::uint32_t i = 0; i < k; ++i) EXPECT_EQ(a[i], i % 2 == 0 ? 1 : 0) << i;
}

TEST(ManifoldCleanup, ManyBowTieFansAreEachResolved) {
  // Vertices c_0, c_1, ...: at each a closed fan (kept) and a two-triangle open fan (removed).
  std::vector<Triangle> tri;
  const std::uint32_t links = 6;
  std::uint32_t next = 1000;
  for (std::uint32_t i = 0; i < links; ++i) {
    const std::uint32_t c = i;
    closedFan(tri, c, next, 6);
    next += 6;
    // Bow-tie partner: two triangles at c sharing edge {c, next}, hanging off a strip.
    tri.push_back({c, next, next + 1});
    tri.push_back({c, next + 1, next + 2});
    next += 3;
  }
  std::vector<char> a(tri.size(), 1);
  const size_t before = countNonManifoldVertices(tri, next, a);
  EXPECT_EQ(before, size_t(links));
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, next, a);
  EXPECT_EQ(st.nonManifoldVertices, size_t(links));
  EXPECT_EQ(st.facesRemoved, size_t(2 * links));
  EXPECT_EQ(alive(a), size_t(6 * links));
  EXPECT_EQ(countNonManifoldVertices(tri, next, a), 0u);
}

TEST(ManifoldCleanup, NonManifoldEdgeIsResolved) {
  // Three triangles on edge {0,1}.
  std::vector<Triangle> tri{{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, 5, a), 2u);
  removeNonManifoldVertices(tri, 5, a);
  EXPECT_EQ(countNonManifoldVertices(tri, 5, a), 0u);
  EXPECT_GE(alive(a), 1u);
  // What is left has no edge with more than two triangles.
  size_t on01 = 0;
  for (size_t f = 0; f < tri.size(); ++f)
    if (a[f]) ++on01;
  EXPECT_LE(on01, 2u);
}

TEST(ManifoldCleanup, SuspectsGiveTheSameResultAsAFullScan) {
  std::vector<Triangle> tri;
  closedFan(tri, 0, 1, 4);
  tri.push_back({0, 5, 6});
  tri.push_back({0, 6, 7});
  tri.push_back({6, 5, 8});
  tri.push_back({7, 6, 9});
  tri.push_back({20, 21, 22});
  tri.push_back({20, 23, 24}); // an unrelated bow-tie at 20
  std::vector<char> full(tri.size(), 1), some(tri.size(), 1);
  const ManifoldCleanupStat a = removeNonManifoldVertices(tri, 25, full);
  const std::vector<std::uint32_t> suspects{20, 0};
  const ManifoldCleanupStat b = removeNonManifoldVertices(tri, 25, some, &suspects);
  EXPECT_EQ(a.facesRemoved, b.facesRemoved);
  EXPECT_EQ(a.nonManifoldVertices, b.nonManifoldVertices);
  EXPECT_EQ(full, some);
  // Suspects that miss a non-manifold vertex leave it (the caller's promise is broken).
  std::vector<char> partial(tri.size(), 1);
  const std::vector<std::uint32_t> onlyZero{0};
  removeNonManifoldVertices(tri, 25, partial, &onlyZero);
  EXPECT_EQ(countNonManifoldVertices(tri, 25, partial), 1u);
}

TEST(ManifoldCleanup, DegenerateTrianglesAreRemoved) {
  std::vector<Triangle> tri{{0, 1, 2}, {2, 2, 3}};
  std::vector<char> a;
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, 4, a);
  EXPECT_EQ(st.facesRemoved, 1u);
  EXPECT_EQ(a[0], 1);
  EXPECT_EQ(a[1], 0);
}

TEST(ManifoldCleanup, LargeMeshWithManyBowTiesEndsManifold) {
  // A strip of 20000 quads (40000 triangles), plus a bow-tie hanging at every 10th vertex.
  std::vector<Triangle> tri;
  const std::uint32_t n = 20000;
  for (std::uint32_t i = 0; i < n; ++i) {
    tri.push_back({i, i + 1, n + 1 + i});
    tri.push_back({i + 1, n + 2 + i, n + 1 + i});
  }
  std::uint32_t next = 2 * n + 2;
  for (std::uint32_t i = 0; i < n; i += 10) {
    tri.push_back({i, next, next + 1});
    next += 2;
  }
  std::vector<char> a(tri.size(), 1);
  EXPECT_EQ(countNonManifoldVertices(tri, next, a), size_t(n / 10));
  const ManifoldCleanupStat st = removeNonManifoldVertices(tri, next, a);
  EXPECT_EQ(st.nonManifoldVertices, size_t(n / 10));
  EXPECT_EQ(st.facesRemoved, size_t(n / 10)); // each lone triangle is the smaller fan
  EXPECT_EQ(countNonManifoldVertices(tri, next, a), 0u);
}

namespace {

// Fans of every vertex by a plain reference: incident alive, non-degenerate triangles joined
// across each edge at the vertex that exactly two of them share.
size_t referenceNonManifold(const std::vector<Triangle>& f, size_t vertexCount) {
  size_t n = 0;
  for (std::uint32_t v = 0; v < vertexCount; ++v) {
    std::vector<size_t> inc;
    for (size_t i = 0; i < f.size(); ++i)
      if (f[i][0] != f[i][1] && f[i][1] != f[i][2] && f[i][2] != f[i][0] &&
          (f[i][0] == v || f[i][1] == v || f[i][2] == v))
        inc.push_back(i);
    std::vector<size_t> comp(inc.size());
    for (size_t i = 0; i < comp.size(); ++i) comp[i] = i;
    auto find = [&](size_t i) {
      while (comp[i] != i) i = comp[i];
      return i;
    };
    for (std::uint32_t w = 0; w < vertexCount; ++w) {
      if (w == v) continue;
      std::vector<size_t> on;
      for (size_t i = 0; i < inc.size(); ++i)
        if (f[inc[i]][0] == w || f[inc[i]][1] == w || f[inc[i]][2] == w) on.push_back(i);
      if (on.size() == 2) comp[find(on[0])] = find(on[1]);
    }
    size_t fans = 0;
    for (size_t i = 0; i < comp.size(); ++i) fans += find(i) == i;
    n += fans > 1;
  }
  return n;
}

} // namespace

TEST(ManifoldCleanup, FanCountsAgreeWithAPlainReferenceOnRandomPatches) {
  // Random subsets of a triangulated grid, some triangles flipped, duplicated or added across it:
  // open and closed fans, bow ties, inconsistent orientations, valences above eight.
  std::uint64_t state = 12345;
  auto next = [&](std::uint32_t m) {
    state = state * 6364136223846793005ull + 1442695040888963407ull;
    return std::uint32_t((state >> 33) % m);
  };
  const std::uint32_t side = 6, vertices = side * side;
  for (int round = 0; round < 300; ++round) {
    std::vector<Triangle> f;
    for (std::uint32_t y = 0; y + 1 < side; ++y)
      for (std::uint32_t x = 0; x + 1 < side; ++x) {
        const std::uint32_t a = y * side + x, b = a + 1, c = a + side, d = c + 1;
        if (next(10) < 8) f.push_back({a, b, d});
        if (next(10) < 8) f.push_back({a, d, c});
      }
    for (Triangle& t : f)
      if (next(20) == 0) std::swap(t[1], t[2]);
    const size_t extra = next(6);
    for (size_t k = 0; k < extra; ++k) {
      if (!f.empty() && next(2) == 0) f.push_back(f[next(std::uint32_t(f.size()))]);
      else f.push_back({next(vertices), next(vertices), next(vertices)});
    }
    ASSERT_EQ(countNonManifoldVertices(f, vertices, std::vector<char>(f.size(), 1)), referenceNonManifold(f, vertices))
        << "round " << round;
  }
}

// Pieces below the size go, the largest stays even when it is below it too, and dead triangles
// neither count nor join pieces.
TEST(ManifoldCleanup, SmallComponentsAreDroppedButNeverTheLargest) {
  std::vector<Triangle> tri;
  closedFan(tri, 0, 1, 6);   // piece A: 6 triangles (vertices 0-6)
  closedFan(tri, 10, 11, 4); // piece B: 4 triangles (10-14)
  tri.push_back({20, 21, 22}); // piece C: 1 triangle
  tri.push_back({22, 21, 23}); // ... 2 triangles with this one
  tri.push_back({2, 11, 30});  // dead: would join A and B
  std::vector<char> a(tri.size(), 1);
  a.back() = 0;
  size_t faces = 0;
  EXPECT_EQ(growth::dropSmallComponents(tri, 31, a, 1, faces), 0u); // minFaces <= 1: nothing
  EXPECT_EQ(growth::dropSmallComponents(tri, 31, a, 4, faces), 1u); // C only: B has 4
  EXPECT_EQ(faces, 2u);
  EXPECT_EQ(alive(a), 10u);
  EXPECT_EQ(a[10], 0);
  EXPECT_EQ(a[11], 0);
  EXPECT_EQ(growth::dropSmallComponents(tri, 31, a, 100, faces), 1u); // B; A is the largest
  EXPECT_EQ(faces, 4u);
  EXPECT_EQ(alive(a), 6u);
  for (size_t f = 0; f < 6; ++f) EXPECT_EQ(a[f], 1);
  EXPECT_EQ(growth::dropSmallComponents(tri, 31, a, 100, faces), 0u); // one piece left
}
