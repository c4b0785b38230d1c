// Times growth::updateNormals against the vcglib calls it replaces (UpdateNormal::
// PerFaceNormalized, PerVertexAngleWeighted, NormalizePerVertex) on a mesh, fastest of 5 each,
// and prints the largest difference between the two results' unit normals; a mesh to time can be
// written by `g2s_run ... -o mesh.ply`.
//
//   normals_time <mesh.ply>
#include <cstring> // (vcglib's headers use strcpy without including it)

#include <growth/meshlab/layer.h>
#include <growth/mesh_normals.h>

#include <vcg/complex/algorithms/update/normal.h>
#include <wrap/io_trimesh/import_ply.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <vector>

int main(int argc, char** argv) {
  if (argc != 2) {
    std::fprintf(stderr, "usage: normals_time <mesh.ply>\n");
    return 2;
  }
  CMeshO m;
  int mask = 0;
  if (vcg::tri::io::ImporterPLY<CMeshO>::Open(m, argv[1], mask) != 0 || m.fn == 0) {
    std::fprintf(stderr, "normals_time: cannot read a mesh with faces from %s\n", argv[1]);
    return 1;
  }
  using Clock = std::chrono::steady_clock;
  auto seconds = [](Clock::time_point a, Clock::time_point b) { return std::chrono::duration<double>(b - a).count(); };
  std::vector<vcg::Point3f> face, vert;
  double vcglib = 1e300, ours = 1e300;
  for (int r = 0; r < 5; ++r) {
    const auto t0 = Clock::now();
    vcg::tri::UpdateNormal<CMeshO>::PerFaceNormalized(m);
    vcg::tri::UpdateNormal<CMeshO>::PerVertexAngleWeighted(m);
    vcg::tri::UpdateNormal<CMeshO>::NormalizePerVertex(m);
    const auto t1 = Clock::now();
    face.clear();
    vert.clear();
    for (const CFaceO& f : m.face) face.push_back(f.cN());
    for (const CVertexO& v : m.vert) vert.push_back(v.cN());
    const auto t2 = Clock::now();
    growth::updateNormals(m);
    const auto t3 = Clock::now();
    vcglib = std::min(vcglib, seconds(t0, t1));
    ours = std::min(ours, seconds(t2, t3));
  }
  double faceDiff = 0, vertDiff = 0;
  for (size_t f = 0; f < m.face.size(); ++f) faceDiff = std::max(faceDiff, double((m.face[f].cN() - face[f]).Norm()));
  for (size_t v = 0; v < m.vert.size(); ++v) vertDiff = std::max(vertDiff, double((m.vert[v].cN() - vert[v]).Norm()));
  std::printf("faces: %d\nvcglib_ms: %.2f\nupdateNormals_ms: %.2f\n", m.fn, vcglib * 1e3, ours * 1e3);
  std::printf("max_face_normal_difference: %.3g\nmax_vertex_normal_difference: %.3g\n", faceDiff, vertDiff);
  return 0;
}
