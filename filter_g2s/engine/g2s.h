#pragma once
// Robust G2S mesh growing: Di Angelo, Di Stefano, Giaccari, "A Fast Mesh-Growing Algorithm for
// Manifold Surface Reconstruction" (sections 3 and 4). Interpolating: the output's vertices are
// the input points; no normals needed.
#include <growth/mesh_arrays.h>
#include <growth/progress.h>

#include <cstdint>
#include <string>
#include <vector>

namespace growth {
namespace g2s {

struct Params {
  double seedSearchFactor = 2.0;     // k, sec. 3.1 step 3.3: third seed point within k*|edge| of the midpoint
  double maxSearchRadiusFactor = 0;  // maximum search radius / local spacing (mean mesh edge length at the edge); <= 0: default
  int sizeLevels = 4;                // n, sec. 4.1: search radii from |edge| to the maximum, pl_d = 1..n
  int flatnessLevels = 8;            // m, sec. 4.1: classes of the angle β in [0°, 180°], pl_f = 1..m
  bool removeNonManifoldVertices = true; // sec. 4.2; with it, self-intersecting faces are removed too
  int maxHoleEdges = 20;             // hole pass (not in the paper): close boundary loops of at most this many edges; 0: off
  bool removeSmallHandles = true;    // not in the paper: cut handles round three points (tunnels between close
                                     // sheets) and close their loops; needs the two passes above
  int minComponentFaces = 50;        // not in the paper: connected pieces with fewer faces are dropped (the largest
                                     // always stays): triangles among stray points; 0 keeps all
  bool thinPartRules = true;         // not in the paper: during the growth, refuse candidates that fold or cross
                                     // into the material between two close sheets (a closed part a few
                                     // spacings thick), and close the rim loops this leaves (g2s_growth.cpp,
                                     // kSheetGap; g2s_thin.cpp); off: the paper's candidate choice
  bool loopClosures = true;          // not in the paper: during the growth, a free edge on a loop of three free
                                     // edges takes the loop's third point (unless an unused point lies inside),
                                     // and one on a loop of four whose search finds nothing closes it by the
                                     // better diagonal (Mesher::findCandidate, quadClosure); off: the G2S search alone
  bool mergeClumps = true;           // not in the paper: dense clumps of points (a scanner dwelling on a spot)
                                     // meshed as one point (Mesher::kClumpNeighbours, g2s_clumps.cpp)
  std::uint64_t randomSeed = 1;      // seed-point choice, sec. 3.1 step 3.1
  int threads = 0;                   // threads for the crossing-face test (0 = automatic, at most
                                     // growth::kMaxThreads); the mesh is the same for any number
};

// The default maximum search radius, in multiples of the local spacing.
constexpr double kDefaultMaxSearchRadiusFactor = 2.5;

struct Stat {
  size_t inputPoints = 0;                 // live vertices of the layer
  size_t duplicatesDropped = 0;           // exact repeats (the first copy is used)
  size_t clumps = 0;                      // dense clumps meshed as one point (Mesher::kClumpNeighbours)
  size_t clumpPointsMerged = 0;           // their other points, not used (nor counted in unusedPoints)
  size_t vertices = 0;                    // output vertices: the input points used by faces
  size_t unusedPoints = 0;                // distinct input points in no face
  size_t faces = 0;
  size_t boundaryEdges = 0;               // edges with one face
  size_t holes = 0;                       // boundary loops
  size_t seeds = 0;                       // seed triangles (sec. 3.1), one or more per component
  size_t seedAttempts = 0;                // points tried as seed starts
  size_t cylinderQueries = 0;             // ball queries of their cylinder tests (sec. 3.1; bounded)
  size_t nonManifoldVerticesRemoved = 0;  // sec. 4.2
  size_t facesRemoved = 0;                // faces of the extra fans removed by sec. 4.2
  size_t nonManifoldVertices = 0;         // left in the output (0 unless the removal is off)
  size_t selfIntersectionFacesRemoved = 0; // faces that intersected others (with the removal above)
  size_t holesClosed = 0;                 // hole pass: boundary loops closed
  size_t holeFacesAdded = 0;              // and the faces it added
  size_t holeFacesReplaced = 0;           // faces it took out at a loop so that it could close
  size_t holesWidened = 0;                // of the holes closed, those closed wider (the faces on their edges,
                                          // or at their points, taken out first)
  size_t holeFacesWidened = 0;            // the faces these took out (in holeFacesReplaced too)
  size_t holesRegrown = 0;                // of the holes closed wider, those grown into again by G2S on the
                                          // points around them (the faces near the loop taken out first)
  size_t holeSpikes = 0;                  // spikes and flaps: a loop vertex with two or one faces, left unused
  size_t handlesCut = 0;                  // small handles cut (Params::removeSmallHandles)
  size_t handleFacesRemoved = 0;          // and the faces they took out
  size_t handleFacesAdded = 0;            // the faces that closed their loops (counted apart from the hole pass's)
  size_t handles = 0;                     // handles of the output (genus summed over its components;
                                          // 0 when sec. 4.2 is off, where it is not defined)
  size_t components = 0;                  // connected pieces of the output (the orientation pass counts them)
  size_t componentsFlipped = 0;           // of them, turned over by the orientation pass (closed shells to face
                                          // out of the material, sheets the way the layer's normals point)
  size_t componentsDropped = 0;           // connected pieces with fewer than Params::minComponentFaces faces
  size_t componentFacesDropped = 0;       // and their faces
  size_t thinPartRefusals = 0;            // candidates refused by the thin-part rules (not in the paper:
                                          // a fold or crossing into a part's material, g2s_growth.cpp)
  size_t edgesLeftAtFullPoints = 0;       // front edges left open: a point had no room for another
                                          // edge (more than PointEdgeMap::kMaxEntries neighbours)
  double spacing = 0;                     // mean nearest-neighbour spacing (growth::meanSpacing)
  std::uint64_t pointsVisited = 0;        // points the index scanned for the growth's queries
  std::uint64_t candidateSearches = 0;    // free edges searched for a candidate (sec. 3.2; see Mesher::grow)
  double maxSearchRadiusFactor = 0;       // the factor used
  size_t workingBytes = 0;                // engine memory at its peak (points, grid, edges, faces)
  double seconds = 0;                     // whole run
  double secondsSetup = 0;                // reading, checks, spacing, spatial order, grid
  double secondsGrowth = 0;               // seeds and front growth
  double secondsCleanup = 0;              // sec. 4.2, boundary and hole counts, orientation
  double secondsOutput = 0;               // filling the output mesh (with the glue's: its layer, bounding box and normals)
  // The passes after the growth (and the rim pass inside it), in the order they ran: the live
  // faces each took out and added, and its time. Passes with nothing to do are listed with zeros.
  struct Pass {
    std::string name;
    size_t facesRemoved = 0, facesAdded = 0;
    double seconds = 0;
  };
  std::vector<Pass> passes;
  size_t grownFaces = 0;                  // faces at the end of the growth, before the passes after it
  std::vector<std::string> warnings;
};

// Defaults derived from the cloud. Never throws: an unusable cloud gives the static defaults.
Params suggestParams(const CloudArrays& cloud);

// Triangulates the points of `cloud` (a layer's live vertices, growth/mesh_arrays.h) into `out`
// (cleared first): out's vertices are the input points that the faces use, bit for bit (unused
// points are left out), in a spatially coherent (Morton) order; faces consistently oriented
// (closed components outwards), with per-face quality Q_t. The layer's normals, where most points
// have one, orient the open sheets. A cloud where no seed triangle exists gives an empty `out`
// and a warning. Throws growth::Error on bad input or parameters and growth::Cancelled on cancel
// (out is then empty). The glue writes `out` into a layer (growth/meshlab/layer.h).
void build(CloudArrays cloud, MeshArrays& out, const Params& params, Stat& stat, CallBackPos* cb = nullptr);

} // namespace g2s
} // namespace growth
