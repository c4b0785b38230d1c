// Sharp features of a point cloud (cloud_features.h).
#include "cloud_features.h"

#include <growth/point_grid.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

namespace growth {
namespace spherepack {
namespace detail {

namespace {

constexpr double kPi = 3.14159265358979323846;
// The two-plane test: each side holds at least this share of the neighbours (and kMinSidePoints),
// at least kSideAgreement of a side's points lie on its own half-plane, the fit's RMS distance is
// below kMaxFitRmsPerRadius of the radius, and the point is within kMaxLineDistPerRadius of the
// radius from the line.
constexpr size_t kMinNeighbours = 10;
constexpr size_t kMinSidePoints = 4;
constexpr double kMinSideShare = 0.15;
constexpr double kSideAgreement = 0.85;
constexpr double kMaxFitRmsPerRadius = 0.08;
constexpr double kMaxLineDistPerRadius = 0.35;
constexpr double kMaxFitRmsPerMedian = 2.5;
constexpr double kMinFitRmsLimitPerRadius = 0.01;
// Tracing: crease points whose directions are within kTraceAngleDeg of the line's are followed.
constexpr double kTraceAngleDeg = 30;
// Rounds of smoothing of the traced lines.
constexpr int kSmoothingRounds = 4;
// The corner from the lines fitted to the stretch from kEndSkipPerD·d to (kEndSkipPerD +
// kEndFitPerD)·d back from the ends; the line's points nearer the corner give way to a straight
// segment. The crease points within the fit radius of a corner see its third plane, and a step of
// the tracing averages those within kTraceRadiusPerD·d: the line bends up to the sum from a corner.
constexpr double kEndSkipPerD = kFitRadiusPerD + kTraceRadiusPerD;
constexpr double kEndFitPerD = 4.0;
// The direction at an end of a line: over this many d of it.
constexpr double kEndStretchPerD = 3.0;
// Tracing: up to this many steps of d/2 are tried in turn where no crease point is found.
constexpr int kTraceBridgeSteps = 4;
// Two ends of lines facing each other along one line are joined up to this many d apart.
constexpr double kMaxJoinGapPerD = 6.0;
// Corners: two ends join when their forward rays pass within kRayGapPerD·d of each other, at most
// kCornerReachPerD·d ahead of each end, as far as facing ends are joined: the crease points stop
// about kFitRadiusPerD·d before a corner (where the fit's ball meets the third plane), and a gap in
// them there leaves the line's end farther back (3.0 to 3.3 d on boxes of other seeds).
constexpr double kRayGapPerD = 0.5;
constexpr double kCornerReachPerD = kMaxJoinGapPerD;
// Patches: the zone around the lines and the linking radius are both this many area spacings (and
// at least half of d); a set of fewer than kMinPatchPoints points is taken as part of the zone.
constexpr double kZonePerAreaSpacing = 2.0;
constexpr size_t kMinPatchPoints = 20;

struct Plane {
  Vec3d c, n;
  double rms = 0;
};

// Eigenvector of the smallest eigenvalue of a symmetric 3 × 3 matrix (Jacobi rotations).
Vec3d smallestEigenvector(double a[3][3], double& smallest) {
  double v[3][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (int sweep = 0; sweep < 30; ++sweep) {
    const double off = a[0][1] * a[0][1] + a[0][2] * a[0][2] + a[1][2] * a[1][2];
    if (off < 1e-30) break;
    for (int p = 0; p < 2; ++p)
      for (int q = p + 1; q < 3; ++q) {
        if (std::abs(a[p][q]) < 1e-300) continue;
        const double theta = (a[q][q] - a[p][p]) / (2 * a[p][q]);
        const double t = (theta >= 0 ? 1.0 : -1.0) / (std::abs(theta) + std::sqrt(theta * theta + 1));
        const double c = 1 / std::sqrt(t * t + 1), s = t * c;
        for (int k = 0; k < 3; ++k) {
          const double akp = a[k][p], akq = a[k][q];
          a[k][p] = c * akp - s * akq;
          a[k][q] = s * akp + c * akq;
        }
        for (int k = 0; k < 3; ++k) {
          const double apk = a[p][k], aqk = a[q][k];
          a[p][k] = c * apk - s * aqk;
          a[q][k] = s * apk + c * aqk;
        }
        for (int k = 0; k < 3; ++k) {
          const double vkp = v[k][p], vkq = v[k][q];
          v[k][p] = c * vkp - s * vkq;
          v[k][q] = s * vkp + c * vkq;
        }
      }
  }
  int m = 0;
  for (int k = 1; k < 3; ++k)
    if (a[k][k] < a[m][m]) m = k;
  smallest = std::max(0.0, a[m][m]);
  Vec3d n(v[0][m], v[1][m], v[2][m]);
  n.Normalize();
  return n;
}

bool fitPlane(const std::vector<Vec3d>& P, const std::vector<std::uint32_t>& idx, Plane& out) {
  if (idx.size() < 3) return false;
  Vec3d c(0, 0, 0);
  for (std::uint32_t i : idx) c += P[i];
  c /= double(idx.size());
  double a[3][3] = {};
  for (std::uint32_t i : idx) {
    const Vec3d q = P[i] - c;
    for (int r = 0; r < 3; ++r)
      for (int s = 0; s < 3; ++s) a[r][s] += q[r] * q[s];
  }
  for (auto& row : a)
    for (double& x : row) x /= double(idx.size());
  double smallest = 0;
  out.c = c;
  out.n = smallestEigenvector(a, smallest);
  out.rms = std::sqrt(smallest);
  return true;
}

// Solves M x = r for a 3 × 3 M by Cramer's rule; false when (nearly) singular.
bool solve3(const Vec3d rows[3], const Vec3d& r, Vec3d& x) {
  const double det = rows[0] * (rows[1] ^ rows[2]);
  const double scale = rows[0].Norm() * rows[1].Norm() * rows[2].Norm();
  if (!(std::abs(det) > 1e-9 * scale)) return false;
  // Columns of M are (rows[k][j]); x = (r · (b × c), ...) / det with the inverse's rows as cross products.
  const Vec3d c0 = rows[1] ^ rows[2], c1 = rows[2] ^ rows[0], c2 = rows[0] ^ rows[1];
  x = (c0 * r[0] + c1 * r[1] + c2 * r[2]) / det;
  return true;
}

struct CreasePoint {
  Vec3d x, t, n;
  double rms = 0; // the larger of the two planes' RMS distances
};

// The two-plane test at point i (cloud_features.h, step 1).
bool creaseAt(std::uint32_t i, const std::vector<Vec3d>& P, const std::vector<Vec3d>& N, const PointGrid& grid,
              double R, double cosHalf, double cosCrease, std::vector<std::uint32_t>& nb, CreasePoint& out) {
  nb.clear();
  grid.forEachInBall(P[i], R, [&](int j, double) { nb.push_back(std::uint32_t(j)); });
  if (nb.size() < kMinNeighbours) return false;
  std::sort(nb.begin(), nb.end());
  bool spread = false;
  for (std::uint32_t j : nb) spread = spread || std::abs(N[i] * N[j]) < cosHalf;
  if (!spread) return false;
  // Seeds: the two neighbours whose normals are farthest apart as lines.
  std::uint32_t sa = nb[0], sb = nb[0];
  double best = 2;
  for (size_t a = 0; a < nb.size(); ++a)
    for (size_t b = a + 1; b < nb.size(); ++b) {
      const double c = std::abs(N[nb[a]] * N[nb[b]]);
      if (c < best) best = c, sa = nb[a], sb = nb[b];
    }
  std::vector<std::uint32_t> side[2];
  for (std::uint32_t j : nb) side[std::abs(N[j] * N[sa]) >= std::abs(N[j] * N[sb]) ? 0 : 1].push_back(j);
  Plane pl[2];
  for (int round = 0; round < 5; ++round) {
    if (!fitPlane(P, side[0], pl[0]) || !fitPlane(P, side[1], pl[1])) return false;
    std::vector<std::uint32_t> next[2];
    for (std::uint32_t j : nb) {
      const double h0 = std::abs((P[j] - pl[0].c) * pl[0].n), h1 = std::abs((P[j] - pl[1].c) * pl[1].n);
      next[h0 <= h1 ? 0 : 1].push_back(j);
    }
    const bool same = next[0] == side[0];
    side[0].swap(next[0]);
    side[1].swap(next[1]);
    if (same) break;
  }
  const size_t minSide = std::max<size_t>(kMinSidePoints, size_t(kMinSideShare * double(nb.size())));
  if (side[0].size() < minSide || side[1].size() < minSide) return false;
  if (!fitPlane(P, side[0], pl[0]) || !fitPlane(P, side[1], pl[1])) return false;
  if (std::abs(pl[0].n * pl[1].n) > cosCrease) return false;
  if (pl[0].rms > kMaxFitRmsPerRadius * R || pl[1].rms > kMaxFitRmsPerRadius * R) return false;
  Vec3d t = pl[0].n ^ pl[1].n;
  t.Normalize();
  const Vec3d rows[3] = {pl[0].n, pl[1].n, t};
  Vec3d x;
  if (!solve3(rows, Vec3d(pl[0].n * pl[0].c, pl[1].n * pl[1].c, t * P[i]), x)) return false;
  if ((x - P[i]).Norm() > kMaxLineDistPerRadius * R) return false;
  // Each side on its own half-plane of the line, and the planes' normals oriented as the points'.
  Vec3d n(0, 0, 0);
  for (int k = 0; k < 2; ++k) {
    const Vec3d u = pl[k].n ^ t; // in plane k, across the line
    size_t pos = 0;
    double orient = 0;
    for (std::uint32_t j : side[k]) {
      pos += (P[j] - x) * u > 0 ? 1 : 0;
      orient += N[j] * pl[k].n;
    }
    const double agree = double(std::max(pos, side[k].size() - pos)) / double(side[k].size());
    if (agree < kSideAgreement) return false;
    n += orient >= 0 ? pl[k].n : -pl[k].n;
  }
  if (!(n.Norm() > 1e-12)) return false;
  n.Normalize();
  out = CreasePoint{x, t, n, std::max(pl[0].rms, pl[1].rms)};
  return true;
}

double polylineLength(const std::vector<Vec3d>& p) {
  double len = 0;
  for (size_t k = 1; k < p.size(); ++k) len += (p[k] - p[k - 1]).Norm();
  return len;
}

// The outward direction at an end of an open line, over its last stretch of kEndStretchPerD·d.
Vec3d endDirection(const std::vector<Vec3d>& p, bool back, double d) {
  const Vec3d e = back ? p.back() : p.front();
  Vec3d from = e;
  for (size_t k = 0; k < p.size(); ++k) {
    from = back ? p[p.size() - 1 - k] : p[k];
    if ((from - e).Norm() >= kEndStretchPerD * d) break;
  }
  Vec3d t = e - from;
  if (t.Norm() > 0) t.Normalize();
  return t;
}

// Two open ends that face each other along one line (a stretch where the two-plane test failed)
// are joined, nearest first, into one line (or a line's own two ends into a closed line).
void joinFacingEnds(std::vector<CloudFeatures::Line>& lines, double d) {
  const double cosFacing = std::cos(kTraceAngleDeg * kPi / 180);
  for (;;) {
    double bestGap = kMaxJoinGapPerD * d;
    size_t bl = 0, bm = 0;
    int bb = -1, bc = -1;
    for (size_t l = 0; l < lines.size(); ++l)
      for (size_t m = l; m < lines.size(); ++m) {
        if (lines[l].closed || lines[m].closed) continue;
        for (int b = 0; b < 2; ++b)
          for (int c = 0; c < 2; ++c) {
            if (l == m && (b == c || lines[l].p.size() < 4)) continue;
            const Vec3d ea = b ? lines[l].p.back() : lines[l].p.front();
            const Vec3d eb = c ? lines[m].p.back() : lines[m].p.front();
            const Vec3d ta = endDirection(lines[l].p, b == 1, d), tb = endDirection(lines[m].p, c == 1, d);
            Vec3d gap = eb - ea;
            const double len = gap.Norm();
            if (!(len < bestGap) || ta * tb > -cosFacing) continue;
            if (len > 0) {
              gap /= len;
              if (gap * ta < cosFacing || -(gap * tb) < cosFacing) continue;
            }
            bestGap = len, bl = l, bm = m, bb = b, bc = c;
          }
      }
    if (bb < 0) return;
    CloudFeatures::Line& A = lines[bl];
    if (bl == bm) {
      if (bb == 0) std::reverse(A.p.begin(), A.p.end()), std::reverse(A.n.begin(), A.n.end());
      A.p.push_back(A.p.front());
      A.n.push_back(A.n.front());
      A.closed = true;
      continue;
    }
    CloudFeatures::Line B = std::move(lines[bm]);
    if (bb == 0) std::reverse(A.p.begin(), A.p.end()), std::reverse(A.n.begin(), A.n.end());
    if (bc == 1) std::reverse(B.p.begin(), B.p.end()), std::reverse(B.n.begin(), B.n.end());
    A.p.insert(A.p.end(), B.p.begin(), B.p.end());
    A.n.insert(A.n.end(), B.n.begin(), B.n.end());
    A.support += B.support;
    lines.erase(lines.begin() + std::ptrdiff_t(bm));
  }
}

} // namespace

double featureScale(double sphereDiameter, double areaSpacing) {
  const double floor = kDefaultDiameterPerAreaSpacing * areaSpacing;
  return floor > sphereDiameter && std::isfinite(floor) ? floor : sphereDiameter;
}

CloudFeatures detectCloudFeatures(const std::vector<Vec3d>& P, const std::vector<Vec3d>& N,
                                  double sphereDiameter, double areaSpacing, double creaseAngleDeg, const Renumbering& order) {
  CloudFeatures f;
  const size_t np = P.size();
  if (np == 0 || N.size() != np || !(sphereDiameter > 0)) return f;
  const double d = featureScale(sphereDiameter, areaSpacing);
  const double crease = std::min(std::max(creaseAngleDeg, 1.0), 179.0) * kPi / 180;
  const double R = kFitRadiusPerD * d;
  f.radius = R;
  f.grid.build(P, R);
  const PointGrid& grid = f.grid;

  // 1. Crease points, in input order.
  std::vector<CreasePoint> cp;
  std::vector<std::uint32_t> nb;
  for (std::uint32_t k = 0; k < np; ++k) {
    const std::uint32_t i = order.rankOf(k);
    CreasePoint c;
    if (creaseAt(i, P, N, grid, R, std::cos(crease / 2), std::cos(crease), nb, c)) cp.push_back(c);
  }
  // A fit much looser than the cloud's usual one (kMaxFitRmsPerMedian times the median of the
  // crease points', at least kMinFitRmsLimitPerRadius of the radius) is not two planes: a third
  // plane near a corner, or a side of a few points that took some of the other side's.
  if (!cp.empty()) {
    std::vector<double> rms(cp.size());
    for (size_t k = 0; k < cp.size(); ++k) rms[k] = cp[k].rms;
    std::nth_element(rms.begin(), rms.begin() + std::ptrdiff_t(rms.size() / 2), rms.end());
    const double limit = std::max(kMaxFitRmsPerMedian * rms[rms.size() / 2], kMinFitRmsLimitPerRadius * R);
    size_t w = 0;
    for (size_t k = 0; k < cp.size(); ++k)
      if (cp[k].rms <= limit) cp[w++] = cp[k];
    cp.resize(w);
  }
  f.creasePoints = cp.size();
  if (cp.empty()) return f;

  // 2. Lines traced through them.
  const double h = kTraceStepPerD * d, reach = kTraceRadiusPerD * d;
  const double cosTrace = std::cos(kTraceAngleDeg * kPi / 180);
  std::vector<Vec3d> cpx(cp.size());
  for (size_t k = 0; k < cp.size(); ++k) cpx[k] = cp[k].x;
  PointGrid cgrid;
  cgrid.build(cpx, reach);
  // The line that took each crease point (kNoLine: none yet).
  constexpr std::uint32_t kNoLine = 0xffffffffu;
  std::vector<std::uint32_t> owner(cp.size(), kNoLine);
  std::uint32_t current = 0;
  // A step of the tracing from x along t: to the step's end y = x + t·h, moved across the line to
  // the mean of the crease points within `reach` of y whose directions agree with t (the new
  // direction: their mean); none when no such point lies beyond y − t·h/4 (the line ends there).
  // The points another line took are not followed: a line whose tracing stopped at a gap in the
  // crease points is met there by the line traced from beyond the gap, end to end, and the two are
  // joined (joinFacingEnds) instead of the second running back along the first.
  auto stepFrom = [&](const Vec3d& x, const Vec3d& t, double len, Vec3d& mx, Vec3d& mt, Vec3d& mn) {
    const Vec3d y = x + t * len;
    Vec3d sx(0, 0, 0), st(0, 0, 0), sn(0, 0, 0);
    size_t cnt = 0;
    bool ahead = false;
    cgrid.forEachInBall(y, reach, [&](int j, double) {
      if (owner[size_t(j)] != kNoLine && owner[size_t(j)] != current) return;
      const double c = cp[size_t(j)].t * t;
      if (std::abs(c) < cosTrace) return;
      sx += cp[size_t(j)].x;
      st += c >= 0 ? cp[size_t(j)].t : -cp[size_t(j)].t;
      sn += cp[size_t(j)].n;
      ++cnt;
      ahead = ahead || (cp[size_t(j)].x - y) * t > -0.25 * h;
    });
    if (cnt == 0 || !ahead || !(st.Norm() > 0) || !(sn.Norm() > 0)) return false;
    const Vec3d off = sx / double(cnt) - y;
    mx = y + off - t * (off * t);
    mt = st;
    mn = sn;
    mt.Normalize();
    mn.Normalize();
    return true;
  };
  // The seed: the mean of the crease points within h of crease point s that agree with it.
  auto seedAt = [&](size_t s, Vec3d& mx, Vec3d& mt, Vec3d& mn) {
    Vec3d sx(0, 0, 0), st(0, 0, 0), sn(0, 0, 0);
    size_t cnt = 0;
    cgrid.forEachInBall(cp[s].x, h, [&](int j, double) {
      if (owner[size_t(j)] != kNoLine) return;
      const double c = cp[size_t(j)].t * cp[s].t;
      if (std::abs(c) < cosTrace) return;
      sx += cp[size_t(j)].x;
      st += c >= 0 ? cp[size_t(j)].t : -cp[size_t(j)].t;
      sn += cp[size_t(j)].n;
      ++cnt;
    });
    if (cnt == 0 || !(st.Norm() > 0) || !(sn.Norm() > 0)) return false;
    mx = sx / double(cnt);
    mt = st;
    mn = sn;
    mt.Normalize();
    mn.Normalize();
    return true;
  };
  size_t support = 0;
  auto markUsed = [&](const Vec3d& x, const Vec3d& t) {
    cgrid.forEachInBall(x, reach, [&](int j, double d2) {
      if (owner[size_t(j)] == kNoLine && (d2 <= h * h || std::abs(cp[size_t(j)].t * t) >= cosTrace))
        owner[size_t(j)] = current, ++support;
    });
  };
  const size_t maxSteps = 4 * np + 16;
  for (size_t s = 0; s < cp.size(); ++s) {
    if (owner[s] != kNoLine) continue;
    Vec3d x0, t0, n0;
    current = std::uint32_t(f.lines.size());
    if (!seedAt(s, x0, t0, n0)) continue;
    support = 0;
    markUsed(x0, t0);
    std::vector<Vec3d> half[2], halfN[2];
    bool closed = false;
    for (int dir = 0; dir < 2 && !closed; ++dir) {
      Vec3d x = x0, t = dir == 0 ? t0 : -t0;
      for (size_t step = 0; step < maxSteps; ++step) {
        Vec3d mx, mt, mn;
        // A gap in the crease points (where the two-plane test failed) is bridged by longer steps.
        bool found = false;
        for (int k = 1; k <= kTraceBridgeSteps && !found; ++k) found = stepFrom(x, t, k * h, mx, mt, mn);
        if (!found) break;
        if (dir == 0 && half[0].size() >= 4 && (mx - x0).Norm() < h) {
          closed = true;
          break;
        }
        x = mx;
        t = mt;
        markUsed(x, t);
        half[dir].push_back(x);
        halfN[dir].push_back(mn);
      }
    }
    CloudFeatures::Line line;
    for (size_t k = half[1].size(); k-- > 0;) line.p.push_back(half[1][k]), line.n.push_back(halfN[1][k]);
    line.p.push_back(x0);
    line.n.push_back(n0);
    for (size_t k = 0; k < half[0].size(); ++k) line.p.push_back(half[0][k]), line.n.push_back(halfN[0][k]);
    if (closed) {
      line.p.push_back(x0);
      line.n.push_back(n0);
      line.closed = true;
    }
    line.support = support;
    f.lines.push_back(std::move(line));
  }
  joinFacingEnds(f.lines, d);
  // The traced points scatter across the line by the noise of the crease points' fits: a few
  // rounds of smoothing (1/4, 1/2, 1/4; the ends of open lines fixed) take most of it out.
  for (auto& L : f.lines) {
    const size_t m = L.p.size();
    if (m < 3) continue;
    for (int round = 0; round < kSmoothingRounds; ++round) {
      std::vector<Vec3d> q = L.p;
      for (size_t k = 0; k < m; ++k) {
        if (!L.closed && (k == 0 || k + 1 == m)) continue;
        // A closed line repeats its first point at the end: its neighbours wrap past it.
        const size_t prev = k > 0 ? k - 1 : m - 2, next = k + 1 < m ? k + 1 : 1;
        q[k] = (L.p[prev] + L.p[k] * 2.0 + L.p[next]) * 0.25;
      }
      if (L.closed) q[m - 1] = q[0];
      L.p.swap(q);
    }
  }
  {
    size_t w = 0;
    for (size_t l = 0; l < f.lines.size(); ++l) {
      const double len = polylineLength(f.lines[l].p);
      if (len < kMinLinePerD * d || double(f.lines[l].support) < kMinSupportPerD * len / d) ++f.linesDropped;
      else if (w++ != l) f.lines[w - 1] = std::move(f.lines[l]);
    }
    f.lines.resize(w);
  }

  // 3. Corners: the open ends, joined where their rays meet, extended to the least-squares point.
  // Near a corner the crease points come from neighbourhoods of three planes and bend the line's
  // last stretch: the corner is computed from the line fitted to the stretch from kEndSkipPerD·d
  // to (kEndSkipPerD + kEndFitPerD)·d back from each end (`fit`, through `fitPoint`), where the
  // line is long enough; the ends are joined by their own rays as traced.
  struct End {
    size_t line;
    bool back;
    Vec3d e, t, n;
    Vec3d fitPoint, fit;
    bool fitted = false;
  };
  std::vector<End> ends;
  for (size_t l = 0; l < f.lines.size(); ++l) {
    const auto& L = f.lines[l];
    if (L.closed) continue;
    for (int b = 0; b < 2; ++b) {
      const Vec3d e = b ? L.p.back() : L.p.front();
      const Vec3d t = endDirection(L.p, b == 1, d);
      if (!(t.Norm() > 0)) continue;
      End E{l, b == 1, e, t, b ? L.n.back() : L.n.front(), e, t, false};
      // The points of the fitted stretch, by arc length from the end.
      std::vector<std::uint32_t> idx;
      std::vector<Vec3d> pts;
      double arc = 0;
      for (size_t k = 1; k < L.p.size(); ++k) {
        const Vec3d& q = b ? L.p[L.p.size() - 1 - k] : L.p[k];
        const Vec3d& q0 = b ? L.p[L.p.size() - k] : L.p[k - 1];
        arc += (q - q0).Norm();
        if (arc > (kEndSkipPerD + kEndFitPerD) * d) break;
        if (arc >= kEndSkipPerD * d) pts.push_back(q);
      }
      if (arc > (kEndSkipPerD + kEndFitPerD) * d && pts.size() >= 4) {
        for (std::uint32_t k = 0; k < pts.size(); ++k) idx.push_back(k);
        Plane pl;
        fitPlane(pts, idx, pl);
        // The line's direction: the largest spread, taken as the chord of the stretch.
        Vec3d dir = pts.front() - pts.back();
        if (dir.Norm() > 0) {
          dir.Normalize();
          E.fitPoint = pl.c;
          E.fit = dir * t >= 0 ? dir : -dir;
          E.fitted = true;
        }
      }
      ends.push_back(E);
    }
  }
  std::vector<std::uint32_t> parent(ends.size());
  std::iota(parent.begin(), parent.end(), 0u);
  auto root = [&](std::uint32_t x) {
    while (parent[x] != x) x = parent[x] = parent[parent[x]];
    return x;
  };
  for (size_t a = 0; a < ends.size(); ++a)
    for (size_t b = a + 1; b < ends.size(); ++b) {
      // Closest points of the two rays e + s·t (s >= 0).
      const End &A = ends[a], &B = ends[b];
      const Vec3d w = A.e - B.e;
      const double tt = A.t * B.t, da = A.t * w, db = B.t * w;
      const double den = 1 - tt * tt;
      double sa = 0, sb = 0;
      if (den > 1e-6) {
        sa = (tt * db - da) / den;
        sb = (db - tt * da) / den;
      } else {
        sa = std::max(0.0, -da); // (nearly) parallel: facing ends only
        sb = std::max(0.0, db);
      }
      if (sa < -0.25 * d || sb < -0.25 * d || sa > kCornerReachPerD * d || sb > kCornerReachPerD * d) continue;
      const Vec3d pa = A.e + A.t * std::max(sa, 0.0), pb = B.e + B.t * std::max(sb, 0.0);
      if ((pa - pb).Norm() > kRayGapPerD * d) continue;
      const std::uint32_t x = root(std::uint32_t(a)), y = root(std::uint32_t(b));
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
  std::vector<int> cornerOfRoot(ends.size(), -1);
  for (size_t a = 0; a < ends.size(); ++a) {
    const std::uint32_t r = root(std::uint32_t(a));
    if (cornerOfRoot[r] >= 0) continue;
    // The point nearest to the lines of the group's ends: sum (I - t tᵀ) x = sum (I - t tᵀ) e.
    double m[3][3] = {};
    Vec3d rhs(0, 0, 0), nsum(0, 0, 0), esum(0, 0, 0);
    size_t cnt = 0;
    for (size_t b = a; b < ends.size(); ++b) {
      if (root(std::uint32_t(b)) != r) continue;
      const End& E = ends[b];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] += (i == j ? 1.0 : 0.0) - E.fit[i] * E.fit[j];
      rhs += E.fitPoint - E.fit * (E.fit * E.fitPoint);
      nsum += E.n;
      esum += E.e;
      ++cnt;
    }
    Vec3d c = esum / double(cnt);
    if (cnt >= 2) {
      const Vec3d rows[3] = {Vec3d(m[0][0], m[0][1], m[0][2]), Vec3d(m[1][0], m[1][1], m[1][2]),
                             Vec3d(m[2][0], m[2][1], m[2][2])};
      Vec3d x;
      if (solve3(rows, rhs, x) && (x - c).Norm() < kCornerReachPerD * d) c = x;
    }
    if (nsum.Norm() > 0) nsum.Normalize();
    cornerOfRoot[r] = int(f.corners.size());
    f.corners.push_back(c);
    f.cornerNormals.push_back(nsum);
  }
  for (const End& E : ends) {
    const int c = cornerOfRoot[root(std::uint32_t(&E - ends.data()))];
    auto& L = f.lines[E.line];
    const Vec3d& x = f.corners[size_t(c)];
    // The line's points that lie beyond the corner, or within d/2 of it (within the stretch left
    // out of the fit where the corner came from fitted lines), give way to it.
    const double keepOff = E.fitted ? kEndSkipPerD * d : 0.5 * d;
    if (E.back) {
      while (L.p.size() > 1 && ((L.p.back() - x) * E.t > 0 || (L.p.back() - x).Norm() < keepOff))
        L.p.pop_back(), L.n.pop_back();
      if ((L.p.back() - x).Norm() > 0) L.p.push_back(x), L.n.push_back(f.cornerNormals[size_t(c)]);
      L.back = c;
    } else {
      while (L.p.size() > 1 && ((L.p.front() - x) * E.t > 0 || (L.p.front() - x).Norm() < keepOff))
        L.p.erase(L.p.begin()), L.n.erase(L.n.begin());
      if ((L.p.front() - x).Norm() > 0) L.p.insert(L.p.begin(), x), L.n.insert(L.n.begin(), f.cornerNormals[size_t(c)]);
      L.front = c;
    }
  }

  // 4. Patches.
  if (f.lines.empty()) return f;
  const double w = std::max(kZonePerAreaSpacing * areaSpacing, 0.5 * d);
  std::vector<Vec3d> dense; // the lines, every w/4
  for (const auto& L : f.lines)
    for (size_t k = 0; k + 1 < L.p.size(); ++k) {
      const double len = (L.p[k + 1] - L.p[k]).Norm();
      const int pieces = std::max(1, int(std::ceil(len / (0.25 * w))));
      for (int j = 0; j <= pieces; ++j) dense.push_back(L.p[k] + (L.p[k + 1] - L.p[k]) * (double(j) / pieces));
    }
  PointGrid lgrid;
  lgrid.build(dense, w);
  // zone: 1 within w of a line, 3 farther than kPatchReachPerZone·w (every patch), 0 between.
  std::vector<char> zone(np, 0);
  const double far = kPatchReachPerZone * w;
  for (std::uint32_t i = 0; i < np; ++i) {
    double nearest = std::numeric_limits<double>::infinity();
    lgrid.forEachInBall(P[i], far, [&](int, double d2) { nearest = std::min(nearest, d2); });
    zone[i] = nearest <= w * w ? 1 : nearest <= far * far ? 0 : 3;
  }
  PointGrid wgrid;
  wgrid.build(P, w);
  f.patch.assign(np, kNoPatch);
  std::vector<std::uint32_t> stack, members;
  std::uint32_t next = 0;
  // The sets are joined through the far points too (which take no patch in the end): a band of
  // 3 w around a face has holes in a random sampling wide enough to cut it (a strip of 0.024 to
  // 0.045 without points across the band on a box of 30000 points, where w = 0.042), the face's
  // interior has none.
  for (std::uint32_t k = 0; k < np; ++k) {
    const std::uint32_t s = order.rankOf(k);
    if (zone[s] != 0 || f.patch[s] != kNoPatch) continue;
    members.clear();
    stack.assign(1, s);
    f.patch[s] = next;
    size_t near = 0;
    while (!stack.empty()) {
      const std::uint32_t i = stack.back();
      stack.pop_back();
      members.push_back(i);
      near += zone[i] == 0 ? 1 : 0;
      wgrid.forEachInBall(P[i], w, [&](int j, double) {
        if ((zone[size_t(j)] != 0 && zone[size_t(j)] != 3) || f.patch[size_t(j)] != kNoPatch) return;
        f.patch[size_t(j)] = next;
        stack.push_back(std::uint32_t(j));
      });
    }
    for (std::uint32_t i : members)
      if (zone[i] == 3) f.patch[i] = kNoPatch;
    if (near < kMinPatchPoints) {
      for (std::uint32_t i : members)
        if (zone[i] == 0) f.patch[i] = kNoPatch, zone[i] = 2; // small: into the zone
      continue;
    }
    ++next;
  }
  f.patches = next;
  if (next == 0) {
    f.patch.clear();
    return f;
  }
  // The zone's points: the patch whose points' tangent planes pass nearest (3 w around) and whose
  // normals agree best with theirs (w per unit of 1 − |n·m|: a point right at the crease lies on
  // both planes, its normal tells which side its splat is on); none found: every patch.
  std::vector<std::uint32_t> assigned(np, kNoPatch);
  for (std::uint32_t i = 0; i < np; ++i) {
    if (zone[i] != 1 && zone[i] != 2) continue;
    double best = 1e300;
    std::uint32_t bestPatch = kNoPatch;
    grid.forEachInBall(P[i], std::max(3 * w, R), [&](int j, double d2) {
      if (zone[size_t(j)] || f.patch[size_t(j)] == kNoPatch) return;
      const double score = std::abs((P[i] - P[size_t(j)]) * N[size_t(j)]) + 0.05 * std::sqrt(d2) +
                           w * (1 - std::abs(N[i] * N[size_t(j)]));
      if (score < best || (score == best && f.patch[size_t(j)] < bestPatch)) best = score, bestPatch = f.patch[size_t(j)];
    });
    assigned[i] = bestPatch;
  }
  for (std::uint32_t i = 0; i < np; ++i)
    if (zone[i] == 1 || zone[i] == 2) f.patch[i] = assigned[i];
  return f;
}

std::vector<std::pair<std::uint32_t, Vec3d>> CloudFeatures::sidesAt(const Vec3d& x, const Vec3d& t,
                                                                    const std::vector<Vec3d>& P) const {
  std::vector<std::pair<std::uint32_t, Vec3d>> sum;
  grid.forEachInBall(x, radius, [&](int j, double) {
    const std::uint32_t p = patch[size_t(j)];
    Vec3d off = P[size_t(j)] - x;
    off -= t * (off * t);
    for (auto& e : sum)
      if (e.first == p) {
        e.second += off;
        return;
      }
    sum.emplace_back(p, off);
  });
  std::sort(sum.begin(), sum.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  size_t w = 0;
  for (auto& e : sum)
    if (e.second.Norm() > 0) e.second.Normalize(), sum[w++] = e;
  sum.resize(w);
  return sum;
}

} // namespace detail
} // namespace spherepack
} // namespace growth
