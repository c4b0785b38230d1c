#include "harness.h"

#include "filter_g2s_layer.h"
#include "filter_spherepack_layer.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/import_ply.h>

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace growth {
namespace fuzz {

namespace {

// Reads the recipe; past the end every byte is 0.
class Bytes {
public:
  Bytes(const std::uint8_t* data, size_t size) : data_(data), size_(size) {}
  // (Every read is a statement of its own: the order of the operands of an expression is
  // unspecified, and a recipe must read the same with every compiler.)
  std::uint8_t u8() { return pos_ < size_ ? data_[pos_++] : 0; }
  std::uint16_t u16() {
    const unsigned lo = u8();
    return std::uint16_t(lo | (unsigned(u8()) << 8));
  }
  std::uint32_t u32() {
    const std::uint32_t lo = u16();
    return lo | (std::uint32_t(u16()) << 16);
  }
  std::uint64_t u64() {
    const std::uint64_t lo = u32();
    return lo | (std::uint64_t(u32()) << 32);
  }
  growth::Vec3d unitPoint() {
    const double x = unit(), y = unit();
    return growth::Vec3d(x, y, unit());
  }
  growth::Vec3d rawPoint() {
    const double x = raw(), y = raw();
    return growth::Vec3d(x, y, raw());
  }
  double unit() { return double(u16()) / 65535.0; }            // [0, 1]
  bool chance(int in256) { return u8() >= 256 - in256; }        // true with probability in256/256 (0: false)
  double raw() {                                                // any double: NaN, inf, subnormal
    const std::uint64_t b = u64();
    double v;
    std::memcpy(&v, &b, sizeof v);
    return v;
  }
  double pow2(int lo, int hi) { return std::ldexp(1.0, lo + int(u16() % unsigned(hi - lo + 1))); } // 2^lo..2^hi

private:
  const std::uint8_t* data_;
  size_t size_;
  size_t pos_ = 0;
};

void check(bool ok, const std::string& what) {
  if (!ok) throw std::logic_error(what);
}

// Cancels the build at its n-th progress report (never when n = 0).
struct CancelAfter {
  static int remaining;
  static bool callback(const int, const char*) { return remaining <= 0 || --remaining > 0; }
};
int CancelAfter::remaining = 0;

template <class BuildFn>
void runEngine(const char* engine, int cancelAfter, CMeshO& out, BuildFn build) {
  CancelAfter::remaining = cancelAfter;
  try {
    build(cancelAfter > 0 ? &CancelAfter::callback : nullptr);
  } catch (const Error& e) {
    check(std::strlen(e.what()) > 0, std::string(engine) + ": growth::Error without a message");
    check(out.vn == 0 && out.fn == 0 && out.vert.empty() && out.face.empty(),
          std::string(engine) + ": output not empty after growth::Error");
  } catch (const Cancelled&) {
    check(cancelAfter > 0, std::string(engine) + ": cancelled without a cancel");
    check(out.vn == 0 && out.fn == 0 && out.vert.empty() && out.face.empty(),
          std::string(engine) + ": output not empty after a cancel");
  }
}

void runSpherepack(const CMeshO& cloud, const spherepack::Params& p, int cancelAfter) {
  CMeshO out;
  spherepack::Stat st;
  bool built = false;
  runEngine("sphere packing", cancelAfter, out, [&](vcg::CallBackPos* cb) {
    spherepack::build(cloud, out, p, st, cb);
    built = true;
  });
  if (!built) return;
  checkOutput(out, st.vertices, st.faces, "sphere packing");
  check(st.nonManifoldVertices == 0 && st.nonManifoldEdges == 0, "sphere packing: non-manifold output");
}

void runG2s(const CMeshO& cloud, const g2s::Params& p, int cancelAfter) {
  CMeshO out;
  g2s::Stat st;
  bool built = false;
  runEngine("Robust G2S", cancelAfter, out, [&](vcg::CallBackPos* cb) {
    g2s::build(cloud, out, p, st, cb);
    built = true;
  });
  if (!built) return;
  checkOutput(out, st.vertices, st.faces, "Robust G2S");
  if (p.removeNonManifoldVertices) check(st.nonManifoldVertices == 0, "Robust G2S: non-manifold output");
}

// A scratch file for vcglib's importer, which reads only from a path; one per process.
const std::string& scratchPath() {
  static const std::string path = [] {
    const char* dir = std::getenv("TMPDIR");
    return std::string(dir != nullptr && *dir != '\0' ? dir : "/tmp") + "/growth_fuzz_" +
           std::to_string(getpid()) + ".ply";
  }();
  return path;
}

// Whether no element is a non-empty "edge" one and every "element <name> <count>" in the bytes has
// its count on its line and declares at most
// kMaxPlyElements, and all of them together too. Looked for anywhere in the bytes, not only in
// the header as parsed: vcglib reads the header in chunks of 511 bytes, so a long line's tail
// counts as a line of its own. A missing count is vcglib's bug, not the engines': its header
// parser checks the name again where it means the count, and calls atoi(NULL), which crashes
// (fuzz/regressions/ply/element_without_count_vcglib_atoi_null.ply), in MeshLab too.
bool plyHeaderAccepted(const std::uint8_t* data, size_t size) {
  // The header is text (the PLY format's rule): vcglib's tokenizer stops at a NUL or other control
  // byte where the checks below read on, and then calls atoi(NULL) on a missing count
  // (fuzz/regressions/ply/binary_in_header_vcglib_atoi_null.ply). Such files are no PLY files; the
  // data after the header is fuzzed as it comes.
  {
    const std::string bytes(reinterpret_cast<const char*>(data), size);
    const size_t headerEnd = std::min(bytes.find("end_header"), size);
    for (size_t i = 0; i < headerEnd; ++i) {
      const unsigned char ch = data[i];
      if (!((ch >= 0x20 && ch < 0x7f) || ch == '\n' || ch == '\r' || ch == '\t')) return false;
    }
  }
  static const char kElement[] = "element";
  const size_t len = sizeof kElement - 1;
  long long total = 0;
  for (size_t i = 0; i + len <= size; ++i) {
    if (std::memcmp(data + i, kElement, len) != 0) continue;
    std::string rest(reinterpret_cast<const char*>(data) + i + len, std::min<size_t>(size - i - len, 200));
    rest = rest.substr(0, rest.find_first_of(std::string("\n\r\0", 3))); // vcglib reads one line
    char name[201] = {0};
    long long count = 0;
    if (std::sscanf(rest.c_str(), "%200s %lld", name, &count) != 2) return false;
    if (count < 0 || count > static_cast<long long>(kMaxPlyElements)) return false;
    // Edges are vcglib's edge reader's business, not the engines' (a cloud has none): it asserts
    // when an edge element lacks the properties vertex1 and vertex2
    // (fuzz/regressions/ply/edge_without_vertex1_vcglib_assert.ply), where a release build reads on.
    if (std::strcmp(name, "edge") == 0 && count > 0) return false;
    total += count;
    if (total > static_cast<long long>(kMaxPlyElements)) return false;
  }
  // Lines of the header longer than vcglib's buffer are read in pieces, so a line's count could
  // come in the next piece: such headers are skipped too.
  const std::string bytes(reinterpret_cast<const char*>(data), size);
  const size_t headerEnd = std::min(bytes.find("end_header"), size);
  for (size_t start = 0; start < headerEnd;) {
    const size_t end = std::min(bytes.find('\n', start), headerEnd);
    if (end - start > 500) return false;
    start = end + 1;
  }
  return true;
}

} // namespace

void checkOutput(const CMeshO& out, size_t statVertices, size_t statFaces, const char* engine) {
  const std::string e(engine);
  check(size_t(out.vn) == statVertices && out.vert.size() == statVertices, e + ": vertex count differs from Stat");
  check(size_t(out.fn) == statFaces && out.face.size() == statFaces, e + ": face count differs from Stat");
  for (const auto& v : out.vert) {
    check(!v.IsD(), e + ": deleted vertex in the output");
    for (int a = 0; a < 3; ++a) check(std::isfinite(v.cP()[a]), e + ": non-finite vertex coordinate");
  }
  const CVertexO* first = out.vert.empty() ? nullptr : &out.vert.front();
  for (const auto& f : out.face) {
    check(!f.IsD(), e + ": deleted face in the output");
    for (int j = 0; j < 3; ++j) {
      const CVertexO* v = f.cV(j);
      check(v != nullptr && v >= first && v < first + out.vert.size(), e + ": face corner outside the vertices");
    }
    check(f.cV(0) != f.cV(1) && f.cV(1) != f.cV(2) && f.cV(2) != f.cV(0), e + ": face with a repeated corner");
  }
}

void runPly(const std::uint8_t* data, size_t size) {
  if (!plyHeaderAccepted(data, size)) return;
  const std::string& path = scratchPath();
  {
    FILE* f = std::fopen(path.c_str(), "wb");
    if (f == nullptr) throw std::runtime_error("cannot write " + path);
    const size_t written = std::fwrite(data, 1, size, f);
    std::fclose(f);
    if (written != size) throw std::runtime_error("cannot write " + path);
  }
  CMeshO cloud;
  int mask = 0;
  const int err = vcg::tri::io::ImporterPLY<CMeshO>::Open(cloud, path.c_str(), mask);
  std::remove(path.c_str());
  if (err != 0 && vcg::tri::io::ImporterPLY<CMeshO>::ErrorCritical(err)) return; // the tools' "cannot read"
  if (size_t(cloud.vn) > kMaxPoints) return;

  spherepack::Params sp = spherepack::suggestParams(cloud);
  sp.threads = 1;
  sp.maxOutputVertices = kMaxOutputVertices;
  runSpherepack(cloud, sp, 0);
  runG2s(cloud, g2s::suggestParams(cloud), 0);
}

namespace {

enum Layout { kShape0 = 0, kPlaneLattice = 4, kSlab, kLine, kTwoSheets, kVolumeLattice, kClusters, kLayouts };

Cloud makeCloud(Bytes& in) {
  const int layout = in.u8() % kLayouts;
  // 3 to 10, 18, 34, ..., 2051 points: mostly small clouds, which run fastest.
  const size_t range = size_t(8) << (in.u8() % 9);
  const size_t count = 3 + in.u16() % range;
  const std::uint64_t seed = in.u64();
  Random rng(seed);
  Cloud c;
  auto add = [&](const growth::Vec3d& p, const growth::Vec3d& n) {
    c.points.push_back(p);
    c.normals.push_back(n);
  };
  switch (layout) {
  case kPlaneLattice: { // every 4 neighbours cocircular, every triangle pair degenerate for G2S
    const size_t side = std::max<size_t>(2, size_t(std::sqrt(double(count))));
    for (size_t i = 0; i < side; ++i)
      for (size_t j = 0; j < side && c.points.size() < count; ++j) add({double(i), double(j), 0}, {0, 0, 1});
    break;
  }
  case kSlab: { // uniform in a box of thickness 2^-k
    const double t = in.pow2(-60, 0);
    for (size_t i = 0; i < count; ++i) add({rng.uniform(), rng.uniform(), t * rng.uniform()}, {0, 0, 1});
    break;
  }
  case kLine: { // collinear but for a few points 2^-k off the line
    const double off = in.pow2(-60, 0);
    const size_t offLine = in.u8() % 4;
    for (size_t i = 0; i < count; ++i) {
      const double y = i < offLine ? off * rng.uniform() : 0.0;
      add({double(i) / double(count), y, 0}, rng.unitVector());
    }
    break;
  }
  case kTwoSheets: { // a thin plate: two sheets 2^-k apart, normals outwards
    const double gap = in.pow2(-40, 0);
    for (size_t i = 0; i < count; ++i) {
      const bool top = (i & 1) != 0;
      add({rng.uniform(), rng.uniform(), top ? gap : 0.0}, {0, 0, top ? 1.0 : -1.0});
    }
    break;
  }
  case kVolumeLattice: { // a cube of points: no surface to find
    const size_t side = std::max<size_t>(2, size_t(std::cbrt(double(count))));
    for (size_t i = 0; i < side; ++i)
      for (size_t j = 0; j < side; ++j)
        for (size_t k = 0; k < side && c.points.size() < count; ++k)
          add({double(i), double(j), double(k)}, rng.unitVector());
    break;
  }
  case kClusters: { // a few positions, each repeated with a jitter of 2^-k (0: exact copies)
    const size_t centres = 1 + in.u8() % 8;
    const double jitter = in.chance(64) ? 0.0 : in.pow2(-50, -1);
    std::vector<growth::Vec3d> centre;
    for (size_t k = 0; k < centres; ++k) centre.push_back(rng.inBall(1.0));
    for (size_t i = 0; i < count; ++i) {
      const growth::Vec3d p = centre[i % centres] + rng.inBall(jitter);
      add(p, rng.unitVector());
    }
    break;
  }
  default: { // the generator's shapes, with its noise, outliers and non-uniform sampling
    CloudSpec spec;
    spec.shape = static_cast<Shape>(layout);
    spec.count = count;
    spec.seed = seed;
    spec.nonUniform = in.chance(64);
    spec.densityRatio = 1.0 + 15.0 * in.unit();
    spec.noiseBound = in.chance(128) ? 0.2 * std::pow(in.unit(), 2) : 0.0;
    spec.gaussianSigma = in.chance(64) ? 0.05 * std::pow(in.unit(), 2) : 0.0;
    spec.outlierFraction = in.chance(96) ? 0.3 * in.unit() : 0.0;
    c = generateCloud(spec);
    break;
  }
  }

  // Exact duplicates of earlier points.
  if (in.chance(64)) {
    const size_t copies = std::min(c.points.size(), size_t(in.u16() % kMaxPoints));
    for (size_t i = 0; i < copies && c.points.size() < kMaxPoints; ++i) {
      const size_t k = size_t(rng.next() % c.points.size());
      add(c.points[k], c.normals[k]);
    }
  }
  // Shuffled order (the generator's order is spatially random already; lattices are not).
  if (in.chance(64))
    for (size_t i = c.points.size(); i > 1; --i) {
      const size_t k = size_t(rng.next() % i);
      std::swap(c.points[i - 1], c.points[k]);
      std::swap(c.normals[i - 1], c.normals[k]);
    }
  // Scale by 2^e and move by 2^k: huge, tiny and far-off coordinates (float holds ±2^127).
  if (in.chance(96)) {
    const double scale = in.pow2(-130, 130);
    double offset = 0;
    if (in.chance(128)) {
      const double sign = in.chance(128) ? -1 : 1;
      offset = sign * in.pow2(-20, 130);
    }
    for (auto& p : c.points) p = p * scale + growth::Vec3d(offset, offset * 0.5, -offset);
  }
  // Normals: noisy, flipped, zero or NaN on some points.
  if (in.chance(96)) {
    const int mode = in.u8() % 4;
    const double fraction = in.unit();
    const double noise = in.unit();
    for (auto& n : c.normals) {
      if (rng.uniform() >= fraction) continue;
      switch (mode) {
      case 0: n = (n + rng.unitVector() * noise).Normalize(); break;
      case 1: n = -n; break;
      case 2: n = growth::Vec3d(0, 0, 0); break;
      default: n = growth::Vec3d(std::numeric_limits<double>::quiet_NaN(), 0, 0); break;
      }
    }
  }
  // A few non-finite coordinates.
  if (in.chance(16)) {
    const double bad[3] = {std::numeric_limits<double>::quiet_NaN(), std::numeric_limits<double>::infinity(),
                           -std::numeric_limits<double>::infinity()};
    const size_t n = 1 + in.u8() % 4;
    for (size_t i = 0; i < n; ++i) {
      const int axis = in.u8() % 3;
      c.points[size_t(rng.next() % c.points.size())][axis] = bad[in.u8() % 3];
    }
  }
  return c;
}

// A length for a parameter: 0 (the default), a multiple 2^-3..2^5 of the rough spacing, or any
// double at all.
double lengthParam(Bytes& in, double spacing) {
  switch (in.u8() % 4) {
  case 0: return 0.0;
  case 1:
  case 2: {
    const double factor = in.pow2(-3, 5);
    return spacing * factor * (1.0 + in.unit());
  }
  default: return in.raw();
  }
}

int intParam(Bytes& in, int lo, int hi, int fallback) {
  switch (in.u8() % 4) {
  case 0: return fallback;
  case 1:
  case 2: return lo + int(in.u16() % std::uint16_t(hi - lo + 1));
  default: return static_cast<int>(in.u32());
  }
}

} // namespace

void runCloud(const std::uint8_t* data, size_t size) {
  Bytes in(data, size);
  const Cloud c = makeCloud(in);
  CMeshO cloud;
  toMesh(c, cloud);

  growth::Box3d box;
  for (const auto& p : c.points)
    if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) box.Add(p);
  const double spacing = box.IsNull() ? 1.0 : box.Diag() / std::sqrt(double(c.points.size()));

  spherepack::Params sp;
  sp.sphereDiameter = lengthParam(in, spacing);
  sp.splatSize = lengthParam(in, spacing);
  sp.localSplatSizes = !in.chance(64);
  sp.windowSize = intParam(in, 0, 16, 8);
  sp.maxBorderLength = intParam(in, 3, 100, 40);
  sp.rejectTwisted = !in.chance(32);
  sp.threads = 1 + in.u8() % 2;
  sp.maxOutputVertices = kMaxOutputVertices;
  if (in.chance(64)) sp.spatialOrderMinPoints = in.u16() % kMaxPoints; // the spatial order on small clouds
  sp.checkInvariants = c.points.size() <= 500 && in.chance(64);
  if (in.chance(32)) {
    sp.useStartPoints = true;
    for (auto& q : sp.startPoint) {
      if (in.chance(32)) {
        q = in.rawPoint();
      } else {
        const growth::Vec3d& p = c.points[in.u16() % c.points.size()];
        q = p + in.unitPoint() * spacing;
      }
    }
  }
  const int spCancel = in.chance(32) ? 1 + in.u8() : 0;

  g2s::Params gp;
  gp.seedSearchFactor = in.chance(32) ? in.raw() : (in.chance(64) ? 0.25 + 8 * in.unit() : 2.0);
  gp.maxSearchRadiusFactor = in.chance(32) ? in.raw() : (in.chance(128) ? 1.0 + 9 * in.unit() : 0.0);
  gp.sizeLevels = intParam(in, 1, 64, 4);
  gp.flatnessLevels = intParam(in, 1, 180, 8);
  gp.removeNonManifoldVertices = !in.chance(32);
  gp.randomSeed = in.u64();
  const int g2sCancel = in.chance(32) ? 1 + in.u8() : 0;

  runSpherepack(cloud, sp, spCancel);
  runG2s(cloud, gp, g2sCancel);
}

} // namespace fuzz
} // namespace growth
