#pragma once
// Splats of the sphere-packing mesher (Lipschütz et al., sec. 3.2 and 4.3).
//
// Every input point p carries a splat S_p: the disk centred at p, orthogonal to its normal n_p,
// of radius s_p. Vertices of the mesh are placed on splats, so the splats must cover the surface.
// The radius is either the global size s, or the local size of sec. 4.3:
//   - the points near p (the paper takes those of the box containing p, sec. 4.1) are rotated
//     about p, in the plane through p, p_i and n_p, onto the tangent plane T_p (distances kept);
//   - sorted cyclically around p they form a central (fan) triangulation;
//   - a central edge p–p_i that is not locally Delaunay is flipped, and p_i is dropped from the
//     fan, until all central edges are locally Delaunay;
//   - s_p is the distance from p to the farthest vertex of p's Voronoi cell among the remaining
//     neighbours, i.e. the largest circumradius of the fan triangles.
// Where the paper is silent we choose, for the coverage guarantee: the neighbours are all points
// near p on its side of the surface (not only those of p's box: at d of one or two point spacings
// a box holds too few of them to close a fan); a fan with an angular gap of at least π (a boundary
// point, or a point with too few neighbours) has an unbounded Voronoi cell and keeps the global s;
// and local sizes never exceed s (sec. 4.3 introduces them as "individual, smaller splat sizes").
#include <growth/vec3.h>

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace growth {

class Progress;

// An orthonormal tangent frame (e1, e2) of a unit normal n, a fixed function of n (so the same
// normal always gives the same frame: angles measured in it are reproducible).
inline void tangentFrame(const Vec3d& n, Vec3d& e1, Vec3d& e2) {
  // Start from the coordinate axis least aligned with n.
  const double ax = std::abs(n[0]), ay = std::abs(n[1]), az = std::abs(n[2]);
  const Vec3d axis = (ax <= ay && ax <= az) ? Vec3d(1, 0, 0)
                            : (ay <= az)           ? Vec3d(0, 1, 0)
                                                   : Vec3d(0, 0, 1);
  e1 = axis - n * (axis * n);
  e1 /= e1.Norm();
  e2 = n ^ e1;
}

// Squared distance from x to the disk of centre c, unit normal n and radius r.
inline double squaredDistanceToDisk(const Vec3d& x, const Vec3d& c, const Vec3d& n, double r) {
  const Vec3d v = x - c;
  const double h = v * n;
  const double radial2 = v.SquaredNorm() - h * h;
  if (radial2 <= r * r) return h * h;
  const double out = std::sqrt(std::max(0.0, radial2)) - r;
  return h * h + out * out;
}

// Closest point of that disk to x.
inline Vec3d projectOntoDisk(const Vec3d& x, const Vec3d& c, const Vec3d& n, double r) {
  const Vec3d v = x - c;
  Vec3d t = v - n * (v * n);
  const double len = t.Norm();
  if (len > r) t *= r / len;
  return c + t;
}

// Sec. 4.3 for one point: the largest circumradius of the Delaunay fan of p among `neighbours`
// (p itself must not be among them), rotated onto the tangent plane of the unit normal n.
// Returns a negative value when p's Voronoi cell is unbounded (no closed fan).
// `keptOut` (optional) receives the indices (into neighbours) of the points left in the fan, in
// counter-clockwise order around n.
double localSplatRadius(const Vec3d& p, const Vec3d& n, const std::vector<Vec3d>& neighbours,
                        std::vector<int>* keptOut = nullptr);

struct SplatSizeStats {
  size_t unbounded = 0;   // points without a closed Delaunay fan: global s kept
  size_t clamped = 0;     // points whose Voronoi radius exceeded s: s kept
  double meanRadius = 0;  // mean of the final radii
};

// Splat radius of every point: the global s (`capRadius`), or (local) the sec. 4.3 radius among
// the point's neighbours, at most s. The neighbours are the points within a reach of p (found
// through a PointGrid over the points, independent of the box grid and so of d) whose normals are
// not opposed to n_p. The reach starts at `firstReach` (about twice the typical Voronoi radius:
// a few point spacings) and grows to 2r when the radius r found needs it (all Delaunay neighbours
// of p lie within 2r), or to 2s for an open fan; beyond 2s the radius would be clamped anyway. So
// the radius is the exact Voronoi radius of p's neighbourhood, whatever d is.
// A point whose fan stays open (a boundary point, or too few neighbours) keeps s: where the
// paper is silent, we choose coverage. Runs on `threads` threads (0 = automatic, parallel.h); the
// radii are the same for any number. Neighbours are handed to localSplatRadius by increasing
// index, or by rankIndex[index] when given (for points renumbered from an original order: the
// same order, so the same radii, as there).
std::vector<float> computeSplatRadii(const std::vector<Vec3d>& points, const std::vector<Vec3d>& normals,
                                     double capRadius, double firstReach, bool local,
                                     SplatSizeStats* stats = nullptr, Progress* progress = nullptr,
                                     int threads = 0, const std::vector<std::uint32_t>* rankIndex = nullptr);

} // namespace growth
