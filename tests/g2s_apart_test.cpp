// The cheap tests in front of the exact face-pair test of Robust G2S's repairs
// (filter_g2s/engine/g2s_apart.h): whenever one says "apart", the exact test (growth::facesIntersect)
// finds no intersection; and they do say it for the pairs they are there for.
#include "g2s_apart.h"

#include <growth/cloud_generator.h>
#include <growth/self_intersections.h>

#include <gtest/gtest.h>

#include <vector>

using namespace growth::g2s;
using growth::Triangle;

namespace {

// Seeded pairs of faces around a triangle t (points 0, 1, 2) in the plane z = 0: u shares
// `shared` of t's points and has its other points near that plane (off it by `lift` times a random
// factor, 0 for coplanar), anywhere within `reach` of the origin. Integer coordinates on a small
// lattice when `lattice` (exact coplanarity and collinearity, touching corners), random doubles
// otherwise.
struct Counts {
  size_t pairs = 0, intersecting = 0, apartPlane = 0, apartShadow = 0;
};

void checkPairs(std::uint64_t seed, int shared, double lift, bool lattice, Counts& counts) {
  growth::Random rng(seed);
  auto uniform = [&](double lo, double hi) { return rng.uniform(lo, hi); };
  auto coordinate = [&](double reach) {
    return lattice ? double(std::int64_t(rng.next() % 9) - 4) : uniform(-reach, reach);
  };
  for (int round = 0; round < 4000; ++round) {
    std::vector<P3> pos;
    for (int i = 0; i < 3; ++i) pos.emplace_back(coordinate(2), coordinate(2), 0.0);
    for (int i = 0; i < 3; ++i) {
      const double off = lattice ? double(std::int64_t(rng.next() % 3) - 1) : uniform(-1, 1);
      pos.emplace_back(coordinate(3), coordinate(3), lift * off);
    }
    const Triangle t{0, 1, 2};
    Triangle u{3, 4, 5};
    // Shared points: u's first corners replaced by t's, in a random rotation of both.
    const int rot = int(rng.next() % 3);
    for (int k = 0; k < shared; ++k) u[size_t(k)] = t[size_t((k + rot) % 3)];
    if (rng.next() % 2) std::swap(u[1], u[2]);
    const Triangle tr{t[size_t(rot)], t[size_t((rot + 1) % 3)], t[size_t((rot + 2) % 3)]};
    const bool exact = growth::facesIntersect(pos, tr, u);
    const PlaneOf plane(pos, tr);
    const bool byPlane = apartByPlane(pos, plane, tr, u) || apartByPlane(pos, u, tr);
    const bool inShadow = apartInShadow(pos, plane, tr, u);
    // The plane built once gives what the plane built per call gives.
    ASSERT_EQ(apartByPlane(pos, plane, tr, u), apartByPlane(pos, tr, u));
    if (byPlane) {
      ASSERT_FALSE(exact) << "seed " << seed << " round " << round << ": plane test";
    }
    if (inShadow) {
      ASSERT_FALSE(exact) << "seed " << seed << " round " << round << ": shadow test";
    }
    ++counts.pairs;
    counts.intersecting += exact;
    counts.apartPlane += byPlane;
    counts.apartShadow += inShadow && !byPlane;
  }
}

} // namespace

TEST(G2SApart, NeverSaysApartWhenTheExactTestFindsAnIntersection) {
  Counts counts;
  for (std::uint64_t seed = 1; seed <= 6; ++seed)
    for (int shared = 0; shared <= 2; ++shared) {
      checkPairs(seed, shared, 0.0, true, counts);  // coplanar on a lattice
      checkPairs(seed, shared, 1.0, true, counts);  // off the plane by one lattice step or none
      checkPairs(seed, shared, 0.0, false, counts); // coplanar, random doubles
      checkPairs(seed, shared, 1e-12, false, counts); // barely off the plane
      checkPairs(seed, shared, 0.3, false, counts);
    }
  // Not vacuous: many pairs intersect, and each test parts many of the others.
  EXPECT_GT(counts.intersecting, counts.pairs / 10);
  EXPECT_GT(counts.apartPlane, counts.pairs / 10);
  EXPECT_GT(counts.apartShadow, counts.pairs / 10);
}

TEST(G2SApart, ShadowTestPartsFacesSideBySideOnAFlatSurface) {
  // Faces at point 0 of t: one beside t (beyond its edge 0-2, the line x = 0), with one point a
  // little above t's plane and one below, and t's points 1 and 2 on either side of its plane, so
  // that the plane test parts neither way; and one lying over t.
  const std::vector<P3> pos = {P3(0, 0, 0),         P3(1, 0, 0),     P3(0, 1, 0),          P3(-1, -0.5, 1e-3),
                               P3(0.5, 0.5, 1e-3), P3(0.8, 0.1, 0), P3(-0.3, 0.2, -1e-3)};
  const Triangle t{0, 1, 2};
  const PlaneOf plane(pos, t);
  const Triangle beside{0, 3, 6};
  const Triangle over{0, 4, 5}; // point 5 lies in t
  EXPECT_FALSE(apartByPlane(pos, plane, t, beside) || apartByPlane(pos, beside, t));
  EXPECT_TRUE(apartInShadow(pos, plane, t, beside));
  EXPECT_FALSE(growth::facesIntersect(pos, t, beside));
  EXPECT_FALSE(apartInShadow(pos, plane, t, over));
  EXPECT_TRUE(growth::facesIntersect(pos, t, over));
}
