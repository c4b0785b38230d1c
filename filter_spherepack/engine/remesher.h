#pragma once
// Sphere-packing remesher: the packing of sphere_packer.h run on a triangle mesh, whose surface
// replaces the splats (Lipschütz et al., sec. 6: "the input mesh will serve as the surface where to
// place new vertices, replacing the splat approximation").
//
// The same growth as the reconstruction (sec. 3.3–3.6) and the same regions (sec. 3.7), on the
// engine's parts (BorderGraph, the crossing check, the region triangulation, the clean-up); what
// changes is where a candidate may lie:
//  - a candidate is a point of the circle of its parents (candidates.h, parentCircle) on the plane
//    of an input triangle, inside that triangle (barycentric test with a tolerance of
//    kInsideTolerance, so that a point on an edge shared by two triangles is kept by at least one);
//  - the triangles near a vertex come from a hash grid of cells of side d (TriangleGrid in
//    remesher.cpp): a cell lists the triangles that meet the ball circumscribing it, and a vertex
//    looks at the 3 × 3 × 3 cells around its own;
//  - the vertex normal (rotation order, crossing check) is the mean of the normals of the triangles
//    within d/2 that face the same side as the triangle the vertex lies on;
//  - every vertex lies on the input surface: candidates are on its triangles and the starting
//    vertices (sec. 3.3) are a triangle's centroid and a point projected onto the closest triangle;
//  - a growth is started on every part of the input it has not reached (a triangle no vertex came
//    within d of), so every connected component gets one;
//  - a region (sec. 3.7) whose triangulation lies mostly beyond the input's boundary (its
//    triangles' centroids project onto a boundary edge of the input, from farther than
//    kOutsideTolerancePerD·d) stays open: an open mesh stays open along its borders.
// Every edge is at least d (all vertices are, sec. 3.1), the output is manifold without
// intersecting faces (the reconstruction's clean-up), and each face carries its Q_t (sec. 5).
#include "sphere_packer.h"

#include <growth/mesh_arrays.h>
#include <growth/progress.h>
#include <growth/vec3.h>

#include <array>
#include <string>
#include <vector>

namespace growth {
namespace spherepack {

struct RemeshParams {
  double sphereDiameter = 0;     // d, absolute; <= 0: defaultDiameterOf(the mean edge length, the area)
  int windowSize = 8;            // w, sec. 4.2
  int maxBorderLength = 40;      // regions bounded by more border edges stay holes, sec. 3.7
  double creaseAngleDeg = 30;    // dihedral angle above which an input edge is a crease
  bool closeHoles = true;        // the hole pass on the output's loops (packer_steps.h, closeHoles)
  size_t maxOutputVertices = 20000000; // refuse a d so small that the output would exceed this
  int minPieceFaces = 10;        // pieces of the output with fewer faces are dropped, but each input
                                 // component keeps its largest piece (0: none dropped)
  int threads = 0;               // threads of the intersection clean-up (0 = automatic)
  bool rejectTwisted = true;     // as Params::rejectTwisted
  bool checkInvariants = false;  // tests: brute-force check of every insertion (O(V²))
};

// The default d is the input's mean edge length: the shortest output edge is then the length the
// input's edges have on average, and the output has about as many vertices as a mesh of that
// edge length (a packing has about area / (0.87·d²) vertices, most edges within 1.25 d). But not
// above the d of about kMinDefaultVertices vertices: a CAD export has few, long triangles, and its
// mean edge length is the size of its parts, not a resolution.
constexpr double kDefaultRemeshDiameterPerEdge = 1.0;
constexpr double kMinDefaultVertices = 1000;
double defaultDiameterOf(double meanEdge, double area);
// Barycentric tolerance of the inside test of a candidate on a triangle.
constexpr double kInsideTolerance = 1e-9;
// A region's triangle lies beyond the input's boundary when its centroid's closest input point is
// on a boundary edge and farther than this many d.
constexpr double kOutsideTolerancePerD = 0.05;
// d is refused when it is larger than this many times the input's bounding-box diagonal.
constexpr double kMaxDiameterPerDiagonal = 0.5;

struct RemeshStat {
  size_t inputVertices = 0, inputFaces = 0;
  size_t inputComponents = 0;     // edge-connected pieces of the input
  size_t inputBoundaryEdges = 0;
  size_t inputSlivers = 0;        // faces of nearly zero area (height below 1e-8 of their longest edge):
                                  // they join their neighbours but hold no vertex, and no crease runs along them
  double inputMeanEdge = 0;
  double inputArea = 0;
  double sphereDiameter = 0;      // d actually used
  std::string diameterReason;
  size_t vertices = 0, faces = 0;
  size_t creaseEdges = 0;         // feature edges: crease edges (faces' normals differ by more than the crease angle) and boundary edges
  size_t featureCorners = 0;      // input vertices where crease lines end or meet
  size_t featureVertices = 0;     // vertices placed on the corners and crease lines before the growth
  size_t featureVerticesSkipped = 0; // corners and crease points left out: closer than d to one placed before
  size_t componentsStarted = 0;   // starting pairs placed (one per part of the input reached)
  size_t unreachedFaces = 0;      // input triangles with no vertex within d
  size_t candidates = 0, requeued = 0, rejectedTooClose = 0, rejectedCrossing = 0, rejectedInconsistent = 0;
  size_t holes = 0;               // regions left open (border limit, not triangulable, beyond the input's boundary)
  size_t regionsOutside = 0;      // of which: beyond the input's boundary
  size_t flatFacesRemoved = 0;
  size_t shortEdgeFacesRemoved = 0; // region faces across two patches with an edge below d (left out)
  size_t nonManifoldVerticesRemoved = 0, selfIntersectionFacesRemoved = 0, facesRemoved = 0;
  size_t holesClosed = 0;         // boundary loops closed by the hole pass (packer_steps.h, closeHoles)
  size_t holeFacesAdded = 0, holeFacesRemoved = 0; // faces the pass added, and took out around the holes
  // Loops the pass left open, by why (as Stat's holesTooLong ... holesOther): too long, not
  // triangulable, not on the input (or an edge below d), folded, crossing, not a simple loop.
  std::array<size_t, 6> holesOpen{};
  size_t piecesDropped = 0, pieceFacesDropped = 0; // pieces below RemeshParams::minPieceFaces, not the largest on their input component
  size_t boundaryLoops = 0;       // of the output
  double smallestEdge = 0;        // as stored
  double qualityAvg = 0;
  double seconds = 0, secondsInput = 0, secondsGrowth = 0, secondsTriangulation = 0, secondsCleanup = 0,
         secondsOutput = 0;
  std::vector<std::string> warnings;
};

// The default d of a mesh (0 when it has no usable edge).
double defaultRemeshDiameter(const MeshArrays& mesh);

// Remeshes `mesh` (vertices and faces; a face index of ~0u or out of range is refused) into `out`
// (cleared first), with per-face quality Q_t. `floatStorage`: the output layer stores float
// coordinates (the checks that must hold on the saved mesh are made on the rounded positions).
// Throws growth::Error on bad input (no faces, a non-manifold edge or vertex, a face of zero area or
// with a repeated vertex, d too small or too large) and growth::Cancelled when cb returns false; `out` is then left empty.
void remesh(const MeshArrays& mesh, bool floatStorage, MeshArrays& out, const RemeshParams& params, RemeshStat& st,
            CallBackPos* cb = nullptr);

} // namespace spherepack
} // namespace growth
