// Sec. 3.1, 4.3 and 5.3: the input checked, the sizes the method runs at, and the points
// renumbered in a spatial order (packer_steps.h).
#include "packer_steps.h"

#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/morton.h>
#include <growth/radix_order.h>

#include <common/ml_mesh_type.h>

#include <algorithm>
#include <cmath>

namespace growth {
namespace spherepack {
namespace detail {

// Input: the cloud's points and normals, checked (what sec. 3.1 assumes of the input).
InputCloud readInput(const CMeshO& cloud, Stat& st) {
  CloudCheck check;
  check.needNormals = true;
  check.allowFaces = false;
  check.minPoints = 3;
  InputCloud in = readCloud(cloud, check);
  st.inputPoints = static_cast<size_t>(cloud.vn);
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
  z.scale = cloudScale(in.points, params.threads);
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
    const vcg::Point3d p0 = in.points[start], n0 = in.normals[start];
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
