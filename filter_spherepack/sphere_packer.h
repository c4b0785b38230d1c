#pragma once
// Sphere-packing mesher: Lipschuetz, Reitebuch, Polthier, Skrodzki, "Manifold Meshing of Point
// Clouds with Guaranteed Smallest Edge Length" (sections 3 and 4).
//
// One entry point, in the manner of vcglib's IsotropicRemeshing: a Params struct with defaults, a
// Stat struct of counters, and build(). Working state (grids, queues, borders) stays inside.
#include <vcg/space/point3.h>
#include <cstring> // wrap/callback.h uses strcpy without including <cstring>
#include <wrap/callback.h>

#include <string>
#include <vector>

class CMeshO;

namespace growth {
namespace spherepack {

struct Params {
  double sphereDiameter = 0;     // d, absolute; <= 0: derived from the cloud's mean spacing
  double splatSize = 0;          // initial (global) splat radius s, absolute; <= 0: derived
  bool localSplatSizes = true;   // sec. 4.3 per-point splat radii (off: the global s everywhere)
  int windowSize = 8;            // w, sec. 4.2
  int maxBorderLength = 40;      // regions bounded by more border edges stay holes, sec. 3.7
  bool useStartPoints = false;   // sec. 3.3: user-given starting vertices instead of automatic ones
  vcg::Point3d startPoint[2] = {vcg::Point3d(0, 0, 0), vcg::Point3d(0, 0, 0)};
  size_t maxOutputVertices = 20000000; // refuse a d so small that the output would exceed this
};

struct Stat {
  size_t inputPoints = 0;
  size_t duplicatesDropped = 0;
  double sphereDiameter = 0;     // d actually used
  double splatSize = 0;          // s actually used
  size_t vertices = 0;
  size_t faces = 0;
  size_t holes = 0;              // regions left open (border longer than maxBorderLength)
  size_t boxes = 0;
  size_t boxesDTooLarge = 0;     // boxes whose box normal has a negative product with a point normal
  double smallestEdge = 0;
  double qualityAvg = 0;         // Q_avg of the output
  double seconds = 0;
  std::vector<std::string> warnings;
};

// Defaults derived from the cloud (d from the mean point spacing, s from d), so that the filter
// works without tuning. Never throws: an unusable cloud gives the static defaults.
Params suggestParams(const CMeshO& cloud);

// Builds the mesh of the live vertices (with normals) of `cloud` into `out` (cleared first), with
// per-vertex normals and per-face quality Q_t. Throws growth::Error on bad input or parameters
// and growth::Cancelled when cb returns false; `out` is then left empty.
void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat,
           vcg::CallBackPos* cb = nullptr);

} // namespace spherepack
} // namespace growth
