#pragma once
// The MeshLab side of the engines' arrays (growth/mesh_arrays.h), compiled once per MeshLab SDK:
// a layer copied into a CloudArrays, a MeshArrays written into a new layer, and the measures of
// growth/mesh_measures.h on a layer, for the tools and tests.
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>
#include <growth/mesh_arrays.h>
#include <growth/mesh_measures.h>
#include <growth/progress.h>
#include <growth/stopwatch.h>

#include <common/ml_mesh_type.h>

namespace growth {
namespace meshlab {

// The live vertices of `mesh` and their normals, in double, with their indices in mesh.vert.
CloudArrays readLayer(const CMeshO& mesh);

// `out` (cleared first) gets the mesh: its vertices rounded to the layer's scalar, its faces with
// their quality (when given), the bounding box, and face and vertex normals (growth::updateNormals),
// what MeshLab expects of a new layer. The arrays are freed as they are copied.
void writeLayer(MeshArrays mesh, CMeshO& out);

// The live vertices of `mesh` renumbered 0..n-1 and its live faces (a deleted vertex as ~0u).
MeshArrays meshArrays(const CMeshO& mesh);

// An engine's build(CloudArrays, MeshArrays&, params, stat, cb) on layers: the live vertices of
// `cloud` in, `out` (cleared first; empty on a throw) out, with the bounding box and normals MeshLab
// expects. Reading the layer counts in stat.*readSeconds, writing it in stat.secondsOutput, both in
// stat.seconds.
template <class Params, class Stat>
void buildOnLayers(void (*engine)(CloudArrays, MeshArrays&, const Params&, Stat&, CallBackPos*),
                   double Stat::*readSeconds, const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat,
                   CallBackPos* cb) {
  out.Clear();
  Stopwatch watch;
  CloudArrays arrays = readLayer(cloud);
  const double read = watch.lap();
  MeshArrays mesh;
  engine(std::move(arrays), mesh, params, stat, cb);
  watch.lap();
  writeLayer(std::move(mesh), out);
  const double write = watch.lap();
  stat.*readSeconds += read;
  stat.secondsOutput += write;
  stat.seconds += read + write;
}

} // namespace meshlab

// growth::readCloud on a layer.
inline InputCloud readCloud(const CMeshO& mesh, const CloudCheck& check) {
  return readCloud(meshlab::readLayer(mesh), check);
}

// Fills a MeshLab mesh (vertices and normals only, in float) with the cloud.
void toMesh(const Cloud& cloud, CMeshO& mesh);

// growth/mesh_measures.h on a layer.
inline MeshMeasures measure(const CMeshO& mesh, const std::vector<Vec3d>* cloud = nullptr,
                            const MeasureOptions& options = MeasureOptions()) {
  return measure(meshlab::meshArrays(mesh), cloud, options);
}
inline MeshTopology measureTopology(const CMeshO& mesh) { return measureTopology(meshlab::meshArrays(mesh)); }
inline size_t countBoundaryEdges(const CMeshO& m) { return measureTopology(m).boundaryEdges; }
inline size_t countNonManifoldEdges(const CMeshO& m) { return measureTopology(m).nonManifoldEdges; }
inline size_t countNonManifoldVertices(const CMeshO& m) { return measureTopology(m).nonManifoldVertices; }
inline size_t countBoundaryLoops(const CMeshO& m) { return measureTopology(m).boundaryLoops; }
inline size_t countComponents(const CMeshO& m) { return measureTopology(m).components; }
inline size_t countInconsistentEdges(const CMeshO& m) { return measureTopology(m).inconsistentEdges; }
inline bool isConsistentlyOriented(const CMeshO& m) { return measureTopology(m).inconsistentEdges == 0; }
inline size_t countDegenerateFaces(const CMeshO& m) { return measureTopology(m).degenerateFaces; }
inline size_t countDuplicateFaces(const CMeshO& m) { return measureTopology(m).duplicateFaces; }
inline size_t countSelfIntersections(const CMeshO& m) { return countSelfIntersections(meshlab::meshArrays(m)); }
inline void measureCloudDistance(const CMeshO& mesh, const std::vector<Vec3d>& cloud, MeshMeasures& out) {
  measureCloudDistance(meshlab::meshArrays(mesh), cloud, out);
}

} // namespace growth
