#pragma once
// Sphere packing on MeshLab layers: the engine's arrays (sphere_packer.h) copied from and to CMeshO at the
// boundary (growth/meshlab/layer.h), for the glue, the tools and the tests.
#include "sphere_packer.h"

#include <growth/meshlab/layer.h>

namespace growth {
namespace spherepack {

inline Params suggestParams(const CMeshO& cloud) { return suggestParams(meshlab::readLayer(cloud)); }

// build() on the live vertices of `cloud`, into `out` (growth/meshlab/layer.h, buildOnLayers).
inline void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat, CallBackPos* cb = nullptr) {
  meshlab::buildOnLayers<Params, Stat>(&build, &Stat::secondsInput, cloud, out, params, stat, cb);
}

} // namespace spherepack
} // namespace growth
