#pragma once
// The sphere packer's method steps, one file per section of the paper, which build()
// (sphere_packer.cpp) runs in the paper's order; the parts they use (box_grid.h, splats.h, ...) are
// listed in sphere_packer.h. Internal to the engine (namespace growth::spherepack::detail); the
// public API is sphere_packer.h. Each step is described at its definition.
#include "sphere_packer.h"

#include "borders.h"
#include "box_grid.h"
#include <growth/input_cloud.h>
#include <growth/mesh_arrays.h>
#include <growth/progress.h>
#include "region_triangulation.h"
#include "splats.h"

#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace growth {
namespace spherepack {
namespace detail {

// First neighbourhood of the local splat radii (splats.h): twice a typical Voronoi radius.
constexpr double kSplatFirstReachPerAreaSpacing = 2.5;
// Splats with a radius above this many d are referred to by the boxes their disk comes near
// (BoxGrid::build's extraReach); smaller ones by the boxes their centre is within d of, as in the
// paper (a location on the surface is nearly always covered by a nearby point's splat as well).
constexpr double kLargeSplatPerD = 1.0;
// A start after the first (sec. 3.3 again) keeps this many d from every vertex: two spacings or
// so more than the d that any vertex keeps, so that no start lands on a second layer of a surface
// already meshed (flaps on misregistered scan layers lie up to about 2 d off the mesh).
constexpr double kStartClearancePerD = 2.0;
constexpr double kTriangleAreaFactor = 0.86602540378443864676; // √3/2: area per vertex of a d-lattice is (√3/2)·d²

// A number for the log and the messages, 4 significant digits (sphere_packer.cpp).
std::string fmt(double v);

// The points renumbered in a spatial order, for memory locality on large clouds: by the Morton
// code of their boxes of side d, equal codes in input order. Everything the method does in an
// order of the points keeps the input order through these maps (box lists, ties of neighbours
// and of the starting vertex), so the mesh is the same as without renumbering. Small clouds fit
// in the caches and are not renumbered (orig/rank stay empty: identity): Params::spatialOrderMinPoints,
// 20,000 by default (below it the order makes no difference to the time).
struct Renumbering {
  std::vector<std::uint32_t> orig; // new index -> input index (until the starting vertices)
  std::vector<std::uint32_t> rank; // input index -> new index (for the box grid)
  std::uint32_t origOf(std::uint32_t i) const { return orig.empty() ? i : orig[i]; }
  std::uint32_t rankOf(std::uint32_t k) const { return rank.empty() ? k : rank[k]; }
};

// A starting pair (sec. 3.3): two positions on splats, between d and 2d apart.
struct StartPair {
  Vec3d s1, s2;
  std::uint32_t splat1 = 0, splat2 = 0;
};

// The sizes the method runs at.
struct Sizes {
  CloudScale scale;    // the cloud's sampling and noise
  double d = 0;        // sphere diameter: the edge length
  double s = 0;        // splat size (sec. 4.3)
  double expected = 0; // vertices expected: the surface area over the area per vertex of a d-lattice
};

// packer_sizes.cpp, sec. 3.1, 4.3 and 5.3: the input checked, the sizes d and s, the spatial order.
InputCloud readInput(CloudArrays cloud, Stat& st);
Sizes chooseSizes(const InputCloud& in, const Params& params, Stat& st);
Renumbering spatialOrder(InputCloud& in, double d, size_t minPoints);
// Points this many d (along an axis) from the bulk of the cloud or more can be left out when the
// cloud does not fit in the box grid: far beyond the reach of any box, splat or sphere of diameter d
// around a point kept (BoxGrid::kMaxExtraReach + 2).
constexpr double kFarGapPerD = 8.0;
// When the points span more than the box grid can index at d (BoxGrid::maxExtent), the points far
// from the bulk of the cloud are left out (Stat::farPointsLeftOut, a warning): per axis, the bulk
// is the 1 %–99 % quantiles of the coordinates, widened by every point joined to it by steps
// shorter than kFarGapPerD·d, then by the further groups of points (split by gaps of at least that)
// nearest first while the span fits; a point outside it on any axis is left out. Throws
// growth::Error when the bulk itself does not fit (parts of the cloud too far apart for d). A
// cloud that fits is left as it is.
void leaveOutFarPoints(InputCloud& in, double d, Stat& st);

// packer_prepare.cpp, sec. 4.3 and 4.1: the splat radii and the box grid.
std::vector<float> splatRadii(const InputCloud& in, const Sizes& z, const Params& params, const Renumbering& order,
                              Stat& st, Progress& progress);
// The engine's peak memory, estimated from the cloud, its sizes and splat radii (Stat::Memory has
// the parts measured): the box grid's references from the boxes within each point's reach, its
// boxes from the surface area, the growth from the vertices expected.
struct MemoryEstimate {
  size_t input = 0, boxGrid = 0, growth = 0, peak = 0;
};
// Boxes a surface crosses per d² of its area (a plane at a random orientation: 1.5; measured 1.63
// on the generated torus, more on noisy scans), also per box of the plane in reach of a point.
constexpr double kSheetBoxesPerArea = 1.8;
// Bytes per box built (its ids' share of the 4 × 4 × 4 blocks a surface crosses, CSR offsets of its
// list and own points, normal code, minimum, state and flags: 40–43 measured), per vertex of the
// growth (graph G: position, normal, rotation; vertex grid; queue) and per entry of the splat
// vertex lists (chunks of three: 16 bytes, about 5.5 an entry), as allocated.
constexpr double kBoxBytes = 42;
constexpr double kGrowthBytesPerVertex = 110;
constexpr double kListBytesPerEntry = 5.5;
// Without the radii (null), every splat is taken as small (reach d): a lower bound, checked before
// the splat radii are computed.
MemoryEstimate estimateMemory(const InputCloud& in, const std::vector<float>* radius, const Sizes& z);
// Sets Stat::memory.estimate and .limit; throws growth::Error, with the estimate, when it exceeds
// Params::maxMemoryBytes (0: the memory available, availableMemoryBytes()).
void checkMemory(const MemoryEstimate& e, const Sizes& z, const Params& params, Stat& st);
// The memory the machine has available for a new process without swapping (Linux: MemAvailable
// in /proc/meminfo); 0 where unknown.
size_t availableMemoryBytes();
void buildBoxGrid(BoxGrid& grid, const InputCloud& in, const std::vector<float>& radius, double d,
                  const Params& params, const Renumbering& order, Stat& st, Progress& progress);

// packer_start.cpp, sec. 3.3: the starting pairs.
// side: the normal of the side asked for (the box's layer facing it, in a two-sided box; zero:
// the first layer).
bool projectOntoClosestSplat(const Vec3d& x, const Vec3d& side, const InputCloud& in,
                             const std::vector<float>& radius, const BoxGrid& grid, const Renumbering& order,
                             bool searchAll, Vec3d& proj, std::uint32_t& splat);
StartPair firstStartPair(const InputCloud& in, const std::vector<float>& radius, const BoxGrid& grid,
                         const Renumbering& order, double d, double s, const Params& params);

// Sec. 3.3 at input point i: s1 = p_i on its own splat, s2 the projection onto the closest splat
// of a point 1.5·d away in p_i's tangent plane (12 directions tried in turn), between d and 2d
// from s1. Both must pass `free` (no vertex closer than d). False when p_i is isolated (fewer
// than 3 other points within d: no part that can hold a triangle) or no direction works.
template <class Free>
bool startPairAt(std::uint32_t i, const InputCloud& in, const std::vector<float>& radius, const BoxGrid& grid,
                 const Renumbering& order, double d, Free&& free, StartPair& out) {
  const Vec3d& p = in.points[i];
  const int box = grid.boxOf(p, in.normals[i]);
  if (box < 0) return false;
  int around = 0;
  for (const std::uint32_t* it = grid.pointsBegin(box); it != grid.pointsEnd(box) && around < 4; ++it)
    around += (in.points[*it] - p).SquaredNorm() <= d * d ? 1 : 0;
  if (around < 4 || !free(p)) return false;
  Vec3d e1, e2;
  tangentFrame(in.normals[i], e1, e2);
  for (int k = 0; k < 12; ++k) {
    const double phi = 2 * 3.14159265358979323846 * k / 12;
    const Vec3d target = p + (e1 * std::cos(phi) + e2 * std::sin(phi)) * (1.5 * d);
    Vec3d q;
    std::uint32_t sq = 0;
    if (!projectOntoClosestSplat(target, in.normals[i], in, radius, grid, order, false, q, sq)) continue;
    const double dist = (q - p).Norm();
    if (dist >= d && dist <= 2 * d && free(q)) {
      out = StartPair{p, q, i, sq};
      return true;
    }
  }
  return false;
}

// packer_growth.h, sec. 3.4-3.6: the disk growing; packer_growth.cpp: on every part of the cloud.
class Growth;
void growEveryPart(Growth& growth, const StartPair& first, const InputCloud& in, const std::vector<float>& radius,
                   const BoxGrid& grid, const Renumbering& order, double d, Stat& st);
size_t unreachedPoints(const Growth& growth, size_t points);
struct CloudFeatures;
void placeCloudFeatures(Growth& growth, const CloudFeatures& features, const std::vector<Vec3d>& points, double d,
                        Stat& st);

// packer_regions.cpp, sec. 3.7: the regions triangulated; the clean-up (manifold, no intersecting
// faces, no small pieces).
// `floatStorage`: the output layer stores float coordinates (CloudArrays::floatStorage); the
// checks that must hold on the saved mesh are made on the positions rounded so.
std::vector<Triangle> triangulate(const BorderGraph& g, const Params& params, bool floatStorage, Stat& st);
void makeManifold(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, bool floatStorage,
                  Stat& st);
void dropSmallPieces(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, Stat& st);

// packer_holes.cpp: the hole pass (docs/design/spherepack-holes.md). Where the cloud is: the
// splats, kept in float (16 bytes a point) once the input is freed.
struct CloudCover {
  std::vector<float> xyz;    // the points, 3 floats each
  std::vector<float> radius; // their splat radii (sec. 4.3)
  float largest = 0;         // the largest radius
  size_t memoryBytes() const { return xyz.capacity() * sizeof(float) + radius.capacity() * sizeof(float); }
};
CloudCover cloudCover(const std::vector<Vec3d>& points, const std::vector<float>& radius);
// A closure's face is where the cloud is when its centroid lies on a splat widened by
// kCoverWidenPerD·d and thickened along the face's normal: a point within its splat radius +
// kCoverWidenPerD·d of the centroid across the normal, and within the reach along it, the larger
// of kCoverReachPerD·d and kCoverReachPerLoopRadius × the loop's radius (the largest distance of
// its vertices from their centroid). A closure is a chord of the surface, off it by up to the
// sagitta of the hole, which grows with the hole; where the sampling is sparser than the largest
// splat radius s allows, the splats (clamped to s) leave gaps, which are the holes the growth
// could not fill. Across a real boundary of an open surface no splat reaches: its loop is longer
// than ∂max, so the middle of its closure lies farther than s + d from the cloud across the
// normal, and the surface does not come back within half the loop's radius along it.
constexpr double kCoverReachPerD = 2.0;
constexpr double kCoverReachPerLoopRadius = 0.5;
constexpr double kCoverWidenPerD = 1.0;
// Loops of more edges are left open without a try (the ear cut is quadratic in the loop's length).
constexpr int kMaxHoleLoop = 2000;
// A hole whose closures all fail a check (but the cloud's) grows by a ring of faces, up to this
// many times, and is tried again: the faces next to it are often the folded ones that kept it open.
constexpr int kMaxHoleRings = 2;
// Where a ring leaves the grown hole pinched or split, the faces around those vertices join it, up
// to this many times.
constexpr int kMaxRingFixes = 3;
// How far the rings are expected to grow a hole, per ring, in d (the packing's edges are d long,
// sec. 3.4, the regions' diagonals a few d): the faces and splats near the holes are gathered that
// far around them. A closure face reaching beyond counts as crossing, one beyond the splats
// gathered as not covered: the hole then stays open.
constexpr double kMaxEdgePerD = 3.0;
// Loops of more edges get the ear cut only, not the least-bend triangulation (cubic in the length).
constexpr int kMaxLeastBendLoop = 150;
// A closure's face and the mesh's face across a loop edge bend by less than this (a face folded
// flat back onto the mesh is refused; the mesh's own creases near a hole can reach 150°).
constexpr double kCosMaxClosureBend = -0.95; // about 162°
// A loop faces away from the mesh when the mean of (the normal of the mesh's face across each loop
// edge) · (the loop's unit area normal) is below −kFacesAwayShare. The outline of a piece that is a
// disk of its own, seen from outside, is near −1 (its closure would double the piece); a loop that runs
// along a crease of about 90° (the rim of a flat end) is near 0, with a sign that noise decides, and
// is tried (the fold check, kCosMaxClosureBend, still refuses a closure lying back on the mesh).
constexpr double kFacesAwayShare = 0.5;
// Every boundary loop of `faces` (manifold, oriented) is closed by sec. 3.7's ear cut of the loop
// projected on the plane of its area normal, using the packing's vertices only (so every new edge
// is >= d), when every new face is where the cloud is (`cover`, kCoverReachPerD) and the new faces
// have no (nearly) collinear vertices, add no edge the mesh has, do not fold back onto the mesh
// along the loop (kCosMaxClosureBend) and intersect neither the mesh nor the closures accepted
// before them; and the loop faces the way the mesh around it does (its area normal and the
// normals of the mesh's faces along it agree on the whole: the loop of a piece that is a disk of
// its own, whose closure would double it, faces the other way: kFacesAwayShare). The mesh stays manifold and
// oriented: a disk is glued along each loop closed.
void closeHoles(std::vector<Triangle>& faces, const BorderGraph& g, const CloudCover& cover, const Params& params,
                bool floatStorage, Stat& st);
// The same pass where the surface is given by a test of a closure's face (a, b, c) instead of the
// cloud (the remesher: on the input mesh); `reach` as for the cloud. Always on; st.sphereDiameter
// is d. Islands are kept: every piece lies on the surface (a second sheet of the input within the
// cover reach, as a misregistered scan has, is part of the surface).
using CoverTest = std::function<bool(const Vec3d& a, const Vec3d& b, const Vec3d& c, double reach)>;
void closeHoles(std::vector<Triangle>& faces, const BorderGraph& g, const CoverTest& covered, bool floatStorage,
                Stat& st);

// packer_output.cpp: the mesh with the triangle quality Q_t of sec. 5, its topology checked (on
// the output alone, once the graph and the faces are freed: the check's arrays, about 100 bytes a
// face, then stay below the growth's peak), and the report.
void writeMesh(const std::vector<Triangle>& faces, const BorderGraph& g, bool floatStorage, MeshArrays& out,
               Stat& st);
// The share of the points whose nearest point's normal points to the other side, asked for when
// many boxes see normals that disagree (Stat::boxesDTooLarge); 0 otherwise.
double oppositeNormalShare(const InputCloud& in, const CloudScale& scale, const Stat& st);
// `opposite`: oppositeNormalShare, taken before the input was freed.
void checkTopology(const MeshArrays& out, Stat& st);
void report(size_t inputPoints, double opposite, double d, double s, size_t graphVertices, bool noFaces, Stat& st);

} // namespace detail
} // namespace spherepack
} // namespace growth
