#include <growth/huge_pages.h>
#include <growth/mesh_normals.h>
#include <growth/meshlab/layer.h>
#include <growth/meshlab/points.h>

#include <vcg/complex/algorithms/update/bounding.h>
#include <vcg/complex/allocate.h>

#include <algorithm>

namespace growth {
namespace meshlab {

CloudArrays readLayer(const CMeshO& mesh) {
  CloudArrays a;
  const size_t n = static_cast<size_t>(std::max(mesh.vn, 0));
  reserveHuge(a.points, n, true);
  reserveHuge(a.normals, n, true);
  reserveHuge(a.vertexIndex, n, true);
  for (size_t i = 0; i < mesh.vert.size(); ++i) {
    const CVertexO& v = mesh.vert[i];
    if (v.IsD()) continue;
    a.points.push_back(Vec3d::Construct(v.cP()));
    a.normals.push_back(Vec3d::Construct(v.cN()));
    a.vertexIndex.push_back(static_cast<int>(i));
  }
  a.layerFaces = static_cast<size_t>(std::max(mesh.fn, 0));
  a.floatStorage = sizeof(CMeshO::ScalarType) == sizeof(float);
  return a;
}

void writeLayer(const MeshArrays& mesh, CMeshO& out) {
  out.Clear();
  if (mesh.faces.empty()) return;
  // Exact sizes reserved first: the vectors are allocated once and made resident in one call.
  reserveHuge(out.vert, mesh.vertices.size(), /*populate=*/true);
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(out, mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i, ++vi) {
    const Vec3d& p = mesh.vertices[i];
    vi->P() = CMeshO::CoordType(p[0], p[1], p[2]);
  }
  const bool quality = mesh.faceQuality.size() == mesh.faces.size();
  if (quality) out.face.EnableQuality();
  reserveHuge(out.face, mesh.faces.size(), /*populate=*/true); // (vcglib's reserve reserves the quality vector too)
  if (quality) prefault(out.face.QV.data(), mesh.faces.size() * sizeof(out.face.QV[0]));
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(out, mesh.faces.size());
  for (size_t k = 0; k < mesh.faces.size(); ++k, ++fi) {
    for (int j = 0; j < 3; ++j) fi->V(j) = &out.vert[mesh.faces[k][j]];
    if (quality) fi->Q() = static_cast<CFaceO::QualityType>(mesh.faceQuality[k]);
  }
  // What MeshLab expects of a new layer (its creation filters call UpdateBoxAndNormals).
  vcg::tri::UpdateBounding<CMeshO>::Box(out);
  updateNormals(out);
}

MeshArrays meshArrays(const CMeshO& mesh) {
  MeshArrays a;
  std::vector<std::uint32_t> index;
  assignHuge(index, mesh.vert.size(), ~0u);
  reserveHuge(a.vertices, static_cast<size_t>(std::max(mesh.vn, 0)), /*populate=*/true);
  for (size_t i = 0; i < mesh.vert.size(); ++i) {
    if (mesh.vert[i].IsD()) continue;
    index[i] = static_cast<std::uint32_t>(a.vertices.size());
    a.vertices.push_back(Vec3d::Construct(mesh.vert[i].cP()));
  }
  reserveHuge(a.faces, static_cast<size_t>(std::max(mesh.fn, 0)), /*populate=*/true);
  for (const auto& f : mesh.face) {
    if (f.IsD()) continue;
    std::array<std::uint32_t, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = index[vcg::tri::Index(mesh, f.cV(k))];
    a.faces.push_back(t);
  }
  return a;
}

} // namespace meshlab

void toMesh(const Cloud& cloud, CMeshO& mesh) {
  mesh.Clear();
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(mesh, cloud.points.size());
  for (size_t i = 0; i < cloud.points.size(); ++i, ++vi) {
    // Rounded to float, as the generator's PLY files store them.
    vi->P() = meshlab::toPoint<CMeshO::CoordType>(Vec3d::Construct(meshlab::toPoint3f(cloud.points[i])));
    vi->N() = meshlab::toPoint<CMeshO::CoordType>(Vec3d::Construct(meshlab::toPoint3f(cloud.normals[i])));
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(mesh);
}

} // namespace growth
