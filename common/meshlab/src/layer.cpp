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

void writeLayer(MeshArrays mesh, CMeshO& out) {
  out.Clear();
  if (mesh.faces.empty()) return;
  // Exact sizes reserved first: the vectors are allocated once, with huge pages advised.
  reserveHuge(out.vert, mesh.vertices.size(), /*populate=*/true);
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(out, mesh.vertices.size());
  for (size_t i = 0; i < mesh.vertices.size(); ++i, ++vi) {
    const Vec3d& p = mesh.vertices[i];
    vi->P() = CMeshO::CoordType(p[0], p[1], p[2]);
  }
  std::vector<Vec3d>().swap(mesh.vertices);
  const size_t faces = mesh.faces.size();
  const bool quality = mesh.faceQuality.size() == faces;
  if (quality) out.face.EnableQuality();
  reserveHuge(out.face, faces); // (vcglib's reserve reserves the quality vector too)
  // The faces are added a block at a time, and the block's arrays are given back (whole pages,
  // growth::discardPages) once it is written, so that the arrays and the layer's faces do not add
  // up at the peak. Within the reserved room no face moves.
  constexpr size_t kBlock = size_t(1) << 13;
  for (size_t first = 0; first < faces; first += kBlock) {
    const size_t last = std::min(faces, first + kBlock);
    prefault(out.face.data() + first, (last - first) * sizeof(CFaceO));
    if (quality) prefault(out.face.QV.data() + first, (last - first) * sizeof(out.face.QV[0]));
    vcg::tri::Allocator<CMeshO>::AddFaces(out, last - first);
    for (size_t k = first; k < last; ++k) {
      CFaceO& f = out.face[k];
      for (int j = 0; j < 3; ++j) f.V(j) = &out.vert[mesh.faces[k][j]];
      if (quality) f.Q() = static_cast<CFaceO::QualityType>(mesh.faceQuality[k]);
    }
    discardPages(mesh.faces.data(), last * sizeof(mesh.faces[0]));
    if (quality) discardPages(mesh.faceQuality.data(), last * sizeof(double));
  }
  mesh = MeshArrays();
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
