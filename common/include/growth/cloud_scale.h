#pragma once
// Robust estimates of how a point cloud samples its surface: the spacing, the area each point
// stands for, and the noise normal to the surface. Medians over a fixed-stride sample of the points,
// so that outliers and a few far points barely move them.
//
// For each sampled point p, its k nearest other points (k = SamplingOptions::neighbours):
// - medianSpacing = median over the samples of the distance to the nearest other point. For a Poisson
//   sample of the plane with area a per point, P(r1 > r) = exp(-pi r^2 / a), so the median is
//   sqrt(a ln 2 / pi) = 0.4697 sqrt(a).
// - areaPerPoint = pi median(r_k)^2 / (k - 1/3), r_k the distance to the k-th nearest other point:
//   for a Poisson sample, pi r_k^2 / a is Gamma(k, 1)-distributed, whose median is k - 1/3 +
//   O(1/k). The same length measured on regular samplings (a square lattice gives 1.002 h^2 at k
//   = 16, a triangular one 0.93 of its area), so sqrt(areaPerPoint) is a sampling length that
//   does not depend on how regular the sampling is, unlike the spacing (0.47 sqrt(a) for random
//   samples, sqrt(a) on a square lattice).
// - noiseSigma: the points' offsets normal to the surface. In a frame from the PCA of p and its k
//   neighbours (normal: the smallest principal axis), a quadric height w = c0 + c1 u + c2 v + c3 u^2
//   + c4 uv + c5 v^2 is fitted to the k + 1 points by least squares; the quadric takes up the
//   curvature, which a plane fit would count as noise, and s^2 = RSS / (k + 1 - 6) estimates the
//   variance of the offsets. Over the samples, sigma^2 = median(s^2) / m with m = (1 - 2/(9 f))^3
//   the median of chi^2_f / f for f = k - 5 degrees of freedom (Wilson-Hilferty): for Gaussian
//   offsets s^2 f / sigma^2 is chi^2_f, so median(s^2) = m sigma^2.
// - noise = nu = sqrt(5) noiseSigma: a noise bound as in the sphere-packing paper, sec. 5.3 (every
//   point moved by a uniformly distributed random vector of length <= nu): the component of such a
//   vector along the normal has variance nu^2 / 5. The paper's advice is d >= 2 nu.
//
// Robustness and cost: the neighbour search only sees the points inside a robust box (the 1 % and
// 99 % quantiles of the sampled coordinates, widened on every side by their largest extent), so a
// point far away changes neither the grid nor any neighbourhood. Its cell size and search radii come
// from the sample itself: the cell size at which a few thousand samples share their cells with
// about 3 others, then the median k-th neighbour distance r among the samples, scaled to the whole
// cloud's density (r^2 proportional to area per point); the grid over the cloud has cells of twice
// that distance. A search starts at 1.3 times it, grows by 1.5 and stops at 4 times it: a sample
// with fewer than k neighbours within the cap is isolated (counted, not used), and a search stops
// after kSamplingVisitLimit points (in a dense cluster the radius then shrinks to the k-th distance
// among those visited; for duplicates, the nearest of those visited are taken).
#include <growth/vec3.h>

#include <cstddef>
#include <vector>

namespace growth {

// The spacing. // Mean distance of each point to its nearest other point (the cloud's mean spacing), computed on
// up to `maxSamples` points taken at a fixed stride (deterministic). 0 for fewer than 2 points.
// Robust: samples whose nearest other point is farther than kSpacingOutlierFactor (5) times the
// median of the samples' distances are left out of the mean (stray points, far outliers: on a
// clean sampling none is, so the value is the plain mean), and the search grid is sized from
// robustBox(), so one far point changes neither the value nor the cost.
constexpr size_t kMeanSpacingSamples = 20000;
constexpr double kSpacingOutlierFactor = 5.0;
double meanSpacing(const std::vector<Vec3d>& points, size_t maxSamples = kMeanSpacingSamples);
// The same value, computed on `threads` threads (0 = automatic, growth/parallel.h).
double meanSpacing(const std::vector<Vec3d>& points, size_t maxSamples, int threads);

// The trimmed mean of meanSpacing() from the samples' squared nearest distances (entries below 0:
// no nearest point, ignored), summed in the given order: for callers that measure the distances on
// their own index (Robust G2S on its grid) and must log the same number as meanSpacing().
double trimmedMeanSpacing(const std::vector<double>& squaredNearest);

// Box diagonal / sqrt(n): a cheap first guess of the spacing, used to size grids.
double roughSpacing(const Box3d& box, size_t n);

// The box of the bulk of a cloud: per axis the 1 % and 99 % quantiles of the finite points among
// up to maxSamples taken at a fixed stride, widened on every side by the largest of those extents.
// A few far points do not move it (they move the bounding box). Null when no point is finite.
Box3d robustBox(const std::vector<Vec3d>& points, size_t maxSamples = kMeanSpacingSamples);


struct SamplingOptions {
  size_t maxSamples = 20000;     // points sampled at a fixed stride (deterministic)
  size_t maxNoiseSamples = 5000; // of those, the ones (again at a fixed stride) with a local fit:
                                 // enough for a stable median of s^2, and the fits are the
                                 // estimate's main cost
  int neighbours = 16;           // k: the k-th neighbour distance gives the area, p and k neighbours
                                 // the fit (tools/sampling_estimate.cpp --k compares other values)
  // The points' normals (same size as the points; null or another size: not used). With them, a
  // neighbour q of a sample p is left out when it lies on another sheet of a thin part: its normal
  // opposes p's (n_p·n_q < 0) and it lies across p's tangent plane rather than along it
  // (|(q − p)·n_p| > kOtherSheetSine |q − p|). Without this, the two sheets of a closed plate a few
  // spacings thick read as one noisy surface sampled twice as densely. A neighbour on p's own sheet
  // whose normal is flipped (inconsistent orientation) lies along the plane and is kept.
  const std::vector<Vec3d>* normals = nullptr;
};

constexpr double kOtherSheetSine = 0.5; // 30 degrees out of the tangent plane

struct SamplingEstimate {
  double spacing = 0;      // the spacing, in every log and statistic of both filters: the trimmed
                           // mean of the samples' nearest distances (trimmedMeanSpacing), the
                           // estimator of meanSpacing() on these samples, within sampling error of it
  double medianSpacing = 0; // median nearest-neighbour distance over the samples
  double areaPerPoint = 0; // pi median(r_k)^2 / (k - 1/3): surface area per point, Poisson-calibrated
  double noiseSigma = 0;   // robust standard deviation of the offsets normal to the local surface
  double noise = 0;        // nu = sqrt(5) noiseSigma: bound of a uniform-in-ball noise (sec. 5.3)
  size_t samples = 0;      // samples that had k neighbours within the search cap (the statistics')
  size_t isolated = 0;     // samples without k neighbours within the cap, or outside the robust box
  size_t noiseSamples = 0; // samples whose local fit was not degenerate (the noise statistics')
  std::vector<float> sheetGaps; // with SamplingOptions::normals: of the samples that saw another
                                // sheet of a thin part (at least 3 of its points) among the points
                                // searched around them, the distance from their tangent plane to
                                // its third nearest point (about the part's thickness there), in
                                // sample order
};

constexpr size_t kSamplingVisitLimit = 1024;

// Estimates on up to options.maxSamples points taken at a fixed stride; non-finite points are
// ignored. All zero for fewer than 2 usable points or when (almost) all points coincide; the noise
// is zero when fewer than 7 points are available. Runs on `threads` threads (0 = automatic,
// growth/parallel.h); the result is the same for any number.
SamplingEstimate estimateSampling(const std::vector<Vec3d>& points, int threads = 0);
SamplingEstimate estimateSampling(const std::vector<Vec3d>& points, const SamplingOptions& options,
                                  int threads = 0);

} // namespace growth
