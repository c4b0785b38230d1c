#include <growth/cloud_scale.h>
#include <growth/input_cloud.h>
#include <growth/morton.h>
#include <growth/parallel.h>
#include <growth/point_grid.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <utility>

namespace growth {

namespace {
using Point = Vec3d;
constexpr double kPi = 3.14159265358979323846;

bool finite(const Point& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }

// Median of v (reordered): the middle value, the mean of the two middle ones for an even count.
double median(std::vector<double>& v) {
  if (v.empty()) return 0;
  const size_t m = v.size() / 2;
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(m), v.end());
  const double hi = v[m];
  if (v.size() % 2 == 1) return hi;
  return 0.5 * (*std::max_element(v.begin(), v.begin() + std::ptrdiff_t(m)) + hi);
}

// The value of rank round(q (n - 1)) of v (reordered).
double quantile(std::vector<double>& v, double q) {
  const size_t r = static_cast<size_t>(std::llround(q * double(v.size() - 1)));
  std::nth_element(v.begin(), v.begin() + std::ptrdiff_t(r), v.end());
  return v[r];
}

// Mean number of points per occupied cell of side h (cells counted from `origin`, at most 2^20
// per axis).
double occupancy(const std::vector<Point>& pts, const Point& origin, double h, std::vector<std::uint64_t>& keys) {
  keys.clear();
  const double inv = 1.0 / h;
  const std::int64_t maxCoord = (std::int64_t(1) << 20) - 1;
  for (const Point& p : pts) {
    std::uint64_t k = 0;
    for (int a = 0; a < 3; ++a) {
      const std::int64_t c =
          std::min(maxCoord, std::max<std::int64_t>(0, std::int64_t(std::floor((p[a] - origin[a]) * inv))));
      k = (k << 21) | std::uint64_t(c);
    }
    keys.push_back(k);
  }
  std::sort(keys.begin(), keys.end());
  const size_t cells = size_t(std::unique(keys.begin(), keys.end()) - keys.begin());
  return double(pts.size()) / double(std::max<size_t>(cells, 1));
}

// Neighbour search with a bounded radius and a bounded number of visited points.
struct Search {
  const PointGrid* grid = nullptr;
  double start = 0, cap = 0;      // first and largest radius
  const Point* points = nullptr;  // with normals: the grid's points and their normals, for
  const Point* normals = nullptr; // leaving out the points on another sheet (SamplingOptions::normals)
};

// Another sheet is seen when at least this many points of it are (a stray point with an opposed
// normal is no sheet: among uniform outliers, many samples see one); its
// gap is the distance across to the kSheetPoints-th nearest of them.
constexpr int kSheetPoints = 3;

// q lies on another sheet than p (SamplingOptions::normals): the squared distance from q to p's
// tangent plane, or -1 when q is on p's sheet.
double otherSheet(const Search& s, std::uint32_t p, std::uint32_t q, double d2) {
  const Point& np = s.normals[p];
  if (np * s.normals[q] >= 0) return -1;
  const double across = (s.points[q] - s.points[p]) * np, across2 = across * across;
  return across2 > kOtherSheetSine * kOtherSheetSine * d2 ? across2 : -1;
}

using Neighbour = std::pair<double, std::uint32_t>; // squared distance, index

// The `want` nearest points to c other than `self`, ascending by (squared distance, index), in
// out. False when fewer than `want` lie within the cap. The radius grows by 1.5 from the start
// while too few points lie within it. When more than kSamplingVisitLimit do (a dense cluster),
// the visit stops there and the radius shrinks to the want-th distance among those visited (the
// want nearest lie within it); when that does not shrink it (duplicates), the nearest of those
// visited are taken. With s.normals, the points on another sheet (otherSheet) are left out, and
// gap2 (when given) receives the squared distance across to the kSheetPoints-th nearest of them
// (-1 when fewer were seen); a search that visits 4 kSamplingVisitLimit points without finding
// `want` on the sample's own sheet fails.
bool nearestOthers(const Search& s, const Point& c, std::uint32_t self, size_t want, std::vector<Neighbour>& out,
                   double* gap2 = nullptr) {
  double r = s.start;
  for (;;) {
    out.clear();
    size_t visited = 0;
    // The kSheetPoints smallest squared distances across (ascending; -1: not yet).
    double across[kSheetPoints];
    std::fill(across, across + kSheetPoints, -1.0);
    const bool complete = s.grid->forEachInBallWhile(c, r, [&](int i, double d2) {
      ++visited;
      const double across2 = s.normals != nullptr && std::uint32_t(i) != self ? otherSheet(s, self, std::uint32_t(i), d2) : -1;
      if (across2 >= 0) {
        for (int j = 0; j < kSheetPoints; ++j) {
          if (across[j] >= 0 && across[j] <= across2) continue;
          for (int m = kSheetPoints - 1; m > j; --m) across[m] = across[m - 1];
          across[j] = across2;
          break;
        }
      } else if (std::uint32_t(i) != self) {
        out.emplace_back(d2, std::uint32_t(i));
      }
      return out.size() < kSamplingVisitLimit && visited < 4 * kSamplingVisitLimit;
    });
    if (gap2 != nullptr) *gap2 = across[kSheetPoints - 1];
    if (!complete && out.size() < want) return false; // thousands of points, all on other sheets
    if (!complete) {
      std::nth_element(out.begin(), out.begin() + std::ptrdiff_t(want - 1), out.end());
      const double shrunk = std::sqrt(out[want - 1].first);
      if (!(shrunk < 0.99 * r)) break;
      r = shrunk;
      continue;
    }
    if (out.size() >= want) break;
    if (r >= s.cap) return false;
    r = std::min(s.cap, 1.5 * r);
  }
  // A typical search ends with fewer than 2 want points: sorting them all is faster than a selection.
  if (out.size() > 2 * want) {
    std::nth_element(out.begin(), out.begin() + std::ptrdiff_t(want - 1), out.end());
    out.resize(want);
  }
  std::sort(out.begin(), out.end());
  out.resize(want);
  return true;
}

// Variance of the offsets normal to the surface around `p` from p and its neighbours (the points
// of `nb`): PCA frame, least-squares quadric height over the tangent plane, RSS / (points - 6).
// -1 when the points do not determine the quadric (too few, collinear, or all on one conic).
double localNoiseVariance(const Point& p, const std::vector<Point>& pts, const std::vector<Neighbour>& nb,
                          std::vector<Eigen::Vector3d>& local) {
  const int count = int(nb.size()) + 1;
  if (count < 7) return -1;
  // Coordinates relative to p and in units of the neighbourhood's radius (conditioning).
  const double radius = std::sqrt(nb.back().first);
  if (!(radius > 0)) return -1;
  const double inv = 1.0 / radius;
  local.resize(size_t(count));
  local[0].setZero();
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (int i = 1; i < count; ++i) {
    const Point d = (pts[nb[size_t(i - 1)].second] - p) * inv;
    local[size_t(i)] = Eigen::Vector3d(d[0], d[1], d[2]);
    mean += local[size_t(i)];
  }
  mean /= double(count);
  Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
  for (auto& e : local) {
    e -= mean;
    cov.noalias() += e * e.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(cov); // eigenvalues ascending: the normal is the first eigenvector
  const Eigen::Vector3d n = eig.eigenvectors().col(0), t1 = eig.eigenvectors().col(2), t2 = eig.eigenvectors().col(1);
  // Normal equations of the least-squares quadric (u, v within [-1, 1]: well scaled), solved by
  // LDL^T; a pivot below 1e-9 of the largest means the points do not determine the quadric.
  Eigen::Matrix<double, 6, 6> ata = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> atw = Eigen::Matrix<double, 6, 1>::Zero();
  for (auto& e : local) {
    const double u = e.dot(t1), v = e.dot(t2), w = e.dot(n);
    e = Eigen::Vector3d(u, v, w); // kept for the residuals
    const double row[6] = {1.0, u, v, u * u, u * v, v * v};
    for (int r = 0; r < 6; ++r) {
      for (int c = 0; c <= r; ++c) ata(r, c) += row[r] * row[c];
      atw[r] += row[r] * w;
    }
  }
  const Eigen::LDLT<Eigen::Matrix<double, 6, 6>, Eigen::Lower> ldlt(ata);
  const auto pivots = ldlt.vectorD();
  if (ldlt.info() != Eigen::Success || !(pivots.minCoeff() > 1e-9 * pivots.maxCoeff())) return -1;
  const Eigen::Matrix<double, 6, 1> c = ldlt.solve(atw);
  double rss = 0; // from the residuals (|w|^2 - c.A^T w would cancel on clean clouds)
  for (const auto& e : local) {
    const double u = e[0], v = e[1];
    const double r = e[2] - (c[0] + c[1] * u + c[2] * v + c[3] * u * u + c[4] * u * v + c[5] * v * v);
    rss += r * r;
  }
  return rss / double(count - 6) * radius * radius;
}

struct Local {
  double nearest2 = -1; // squared distance to the nearest other point; -1: isolated
  double kth2 = -1;     // squared distance to the k-th nearest other point
  double noise2 = -1;   // local offset variance; -1: not measured
  double gap2 = -1;     // squared distance across to another sheet seen (nearestOthers); -1: none
};

// Measures the samples (indices into pts) against `grid` over pts, on `threads` threads. They are
// visited in the Morton order of cells of side `cell` (from `origin`): consecutive searches then
// touch the same memory; each result goes to its sample's slot, so the order changes nothing else.
std::vector<Local> measureSamples(const std::vector<Point>& pts, const std::vector<std::uint32_t>& samples,
                                  const Search& search, const Point& origin, double cell, size_t k,
                                  size_t noiseStride, int threads) {
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(samples.size());
  const double inv = 1.0 / cell;
  for (size_t s = 0; s < samples.size(); ++s) {
    std::uint64_t c[3];
    for (int a = 0; a < 3; ++a)
      c[a] = std::uint64_t(std::min(2097151.0, std::max(0.0, std::floor((pts[samples[s]][a] - origin[a]) * inv))));
    order[s] = {mortonCode(c[0], c[1], c[2]), std::uint32_t(s)};
  }
  std::sort(order.begin(), order.end());
  std::vector<Local> out(samples.size());
  const int parts = parallelParts(samples.size(), threads, 256);
  parallelFor(samples.size(), parts, [&](size_t b, size_t e, int) {
    std::vector<Neighbour> nb;
    nb.reserve(kSamplingVisitLimit);
    std::vector<Eigen::Vector3d> scratch;
    for (size_t o = b; o < e; ++o) {
      const size_t s = order[o].second;
      const Point& p = pts[samples[s]];
      if (!nearestOthers(search, p, samples[s], k, nb, &out[s].gap2)) continue;
      out[s].nearest2 = nb.front().first;
      out[s].kth2 = nb.back().first;
      if (noiseStride > 0 && s % noiseStride == 0) out[s].noise2 = localNoiseVariance(p, pts, nb, scratch);
    }
  });
  return out;
}

// Median of the k-th neighbour distances squared of the measured samples (0 when none).
double medianKth2(const std::vector<Local>& m) {
  std::vector<double> v;
  for (const Local& l : m)
    if (l.kth2 >= 0) v.push_back(l.kth2);
  return median(v);
}
} // namespace

SamplingEstimate estimateSampling(const std::vector<Vec3d>& points, int threads) {
  return estimateSampling(points, SamplingOptions(), threads);
}

SamplingEstimate estimateSampling(const std::vector<Vec3d>& points, const SamplingOptions& options,
                                  int threads) {
  SamplingEstimate est;
  const size_t n = points.size();
  const size_t maxSamples = std::max<size_t>(options.maxSamples, 1);
  const size_t stride = std::max<size_t>(1, (n + maxSamples - 1) / maxSamples);
  std::vector<size_t> sampled; // finite sampled points, indices into `points`
  for (size_t i = 0; i < n; i += stride)
    if (finite(points[i])) sampled.push_back(i);
  if (sampled.size() < 2) {
    est.isolated = sampled.size();
    return est;
  }

  // The robust box: 1 % and 99 % quantiles of the sampled coordinates, widened on every side by
  // their largest extent.
  Point lo, hi;
  double extent = 0;
  {
    std::vector<double> c(sampled.size());
    for (int a = 0; a < 3; ++a) {
      for (size_t i = 0; i < sampled.size(); ++i) c[i] = points[sampled[i]][a];
      lo[a] = c.empty() ? 0 : quantile(c, 0.01);
      hi[a] = c.empty() ? 0 : quantile(c, 0.99);
      extent = std::max(extent, hi[a] - lo[a]);
    }
  }
  if (!(extent > 0) || !std::isfinite(extent)) {
    // All but a few sampled points coincide: the spacing is 0 (duplicates), there is no surface.
    est.samples = sampled.size();
    return est;
  }
  for (int a = 0; a < 3; ++a) lo[a] -= extent, hi[a] += extent;
  auto inBox = [&](const Point& p) {
    return finite(p) && p[0] >= lo[0] && p[0] <= hi[0] && p[1] >= lo[1] && p[1] <= hi[1] && p[2] >= lo[2] &&
           p[2] <= hi[2];
  };

  // The points the search sees (the input itself when all are inside the box, else a copy of
  // those inside), and the samples' indices among them.
  size_t inside = 0;
  for (const Point& p : points) inside += inBox(p);
  const bool withNormals = options.normals != nullptr && options.normals->size() == n;
  std::vector<Point> copy, copyNormals;
  std::vector<std::uint32_t> samples;
  if (inside < n) {
    copy.reserve(inside);
    for (size_t i = 0; i < n; ++i) {
      if (!inBox(points[i])) continue;
      if (i % stride == 0) samples.push_back(std::uint32_t(copy.size()));
      copy.push_back(points[i]);
      if (withNormals) copyNormals.push_back((*options.normals)[i]);
    }
  } else {
    for (size_t i : sampled) samples.push_back(std::uint32_t(i));
  }
  const std::vector<Point>& kept = inside < n ? copy : points;
  const Point* keptNormals = !withNormals ? nullptr : inside < n ? copyNormals.data() : options.normals->data();
  const size_t outside = sampled.size() - samples.size();
  if (kept.size() < 2) {
    est.isolated = sampled.size();
    return est;
  }
  const size_t k = std::min<size_t>(size_t(std::max(options.neighbours, 1)), kept.size() - 1);

  // First guess of the scale, on the samples alone: a cell size from their occupancy, then their
  // median k-th neighbour distance in a grid of that size.
  std::vector<Point> subset; // the samples, as points
  subset.reserve(samples.size());
  for (std::uint32_t s : samples) subset.push_back(kept[s]);
  double cell;
  {
    std::vector<Point> few; // at most 4096 of them for the occupancy
    const size_t fewStride = (subset.size() + 4095) / 4096;
    for (size_t i = 0; i < subset.size(); i += fewStride) few.push_back(subset[i]);
    std::vector<std::uint64_t> keys;
    const double target = 4.0; // points per occupied cell
    double a = 3 * extent / double(1 << 20), b = 3 * extent;
    if (occupancy(few, lo, a, keys) >= target) {
      b = a; // mostly duplicates: the finest cells
    } else {
      for (int it = 0; it < 10; ++it) {
        const double mid = std::sqrt(a * b);
        (occupancy(few, lo, mid, keys) >= target ? b : a) = mid;
      }
    }
    // Cells of the subset: the occupancy's cell for `few`, scaled to the subset's density.
    cell = b * std::sqrt(double(few.size()) / double(subset.size()));
  }
  double kth; // the k-th neighbour distance expected in the whole cloud
  {
    PointGrid grid;
    grid.build(subset, cell);
    Search search;
    search.grid = &grid;
    search.start = 0.5 * cell;
    search.cap = 8 * cell;
    std::vector<std::uint32_t> queries;
    const size_t qStride = (subset.size() + 1999) / 2000;
    for (size_t i = 0; i < subset.size(); i += qStride) queries.push_back(std::uint32_t(i));
    const double subsetKth2 = medianKth2(measureSamples(subset, queries, search, lo, cell, k, 0, threads));
    // r_k^2 is proportional to the area per point: the whole cloud is denser by kept / subset.
    kth = std::sqrt(subsetKth2 * double(subset.size()) / double(kept.size()));
    if (!(kth > 0)) kth = cell * std::sqrt(double(subset.size()) / double(kept.size()));
  }

  // The samples measured against the whole cloud. A guess off by more than 2 (a stride sample of
  // a cloud stored in a regular order is not a random thinning) is corrected from the result.
  std::vector<Local> local;
  for (int pass = 0; pass < 3; ++pass) {
    PointGrid grid;
    grid.build(kept, 2 * kth);
    Search search;
    search.grid = &grid;
    search.start = 1.3 * kth;
    search.cap = 4 * kth;
    search.points = kept.data();
    search.normals = keptNormals;
    const size_t maxNoise = std::max<size_t>(options.maxNoiseSamples, 1);
    const size_t noiseStride = std::max<size_t>(1, (samples.size() + maxNoise - 1) / maxNoise);
    local = measureSamples(kept, samples, search, lo, kth, k, noiseStride, threads);
    size_t found = 0;
    for (const Local& l : local) found += l.kth2 >= 0;
    const double measured = std::sqrt(medianKth2(local));
    if (pass == 2) break;
    if (2 * found < local.size()) kth *= 4; // most isolated: the guess was far too small
    else if (measured > 2 * kth || (measured > 0 && measured < 0.5 * kth)) kth = measured;
    else break;
  }

  std::vector<double> nearest, kth2, noise2;
  for (const Local& l : local) {
    if (l.kth2 < 0) continue;
    nearest.push_back(l.nearest2);
    kth2.push_back(l.kth2);
    if (l.noise2 >= 0) noise2.push_back(l.noise2);
    if (l.gap2 >= 0) est.sheetGaps.push_back(float(std::sqrt(l.gap2)));
  }
  est.samples = kth2.size();
  est.isolated = outside + (samples.size() - kth2.size());
  est.noiseSamples = noise2.size();
  if (kth2.empty()) return est;
  // The trimmed mean first (median() reorders): growth::meanSpacing's estimator on these samples.
  est.spacing = trimmedMeanSpacing(nearest);
  est.medianSpacing = std::sqrt(median(nearest));
  est.areaPerPoint = kPi * median(kth2) / (double(k) - 1.0 / 3.0);
  if (!noise2.empty()) {
    const double dof = double(k + 1) - 6.0;
    const double m = std::pow(1.0 - 2.0 / (9.0 * dof), 3.0);
    est.noiseSigma = std::sqrt(median(noise2) / m);
    est.noise = std::sqrt(5.0) * est.noiseSigma;
  }
  return est;
}

namespace {
bool finite3(const Vec3d& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
} // namespace

double roughSpacing(const Box3d& box, size_t n) {
  if (n < 2 || box.IsNull()) return 0;
  return box.Diag() / std::sqrt(double(n));
}

Box3d robustBox(const std::vector<Vec3d>& points, size_t maxSamples) {
  Box3d box;
  const size_t stride = std::max<size_t>(1, points.size() / std::max<size_t>(1, maxSamples));
  std::vector<double> c[3];
  for (size_t i = 0; i < points.size(); i += stride)
    if (finite3(points[i]))
      for (int a = 0; a < 3; ++a) c[a].push_back(points[i][a]);
  if (c[0].empty()) return box;
  double lo[3], hi[3], extent = 0;
  for (int a = 0; a < 3; ++a) {
    auto at = [&](double q) {
      const size_t k = std::min(c[a].size() - 1, size_t(q * double(c[a].size() - 1) + 0.5));
      std::nth_element(c[a].begin(), c[a].begin() + std::ptrdiff_t(k), c[a].end());
      return c[a][k];
    };
    lo[a] = at(0.01);
    hi[a] = at(0.99);
    extent = std::max(extent, hi[a] - lo[a]);
  }
  box.Add(Vec3d(lo[0] - extent, lo[1] - extent, lo[2] - extent));
  box.Add(Vec3d(hi[0] + extent, hi[1] + extent, hi[2] + extent));
  return box;
}

double meanSpacing(const std::vector<Vec3d>& points, size_t maxSamples) {
  return meanSpacing(points, maxSamples, 0);
}

double meanSpacing(const std::vector<Vec3d>& points, size_t maxSamples, int threads) {
  if (points.size() < 2) return 0;
  // Cells from the bulk of the cloud (a far point would make them huge, and a cell hold everything).
  const Box3d box = robustBox(points, maxSamples);
  if (box.IsNull()) return 0;
  size_t inside = 0;
  for (const auto& p : points) inside += box.IsIn(p) ? 1 : 0;
  PointGrid grid;
  grid.build(points, std::max(roughSpacing(box, std::max<size_t>(inside, 2)), 1e-12 * (1.0 + box.Diag())));
  const size_t stride = std::max<size_t>(1, points.size() / std::max<size_t>(1, maxSamples));
  // The samples' nearest distances, batched by grid cell (the same values as one nearest() query
  // per sample), then summed in sample order, leaving out those beyond kSpacingOutlierFactor times
  // their median.
  std::vector<double> d2;
  grid.nearestOtherSquaredDistances(stride, d2, threads);
  return trimmedMeanSpacing(d2);
}

double trimmedMeanSpacing(const std::vector<double>& d2) {
  std::vector<double> valid;
  valid.reserve(d2.size());
  for (const double v : d2)
    if (v >= 0) valid.push_back(v);
  if (valid.empty()) return 0;
  const size_t mid = valid.size() / 2;
  std::nth_element(valid.begin(), valid.begin() + std::ptrdiff_t(mid), valid.end());
  // (A median of 0, more than half the samples on a duplicate, leaves nothing out.)
  const double cut2 = valid[mid] > 0 ? kSpacingOutlierFactor * kSpacingOutlierFactor * valid[mid]
                                     : std::numeric_limits<double>::infinity();
  double sum = 0;
  size_t n = 0;
  for (const double v : d2) {
    if (v >= 0 && v <= cut2) {
      sum += std::sqrt(v);
      ++n;
    }
  }
  return n > 0 ? sum / double(n) : 0;
}

} // namespace growth
