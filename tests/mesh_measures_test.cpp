#include <growth/meshlab/layer.h>
#include <growth/meshlab/points.h>
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>

#include <common/ml_mesh_type.h>

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <string>
#include <vector>

using growth::MeshMeasures;
using growth::measure;
using Point3d = growth::Vec3d;

namespace {

// Builds a mesh from coordinates and vertex-index triples.
void makeMesh(CMeshO& m, const std::vector<Point3d>& v, const std::vector<std::array<int, 3>>& f) {
  m.Clear();
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(m, v.size());
  for (size_t i = 0; i < v.size(); ++i, ++vi) vi->P() = growth::meshlab::toPoint3f(v[i]);
  // Corners set by hand: Allocator::AddFace asserts they are distinct, and some faces here repeat one.
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(m, f.size());
  for (size_t i = 0; i < f.size(); ++i, ++fi)
    for (int j = 0; j < 3; ++j) fi->V(j) = &m.vert[size_t(f[i][size_t(j)])];
}

// Regular tetrahedron, edge 2·√2, consistently oriented.
void tetrahedron(CMeshO& m, Point3d offset = Point3d(0, 0, 0)) {
  makeMesh(m, {Point3d(1, 1, 1) + offset, Point3d(1, -1, -1) + offset, Point3d(-1, 1, -1) + offset, Point3d(-1, -1, 1) + offset},
           {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}});
}

// The unit square [0,1]² as two right isosceles triangles.
void openSquare(CMeshO& m) {
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1, 1, 0), Point3d(0, 1, 0)}, {{0, 1, 2}, {0, 2, 3}});
}

// A closed torus of n × k quads, each split into two triangles, consistently oriented.
void gridTorus(CMeshO& m, int n, int k) {
  std::vector<Point3d> v;
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const double u = 2 * M_PI * i / n, w = 2 * M_PI * j / k;
      v.push_back(Point3d((2 + std::cos(w)) * std::cos(u), (2 + std::cos(w)) * std::sin(u), std::sin(w)));
    }
  auto id = [&](int i, int j) { return ((i + n) % n) * k + (j + k) % k; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  makeMesh(m, v, f);
}

// A flat grid of n × n quads over [0,1]², split into triangles.
void gridPatch(CMeshO& m, int n, double z = 0) {
  std::vector<Point3d> v;
  std::vector<std::array<int, 3>> f;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) v.push_back(Point3d(double(i) / n, double(j) / n, z));
  auto id = [&](int i, int j) { return i * (n + 1) + j; };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      f.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      f.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  makeMesh(m, v, f);
}

const double kSqrt3 = std::sqrt(3.0);

} // namespace

// --- Single triangles ---

TEST(TriangleShape, EquilateralIsOne) {
  const Point3d a(0, 0, 0), b(1, 0, 0), c(0.5, kSqrt3 / 2, 0);
  EXPECT_NEAR(growth::triangleQuality(a, b, c), 1.0, 1e-12);
  EXPECT_NEAR(growth::triangleQF(a, b, c), 1.0, 1e-12);
  // Scale and position do not matter.
  EXPECT_NEAR(growth::triangleQuality(a * 7 + Point3d(3, 4, 5), b * 7 + Point3d(3, 4, 5), c * 7 + Point3d(3, 4, 5)), 1.0, 1e-12);
}

TEST(TriangleShape, RightIsoscelesHasKnownValues) {
  const Point3d a(0, 0, 0), b(1, 0, 0), c(0, 1, 0);
  EXPECT_NEAR(growth::triangleQuality(a, b, c), kSqrt3 / 2, 1e-12);   // 0.866...
  // QF = √12 · A / (p · d_max), A = 1/2, p = (2 + √2)/2, d_max = √2.
  const double p = (2 + std::sqrt(2.0)) / 2;
  EXPECT_NEAR(growth::triangleQF(a, b, c), std::sqrt(12.0) * 0.5 / (p * std::sqrt(2.0)), 1e-12);
  EXPECT_NEAR(growth::triangleQF(a, b, c), 0.7174389352, 1e-9);
}

TEST(TriangleShape, QFMatchesHeronForm) {
  // eq. 5.1 written out with Heron's product, on a scalene triangle.
  const Point3d a(0, 0, 0), b(3, 0, 0), c(0.5, 2, 0.3);
  const double d1 = (b - a).Norm(), d2 = (c - b).Norm(), d3 = (a - c).Norm();
  const double p = (d1 + d2 + d3) / 2, dmax = std::max({d1, d2, d3});
  const double qf = std::sqrt(12.0) / dmax * std::sqrt((p - d1) * (p - d2) * (p - d3) / p);
  EXPECT_NEAR(growth::triangleQF(a, b, c), qf, 1e-12);
  EXPECT_LT(growth::triangleQF(a, b, c), 1.0);
}

TEST(TriangleShape, DegenerateTrianglesAreZero) {
  const Point3d a(0, 0, 0), b(1, 0, 0), c(2, 0, 0);
  EXPECT_EQ(growth::triangleQuality(a, b, c), 0.0);
  EXPECT_EQ(growth::triangleQF(a, b, c), 0.0);
  EXPECT_EQ(growth::triangleQuality(a, a, a), 0.0);
  EXPECT_EQ(growth::triangleQF(a, a, a), 0.0);
}

// --- Whole meshes with known answers ---

TEST(MeshMeasures, EmptyMeshHasNoNumbers) {
  CMeshO m;
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.vertices, 0u);
  EXPECT_EQ(r.faces, 0u);
  EXPECT_TRUE(std::isnan(r.edgeMean));
  EXPECT_TRUE(std::isnan(r.qualityMean));
  EXPECT_EQ(r.components, 0u);
  EXPECT_NE(r.toJson().find("\"edge_mean\": null"), std::string::npos);
}

TEST(MeshMeasures, RegularTetrahedron) {
  CMeshO m;
  tetrahedron(m);
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.vertices, 4u);
  EXPECT_EQ(r.faces, 4u);
  EXPECT_EQ(r.edges, 6u);
  EXPECT_EQ(r.boundaryEdges, 0u);
  EXPECT_EQ(r.boundaryLoops, 0u);
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.nonManifoldVertices, 0u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.inconsistentEdges, 0u);
  EXPECT_EQ(r.degenerateFaces, 0u);
  EXPECT_EQ(r.duplicateFaces, 0u);
  EXPECT_EQ(r.unreferencedVertices, 0u);
  EXPECT_EQ(r.eulerCharacteristic, 2);
  EXPECT_EQ(r.genus, 0);
  EXPECT_NEAR(r.boxDiagonal, 2 * std::sqrt(3.0), 1e-12);
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.consistentlyOriented());
  const double edge = 2 * std::sqrt(2.0);
  EXPECT_NEAR(r.edgeMean, edge, 1e-6);       // float storage of exact coordinates
  EXPECT_NEAR(r.edgeMin, edge, 1e-6);
  EXPECT_NEAR(r.edgeMax, edge, 1e-6);
  EXPECT_NEAR(r.edgeRmsPercent, 0.0, 1e-6);
  EXPECT_NEAR(r.minVertexDistance, edge, 1e-6);
  EXPECT_NEAR(r.qualityMean, 1.0, 1e-9);
  EXPECT_NEAR(r.qualityRmsPercent, 0.0, 1e-6);
  EXPECT_NEAR(r.qfMean, 1.0, 1e-9);
  EXPECT_NEAR(r.minAngleDeg, 60.0, 1e-6);
  EXPECT_NEAR(r.maxAngleDeg, 60.0, 1e-6);
}

TEST(MeshMeasures, OpenSquare) {
  CMeshO m;
  openSquare(m);
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.faces, 2u);
  EXPECT_EQ(r.edges, 5u);
  EXPECT_EQ(r.boundaryEdges, 4u);
  EXPECT_EQ(r.boundaryLoops, 1u);
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.nonManifoldVertices, 0u);   // boundary vertices with one open fan are manifold
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.inconsistentEdges, 0u);
  EXPECT_EQ(r.eulerCharacteristic, 1);
  EXPECT_EQ(r.genus, 0);
  const double mean = (4 + std::sqrt(2.0)) / 5;
  EXPECT_NEAR(r.edgeMean, mean, 1e-12);
  const double rms = std::sqrt((4 * (1 - mean) * (1 - mean) + (std::sqrt(2.0) - mean) * (std::sqrt(2.0) - mean)) / 5);
  EXPECT_NEAR(r.edgeRmsPercent, 100 * rms / mean, 1e-9);
  EXPECT_NEAR(r.edgeMin, 1.0, 1e-12);
  EXPECT_NEAR(r.edgeMax, std::sqrt(2.0), 1e-7);
  EXPECT_NEAR(r.qualityMean, kSqrt3 / 2, 1e-9);
  EXPECT_NEAR(r.qualityRmsPercent, 0.0, 1e-6);
  EXPECT_NEAR(r.qfMean, 0.7174389352, 1e-8);
  EXPECT_NEAR(r.minAngleDeg, 45.0, 1e-6);
  EXPECT_NEAR(r.maxAngleDeg, 90.0, 1e-6);
  EXPECT_EQ(growth::countBoundaryEdges(m), 4u);
  EXPECT_EQ(growth::countBoundaryLoops(m), 1u);
  EXPECT_TRUE(growth::isConsistentlyOriented(m));
}

TEST(MeshMeasures, EquilateralTriangle) {
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0.5, kSqrt3 / 2, 0)}, {{0, 1, 2}});
  const MeshMeasures r = measure(m);
  EXPECT_NEAR(r.qualityMean, 1.0, 1e-6);
  EXPECT_NEAR(r.qfMean, 1.0, 1e-6);
  EXPECT_NEAR(r.minAngleDeg, 60.0, 1e-4);
  EXPECT_EQ(r.boundaryEdges, 3u);
  EXPECT_EQ(r.boundaryLoops, 1u);
  EXPECT_EQ(r.components, 1u);
  // Histograms: three angles near 60°, one Q_t in the last bin (1 is included), three edges.
  EXPECT_EQ(r.angleHistogram.total(), 3u);
  EXPECT_EQ(r.angleHistogram.counts[59] + r.angleHistogram.counts[60], 3u);
  EXPECT_EQ(r.qualityHistogram.counts.back() + r.qualityHistogram.counts[r.qualityHistogram.counts.size() - 2], 1u);
  EXPECT_EQ(r.qualityHistogram.total(), 1u);
  EXPECT_EQ(r.edgeHistogram.total(), 3u);
  EXPECT_EQ(r.edgeHistogram.above, 0u);
}

TEST(MeshMeasures, BowTieVertexIsNonManifold) {
  // Two triangles sharing only vertex 0.
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1, 1, 0), Point3d(-1, 0, 0), Point3d(-1, -1, 0)},
           {{0, 1, 2}, {0, 3, 4}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.nonManifoldVertices, 1u);
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.boundaryEdges, 6u);
  EXPECT_EQ(r.boundaryLoops, 2u);   // one around each triangle, not one figure-eight
  EXPECT_EQ(r.components, 2u);
  EXPECT_FALSE(r.manifold());
  EXPECT_EQ(growth::countNonManifoldVertices(m), 1u);
}

TEST(MeshMeasures, BowTieOfFansIsNonManifold) {
  // Two open fans of two triangles each at vertex 0: every edge manifold, the vertex not.
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1, 1, 0), Point3d(0, 1, 0.2), Point3d(-1, 0, 0),
               Point3d(-1, -1, 0), Point3d(0, -1, 0.2)},
           {{0, 1, 2}, {0, 2, 3}, {0, 4, 5}, {0, 5, 6}});
  EXPECT_EQ(growth::countNonManifoldVertices(m), 1u);
  EXPECT_EQ(growth::countNonManifoldEdges(m), 0u);
  EXPECT_EQ(growth::countBoundaryLoops(m), 2u);
  // Closing one of the fans into a full disk does not make the vertex manifold: still two fans.
  CMeshO closed;
  makeMesh(closed, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(-1, 0, 0), Point3d(0, -1, 0),
                    Point3d(0, 0, 1), Point3d(0.3, 0.3, 1)},
           {{0, 1, 2}, {0, 2, 3}, {0, 3, 4}, {0, 4, 1}, {0, 5, 6}});
  EXPECT_EQ(growth::countNonManifoldVertices(closed), 1u);
  EXPECT_EQ(growth::countBoundaryLoops(closed), 2u);
}

TEST(MeshMeasures, TwoTetrahedraTouchingAtAVertex) {
  // Closed surfaces sharing one vertex: no boundary, no non-manifold edge, one non-manifold vertex.
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(0, 0, 1), Point3d(-1, 0, 0),
               Point3d(0, -1, 0), Point3d(0, 0, -1)},
           {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.boundaryEdges, 0u);
  EXPECT_EQ(r.nonManifoldEdges, 0u);
  EXPECT_EQ(r.nonManifoldVertices, 1u);
  EXPECT_EQ(r.components, 2u);
  EXPECT_EQ(r.inconsistentEdges, 0u);
}

TEST(MeshMeasures, ThreeTrianglesOnOneEdge) {
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0.5, 1, 0), Point3d(0.5, -1, 0), Point3d(0.5, 0, 1)},
           {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.nonManifoldEdges, 1u);
  EXPECT_EQ(r.nonManifoldVertices, 2u);   // both ends of the non-manifold edge
  EXPECT_EQ(r.boundaryEdges, 6u);
  EXPECT_EQ(r.edges, 7u);
  EXPECT_EQ(r.components, 1u);
  EXPECT_EQ(r.inconsistentEdges, 0u);     // only two-face edges have an orientation to compare
  EXPECT_GE(r.boundaryLoops, 1u);
  EXPECT_FALSE(r.manifold());
  EXPECT_EQ(growth::countNonManifoldEdges(m), 1u);
}

TEST(MeshMeasures, FlippedFaceIsInconsistent) {
  CMeshO square;
  makeMesh(square, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1, 1, 0), Point3d(0, 1, 0)}, {{0, 1, 2}, {0, 3, 2}});
  EXPECT_EQ(growth::countInconsistentEdges(square), 1u);
  EXPECT_FALSE(growth::isConsistentlyOriented(square));
  EXPECT_EQ(growth::countBoundaryLoops(square), 1u);   // the loop does not depend on orientation

  CMeshO tet;
  makeMesh(tet, {Point3d(1, 1, 1), Point3d(1, -1, -1), Point3d(-1, 1, -1), Point3d(-1, -1, 1)},
           {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 2, 3}});   // last face flipped
  const MeshMeasures r = measure(tet);
  EXPECT_EQ(r.inconsistentEdges, 3u);
  EXPECT_EQ(r.boundaryEdges, 0u);
  EXPECT_EQ(r.nonManifoldVertices, 0u);   // orientation does not change the fans
  EXPECT_FALSE(r.consistentlyOriented());
}

TEST(MeshMeasures, DegenerateFaces) {
  CMeshO m;
  // Face 1 repeats a vertex, face 2 is collinear (zero area), face 0 is fine.
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(2, 0, 0), Point3d(3, 0, 0)},
           {{0, 1, 2}, {0, 0, 1}, {1, 3, 4}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.faces, 3u);
  EXPECT_EQ(r.degenerateFaces, 2u);
  EXPECT_EQ(growth::countDegenerateFaces(m), 2u);
  EXPECT_NEAR(r.qualityMin, 0.0, 1e-12);              // the collinear face takes part with Q_t = 0
  EXPECT_NEAR(r.qualityMean, (kSqrt3 / 2) / 2, 1e-7); // the repeated-vertex face does not
  EXPECT_NEAR(r.minAngleDeg, 0.0, 1e-9);
  EXPECT_NEAR(r.maxAngleDeg, 180.0, 1e-9);

  // Two distinct vertices at the same place give a zero-area face too.
  CMeshO coincident;
  makeMesh(coincident, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(1, 0, 0)}, {{0, 1, 2}});
  EXPECT_EQ(growth::countDegenerateFaces(coincident), 1u);
  EXPECT_NEAR(measure(coincident).minVertexDistance, 0.0, 1e-12);

  // A thin but real triangle is not degenerate.
  CMeshO thin;
  makeMesh(thin, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0.5, 1e-4, 0)}, {{0, 1, 2}});
  EXPECT_EQ(growth::countDegenerateFaces(thin), 0u);
}

TEST(MeshMeasures, DuplicateFaces) {
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(1, 1, 0)},
           {{0, 1, 2}, {0, 1, 2}, {2, 1, 0}, {1, 3, 2}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.duplicateFaces, 2u);   // same vertex set in either orientation
  EXPECT_EQ(growth::countDuplicateFaces(m), 2u);
  EXPECT_EQ(r.nonManifoldEdges, 3u);  // the tripled triangle's edges have three or four faces
  EXPECT_EQ(r.degenerateFaces, 0u);
  EXPECT_EQ(r.selfIntersectingPairs, 3u); // each two of the three copies; the fourth face is flat beside them
}

TEST(MeshMeasures, SelfIntersectingPairs) {
  // A closed torus has none.
  CMeshO torus;
  gridTorus(torus, 24, 12);
  EXPECT_EQ(measure(torus).selfIntersectingPairs, 0u);
  EXPECT_EQ(growth::countSelfIntersections(torus), 0u);
  // Vertex 0, on the outer equator at (3, 0, 0), pulled across the tube to (0.5, 0, 0): its six
  // faces cross the inner side of the tube.
  torus.vert[0].P() = vcg::Point3f(0.5f, 0, 0);
  const MeshMeasures r = measure(torus);
  EXPECT_GT(r.selfIntersectingPairs, 0u);
  EXPECT_EQ(growth::countSelfIntersections(torus), r.selfIntersectingPairs);
  const std::string json = r.toJson();
  EXPECT_NE(json.find("\"self_intersecting_pairs\": " + std::to_string(r.selfIntersectingPairs)), std::string::npos);
  EXPECT_LT(json.find("\"duplicate_faces\""), json.find("\"self_intersecting_pairs\""));
  // Deleted faces take no part: without the moved vertex's faces there is none left.
  for (auto& f : torus.face)
    if (f.V(0) == &torus.vert[0] || f.V(1) == &torus.vert[0] || f.V(2) == &torus.vert[0])
      vcg::tri::Allocator<CMeshO>::DeleteFace(torus, f);
  EXPECT_EQ(growth::countSelfIntersections(torus), 0u);
  EXPECT_EQ(measure(torus).selfIntersectingPairs, 0u);

  // Two triangles crossing, and the same two apart.
  CMeshO crossing;
  makeMesh(crossing, {Point3d(0, 0, 0), Point3d(2, 0, 0), Point3d(0, 2, 0), Point3d(0.5, 0.5, -1), Point3d(0.5, 0.5, 1), Point3d(2, 2, 0)},
           {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(growth::countSelfIntersections(crossing), 1u);
  crossing.vert[3].P() = vcg::Point3f(0.5f, 0.5f, 0.25f);
  EXPECT_EQ(growth::countSelfIntersections(crossing), 0u);
}

TEST(MeshMeasures, DeletedElementsAreIgnoredAndUnreferencedCounted) {
  CMeshO m;
  tetrahedron(m);
  vcg::tri::Allocator<CMeshO>::DeleteFace(m, m.face[3]);
  auto v = vcg::tri::Allocator<CMeshO>::AddVertices(m, 2);
  v->P() = vcg::Point3f(5, 5, 5);
  vcg::tri::Allocator<CMeshO>::DeleteVertex(m, *v);
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.faces, 3u);
  EXPECT_EQ(r.vertices, 5u);
  EXPECT_EQ(r.unreferencedVertices, 1u);
  EXPECT_EQ(r.boundaryEdges, 3u);
  EXPECT_EQ(r.boundaryLoops, 1u);
  EXPECT_EQ(r.nonManifoldVertices, 0u);
}

TEST(MeshMeasures, AnnulusHasTwoBoundaryLoops) {
  // Square ring: outer square 0-3, inner square 4-7, eight triangles.
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(3, 0, 0), Point3d(3, 3, 0), Point3d(0, 3, 0), Point3d(1, 1, 0),
               Point3d(2, 1, 0), Point3d(2, 2, 0), Point3d(1, 2, 0)},
           {{0, 1, 5}, {0, 5, 4}, {1, 2, 6}, {1, 6, 5}, {2, 3, 7}, {2, 7, 6}, {3, 0, 4}, {3, 4, 7}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.boundaryEdges, 8u);
  EXPECT_EQ(r.boundaryLoops, 2u);
  EXPECT_EQ(r.eulerCharacteristic, 0);
  EXPECT_EQ(r.genus, 0);  // an annulus: χ = 0 from its two loops, not from a handle
  EXPECT_EQ(r.nonManifoldVertices, 0u);
  EXPECT_EQ(r.inconsistentEdges, 0u);
  EXPECT_EQ(r.components, 1u);
}

// A closed tetrahedron whose vertex 3 lies between 0 and 1: face (0, 1, 3) has zero area, yet it is
// a face of a sphere, and the genus is still defined (the scans' meshes have such faces in float).
TEST(MeshMeasures, GenusCountsZeroAreaFaces) {
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(2, 0, 0), Point3d(1, 1, 1), Point3d(1, 0, 0)},
           {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}});
  const MeshMeasures r = measure(m);
  EXPECT_EQ(r.degenerateFaces, 1u);
  EXPECT_EQ(r.eulerCharacteristic, 2);
  EXPECT_TRUE(r.manifold());
  EXPECT_TRUE(r.consistentlyOriented());
  EXPECT_EQ(r.genus, 0);
}

TEST(MeshMeasures, SeparateTrianglesAreSeparateComponents) {
  CMeshO m;
  makeMesh(m, {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(5, 0, 0), Point3d(6, 0, 0), Point3d(5, 1, 0)},
           {{0, 1, 2}, {3, 4, 5}});
  EXPECT_EQ(growth::countComponents(m), 2u);
  EXPECT_EQ(growth::countBoundaryLoops(m), 2u);
}

TEST(MeshMeasures, LargerClosedAndOpenGrids) {
  CMeshO torus;
  gridTorus(torus, 40, 20);
  const MeshMeasures t = measure(torus);
  EXPECT_EQ(t.faces, 1600u);
  EXPECT_EQ(t.eulerCharacteristic, 0);
  EXPECT_EQ(t.genus, 1);
  EXPECT_EQ(t.boundaryEdges, 0u);
  EXPECT_EQ(t.boundaryLoops, 0u);
  EXPECT_EQ(t.components, 1u);
  EXPECT_TRUE(t.manifold());
  EXPECT_TRUE(t.consistentlyOriented());

  CMeshO patch;
  gridPatch(patch, 30);
  const MeshMeasures p = measure(patch);
  EXPECT_EQ(p.boundaryEdges, 120u);
  EXPECT_EQ(p.boundaryLoops, 1u);
  EXPECT_EQ(p.eulerCharacteristic, 1);
  EXPECT_EQ(p.genus, 0);
  EXPECT_TRUE(p.manifold());
  EXPECT_NEAR(p.qualityMean, kSqrt3 / 2, 1e-6);
  EXPECT_NEAR(p.minVertexDistance, 1.0 / 30, 1e-6);

  // Deleting the two quads (14,15) and (15,14) of the four around inner vertex (15,15) leaves the
  // quads (14,14) and (15,15) touching only there: two open fans. Split into its fans, the vertex
  // joins the borders of the two deleted quads into one loop (like the bow-tie, where splitting
  // separates them), so with the outer border two loops.
  const int n = 30, i = 15, j = 15;
  auto faceIndex = [&](int qi, int qj, int half) { return size_t(2 * (qi * n + qj) + half); };
  vcg::tri::Allocator<CMeshO>::DeleteFace(patch, patch.face[faceIndex(i - 1, j, 0)]);
  vcg::tri::Allocator<CMeshO>::DeleteFace(patch, patch.face[faceIndex(i - 1, j, 1)]);
  vcg::tri::Allocator<CMeshO>::DeleteFace(patch, patch.face[faceIndex(i, j - 1, 0)]);
  vcg::tri::Allocator<CMeshO>::DeleteFace(patch, patch.face[faceIndex(i, j - 1, 1)]);
  const MeshMeasures cut = measure(patch);
  EXPECT_EQ(cut.nonManifoldVertices, 1u);
  EXPECT_EQ(cut.boundaryLoops, 2u);
  EXPECT_EQ(cut.boundaryEdges, 120u + 8u);
  EXPECT_EQ(cut.genus, -1);  // not a surface there: no genus
}

TEST(MeshMeasures, HistogramsCountEveryValue) {
  CMeshO patch;
  gridPatch(patch, 10);
  growth::MeasureOptions o;
  o.edgeHistogramMax = 0.12;   // the diagonals (0.1414) are above the range, and counted there
  const MeshMeasures r = measure(patch, nullptr, o);
  EXPECT_EQ(r.angleHistogram.total(), 3 * r.faces);
  EXPECT_EQ(r.qualityHistogram.total(), r.faces);
  EXPECT_EQ(r.edges, 320u);
  EXPECT_EQ(r.edgeHistogram.total(), r.edges);
  EXPECT_EQ(r.edgeHistogram.above, 100u);
  EXPECT_EQ(r.edgeHistogram.below, 0u);
  EXPECT_EQ(r.edgeHistogram.counts[83], 220u);   // length 0.1 in bins of 0.0012
  // Right isosceles triangles: angles 45 and 90 only.
  EXPECT_EQ(r.angleHistogram.counts[45] + r.angleHistogram.counts[44], 2 * r.faces);
  EXPECT_EQ(r.angleHistogram.counts[90] + r.angleHistogram.counts[89], r.faces);
}

// --- Distance of the input points to the mesh ---

TEST(MeshDistance, KnownDistancesToASquare) {
  CMeshO m;
  openSquare(m);
  const growth::MeshDistance d(growth::meshlab::meshArrays(m));
  EXPECT_NEAR(d.distance(Point3d(0.25, 0.25, 0)), 0.0, 1e-12);
  EXPECT_NEAR(d.distance(Point3d(0.5, 0.5, 0.3)), 0.3, 1e-12);
  EXPECT_NEAR(d.distance(Point3d(0.5, 0.5, -0.3)), 0.3, 1e-12);
  EXPECT_NEAR(d.distance(Point3d(2, 0.5, 0)), 1.0, 1e-12);          // to the edge x = 1
  EXPECT_NEAR(d.distance(Point3d(2, 2, 0)), std::sqrt(2.0), 1e-12); // to the corner
  EXPECT_NEAR(d.distance(Point3d(-3, 0.5, 4)), 5.0, 1e-12);
}

TEST(MeshDistance, EmptyMeshIsInfinitelyFar) {
  CMeshO m;
  const growth::MeshDistance d(growth::meshlab::meshArrays(m));
  EXPECT_TRUE(d.empty());
  EXPECT_TRUE(std::isinf(d.distance(Point3d(0, 0, 0))));
}

TEST(MeshDistance, HierarchyAgreesWithBruteForce) {
  // Random triangles (some degenerate) and random query points near and far.
  growth::Random rng(7);
  std::vector<Point3d> v;
  std::vector<std::array<int, 3>> f;
  for (int t = 0; t < 600; ++t) {
    const Point3d c(rng.uniform(-1, 1), rng.uniform(-1, 1), rng.uniform(-1, 1));
    const int base = int(v.size());
    v.push_back(c);
    v.push_back(c + rng.unitVector() * 0.1);
    v.push_back(t % 50 == 0 ? c + (v.back() - c) * 2.0 : c + rng.unitVector() * 0.1);   // every 50th collinear
    f.push_back({base, base + 1, base + 2});
  }
  CMeshO m;
  makeMesh(m, v, f);
  const growth::MeshDistance index(growth::meshlab::meshArrays(m));
  // Brute force from the float-stored coordinates, as the index sees them.
  std::vector<Point3d> stored;
  for (const auto& vert : m.vert) stored.push_back(Point3d::Construct(vert.cP()));
  auto segment = [](const Point3d& p, const Point3d& a, const Point3d& b) {
    const Point3d ab = b - a;
    double t = ab.SquaredNorm() > 0 ? ((p - a) * ab) / ab.SquaredNorm() : 0;
    t = std::min(1.0, std::max(0.0, t));
    return (p - (a + ab * t)).Norm();
  };
  auto triangle = [&](const Point3d& p, const Point3d& a, const Point3d& b, const Point3d& c) {
    double best = std::min({segment(p, a, b), segment(p, b, c), segment(p, c, a)});
    Point3d n = (b - a) ^ (c - a);
    if (n.Norm() > 1e-12) {
      n /= n.Norm();
      const Point3d q = p - n * ((p - a) * n);
      const double s1 = ((b - a) ^ (q - a)) * n, s2 = ((c - b) ^ (q - b)) * n, s3 = ((a - c) ^ (q - c)) * n;
      if ((s1 >= 0 && s2 >= 0 && s3 >= 0) || (s1 <= 0 && s2 <= 0 && s3 <= 0)) best = std::min(best, (p - q).Norm());
    }
    return best;
  };
  int hint = -1;
  for (int i = 0; i < 300; ++i) {
    const double r = i < 200 ? 1.2 : 5.0;
    const Point3d p(rng.uniform(-r, r), rng.uniform(-r, r), rng.uniform(-r, r));
    double brute = std::numeric_limits<double>::infinity();
    for (const auto& t : f) brute = std::min(brute, triangle(p, stored[size_t(t[0])], stored[size_t(t[1])], stored[size_t(t[2])]));
    ASSERT_NEAR(index.distance(p), brute, 1e-12 * (1 + brute)) << "query " << i;
    // A hint (the previous query's triangle, far from this one) changes nothing but the speed.
    ASSERT_NEAR(index.distance(p, &hint), brute, 1e-12 * (1 + brute)) << "query " << i << " with hint";
    ASSERT_GE(hint, 0);
  }
}

TEST(MeshMeasures, CloudDistanceAndMuD) {
  // A 10 × 10 grid of points with spacing 0.1, 0.02 above the unit square: every point is 0.02 from
  // the mesh, the mean spacing is 0.1, so μd = 20 %.
  CMeshO m;
  gridPatch(m, 5);
  std::vector<Point3d> cloud;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) cloud.push_back(Point3d(0.05 + 0.1 * i, 0.05 + 0.1 * j, 0.02));
  const MeshMeasures r = measure(m, &cloud);
  EXPECT_TRUE(r.hasCloud);
  EXPECT_EQ(r.cloudPoints, 100u);
  EXPECT_NEAR(r.cloudSpacing, 0.1, 1e-9);
  EXPECT_NEAR(r.distanceMean, 0.02, 1e-7);
  EXPECT_NEAR(r.distanceMax, 0.02, 1e-7);
  EXPECT_NEAR(r.muDPercent, 20.0, 1e-4);
  EXPECT_EQ(r.pointsFartherThanSpacing, 0u);
  // One point far away (an "unmeshed" point) moves the mean and the maximum.
  cloud.push_back(Point3d(0.5, 0.5, 1.0));
  const MeshMeasures s = measure(m, &cloud);
  EXPECT_NEAR(s.distanceMax, 1.0, 1e-7);
  EXPECT_NEAR(s.distanceMean, (100 * 0.02 + 1.0) / 101, 1e-7);
  EXPECT_EQ(s.pointsFartherThanSpacing, 1u);
  EXPECT_NE(s.toJson().find("\"mu_d_percent\""), std::string::npos);
}

TEST(MeshMeasures, InterpolatingMeshHasZeroDistance) {
  // The vertices of a mesh, used as its cloud, lie on it.
  CMeshO m;
  gridTorus(m, 30, 15);
  std::vector<Point3d> cloud;
  for (const auto& v : m.vert) cloud.push_back(Point3d::Construct(v.cP()));
  const MeshMeasures r = measure(m, &cloud);
  EXPECT_NEAR(r.distanceMax, 0.0, 1e-12);
  EXPECT_NEAR(r.muDPercent, 0.0, 1e-9);
}

// --- Per-component topology and the distance between two surfaces (the remeshing benchmark's) ---

namespace {

using growth::MeshArrays;

// Appends `add` to `mesh` (its vertices renumbered after mesh's).
void append(MeshArrays& mesh, const MeshArrays& add) {
  const std::uint32_t base = std::uint32_t(mesh.vertices.size());
  mesh.vertices.insert(mesh.vertices.end(), add.vertices.begin(), add.vertices.end());
  for (auto f : add.faces) mesh.faces.push_back({f[0] + base, f[1] + base, f[2] + base});
}

MeshArrays torusArrays(int n, int k, Point3d offset) {
  MeshArrays m;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      const double u = 2 * M_PI * i / n, w = 2 * M_PI * j / k;
      m.vertices.push_back(Point3d((2 + std::cos(w)) * std::cos(u), (2 + std::cos(w)) * std::sin(u), std::sin(w)) + offset);
    }
  auto id = [&](int i, int j) { return std::uint32_t(((i + n) % n) * k + (j + k) % k); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < k; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

// A disk of `rings` rings of 6·r vertices around a centre (a triangulated hexagon), in the plane z.
MeshArrays diskArrays(int rings, Point3d offset) {
  MeshArrays m;
  m.vertices.push_back(offset);
  std::vector<std::vector<std::uint32_t>> ring{{0}};
  for (int r = 1; r <= rings; ++r) {
    ring.emplace_back();
    for (int j = 0; j < 6 * r; ++j) {
      const double t = 2 * M_PI * j / (6 * r);
      ring.back().push_back(std::uint32_t(m.vertices.size()));
      m.vertices.push_back(offset + Point3d(r * std::cos(t), r * std::sin(t), 0));
    }
  }
  // Between rings r−1 and r: each of the 6 sectors has r outer and r−1 inner vertices (plus the
  // next sector's first): a strip of 2r − 1 triangles.
  for (int r = 1; r <= rings; ++r) {
    const auto& in = ring[size_t(r - 1)];
    const auto& out = ring[size_t(r)];
    for (int s = 0; s < 6; ++s)
      for (int j = 0; j < r; ++j) {
        const std::uint32_t o0 = out[size_t(s * r + j)], o1 = out[size_t((s * r + j + 1) % (6 * r))];
        const std::uint32_t i0 = r == 1 ? in[0] : in[size_t((s * (r - 1) + j) % (6 * (r - 1)))];
        m.faces.push_back({i0, o0, o1});
        if (j + 1 < r) {
          const std::uint32_t i1 = in[size_t((s * (r - 1) + j + 1) % (6 * (r - 1)))];
          m.faces.push_back({i0, o1, i1});
        }
      }
  }
  return m;
}

MeshArrays squareArrays(int n, double width, double z) {
  MeshArrays m;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) m.vertices.push_back(Point3d(width * i / n, double(j) / n, z));
  auto id = [&](int i, int j) { return std::uint32_t(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return m;
}

} // namespace

TEST(ComponentTopology, TorusDiskAndTetrahedronEachHaveTheirOwnGenusAndLoops) {
  const MeshArrays disk = diskArrays(5, Point3d(20, 0, 0));
  {
    const std::vector<growth::ComponentTopology> c = growth::componentTopology(disk);
    ASSERT_EQ(c.size(), 1u);
    EXPECT_EQ(c[0].faces, 150u);             // 6·r² triangles
    EXPECT_EQ(c[0].vertices, 91u);           // 1 + 3·r·(r + 1)
    EXPECT_EQ(c[0].eulerCharacteristic, 1);
    EXPECT_EQ(c[0].boundaryLoops, 1u);
    EXPECT_EQ(c[0].genus, 0);
  }
  MeshArrays all = torusArrays(30, 12, Point3d(0, 0, 0));   // 720 faces
  append(all, disk);                                        // 150 faces
  MeshArrays tet;
  tet.vertices = {Point3d(1, 1, 1), Point3d(1, -1, -1), Point3d(-1, 1, -1), Point3d(-1, -1, 1)};
  for (auto& p : tet.vertices) p = p + Point3d(0, 20, 0);
  tet.faces = {{0, 1, 2}, {0, 3, 1}, {0, 2, 3}, {1, 3, 2}};
  append(all, tet);
  const std::vector<growth::ComponentTopology> c = growth::componentTopology(all);
  ASSERT_EQ(c.size(), 3u);   // largest first
  EXPECT_EQ(c[0].faces, 720u);
  EXPECT_EQ(c[0].genus, 1);
  EXPECT_EQ(c[0].boundaryLoops, 0u);
  EXPECT_EQ(c[0].eulerCharacteristic, 0);
  EXPECT_EQ(c[1].faces, 150u);
  EXPECT_EQ(c[1].genus, 0);
  EXPECT_EQ(c[1].boundaryLoops, 1u);
  EXPECT_EQ(c[2].faces, 4u);
  EXPECT_EQ(c[2].genus, 0);
  EXPECT_EQ(c[2].eulerCharacteristic, 2);
  const MeshMeasures m = growth::measure(all);
  EXPECT_EQ(m.genus, 1);     // the sum
  EXPECT_EQ(m.boundaryLoops, 1u);
  ASSERT_EQ(m.perComponent.size(), 3u);
  EXPECT_NE(m.toJson().find("\"genus_per_component\": [1, 0, 0]"), std::string::npos) << m.toJson();
  EXPECT_NE(m.toJson().find("\"boundary_loops_per_component\": [0, 1, 0]"), std::string::npos);
}

TEST(ComponentTopology, AnnulusAndTwoHandledTorusPairs) {
  // Two tori: genus 1 each, summed 2; a disk with its centre fan removed is an annulus: 2 loops.
  MeshArrays two = torusArrays(20, 10, Point3d(0, 0, 0));
  append(two, torusArrays(24, 10, Point3d(10, 0, 0)));
  MeshArrays annulus = diskArrays(4, Point3d(0, 20, 0));
  annulus.faces.erase(annulus.faces.begin(), annulus.faces.begin() + 6);   // the six around the centre
  append(two, annulus);
  const std::vector<growth::ComponentTopology> c = growth::componentTopology(two);
  ASSERT_EQ(c.size(), 3u);
  EXPECT_EQ(c[0].faces, 480u);
  EXPECT_EQ(c[0].genus, 1);
  EXPECT_EQ(c[1].faces, 400u);
  EXPECT_EQ(c[1].genus, 1);
  EXPECT_EQ(c[2].boundaryLoops, 2u);
  EXPECT_EQ(c[2].genus, 0);
  EXPECT_EQ(growth::measure(two).genus, 2);
}

TEST(ComponentTopology, NoGenusWithoutASurface) {
  // Three triangles on one edge: not a surface, so no component has a genus.
  MeshArrays m;
  m.vertices = {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(0, -1, 0), Point3d(0, 0, 1)};
  m.faces = {{0, 1, 2}, {1, 0, 3}, {0, 1, 4}};
  const std::vector<growth::ComponentTopology> c = growth::componentTopology(m);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].genus, -1);
  EXPECT_TRUE(growth::componentTopology(MeshArrays()).empty());
}

TEST(SurfaceDistance, ParallelSquaresAreTheirGapApartBothWays) {
  const MeshArrays a = squareArrays(10, 1, 0), b = squareArrays(7, 1, 0.25);
  for (const auto& s : {growth::surfaceDistance(a, b), growth::surfaceDistance(b, a)}) {
    EXPECT_NEAR(s.mean, 0.25, 1e-12);
    EXPECT_NEAR(s.max, 0.25, 1e-12);
    EXPECT_NEAR(s.vertexMax, 0.25, 1e-12);
  }
  const growth::SurfaceDistance s = growth::surfaceDistance(a, b);
  EXPECT_EQ(s.vertexSamples, 121u);
  EXPECT_EQ(s.samples, 121u + 200u);   // the vertices and one point per face
}

TEST(SurfaceDistance, LongerSquareIsFartherFromTheShorterThanTheOtherWay) {
  // [0,2]×[0,1] against [0,1]² in one plane: the shorter lies on the longer (distance 0); from the
  // longer, a point at x is max(0, x − 1) away: mean 1/4 over its area, max 1 (its far edge).
  const MeshArrays shortSquare = squareArrays(20, 1, 0), longSquare = squareArrays(40, 2, 0);
  const growth::SurfaceDistance in = growth::surfaceDistance(shortSquare, longSquare);
  EXPECT_NEAR(in.max, 0, 1e-12);
  EXPECT_NEAR(in.mean, 0, 1e-12);
  const growth::SurfaceDistance out = growth::surfaceDistance(longSquare, shortSquare);
  EXPECT_NEAR(out.max, 1, 1e-12);
  EXPECT_NEAR(out.vertexMax, 1, 1e-12);
  EXPECT_NEAR(out.mean, 0.25, 0.02);   // vertices (mean 0.25 on this grid) and 3,200 random points
}

TEST(SurfaceDistance, SamplesLieOnTheSurfaceByAreaAndRepeatWithTheSeed) {
  // Two triangles of areas 1/2 and 3/2 side by side: a quarter of the random points in the first.
  MeshArrays m;
  m.vertices = {Point3d(0, 0, 0), Point3d(1, 0, 0), Point3d(0, 1, 0), Point3d(1, 3, 0), Point3d(0, 4, 0)};
  m.faces = {{0, 1, 2}, {1, 3, 2}};
  m.vertices.push_back(Point3d(9, 9, 9));   // used by no face: not a sample
  size_t vertexSamples = 0;
  const std::vector<Point3d> s = growth::sampleSurface(m, 8000, 7, &vertexSamples);
  ASSERT_EQ(vertexSamples, 4u);
  ASSERT_EQ(s.size(), 8004u);
  size_t first = 0;
  const growth::MeshDistance index(m);
  for (size_t i = vertexSamples; i < s.size(); ++i) {
    EXPECT_LT(index.distance(s[i]), 1e-12);
    if (s[i][0] + s[i][1] <= 1) ++first;
  }
  EXPECT_NEAR(double(first) / 8000, 0.25, 0.02);
  EXPECT_EQ(growth::sampleSurface(m, 100, 7), growth::sampleSurface(m, 100, 7));
  EXPECT_NE(growth::sampleSurface(m, 100, 7), growth::sampleSurface(m, 100, 8));
  EXPECT_TRUE(std::isnan(growth::surfaceDistance(m, MeshArrays()).max));
}
