#pragma once
// Reading a MeshLab layer as a point cloud, with the input checks both filters share.
//
// The engine computes in double (MeshLab stores float): the live vertices are copied into double
// arrays once. Bad input is refused with a growth::Error whose message says what is wrong and what
// to do in MeshLab; nothing in the layer is changed.
#include <vcg/space/box3.h>
#include <vcg/space/point3.h>

#include <string>
#include <vector>

class CMeshO;

namespace growth {

struct InputCloud {
  std::vector<vcg::Point3d> points;
  std::vector<vcg::Point3d> normals;   // unit length (zero where unusable, with readNormals); empty
                                       // when normals were not asked for
  std::vector<int> vertexIndex;        // index of each point in the layer's vertex vector
  vcg::Box3d box;
  size_t duplicatesDropped = 0;        // exact repeats of an earlier point (first one kept)
  size_t layerFaces = 0;
};

struct CloudCheck {
  bool needNormals = false;            // refuse points without a usable normal
  bool readNormals = false;            // read the normals without needing them (zero where a
                                       // vertex has no usable one); needNormals reads them too
  bool allowFaces = false;             // refuse a layer that is already a mesh
  size_t minPoints = 3;
};

// Coordinates beyond ±kMaxAbsCoordinate are refused: far beyond any scan (a kilometre in
// nanometres is 1e12), and past it the engines' squared lengths, products of squared lengths and
// float sums of lengths would overflow (a cloud 1e38 across gave a NaN search centre in G2S).
constexpr double kMaxAbsCoordinate = 1e15;

// Copies the live vertices of `mesh`; throws growth::Error (user-facing message) on: an empty
// layer, fewer than check.minPoints distinct points, NaN, infinite or huge coordinates, all points
// identical or on one line, faces when !allowFaces, missing/zero/NaN normals when needNormals.
InputCloud readCloud(const CMeshO& mesh, const CloudCheck& check);

// Mean distance of each point to its nearest other point (the cloud's mean spacing), computed on
// up to `maxSamples` points taken at a fixed stride (deterministic). 0 for fewer than 2 points.
// Robust: samples whose nearest other point is farther than kSpacingOutlierFactor (5) times the
// median of the samples' distances are left out of the mean (stray points, far outliers: on a
// clean sampling none is, so the value is the plain mean), and the search grid is sized from
// robustBox(), so one far point changes neither the value nor the cost.
constexpr size_t kMeanSpacingSamples = 20000;
constexpr double kSpacingOutlierFactor = 5.0;
double meanSpacing(const std::vector<vcg::Point3d>& points, size_t maxSamples = kMeanSpacingSamples);
// The same value, computed on `threads` threads (0 = automatic, growth/parallel.h).
double meanSpacing(const std::vector<vcg::Point3d>& points, size_t maxSamples, int threads);

// The trimmed mean of meanSpacing() from the samples' squared nearest distances (entries below 0:
// no nearest point, ignored), summed in the given order: for callers that measure the distances on
// their own index (Robust G2S on its grid) and must log the same number as meanSpacing().
double trimmedMeanSpacing(const std::vector<double>& squaredNearest);

// Box diagonal / sqrt(n): a cheap first guess of the spacing, used to size grids.
double roughSpacing(const vcg::Box3d& box, size_t n);

// The box of the bulk of a cloud: per axis the 1 % and 99 % quantiles of the finite points among
// up to maxSamples taken at a fixed stride, widened on every side by the largest of those extents.
// A few far points do not move it (they move the bounding box). Null when no point is finite.
vcg::Box3d robustBox(const std::vector<vcg::Point3d>& points, size_t maxSamples = kMeanSpacingSamples);

} // namespace growth
