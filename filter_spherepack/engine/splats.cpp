#include <growth/point_grid.h>
#include <growth/parallel.h>
#include <growth/progress.h>
#include "splats.h"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace growth {

namespace {
struct Q {
  double x, y;
  double angle;
  double dist2;
  int index;
};
inline double cross(const Q& a, const Q& b) { return a.x * b.y - a.y * b.x; }
// A monotonic function of the polar angle of (x, y) over [0, 2π), in [0, 4): the same cyclic
// order as atan2 without the trigonometry.
inline double pseudoAngle(double x, double y) {
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}
inline double orient(const Q& a, const Q& b, double cx, double cy) {
  return (b.x - a.x) * (cy - a.y) - (b.y - a.y) * (cx - a.x);
}
// > 0 when d lies inside the circumcircle of the counter-clockwise triangle (origin, b, c).
inline double inCircleOrigin(const Q& b, const Q& c, const Q& d) {
  const double b2 = b.x * b.x + b.y * b.y, c2 = c.x * c.x + c.y * c.y, d2 = d.x * d.x + d.y * d.y;
  return -(b.x * (c.y * d2 - c2 * d.y) - b.y * (c.x * d2 - c2 * d.x) + b2 * (c.x * d.y - c.y * d.x));
}
} // namespace

namespace {
// Scratch buffers of the computation, reused from point to point (grown, never shrunk).
struct FanScratch {
  std::vector<Q> fan;
  std::vector<int> links; // prev, next, work stack: 5 per fan point
  std::vector<char> alive;
};

// Sorts fan[0, m) by (angle, dist2, index): insertion sort for the usual short fans (a strict
// total order, so the same result as any other sort), std::sort for long ones, and for fans with a
// NaN angle (a neighbour on the normal line up to rounding: then the comparison is no order, and
// only the same algorithm as before gives the same result).
void sortFan(Q* fan, int m, bool nanAngle) {
  auto less = [](const Q& a, const Q& b) {
    if (a.angle != b.angle) return a.angle < b.angle;
    if (a.dist2 != b.dist2) return a.dist2 < b.dist2;
    return a.index < b.index;
  };
  if (m > 48 || nanAngle) {
    std::sort(fan, fan + m, less);
    return;
  }
  for (int i = 1; i < m; ++i) {
    const Q q = fan[i];
    int j = i;
    for (; j > 0 && less(q, fan[j - 1]); --j) fan[j] = fan[j - 1];
    fan[j] = q;
  }
}

// Step 1: the neighbours rotated about p onto T_p, each inside the plane spanned by n and p_i - p:
// the tangential part of p_i - p, rescaled to the full distance |p_i - p|. Gives their number.
// (e1, e2 are orthogonal to n, so <t, e> = <p_i − p, e>, and |t|² = |p_i − p|² − h².)
inline int projectOntoTangentPlane(const Vec3d& p, const Vec3d& n,
                                   const std::vector<Vec3d>& neighbours, Q* fan) {
  Vec3d e1, e2;
  tangentFrame(n, e1, e2);
  int size = 0;
  for (size_t i = 0; i < neighbours.size(); ++i) {
    const Vec3d v = neighbours[i] - p;
    const double len2 = v.SquaredNorm();
    const double h = v * n;
    const double tlen2 = len2 - h * h;
    if (!(tlen2 > 1e-24 * len2)) continue; // on the normal line: no direction in T_p
    const double scale = std::sqrt(len2 / tlen2);
    Q& q = fan[size++];
    q.x = (v * e1) * scale;
    q.y = (v * e2) * scale;
    q.angle = pseudoAngle(q.x, q.y);
    q.dist2 = len2;
    q.index = static_cast<int>(i);
  }
  return size;
}

// Step 2, on the fan sorted by angle: of the points in the same direction (up to rounding) only
// the nearer can be a Delaunay neighbour. Gives the number left.
inline int keepNearestPerDirection(Q* fan, int size) {
  int w = 0;
  for (int i = 0; i < size; ++i) {
    if (w > 0) {
      const Q& a = fan[w - 1];
      const double c = cross(a, fan[i]);
      if (c * c <= 1e-24 * a.dist2 * fan[i].dist2 && a.x * fan[i].x + a.y * fan[i].y > 0) {
        if (fan[i].dist2 < a.dist2) fan[w - 1] = fan[i];
        continue;
      }
    }
    fan[w++] = fan[i];
  }
  size = w;
  // The same check across the seam of the sort.
  if (size > 1) {
    const Q &a = fan[size - 1], &b = fan[0];
    const double c = cross(a, b);
    if (c * c <= 1e-24 * a.dist2 * b.dist2 && a.x * b.x + a.y * b.y > 0) {
      if (a.dist2 < b.dist2) fan[0] = a;
      --size;
    }
  }
  return size;
}

// Step 3: the central edges p–q_i that are not locally Delaunay flipped; a flipped q_i leaves the
// fan (alive[i] = 0); next: the fan's cyclic links.
inline void flipToDelaunay(const Q* fan, int m, FanScratch& scratch, int*& next, char*& alive) {
  // The work stack holds at most m + 2 per flip (at most m flips) entries.
  if (scratch.links.size() < size_t(5 * m)) scratch.links.resize(size_t(5 * m) + 64);
  if (scratch.alive.size() < size_t(m)) scratch.alive.resize(size_t(m) + 16);
  int* prev = scratch.links.data();
  next = prev + m;
  int* work = next + m; // 3m entries
  alive = scratch.alive.data();
  for (int i = 0; i < m; ++i) prev[i] = i - 1, next[i] = i + 1, alive[i] = 1, work[i] = m - 1 - i;
  prev[0] = m - 1;
  next[m - 1] = 0;
  int top = m; // popped from the back: index 0 first
  int count = m;
  while (top > 0 && count > 3) {
    const int i = work[--top];
    if (!alive[i]) continue;
    const int j = prev[i], l = next[i];
    const Q &qj = fan[j], &qi = fan[i], &ql = fan[l];
    // Both fan triangles (p, q_j, q_i) and (p, q_i, q_l) must exist (angles in (0, π)).
    if (!(cross(qj, qi) > 0) || !(cross(qi, ql) > 0)) continue;
    // The quadrilateral p, q_j, q_i, q_l must be convex for the flip: p and q_i on opposite sides
    // of the new diagonal q_j–q_l.
    const double sp = orient(qj, ql, 0.0, 0.0), si = orient(qj, ql, qi.x, qi.y);
    if (!(sp > 0 && si < 0)) continue;
    if (!(inCircleOrigin(qj, qi, ql) > 0)) continue; // locally Delaunay: keep
    alive[i] = 0;
    --count;
    next[j] = l;
    prev[l] = j;
    work[top++] = l;
    work[top++] = j;
  }
}

// Step 4: the largest distance from p to a vertex of its Voronoi cell, the circumradii of the fan
// triangles (p, a, b); -1 when the fan is not closed (an angle of π or more: the cell is
// unbounded). The kept neighbours into keptOut.
inline double voronoiRadius(const Q* fan, const int* next, const char* alive, std::vector<int>* keptOut) {
  int start = 0;
  while (!alive[start]) ++start;
  double radius = 0;
  int i = start;
  do {
    const int l = next[i];
    const Q &a = fan[i], &b = fan[l];
    const double c = cross(a, b);
    if (!(c > 0) || l == i) return -1;
    // Circumradius of (p, a, b) = distance from p to the Voronoi vertex of the three.
    const double ab2 = (a.x - b.x) * (a.x - b.x) + (a.y - b.y) * (a.y - b.y);
    radius = std::max(radius, std::sqrt(a.dist2 * b.dist2 * ab2) / (2.0 * c));
    if (keptOut != nullptr) keptOut->push_back(a.index);
    i = l;
  } while (i != start);
  return radius;
}

double fanRadius(const Vec3d& p, const Vec3d& n, const std::vector<Vec3d>& neighbours,
                 std::vector<int>* keptOut, FanScratch& scratch) {
  if (keptOut != nullptr) keptOut->clear();
  if (scratch.fan.size() < neighbours.size()) scratch.fan.resize(neighbours.size() + 16);
  Q* fan = scratch.fan.data();
  // 1. The neighbours in T_p, at their distances.
  int size = projectOntoTangentPlane(p, n, neighbours, fan);
  // 2. Sorted by angle, one per direction.
  bool nanAngle = false;
  for (int i = 0; i < size; ++i) nanAngle |= fan[i].angle != fan[i].angle;
  sortFan(fan, size, nanAngle);
  const int m = keepNearestPerDirection(fan, size);
  if (m < 3) return -1;
  // 3. The Delaunay fan of p by flips.
  int* next;
  char* alive;
  flipToDelaunay(fan, m, scratch, next, alive);
  // 4. The fan must be closed (every angle below π) for p's Voronoi cell to be bounded.
  return voronoiRadius(fan, next, alive, keptOut);
}

} // namespace

double localSplatRadius(const Vec3d& p, const Vec3d& n, const std::vector<Vec3d>& neighbours,
                        std::vector<int>* keptOut) {
  FanScratch scratch;
  return fanRadius(p, n, neighbours, keptOut, scratch);
}

std::vector<float> computeSplatRadii(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                                     double capRadius, double firstReach, bool local, SplatSizeStats* stats,
                                     Progress* progress, int threads, const std::vector<std::uint32_t>* rankIndex) {
  std::vector<float> radius(points.size(), static_cast<float>(capRadius));
  SplatSizeStats st;
  if (local && !points.empty() && capRadius > 0) {
    // The first neighbourhood: `firstReach`, at most the largest one ever needed (2·cap).
    const double reach0 = std::min(2 * capRadius, firstReach > 0 ? firstReach : 2 * capRadius);
    // Cells of side reach0 for the first neighbourhood; the larger ones (up to 2·cap) from cells of
    // a third of their largest radius when that is much larger (a query then visits at most 7³
    // cells, whatever the ratio of cap to reach0).
    PointGrid grid, wide;
    grid.build(points, reach0);
    const bool useWide = 2 * capRadius > 3 * reach0;
    if (useWide) wide.build(points, 2 * capRadius / 3);
    const size_t n = points.size();
    const int workers = parallelParts(n, threads, 2048);
    struct Near {
      std::uint32_t rank, idx;
    };
    struct Worker {
      FanScratch scratch;
      std::vector<Near> near;
      std::vector<Vec3d> nb;
      SplatSizeStats stats;
      char pad[64]; // no cache line shared with the next thread's state
    };
    std::vector<Worker> state(static_cast<size_t>(workers));
    // Each point's radius goes to its own slot and the counters are integers summed per thread:
    // the result is the same for any number of threads and any scheduling.
    parallelChunks(n, workers, 1024, [&](size_t k0, size_t k1, int worker) {
      Worker& w = state[size_t(worker)];
      for (size_t i = k0; i < k1; ++i) {
        const Vec3d& p = points[i];
        const Vec3d& np = normals[i];
        // The neighbours within `reach` on p's side of the surface (normals not opposed to n_p:
        // the paper's normal filter, sec. 4.1), in a fixed order (by rank): the same fan for any
        // numbering of the points.
        auto fanWithin = [&](double reach) {
          w.near.clear();
          (reach > 3 * reach0 && useWide ? wide : grid).forEachInBall(p, reach, [&](int j, double) {
            if (size_t(j) != i && normals[size_t(j)] * np >= 0)
              w.near.push_back(Near{rankIndex != nullptr ? (*rankIndex)[size_t(j)] : std::uint32_t(j), std::uint32_t(j)});
          });
          std::sort(w.near.begin(), w.near.end(), [](const Near& a, const Near& b) { return a.rank < b.rank; });
          w.nb.clear();
          for (const Near& q : w.near) w.nb.push_back(points[q.idx]);
          return fanRadius(p, np, w.nb, nullptr, w.scratch);
        };
        double reach = reach0;
        double r = fanWithin(reach);
        // Every Delaunay triangle of p has its circumcircle through p, of radius at most r (fewer
        // points can only make p's Voronoi cell larger): all Delaunay neighbours of p lie within
        // 2r. So the fan is exact when 2r <= reach; otherwise gather again within 2r (an open fan:
        // within the largest reach), up to 2·cap, beyond which the radius is clamped anyway.
        if ((r < 0 || 2 * r > reach) && reach < 2 * capRadius) {
          reach = r < 0 ? 2 * capRadius : std::min(2 * r, 2 * capRadius);
          r = fanWithin(reach);
        }
        if (r < 0) {
          ++w.stats.unbounded;
        } else if (r > capRadius) {
          ++w.stats.clamped;
        } else {
          radius[i] = static_cast<float>(r);
        }
      }
      if (worker == 0 && progress != nullptr) progress->advanceTo(double(k1) / double(n));
    });
    if (progress != nullptr) progress->advanceTo(1.0);
    for (const Worker& w : state) st.unbounded += w.stats.unbounded, st.clamped += w.stats.clamped;
  }
  double sum = 0;
  for (float r : radius) sum += r;
  st.meanRadius = radius.empty() ? 0 : sum / double(radius.size());
  if (stats != nullptr) *stats = st;
  return radius;
}

} // namespace growth
