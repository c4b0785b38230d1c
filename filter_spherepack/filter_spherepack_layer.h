#pragma once
// Sphere packing on MeshLab layers: the engine's arrays (sphere_packer.h) copied from and to CMeshO at the
// boundary (growth/meshlab/layer.h), for the glue, the tools and the tests.
#include "remesher.h"
#include "sphere_packer.h"

#include <growth/meshlab/layer.h>

namespace growth {
namespace spherepack {

inline Params suggestParams(const CMeshO& cloud) { return suggestParams(meshlab::readLayer(cloud)); }

// build() on the live vertices of `cloud`, into `out` (growth/meshlab/layer.h, buildOnLayers).
inline void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat, CallBackPos* cb = nullptr) {
  meshlab::buildOnLayers<Params, Stat>(&build, &Stat::secondsInput, cloud, out, params, stat, cb);
}

// remesh() on the live vertices and faces of `mesh`, into `out` (cleared first; empty on a throw),
// with the bounding box and normals MeshLab expects. `mesh` is not changed.
inline void remesh(const CMeshO& mesh, CMeshO& out, const RemeshParams& params, RemeshStat& stat,
                   CallBackPos* cb = nullptr) {
  out.Clear();
  Stopwatch watch;
  const MeshArrays in = meshlab::meshArrays(mesh);
  const double read = watch.lap();
  MeshArrays result;
  remesh(in, sizeof(CMeshO::ScalarType) == sizeof(float), result, params, stat, cb);
  watch.lap();
  meshlab::writeLayer(std::move(result), out);
  const double write = watch.lap();
  stat.secondsInput += read;
  stat.secondsOutput += write;
  stat.seconds += read + write;
}

inline double defaultRemeshDiameter(const CMeshO& mesh) { return defaultRemeshDiameter(meshlab::meshArrays(mesh)); }

} // namespace spherepack
} // namespace growth
