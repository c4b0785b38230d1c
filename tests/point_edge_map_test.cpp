#include "point_edge_map.h"

#include <gtest/gtest.h>

#include <array>
#include <set>
#include <vector>
#include <stdexcept>

using growth::PointEdgeMap;

TEST(PointEdgeMap, EmptyMapHasNoEdges) {
  PointEdgeMap m(4);
  EXPECT_EQ(m.pointCount(), 4u);
  for (std::uint32_t v = 0; v < 4; ++v) {
    EXPECT_TRUE(m.isolated(v));
    EXPECT_FALSE(m.hasFreeEdge(v));
    EXPECT_FALSE(m.closed(v));
    EXPECT_EQ(m.degree(v), 0);
  }
  EXPECT_FALSE(m.used(0, 1));
  EXPECT_EQ(m.triangles(0, 1), 0);
  EXPECT_TRUE(m.canAddTriangle(0, 1, 2));
  EXPECT_FALSE(m.canAddTriangle(0, 0, 2)); // repeated vertex
}

TEST(PointEdgeMap, OneTriangleUsesItsThreeHalfEdgesOneWay) {
  PointEdgeMap m(3);
  EXPECT_EQ(m.addTriangle(0, 1, 2), 7u); // all three edges new
  EXPECT_TRUE(m.used(0, 1) && m.used(1, 2) && m.used(2, 0));
  EXPECT_FALSE(m.used(1, 0) || m.used(2, 1) || m.used(0, 2));
  EXPECT_EQ(m.triangles(0, 1), 1);
  EXPECT_EQ(m.triangles(1, 0), 1);
  for (std::uint32_t v = 0; v < 3; ++v) {
    EXPECT_EQ(m.degree(v), 2);
    EXPECT_TRUE(m.hasFreeEdge(v));
    EXPECT_FALSE(m.closed(v));
  }
}

TEST(PointEdgeMap, ConsistentNeighbourIsAllowedInconsistentOrThirdTriangleIsNot) {
  PointEdgeMap m(5);
  m.addTriangle(0, 1, 2);
  // Across edge {0,1} with consistent orientation: traverses 1→0.
  EXPECT_TRUE(m.canAddTriangle(1, 0, 3));
  // Same direction 0→1 as the first triangle: inconsistent orientation.
  EXPECT_FALSE(m.canAddTriangle(0, 1, 3));
  EXPECT_EQ(m.addTriangle(1, 0, 3), 6u); // {1,0} existed; {0,3} and {3,1} are new
  EXPECT_EQ(m.triangles(0, 1), 2);
  // Edge {0,1} has two triangles: no third one, in either direction.
  EXPECT_FALSE(m.canAddTriangle(0, 1, 4));
  EXPECT_FALSE(m.canAddTriangle(1, 0, 4));
}

TEST(PointEdgeMap, ClosedFanMakesTheCentreInterior) {
  // Hexagon fan around vertex 0 (rim 1..6), consistently oriented.
  PointEdgeMap m(7);
  for (std::uint32_t i = 1; i <= 6; ++i) {
    const std::uint32_t j = i % 6 + 1;
    ASSERT_TRUE(m.canAddTriangle(0, i, j));
    m.addTriangle(0, i, j);
    if (i < 6) {
      EXPECT_FALSE(m.closed(0)) << "open after " << i << " triangles";
    }
  }
  EXPECT_TRUE(m.closed(0));
  EXPECT_FALSE(m.hasFreeEdge(0));
  EXPECT_EQ(m.degree(0), 6);
  for (std::uint32_t i = 1; i <= 6; ++i) EXPECT_TRUE(m.hasFreeEdge(i));
}

TEST(PointEdgeMap, ManyNeighboursChainOverflowBlocks) {
  // A vertex with 40 neighbours (a fan of 39 triangles): beyond the inline block.
  const std::uint32_t n = 40;
  PointEdgeMap m(n + 1);
  for (std::uint32_t i = 1; i < n; ++i) m.addTriangle(0, i, i + 1);
  EXPECT_EQ(m.degree(0), int(n));
  std::set<std::uint32_t> seen;
  m.forEachEdge(0, [&](std::uint32_t w, bool out, bool in) {
    seen.insert(w);
    EXPECT_TRUE(out || in);
  });
  EXPECT_EQ(seen.size(), size_t(n));
  for (std::uint32_t i = 1; i < n; ++i) {
    EXPECT_TRUE(m.used(0, i));
    EXPECT_TRUE(m.used(i + 1, 0));
    EXPECT_EQ(m.triangles(0, i), i == 1 ? 1 : 2);
  }
  // Close the fan: the first and last edge get their second triangle.
  m.addTriangle(0, n, 1);
  EXPECT_TRUE(m.closed(0));
  // Removal restores the open fan.
  m.removeTriangle(0, n, 1);
  EXPECT_FALSE(m.closed(0));
  EXPECT_FALSE(m.used(0, n));
  EXPECT_TRUE(m.canAddTriangle(0, n, 1));
}

TEST(PointEdgeMap, RemoveTriangleMakesItsHalfEdgesFreeAgain) {
  PointEdgeMap m(4);
  m.addTriangle(0, 1, 2);
  m.addTriangle(1, 0, 3);
  m.removeTriangle(0, 1, 2);
  EXPECT_FALSE(m.used(0, 1));
  EXPECT_TRUE(m.used(1, 0));
  EXPECT_EQ(m.triangles(0, 1), 1);
  EXPECT_TRUE(m.isolated(2));
  EXPECT_TRUE(m.canAddTriangle(0, 1, 2));
  // A re-added edge after removal counts as new again.
  EXPECT_EQ(m.addTriangle(0, 1, 2) & 6u, 6u);
}

// reverseAt on every vertex of a set of triangles is the same as removing them and adding them
// again flipped: here a closed fan of 12 around point 0 (its centre has more entries than one
// inline block holds) plus a triangle on its rim, flipped as one component, and a separate
// triangle left alone.
TEST(PointEdgeMap, ReverseAtEveryVertexFlipsAComponent) {
  const std::uint32_t rim = 12;
  std::vector<std::array<std::uint32_t, 3>> comp;
  for (std::uint32_t k = 0; k < rim; ++k) comp.push_back({0, 1 + k, 1 + (k + 1) % rim});
  comp.push_back({2, 1, 13}); // outside the fan, on the rim edge 1–2
  PointEdgeMap flipped(17), expected(17);
  for (const auto& t : comp) {
    flipped.addTriangle(t[0], t[1], t[2]);
    expected.addTriangle(t[0], t[2], t[1]);
  }
  flipped.addTriangle(14, 15, 16);
  expected.addTriangle(14, 15, 16);
  flipped.setMark(0, 1, true); // marks are kept
  for (std::uint32_t v = 0; v <= 13; ++v) flipped.reverseAt(v);
  for (std::uint32_t v = 0; v < 17; ++v)
    for (std::uint32_t w = 0; w < 17; ++w) {
      EXPECT_EQ(flipped.used(v, w), expected.used(v, w)) << v << "->" << w;
      EXPECT_EQ(flipped.triangles(v, w), expected.triangles(v, w)) << v << "-" << w;
    }
  EXPECT_TRUE(flipped.marked(0, 1));
  EXPECT_TRUE(flipped.closed(0));
  EXPECT_FALSE(flipped.used(1, 13)); // was 1→13 (triangle 2, 1, 13), now 13→1
  EXPECT_TRUE(flipped.used(13, 1));
}

TEST(PointEdgeMap, MarksAreSetPerHalfEdgeAndCleared) {
  PointEdgeMap m(3);
  m.addTriangle(0, 1, 2);
  m.setMark(0, 1, true);
  EXPECT_TRUE(m.marked(0, 1));
  EXPECT_FALSE(m.marked(1, 0));
  EXPECT_TRUE(m.used(0, 1)); // marks do not disturb the direction bits
  m.clearMarks();
  EXPECT_FALSE(m.marked(0, 1));
  EXPECT_TRUE(m.used(0, 1));
}

TEST(PointEdgeMap, APointHoldsHundredsOfNeighboursUpToItsCapacity) {
  // The pole of a latitude-longitude sphere: a closed fan of 600 triangles around point 0.
  const std::uint32_t rim = 600;
  PointEdgeMap m(rim + 1);
  for (std::uint32_t k = 0; k < rim; ++k) {
    ASSERT_TRUE(m.canAddTriangle(0, 1 + k, 1 + (k + 1) % rim)) << k;
    m.addTriangle(0, 1 + k, 1 + (k + 1) % rim);
  }
  EXPECT_EQ(m.degree(0), int(rim));
  EXPECT_EQ(m.entries(0), rim);
  EXPECT_TRUE(m.closed(0));
  for (std::uint32_t k = 0; k < rim; ++k) EXPECT_EQ(m.triangles(0, 1 + k), 2);
}

TEST(PointEdgeMap, AFullPointRefusesNewEdgesButNotExistingOnes) {
  // An open fan around point 0 until it holds kMaxEntries neighbours.
  const std::uint32_t cap = PointEdgeMap::kMaxEntries;
  PointEdgeMap m(cap + 3);
  for (std::uint32_t k = 1; k < cap; ++k) {
    ASSERT_TRUE(m.hasRoom(0, k, k + 1));
    m.addTriangle(0, k, k + 1);
  }
  EXPECT_EQ(m.entries(0), cap);
  // A triangle with a new edge at 0: no room; it is refused, not added.
  EXPECT_FALSE(m.hasRoom(0, cap, cap + 1));
  EXPECT_FALSE(m.canAddTriangle(0, cap, cap + 1));
  EXPECT_THROW(m.addTriangle(0, cap, cap + 1), std::length_error);
  // Closing the fan uses existing edges only ({0, cap} and {0, 1}) and a new one elsewhere.
  EXPECT_TRUE(m.hasRoom(0, cap, 1));
  ASSERT_TRUE(m.canAddTriangle(0, cap, 1));
  m.addTriangle(0, cap, 1);
  EXPECT_TRUE(m.closed(0));
  // A point far from full is not affected.
  EXPECT_TRUE(m.canAddTriangle(cap + 1, cap + 2, 2));
}

TEST(PointEdgeMap, ASmallerCapacityIsHonouredAndBounded) {
  PointEdgeMap m(20);
  EXPECT_EQ(m.capacity(), std::uint32_t{PointEdgeMap::kMaxEntries});
  EXPECT_THROW(m.setCapacity(1), std::invalid_argument);
  EXPECT_THROW(m.setCapacity(PointEdgeMap::kMaxEntries + 1), std::invalid_argument);
  m.setCapacity(4);
  m.addTriangle(0, 1, 2);
  m.addTriangle(0, 2, 3); // 0 has 1, 2, 3
  EXPECT_TRUE(m.hasRoom(0, 3, 4));  // one new entry at 0: four
  m.addTriangle(0, 3, 4);
  EXPECT_EQ(m.entries(0), 4u);
  EXPECT_FALSE(m.canAddTriangle(0, 4, 5));
  EXPECT_TRUE(m.canAddTriangle(0, 4, 1)); // closes the fan: no new entry at 0
}

TEST(PointEdgeMap, ReleaseFreesEverythingAndResetMakesItUsableAgain) {
  PointEdgeMap m(1000);
  for (std::uint32_t v = 1; v + 1 < 40; ++v) m.addTriangle(0, v, v + 1); // overflow blocks at 0
  EXPECT_GT(m.memoryBytes(), 1000u * 4);
  m.release();
  EXPECT_EQ(m.memoryBytes(), 0u);
  EXPECT_EQ(m.pointCount(), 0u);
  m.reset(3);
  EXPECT_EQ(m.pointCount(), 3u);
  EXPECT_TRUE(m.isolated(0));
  EXPECT_EQ(m.addTriangle(0, 1, 2), 7u);
  EXPECT_TRUE(m.used(0, 1));
}

// anyOutOnly visits exactly the free edges leaving v (v→w used, w→v not), in forEachEdge's order,
// and stops at the first for which f returns true: checked at fans of 1 to 20 triangles around
// point 0 (inline block and chained blocks), open, with gaps (removed triangles) and with some
// entries left without a triangle at all.
TEST(PointEdgeMap, AnyOutOnlyVisitsTheFreeEdgesLeavingAPointInOrder) {
  for (std::uint32_t fan = 1; fan <= 20; ++fan) {
    for (std::uint32_t gap = 0; gap <= fan; ++gap) {
      PointEdgeMap m(fan + 2);
      for (std::uint32_t i = 1; i <= fan; ++i) m.addTriangle(0, i, i + 1);
      // A gap: one triangle taken out (its entries stay, some edges lose their only triangle).
      if (gap > 0) m.removeTriangle(0, gap, gap + 1);
      std::vector<std::uint32_t> want;
      m.forEachEdge(0, [&](std::uint32_t w, bool out, bool in) {
        if (out && !in) want.push_back(w);
      });
      std::vector<std::uint32_t> got;
      EXPECT_FALSE(m.anyOutOnly(0, [&](std::uint32_t w) {
        got.push_back(w);
        return false;
      }));
      EXPECT_EQ(got, want) << "fan " << fan << " gap " << gap;
      // Stops at the first accepted one.
      for (size_t k = 0; k < want.size(); ++k) {
        std::vector<std::uint32_t> seen;
        EXPECT_TRUE(m.anyOutOnly(0, [&](std::uint32_t w) {
          seen.push_back(w);
          return w == want[k];
        }));
        EXPECT_EQ(seen, std::vector<std::uint32_t>(want.begin(), want.begin() + std::ptrdiff_t(k) + 1));
      }
      // At the rim points too (in and out entries mixed).
      for (std::uint32_t v = 1; v <= fan + 1; ++v) {
        std::vector<std::uint32_t> w1, w2;
        m.forEachEdge(v, [&](std::uint32_t w, bool out, bool in) {
          if (out && !in) w1.push_back(w);
        });
        m.anyOutOnly(v, [&](std::uint32_t w) {
          w2.push_back(w);
          return false;
        });
        EXPECT_EQ(w1, w2);
      }
    }
  }
}
