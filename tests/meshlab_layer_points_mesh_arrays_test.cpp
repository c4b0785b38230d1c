// The MeshLab side of the engines' arrays (growth/mesh_arrays.h, growth/meshlab/layer.h,
// growth/meshlab/points.h): a layer read into a CloudArrays skips deleted vertices and keeps each
// point's layer index and normal; a MeshArrays written into a layer keeps its vertices, faces and
// quality; a layer read back as a MeshArrays renumbers its live vertices.
#include <growth/mesh_arrays.h>
#include <growth/meshlab/layer.h>
#include <growth/meshlab/points.h>

#include <vcg/complex/allocate.h>

#include <gtest/gtest.h>

namespace {

using growth::Vec3d;

TEST(MeshlabLayer, ReadLayerSkipsDeletedVerticesAndKeepsIndicesAndNormals) {
  CMeshO m;
  vcg::tri::Allocator<CMeshO>::AddVertices(m, 3);
  for (int i = 0; i < 3; ++i) {
    m.vert[i].P() = CMeshO::CoordType(float(i), 0.5f, -1.25f);
    m.vert[i].N() = CMeshO::CoordType(0, 0, float(i + 1));
  }
  vcg::tri::Allocator<CMeshO>::DeleteVertex(m, m.vert[1]);
  const growth::CloudArrays c = growth::meshlab::readLayer(m);
  ASSERT_EQ(c.points.size(), 2u);
  ASSERT_EQ(c.vertexIndex.size(), 2u);
  EXPECT_EQ(c.vertexIndex[0], 0);
  EXPECT_EQ(c.vertexIndex[1], 2);
  EXPECT_EQ(c.points[1], Vec3d(2.0, 0.5, -1.25));
  ASSERT_EQ(c.normals.size(), 2u);
  EXPECT_EQ(c.normals[1], Vec3d(0, 0, 3));
  EXPECT_EQ(c.layerFaces, 0u);
}

TEST(MeshlabLayer, WrittenMeshReadsBackWithItsFacesAndQuality) {
  growth::MeshArrays a;
  a.vertices = {Vec3d(0, 0, 0), Vec3d(1, 0, 0), Vec3d(0, 1, 0), Vec3d(0, 0, 1)};
  a.faces = {{0, 2, 1}, {0, 1, 3}, {1, 2, 3}, {0, 3, 2}};
  a.faceQuality = {0.25, 0.5, 0.75, 1.0};
  const growth::MeshArrays copy = a;
  CMeshO m;
  growth::meshlab::writeLayer(a, m);
  ASSERT_EQ(m.vn, 4);
  ASSERT_EQ(m.fn, 4);
  ASSERT_TRUE(m.face.IsQualityEnabled());
  for (int f = 0; f < 4; ++f) EXPECT_FLOAT_EQ(m.face[f].cQ(), float(copy.faceQuality[size_t(f)]));
  const growth::MeshArrays back = growth::meshlab::meshArrays(m);
  EXPECT_EQ(back.vertices, copy.vertices);
  EXPECT_EQ(back.faces, copy.faces);
  EXPECT_EQ(growth::measureTopology(m).boundaryEdges, 0u); // the closed tetrahedron
}

TEST(MeshlabPoints, ToPointRoundsEachCoordinateToTheScalar) {
  const Vec3d p(0.1, -2.5, 1e-40);
  const vcg::Point3f f = growth::meshlab::toPoint3f(p);
  EXPECT_EQ(f[0], 0.1f);
  EXPECT_EQ(f[1], -2.5f);
  EXPECT_EQ(f[2], float(1e-40));
  const vcg::Point3d d = growth::meshlab::toPoint<vcg::Point3d>(p);
  EXPECT_EQ(d[0], 0.1);
}

} // namespace
