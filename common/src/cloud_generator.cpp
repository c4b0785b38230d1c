#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/algorithms/update/bounding.h>

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
  vcg::Point3d p, n;
};

Sample sampleSurface(const CloudSpec& s, Random& rng) {
  switch (s.shape) {
  case Shape::Sphere: {
    const vcg::Point3d n = rng.unitVector();
    return {n * s.sphereRadius, n};
  }
  case Shape::Torus: {
    // Uniform by area: the area element is proportional to R + r cos v (rejection).
    for (;;) {
      const double u = rng.uniform(0, 2 * kPi), v = rng.uniform(0, 2 * kPi);
      const double w = (s.torusMajor + s.torusMinor * std::cos(v)) / (s.torusMajor + s.torusMinor);
      if (rng.uniform() > w) continue;
      const vcg::Point3d n(std::cos(v) * std::cos(u), std::cos(v) * std::sin(u), std::sin(v));
      const vcg::Point3d c(s.torusMajor * std::cos(u), s.torusMajor * std::sin(u), 0);
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
      vcg::Point3d n(-hx, -hy, 1.0);
      n /= n.Norm();
      return {vcg::Point3d(x, y, patchHeight(x, y)), n};
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

vcg::Point3d Random::unitVector() {
  const double z = uniform(-1, 1), a = uniform(0, 2 * kPi), r = std::sqrt(std::max(0.0, 1 - z * z));
  return vcg::Point3d(r * std::cos(a), r * std::sin(a), z);
}

vcg::Point3d Random::inBall(double radius) { return unitVector() * (radius * std::cbrt(uniform())); }

Cloud generateCloud(const CloudSpec& spec) {
  if (spec.count == 0) throw Error("a cloud needs at least one point");
  Random rng(spec.seed);
  Cloud c;
  const size_t outliers = static_cast<size_t>(std::llround(spec.outlierFraction * double(spec.count)));
  c.points.reserve(spec.count + outliers);
  c.normals.reserve(spec.count + outliers);
  double zmin = 0;
  const double zspan = zRange(spec, zmin);
  if (spec.nonUniform && !(spec.densityRatio >= 1.0 && std::isfinite(spec.densityRatio)))
    throw Error("the density ratio of a non-uniform cloud must be a finite number >= 1");
  // Accepted with probability 1/ratio at the bottom rising linearly to 1 at the top: for the
  // default ratio 4 exactly 0.25 + 0.75 t, as before densityRatio existed (the same clouds).
  const double bottom = 1.0 / spec.densityRatio, rise = 1.0 - bottom;
  while (c.points.size() < spec.count) {
    Sample s = sampleSurface(spec, rng);
    if (spec.nonUniform) {
      const double t = (s.p[2] - zmin) / zspan;
      if (rng.uniform() > bottom + rise * t) continue;
    }
    if (spec.noiseBound > 0) s.p += rng.inBall(spec.noiseBound);
    if (spec.gaussianSigma > 0)
      s.p += vcg::Point3d(rng.gaussian(), rng.gaussian(), rng.gaussian()) * spec.gaussianSigma;
    c.points.push_back(s.p);
    c.normals.push_back(s.n);
  }
  if (outliers > 0) {
    vcg::Point3d lo = c.points[0], hi = c.points[0];
    for (const auto& p : c.points)
      for (int a = 0; a < 3; ++a) {
        lo[a] = std::min(lo[a], p[a]);
        hi[a] = std::max(hi[a], p[a]);
      }
    const vcg::Point3d margin = (hi - lo) * 0.05;
    lo -= margin;
    hi += margin;
    for (size_t i = 0; i < outliers; ++i) {
      c.points.emplace_back(rng.uniform(lo[0], hi[0]), rng.uniform(lo[1], hi[1]), rng.uniform(lo[2], hi[2]));
      c.normals.push_back(rng.unitVector());
    }
  }
  return c;
}

double distanceToShape(const CloudSpec& s, const vcg::Point3d& p) {
  switch (s.shape) {
  case Shape::Sphere: return std::abs(p.Norm() - s.sphereRadius);
  case Shape::Torus: {
    const double rho = std::hypot(p[0], p[1]);
    return std::abs(std::hypot(rho - s.torusMajor, p[2]) - s.torusMinor);
  }
  case Shape::Patch: return std::abs(p[2] - patchHeight(p[0], p[1]));
  }
  return 0;
}

Shape parseShape(const std::string& name) {
  if (name == "sphere") return Shape::Sphere;
  if (name == "torus") return Shape::Torus;
  if (name == "patch") return Shape::Patch;
  throw Error("unknown shape '" + name + "' (sphere, torus or patch)");
}

const char* shapeName(Shape s) {
  switch (s) {
  case Shape::Sphere: return "sphere";
  case Shape::Torus: return "torus";
  case Shape::Patch: return "patch";
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
  std::vector<float> buf;
  buf.reserve(cloud.points.size() * 6);
  for (size_t i = 0; i < cloud.points.size(); ++i) {
    for (int a = 0; a < 3; ++a) buf.push_back(static_cast<float>(cloud.points[i][a]));
    for (int a = 0; a < 3; ++a) buf.push_back(static_cast<float>(cloud.normals[i][a]));
  }
  static_assert(sizeof(float) == 4, "PLY float is 4 bytes");
  // x86-64 is little-endian, which is what the header declares.
  if (std::fwrite(buf.data(), sizeof(float), buf.size(), f.get()) != buf.size())
    throw Error("cannot write " + path);
}

void toMesh(const Cloud& cloud, CMeshO& mesh) {
  mesh.Clear();
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(mesh, cloud.points.size());
  for (size_t i = 0; i < cloud.points.size(); ++i, ++vi) {
    vi->P() = vcg::Point3f::Construct(cloud.points[i]);
    vi->N() = vcg::Point3f::Construct(cloud.normals[i]);
  }
  vcg::tri::UpdateBounding<CMeshO>::Box(mesh);
}

} // namespace growth
