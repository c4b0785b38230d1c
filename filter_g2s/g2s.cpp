#include "g2s.h"

#include <growth/error.h>

#include <common/ml_mesh_type.h>

namespace growth {
namespace g2s {

Params suggestParams(const CMeshO&) { return Params(); }

void build(const CMeshO&, CMeshO& out, const Params&, Stat&, vcg::CallBackPos*) {
  out.Clear();
  throw Error("Robust G2S: not implemented yet.");
}

} // namespace g2s
} // namespace growth
