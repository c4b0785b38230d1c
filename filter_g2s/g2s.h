#pragma once
// Robust G2S mesh growing: Di Angelo, Di Stefano, Giaccari, "A Fast Mesh-Growing Algorithm for
// Manifold Surface Reconstruction" (sections 3 and 4). Interpolating: the output's vertices are
// the input points; no normals needed.
#include <cstring> // wrap/callback.h uses strcpy without including <cstring>
#include <wrap/callback.h>

#include <cstdint>
#include <string>
#include <vector>

class CMeshO;

namespace growth {
namespace g2s {

struct Params {
  double seedSearchFactor = 2.0;     // k, sec. 3.1 step 3.3: third seed point within k*|edge| of the midpoint
  double maxSearchRadiusFactor = 0;  // maximum search radius / local spacing; <= 0: derived from the cloud
  int sizeLevels = 4;                // n, sec. 4.1
  int flatnessLevels = 8;            // m, sec. 4.1
  bool removeNonManifoldVertices = true; // sec. 4.2
  std::uint64_t randomSeed = 1;      // seed-point choice, sec. 3.1 step 3.1
};

struct Stat {
  size_t inputPoints = 0;
  size_t duplicatesDropped = 0;
  size_t faces = 0;
  size_t boundaryEdges = 0;
  size_t holes = 0;
  size_t seeds = 0;
  size_t nonManifoldVerticesRemoved = 0;
  size_t facesRemoved = 0;
  double seconds = 0;
  std::vector<std::string> warnings;
};

// Defaults derived from the cloud. Never throws: an unusable cloud gives the static defaults.
Params suggestParams(const CMeshO& cloud);

// Triangulates the live vertices of `cloud` into `out` (cleared first): out's vertices are copies
// of the input points (same order as the layer's live vertices), faces consistently oriented, with
// per-face quality Q_t. Throws growth::Error on bad input and growth::Cancelled on cancel.
void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat,
           vcg::CallBackPos* cb = nullptr);

} // namespace g2s
} // namespace growth
