#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/mesh_generator.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <functional>
#include <memory>
#include <unordered_map>

namespace growth {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Grid lines through every feature coordinate; between two features, round(span / h) intervals
// (at least one) of random relative widths in [0.5, 1.5].
std::vector<double> gridLines(const std::vector<double>& features, double h, Random& rng) {
  std::vector<double> lines{features.front()};
  for (size_t s = 0; s + 1 < features.size(); ++s) {
    const double a = features[s], b = features[s + 1];
    const size_t n = std::max<size_t>(1, size_t(std::lround((b - a) / h)));
    std::vector<double> w(n);
    double sum = 0;
    for (double& x : w) sum += (x = rng.uniform(0.5, 1.5));
    double acc = 0;
    for (size_t i = 0; i + 1 < n; ++i) lines.push_back(a + (b - a) * ((acc += w[i]) / sum));
    lines.push_back(b);
  }
  return lines;
}

// Largest random move of a grid coordinate: jitter × the shorter neighbouring interval (none at the
// ends of the grid).
double gridMove(const std::vector<double>& lines, size_t i, double jitter, Random& rng) {
  if (i == 0 || i + 1 >= lines.size()) return 0;
  const double room = std::min(lines[i] - lines[i - 1], lines[i + 1] - lines[i]);
  return jitter * room * rng.uniform(-1.0, 1.0);
}

class Builder {
public:
  MeshArrays mesh;
  // The triangle a, b, c, turned so that its normal points along `outward`.
  void triangle(std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec3d& outward) {
    const Vec3d& pa = mesh.vertices[a];
    const Vec3d n = (mesh.vertices[b] - pa) ^ (mesh.vertices[c] - pa);
    if (n * outward < 0) std::swap(b, c);
    mesh.faces.push_back({a, b, c});
  }
  // Quad a, b, c, d (in cyclic order) as two triangles: the diagonal a–c or b–d at random, or the
  // other one when the random one gives a triangle turned against `outward` or nearly flat.
  void quad(const std::array<std::uint32_t, 4>& q, const Vec3d& outward, Random& rng) {
    const bool first = rng.uniform() < 0.5;
    for (int attempt = 0; attempt < 2; ++attempt) {
      const bool ac = (attempt == 0) == first;
      const std::array<std::uint32_t, 3> t1 = ac ? std::array<std::uint32_t, 3>{q[0], q[1], q[2]}
                                                 : std::array<std::uint32_t, 3>{q[0], q[1], q[3]};
      const std::array<std::uint32_t, 3> t2 = ac ? std::array<std::uint32_t, 3>{q[0], q[2], q[3]}
                                                 : std::array<std::uint32_t, 3>{q[1], q[2], q[3]};
      if (attempt == 0 && !(wellTurned(q, t1, outward) && wellTurned(q, t2, outward))) continue;
      triangle(t1[0], t1[1], t1[2], outward);
      triangle(t2[0], t2[1], t2[2], outward);
      return;
    }
  }

private:
  // The triangle, in the quad's cyclic orientation, faces the same way as the quad and is not a
  // sliver (height above 5 % of its longest edge).
  bool wellTurned(const std::array<std::uint32_t, 4>& q, const std::array<std::uint32_t, 3>& t, const Vec3d& outward) const {
    const Vec3d& a = mesh.vertices[t[0]];
    const Vec3d& b = mesh.vertices[t[1]];
    const Vec3d& c = mesh.vertices[t[2]];
    const Vec3d quadNormal = (mesh.vertices[q[2]] - mesh.vertices[q[0]]) ^ (mesh.vertices[q[3]] - mesh.vertices[q[1]]);
    const Vec3d n = (b - a) ^ (c - a);
    const double sign = (quadNormal * outward) >= 0 ? 1 : -1;
    const double lmax = std::max({(b - a).Norm(), (c - b).Norm(), (a - c).Norm()});
    return sign * (n * outward) > 0 && n.Norm() > 0.05 * lmax * lmax;
  }
};

// --- Orthogonal prisms ---

struct Prism {
  std::vector<double> xFeatures, yFeatures;
  double height = 1;
  std::function<bool(double, double)> inside;   // the cross-section, asked at cell centres
  bool top = true;                               // the top face is there
};

Prism prismOf(MeshShape shape) {
  Prism p;
  switch (shape) {
    case MeshShape::Box:
    case MeshShape::OpenBox:
      p.xFeatures = {0, 1};
      p.yFeatures = {0, 0.8};
      p.height = 0.6;
      p.inside = [](double, double) { return true; };
      p.top = shape == MeshShape::Box;
      break;
    case MeshShape::LPrism:
      p.xFeatures = p.yFeatures = {0, 0.45, 1};
      p.height = 0.4;
      p.inside = [](double x, double y) { return !(x > 0.45 && y > 0.45); };
      break;
    case MeshShape::HoledBox:
      p.xFeatures = p.yFeatures = {0, 0.35, 0.65, 1};
      p.height = 0.5;
      p.inside = [](double x, double y) { return !(x > 0.35 && x < 0.65 && y > 0.35 && y < 0.65); };
      break;
    default:
      throw Error("not a prism shape");
  }
  return p;
}

MeshArrays prismMesh(const Prism& p, double h, double jitter, Random& rng) {
  const std::vector<double> xs = gridLines(p.xFeatures, h, rng), ys = gridLines(p.yFeatures, h, rng),
                            zs = gridLines({0, p.height}, h, rng);
  const size_t nx = xs.size() - 1, ny = ys.size() - 1, nz = zs.size() - 1;
  auto inside = [&](long i, long j) {
    return i >= 0 && j >= 0 && size_t(i) < nx && size_t(j) < ny && p.inside(0.5 * (xs[size_t(i)] + xs[size_t(i) + 1]), 0.5 * (ys[size_t(j)] + ys[size_t(j) + 1]));
  };
  // The quads with their outward axis (0, 1, 2) and sign, on grid vertices (i, j, k).
  struct Quad {
    std::array<std::uint64_t, 4> key;
    int axis;
    double sign;
  };
  auto key = [&](size_t i, size_t j, size_t k) { return (std::uint64_t(i) * (ny + 1) + j) * (nz + 1) + k; };
  std::vector<Quad> quads;
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j) {
      if (!inside(long(i), long(j))) continue;
      quads.push_back({{key(i, j, 0), key(i + 1, j, 0), key(i + 1, j + 1, 0), key(i, j + 1, 0)}, 2, -1});
      if (p.top) quads.push_back({{key(i, j, nz), key(i + 1, j, nz), key(i + 1, j + 1, nz), key(i, j + 1, nz)}, 2, 1});
      for (size_t k = 0; k < nz; ++k) {
        if (!inside(long(i) - 1, long(j))) quads.push_back({{key(i, j, k), key(i, j + 1, k), key(i, j + 1, k + 1), key(i, j, k + 1)}, 0, -1});
        if (!inside(long(i) + 1, long(j))) quads.push_back({{key(i + 1, j, k), key(i + 1, j + 1, k), key(i + 1, j + 1, k + 1), key(i + 1, j, k + 1)}, 0, 1});
        if (!inside(long(i), long(j) - 1)) quads.push_back({{key(i, j, k), key(i + 1, j, k), key(i + 1, j, k + 1), key(i, j, k + 1)}, 1, -1});
        if (!inside(long(i), long(j) + 1)) quads.push_back({{key(i, j + 1, k), key(i + 1, j + 1, k), key(i + 1, j + 1, k + 1), key(i, j + 1, k + 1)}, 1, 1});
      }
    }
  // Vertices in the order of first use; an axis is blocked for a vertex when one of its quads is
  // perpendicular to it (moving along it would bend that face).
  Builder b;
  std::unordered_map<std::uint64_t, std::uint32_t> index;
  std::vector<std::uint64_t> keys;
  std::vector<unsigned> blocked;
  for (const Quad& q : quads)
    for (std::uint64_t k : q.key) {
      auto it = index.emplace(k, std::uint32_t(keys.size()));
      if (it.second) {
        keys.push_back(k);
        blocked.push_back(0);
      }
      blocked[it.first->second] |= 1u << q.axis;
    }
  b.mesh.vertices.resize(keys.size());
  for (size_t v = 0; v < keys.size(); ++v) {
    const size_t k = size_t(keys[v] % (nz + 1)), j = size_t(keys[v] / (nz + 1) % (ny + 1)), i = size_t(keys[v] / (nz + 1) / (ny + 1));
    const std::vector<double>* lines[3] = {&xs, &ys, &zs};
    const size_t at[3] = {i, j, k};
    for (int a = 0; a < 3; ++a) {
      const double move = (blocked[v] >> a & 1u) ? 0.0 : gridMove(*lines[a], at[a], jitter, rng);
      b.mesh.vertices[v][a] = (*lines[a])[at[a]] + move;
    }
  }
  for (const Quad& q : quads) {
    Vec3d outward(0, 0, 0);
    outward[q.axis] = q.sign;
    b.quad({index[q.key[0]], index[q.key[1]], index[q.key[2]], index[q.key[3]]}, outward, rng);
  }
  return std::move(b.mesh);
}

// --- Cylinder ---

// Triangles between two closed loops around the z axis in a plane z = const, each in increasing
// angle, `inner` nearer the axis: a zipper that advances on the loop whose next vertex comes first in
// angle, unless only the other choice gives a triangle turned the right way (the moves of the rings'
// vertices can put a vertex behind its neighbour of the other ring). Seen from +z, (inner_i,
// outer_j, inner_i+1) and (inner_i, outer_j, outer_j+1) turn counter-clockwise; `up` < 0 (the
// bottom cap) turns them over.
void stitch(Builder& b, const std::vector<std::uint32_t>& inner, const std::vector<std::uint32_t>& outer, double up) {
  const std::vector<Vec3d>& v = b.mesh.vertices;
  auto angle = [&](std::uint32_t i) { return std::atan2(v[i][1], v[i][0]); };
  auto unwrap = [&](const std::vector<std::uint32_t>& loop, size_t start, double from) {
    std::vector<double> a;
    for (size_t s = 0; s <= loop.size(); ++s) {
      double t = angle(loop[(start + s) % loop.size()]);
      while (t < from) t += 2 * kPi;
      while (!a.empty() && t < a.back()) t += 2 * kPi;
      a.push_back(t);
    }
    a.back() = a.front() + 2 * kPi;
    return a;
  };
  auto counterClockwise = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
    return (v[q][0] - v[p][0]) * (v[r][1] - v[p][1]) - (v[q][1] - v[p][1]) * (v[r][0] - v[p][0]) > 0;
  };
  auto emit = [&](std::uint32_t p, std::uint32_t q, std::uint32_t r) {
    if (up > 0) b.mesh.faces.push_back({p, q, r});
    else b.mesh.faces.push_back({p, r, q});
  };
  const std::vector<double> ai = unwrap(inner, 0, angle(inner[0]));
  const double a0 = ai[0];
  size_t start = 0;
  double best = 1e300;
  for (size_t s = 0; s < outer.size(); ++s) {
    double d = angle(outer[s]) - a0;
    while (d < 0) d += 2 * kPi;
    if (d < best) best = d, start = s;
  }
  const std::vector<double> ao = unwrap(outer, start, a0);
  size_t i = 0, j = 0;
  const size_t ni = inner.size(), no = outer.size();
  while (i < ni || j < no) {
    const std::uint32_t p = inner[i % ni], p1 = inner[(i + 1) % ni], q = outer[(start + j) % no], q1 = outer[(start + j + 1) % no];
    bool advanceInner = j == no;
    if (i < ni && j < no) {
      const bool innerTurns = counterClockwise(p, q, p1), outerTurns = counterClockwise(p, q, q1);
      advanceInner = innerTurns != outerTurns ? innerTurns : ai[i + 1] < ao[j + 1];
    }
    if (advanceInner) {
      emit(p, q, p1);
      ++i;
    } else {
      emit(p, q, q1);
      ++j;
    }
  }
}

MeshArrays cylinderMesh(double h, double jitter, Random& rng) {
  const double radius = 0.5, height = 1.0;
  const size_t around = std::max<size_t>(8, size_t(std::lround(2 * kPi * radius / h)));
  const std::vector<double> zs = gridLines({0, height}, h, rng);
  const size_t nz = zs.size() - 1;
  Builder b;
  const double phase = rng.uniform(0, 2 * kPi / double(around));
  // The side: rows of `around` vertices; a rim vertex slides along its rim only.
  std::vector<std::vector<std::uint32_t>> rows(nz + 1);
  for (size_t k = 0; k <= nz; ++k)
    for (size_t j = 0; j < around; ++j) {
      const double t = phase + 2 * kPi * (double(j) + jitter * rng.uniform(-1.0, 1.0)) / double(around);
      const double z = zs[k] + gridMove(zs, k, jitter, rng);
      rows[k].push_back(std::uint32_t(b.mesh.vertices.size()));
      b.mesh.vertices.push_back(Vec3d(radius * std::cos(t), radius * std::sin(t), z));
    }
  for (size_t k = 0; k < nz; ++k)
    for (size_t j = 0; j < around; ++j) {
      const size_t j1 = (j + 1) % around;
      const Vec3d mid = (b.mesh.vertices[rows[k][j]] + b.mesh.vertices[rows[k + 1][j1]]) * 0.5;
      b.quad({rows[k][j], rows[k][j1], rows[k + 1][j1], rows[k + 1][j]}, Vec3d(mid[0], mid[1], 0), rng);
    }
  // The caps: rings at radius R·m / rings (m = 1 .. rings − 1) of about 2πr / h vertices each, moved
  // by up to jitter × their angular spacing and jitter / 2 × the ring spacing; the centre, the rim;
  // consecutive rings zipped together.
  const size_t rings = std::max<size_t>(1, size_t(std::lround(radius / h)));
  for (int cap = 0; cap < 2; ++cap) {
    const double z = cap == 0 ? 0.0 : height;
    const Vec3d outward(0, 0, cap == 0 ? -1 : 1);
    const std::uint32_t centre = std::uint32_t(b.mesh.vertices.size());
    b.mesh.vertices.push_back(Vec3d(0, 0, z));
    std::vector<std::uint32_t> previous{centre};
    for (size_t m = 1; m <= rings; ++m) {
      std::vector<std::uint32_t> ring;
      if (m == rings) ring = rows[cap == 0 ? 0 : nz];
      else {
        const double r0 = radius * double(m) / double(rings);
        const size_t count = std::max<size_t>(6, size_t(std::lround(2 * kPi * r0 / h)));
        const double ringPhase = rng.uniform(0, 2 * kPi);
        for (size_t j = 0; j < count; ++j) {
          const double t = ringPhase + 2 * kPi * (double(j) + jitter * rng.uniform(-1.0, 1.0)) / double(count);
          const double r = r0 + 0.5 * jitter * (radius / double(rings)) * rng.uniform(-1.0, 1.0);
          ring.push_back(std::uint32_t(b.mesh.vertices.size()));
          b.mesh.vertices.push_back(Vec3d(r * std::cos(t), r * std::sin(t), z));
        }
        // In increasing angle (the ring's phase may wrap).
        std::sort(ring.begin(), ring.end(), [&](std::uint32_t u, std::uint32_t v) {
          return std::atan2(b.mesh.vertices[u][1], b.mesh.vertices[u][0]) < std::atan2(b.mesh.vertices[v][1], b.mesh.vertices[v][0]);
        });
      }
      if (previous.size() == 1)
        for (size_t j = 0; j < ring.size(); ++j) b.triangle(centre, ring[j], ring[(j + 1) % ring.size()], outward);
      else
        stitch(b, previous, ring, outward[2]);
      previous = ring;
    }
  }
  return std::move(b.mesh);
}

// --- Sheet with holes ---

double sheetHeight(double x, double y) { return 0.06 * std::sin(2 * kPi * x) * std::cos(kPi * y); }

MeshArrays sheetMesh(double h, double jitter, Random& rng) {
  const std::vector<double> xs = gridLines({0, 1}, h, rng), ys = gridLines({0, 1}, h, rng);
  const size_t nx = xs.size() - 1, ny = ys.size() - 1;
  struct Hole {
    double x, y, r;
  };
  const Hole holes[] = {{0.28, 0.3, 0.12}, {0.72, 0.34, 0.1}, {0.46, 0.72, 0.14}};
  std::vector<char> keep(nx * ny, 1);
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j) {
      const double cx = 0.5 * (xs[i] + xs[i + 1]), cy = 0.5 * (ys[j] + ys[j + 1]);
      for (const Hole& o : holes)
        if ((cx - o.x) * (cx - o.x) + (cy - o.y) * (cy - o.y) < o.r * o.r) keep[i * ny + j] = 0;
    }
  // No two kept cells may meet at a corner only (a non-manifold vertex): drop one of them.
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t i = 1; i < nx; ++i)
      for (size_t j = 1; j < ny; ++j) {
        char& c00 = keep[(i - 1) * ny + j - 1];
        char& c10 = keep[i * ny + j - 1];
        char& c11 = keep[i * ny + j];
        char& c01 = keep[(i - 1) * ny + j];
        if (c00 && c11 && !c10 && !c01) c11 = 0, changed = true;
        else if (c10 && c01 && !c00 && !c11) c01 = 0, changed = true;
      }
  }
  Builder b;
  std::vector<std::uint32_t> index((nx + 1) * (ny + 1), UINT32_MAX);
  auto vertex = [&](size_t i, size_t j) {
    std::uint32_t& v = index[i * (ny + 1) + j];
    if (v == UINT32_MAX) {
      v = std::uint32_t(b.mesh.vertices.size());
      const double x = xs[i] + gridMove(xs, i, jitter, rng), y = ys[j] + gridMove(ys, j, jitter, rng);
      b.mesh.vertices.push_back(Vec3d(x, y, sheetHeight(x, y)));
    }
    return v;
  };
  for (size_t i = 0; i < nx; ++i)
    for (size_t j = 0; j < ny; ++j)
      if (keep[i * ny + j])
        b.quad({vertex(i, j), vertex(i + 1, j), vertex(i + 1, j + 1), vertex(i, j + 1)}, Vec3d(0, 0, 1), rng);
  return std::move(b.mesh);
}

MeshArrays generateAt(const MeshSpec& spec, double h) {
  Random rng(spec.seed);
  switch (spec.shape) {
    case MeshShape::Cylinder: return cylinderMesh(h, spec.jitter, rng);
    case MeshShape::Sheet: return sheetMesh(h, spec.jitter, rng);
    default: return prismMesh(prismOf(spec.shape), h, spec.jitter, rng);
  }
}

} // namespace

MeshArrays generateMesh(const MeshSpec& spec) {
  if (spec.faces < 12) throw Error("a generated mesh needs at least 12 faces");
  if (!(spec.jitter >= 0 && spec.jitter <= 0.45)) throw Error("jitter must be in [0, 0.45]");
  // The spacing for a surface of about 4 square units, then fitted twice to the face count found.
  double h = std::sqrt(2.0 * 4.0 / double(spec.faces));
  MeshArrays mesh;
  for (int pass = 0; pass < 3; ++pass) {
    mesh = generateAt(spec, h);
    const double ratio = double(mesh.faces.size()) / double(spec.faces);
    if (std::abs(ratio - 1) < 0.03) break;
    h *= std::sqrt(ratio);
  }
  return mesh;
}

MeshShapeTopology shapeTopology(MeshShape shape) {
  MeshShapeTopology t;
  switch (shape) {
    case MeshShape::HoledBox: t.genus = 1; break;
    case MeshShape::OpenBox: t.boundaryLoops = 1; break;
    case MeshShape::Sheet:
      t.boundaryLoops = 4;
      t.hasCreases = false;
      break;
    default: break;
  }
  return t;
}

MeshShape parseMeshShape(const std::string& name) {
  for (MeshShape s : {MeshShape::Box, MeshShape::Cylinder, MeshShape::LPrism, MeshShape::HoledBox, MeshShape::OpenBox, MeshShape::Sheet})
    if (name == meshShapeName(s)) return s;
  throw Error("unknown mesh shape '" + name + "' (box, cylinder, lprism, holedbox, openbox, sheet)");
}

const char* meshShapeName(MeshShape shape) {
  switch (shape) {
    case MeshShape::Box: return "box";
    case MeshShape::Cylinder: return "cylinder";
    case MeshShape::LPrism: return "lprism";
    case MeshShape::HoledBox: return "holedbox";
    case MeshShape::OpenBox: return "openbox";
    case MeshShape::Sheet: return "sheet";
  }
  return "?";
}

void writeMeshPly(const std::string& path, const MeshArrays& mesh) {
  std::unique_ptr<FILE, int (*)(FILE*)> f(std::fopen(path.c_str(), "wb"), &std::fclose);
  if (!f) throw Error("cannot write " + path);
  std::fprintf(f.get(),
               "ply\nformat binary_little_endian 1.0\ncomment generated by growth::generateMesh\n"
               "element vertex %zu\nproperty float x\nproperty float y\nproperty float z\n"
               "element face %zu\nproperty list uchar int vertex_indices\nend_header\n",
               mesh.vertices.size(), mesh.faces.size());
  std::vector<float> xyz;
  xyz.reserve(3 * mesh.vertices.size());
  for (const Vec3d& p : mesh.vertices)
    for (int a = 0; a < 3; ++a) xyz.push_back(float(p[a]));
  bool ok = std::fwrite(xyz.data(), sizeof(float), xyz.size(), f.get()) == xyz.size();
  std::vector<unsigned char> faces(13 * mesh.faces.size());
  for (size_t i = 0; i < mesh.faces.size(); ++i) {
    faces[13 * i] = 3;
    for (int k = 0; k < 3; ++k) {
      const std::int32_t v = std::int32_t(mesh.faces[i][k]);
      std::memcpy(&faces[13 * i + 1 + 4 * size_t(k)], &v, 4);
    }
  }
  ok = ok && std::fwrite(faces.data(), 1, faces.size(), f.get()) == faces.size();
  if (!ok) throw Error("cannot write " + path);
}

} // namespace growth
