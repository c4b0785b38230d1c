// The sphere packer's method steps on their own (packer_steps.h): the sizes' checks (sec. 3.1,
// 4.3, 5.3), the spatial order, the starting pairs (sec. 3.3) and the small pieces dropped after
// the clean-up. The whole method: sphere_packer_test.cpp.
#include "packer_steps.h"

#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <vector>

namespace sp = growth::spherepack;
namespace detail = growth::spherepack::detail;
using Point3d = growth::Vec3d;

namespace {

growth::InputCloud inputOf(growth::Shape shape, size_t count, std::uint64_t seed) {
  growth::CloudSpec spec;
  spec.shape = shape;
  spec.count = count;
  spec.seed = seed;
  const growth::Cloud c = growth::generateCloud(spec);
  growth::InputCloud in;
  in.points = c.points;
  in.normals = c.normals;
  for (const Point3d& p : in.points) in.box.Add(p);
  return in;
}

double meanStep(const std::vector<Point3d>& points) {
  double sum = 0;
  for (size_t i = 1; i < points.size(); ++i) sum += (points[i] - points[i - 1]).Norm();
  return sum / double(points.size() - 1);
}

} // namespace

TEST(PackerSizes, ParametersOutsideTheirRangesAreRefused) {
  const growth::InputCloud in = inputOf(growth::Shape::Sphere, 5000, 1);
  sp::Stat st;
  sp::Params p;
  p.windowSize = -1;
  EXPECT_THROW(detail::chooseSizes(in, p, st), growth::Error);
  p = sp::Params();
  p.maxBorderLength = 2;
  EXPECT_THROW(detail::chooseSizes(in, p, st), growth::Error);
  p = sp::Params();
  p.minComponentFaces = -1;
  EXPECT_THROW(detail::chooseSizes(in, p, st), growth::Error);
  p = sp::Params();
  p.sphereDiameter = 2.0; // the unit sphere's box diagonal is 2√3: d above half of it
  EXPECT_THROW(detail::chooseSizes(in, p, st), growth::Error);
  p = sp::Params();
  p.maxOutputVertices = 100; // the default d gives about 0.3 vertices per point: 1500
  EXPECT_THROW(detail::chooseSizes(in, p, st), growth::Error);
}

TEST(PackerSizes, DefaultsComeFromTheCloudsScale) {
  const growth::InputCloud in = inputOf(growth::Shape::Sphere, 5000, 2);
  sp::Stat st;
  const detail::Sizes z = detail::chooseSizes(in, sp::Params(), st);
  EXPECT_EQ(z.d, sp::defaultDiameter(z.scale));
  EXPECT_EQ(z.s, sp::defaultSplatSize(z.scale, z.d));
  EXPECT_EQ(st.sphereDiameter, z.d);
  // The unit sphere's area 4π over the area per vertex of a d-lattice, within the area estimate's
  // sampling error.
  EXPECT_NEAR(z.expected, 4 * M_PI / (z.d * z.d * detail::kTriangleAreaFactor), 0.1 * z.expected);
  sp::Params given;
  given.sphereDiameter = 0.1;
  given.splatSize = 0.07;
  const detail::Sizes g = detail::chooseSizes(in, given, st);
  EXPECT_EQ(g.d, 0.1);
  EXPECT_EQ(g.s, 0.07);
  EXPECT_EQ(st.diameterReason, "given");
}

TEST(PackerSpatialOrder, APermutationThatKeepsEachPointWithItsNormalAndBringsNeighboursTogether) {
  growth::InputCloud in = inputOf(growth::Shape::Torus, 30000, 3);
  const growth::InputCloud original = in;
  const detail::Renumbering r = detail::spatialOrder(in, 0.05, 0);
  const size_t n = original.points.size();
  ASSERT_EQ(r.orig.size(), n);
  ASSERT_EQ(r.rank.size(), n);
  for (std::uint32_t i = 0; i < n; ++i) {
    ASSERT_LT(r.orig[i], n);
    ASSERT_EQ(r.rank[r.orig[i]], i); // orig and rank are inverse permutations
    ASSERT_EQ(in.points[i], original.points[r.orig[i]]);
    ASSERT_EQ(in.normals[i], original.normals[r.orig[i]]);
    ASSERT_EQ(r.origOf(i), r.orig[i]);
  }
  // Generated points come in random order (a step between consecutive ones is about the torus'
  // size); in the Morton order of boxes of side 0.05 most steps stay within a box or two.
  EXPECT_LT(meanStep(in.points), 0.1 * meanStep(original.points));
}

TEST(PackerSpatialOrder, SmallCloudsKeepTheirOrder) {
  growth::InputCloud in = inputOf(growth::Shape::Sphere, 2000, 4);
  const growth::InputCloud original = in;
  const detail::Renumbering r = detail::spatialOrder(in, 0.05, 2001);
  EXPECT_TRUE(r.orig.empty());
  EXPECT_TRUE(r.rank.empty());
  EXPECT_EQ(r.origOf(17), 17u);
  EXPECT_EQ(r.rankOf(17), 17u);
  EXPECT_EQ(in.points, original.points);
}

TEST(PackerStart, PairsLieOnSplatsBetweenDAnd2DApartAndPassTheFreeTest) {
  growth::InputCloud in = inputOf(growth::Shape::Sphere, 10000, 5);
  sp::Params params;
  sp::Stat st;
  growth::Progress progress(nullptr);
  const detail::Sizes z = detail::chooseSizes(in, params, st);
  const detail::Renumbering order; // identity
  const std::vector<float> radius = detail::splatRadii(in, z, params, order, st, progress);
  growth::BoxGrid grid;
  detail::buildBoxGrid(grid, in, radius, z.d, params, order, st, progress);
  grid.finishNormals();
  const double d = z.d;
  size_t found = 0;
  for (std::uint32_t i = 0; i < 200; ++i) {
    detail::StartPair pair;
    if (!detail::startPairAt(i, in, radius, grid, order, d, [](const Point3d&) { return true; }, pair)) continue;
    ++found;
    EXPECT_EQ(pair.s1, in.points[i]);
    EXPECT_EQ(pair.splat1, i);
    const double dist = (pair.s2 - pair.s1).Norm();
    EXPECT_GE(dist, d);
    EXPECT_LE(dist, 2 * d);
    const std::uint32_t j = pair.splat2;
    EXPECT_LT(growth::squaredDistanceToDisk(pair.s2, in.points[j], in.normals[j], radius[j]), 1e-20);
    // Nothing passes a test that refuses everything; the second position is tested too.
    detail::StartPair none;
    EXPECT_FALSE(detail::startPairAt(i, in, radius, grid, order, d, [](const Point3d&) { return false; }, none));
    int asked = 0;
    EXPECT_FALSE(detail::startPairAt(i, in, radius, grid, order, d,
                                     [&](const Point3d&) { return ++asked == 1; }, none));
    EXPECT_GE(asked, 2);
  }
  // A clean sphere at the default d: nearly every point has 4 points within d and a direction that
  // works (199 of these 200).
  EXPECT_GE(found, 190u);
}

TEST(PackerRegions, SmallPiecesAreDroppedButNeverTheLargest) {
  growth::BorderGraph g;
  for (int v = 0; v < 100; ++v) g.addVertex(Point3d(v, 0, 0), Point3d(0, 0, 1));
  // Three pieces, each a strip of faces {k, k+1, k+2}: 10 faces on 0..11, 60 on 20..81, 3 on 90..94.
  std::vector<growth::Triangle> faces;
  auto strip = [&](std::uint32_t first, int count) {
    for (int k = 0; k < count; ++k) faces.push_back({first + k, first + k + 1, first + k + 2});
  };
  strip(0, 10);
  strip(20, 60);
  strip(90, 3);
  const std::vector<growth::Triangle> all = faces;

  sp::Params p;
  sp::Stat st;
  p.minComponentFaces = 50;
  detail::dropSmallPieces(faces, g, p, st);
  EXPECT_EQ(st.componentsDropped, 2u);
  EXPECT_EQ(st.componentFacesDropped, 13u);
  EXPECT_EQ(faces, std::vector<growth::Triangle>(all.begin() + 10, all.begin() + 70)); // order kept

  faces = all;
  st = sp::Stat();
  p.minComponentFaces = 5;
  detail::dropSmallPieces(faces, g, p, st);
  EXPECT_EQ(st.componentsDropped, 1u);
  EXPECT_EQ(faces, std::vector<growth::Triangle>(all.begin(), all.begin() + 70));

  faces = all;
  st = sp::Stat();
  p.minComponentFaces = 1000; // every piece is small: the largest stays
  detail::dropSmallPieces(faces, g, p, st);
  EXPECT_EQ(st.componentsDropped, 2u);
  EXPECT_EQ(faces.size(), 60u);

  faces = all;
  st = sp::Stat();
  p.minComponentFaces = 0; // keep all
  detail::dropSmallPieces(faces, g, p, st);
  EXPECT_EQ(st.componentsDropped, 0u);
  EXPECT_EQ(faces, all);
}
