#pragma once
// Sphere-packing mesher: Lipschuetz, Reitebuch, Polthier, Skrodzki, "Manifold Meshing of Point
// Clouds with Guaranteed Smallest Edge Length" (sections 3 and 4).
//
// One entry point, in the manner of vcglib's IsotropicRemeshing: a Params struct with defaults, a
// Stat struct of counters, and build(). Working state (grids, queues, borders) stays inside.
//
// The parts, one header each beside this one in filter_spherepack/engine/: box_grid.h (sec. 4.1),
// splats.h (sec. 3.2, 4.3), candidates.h (fig. 4c, sec. 4.4), borders.h (sec. 3.4, 3.5, 4.2),
// crossing.h (sec. 3.6), region_triangulation.h (sec. 3.7), vertex_grid.h (the vertex look-ups of
// sec. 3.6 and 4.4); in common/, growth/bucket_queue.h (one FIFO per priority level, sec. 4.4),
// shared with Robust G2S. The method's steps that tie them together, one file per paper section
// (the initialization of sec. 3.3, the growth loop of sec. 3.4–3.6, ...), are the packer_*.cpp
// files beside it (packer_steps.h lists them); build() in sphere_packer.cpp runs them in order.
#include <growth/vec3.h>
#include <growth/mesh_arrays.h>
#include <growth/progress.h>

#include <string>
#include <vector>

namespace growth {
namespace spherepack {

struct Params {
  double sphereDiameter = 0;     // d, absolute; <= 0: derived from the cloud's mean spacing
  double splatSize = 0;          // initial (global) splat radius s, absolute; <= 0: derived from d
  bool localSplatSizes = true;   // sec. 4.3 per-point splat radii (off: the global s everywhere)
  int windowSize = 8;            // w, sec. 4.2
  int maxBorderLength = 40;      // regions bounded by more border edges stay holes, sec. 3.7
  bool useStartPoints = false;   // sec. 3.3: user-given starting vertices instead of automatic ones
  Vec3d startPoint[2] = {Vec3d(0, 0, 0), Vec3d(0, 0, 0)};
  int minComponentFaces = 50;    // connected pieces of the output with fewer faces are dropped (the
                                 // largest always stays): flaps of misregistered scan layers, bits
                                 // of stray points; 0 keeps all
  size_t maxOutputVertices = 20000000; // refuse a d so small that the output would exceed this
  size_t maxMemoryBytes = 0;     // refuse, before the box grid, a run whose estimated peak
                                 // (Stat::memory.estimate) exceeds this; 0: the memory the machine
                                 // has available (Linux: MemAvailable), no limit where unknown
  size_t spatialOrderMinPoints = 20000; // clouds with at least this many points are processed in a
                                 // spatial order of the points (memory locality); the same mesh
  int threads = 0;                // threads for the per-box and per-point phases (0 = automatic, at
                                 // most the hardware's); the output is the same for any number
  bool rejectTwisted = true;     // reject a candidate whose new edges fall into other corners of its
                                 // parents seen along the box normal than in their own planes
  bool closeHoles = true;        // close the holes of the output that the cloud covers with the
                                 // packing's own vertices (packer_holes.cpp; a real boundary of an
                                 // open surface is not covered and stays open)
  bool keepFeatures = false;     // detect crease lines and corners in the cloud and start the growth
                                 // from them, no face across a crease (cloud_features.h)
  double creaseAngleDeg = 30;    // keepFeatures: planes meeting at more than this angle make a crease
  bool checkInvariants = false;  // tests: after every insertion, compare the new vertex with all
                                 // others by brute force (O(V²)); a violation throws std::logic_error
};

// The scale of a cloud, from which the defaults are derived: robust estimates (medians over a
// sample of the points, growth/cloud_scale.h), so that outliers and far points barely move them.
struct CloudScale {
  double spacing = 0;        // the spacing: the robust (trimmed) mean nearest-neighbour distance
                             // (growth/cloud_scale.h), as Robust G2S, the measures and every log use it
  double medianSpacing = 0;  // median nearest-neighbour distance (for the packer's own checks)
  double areaSpacing = 0;    // sqrt(surface area per point): a sampling length that does not depend
                             // on how regular the sampling is (0.47 of it is the median spacing of
                             // a random sample, all of it that of a square lattice)
  double area = 0;           // estimated surface area: area per point × points
  double noise = 0;          // ν, the estimated bound of the points' offsets from the surface
  // Thin parts (with the normals): the share of the samples that see another sheet (opposed
  // normals, across the tangent plane) closer than kThinGapPerD × the sampling's d, and the median
  // of those distances (the parts' thickness); 0 without normals or thin parts.
  double thinShare = 0;
  double sheetGap = 0;
};
// `threads`: for the estimates (0 = automatic); the scale is the same for any number. With the
// normals, neighbours on another sheet of a thin part are left out (SamplingOptions::normals).
CloudScale cloudScale(const std::vector<Vec3d>& points, int threads = 0,
                      const std::vector<Vec3d>* normals = nullptr);

// Defaults.
// d = max(1.8 × sqrt(area per point), 3ν): at the sampling's resolution (a packing of spheres of
// diameter d has about area / (0.96·d²) vertices, so 1.8 gives about 0.3 vertices per point: a
// random sample's 4 median spacings, a range scan's 2.5–3), and at least 2ν as sec. 5.3 advises,
// with a margin (manifoldness was lost there from 2ν = 0.6–1.0·d).
// s = 2.5 × sqrt(area per point): the radius of a splat whose fan stays open (a boundary), and
// the largest local radius (sec. 4.3; the local radii cover the surface, sec. 5.2).
constexpr double kDefaultDiameterPerAreaSpacing = 1.8;
constexpr double kDefaultDiameterPerNoise = 3.0;
// Thin parts: when at least kThinShareForSmallerD of the surface lies on parts thinner than
// kThinGapPerD × that d (two sheets with opposed normals, such as a closed plate), d is lowered to
// their median thickness / kThinGapPerD, so that both sheets hold vertices (every vertex is at
// least d from every other, so sheets closer than d cannot both be meshed, and the boxes see both
// within about d, BoxGrid's two-sided boxes); not below kMinThinDiameterPerAreaSpacing ×
// sqrt(area per point) (0.7: about 1.5 median spacings of a random sample, about 6 times the
// vertices of the usual d) nor below 2ν (sec. 5.3).
constexpr double kThinGapPerD = 1.2;
constexpr double kThinShareForSmallerD = 0.1;
constexpr double kMinThinDiameterPerAreaSpacing = 0.7;
// And s = min(2.5, max(kThinSplatPerGap × gap / sqrt(area per point), 1.25)) × sqrt(area per
// point) there: the splats of the points at a rim (an open fan) take s, and both sheets' growths
// run past the rim by up to s; overhangs longer than the gap meet and leave holes there.
constexpr double kThinSplatPerGap = 0.9;
constexpr double kMinThinSplatPerAreaSpacing = 1.25;
// The d from the sampling and the noise alone.
double samplingDiameter(const CloudScale& scale);
constexpr double kDefaultSplatPerAreaSpacing = 2.5;
double defaultDiameter(const CloudScale& scale);
// Why defaultDiameter chose its value, for the log.
std::string defaultDiameterReason(const CloudScale& scale);
double defaultSplatSize(const CloudScale& scale, double d);

// Stat::smallestEdge below d·(1 − kSmallestEdgeTolerance) is warned about. The engine keeps every
// edge at least d in double; float storage rounds a coordinate x by up to |x|·2^-24, which is
// negligible near the origin and a large share of d far from it (geo-referenced coordinates).
// Shortfalls below 0.01 % are reported, not warned about.
constexpr double kSmallestEdgeTolerance = 1e-4;

struct Stat {
  size_t inputPoints = 0;         // live vertices of the layer (as g2s::Stat), duplicates included
  size_t duplicatesDropped = 0;  // exact repeats (the first copy is used)
  size_t farPointsLeftOut = 0;   // points left out of the packing: beyond the box grid's reach
                                 // (2^21 boxes of side d per axis) from the bulk of the cloud, and
                                 // at least farPointsGap from every point kept
  double farPointsGap = 0;       // the smallest gap, along an axis, between them and the points kept
  double sphereDiameter = 0;     // d actually used
  double splatSize = 0;          // s actually used
  CloudScale scale;              // the cloud's estimated sampling and noise
  std::string diameterReason;    // how d was chosen (automatic: from the sampling or the noise)
  double meanSplatRadius = 0;    // mean of the per-point radii (= s with local sizes off)
  size_t splatsUnbounded = 0;    // local sizes: points without a closed Delaunay fan (kept s)
  size_t splatsClamped = 0;      // local sizes: points whose Voronoi radius exceeded s (kept s)
  size_t vertices = 0;           // output vertices
  size_t faces = 0;
  size_t holes = 0;              // holes of the output: its boundary loops (= boundaryLoops)
  size_t regionsLeftOpen = 0;    // regions sec. 3.7 left open (border longer than maxBorderLength,
                                 // or not triangulable)
  // The hole pass (Params::closeHoles): loops of the mesh after the clean-up closed with the
  // packing's vertices, the faces it added, and why the others stayed open: longer than
  // kMaxHoleLoop; no triangulation without (nearly) flat faces or edges already there; a face
  // where the cloud is not (a real boundary); a face folded back onto the mesh; a face through
  // the mesh; a vertex of the loop where the boundary is not a single loop.
  size_t holesClosed = 0;
  size_t holeFacesAdded = 0;
  size_t holeFacesRemoved = 0;   // faces of the rings taken out around holes before closing them,
                                 // and of the islands dropped
  size_t holeIslandsDropped = 0; // pieces bounded by one loop that faces away, lying on the rest of
                                 // the mesh (a second layer left in a hole closed under it)
  size_t holesTooLong = 0, holesNotTriangulable = 0, holesNotCovered = 0, holesFolded = 0,
         holesCrossing = 0, holesOther = 0;
  size_t flatFacesRemoved = 0;   // faces of the regions left out because their vertices (as stored)
                                 // lie (nearly) on a line: an angle above 179° (region_triangulation.h)
  size_t longestBorder = 0;      // border edges of the longest region
  double meanBorderLength = 0;   // mean border length of the regions (about 4, sec. 3.7)
  size_t boxes = 0;              // boxes built: those the splats' disks meet (BoxGrid::build)
  size_t boxReferences = 0;      // their references to the points within d (sec. 4.1)
  size_t boxesDTooLarge = 0;     // boxes whose box normal has a negative product with a point normal
  size_t boxesTwoSided = 0;      // of those, the boxes that see two sides and keep both, as two
                                 // layers (BoxGrid, filterOrSplitBox; the paper drops one)
  size_t candidates = 0;         // candidates queued (including re-queued ones)
  size_t requeued = 0;           // stale candidates moved to their new level (sec. 3.6)
  size_t rejectedTooClose = 0;   // candidates closer than d to a vertex (sec. 3.6)
  size_t rejectedCrossing = 0;   // candidates whose edges crossed existing edges (sec. 3.6, fig. 4b)
  size_t rejectedInconsistent = 0; // candidates whose edges fall into other corners seen along n
  size_t unreachedPoints = 0;    // input points with no vertex within d of their splat
  size_t featureCreasePoints = 0; // keepFeatures: points that passed the two-plane test
  size_t featureLines = 0;       // keepFeatures: crease lines kept (at least 2 d long)
  size_t featureCorners = 0;     // keepFeatures: corners (where lines meet or end)
  size_t featureVertices = 0;    // keepFeatures: vertices placed on corners and lines before the growth
  size_t featurePatches = 0;     // keepFeatures: sides of the crease lines (connected sets of points)
  size_t componentsStarted = 0;  // starting pairs placed (sec. 3.3): the first, and one for each
                                 // part of the cloud the growth had not reached when it stopped
  size_t startsRefusedNearMesh = 0; // unreached points where no start was placed because a vertex
                                 // lay within 2d (a second layer of a surface already meshed)
  size_t nonManifoldVerticesRemoved = 0; // vertices of the triangulated packing with more than one
                                 // fan of faces (or on an edge with more than two), made manifold
  size_t selfIntersectionFacesRemoved = 0; // faces removed because they intersected others
  size_t facesRemoved = 0;       // faces removed in all (the extra fans, the intersecting faces)
  size_t componentsDropped = 0;  // connected pieces with fewer than Params::minComponentFaces faces
  size_t componentFacesDropped = 0; // their faces (not in facesRemoved)
  size_t nonManifoldVertices = 0; // output vertices whose faces form more than one fan (0)
  size_t nonManifoldEdges = 0;   // output edges with more than two faces (0)
  size_t boundaryLoops = 0;      // boundary loops of the output (holes, including the ∂max ones)
  double smallestEdge = 0;       // on the coordinates as the output layer stores them (float in
                                 // MeshLab 2020.09): below d where rounding moved the vertices (a
                                 // warning says so when by more than kSmallestEdgeTolerance·d)
  double qualityAvg = 0;         // Q_avg of the output
  // The engine's own arrays, in bytes as allocated: each part at its largest, and the largest sum
  // of the parts held at the same time (the engine's peak; the host's copy of the cloud and the
  // output layer come on top).
  struct Memory {
    size_t input = 0;   // positions and normals (double), splat radii, the spatial order
    size_t boxGrid = 0; // box hash, per-box normals and flags, the boxes' point lists (sec. 4.1)
    size_t growth = 0;  // graph G with its rotations, vertex grid, splat vertex lists, candidate queue
    size_t faces = 0;   // the triangles of the regions (the clean-up's and the hole pass's working
                        // arrays, up to about 150 bytes a face while they run, are not counted: they
                        // come after the graph's rotations are freed, below the growth's peak;
                        // spherepack_run's bytes_per_point_engine, from the RSS, includes them)
    size_t output = 0;  // the mesh handed to the caller (MeshArrays)
    size_t peak = 0;
    size_t estimate = 0; // the peak as estimated before the box grid (Params::maxMemoryBytes)
    size_t limit = 0;    // the limit it was checked against (0: none)
  } memory;
  double seconds = 0;
  double secondsInput = 0;       // of which: reading the cloud, mean spacing and area (defaults)
  double secondsBoxGrid = 0;     //           box grid, normal filter, some box normals (sec. 4.1)
  double secondsSplats = 0;      //           splat radii (sec. 4.3)
  double secondsGrowth = 0;      //           initialization and disk growing (sec. 3.3–3.6), and
                                 //           the other box normals, on another thread meanwhile
  double secondsTriangulation = 0; //         regions (sec. 3.7)
  double secondsCleanup = 0;     //           manifold and intersection clean-up
  double secondsOutput = 0;      //           writing the mesh (with the glue's: its layer and normals), the topology check
  std::vector<std::string> warnings;
};

// Defaults derived from the cloud (d and s from its sampling and noise), so that the filter works
// without tuning. Never throws: an unusable cloud gives the static defaults.
Params suggestParams(const CloudArrays& cloud);

// Builds the mesh of the points (with normals) of `cloud` (a layer's live vertices,
// growth/mesh_arrays.h) into `out` (cleared first), with per-face quality Q_t. Throws growth::Error
// on bad input or parameters and growth::Cancelled when cb returns false; `out` is then left empty.
// The glue writes `out` into a layer, with its normals (growth/meshlab/layer.h).
void build(CloudArrays cloud, MeshArrays& out, const Params& params, Stat& stat, CallBackPos* cb = nullptr);

} // namespace spherepack
} // namespace growth
