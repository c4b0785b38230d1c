#include "g2s.h"

#include "g2s_mesher.h"

#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>
#include <growth/mesh_normals.h>
#include <growth/progress.h>
#include <growth/stopwatch.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/algorithms/update/bounding.h>

#include <algorithm>
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

// The distinct finite points of the layer (input checks: growth/input_cloud.h).
InputCloud readPoints(const CMeshO& cloud, Stat& stat) {
  CloudCheck check;
  check.minPoints = 3;
  InputCloud input = readCloud(cloud, check);
  stat.inputPoints = static_cast<size_t>(cloud.vn);
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
std::vector<P3> layerNormals(const CMeshO& cloud, const InputCloud& input, const Mesher& mesher) {
  std::vector<P3> normals;
  const std::vector<std::uint32_t>& order = mesher.order();
  if (input.vertexIndex.empty()) return normals;
  normals.resize(order.size());
  size_t usable = 0;
  for (size_t i = 0; i < order.size(); ++i) {
    const auto& n = cloud.vert[size_t(input.vertexIndex[order[i]])].cN();
    const P3 v = P3(static_cast<double>(n[0]), static_cast<double>(n[1]), static_cast<double>(n[2]));
    const bool ok = std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]) && v.SquaredNorm() > 0;
    normals[i] = ok ? v : P3(0, 0, 0);
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
void cleanUp(Mesher& mesher, const Params& p, Stat& stat, const CMeshO& cloud, const InputCloud& input) {
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
    const std::vector<P3> normals = boundary.edges > 0 ? layerNormals(cloud, input, mesher) : std::vector<P3>();
    mesher.orientComponents(normals.empty() ? nullptr : &normals);
  });
  stat.workingBytes = std::max(stat.workingBytes, mesher.memoryBytes());
  mesher.releaseWorkingState();
  releaseFreeHeap(); // its freed blocks would otherwise stay resident under the output layer
}

// The live triangles into `out`, on copies of the layer's points that they use (see build()).
void writeMesh(const CMeshO& cloud, InputCloud& input, Mesher& mesher, CMeshO& out, Stat& stat, Progress& progress) {
  // The live triangles, in order, taken out of the mesher (with alive() freed): they are
  // consumed below while the output faces are written.
  std::vector<Triangle> tri = mesher.takeLiveTriangles();
  const std::vector<std::uint32_t>& order = mesher.order();
  // Output vertices: the used points in the mesher's (spatially coherent) order, copied from the
  // layer's own vertices (mesher point i is distinct point order[i], layer vertex
  // vertexIndex[order[i]]): the input points bit for bit. The mesher's working state is freed
  // first, so that its memory and the output layer's do not add up.
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
    // Exact sizes reserved first, so the vectors are allocated once, with huge pages advised.
    reserveHuge(out.vert, stat.vertices, true);
    vcg::tri::Allocator<CMeshO>::AddVertices(out, stat.vertices);
    for (size_t i = 0; i < points; ++i)
      if (outIndex[i] != ~0u) out.vert[outIndex[i]].P() = cloud.vert[size_t(input.vertexIndex[order[i]])].P();
    // Only outIndex is needed from here on.
    mesher.releaseOrder();
    decltype(input.vertexIndex)().swap(input.vertexIndex);
    out.face.EnableQuality();
    reserveHuge(out.face, faces); // (vcglib's reserve reserves the quality vector too)
    // The faces are added a block at a time, and the block's triangles are given back (whole
    // pages, growth::discardPages) once it is written: the faces take four times the
    // triangles' memory, so the two would otherwise add up at the peak. Within the reserved
    // room no face moves. Blocks of 8192 faces (384 KiB of faces, 96 KiB of triangles): with
    // 65536, a cloud of 30k points kept all its 720 KB of triangles to the end, and the
    // meshlabserver peak on torus-30k was 420 kB higher.
    constexpr size_t kBlock = size_t(1) << 13;
    for (size_t first = 0; first < faces; first += kBlock) {
      const size_t last = std::min(faces, first + kBlock);
      // The block's room made resident at once (within the reserved capacity), block by block
      // so that the faces do not take their memory before the triangles give theirs back.
      prefault(out.face.data() + first, (last - first) * sizeof(CFaceO));
      prefault(out.face.QV.data() + first, (last - first) * sizeof(out.face.QV[0]));
      vcg::tri::Allocator<CMeshO>::AddFaces(out, last - first);
      for (size_t f = first; f < last; ++f) {
        CFaceO& face = out.face[f];
        for (int j = 0; j < 3; ++j) face.V(j) = &out.vert[outIndex[tri[f][j]]];
        face.Q() = static_cast<CFaceO::QualityType>(triangleQuality(
            P3::Construct(face.cP(0)), P3::Construct(face.cP(1)), P3::Construct(face.cP(2))));
      }
      discardPages(tri.data(), last * sizeof(Triangle));
      progress.update(double(last) / double(faces));
    }
    std::vector<Triangle>().swap(tri);
    // What MeshLab expects of a new layer (its creation filters call UpdateBoxAndNormals): the
    // bounding box, and face and angle-weighted vertex normals. Part of the filter's time.
    vcg::tri::UpdateBounding<CMeshO>::Box(out);
    updateNormals(out);
    progress.update(1.0);
  } else {
    stat.warnings.push_back("No seed triangle was found, so no surface was built: the points are too "
                            "few or too scattered to lie on a surface (try a larger seed search factor k), or sampled far "
                            "more coarsely in one direction than in another (rings or lines many spacings "
                            "apart), which Robust G2S does not mesh.");
  }
}

} // namespace

Params suggestParams(const CMeshO&) {
  Params p;
  p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
  return p;
}

void build(const CMeshO& cloud, CMeshO& out, const Params& params, Stat& stat, CallBackPos* cb) {
  Stopwatch watch;
  out.Clear();
  stat = Stat();
  try {
    checkParams(params);
    Params p = params;
    if (p.maxSearchRadiusFactor <= 0) p.maxSearchRadiusFactor = kDefaultMaxSearchRadiusFactor;
    stat.maxSearchRadiusFactor = p.maxSearchRadiusFactor;

    Progress progress(cb);
    progress.phase("Robust G2S: reading the points", 0, 3);
    InputCloud input = readPoints(cloud, stat);
    // The mesher sorts the points into its grid's cell order and measures their spacing.
    // input.vertexIndex (layer vertex of each distinct point) is kept for the output.
    progress.phase("Robust G2S: growing the mesh", 3, 92);
    Mesher mesher(std::move(input.points), p);
    stat.spacing = mesher.spacing();
    stat.clumps = mesher.clumps();
    stat.clumpPointsMerged = mesher.clumpPointsMerged();
    stat.secondsSetup = watch.lap();
    grow(mesher, stat, progress); // sec. 3
    stat.secondsGrowth = watch.lap();
    progress.phase("Robust G2S: removing non-manifold vertices", 92, 95);
    cleanUp(mesher, p, stat, cloud, input); // sec. 4.2 and the repairs after it
    stat.secondsCleanup = watch.lap();
    progress.phase("Robust G2S: writing the mesh", 95, 100);
    writeMesh(cloud, input, mesher, out, stat, progress);
  } catch (...) {
    // Cancelled, bad input, out of memory: nothing of a partial result is kept.
    out.Clear();
    throw;
  }
  stat.secondsOutput = watch.lap();
  stat.seconds = watch.total();
}

} // namespace g2s
} // namespace growth
