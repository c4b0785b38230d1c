#pragma once
// Sharp features of a point cloud with normals, for the reconstruction's "keep features" option
// (Params::keepFeatures): the crease lines and corners the growth starts from, as the remesher
// starts from the creases of its input mesh (sec. 3.3 with more than two starting vertices; the
// paper's sec. 6: "placing starting vertices in high-curvature regions ensures that sampled
// features persist").
//
// The lengths below (d in steps 1-4) are in units of the feature scale
// d_f = max(d, kDefaultDiameterPerAreaSpacing · areaSpacing), the larger of d and the default d's
// sampling part (featureScale). With a = the area per point, the fit's ball of radius
// kFitRadiusPerD · d_f holds π·(1.5·1.8)² ≈ 23 points at least, and the band of crease points
// (within kMaxLineDistPerRadius of the fit radius from the line) about 3.4 per d_f of line; at
// d = 1.44·√a the ball holds 15 points (kMinNeighbours is 10) and the band 2.2 per d
// (kMinSupportPerD is 2): the fits fail often, the crease points thin out into gaps and lines are
// dropped. So the lines are found at the sampling's scale and only sampled at d (feature_lines.h).
//
// 1. Crease points. A point whose neighbours within kFitRadiusPerD·d have normals (compared as
//    lines, |n·m|: estimated normals need not be consistently oriented) more than half the crease
//    angle apart is tested: its neighbours are split into two sets by their normals, then by
//    their distances to two planes fitted to the sets' points (a few rounds of k-planes); the
//    normals only seed the split, since estimated normals are smoothed across a crease. The point
//    is a crease point when the planes differ by more than the crease angle, both sets are large
//    enough and lie on their own sides of the planes' intersection line, the fit is tight, and the
//    point is near that line; the crease point is the point moved onto the line, with the line's
//    direction and the mean of the two planes' normals. Crease points whose fit is much looser
//    than the median one (2.5 times its RMS distance) are dropped: a third plane near a corner,
//    or a side of a few points that took some of the other side's, moves them off the crease.
// 2. Crease lines. From the crease points in input order, a line is traced both ways in steps of
//    d/2, each step to the mean of the crease points within d of the step's end whose directions
//    agree (a gap of up to about 2 d between crease points is bridged). A tracing does not follow
//    the crease points an earlier line took: where a line stopped at a wider gap, the line traced
//    from beyond it stops at its end, and ends facing each other are joined (up to 6 d apart).
//    Lines with fewer than kMinSupportPerD crease points per d are scattered noise and dropped;
//    lines shorter than kMinLinePerD·d are noise and dropped.
// 3. Corners. Near a corner three planes meet and the two-plane test fails, so the traced lines
//    stop short of it: ends whose forward rays meet are extended to the point nearest to all
//    their lines (least squares), which is the corner; an end that meets no other is a corner of
//    its own (a crease ending, at the cloud's border or where it fades out).
// 4. Patches. The points farther than the zone width from every line are joined to their
//    neighbours; the connected sets are the patches (the sides of the crease lines), and a set
//    needs kMinPatchPoints points within kPatchReachPerZone zone widths of a line. Only those
//    points keep their patch: the points farther from every line belong to every patch
//    (kNoPatch), so that gaps in the sampling away from the creases do not split the growth, but
//    the sets are joined through them, since a band along the lines has holes that cut it. The
//    points within the zone take the patch whose points' tangent planes pass nearest to them.
#include "packer_steps.h"

#include <growth/point_grid.h>
#include <growth/vec3.h>

#include <cstdint>
#include <utility>
#include <vector>

namespace growth {
namespace spherepack {
namespace detail {

constexpr double kFitRadiusPerD = 1.5;    // neighbourhood of the two-plane fit
constexpr double kTraceStepPerD = 0.5;    // step of the line tracing
constexpr double kTraceRadiusPerD = 1.0;  // the crease points within this of a step's end are averaged
constexpr double kMinLinePerD = 2.0;      // shorter crease lines are dropped
constexpr double kMinSupportPerD = 2.0;   // and lines with fewer crease points per d of length (a
                                          // line bridged over scattered crease points is noise)
constexpr double kPatchReachPerZone = 4.0;
constexpr std::uint32_t kNoPatch = 0xffffffffu; // a point of every patch (also Growth::kNoVertex)

struct CloudFeatures {
  struct Line {
    std::vector<Vec3d> p; // the polyline; a corner at an end where one was found
    std::vector<Vec3d> n; // per vertex: the mean of the two planes' normals
    bool closed = false;  // p.front() == p.back()
    int front = -1, back = -1; // corners at the ends (indices into corners), -1 for none
    size_t support = 0;   // crease points the tracing went through
  };
  std::vector<Line> lines;
  std::vector<Vec3d> corners, cornerNormals;
  std::vector<std::uint32_t> patch; // per point (working order), kNoPatch: every patch; empty when there is no line
  size_t creasePoints = 0;          // points that passed the two-plane test
  size_t linesDropped = 0;          // traced lines shorter than kMinLinePerD·d
  size_t patches = 0;
  PointGrid grid;                   // the points, cells of kFitRadiusPerD·d
  double radius = 0;                // kFitRadiusPerD·d_f
  // The sides of a crease at a feature vertex f on a line of direction t: for each patch with
  // points within `radius` of f, the direction across the line into them (their mean offset from
  // f, without its part along t). A candidate of that patch with f as a parent must lie on that
  // side (Growth::addFeatureVertex): the splats of a patch run past the crease, and the circle of
  // two crease vertices meets them on both sides of the line.
  std::vector<std::pair<std::uint32_t, Vec3d>> sidesAt(const Vec3d& f, const Vec3d& t,
                                                       const std::vector<Vec3d>& points) const;
};

// The length unit of the detection: the larger of the sphere diameter and
// kDefaultDiameterPerAreaSpacing · areaSpacing (the sphere diameter when areaSpacing is not finite).
double featureScale(double sphereDiameter, double areaSpacing);

// `points`, `normals`: the cloud in the packer's working order; `order` gives the input order, in
// which the lines are seeded (so the result does not depend on the spatial renumbering's order).
CloudFeatures detectCloudFeatures(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                                  double sphereDiameter, double areaSpacing, double creaseAngleDeg, const Renumbering& order);

} // namespace detail
} // namespace spherepack
} // namespace growth
