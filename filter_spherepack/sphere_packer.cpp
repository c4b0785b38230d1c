#include "sphere_packer.h"

#include <growth/error.h>

#include <common/ml_mesh_type.h>

namespace growth {
namespace spherepack {

Params suggestParams(const CMeshO&) { return Params(); }

void build(const CMeshO&, CMeshO& out, const Params&, Stat&, vcg::CallBackPos*) {
  out.Clear();
  throw Error("Sphere Packing: not implemented yet.");
}

} // namespace spherepack
} // namespace growth
