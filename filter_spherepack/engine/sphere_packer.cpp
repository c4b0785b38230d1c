// The public API of sphere_packer.h: the defaults derived from a cloud, and build(), which runs the
// method's steps (packer_steps.h) in the paper's order.
#include "sphere_packer.h"

#include "cloud_features.h"
#include "packer_growth.h"
#include "packer_steps.h"

#include <growth/cloud_scale.h>
#include <growth/stopwatch.h>


#include <algorithm>
#include <cmath>
#include <sstream>

namespace growth {
namespace spherepack {

namespace detail {

std::string fmt(double v) {
  std::ostringstream s;
  s.precision(4);
  s << v;
  return s.str();
}

} // namespace detail

using namespace detail;

CloudScale cloudScale(const std::vector<Vec3d>& points, int threads, const std::vector<Vec3d>* normals) {
  CloudScale sc;
  // 8,000 samples (3,000 of them with a local fit) give medians within about 1 %; more only cost
  // time (docs/design/spherepack-default-sizes.md).
  SamplingOptions options;
  options.maxSamples = 8000;
  options.maxNoiseSamples = 3000;
  options.normals = normals;
  const SamplingEstimate e = estimateSampling(points, options, threads);
  if (!(e.areaPerPoint > 0) || !std::isfinite(e.areaPerPoint)) return sc;
  sc.spacing = e.spacing;
  sc.medianSpacing = e.medianSpacing;
  sc.areaSpacing = std::sqrt(e.areaPerPoint);
  sc.area = e.areaPerPoint * double(points.size());
  sc.noise = std::isfinite(e.noise) ? e.noise : 0.0;
  if (!e.sheetGaps.empty() && e.samples > 0) {
    const double reach = kThinGapPerD * samplingDiameter(sc);
    std::vector<double> thin;
    for (const float g : e.sheetGaps)
      if (double(g) < reach) thin.push_back(double(g));
    if (!thin.empty()) {
      sc.thinShare = double(thin.size()) / double(e.samples);
      std::nth_element(thin.begin(), thin.begin() + std::ptrdiff_t(thin.size() / 2), thin.end());
      sc.sheetGap = thin[thin.size() / 2];
    }
  }
  return sc;
}

double samplingDiameter(const CloudScale& scale) {
  return std::max(kDefaultDiameterPerAreaSpacing * scale.areaSpacing, kDefaultDiameterPerNoise * scale.noise);
}

namespace {
bool thinPartsLowerD(const CloudScale& scale) {
  return scale.thinShare >= kThinShareForSmallerD && scale.sheetGap > 0 &&
         scale.sheetGap / kThinGapPerD < samplingDiameter(scale);
}
double thinFloor(const CloudScale& scale) {
  return std::max(kMinThinDiameterPerAreaSpacing * scale.areaSpacing, 2.0 * scale.noise);
}
} // namespace

double defaultDiameter(const CloudScale& scale) {
  const double d = samplingDiameter(scale);
  if (!thinPartsLowerD(scale)) return d;
  return std::min(d, std::max(scale.sheetGap / kThinGapPerD, thinFloor(scale)));
}

std::string defaultDiameterReason(const CloudScale& scale) {
  if (thinPartsLowerD(scale)) {
    const bool floored = scale.sheetGap / kThinGapPerD < thinFloor(scale);
    return "from thin parts: " + fmt(100 * scale.thinShare) + " % of the surface lies on parts about " +
           fmt(scale.sheetGap) + " thick (two sheets with opposed normals), so d = thickness / 1.2" +
           (floored ? std::string(", but not below 0.7 x sqrt(area per point) or 2x the noise: the thinnest parts "
                                  "get one side only") : std::string()) +
           " (the sampling alone gives " + fmt(samplingDiameter(scale)) + ")";
  }
  if (kDefaultDiameterPerNoise * scale.noise > kDefaultDiameterPerAreaSpacing * scale.areaSpacing)
    return "from the noise: 3 x the estimated noise bound (at least 2x, sec. 5.3; larger than the sampling's " +
           fmt(kDefaultDiameterPerAreaSpacing * scale.areaSpacing) + ")";
  return "from the sampling: 1.8 x sqrt(area per point) (the noise asks for at least " +
         fmt(kDefaultDiameterPerNoise * scale.noise) + ")";
}

double defaultSplatSize(const CloudScale& scale, double d) {
  double s = kDefaultSplatPerAreaSpacing * scale.areaSpacing;
  if (thinPartsLowerD(scale))
    s = std::min(s, std::max(kThinSplatPerGap * scale.sheetGap, kMinThinSplatPerAreaSpacing * scale.areaSpacing));
  return s > 0 ? s : d;
}

Params suggestParams(const CloudArrays& cloud) {
  Params p;
  try {
    CloudCheck check;
    check.needNormals = false;
    check.readNormals = true; // as build() reads them (zero where missing: no other sheet there)
    check.allowFaces = true;
    InputCloud in = readCloud(cloud, check);
    const CloudScale sc = cloudScale(in.points, 0, &in.normals);
    if (sc.areaSpacing > 0 && std::isfinite(sc.areaSpacing)) {
      p.sphereDiameter = defaultDiameter(sc);
      p.splatSize = defaultSplatSize(sc, p.sphereDiameter);
    }
  } catch (const std::exception&) {
    // An unusable cloud: keep the static defaults; build() will explain what is wrong.
  }
  return p;
}

// The method's phases in the paper's order; each phase's time goes to its Stat::seconds* field.
void build(CloudArrays cloud, MeshArrays& out, const Params& params, Stat& st, CallBackPos* cb) {
  Stopwatch watch;
  out = MeshArrays();
  st = Stat();
  Progress progress(cb);

  // Input and sizes; the points renumbered in a spatial order (the same mesh, faster).
  progress.phase("Sphere packing: reading the cloud", 0, 3);
  const bool floatStorage = cloud.floatStorage;
  InputCloud in = readInput(std::move(cloud), st);
  const Sizes sizes = chooseSizes(in, params, st);
  leaveOutFarPoints(in, sizes.d, st);
  const CloudScale& scale = sizes.scale;
  const double d = sizes.d, s = sizes.s, expected = sizes.expected;
  std::vector<int>().swap(in.vertexIndex); // not needed here
  Renumbering order = spatialOrder(in, d, params.spatialOrderMinPoints);

  checkMemory(estimateMemory(in, nullptr, sizes), sizes, params, st); // (a lower bound: refused early)

  // Sec. 4.3: splat radii.
  progress.phase("Sphere packing: splat sizes", 3, 22);
  st.secondsInput = watch.lap();
  std::vector<float> radius = splatRadii(in, sizes, params, order, st, progress);
  st.secondsSplats = watch.lap();
  checkMemory(estimateMemory(in, &radius, sizes), sizes, params, st);

  // Sec. 4.1: box grid.
  progress.phase("Sphere packing: box grid", 22, 50);
  BoxGrid grid;
  buildBoxGrid(grid, in, radius, d, params, order, st, progress);
  st.secondsBoxGrid = watch.lap();

  // Sec. 3.3: start.
  progress.phase("Sphere packing: starting vertices", 50, 51);
  const StartPair first = firstStartPair(in, radius, grid, order, d, s, params);

  // Sec. 3.4-3.6: growth of the front, on every part of the cloud; meanwhile the deferred box
  // normals (sec. 4.1) on another thread, those near the start first (the growth spreads from there).
  grid.startNormals(params.threads, first.s1);
  progress.phase("Sphere packing: growing", 51, 90);
  Growth growth(in, grid, radius, d, params, st, progress, static_cast<size_t>(expected));
  CloudFeatures features;
  if (params.keepFeatures) {
    features = detectCloudFeatures(in.points, in.normals, d, scale.areaSpacing, params.creaseAngleDeg, order);
    st.featureCreasePoints = features.creasePoints;
    st.featurePatches = features.patches;
    if (!features.lines.empty()) {
      growth.setPatches(&features.patch);
      placeCloudFeatures(growth, features, in.points, d, st);
    }
  }
  growEveryPart(growth, first, in, radius, grid, order, d, st);
  const BorderGraph& g = growth.graph();
  grid.finishNormals();
  st.boxesDTooLarge = grid.dTooLargeCount();
  st.boxesTwoSided = grid.twoSidedBoxes();
  st.unreachedPoints = unreachedPoints(growth, in.points.size());
  const size_t inputPoints = in.points.size();
  const double opposite = oppositeNormalShare(in, scale, st);
  // The peak: everything is held at the end of the growth. What the regions and the output do not
  // need is freed before them.
  st.memory.input = in.points.capacity() * sizeof(Vec3d) + in.normals.capacity() * sizeof(Vec3d) +
                    radius.capacity() * sizeof(float) + (order.orig.capacity() + order.rank.capacity()) * sizeof(std::uint32_t);
  st.memory.boxGrid = grid.memoryBytes();
  st.memory.growth = growth.memoryBytes();
  st.memory.peak = st.memory.input + st.memory.boxGrid + st.memory.growth;
  grid.release();
  growth.releaseSearch();
  // Where the cloud is, for the hole pass (the input is freed before it): the splats in float,
  // copied once the box grid and the growth's search are freed (below the peak).
  CloudCover cover;
  if (params.closeHoles) cover = cloudCover(in.points, radius);
  in = InputCloud();
  order = Renumbering();
  std::vector<float>().swap(radius);
  releaseFreeHeap();
  const size_t coverBytes = cover.memoryBytes();
  st.secondsGrowth = watch.lap();

  // Sec. 3.7: region triangulation.
  progress.phase("Sphere packing: triangulating the regions", 90, 97);
  std::vector<Triangle> faces = triangulate(g, params, floatStorage, st);
  growth.releaseAdjacency(); // the positions stay
  st.secondsTriangulation = watch.lap();

  // Clean-up: manifold and free of self-intersections (sec. 3.1's guarantee on any input), no small pieces.
  makeManifold(faces, g, params, floatStorage, st);
  dropSmallPieces(faces, g, params, st);
  // The holes left where the cloud continues, closed with the packing's vertices.
  closeHoles(faces, g, cover, params, floatStorage, st);
  cover = CloudCover();
  st.memory.faces = faces.capacity() * sizeof(Triangle);
  st.memory.peak = std::max(st.memory.peak, growth.memoryBytes() + coverBytes + st.memory.faces);
  st.secondsCleanup = watch.lap();

  // Output and report.
  // (The ranges follow the phases' shares of the time on large clouds with two threads.)
  progress.phase("Sphere packing: writing the mesh", 97, 100);
  writeMesh(faces, g, floatStorage, out, st);
  st.memory.faces = faces.capacity() * sizeof(Triangle);
  st.memory.output = out.vertices.capacity() * sizeof(Vec3d) + out.faces.capacity() * sizeof(out.faces[0]) +
                     out.faceQuality.capacity() * sizeof(double);
  st.memory.peak = std::max(st.memory.peak, growth.memoryBytes() + st.memory.faces + st.memory.output);
  const size_t graphVertices = g.vertexCount();
  const bool noFaces = faces.empty();
  std::vector<Triangle>().swap(faces);
  growth.releaseGraph();
  checkTopology(out, st);
  report(inputPoints, opposite, d, s, graphVertices, noFaces, st);
  st.secondsOutput = watch.lap();
  st.seconds = watch.total();
  try {
    progress.update(1.0); // done: 100 %
  } catch (const Cancelled&) {
    out = MeshArrays(); // cancelled at the last moment: nothing is given back, as on any cancel
    throw;
  }
}

} // namespace spherepack
} // namespace growth
