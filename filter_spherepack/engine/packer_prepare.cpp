// Sec. 4.3 and 4.1: the splat radii and the box grid the growth runs on (packer_steps.h).
#include "packer_steps.h"

#include <growth/error.h>

#include <algorithm>
#include <cstdio>

namespace growth {
namespace spherepack {
namespace detail {

// Sec. 4.3: the splat radii, from the points' own neighbourhoods (independent of d).
std::vector<float> splatRadii(const InputCloud& in, const Sizes& z, const Params& params, const Renumbering& order,
                              Stat& st, Progress& progress) {
  SplatSizeStats splatStats;
  std::vector<float> radius =
      computeSplatRadii(in.points, in.normals, z.s, kSplatFirstReachPerAreaSpacing * z.scale.areaSpacing,
                        params.localSplatSizes, &splatStats, &progress, params.threads,
                        order.orig.empty() ? nullptr : &order.orig);
  st.meanSplatRadius = splatStats.meanRadius;
  st.splatsUnbounded = splatStats.unbounded;
  st.splatsClamped = splatStats.clamped;
  return radius;
}

namespace {
// The boxes of side 1 that a surface crosses within distance rho of one of its points, per box a
// plane crosses: the unit square grown by rho (Steiner's formula in the plane).
double sheetBoxesWithin(double rho) {
  const double pi = 3.14159265358979323846;
  return 1 + 4 * rho + pi * rho * rho;
}
} // namespace

// Bytes as a size_t, saturating at 1e18 (also for NaN): the estimate of an absurd area or d is then
// more than any machine has, and the run is refused, instead of a conversion out of range.
static size_t toBytes(double x) { return x < 1e18 ? size_t(std::max(0.0, x)) : size_t(1e18); }

MemoryEstimate estimateMemory(const InputCloud& in, const std::vector<float>* radius, const Sizes& z) {
  MemoryEstimate e;
  const double pi = 3.14159265358979323846;
  const double n = double(in.points.size()), d = z.d;
  double refs = 0, radiusSum = 0;
  if (radius == nullptr) {
    refs = n * kSheetBoxesPerArea * sheetBoxesWithin(1.0);
  } else {
    for (float r : *radius) {
      const double rho = r > kLargeSplatPerD * d ? 1 + std::min(double(r) / d, double(BoxGrid::kMaxExtraReach)) : 1.0;
      refs += kSheetBoxesPerArea * sheetBoxesWithin(rho);
      radiusSum += double(r);
    }
  }
  // The boxes built are those the surface (its splats) crosses; the point lists, the index of the
  // points by their own boxes (4 bytes a point).
  // (Each box built is referred to at least once: at most the references.)
  const double boxes = std::min(refs, kSheetBoxesPerArea * z.scale.area / (d * d));
  e.input = toBytes(n * (2 * sizeof(Vec3d) + sizeof(float) + 2 * sizeof(std::uint32_t)));
  e.boxGrid = toBytes(4 * refs + boxes * kBoxBytes + 4 * n);
  // The growth: the graph per vertex, and per splat the vertices within d of its disk (an area of
  // π(r + d)², at (√3/2)·d² per vertex), in the lists' chunks. Without the radii, r = 0.
  const double meanRadius = n > 0 ? radiusSum / n : 0.0;
  const double listed = pi * (1 + meanRadius / d) * (1 + meanRadius / d) / kTriangleAreaFactor;
  e.growth = toBytes(z.expected * kGrowthBytesPerVertex + n * (4 + kListBytesPerEntry * listed));
  // Fixed sizes (tables at their smallest, the queue's levels): 2 MB more.
  e.peak = e.input + e.boxGrid + e.growth + (size_t(2) << 20);
  return e;
}

size_t availableMemoryBytes() {
  std::FILE* f = std::fopen("/proc/meminfo", "r");
  if (f == nullptr) return 0;
  char line[256];
  size_t kib = 0;
  while (std::fgets(line, sizeof line, f) != nullptr)
    if (std::sscanf(line, "MemAvailable: %zu kB", &kib) == 1) break;
  std::fclose(f);
  return kib * 1024;
}

void checkMemory(const MemoryEstimate& e, const Sizes& z, const Params& params, Stat& st) {
  st.memory.estimate = e.peak;
  st.memory.limit = params.maxMemoryBytes > 0 ? params.maxMemoryBytes : availableMemoryBytes();
  if (st.memory.limit == 0 || e.peak <= st.memory.limit) return;
  const double gib = 1.0 / (1024.0 * 1024.0 * 1024.0);
  throw Error("Sphere packing would need about " + fmt(gib * double(e.peak)) + " GiB of memory for " +
              std::to_string(st.inputPoints) + " points at d = " + fmt(z.d) + " (box grid " + fmt(gib * double(e.boxGrid)) +
              ", growth " + fmt(gib * double(e.growth)) + ", input " + fmt(gib * double(e.input)) + " GiB, for about " +
              fmt(z.expected) + " vertices), more than the " + fmt(gib * double(st.memory.limit)) +
              " GiB " + (params.maxMemoryBytes > 0 ? "allowed" : "available") +
              ". A larger d needs less (the vertices fall with d squared); or subsample the cloud.");
}

// Sec. 4.1: the box grid, normal filter and box normals. A splat larger than d is referred to by
// every box it comes within d of (sec. 4.4 needs all splats within d of a vertex), not only by
// those its centre is within d of. The normals of the boxes holding input points are deferred:
// computed on another thread while the growth (one thread) runs, which asks for them as it goes
// (BoxGrid::startNormals).
void buildBoxGrid(BoxGrid& grid, const InputCloud& in, const std::vector<float>& radius, double d,
                  const Params& params, const Renumbering& order, Stat& st, Progress& progress) {
  std::vector<float> extraReach;
  {
    size_t large = 0;
    for (float r : radius) large += r > kLargeSplatPerD * d ? 1 : 0;
    if (large > 0) {
      extraReach.assign(radius.size(), 0.0f);
      for (size_t i = 0; i < radius.size(); ++i)
        if (radius[i] > kLargeSplatPerD * d) extraReach[i] = radius[i];
    }
  }
  grid.build(in.points, in.normals, d, &progress, params.threads, /*deferNormals=*/true,
             order.rank.empty() ? nullptr : &order.rank, extraReach.empty() ? nullptr : &extraReach, &radius);
  std::vector<float>().swap(extraReach);
  st.boxes = grid.boxCount();
  st.boxReferences = grid.references();
}

} // namespace detail
} // namespace spherepack
} // namespace growth
