#pragma once
// Sampling of feature lines by spheres of diameter d (sec. 3.3 with more than two starting
// vertices): shared by the remesher (crease lines of the input mesh) and the reconstruction
// (crease lines detected in the cloud, cloud_features.h).
#include <growth/vec3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <limits>
#include <vector>

namespace growth {
namespace spherepack {

// The points of a polyline P[0..m] at chord distance s from each other,
// from P[0] on, each the first point after the previous one where the polyline leaves the ball of
// radius s around it; with the segment it lies on. Stops after `limit` points, or where the rest of
// the polyline stays inside the ball.
struct LinePoint {
  Vec3d p;
  size_t seg;
};
inline std::vector<LinePoint> chordWalk(const std::vector<Vec3d>& P, double s, size_t limit) {
  std::vector<LinePoint> out;
  Vec3d q = P[0];
  size_t seg = 0;
  double t = 0;
  while (out.size() < limit) {
    bool found = false;
    for (; seg + 1 < P.size(); ++seg, t = 0) {
      if ((P[seg + 1] - q).SquaredNorm() < s * s) continue;
      const Vec3d a = P[seg], e = P[seg + 1] - a, aq = a - q;
      const double A = e * e, B = 2 * (e * aq), C = aq.SquaredNorm() - s * s;
      const double root = (-B + std::sqrt(std::max(0.0, B * B - 4 * A * C))) / (2 * A);
      t = std::min(1.0, std::max(t, root));
      q = a + e * t;
      out.push_back(LinePoint{q, seg});
      found = true;
      break;
    }
    if (!found) break;
  }
  return out;
}

// The points between the ends of a crease line (P[0] and P.back(), equal for a closed line): the
// most points m whose chord spacing s > d can end exactly at P.back() (|P.back() − last| = s), s
// found by bisection; empty when not even one fits (the ends are then joined directly). The spacing
// stays above d by a relative 1e-9, so that rounding never brings two feature vertices below d.
inline std::vector<LinePoint> sampleLine(const std::vector<Vec3d>& P, double d) {
  const std::vector<LinePoint> atD = chordWalk(P, d, std::numeric_limits<size_t>::max());
  const Vec3d& end = P.back();
  std::vector<LinePoint> pts;
  for (size_t m = atD.size() > 0 ? atD.size() - 1 : 0; m >= 1; --m) {
    auto gap = [&](double s) {
      pts = chordWalk(P, s, m);
      if (pts.size() < m) return -1.0;
      return (end - pts.back().p).Norm() - s;
    };
    double lo = d * (1 + 1e-9), hi = 2 * d;
    if (gap(lo) < 0 || gap(hi) >= 0) continue;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      if (gap(mid) >= 0) lo = mid;
      else hi = mid;
    }
    gap(lo);
    return pts;
  }
  return {};
}

} // namespace spherepack
} // namespace growth
