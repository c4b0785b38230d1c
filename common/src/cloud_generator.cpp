#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <memory>

namespace growth {

namespace {
constexpr double kPi = 3.14159265358979323846;

std::uint64_t splitmix(std::uint64_t& x) {
  std::uint64_t z = (x += 0x9E3779B97F4A7C15ull);
  z = (z ^ (z >> 30)) * 0xBF58476D1CE4E5B9ull;
  z = (z ^ (z >> 27)) * 0x94D049BB133111EBull;
  return z ^ (z >> 31);
}
std::uint64_t rotl(std::uint64_t x, int k) { return (x << k) | (x >> (64 - k)); }

// Height field of the open patch and its gradient.
double patchHeight(double x, double y) { return 0.15 * std::sin(1.5 * x) * std::cos(1.2 * y); }
void patchGradient(double x, double y, double& hx, double& hy) {
  hx = 0.15 * 1.5 * std::cos(1.5 * x) * std::cos(1.2 * y);
  hy = -0.15 * 1.2 * std::sin(1.5 * x) * std::sin(1.2 * y);
}

// Exact surface sample: position, normal, and the z range used for the non-uniform density.
struct Sample {
  Vec3d p, n;
};

// ---- Genus 2 ----------------------------------------------------------------------------------

// One torus T = (rho - R)^2 + z^2 - r^2 around the axis through (cx, 0, 0), and its gradient.
double torusFunction(const Vec3d& p, double cx, Vec3d& g) {
  const double x = p[0] - cx, rho = std::sqrt(x * x + p[1] * p[1]);
  const double radial = rho - kGenus2Major;
  // On the axis (inside the hole, far from the surface) the radial direction is undefined.
  const double k = rho > 0 ? 2 * radial / rho : 0.0;
  g = Vec3d(k * x, k * p[1], 2 * p[2]);
  return radial * radial + p[2] * p[2] - kGenus2Minor * kGenus2Minor;
}

// p moved onto F = 0 by Newton steps along the gradient, until a step is below 1e-15 of the size.
Vec3d genus2Project(Vec3d q) {
  for (int it = 0; it < 50; ++it) {
    Vec3d g;
    const double f = genus2Function(q, &g);
    const double g2 = g.SquaredNorm();
    if (!(g2 > 0)) break;
    const Vec3d step = g * (f / g2);
    q -= step;
    if (step.SquaredNorm() <= 1e-30 * (1.0 + q.SquaredNorm())) break;
  }
  return q;
}

// The triangulation samples are drawn from: marching tetrahedra (6 tetrahedra per grid cube
// around its main diagonal, the same split in every cube, so neighbours share their faces'
// edge points bit for bit) on a grid of step 0.08 over the shape's box. Finer grids only cost
// time: the rejection below removes the triangulation's error (a grid of 0.04 gives the same area
// to 4e-7).
struct Genus2Mesh {
  std::vector<Vec3d> corner;   // 3 per triangle
  std::vector<double> cumulativeArea; // flat areas, summed in triangle order
  double surfaceArea = 0;             // of the surface (the triangles' areas times the map's scale)
  double zmin = 0, zmax = 0;          // of the surface
};

// The area scale of the map triangle -> surface at barycentric (u, v) of triangle abc (surface
// area over flat area): forward differences of the projection along an orthonormal frame of the
// triangle's plane, steps of 1e-7. 0 for a degenerate triangle (no plane).
double genus2AreaScale(const Vec3d& a, const Vec3d& b, const Vec3d& c, double u, double v,
                       Vec3d& onSurface) {
  const Vec3d e1 = b - a, e2 = c - a, q = a + e1 * u + e2 * v;
  onSurface = genus2Project(q);
  Vec3d normal = e1 ^ e2;
  const double e1n = e1.Norm(), nn = normal.Norm();
  if (!(nn > 0) || !(e1n > 0)) return 0.0;
  const Vec3d s = e1 / e1n, t = (normal / nn) ^ s;
  const double step = 1e-7;
  const Vec3d ps = genus2Project(q + s * step), pt = genus2Project(q + t * step);
  return ((ps - onSurface) ^ (pt - onSurface)).Norm() / (step * step);
}

Genus2Mesh buildGenus2Mesh() {
  const double h = 0.08;
  const Vec3d lo(-3.6, -2.0, -1.0);
  const int nx = int(7.2 / h) + 2, ny = int(4.0 / h) + 2, nz = int(2.0 / h) + 2;
  auto node = [&](int i, int j, int k) { return Vec3d(lo[0] + i * h, lo[1] + j * h, lo[2] + k * h); };
  std::vector<double> f(size_t(nx) * ny * nz);
  auto at = [&](int i, int j, int k) -> double& { return f[(size_t(i) * ny + j) * nz + k]; };
  for (int i = 0; i < nx; ++i)
    for (int j = 0; j < ny; ++j)
      for (int k = 0; k < nz; ++k) at(i, j, k) = genus2Function(node(i, j, k));

  Genus2Mesh m;
  // Where the segment from an inside corner to an outside one crosses F = 0 (linearly).
  auto cross = [](const Vec3d& pin, double fin, const Vec3d& pout, double fout) {
    return pin + (pout - pin) * (fin / (fin - fout));
  };
  auto add = [&](const Vec3d& a, const Vec3d& b, const Vec3d& c) {
    m.corner.push_back(a);
    m.corner.push_back(b);
    m.corner.push_back(c);
  };
  static const int perm[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  for (int i = 0; i + 1 < nx; ++i)
    for (int j = 0; j + 1 < ny; ++j)
      for (int k = 0; k + 1 < nz; ++k) {
        double cf[8];
        bool anyIn = false, anyOut = false;
        for (int b = 0; b < 8; ++b) {
          cf[b] = at(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
          (cf[b] < 0 ? anyIn : anyOut) = true;
        }
        if (!anyIn || !anyOut) continue;
        for (const auto& pa : perm) {
          // Tetrahedron 0 -> +e_a1 -> +e_a2 -> 7 (corner bits: x = 1, y = 2, z = 4).
          int v[4] = {0, 0, 0, 7};
          v[1] = 1 << pa[0];
          v[2] = v[1] | (1 << pa[1]);
          int in[4], out[4], nin = 0, nout = 0;
          for (int t = 0; t < 4; ++t) (cf[v[t]] < 0 ? in[nin++] : out[nout++]) = v[t];
          if (nin == 0 || nout == 0) continue;
          auto pos = [&](int b) { return node(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1)); };
          auto e = [&](int a, int b) { return cross(pos(a), cf[a], pos(b), cf[b]); };
          if (nin == 1) add(e(in[0], out[0]), e(in[0], out[1]), e(in[0], out[2]));
          else if (nin == 3) add(e(in[0], out[0]), e(in[1], out[0]), e(in[2], out[0]));
          else {
            const Vec3d a = e(in[0], out[0]), b = e(in[0], out[1]), c = e(in[1], out[1]), d = e(in[1], out[0]);
            add(a, b, c);
            add(a, c, d);
          }
        }
      }
  const size_t triangles = m.corner.size() / 3;
  m.cumulativeArea.resize(triangles);
  double sum = 0;
  m.zmin = 1e300;
  m.zmax = -1e300;
  for (size_t t = 0; t < triangles; ++t) {
    const Vec3d &a = m.corner[3 * t], &b = m.corner[3 * t + 1], &c = m.corner[3 * t + 2];
    // Slivers with no numerically usable plane are never picked.
    const double flat = 0.5 * ((b - a) ^ (c - a)).Norm();
    const double area = flat > 1e-12 * h * h ? flat : 0.0;
    sum += area;
    m.cumulativeArea[t] = sum;
    // The map's area scale integrated by the edge-midpoint rule (exact to degree 2; a 4x finer
    // rule changes the total by 1e-8 of it, the centroid rule is 1.4e-4 off).
    double scale = 0;
    const double mid[3][2] = {{0.5, 0}, {0.5, 0.5}, {0, 0.5}};
    for (int e = 0; e < 3 && area > 0; ++e) {
      Vec3d onSurface;
      scale += genus2AreaScale(a, b, c, mid[e][0], mid[e][1], onSurface);
      m.zmin = std::min(m.zmin, onSurface[2]);
      m.zmax = std::max(m.zmax, onSurface[2]);
    }
    m.surfaceArea += area * scale / 3;
  }
  return m;
}

// Built on first use, then shared; thread-safe (C++11 static initialisation).
const Genus2Mesh& genus2Mesh() {
  static const Genus2Mesh mesh = buildGenus2Mesh();
  return mesh;
}

// The map's area scale stays below this bound (measured on 3 random points of every triangle:
// 0.9545 to 1.0122); above it the rejection would under-sample.
constexpr double kGenus2MaxAreaScale = 1.05;

Sample sampleGenus2(Random& rng) {
  const Genus2Mesh& m = genus2Mesh();
  for (;;) {
    const double pick = rng.uniform() * m.cumulativeArea.back();
    const size_t t = std::min<size_t>(
        size_t(std::upper_bound(m.cumulativeArea.begin(), m.cumulativeArea.end(), pick) - m.cumulativeArea.begin()),
        m.cumulativeArea.size() - 1);
    double u = rng.uniform(), v = rng.uniform();
    if (u + v > 1) u = 1 - u, v = 1 - v;
    Vec3d p;
    const double scale = genus2AreaScale(m.corner[3 * t], m.corner[3 * t + 1], m.corner[3 * t + 2], u, v, p);
    if (rng.uniform() * kGenus2MaxAreaScale > scale) continue;
    Vec3d g;
    genus2Function(p, &g);
    return {p, g / g.Norm()};
  }
}

// The parts of a scan at their places; with their areas only when asked (the patch's is a
// quadrature of 160,000 points), which sampling needs and distances do not.
std::vector<ScanPart> scanLayout(const CloudSpec& s, bool withAreas);

Sample sampleSurface(const CloudSpec& s, Random& rng, const std::vector<ScanPart>* parts = nullptr);

// A sample of a scan: a part picked by area, a sample of its shape, scaled, turned and moved there.
Sample sampleScan(Random& rng, const std::vector<ScanPart>& parts) {
  double total = 0;
  for (const ScanPart& part : parts) total += part.area;
  double pick = rng.uniform() * total;
  size_t i = 0;
  while (i + 1 < parts.size() && pick >= parts[i].area) pick -= parts[i++].area;
  const ScanPart& part = parts[i];
  const Sample local = sampleSurface(part.spec, rng);
  Sample out;
  for (int a = 0; a < 3; ++a) {
    out.p[a] = part.rotation[a] * local.p * part.scale + part.offset[a];
    out.n[a] = part.rotation[a] * local.n;
  }
  return out;
}

Sample sampleSurface(const CloudSpec& s, Random& rng, const std::vector<ScanPart>* parts) {
  switch (s.shape) {
  case Shape::Scan:
    if (parts == nullptr || parts->empty()) throw Error("a scan's sample needs its parts");
    return sampleScan(rng, *parts);
  case Shape::Sphere: {
    const Vec3d n = rng.unitVector();
    return {n * s.sphereRadius, n};
  }
  case Shape::Torus: {
    // Uniform by area: the area element is proportional to R + r cos v (rejection).
    for (;;) {
      const double u = rng.uniform(0, 2 * kPi), v = rng.uniform(0, 2 * kPi);
      const double w = (s.torusMajor + s.torusMinor * std::cos(v)) / (s.torusMajor + s.torusMinor);
      if (rng.uniform() > w) continue;
      const Vec3d n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      const Vec3d c(s.torusMajor * std::cos(u), s.torusMajor * std::sin(u), 0);
      return {c + n * s.torusMinor, n};
    }
  }
  case Shape::Patch: {
    const double h = s.patchHalfSize;
    const double maxArea = std::sqrt(1.0 + 2 * 0.225 * 0.225); // bound of sqrt(1 + |grad|^2)
    for (;;) {
      const double x = rng.uniform(-h, h), y = rng.uniform(-h, h);
      double hx, hy;
      patchGradient(x, y, hx, hy);
      const double area = std::sqrt(1.0 + hx * hx + hy * hy);
      if (rng.uniform() * maxArea > area) continue;
      Vec3d n(-hx, -hy, 1.0);
      n /= n.Norm();
      return {Vec3d(x, y, patchHeight(x, y)), n};
    }
  }
  case Shape::Genus2: return sampleGenus2(rng);
  case Shape::LatLongSphere: {
    // The grid is laid out in generateCloud; this is for the dense cluster's centre.
    const Vec3d n = rng.unitVector();
    return {n * s.sphereRadius, n};
  }
  case Shape::HollowBall: {
    // Uniform by area over both spheres: the inner one with probability r^2 / (R^2 + r^2).
    const double R = s.sphereRadius, r = s.innerRadius;
    const bool inner = rng.uniform() * (R * R + r * r) < r * r;
    const Vec3d n = rng.unitVector();
    return inner ? Sample{n * r, -n} : Sample{n * R, n};
  }
  case Shape::Slab: {
    // Uniform by area: a face with probability proportional to its area, then a uniform point on it.
    const double h = s.slabHalfSize, t = s.slabThickness;
    const double big = 4 * h * h, small = 2 * h * t; // each of the 2 large and 4 side faces
    const double pick = rng.uniform() * (2 * big + 4 * small);
    const double u = rng.uniform(-1, 1), v = rng.uniform(-1, 1);
    if (pick < 2 * big) {
      const double sign = pick < big ? 1.0 : -1.0;
      return {Vec3d(u * h, v * h, sign * 0.5 * t), Vec3d(0, 0, sign)};
    }
    const int side = std::min(3, int((pick - 2 * big) / small));
    const double z = v * 0.5 * t;
    switch (side) {
    case 0: return {Vec3d(h, u * h, z), Vec3d(1, 0, 0)};
    case 1: return {Vec3d(-h, u * h, z), Vec3d(-1, 0, 0)};
    case 2: return {Vec3d(u * h, h, z), Vec3d(0, 1, 0)};
    default: return {Vec3d(u * h, -h, z), Vec3d(0, -1, 0)};
    }
  }
  }
  throw Error("unknown shape");
}

double zRange(const CloudSpec& s, double& zmin) {
  switch (s.shape) {
  case Shape::Sphere: zmin = -s.sphereRadius; return 2 * s.sphereRadius;
  case Shape::Torus: zmin = -s.torusMinor; return 2 * s.torusMinor;
  case Shape::Patch: zmin = -0.15; return 0.3;
  case Shape::Genus2: zmin = genus2Mesh().zmin; return genus2Mesh().zmax - zmin;
  case Shape::LatLongSphere:
  case Shape::HollowBall: zmin = -s.sphereRadius; return 2 * s.sphereRadius;
  case Shape::Slab: zmin = -0.5 * s.slabThickness; return s.slabThickness;
  case Shape::Scan: {
    // The parts lie in balls about points of the plane z = 0.
    double r = 0;
    for (const ScanPart& part : scanLayout(s, false)) r = std::max(r, part.radius);
    zmin = -r;
    return 2 * r;
  }
  }
  zmin = 0;
  return 1;
}
} // namespace

Random::Random(std::uint64_t seed) {
  std::uint64_t x = seed;
  for (auto& v : s_) v = splitmix(x);
}

std::uint64_t Random::next() {
  const std::uint64_t result = rotl(s_[1] * 5, 7) * 9;
  const std::uint64_t t = s_[1] << 17;
  s_[2] ^= s_[0];
  s_[3] ^= s_[1];
  s_[1] ^= s_[2];
  s_[0] ^= s_[3];
  s_[2] ^= t;
  s_[3] = rotl(s_[3], 45);
  return result;
}

double Random::uniform() { return double(next() >> 11) * (1.0 / 9007199254740992.0); }

double Random::gaussian() {
  double u1 = uniform();
  while (u1 <= 0.0) u1 = uniform();
  const double u2 = uniform();
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2 * kPi * u2);
}

Vec3d Random::unitVector() {
  const double z = uniform(-1, 1), a = uniform(0, 2 * kPi), r = std::sqrt(std::max(0.0, 1 - z * z));
  return Vec3d(r * std::cos(a), r * std::sin(a), z);
}

Vec3d Random::inBall(double radius) {
  // The radius is drawn before the direction (here and below, draws that were once the unsequenced
  // operands of one expression are made statements in the order GCC evaluated them, so the seeded
  // clouds are the same with every compiler, clang included).
  const double r = radius * std::cbrt(uniform());
  return unitVector() * r;
}

double shapeSize(const CloudSpec& s);

Cloud generateCloud(const CloudSpec& spec) {
  if (spec.count == 0) throw Error("a cloud needs at least one point");
  Random rng(spec.seed);
  Cloud c;
  // Outliers and the cluster are fractions of the surface's points (for the grid, its size).
  const size_t surfaceCount =
      spec.shape == Shape::LatLongSphere
          ? size_t(std::max(spec.latitudeRings, 0)) * size_t(std::max(spec.longitudeSegments, 0)) + 2
          : spec.count;
  const size_t outliers = static_cast<size_t>(std::llround(spec.outlierFraction * double(surfaceCount)));
  c.points.reserve(spec.count + outliers);
  c.normals.reserve(spec.count + outliers);
  double zmin = 0;
  const double zspan = zRange(spec, zmin);
  if (spec.nonUniform && !(spec.densityRatio >= 1.0 && std::isfinite(spec.densityRatio)))
    throw Error("the density ratio of a non-uniform cloud must be a finite number >= 1");
  // Accepted with probability 1/ratio at the bottom rising linearly to 1 at the top: for the
  // default ratio 4 exactly 0.25 + 0.75 t, as before densityRatio existed (the same clouds).
  const double bottom = 1.0 / spec.densityRatio, rise = 1.0 - bottom;
  if (!(spec.flippedNormals >= 0.0 && spec.flippedNormals <= 1.0))
    throw Error("the fraction of flipped normals must lie in [0, 1]");
  const std::vector<ScanPart> parts =
      spec.shape == Shape::Scan ? scanLayout(spec, true) : std::vector<ScanPart>();
  if (spec.shape == Shape::LatLongSphere) {
    if (spec.latitudeRings < 1 || spec.longitudeSegments < 3)
      throw Error("a latitude-longitude sphere needs at least 1 ring of at least 3 points");
    if (spec.nonUniform) throw Error("a latitude-longitude sphere is a fixed grid: it has no non-uniform density");
    const double R = spec.sphereRadius;
    auto add = [&](const Vec3d& n) {
      Vec3d p = n * R;
      if (spec.noiseBound > 0) p += rng.inBall(spec.noiseBound);
      if (spec.gaussianSigma > 0) p += Vec3d(rng.gaussian(), rng.gaussian(), rng.gaussian()) * spec.gaussianSigma;
      c.points.push_back(p);
      c.normals.push_back(n);
    };
    add(Vec3d(0, 0, 1));
    for (int i = 1; i <= spec.latitudeRings; ++i) {
      const double theta = kPi * double(i) / double(spec.latitudeRings + 1);
      for (int j = 0; j < spec.longitudeSegments; ++j) {
        const double phi = 2 * kPi * double(j) / double(spec.longitudeSegments);
        add(Vec3d(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta)));
      }
    }
    add(Vec3d(0, 0, -1));
  }
  while (c.points.size() < surfaceCount) {
    Sample s = sampleSurface(spec, rng, &parts);
    if (spec.nonUniform) {
      const double t = (s.p[2] - zmin) / zspan;
      if (rng.uniform() > bottom + rise * t) continue;
    }
    if (spec.noiseBound > 0) s.p += rng.inBall(spec.noiseBound);
    if (spec.gaussianSigma > 0) {
      const double gz = rng.gaussian(), gy = rng.gaussian(), gx = rng.gaussian();
      s.p += Vec3d(gx, gy, gz) * spec.gaussianSigma;
    }
    // Drawn only when asked for, so the clouds without flips are the same as before.
    if (spec.flippedNormals > 0 && rng.uniform() < spec.flippedNormals) s.n = s.n * -1.0;
    c.points.push_back(s.p);
    c.normals.push_back(s.n);
  }
  if (outliers > 0) {
    Vec3d lo = c.points[0], hi = c.points[0];
    for (const auto& p : c.points)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    const Vec3d margin = (hi - lo) * 0.05;
    lo -= margin;
    hi += margin;
    for (size_t i = 0; i < outliers; ++i) {
      const double z = rng.uniform(lo[2], hi[2]), y = rng.uniform(lo[1], hi[1]), x = rng.uniform(lo[0], hi[0]);
      c.points.emplace_back(x, y, z);
      c.normals.push_back(rng.unitVector());
    }
  }
  // Drawn after everything above, so the clouds without them are the same as before.
  if (spec.clusterFraction > 0) {
    // A dense cluster on the surface: that fraction of `count` points, moved by at most a
    // hundredth of the surface's mean spacing about a surface sample (the normal of that sample).
    const size_t k = static_cast<size_t>(std::llround(spec.clusterFraction * double(surfaceCount)));
    const Sample centre = sampleSurface(spec, rng, &parts);
    const double spread = 0.01 * std::sqrt(shapeArea(spec) / double(surfaceCount));
    for (size_t i = 0; i < k; ++i) {
      c.points.push_back(centre.p + rng.inBall(spread));
      c.normals.push_back(centre.n);
    }
  }
  for (size_t i = 0; i < spec.farPoints; ++i) {
    // 10^4 times the shape's size away, in a random direction.
    const Vec3d dir = rng.unitVector();
    c.points.push_back(dir * (1e4 * shapeSize(spec)));
    c.normals.push_back(dir);
  }
  return c;
}

double distanceToShape(const CloudSpec& s, const Vec3d& p) {
  switch (s.shape) {
  case Shape::Sphere:
  case Shape::LatLongSphere: return std::abs(p.Norm() - s.sphereRadius);
  case Shape::HollowBall: return std::min(std::abs(p.Norm() - s.sphereRadius), std::abs(p.Norm() - s.innerRadius));
  case Shape::Slab: {
    // Outside the box: the distance to it; inside: to the nearest face.
    const double half[3] = {s.slabHalfSize, s.slabHalfSize, 0.5 * s.slabThickness};
    double out2 = 0, inside = 1e300;
    for (int a = 0; a < 3; ++a) {
      const double d = std::abs(p[a]) - half[a];
      if (d > 0) out2 += d * d;
      inside = std::min(inside, -d);
    }
    return out2 > 0 ? std::sqrt(out2) : inside;
  }
  case Shape::Torus: {
    const double rho = std::hypot(p[0], p[1]);
    return std::abs(std::hypot(rho - s.torusMajor, p[2]) - s.torusMinor);
  }
  case Shape::Patch: return std::abs(p[2] - patchHeight(p[0], p[1]));
  case Shape::Genus2: {
    // Alternately onto the surface and along it to the foot of p (the tangential part of p - q
    // removed): converges to the closest point when p is near the surface.
    Vec3d q = genus2Project(p);
    for (int it = 0; it < 50; ++it) {
      Vec3d g;
      genus2Function(q, &g);
      const double gn = g.Norm();
      if (!(gn > 0)) break;
      const Vec3d n = g / gn, d = p - q;
      const Vec3d tangential = d - n * (d * n);
      q = genus2Project(q + tangential);
      if (tangential.SquaredNorm() <= 1e-30 * (1.0 + d.SquaredNorm())) break;
    }
    return (p - q).Norm();
  }
  case Shape::Scan: {
    double d = 0;
    nearestScanPart(s, scanLayout(s, false), p, &d);
    return d;
  }
  }
  return 0;
}

namespace {
// The parts' shapes and their balls' radii about the shape's origin, at scale 1.
constexpr Shape kScanShapes[4] = {Shape::Torus, Shape::Genus2, Shape::Sphere, Shape::Patch};

std::vector<ScanPart> scanLayout(const CloudSpec& s, bool withAreas) {
  if (s.scanParts < 1 || s.scanParts > 64) throw Error("a scan has 1 to 64 parts");
  std::vector<ScanPart> parts(size_t(s.scanParts));
  double largest = 0;
  for (size_t i = 0; i < parts.size(); ++i) {
    ScanPart& part = parts[i];
    part.spec.shape = kScanShapes[i % 4];
    part.spec.sphereRadius = 1.5;
    part.spec.patchHalfSize = 2.0;
    double radius = 0;
    switch (part.spec.shape) {
    case Shape::Torus: radius = part.spec.torusMajor + part.spec.torusMinor; break;
    // |p| <= c + R + r = 3.3 on both tori (the blend fills the crease at the origin only).
    case Shape::Genus2: radius = kGenus2Offset + kGenus2Major + kGenus2Minor + 0.05; break;
    case Shape::Sphere: radius = part.spec.sphereRadius; break;
    default: radius = std::sqrt(2 * part.spec.patchHalfSize * part.spec.patchHalfSize + 0.15 * 0.15); break;
    }
    // Each further round of the four shapes is smaller: 1, 0.8, 0.64, ...
    part.scale = std::pow(0.8, double(i / 4));
    part.radius = radius * part.scale;
    largest = std::max(largest, part.radius);
    // A turn about a random axis, from a generator of the part's own (not the cloud's seed).
    Random turn(0x5CA4ull + i);
    const Vec3d k = turn.unitVector();
    const double angle = turn.uniform(0, 2 * kPi), c = std::cos(angle), sn = std::sin(angle), t = 1 - c;
    part.rotation[0] = Vec3d(c + t * k[0] * k[0], t * k[0] * k[1] - sn * k[2], t * k[0] * k[2] + sn * k[1]);
    part.rotation[1] = Vec3d(t * k[0] * k[1] + sn * k[2], c + t * k[1] * k[1], t * k[1] * k[2] - sn * k[0]);
    part.rotation[2] = Vec3d(t * k[0] * k[2] - sn * k[1], t * k[1] * k[2] + sn * k[0], c + t * k[2] * k[2]);
    if (withAreas) part.area = shapeArea(part.spec) * part.scale * part.scale;
  }
  // A square grid of cells of side 2 * largest + gap, centred on the origin.
  const int columns = int(std::ceil(std::sqrt(double(parts.size()) - 0.5)));
  const int rows = int((parts.size() + size_t(columns) - 1) / size_t(columns));
  const double pitch = 2 * largest + kScanGap;
  for (size_t i = 0; i < parts.size(); ++i)
    parts[i].offset = Vec3d((double(i % size_t(columns)) - 0.5 * (columns - 1)) * pitch,
                            (double(i / size_t(columns)) - 0.5 * (rows - 1)) * pitch, 0);
  return parts;
}
} // namespace

std::vector<ScanPart> scanParts(const CloudSpec& spec) { return scanLayout(spec, true); }

size_t nearestScanPart(const CloudSpec& spec, const std::vector<ScanPart>& parts, const Vec3d& p,
                       double* distance) {
  (void)spec;
  // The part whose ball is nearest (the balls are disjoint; a shape's own distance is not used
  // to choose: the patch's is the vertical one to its height field, which runs on past its square).
  size_t best = 0;
  double bestBall = 1e300;
  for (size_t i = 0; i < parts.size(); ++i) {
    const double ball = std::max(0.0, (p - parts[i].offset).Norm() - parts[i].radius);
    if (ball < bestBall) bestBall = ball, best = i;
  }
  if (distance != nullptr) {
    const ScanPart& part = parts[best];
    const Vec3d q = p - part.offset;
    // The rotation's transpose takes q back to the part's own frame.
    Vec3d local(0, 0, 0);
    for (int a = 0; a < 3; ++a) local += part.rotation[a] * q[a];
    *distance = distanceToShape(part.spec, local / part.scale) * part.scale;
  }
  return best;
}

// The shape's size: the radius of a ball around the origin holding it (for the far points).
double shapeSize(const CloudSpec& s) {
  switch (s.shape) {
  case Shape::Sphere:
  case Shape::LatLongSphere:
  case Shape::HollowBall: return s.sphereRadius;
  case Shape::Slab: return std::sqrt(2.0) * s.slabHalfSize + s.slabThickness;
  case Shape::Torus: return s.torusMajor + s.torusMinor;
  case Shape::Patch: return 2 * s.patchHalfSize;
  case Shape::Scan: {
    double r = 0;
    for (const ScanPart& part : scanLayout(s, false)) r = std::max(r, part.offset.Norm() + part.radius);
    return r;
  }
  default: return 4.0; // genus 2: extent about 6.6 x 3.6 x 1.2
  }
}

double shapeArea(const CloudSpec& s) {
  switch (s.shape) {
  case Shape::Sphere:
  case Shape::LatLongSphere: return 4 * kPi * s.sphereRadius * s.sphereRadius;
  case Shape::HollowBall: return 4 * kPi * (s.sphereRadius * s.sphereRadius + s.innerRadius * s.innerRadius);
  case Shape::Slab: return 8 * s.slabHalfSize * s.slabHalfSize + 8 * s.slabHalfSize * s.slabThickness;
  case Shape::Torus: return 4 * kPi * kPi * s.torusMajor * s.torusMinor;
  case Shape::Patch: {
    // Composite Simpson rule in x and y on the area element sqrt(1 + |grad h|^2).
    const int n = 400;
    const double h = s.patchHalfSize, step = 2 * h / n;
    double sum = 0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j) {
        const double wi = (i == 0 || i == n) ? 1 : (i % 2 ? 4 : 2), wj = (j == 0 || j == n) ? 1 : (j % 2 ? 4 : 2);
        double hx, hy;
        patchGradient(-h + i * step, -h + j * step, hx, hy);
        sum += wi * wj * std::sqrt(1.0 + hx * hx + hy * hy);
      }
    return sum * step * step / 9.0;
  }
  case Shape::Genus2: return genus2Mesh().surfaceArea;
  case Shape::Scan: {
    double a = 0;
    for (const ScanPart& part : scanLayout(s, true)) a += part.area;
    return a;
  }
  }
  return 0;
}

double genus2Function(const Vec3d& p, Vec3d* gradient) {
  Vec3d g1, g2;
  const double t1 = torusFunction(p, -kGenus2Offset, g1), t2 = torusFunction(p, kGenus2Offset, g2);
  // smin = min - k h^3 / 6; d smin / d min = 1 - h^2 / 2, d smin / d other = h^2 / 2.
  const double lo = std::min(t1, t2);
  const double h = std::max(kGenus2Blend - std::abs(t1 - t2), 0.0) / kGenus2Blend;
  if (gradient != nullptr) {
    const double w = 0.5 * h * h;
    *gradient = t1 <= t2 ? g1 * (1 - w) + g2 * w : g2 * (1 - w) + g1 * w;
  }
  return lo - kGenus2Blend * h * h * h / 6.0;
}

Shape parseShape(const std::string& name) {
  if (name == "sphere") return Shape::Sphere;
  if (name == "torus") return Shape::Torus;
  if (name == "patch") return Shape::Patch;
  if (name == "genus2") return Shape::Genus2;
  if (name == "latlong") return Shape::LatLongSphere;
  if (name == "hollowball") return Shape::HollowBall;
  if (name == "slab") return Shape::Slab;
  if (name == "scan") return Shape::Scan;
  throw Error("unknown shape '" + name + "' (sphere, torus, patch, genus2, latlong, hollowball, slab or scan)");
}

const char* shapeName(Shape s) {
  switch (s) {
  case Shape::Sphere: return "sphere";
  case Shape::Torus: return "torus";
  case Shape::Patch: return "patch";
  case Shape::Genus2: return "genus2";
  case Shape::LatLongSphere: return "latlong";
  case Shape::HollowBall: return "hollowball";
  case Shape::Slab: return "slab";
  case Shape::Scan: return "scan";
  }
  return "?";
}

void writePly(const std::string& path, const Cloud& cloud) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw Error("cannot write " + path);
  std::fprintf(f.get(),
               "ply\nformat binary_little_endian 1.0\ncomment generated by growth::generateCloud\n"
               "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
               "property float nx\nproperty float ny\nproperty float nz\nend_header\n",
               cloud.points.size());
  // In blocks of 65,536 points: a 10M-point cloud is not copied whole once more.
  static_assert(sizeof(float) == 4, "PLY float is 4 bytes");
  const size_t block = 65536;
  std::vector<float> buf;
  buf.reserve(std::min(block, cloud.points.size()) * 6);
  for (size_t start = 0; start < cloud.points.size(); start += block) {
    buf.clear();
    const size_t end = std::min(cloud.points.size(), start + block);
    for (size_t i = start; i < end; ++i) {
      for (int a = 0; a < 3; ++a) buf.push_back(static_cast<float>(cloud.points[i][a]));
      for (int a = 0; a < 3; ++a) buf.push_back(static_cast<float>(cloud.normals[i][a]));
    }
    // x86-64 is little-endian, which is what the header declares.
    if (std::fwrite(buf.data(), sizeof(float), buf.size(), f.get()) != buf.size())
      throw Error("cannot write " + path);
  }
}

CloudArrays toArrays(const Cloud& cloud) {
  // Rounded to float, as a layer stores them.
  auto asFloat = [](const Vec3d& p) { return Vec3d(double(float(p[0])), double(float(p[1])), double(float(p[2]))); };
  CloudArrays a;
  a.points.reserve(cloud.points.size());
  a.normals.reserve(cloud.normals.size());
  for (const Vec3d& p : cloud.points) a.points.push_back(asFloat(p));
  for (const Vec3d& n : cloud.normals) a.normals.push_back(asFloat(n));
  return a;
}

} // namespace growth
