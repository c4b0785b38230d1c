#pragma once
// Seeded point clouds with exact normals, for tests, the demo and the benchmark.
//
// Shapes: the unit sphere, the torus (tube radius r swept around a circle of radius R, sphere-packing
// paper sec. 5.2 uses R = 2, r = 1), an open, gently curved height-field patch and a closed genus-2
// surface (two tori joined by a smooth blend, genus2Function below). For the robustness tests of the
// meshers: the sphere sampled on a latitude–longitude grid (a UV-sphere mesh's vertices, or a
// turntable scan: hundreds of points around each pole), a hollow ball (two concentric spheres, the
// inner one's normals pointing into the hollow, out of the material) and a thin closed slab (a flat
// box sampled on all six faces). Sampling is uniform by area,
// or non-uniform with a density ratio (4:1 unless asked otherwise) along z. Perturbations follow
// the two papers' experiments: bounded noise (every point moved by a uniformly distributed vector of length
// <= nu, sphere packing sec. 5.3), Gaussian noise (Robust G2S sec. 5.2) and uniformly scattered
// outliers. Normals are always those of the exact surface at the unperturbed sample (reversed for
// a chosen fraction of the surface points, flippedNormals, as an unoriented normal estimate leaves
// some of a scan's). The scan shape is several of the others, scaled, turned and set apart (see
// scanParts below): with Gaussian noise, outliers and flipped normals, a scanner's multi-part cloud.
// The same spec gives the same cloud on every machine (own random number transforms, not the
// implementation-defined std:: distributions).
#include <growth/mesh_arrays.h>
#include <growth/vec3.h>

#include <cstdint>
#include <string>
#include <vector>

namespace growth {

enum class Shape { Sphere, Torus, Patch, Genus2, LatLongSphere, HollowBall, Slab, Scan };

struct CloudSpec {
  Shape shape = Shape::Sphere;
  size_t count = 10000;         // points on the surface (outliers come on top)
  std::uint64_t seed = 1;
  bool nonUniform = false;      // density varies along z, densityRatio:1 from the top to the bottom
  double densityRatio = 4.0;    // with nonUniform: density at the top / density at the bottom (>= 1)
  double noiseBound = 0.0;      // nu: each point moves by a uniform random vector of length <= nu
  double gaussianSigma = 0.0;   // standard deviation of isotropic Gaussian noise (absolute units)
  double outlierFraction = 0.0; // outliers added, as a fraction of count, uniform in the enlarged box
  double clusterFraction = 0.0; // a dense cluster added, as a fraction of count: points within a
                                // hundredth of the mean spacing of one surface sample
  size_t farPoints = 0;         // points added 10^4 times the shape's size away (random directions)
  double sphereRadius = 1.0;
  double torusMajor = 2.0;      // R
  double torusMinor = 1.0;      // r
  double patchHalfSize = 1.0;   // the patch spans [-h, h]^2 in x, y
  // LatLongSphere: latitudeRings rings of longitudeSegments points each, at polar angles
  // pi*i/(rings + 1), i = 1..rings, and longitudes 2*pi*j/segments, plus the two poles; count is
  // not used (the cloud has rings*segments + 2 points before outliers), nor is nonUniform.
  int latitudeRings = 300;
  int longitudeSegments = 600;
  double innerRadius = 0.8;     // HollowBall: the inner sphere's radius (the outer one's is sphereRadius)
  double slabHalfSize = 1.0;    // Slab: the box [-h, h]^2 x [-t/2, t/2], uniform by area on all faces
  double slabThickness = 0.05;  // t
  int scanParts = 4;            // Scan: the number of separate parts (1 to 64)
  double flippedNormals = 0.0;  // the fraction of the surface points whose normal is reversed (drawn
                                // per point; the surface stays orientable, most normals agree)
};

// The parts of a Scan cloud: part i is the shape kScanShapes[i % 4] (torus R = 2, r = 1; genus 2;
// sphere of radius 1.5; the open patch with half-size 2), of its own size, scaled by `scale`,
// turned by `rotation` (rows of an orthonormal matrix, fixed per part index, not by the seed) and
// moved to `offset`: a point p of the part's shape is at rotation * (scale * p) + offset. The parts
// sit on a square grid in the z = 0 plane, each in a ball of `radius` about its offset, and any
// two balls are at least kScanGap apart, so the parts are separate (for noise well below 1).
// Surface points are drawn from the parts by area (the same density on all of them, as a scanner's
// fixed resolution); `area` is the part's surface area.
constexpr double kScanGap = 1.0;
struct ScanPart {
  CloudSpec spec;     // the part's shape at its own size (shape, patchHalfSize, sphereRadius)
  double scale = 1;
  Vec3d rotation[3];
  Vec3d offset;
  double radius = 0;
  double area = 0;
};
std::vector<ScanPart> scanParts(const CloudSpec& spec);
// The part of a scan whose ball is nearest to a point (the one it lies in, if any), and the
// point's distance to that part's surface (distanceToShape of the part's shape, scaled).
size_t nearestScanPart(const CloudSpec& spec, const std::vector<ScanPart>& parts, const Vec3d& p,
                       double* distance = nullptr);

struct Cloud {
  std::vector<Vec3d> points;
  std::vector<Vec3d> normals;   // unit length
};

Cloud generateCloud(const CloudSpec& spec);

// Distance of p to the exact (noise-free) surface of the spec's shape; for the patch, the vertical
// distance to the height field (a bound of the true distance, tight for its gentle slopes); for
// genus 2, the distance to the foot point found by Newton steps from p (the closest point for
// points nearer to the surface than its smallest radius of curvature, about 0.3); for a scan, the
// distance to the part whose ball is nearest (nearestScanPart).
double distanceToShape(const CloudSpec& spec, const Vec3d& p);

// Area of the spec's exact surface: closed forms for the sphere and the torus, a quadrature for the
// patch, for genus 2 the integral of the area scale of the map from the triangulation its samples
// are drawn from onto the surface (52.4955; a finer triangulation and rule change it by < 1e-6);
// for a scan, the sum of its parts'.
double shapeArea(const CloudSpec& spec);

// The genus-2 surface is the zero set of F = smin(T1, T2), negative inside: T_i = (rho_i - R)^2 +
// z^2 - r^2 are two tori with axes parallel to z through (-c, 0, 0) and (c, 0, 0) (rho_i the
// distance to the axis), R = kGenus2Major, r = kGenus2Minor, c = kGenus2Offset; the tubes overlap
// around the origin, the holes stay open. smin(a, b) = min(a, b) - k h^3 / 6 with h = max(k -
// |a - b|, 0) / k, k = kGenus2Blend, is the cubic smooth minimum: F is C2, equal to one torus's
// function wherever |T1 - T2| >= k (all of x < -c and x > c lies on the plain tori), and fills the
// crease where the tubes meet. Extent about 6.6 x 3.6 x 1.2 (the torus's is 6 x 6 x 2).
// Samples are uniform by area: a point uniform on a marching-tetrahedra triangulation of F (grid
// step 0.08), moved onto F = 0 by Newton steps along the gradient, kept with a probability
// proportional to the area scale of that map (finite differences), so the triangulation's own
// flaws do not show. Normals are grad F / |grad F| (outward).
constexpr double kGenus2Major = 1.2, kGenus2Minor = 0.6, kGenus2Offset = 1.5, kGenus2Blend = 0.6;
// F at p; its gradient in *gradient when not null.
double genus2Function(const Vec3d& p, Vec3d* gradient = nullptr);

// Parses "sphere", "torus", "patch", "genus2", "latlong", "hollowball", "slab", "scan"; throws growth::Error
// otherwise.
Shape parseShape(const std::string& name);
const char* shapeName(Shape s);

// Binary little-endian PLY with float x y z nx ny nz, which MeshLab reads; written in blocks (no
// copy of the whole cloud).
void writePly(const std::string& path, const Cloud& cloud);

// The cloud as the engines' input (the points and normals of a layer stored in float).
CloudArrays toArrays(const Cloud& cloud);

// A small seeded generator with portable transforms (splitmix64-seeded xoshiro256**).
class Random {
public:
  explicit Random(std::uint64_t seed);
  std::uint64_t next();
  double uniform();                       // [0, 1)
  double uniform(double a, double b) { return a + (b - a) * uniform(); }
  double gaussian();                      // standard normal, Box-Muller
  Vec3d unitVector();              // uniform on the unit sphere
  Vec3d inBall(double radius);     // uniform in the ball
private:
  std::uint64_t s_[4];
};

} // namespace growth
