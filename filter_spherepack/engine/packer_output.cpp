// The output mesh with the triangle quality Q_t of sec. 5, and the report (packer_steps.h).
#include "packer_steps.h"

#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/mesh_measures.h>
#include <growth/point_grid.h>

#include "stored_positions.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace growth {
namespace spherepack {
namespace detail {

namespace {

// Unoriented normals (a sign that changes from point to point) are told from thin parts and folds,
// which also make boxes see two sides (BoxGrid's d-too-large count), by the points' nearest
// neighbours: their normals point to opposite sides for about half of the points when the signs
// are random, and for almost none on an oriented cloud (the nearest neighbour of a point of a thin
// part lies on the same side). Checked when at least kTwoSidedBoxShareToCheck of the boxes see two
// sides; the normals look unoriented when at least kOppositeNeighbourShare of the points have an
// opposite nearest neighbour.
constexpr double kTwoSidedBoxShareToCheck = 0.1;
constexpr double kOppositeNeighbourShare = 0.2;
constexpr size_t kOrientationSamples = 4096;

// Share of the sampled points (a fixed stride) whose nearest other point has a normal with a
// negative product with theirs. `cell`: the grid's cell size (about the spacing).
double oppositeNeighbourShare(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                              double cell) {
  if (points.size() < 2 || !(cell > 0)) return 0;
  PointGrid grid;
  grid.build(points, cell);
  const size_t stride = std::max<size_t>(1, points.size() / kOrientationSamples);
  size_t sampled = 0, opposite = 0;
  for (size_t i = 0; i < points.size(); i += stride) {
    const int j = grid.nearest(points[i], nullptr, int(i));
    if (j < 0) continue;
    ++sampled;
    opposite += normals[i] * normals[size_t(j)] < 0 ? 1 : 0;
  }
  return sampled > 0 ? double(opposite) / double(sampled) : 0;
}

} // namespace

// Output: referenced vertices only (in the order of creation), the triangle quality Q_t of sec. 5
// per face; its topology measured. (The glue gives the layer its normals.)
void writeMesh(const std::vector<Triangle>& faces, const BorderGraph& g, bool floatStorage, MeshArrays& out,
               Stat& st) {
  std::vector<std::int32_t> remap;
  assignHuge(remap, g.vertexCount(), std::int32_t(-1));
  std::vector<std::uint32_t> used;
  reserveHuge(used, g.vertexCount(), /*populate=*/true); // all of it but unreferenced vertices
  for (const auto& f : faces)
    for (std::uint32_t v : f)
      if (remap[v] < 0) {
        remap[v] = static_cast<std::int32_t>(used.size());
        used.push_back(v);
      }
  // Deterministic vertex order: by the order of creation.
  std::sort(used.begin(), used.end());
  for (size_t i = 0; i < used.size(); ++i) remap[used[i]] = static_cast<std::int32_t>(i);

  if (!faces.empty()) {
    // Exact sizes reserved first: the vectors are allocated once and made resident in one call.
    reserveHuge(out.vertices, used.size(), /*populate=*/true);
    for (size_t i = 0; i < used.size(); ++i) out.vertices.push_back(g.position(used[i]));
    reserveHuge(out.faces, faces.size(), /*populate=*/true);
    reserveHuge(out.faceQuality, faces.size(), /*populate=*/true);
    double qsum = 0, minEdge = std::numeric_limits<double>::infinity();
    for (size_t k = 0; k < faces.size(); ++k) {
      const auto& f = faces[k];
      out.faces.push_back({std::uint32_t(remap[f[0]]), std::uint32_t(remap[f[1]]), std::uint32_t(remap[f[2]])});
      const Vec3d a = g.position(f[0]), b = g.position(f[1]), c = g.position(f[2]);
      const double l1 = (b - a).SquaredNorm(), l2 = (c - b).SquaredNorm(), l3 = (a - c).SquaredNorm();
      const double area2 = ((b - a) ^ (c - a)).Norm();
      const double q = (l1 + l2 + l3) > 0 ? 2 * std::sqrt(3.0) * area2 / (l1 + l2 + l3) : 0;
      out.faceQuality.push_back(q);
      qsum += q;
      // The smallest edge as the layer stores it (rounded to its scalar), not as computed.
      const Vec3d sa = asStored(a, floatStorage), sb = asStored(b, floatStorage), sc = asStored(c, floatStorage);
      minEdge = std::min(minEdge, std::sqrt(std::min((sb - sa).SquaredNorm(),
                                                     std::min((sc - sb).SquaredNorm(), (sa - sc).SquaredNorm()))));
    }
    st.qualityAvg = qsum / double(faces.size());
    st.smallestEdge = minEdge;
    const double d = st.sphereDiameter;
    if (minEdge < d * (1 - kSmallestEdgeTolerance)) {
      double magnitude = 0;
      for (const Vec3d& v : out.vertices)
        for (int a = 0; a < 3; ++a) magnitude = std::max(magnitude, std::abs(asStored(v, floatStorage)[a]));
      // The storage's step at that magnitude.
      auto stepAt = [](auto big) { return double(std::nextafter(big, std::numeric_limits<decltype(big)>::max()) - big); };
      const double step = floatStorage ? stepAt(static_cast<float>(magnitude)) : stepAt(magnitude);
      const int digits = floatStorage ? std::numeric_limits<float>::digits : std::numeric_limits<double>::digits;
      st.warnings.push_back(
          "The smallest edge of the mesh as stored is " + fmt(minEdge) + ", below d = " + fmt(d) + " (by " +
          fmt(100 * (1 - minEdge / d)) + " %): every edge is at least d in the engine's double precision, but "
          "the layer stores " + std::string(digits > 24 ? "double" : "float") + " coordinates, and at "
          "coordinates up to " + fmt(magnitude) + " they are rounded to steps of " + fmt(step) + " (a vertex "
          "moves by up to half a step on each axis). To keep the guarantee, mesh and keep the cloud near the "
          "origin (Filters > Normals, Curvatures and Orientation > Transform: Translate, Center, set Origin), "
          "or use a double-precision build (MeshLab 2025.07d, PyMeshLab): moved back to these coordinates in "
          "float, the mesh is rounded the same way.");
    }
  }
  st.vertices = used.size();
  st.faces = faces.size();
}

void checkTopology(const MeshArrays& out, Stat& st) {
  if (out.faces.empty()) return;
  const MeshTopology topo = measureTopology(out);
  st.nonManifoldVertices = topo.nonManifoldVertices;
  st.nonManifoldEdges = topo.nonManifoldEdges;
  st.boundaryLoops = topo.boundaryLoops;
  st.holes = topo.boundaryLoops;
}

// The report: warnings on what the cloud made the method do (unoriented normals, d too large for
// sec. 4.1's normal filter, faces removed, points unreached), and the errors of a non-manifold or
// empty result.
double oppositeNormalShare(const InputCloud& in, const CloudScale& scale, const Stat& st) {
  return double(st.boxesDTooLarge) >= kTwoSidedBoxShareToCheck * double(st.boxes)
             ? oppositeNeighbourShare(in.points, in.normals, scale.medianSpacing)
             : 0.0;
}

void report(size_t inputPoints, double opposite, double d, double s, size_t graphVertices, bool noFaces, Stat& st) {
  if (opposite >= kOppositeNeighbourShare)
    st.warnings.push_back("The normals look unoriented: for " + fmt(100 * opposite) + " % of the points the "
                          "nearest point's normal points to the other side, and in " +
                          std::to_string(st.boxesDTooLarge) + " of " + std::to_string(st.boxes) + " boxes the "
                          "normals within d disagree, so the mesh has holes there. Orient them consistently "
                          "(Filters > Normals, Curvatures and Orientation > Compute normals for point sets "
                          "propagates one orientation) and run the filter again.");
  else if (st.boxesDTooLarge > 0)
    st.warnings.push_back("In " + std::to_string(st.boxesDTooLarge) + " of " + std::to_string(st.boxes) +
                          " boxes the point normals within d disagree (the box sees two sides of the surface): "
                          "d = " + fmt(d) + " is too large there for the paper's manifold guarantee (section 4.1): "
                          "thin parts, folds, or normals not consistently oriented. " +
                          (st.boxesTwoSided > 0 ? std::to_string(st.boxesTwoSided) + " of them kept both sides "
                                                  "apart (two layers), so both are meshed where the part is at "
                                                  "least d thick; a part thinner than d gets one side only (no two "
                                                  "vertices are closer than d). "
                                                : std::string()) +
                          "Try a smaller d, or re-orient the normals.");
  if (st.facesRemoved > 0)
    st.warnings.push_back("The packing was not manifold at " + std::to_string(st.nonManifoldVerticesRemoved) +
                          " vertices and had " + std::to_string(st.selfIntersectionFacesRemoved) +
                          " faces through others; " + std::to_string(st.facesRemoved) + " faces were removed "
                          "there (the fewest that make it manifold and free of intersections), leaving holes. "
                          "Usual causes: noise beyond d/2 (paper, section 5.3: use a larger d), thin parts (a "
                          "smaller d), misregistered scans.");
  if (st.nonManifoldVertices > 0 || st.nonManifoldEdges > 0) // cannot happen: makeManifold
    throw std::logic_error("sphere packing: the output is not manifold after the clean-up");
  if (st.unreachedPoints * 100 > inputPoints)
    st.warnings.push_back(fmt(100.0 * double(st.unreachedPoints) / double(inputPoints)) +
                          " % of the points have no vertex within d: parts too small or too sparse to hold a "
                          "triangle of side d (a growth was started on every part that could), or the growth "
                          "was stopped by a defect there.");
  if (noFaces)
    throw Error("No triangle could be built: the growth stopped after " + std::to_string(graphVertices) +
                " vertices. d = " + fmt(d) + " and s = " + fmt(s) + " do not fit this cloud: the splats must cover "
                "the surface, and the noise must stay below d/2 (paper, section 5.3). Try the defaults, or a larger d.");
}

} // namespace detail
} // namespace spherepack
} // namespace growth
