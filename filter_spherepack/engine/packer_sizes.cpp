// Sec. 3.1, 4.3 and 5.3: the input checked, the sizes the method runs at, and the points
// renumbered in a spatial order (packer_steps.h).
#include "packer_steps.h"

#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/morton.h>
#include <growth/radix_order.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace growth {
namespace spherepack {
namespace detail {

// Input: the cloud's points and normals, checked (what sec. 3.1 assumes of the input).
InputCloud readInput(CloudArrays cloud, Stat& st) {
  CloudCheck check;
  check.needNormals = true;
  check.allowFaces = false;
  check.minPoints = 3;
  st.inputPoints = cloud.points.size();
  InputCloud in = readCloud(std::move(cloud), check);
  st.duplicatesDropped = in.duplicatesDropped;
  return in;
}

// Sec. 3.1, 4.3 and 5.3: the parameters checked, the sphere diameter d (given, or from the sampling
// and the noise), the splat size s, and the vertices expected within Params::maxOutputVertices.
Sizes chooseSizes(const InputCloud& in, const Params& params, Stat& st) {
  if (params.windowSize < 0 || params.windowSize > 1000)
    throw Error("The window size w must be between 0 and 1000 (the paper uses 8).");
  if (params.minComponentFaces < 0)
    throw Error("The smallest piece to keep must be 0 faces (keep all) or more.");
  if (params.maxBorderLength < 3)
    throw Error("The border limit must be at least 3 (a triangle); the paper uses 40.");
  Sizes z;
  z.scale = cloudScale(in.points, params.threads, &in.normals);
  const CloudScale& scale = z.scale;
  const double diag = in.box.Diag();
  st.scale = scale;
  double d = params.sphereDiameter;
  st.diameterReason = "given";
  if (!(d > 0)) {
    d = defaultDiameter(scale);
    st.diameterReason = defaultDiameterReason(scale);
    if (!(d > 0) || !std::isfinite(d))
      throw Error("Could not estimate the point spacing of this cloud (too few points with neighbours around "
                  "them): give the sphere diameter d by hand.");
  }
  if (!std::isfinite(d) || !(d > 0)) throw Error("The sphere diameter d must be a positive number.");
  if (d > 0.5 * diag) {
    const double automatic = defaultDiameter(scale);
    if (!(params.sphereDiameter > 0) || !(automatic <= 0.5 * diag))
      // The cloud's own sampling asks for edges longer than the cloud.
      throw Error("Too few points, or too sparse, for a mesh: the automatic sphere diameter d = " + fmt(automatic) +
                  " (from the spacing of the " + std::to_string(in.points.size()) + " points) is larger than "
                  "the cloud (bounding box diagonal " + fmt(diag) + "). Give a d below " + fmt(0.5 * diag) +
                  " by hand, or use a denser cloud.");
    throw Error("The sphere diameter d = " + fmt(d) + " is larger than the cloud (bounding box diagonal " +
                fmt(diag) + "): no mesh with edges that long fits on it. Use a smaller d, e.g. the default " +
                fmt(automatic) + ".");
  }
  double s = params.splatSize;
  if (!(s > 0)) s = defaultSplatSize(scale, d);
  if (!std::isfinite(s)) throw Error("The splat radius s must be a positive number.");
  st.sphereDiameter = d;
  st.splatSize = s;

  const double area = scale.area;
  const double expected = area / (d * d * kTriangleAreaFactor);
  if (expected > double(params.maxOutputVertices)) {
    const double dMin = std::sqrt(area / (double(params.maxOutputVertices) * kTriangleAreaFactor));
    throw Error("The sphere diameter d = " + fmt(d) + " is too small for this cloud: the mesh would have about " +
                fmt(expected) + " vertices (surface area about " + fmt(area) + " / (d²·√3/2)), more than the limit of " +
                std::to_string(params.maxOutputVertices) + ". Use a larger d (at least about " + fmt(dMin) +
                "; the default for this cloud is " + fmt(defaultDiameter(scale)) + ").");
  }
  z.d = d;
  z.s = s;
  z.expected = expected;
  return z;
}

void leaveOutFarPoints(InputCloud& in, double d, Stat& st) {
  const double span = BoxGrid::maxExtent(d);
  const Vec3d dim = in.box.Dim();
  if (std::max(dim[0], std::max(dim[1], dim[2])) <= span) return;
  const size_t n = in.points.size();
  const double gap = kFarGapPerD * d;
  double keepLo[3], keepHi[3], leftGap = std::numeric_limits<double>::infinity();
  std::vector<double> c(n);
  for (int a = 0; a < 3; ++a) {
    for (size_t i = 0; i < n; ++i) c[i] = in.points[i][a];
    std::sort(c.begin(), c.end());
    size_t lo = size_t(0.01 * double(n - 1) + 0.5), hi = size_t(0.99 * double(n - 1) + 0.5);
    while (lo > 0 && c[lo] - c[lo - 1] < gap) --lo;
    while (hi + 1 < n && c[hi + 1] - c[hi] < gap) ++hi;
    if (c[hi] - c[lo] > span) {
      const char* axis = a == 0 ? "x" : a == 1 ? "y" : "z";
      throw Error("The sphere diameter d = " + fmt(d) + " is too small for the extent of this cloud: along " + axis +
                  " its bulk (the 1-99 % quantiles of the points, and the points joined to them by gaps shorter "
                  "than 8 d) spans " + fmt(c[hi] - c[lo]) + ", " + fmt((c[hi] - c[lo]) / d) + " boxes of side d, "
                  "more than the " + std::to_string(BoxIndexer::kMax) + " per axis the box grid indexes. Parts of "
                  "the cloud that far apart cannot be meshed in one run at this d: mesh them one at a time (split "
                  "the layer), or give a d of at least " + fmt((c[hi] - c[lo]) / (span / d)) + ".");
    }
    // Then the further groups of points (split by gaps of kFarGapPerD·d or more), the nearest
    // first, as long as the span still fits: only what the grid cannot reach is left out.
    auto groupUp = [&](size_t h) {
      size_t e = h + 1;
      while (e + 1 < n && c[e + 1] - c[e] < gap) ++e;
      return e;
    };
    auto groupDown = [&](size_t l) {
      size_t e = l - 1;
      while (e > 0 && c[e] - c[e - 1] < gap) --e;
      return e;
    };
    size_t up = hi + 1 < n ? groupUp(hi) : hi, down = lo > 0 ? groupDown(lo) : lo;
    for (;;) {
      const bool fitsUp = hi + 1 < n && c[up] - c[lo] <= span, fitsDown = lo > 0 && c[hi] - c[down] <= span;
      if (fitsUp && (!fitsDown || c[hi + 1] - c[hi] <= c[lo] - c[lo - 1])) {
        hi = up;
        if (hi + 1 < n) up = groupUp(hi);
      } else if (fitsDown) {
        lo = down;
        if (lo > 0) down = groupDown(lo);
      } else {
        break;
      }
    }
    keepLo[a] = c[lo];
    keepHi[a] = c[hi];
    if (lo > 0) leftGap = std::min(leftGap, c[lo] - c[lo - 1]);
    if (hi + 1 < n) leftGap = std::min(leftGap, c[hi + 1] - c[hi]);
  }
  std::vector<double>().swap(c);
  size_t kept = 0;
  const bool withIndex = in.vertexIndex.size() == n;
  Box3d box;
  for (size_t i = 0; i < n; ++i) {
    const Vec3d& p = in.points[i];
    bool inside = true;
    for (int a = 0; a < 3; ++a) inside = inside && p[a] >= keepLo[a] && p[a] <= keepHi[a];
    if (!inside) continue;
    in.points[kept] = p;
    in.normals[kept] = in.normals[i];
    if (withIndex) in.vertexIndex[kept] = in.vertexIndex[i];
    box.Add(p);
    ++kept;
  }
  in.points.resize(kept);
  in.normals.resize(kept);
  if (withIndex) in.vertexIndex.resize(kept);
  in.box = box;
  st.farPointsLeftOut = n - kept;
  st.farPointsGap = leftGap;
  st.warnings.push_back(std::to_string(n - kept) + (n - kept == 1 ? " point lies " : " points lie ") + fmt(leftGap) +
                        " or more (" + fmt(leftGap / d) + " d) from the bulk of the cloud, which spans " +
                        fmt(std::max(box.Dim()[0], std::max(box.Dim()[1], box.Dim()[2]))) + ": with them the cloud "
                        "spans " + fmt(std::max(dim[0], std::max(dim[1], dim[2]))) + ", more than the box grid "
                        "indexes at d = " + fmt(d) + " (" + std::to_string(BoxIndexer::kMax) + " boxes per axis). "
                        "They were left out of the mesh: a point that far shares no sphere of diameter d with "
                        "the bulk. If they are a separate part, mesh it on its own.");
}

Renumbering spatialOrder(InputCloud& in, double d, size_t minPoints) {
  Renumbering r;
  const size_t n = in.points.size();
  if (n < std::max<size_t>(minPoints, 2)) return r;
  // Box coordinates (at most 21 bits each, as the box grid's), interleaved.
  HugeVector<std::uint64_t> code(n);
  std::uint64_t maxCode = 0;
  for (size_t i = 0; i < n; ++i) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::min<std::uint64_t>(std::uint64_t(std::max(0.0, std::floor((in.points[i][a] - in.box.min[a]) / d))),
                                     (std::uint64_t(1) << 21) - 1);
    code[i] = mortonCode(c[0], c[1], c[2]);
    maxCode = std::max(maxCode, code[i]);
  }
  // Stable order of the codes (equal codes in input order).
  int bits = 0;
  while (bits < 64 && (maxCode >> bits) != 0) ++bits;
  reserveHuge(r.orig, n, /*populate=*/true); // written whole: resident in one call (huge_pages.h)
  stableRadixOrder(code.data(), n, bits, r.orig);
  reserveHuge(r.rank, n, /*populate=*/true);
  r.rank.resize(n);
  for (size_t i = 0; i < n; ++i) r.rank[r.orig[i]] = static_cast<std::uint32_t>(i);
  // Permute the arrays in place, cycle by cycle (no second copy of them: the peak memory).
  std::vector<bool> done(n, false);
  for (size_t start = 0; start < n; ++start) {
    if (done[start]) continue;
    const Vec3d p0 = in.points[start], n0 = in.normals[start];
    size_t i = start;
    for (;;) {
      done[i] = true;
      const size_t from = r.orig[i];
      if (from == start) break;
      in.points[i] = in.points[from];
      in.normals[i] = in.normals[from];
      i = from;
    }
    in.points[i] = p0;
    in.normals[i] = n0;
  }
  return r;
}

} // namespace detail
} // namespace spherepack
} // namespace growth
