#pragma once
// Mesh quality measures: the instrument the tests, the filters' logs and the benchmark share.
//
// Everything is computed in double on a mesh's arrays (MeshArrays; the glue's overloads for a
// MeshLab layer, growth/meshlab/layer.h, ignore its deleted faces and vertices). Definitions:
// - Q_t = 4·√3·A / (l1² + l2² + l3²), Q_avg its mean, Q_RMS the RMS deviation in % of Q_avg
//   (sphere-packing paper, sec. 5; equals vcglib's QualityMeanRatio). 1 for the equilateral
//   triangle, √3/2 for the right isosceles one.
// - QF = √12 / d_max · sqrt((p − d1)(p − d2)(p − d3) / p), p the half perimeter (Robust G2S,
//   eq. 5.1); computed as √12·A / (p·d_max), the same value by Heron's formula.
// - E_avg, E_RMS (in % of E_avg), E_min, E_max over the unique undirected edges.
// - Topology: an edge with one face is a boundary edge, with more than two a non-manifold edge;
//   an edge with two faces that both traverse it in the same direction is orientation-inconsistent.
//   A vertex is non-manifold when its incident faces form more than one fan, a fan being a sequence
//   of faces in which consecutive faces share an edge at the vertex that has exactly these two faces
//   (so a vertex on a non-manifold edge is always non-manifold, and boundary vertices are checked
//   too: two open fans at one vertex make it non-manifold). Boundary loops (holes) are traced by
//   walking around the fans of their vertices: they are the loops of the surface in which every
//   non-manifold vertex is split into its fans, so the two triangles of a bow-tie have two loops
//   and two holes touching at one vertex are one loop. Exact on meshes without non-manifold edges
//   (a walk that meets one ends its loop there). Components are edge-connected sets of faces
//   (like MeshLab's), so a bow-tie is two components.
// - A face with a repeated vertex is degenerate and takes no part in the edge, quality, angle and
//   topology measures (it has no well defined edges). A face whose vertices are distinct but whose
//   height is zero up to float storage (height <= 4·FLT_EPSILON·max|coordinate|) is degenerate
//   too, but still a face: its Q_t and QF are ~0 and it counts in the topology. Duplicate faces
//   are faces with the same vertex set as an earlier one (any orientation).
// - Self-intersecting pairs: pairs of faces that meet other than in the vertices and edge they
//   share, decided exactly (growth/self_intersections.h: faces sharing an edge count only when
//   folded onto each other, duplicate faces always count); faces with a repeated vertex take no
//   part.
// - Given the input cloud: the distance of every input point to the nearest face (exact point–
//   triangle distance through a bounding-volume hierarchy), its mean and maximum, and
//   μd % = mean distance / the cloud's mean nearest-neighbour spacing (growth::meanSpacing) · 100
//   (Robust G2S, sec. 5). The mean is over all input points; the points used as vertices by an
//   interpolating mesher contribute 0, so it is the paper's "distance of the unmeshed points"
//   spread over the whole cloud.
#include <growth/mesh_arrays.h>
#include <growth/vec3.h>

#include <array>
#include <cstddef>
#include <limits>
#include <string>
#include <vector>

namespace growth {

// Equal-width bins over [lo, hi]; hi itself falls into the last bin, values outside are counted in
// `below` / `above` (never silently dropped).
struct Histogram {
  double lo = 0, hi = 1;
  std::vector<size_t> counts;
  size_t below = 0, above = 0;

  Histogram() = default;
  Histogram(double lo_, double hi_, size_t bins) : lo(lo_), hi(hi_), counts(bins, 0) {}
  void add(double v);
  double binWidth() const { return counts.empty() ? 0 : (hi - lo) / double(counts.size()); }
  size_t total() const;   // all values added, including below and above
};

struct MeasureOptions {
  size_t angleBins = 180;      // angle histogram over [0°, 180°]
  size_t qualityBins = 100;    // Q_t histogram over [0, 1]
  size_t edgeBins = 100;       // edge length histogram over [0, edgeHistogramMax]
  double edgeHistogramMax = 0; // 0: 3·E_avg; give the same value to compare several meshes
  bool minVertexDistance = true; // compute the smallest distance between two vertices
};

// One edge-connected component: its own counts. The genus is (2 − χ − boundaryLoops) / 2, defined
// (otherwise −1) under the same conditions as MeshMeasures::genus, which is the sum of these.
struct ComponentTopology {
  size_t faces = 0, vertices = 0, edges = 0, boundaryLoops = 0;
  int eulerCharacteristic = 0;   // V − E + F of the component
  int genus = -1;
};

struct MeshMeasures {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

  // Counts
  size_t vertices = 0;              // live vertices
  size_t faces = 0;                 // live faces
  size_t unreferencedVertices = 0;  // live vertices used by no face
  size_t edges = 0;                 // unique undirected edges (of faces without repeated vertex)
  double boxDiagonal = kNaN;        // bounding-box diagonal of the live vertices

  // Edge lengths
  double edgeMean = kNaN;           // E_avg
  double edgeRmsPercent = kNaN;     // E_RMS, % of E_avg
  double edgeMin = kNaN, edgeMax = kNaN;
  double minVertexDistance = kNaN;  // smallest distance between two distinct live vertices

  // Triangle shape
  double qualityMean = kNaN;        // Q_avg
  double qualityRmsPercent = kNaN;  // Q_RMS, % of Q_avg
  double qualityMin = kNaN;
  double qfMean = kNaN;             // Di Angelo's QF, mean
  double minAngleDeg = kNaN, maxAngleDeg = kNaN;

  // Topology and defects
  size_t boundaryEdges = 0;
  size_t nonManifoldEdges = 0;      // edges with more than two faces
  size_t nonManifoldVertices = 0;   // vertices whose incident faces form more than one fan
  size_t boundaryLoops = 0;         // holes
  size_t components = 0;            // edge-connected face sets
  size_t inconsistentEdges = 0;     // two-face edges traversed in the same direction by both
  size_t degenerateFaces = 0;       // repeated vertex or zero area
  size_t duplicateFaces = 0;        // same vertex set as an earlier face
  size_t selfIntersectingPairs = 0; // face pairs meeting beyond their shared vertices and edge
  int eulerCharacteristic = 0;      // V − E + F over the referenced vertices and proper faces
  std::vector<ComponentTopology> perComponent; // largest (most faces) first
  int genus = -1;                   // handles, summed over components: (2·components − χ − boundaryLoops) / 2;
                                    // −1 unless manifold, consistently oriented, without duplicate faces or faces with a
                                    // repeated vertex (zero-area faces count: they are faces of the surface)

  // Distance of the input cloud to the mesh (only when a cloud was given)
  bool hasCloud = false;
  size_t cloudPoints = 0;
  double cloudSpacing = kNaN;       // mean nearest-neighbour spacing of the cloud
  double distanceMean = kNaN;
  double distanceMax = kNaN;
  double muDPercent = kNaN;         // distanceMean / cloudSpacing · 100
  size_t pointsFartherThanSpacing = 0; // input points farther from the mesh than cloudSpacing

  Histogram angleHistogram;         // degrees, three angles per face
  Histogram edgeHistogram;          // absolute lengths
  Histogram qualityHistogram;       // Q_t

  bool consistentlyOriented() const { return inconsistentEdges == 0; }
  bool manifold() const { return nonManifoldEdges == 0 && nonManifoldVertices == 0; }
  std::string toJson() const;       // one JSON object; NaN written as null
};

// All measures at once. `cloud`: the input points (e.g. growth::readCloud(...).points), or null.
MeshMeasures measure(const MeshArrays& mesh, const std::vector<Vec3d>* cloud = nullptr,
                     const MeasureOptions& options = MeasureOptions());

// --- Single triangles (lengths in any unit) ---
double triangleQuality(const Vec3d& a, const Vec3d& b, const Vec3d& c); // Q_t
double triangleQF(const Vec3d& a, const Vec3d& b, const Vec3d& c);      // QF

// --- Topology only, for tests (each call analyses the whole mesh once) ---
struct MeshTopology {
  size_t boundaryEdges = 0, nonManifoldEdges = 0, nonManifoldVertices = 0, boundaryLoops = 0,
         components = 0, inconsistentEdges = 0, degenerateFaces = 0, duplicateFaces = 0,
         unreferencedVertices = 0, edges = 0;
};
MeshTopology measureTopology(const MeshArrays& mesh);

std::vector<ComponentTopology> componentTopology(const MeshArrays& mesh); // largest first

size_t countBoundaryEdges(const MeshArrays& mesh);
size_t countNonManifoldEdges(const MeshArrays& mesh);
size_t countNonManifoldVertices(const MeshArrays& mesh);
size_t countBoundaryLoops(const MeshArrays& mesh);
size_t countComponents(const MeshArrays& mesh);
size_t countInconsistentEdges(const MeshArrays& mesh);
bool isConsistentlyOriented(const MeshArrays& mesh);
size_t countDegenerateFaces(const MeshArrays& mesh);
size_t countDuplicateFaces(const MeshArrays& mesh);
size_t countSelfIntersections(const MeshArrays& mesh); // self-intersecting face pairs

// Exact distance from points to the nearest live face of a mesh, in double, through a bounding
// volume hierarchy over the faces (built once; a query costs about log(faces)). The mesh may be
// changed or destroyed after construction: the index keeps its own copy.
class MeshDistance {
public:
  explicit MeshDistance(const MeshArrays& mesh);
  bool empty() const { return tri_.empty(); }
  // Distance to the nearest face; +infinity when the mesh has no face. `hint` (optional), on entry
  // a triangle likely near p or -1, on return the nearest triangle: passing the previous answer
  // speeds up queries made in spatial order.
  double distance(const Vec3d& p, int* hint = nullptr) const;

private:
  struct Node {
    double lo[3], hi[3];
    int first;   // leaf: first triangle in tri_; inner: index of the left child (right = first + 1)
    int count;   // leaf: number of triangles (> 0); inner: 0
  };
  struct Item {
    Vec3d centroid;
    int face;
  };
  void build(int node, int begin, int end, std::vector<Item>& items);
  double squaredDistanceToTriangle(const Vec3d& p, int t) const;

  std::vector<Vec3d> vert_;
  std::vector<std::array<int, 3>> tri_;
  std::vector<Node> nodes_;
};

// Distance statistics of `cloud` to `mesh` (fields hasCloud … pointsFartherThanSpacing of
// MeshMeasures are filled).
void measureCloudDistance(const MeshArrays& mesh, const std::vector<Vec3d>& cloud, MeshMeasures& out);

// --- Distance between two surfaces (a remeshed mesh and its input) ---
// Points on a mesh's surface: every vertex some proper face uses (their count in *vertexSamples),
// then `extra` points drawn with growth::Random(seed), each on a face taken with probability
// proportional to its area and uniform in it.
std::vector<Vec3d> sampleSurface(const MeshArrays& mesh, size_t extra, std::uint64_t seed, size_t* vertexSamples = nullptr);

// Distance from the surface of `from` to the faces of `to`: from's vertices and as many area-weighted
// points as from has faces (sampleSurface), each measured exactly to the nearest triangle of `to`
// (MeshDistance). `max` is a lower bound of the one-sided Hausdorff distance, reached where the
// farthest point of `from` is a vertex or a sample. NaN when either mesh has no face.
struct SurfaceDistance {
  size_t samples = 0, vertexSamples = 0;
  double mean = MeshMeasures::kNaN, max = MeshMeasures::kNaN;
  double vertexMax = MeshMeasures::kNaN;   // the largest over from's vertices alone
};
SurfaceDistance surfaceDistance(const MeshArrays& from, const MeshArrays& to, std::uint64_t seed = 1);

} // namespace growth
