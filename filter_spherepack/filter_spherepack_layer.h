#pragma once
// Sphere packing on MeshLab layers: the engine's arrays (sphere_packer.h) copied from and to CMeshO at the
// boundary (growth/meshlab/layer.h), for the glue, the tools and the tests.
#include "sphere_packer.h"

#include <growth/meshlab/layer.h>
#include <growth/stopwatch.h>

namespace growth {
namespace spherepack {

inline Params suggestParams(const CMeshO& cloud) { return suggestParams(meshlab::readLayer(cloud)); }

// build() on the live vertices (with normals) of `cloud`, into `out` (cleared first; empty on a throw), with the
// bounding box and normals MeshLab expects; the times of reading and writing the layers count in
// the Stat.
inline void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat, CallBackPos* cb = nullptr) {
  out.Clear();
  Stopwatch watch;
  CloudArrays arrays = meshlab::readLayer(cloud);
  const double read = watch.lap();
  MeshArrays mesh;
  build(std::move(arrays), mesh, params, stat, cb);
  watch.lap();
  meshlab::writeLayer(std::move(mesh), out);
  const double write = watch.lap();
  stat.secondsInput += read;
  stat.secondsOutput += write;
  stat.seconds += read + write;
}

} // namespace spherepack
} // namespace growth
