#include "g2s.h"

#include "g2s_mesher.h"

#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>
#include <growth/progress.h>
#include <growth/stopwatch.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <sstream>

namespace growth {
namespace g2s {

namespace {

void checkParams(const Params& p) {
  if (!(p.seedSearchFactor > 0) || !(p.seedSearchFactor <= 100))
    throw Error("The seed search factor k must be greater than 0 and at most 100 (default 2).");
  if (!std::isfinite(p.maxSearchRadiusFactor) || p.maxSearchRadiusFactor > 100 ||
      (p.maxSearchRadiusFactor > 0 && p.maxSearchRadiusFactor < 1))
    throw Error("The maximum search radius must be between 1 and 100 times the local spacing (or 0 for "
                "the default, " + std::to_string(kDefaultMaxSearchRadiusFactor).substr(0, 3) + ").");
  if (p.sizeLevels < 1 || p.sizeLevels > 64)
    throw Error("The number of size priority levels n must be between 1 and 64 (default 4).");
  if (p.maxHoleEdges < 0 || p.maxHoleEdges > 10000)
    throw Error("The largest hole to close must be between 0 (off) and 10000 edges.");
  if (p.minComponentFaces < 0)
    throw Error("The smallest piece kept must be at least 0 faces (0 keeps all).");
  if (p.threads < 0 || p.threads > 1024)
    throw Error("The number of threads must be between 0 (automatic) and 1024.");
  if (p.flatnessLevels < 1 || p.flatnessLevels > 180)
    throw Error("The number of flatness priority levels m must be between 1 and 180 (default 8).");
}

// The distinct finite points of the layer (input checks: growth/input_cloud.h), with the normals
// as the layer stores them (zero where unusable), for orientComponents.
InputCloud readPoints(CloudArrays cloud, Stat& stat) {
  CloudCheck check;
  check.minPoints = 3;
  check.readNormals = true;
  check.normalsAsStored = true;
  stat.inputPoints = cloud.points.size();
  InputCloud input = readCloud(std::move(cloud), check);
  stat.duplicatesDropped = input.duplicatesDropped;
  if (input.points.size() > PointEdgeMap::kMaxPoints)
    throw Error("The layer has more than " + std::to_string(PointEdgeMap::kMaxPoints) +
                " points, more than this filter can handle; subsample it first.");
  return input;
}

// Seeds and front growth (sec. 3.1-3.2, 4.1), with their counts.
void grow(Mesher& mesher, Stat& stat, Progress& progress) {
  mesher.meshAll(&progress);
  stat.workingBytes = mesher.memoryBytes();
  stat.seeds = mesher.seeds();
  stat.seedAttempts = mesher.seedAttempts();
  stat.cylinderQueries = mesher.cylinderQueries();
  stat.pointsVisited = mesher.pointsVisited();
  stat.candidateSearches = mesher.candidateSearches();
  stat.edgesLeftAtFullPoints = mesher.edgesLeftAtFullPoints();
  stat.thinPartRefusals = mesher.foldsRefused();
  Stat::Pass rim;
  rim.name = "thin-part rims (in the growth)";
  rim.facesRemoved = mesher.rimPassFacesRemoved();
  rim.facesAdded = mesher.rimPassFacesAdded();
  rim.seconds = mesher.rimPassSeconds();
  stat.passes.push_back(rim);
  stat.grownFaces = mesher.liveTriangles();
  if (stat.edgesLeftAtFullPoints > 0)
    stat.warnings.push_back(std::to_string(stat.edgesLeftAtFullPoints) + " front edges were left open at points "
                            "that already had " + std::to_string(PointEdgeMap::kMaxEntries) +
                            " neighbours (the most one point can hold): the mesh has holes there.");
}

// The layer's vertex normals in the mesher's point order, where most points have a usable one
// (finite, not zero); empty otherwise. Robust G2S needs none; orientComponents uses them for the
// pieces that do not close.
std::vector<P3> layerNormals(const InputCloud& input, const Mesher& mesher) {
  std::vector<P3> normals;
  const std::vector<std::uint32_t>& order = mesher.order();
  // (order() holds the mesher's points, fewer than the input's where clumps were merged.)
  if (input.normals.empty()) return normals;
  normals.resize(order.size());
  size_t usable = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    const P3& v = input.normals[order[i]];
    const bool ok = v.SquaredNorm() > 0; // (readCloud left the unusable ones zero)
    normals[i] = v;
    usable += ok;
  }
  if (2 * usable < order.size()) normals.clear();
  return normals;
}

// One pass of the clean-up, timed, with the live faces it took out and added (new faces are
// appended to the triangles, so the added ones are the growth of that array).
// `live`: the live faces before the pass (one count per pass), updated.
template <class F>
void runPass(Mesher& mesher, Stat& stat, size_t& live, const char* name, F&& pass) {
  Stopwatch watch;
  const size_t allBefore = mesher.triangles().size();
  pass();
  Stat::Pass p;
  p.name = name;
  p.facesAdded = mesher.triangles().size() - allBefore;
  const size_t liveAfter = mesher.liveTriangles();
  p.facesRemoved = live + p.facesAdded - liveAfter;
  live = liveAfter;
  p.seconds = watch.total();
  stat.passes.push_back(p);
}

// Sec. 4.2, then what is not in the paper: faces intersecting others removed, small pieces dropped,
// small holes closed; then the boundary counts and the orientation of every component (by the
// layer's normals for the sheets, where it has them).
void cleanUp(Mesher& mesher, const Params& p, Stat& stat, InputCloud& input) {
  size_t live = mesher.liveTriangles();
  if (p.removeNonManifoldVertices) {
    runPass(mesher, stat, live, "non-manifold vertices (sec. 4.2)", [&] {
      const ManifoldCleanupStat cs = mesher.removeNonManifoldVertices();
      stat.nonManifoldVerticesRemoved = cs.nonManifoldVertices;
      stat.facesRemoved = cs.facesRemoved;
    });
    // Not in the paper: no two faces may intersect (g2s_repair.cpp).
    runPass(mesher, stat, live, "crossing faces", [&] {
      const Mesher::SelfIntersectionStat si = mesher.removeSelfIntersections();
      stat.selfIntersectionFacesRemoved = si.facesRemoved;
      stat.nonManifoldVerticesRemoved += si.nonManifoldVertices;
      stat.facesRemoved += si.fanFacesRemoved;
    });
  } else {
    stat.nonManifoldVertices = countNonManifoldVertices(mesher.triangles(), mesher.points().size(),
                                                        std::vector<char>(mesher.triangles().size(), 1));
  }
  // Not in the paper: pieces too small to be a part of the surface (triangles among stray points)
  // go before the hole pass, which then spends no time on their loops.
  if (p.minComponentFaces > 1)
    runPass(mesher, stat, live, "small pieces", [&] {
      stat.componentsDropped = mesher.dropSmallComponents(size_t(p.minComponentFaces), stat.componentFacesDropped);
    });
  if (p.maxHoleEdges > 0 && p.removeNonManifoldVertices) { // (its loops need manifold vertices)
    Mesher::HoleStat hs;
    runPass(mesher, stat, live, "hole closure", [&] { hs = mesher.closeHoles(p.maxHoleEdges); });
    runPass(mesher, stat, live, "wider hole closure and regrowth", [&] { mesher.widenHoles(p.maxHoleEdges, hs); });
    stat.holesClosed = hs.closed;
    stat.holeFacesAdded = hs.facesAdded;
    stat.holeFacesReplaced = hs.facesReplaced;
    stat.holeSpikes = hs.spikes;
    stat.holesWidened = hs.widened;
    stat.holeFacesWidened = hs.widenedFaces;
    stat.holesRegrown = hs.regrown;
  }
  Mesher::BoundaryCount boundary = mesher.boundary();
  if (p.removeNonManifoldVertices) { // (a handle count needs manifold vertices)
    // Not in the paper: small handles (tunnels between close sheets) cut, their loops closed.
    runPass(mesher, stat, live, "small handles", [&] {
      if (p.removeSmallHandles) {
        const Mesher::HandleStat hs = mesher.removeSmallHandles(boundary, p.maxHoleEdges);
        stat.handlesCut = hs.handles;
        stat.handleFacesRemoved = hs.facesRemoved;
        stat.nonManifoldVerticesRemoved += hs.nonManifoldVertices;
        stat.handleFacesAdded = hs.holeFacesAdded;
        stat.handles = hs.handlesBefore;
        if (hs.handles > 0) {
          boundary = mesher.boundary();
          stat.handles = mesher.handleCount(boundary);
        }
      } else {
        stat.handles = mesher.handleCount(boundary);
      }
    });
  }
  // The search structures go before the output's memory is taken (the repairs search).
  stat.workingBytes = std::max(stat.workingBytes, mesher.memoryBytes());
  mesher.releaseGrowthState();
  stat.boundaryEdges = boundary.edges;
  stat.holes = boundary.loops;
  runPass(mesher, stat, live, "orientation", [&] {
    // (The layer's normals only matter for pieces with a free edge: none on a closed mesh.)
    const std::vector<P3> normals = boundary.edges > 0 ? layerNormals(input, mesher) : std::vector<P3>();
    const Mesher::OrientationStat os = mesher.orientComponents(normals.empty() ? nullptr : &normals);
    stat.components = os.components;
    stat.componentsFlipped = os.flipped;
  });
  stat.workingBytes = std::max(stat.workingBytes, mesher.memoryBytes());
  // The points for the output, in the mesher's order (its point i is input point order()[i]),
  // taken before it frees them.
  input.points = mesher.points();
  mesher.releaseWorkingState();
  releaseFreeHeap(); // its freed blocks would otherwise stay resident under the output layer
}

// The live triangles into `out`, on the input points that they use (see build()).
void writeMesh(InputCloud& input, Mesher& mesher, MeshArrays& out, Stat& stat, Progress& progress) {
  // The live triangles, in order, taken out of the mesher (with alive() freed).
  std::vector<Triangle> tri = mesher.takeLiveTriangles();
  const std::vector<std::uint32_t>& order = mesher.order();
  // Output vertices: the used points in the mesher's (spatially coherent) order (mesher point i
  // is distinct point order[i]): the layer's points bit for bit.
  const size_t points = order.size();
  std::vector<std::uint32_t>& outIndex = mesher.scratch();
  outIndex.assign(points, 0);
  for (const Triangle& t : tri)
    for (std::uint32_t v : t) outIndex[v] = 1;
  std::uint32_t next = 0;
  for (std::uint32_t& o : outIndex) o = o != 0 ? next++ : ~0u;
  stat.vertices = next;
  stat.unusedPoints = points - stat.vertices;
  const size_t faces = tri.size();
  stat.faces = faces;
  if (faces > 0) {
    reserveHuge(out.vertices, stat.vertices, true);
    out.vertices.resize(stat.vertices);
    for (size_t i = 0; i < points; ++i)
      if (outIndex[i] != ~0u) out.vertices[outIndex[i]] = input.points[i];
    // Only outIndex is needed from here on.
    mesher.releaseOrder();
    std::vector<P3>().swap(input.points);
    reserveHuge(out.faces, faces, true);
    reserveHuge(out.faceQuality, faces, true);
    for (size_t f = 0; f < faces; ++f) {
      std::array<std::uint32_t, 3> t;
      for (int j = 0; j < 3; ++j) t[j] = outIndex[tri[f][j]];
      out.faces.push_back(t);
      out.faceQuality.push_back(triangleQuality(out.vertices[t[0]], out.vertices[t[1]], out.vertices[t[2]]));
      // The triangles written so far are given back a block at a time, so that they and the
      // output's faces do not add up at the peak.
      if (((f + 1) & 8191) == 0) {
        discardPages(tri.data(), (f + 1) * sizeof(Triangle));
        progress.update(double(f + 1) / double(faces));
      }
    }
    std::vector<Triangle>().swap(tri);
    progress.update(1.0);
  } else {
    stat.warnings.push_back("No seed triangle was found, so no surface was built: the points are too "
                            "few or too scattered to lie on a surface (try a larger seed search factor k), or sampled far "
                            "more coarsely in one direction than in another (rings or lines many spacings "
                            "apart), which Robust G2S does not mesh.");
  }
}

} // namespace

Params suggestParams(const CloudArrays&) {
  Params p;
  p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
  return p;
}

void build(CloudArrays cloud, MeshArrays& out, const Params& params, Stat& stat, CallBackPos* cb) {
  Stopwatch watch;
  out = MeshArrays();
  stat = Stat();
  try {
    checkParams(params);
    Params p = params;
    if (p.maxSearchRadiusFactor <= 0) p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
    stat.maxSearchRadiusFactor = p.maxSearchRadiusFactor;

    Progress progress(cb);
    progress.phase("Robust G2S: reading the points", 0, 3);
    InputCloud input = readPoints(std::move(cloud), stat);
    // The mesher sorts the points into its grid's cell order and measures their spacing.
    // input.normals is kept for the orientation.
    progress.phase("Robust G2S: growing the mesh", 3, 92);
    Mesher mesher(std::move(input.points), p);
    stat.spacing = mesher.spacing();
    stat.clumps = mesher.clumps();
    stat.clumpPointsMerged = mesher.clumpPointsMerged();
    stat.secondsSetup = watch.lap();
    grow(mesher, stat, progress); // sec. 3
    stat.secondsGrowth = watch.lap();
    progress.phase("Robust G2S: removing non-manifold vertices", 92, 95);
    cleanUp(mesher, p, stat, input); // sec. 4.2 and the repairs after it
    stat.secondsCleanup = watch.lap();
    progress.phase("Robust G2S: writing the mesh", 95, 100);
    writeMesh(input, mesher, out, stat, progress);
  } catch (...) {
    // Cancelled, bad input, out of memory: nothing of a partial result is kept.
    out = MeshArrays();
    throw;
  }
  stat.secondsOutput = watch.lap();
  stat.seconds = watch.total();
}

} // namespace g2s
} // namespace growth
