#include <growth/error.h>
#include <growth/mesh_generator.h>
#include <growth/mesh_measures.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <utility>
#include <vector>

using growth::MeshArrays;
using growth::MeshShape;
using growth::MeshSpec;
using growth::Vec3d;

namespace {

const MeshShape kShapes[] = {MeshShape::Box, MeshShape::Cylinder, MeshShape::LPrism, MeshShape::HoledBox, MeshShape::OpenBox,
                             MeshShape::Sheet};

MeshArrays make(MeshShape shape, size_t faces, std::uint64_t seed = 1, double jitter = 0.3) {
  MeshSpec spec;
  spec.shape = shape;
  spec.faces = faces;
  spec.seed = seed;
  spec.jitter = jitter;
  return growth::generateMesh(spec);
}

// Signed volume (divergence theorem): positive for a closed mesh with outward normals.
double volume(const MeshArrays& m) {
  double v = 0;
  for (const auto& f : m.faces) v += (m.vertices[f[0]] * (m.vertices[f[1]] ^ m.vertices[f[2]])) / 6.0;
  return v;
}

// Total length of the edges whose two faces meet at more than `degrees` (dihedral angle between
// their normals).
double sharpEdgeLength(const MeshArrays& m, double degrees) {
  std::map<std::pair<std::uint32_t, std::uint32_t>, std::vector<Vec3d>> normals;
  for (const auto& f : m.faces) {
    Vec3d n = (m.vertices[f[1]] - m.vertices[f[0]]) ^ (m.vertices[f[2]] - m.vertices[f[0]]);
    n = n / n.Norm();
    for (int k = 0; k < 3; ++k) normals[{std::min(f[k], f[(k + 1) % 3]), std::max(f[k], f[(k + 1) % 3])}].push_back(n);
  }
  double length = 0;
  for (const auto& e : normals)
    if (e.second.size() == 2 && e.second[0] * e.second[1] < std::cos(degrees * M_PI / 180))
      length += (m.vertices[e.first.first] - m.vertices[e.first.second]).Norm();
  return length;
}

} // namespace

TEST(MeshGenerator, EveryShapeIsAClean2ManifoldWithItsTopology) {
  for (MeshShape shape : kShapes) {
    SCOPED_TRACE(growth::meshShapeName(shape));
    const MeshArrays m = make(shape, 6000);
    const growth::MeshMeasures r = growth::measure(m);
    const growth::MeshShapeTopology t = growth::shapeTopology(shape);
    EXPECT_NEAR(double(r.faces), 6000.0, 600.0);
    EXPECT_TRUE(r.manifold());
    EXPECT_TRUE(r.consistentlyOriented());
    EXPECT_EQ(r.degenerateFaces, 0u);
    EXPECT_EQ(r.duplicateFaces, 0u);
    EXPECT_EQ(r.selfIntersectingPairs, 0u);
    EXPECT_EQ(r.unreferencedVertices, 0u);
    EXPECT_EQ(r.components, t.components);
    EXPECT_EQ(r.boundaryLoops, t.boundaryLoops);
    EXPECT_EQ(r.genus, t.genus);
    // Irregular: edge lengths spread (a regular grid of one spacing has E_RMS near 0 per direction)
    // and not every triangle alike.
    EXPECT_GT(r.edgeRmsPercent, 15.0);
    EXPECT_GT(r.qualityRmsPercent, 5.0);
    EXPECT_GT(r.minAngleDeg, 2.0);
  }
}

TEST(MeshGenerator, ClosedPartsHaveTheirVolumeOutwardAndTheirCreases) {
  // Exact volumes of the prisms (faces stay flat under the moves); the cylinder's is that of its
  // inscribed polygon, a little below π/4.
  EXPECT_NEAR(volume(make(MeshShape::Box, 4000)), 1.0 * 0.8 * 0.6, 1e-9);
  EXPECT_NEAR(volume(make(MeshShape::LPrism, 4000)), (1 - 0.55 * 0.55) * 0.4, 1e-9);
  EXPECT_NEAR(volume(make(MeshShape::HoledBox, 4000)), (1 - 0.3 * 0.3) * 0.5, 1e-9);
  const double cylinder = volume(make(MeshShape::Cylinder, 4000));
  EXPECT_LT(cylinder, M_PI / 4);
  EXPECT_GT(cylinder, 0.99 * M_PI / 4);
  // Creases stay straight and whole: the box's twelve edges, 4 · (1 + 0.8 + 0.6) long, are edges of
  // the mesh, and no other edge is sharp.
  EXPECT_NEAR(sharpEdgeLength(make(MeshShape::Box, 4000), 45), 9.6, 1e-9);
  // The box with a hole: its outer 12 edges, the hole's 4 vertical edges and the 2 × 4 rims.
  EXPECT_NEAR(sharpEdgeLength(make(MeshShape::HoledBox, 4000), 45), 4 * (1 + 1 + 0.5) + 4 * 0.5 + 8 * 0.3, 1e-9);
  // The sheet is smooth.
  EXPECT_EQ(sharpEdgeLength(make(MeshShape::Sheet, 4000), 45), 0.0);
}

TEST(MeshGenerator, VerticesLieOnTheExactSurface) {
  for (const Vec3d& p : make(MeshShape::Box, 3000).vertices) {
    const double onFace = std::min({std::abs(p[0]), std::abs(p[0] - 1), std::abs(p[1]), std::abs(p[1] - 0.8), std::abs(p[2]),
                                    std::abs(p[2] - 0.6)});
    ASSERT_LT(onFace, 1e-12) << p[0] << " " << p[1] << " " << p[2];
  }
  for (const Vec3d& p : make(MeshShape::Cylinder, 3000).vertices) {
    const double r = std::hypot(p[0], p[1]);
    const bool side = std::abs(r - 0.5) < 1e-12 && p[2] >= 0 && p[2] <= 1;
    const bool cap = (std::abs(p[2]) < 1e-12 || std::abs(p[2] - 1) < 1e-12) && r <= 0.5 + 1e-12;
    ASSERT_TRUE(side || cap) << p[0] << " " << p[1] << " " << p[2];
  }
  for (const Vec3d& p : make(MeshShape::Sheet, 3000).vertices)
    ASSERT_NEAR(p[2], 0.06 * std::sin(2 * M_PI * p[0]) * std::cos(M_PI * p[1]), 1e-12);
}

TEST(MeshGenerator, SeedDecidesTheMeshAndFaceCountFollowsTheRequest) {
  const MeshArrays a = make(MeshShape::HoledBox, 3000, 5), b = make(MeshShape::HoledBox, 3000, 5),
                   c = make(MeshShape::HoledBox, 3000, 6);
  EXPECT_EQ(a.faces, b.faces);
  EXPECT_EQ(a.vertices, b.vertices);
  EXPECT_NE(a.vertices, c.vertices);
  for (size_t faces : {200u, 20000u, 100000u}) {
    const MeshArrays m = make(MeshShape::Cylinder, faces);
    EXPECT_NEAR(double(m.faces.size()) / double(faces), 1.0, 0.1) << faces;
  }
  // Without moves the prisms are still irregular (uneven spacings), and still clean.
  const growth::MeshMeasures still = growth::measure(make(MeshShape::LPrism, 3000, 1, 0.0));
  EXPECT_TRUE(still.manifold());
  EXPECT_EQ(still.selfIntersectingPairs, 0u);
  EXPECT_EQ(still.genus, 0);
}

TEST(MeshGenerator, BadSpecsAreClearErrors) {
  EXPECT_THROW(make(MeshShape::Box, 5), growth::Error);
  EXPECT_THROW(make(MeshShape::Box, 1000, 1, 0.6), growth::Error);
  EXPECT_THROW(make(MeshShape::Box, 1000, 1, -0.1), growth::Error);
  EXPECT_THROW(growth::parseMeshShape("sphere"), growth::Error);
  for (MeshShape s : kShapes) EXPECT_EQ(growth::parseMeshShape(growth::meshShapeName(s)), s);
}
