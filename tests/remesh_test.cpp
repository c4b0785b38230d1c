// The sphere-packing remesher (filter_spherepack/engine/remesher.h) on meshes made here: every edge
// >= d, manifold, no intersecting faces, the input's components, boundary loops and genus kept,
// vertices on the input surface, the input within reach of the output, the same mesh twice, and
// clear errors on bad input.
#include "remesher.h"

#include <growth/error.h>
#include <growth/mesh_measures.h>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <numeric>
#include <random>
#include <tuple>

using growth::MeshArrays;
using growth::Vec3d;
using growth::spherepack::RemeshParams;
using growth::spherepack::RemeshStat;
using growth::spherepack::remesh;

namespace {

using Face = std::array<std::uint32_t, 3>;

// Icosahedron subdivided `levels` times, projected onto the sphere of radius r around c.
MeshArrays icosphere(int levels, double r, const Vec3d& c = Vec3d(0, 0, 0)) {
  const double t = (1 + std::sqrt(5.0)) / 2;
  std::vector<Vec3d> v = {{-1, t, 0}, {1, t, 0}, {-1, -t, 0}, {1, -t, 0}, {0, -1, t}, {0, 1, t},
                          {0, -1, -t}, {0, 1, -t}, {t, 0, -1}, {t, 0, 1}, {-t, 0, -1}, {-t, 0, 1}};
  std::vector<Face> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11}, {1, 5, 9}, {5, 11, 4},
                         {11, 10, 2}, {10, 7, 6}, {7, 1, 8},   {3, 9, 4},  {3, 4, 2},   {3, 2, 6}, {3, 6, 8},
                         {3, 8, 9},  {4, 9, 5},  {2, 4, 11},  {6, 2, 10}, {8, 6, 7},   {9, 8, 1}};
  for (auto& p : v) p = p / p.Norm();
  for (int l = 0; l < levels; ++l) {
    std::map<std::pair<std::uint32_t, std::uint32_t>, std::uint32_t> mid;
    auto midpoint = [&](std::uint32_t a, std::uint32_t b) {
      const auto key = std::make_pair(std::min(a, b), std::max(a, b));
      auto it = mid.find(key);
      if (it != mid.end()) return it->second;
      Vec3d m = (v[a] + v[b]) * 0.5;
      m = m / m.Norm();
      v.push_back(m);
      mid[key] = std::uint32_t(v.size() - 1);
      return std::uint32_t(v.size() - 1);
    };
    std::vector<Face> g;
    for (const Face& x : f) {
      const std::uint32_t ab = midpoint(x[0], x[1]), bc = midpoint(x[1], x[2]), ca = midpoint(x[2], x[0]);
      g.push_back({x[0], ab, ca});
      g.push_back({x[1], bc, ab});
      g.push_back({x[2], ca, bc});
      g.push_back({ab, bc, ca});
    }
    f.swap(g);
  }
  MeshArrays m;
  for (const auto& p : v) m.vertices.push_back(c + p * r);
  m.faces = f;
  return m;
}

// Torus of radii R and r, n × m quads split into triangles.
MeshArrays torus(double R, double r, int n, int m) {
  MeshArrays t;
  const double pi = 3.14159265358979323846;
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      const double u = 2 * pi * i / n, w = 2 * pi * j / m;
      t.vertices.push_back(Vec3d((R + r * std::cos(w)) * std::cos(u), (R + r * std::cos(w)) * std::sin(u), r * std::sin(w)));
    }
  auto id = [&](int i, int j) { return std::uint32_t(((i + n) % n) * m + (j + m) % m); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < m; ++j) {
      t.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return t;
}

// A sphere of radius 1 from its south pole up to latitude `top` (radians), open there: a rim circle
// of n segments; m rows of latitude, a fan at the pole.
MeshArrays openSphere(double top, int n, int m) {
  const double pi = 3.14159265358979323846;
  MeshArrays s;
  s.vertices.push_back(Vec3d(0, 0, -1));
  for (int j = 1; j <= m; ++j) {
    const double lat = -pi / 2 + (top + pi / 2) * j / m;
    for (int i = 0; i < n; ++i)
      s.vertices.push_back(Vec3d(std::cos(lat) * std::cos(2 * pi * i / n), std::cos(lat) * std::sin(2 * pi * i / n),
                                 std::sin(lat)));
  }
  auto id = [&](int i, int j) { return std::uint32_t(1 + (j - 1) * n + (i + n) % n); };
  for (int i = 0; i < n; ++i) s.faces.push_back({0, id(i + 1, 1), id(i, 1)});
  for (int j = 1; j < m; ++j)
    for (int i = 0; i < n; ++i) {
      s.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      s.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return s;
}

// The faces of `m` whose centroid passes `keep`, with the unreferenced vertices dropped.
template <class Keep>
MeshArrays keepFaces(const MeshArrays& m, Keep keep) {
  MeshArrays out;
  std::vector<std::int64_t> remap(m.vertices.size(), -1);
  for (const auto& f : m.faces) {
    if (!keep((m.vertices[f[0]] + m.vertices[f[1]] + m.vertices[f[2]]) / 3.0)) continue;
    Face g;
    for (int k = 0; k < 3; ++k) {
      if (remap[f[k]] < 0) {
        remap[f[k]] = std::int64_t(out.vertices.size());
        out.vertices.push_back(m.vertices[f[k]]);
      }
      g[k] = std::uint32_t(remap[f[k]]);
    }
    out.faces.push_back(g);
  }
  return out;
}

// The surface of the cube [0, s]³, n × n quads per side, shared vertices along the edges.
MeshArrays cube(double s, int n) {
  MeshArrays m;
  std::map<std::tuple<int, int, int>, std::uint32_t> ids;
  auto vid = [&](int x, int y, int z) {
    const auto key = std::make_tuple(x, y, z);
    auto it = ids.find(key);
    if (it != ids.end()) return it->second;
    m.vertices.push_back(Vec3d(s * x / n, s * y / n, s * z / n));
    ids[key] = std::uint32_t(m.vertices.size() - 1);
    return std::uint32_t(m.vertices.size() - 1);
  };
  // For each axis and side, a grid in the other two axes, oriented outwards.
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          auto p = [&](int a, int b) {
            int c[3];
            c[axis] = side * n;
            c[(axis + 1) % 3] = a;
            c[(axis + 2) % 3] = b;
            return vid(c[0], c[1], c[2]);
          };
          const std::uint32_t v00 = p(i, j), v10 = p(i + 1, j), v11 = p(i + 1, j + 1), v01 = p(i, j + 1);
          if (side == 1) {
            m.faces.push_back({v00, v10, v11});
            m.faces.push_back({v00, v11, v01});
          } else {
            m.faces.push_back({v00, v11, v10});
            m.faces.push_back({v00, v01, v11});
          }
        }
  return m;
}

MeshArrays concat(const MeshArrays& a, const MeshArrays& b) {
  MeshArrays m = a;
  const std::uint32_t off = std::uint32_t(a.vertices.size());
  m.vertices.insert(m.vertices.end(), b.vertices.begin(), b.vertices.end());
  for (const auto& f : b.faces) m.faces.push_back({f[0] + off, f[1] + off, f[2] + off});
  return m;
}

struct Checked {
  MeshArrays out;
  RemeshStat st;
  growth::MeshMeasures in, res;
  double maxOutToIn = 0, maxInToOut = 0;
};

// Remeshes and checks what holds for every input: edges >= d, manifold, no intersections, vertices
// on the input, face quality.
Checked remeshChecked(const MeshArrays& input, const RemeshParams& p) {
  Checked c;
  remesh(input, false, c.out, p, c.st);
  const double d = c.st.sphereDiameter;
  EXPECT_GT(c.st.faces, 0u);
  EXPECT_EQ(c.out.faceQuality.size(), c.out.faces.size());
  c.in = growth::measure(input);
  c.res = growth::measure(c.out);
  EXPECT_GE(c.res.edgeMin, d * (1 - 1e-12));
  EXPECT_EQ(c.res.nonManifoldEdges, 0u);
  EXPECT_EQ(c.res.nonManifoldVertices, 0u);
  EXPECT_EQ(c.res.selfIntersectingPairs, 0u);
  EXPECT_EQ(c.res.inconsistentEdges, 0u);
  EXPECT_EQ(c.st.boundaryLoops, c.res.boundaryLoops); // the log's count is the output's
  const growth::MeshDistance toIn(input), toOut(c.out);
  for (const Vec3d& v : c.out.vertices) c.maxOutToIn = std::max(c.maxOutToIn, toIn.distance(v));
  for (const Vec3d& v : input.vertices) c.maxInToOut = std::max(c.maxInToOut, toOut.distance(v));
  EXPECT_LE(c.maxOutToIn, 1e-9 * d);
  return c;
}

TEST(Remesh, SphereKeepsTopologyAndLiesOnTheInput) {
  const MeshArrays s = icosphere(4, 1.0); // 5120 faces, mean edge about 0.06
  RemeshParams p;
  p.sphereDiameter = 0.1;
  const Checked c = remeshChecked(s, p);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_EQ(c.res.genus, 0);
  EXPECT_LE(c.maxInToOut, 0.3 * p.sphereDiameter);
  EXPECT_GT(c.st.qualityAvg, 0.85);
}

TEST(Remesh, TorusKeepsGenusOne) {
  const MeshArrays t = torus(1.0, 0.35, 96, 36);
  RemeshParams p;
  p.sphereDiameter = 0.08;
  const Checked c = remeshChecked(t, p);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_EQ(c.res.genus, 1);
  EXPECT_LE(c.maxInToOut, 0.3 * p.sphereDiameter);
}

TEST(Remesh, DefaultDiameterIsTheMeanEdgeLength) {
  const MeshArrays t = torus(1.0, 0.35, 96, 36);
  MeshArrays out;
  RemeshStat st;
  remesh(t, false, out, RemeshParams(), st);
  EXPECT_NEAR(st.sphereDiameter, growth::spherepack::defaultRemeshDiameter(t), 1e-12);
  EXPECT_NEAR(st.sphereDiameter, growth::measure(t).edgeMean, 1e-12);
  EXPECT_EQ(growth::measure(out).genus, 1);
}

TEST(Remesh, OpenMeshesStayOpen) {
  // A hemisphere: one boundary loop, 2π long (about 60 d: beyond the border limit).
  const MeshArrays half = openSphere(0, 96, 24);
  // A sphere with a small hole: its rim is 2π·cos(68°) = 2.35 long, 23 d, within the border limit,
  // so only the rule that keeps regions beyond the input's boundary open keeps it.
  const MeshArrays holed = openSphere(68 * 3.14159265358979323846 / 180, 96, 40);
  // A jagged rim (the faces of an icosphere below a plane): the rim is a feature line whose turns
  // are corners, and its samples keep d from them; the output's border stays within d of it.
  const MeshArrays jagged = keepFaces(icosphere(4, 1.0), [](const Vec3d& c) { return c[2] < 0.93; });
  RemeshParams p;
  p.sphereDiameter = 0.1;
  for (const MeshArrays* m : {&half, &holed, &jagged}) {
    const Checked c = remeshChecked(*m, p);
    EXPECT_EQ(c.in.boundaryLoops, 1u);
    EXPECT_EQ(c.res.boundaryLoops, 1u);
    EXPECT_EQ(c.res.components, 1u);
    EXPECT_EQ(c.res.genus, 0);
    if (m == &holed) { EXPECT_EQ(c.st.regionsOutside, 1u); }
    // The rim is a feature line: the output's border runs along it.
    EXPECT_LE(c.maxInToOut, (m == &jagged ? 1.0 : 0.3) * p.sphereDiameter);
  }
}

TEST(Remesh, EveryComponentIsMeshed) {
  const MeshArrays two = concat(icosphere(3, 1.0), torus(1.0, 0.3, 64, 24));
  // The torus around the sphere, out of its way.
  MeshArrays m = two;
  for (size_t i = icosphere(3, 1.0).vertices.size(); i < m.vertices.size(); ++i) m.vertices[i][0] += 4;
  RemeshParams p;
  p.sphereDiameter = 0.1;
  const Checked c = remeshChecked(m, p);
  EXPECT_EQ(c.in.components, 2u);
  EXPECT_EQ(c.res.components, 2u);
  EXPECT_EQ(c.res.genus, 1);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_GE(c.st.componentsStarted, 2u);
}

// A scanned surface's triangulation: neighbouring faces meet at any angle, but at the scale of d
// the surface is smooth. An icosphere (20,480 faces, mean edge 0.031) with every vertex moved
// radially by a seeded uniform amount of up to `noise` mean edges. Lines of edges whose faces are
// more than 30° apart, longer than 2 d, are no creases unless the surface d to either side turns
// too: at d = 0.1 none is left, and at d = 0.04 (noise 0.5) the few left do not cut the sphere.
// With every such line a crease, the growth left strips along them open (d = 0.04: 2,468 crease
// edges, 4 components, 6 boundary loops, faces removed by the clean-up).
TEST(Remesh, NoisySurfaceHasNoCreases) {
  for (const std::pair<double, double>& noiseAndD : {std::make_pair(0.3, 0.1), std::make_pair(0.5, 0.04)}) {
    const double noise = noiseAndD.first, d = noiseAndD.second;
    MeshArrays s = icosphere(5, 1.0);
    const double meanEdge = growth::measure(s).edgeMean;
    std::mt19937_64 rng(7);
    std::uniform_real_distribution<double> u(-noise, noise);
    for (Vec3d& v : s.vertices) v = v * (1 + u(rng) * meanEdge);
    RemeshParams p;
    p.sphereDiameter = d;
    const Checked c = remeshChecked(s, p);
    if (d == 0.1) { EXPECT_EQ(c.st.creaseEdges, 0u); }
    EXPECT_EQ(c.res.components, 1u) << "d = " << d;
    EXPECT_EQ(c.res.boundaryLoops, 0u) << "d = " << d;
    EXPECT_EQ(c.res.genus, 0) << "d = " << d;
    EXPECT_EQ(c.st.facesRemoved, 0u) << "d = " << d;
    EXPECT_LE(c.maxInToOut, d) << "d = " << d; // the noise is up to 0.39 d at d = 0.04
  }
}

// A sphere with a lace of holes (the fans of vertices at least 2.5 mean edges apart removed: 876
// holes, bridges between them of about a quarter of d = 0.06): the regions over the holes stay
// open and cut off pieces of a few faces. They are dropped (RemeshParams::minPieceFaces), but an
// input component keeps its largest piece however small: a small sphere beside the lace.
TEST(Remesh, SmallPiecesAreDroppedButNotComponents) {
  MeshArrays s = icosphere(5, 1.0);
  const double e = growth::measure(s).edgeMean;
  std::mt19937_64 rng(3);
  std::vector<std::uint32_t> order(s.vertices.size());
  std::iota(order.begin(), order.end(), 0u);
  std::shuffle(order.begin(), order.end(), rng);
  std::vector<Vec3d> centres;
  std::vector<char> hole(s.vertices.size(), 0);
  for (const std::uint32_t v : order) {
    bool apart = true;
    for (const Vec3d& q : centres) apart = apart && (q - s.vertices[v]).Norm() >= 2.5 * e;
    if (apart) {
      centres.push_back(s.vertices[v]);
      hole[v] = 1;
    }
  }
  MeshArrays holed = s;
  holed.faces.clear();
  for (const auto& f : s.faces)
    if (!hole[f[0]] && !hole[f[1]] && !hole[f[2]]) holed.faces.push_back(f);
  const MeshArrays lace = keepFaces(holed, [](const Vec3d&) { return true; }); // without the holes' centres
  RemeshParams p;
  p.sphereDiameter = 0.06;
  p.minPieceFaces = 0;
  p.closeHoles = false; // the rule alone (the hole pass may take pieces into the rings of its closures)
  const Checked all = remeshChecked(lace, p);
  EXPECT_EQ(all.in.components, 1u);
  EXPECT_GT(all.in.boundaryLoops, 800u);
  EXPECT_GT(all.res.components, 3u); // the fragments the rule is for
  p.minPieceFaces = RemeshParams().minPieceFaces;
  const Checked kept = remeshChecked(lace, p);
  EXPECT_EQ(kept.res.components, 1u);
  EXPECT_EQ(kept.st.piecesDropped + 1, all.res.components);
  // A sphere of radius 0.1 beside it: one piece of fewer faces than the limit, kept.
  MeshArrays both = concat(lace, icosphere(3, 0.1, Vec3d(3, 0, 0)));
  p.minPieceFaces = 1000;
  const Checked two = remeshChecked(both, p);
  EXPECT_EQ(two.res.components, 2u);
  EXPECT_LT(two.res.perComponent.back().faces, 1000u);
}

TEST(Remesh, CubeWithCreasesIsClosedAndManifold) {
  const MeshArrays b = cube(1.0, 12);
  RemeshParams p;
  p.sphereDiameter = 0.1;
  const Checked c = remeshChecked(b, p);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_EQ(c.res.genus, 0);
}

// Item 2: creases and corners. The cube's 8 corners are output vertices exactly, its 12 edges lie
// on the output (every point of them within rounding), no face bends over an edge (its three
// vertices lie on one side of the cube), and every input vertex is within 0.3 d of the output.
TEST(RemeshFeatures, CubeKeepsCornersAndEdges) {
  for (const double d : {0.1, 0.093, 0.17}) {
    const MeshArrays b = cube(1.0, 12);
    RemeshParams p;
    p.sphereDiameter = d;
    const Checked c = remeshChecked(b, p);
    EXPECT_EQ(c.res.boundaryLoops, 0u);
    EXPECT_EQ(c.res.genus, 0);
    EXPECT_EQ(c.st.featureCorners, 8u);
    EXPECT_EQ(c.st.creaseEdges, 12u * 12u);
    EXPECT_EQ(c.st.featureVerticesSkipped, 0u);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d x(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
      bool found = false;
      for (const Vec3d& v : c.out.vertices) found = found || v == x;
      EXPECT_TRUE(found) << "corner " << corner << " at d = " << d;
    }
    const growth::MeshDistance toOut(c.out);
    double worst = 0;
    for (int axis = 0; axis < 3; ++axis)
      for (int corner = 0; corner < 4; ++corner)
        for (int k = 0; k <= 200; ++k) {
          Vec3d x(0, 0, 0);
          x[axis] = k / 200.0;
          x[(axis + 1) % 3] = corner & 1;
          x[(axis + 2) % 3] = (corner >> 1) & 1;
          worst = std::max(worst, toOut.distance(x));
        }
    EXPECT_LE(worst, 1e-12) << "d = " << d;
    EXPECT_LE(c.maxInToOut, 0.3 * d);
    size_t bent = 0;
    for (const auto& f : c.out.faces) {
      bool flat = false;
      for (int axis = 0; axis < 3 && !flat; ++axis)
        for (const double side : {0.0, 1.0}) {
          bool all = true;
          for (const auto v : f) all = all && std::abs(c.out.vertices[v][axis] - side) < 1e-12;
          flat = flat || all;
        }
      bent += flat ? 0 : 1;
    }
    EXPECT_EQ(bent, 0u) << "faces over an edge of the cube at d = " << d;
  }
}

// A sharp concave crease: two unit squares folded along a common side to an interior angle of 30°.
// Within about 1.9 d of the crease the two sides are closer than d to each other; both are meshed
// (vertices of two patches may be closer than d, and no edge joins them), so the fold keeps its one
// border and every edge is at least d. Feature vertices keep d from every vertex, so near the ends of
// the crease the border's points of one side keep the other side's vertices off: every input vertex
// is within d of the output (0.69 d), not 0.3 d.
TEST(RemeshFeatures, SharpConcaveCreaseKeepsBothSides) {
  const double pi = 3.14159265358979323846, a = 30 * pi / 180;
  const int n = 24;
  MeshArrays m;
  for (int j = 0; j <= 2 * n; ++j)
    for (int i = 0; i <= n; ++i) {
      const double x = double(i) / n, t = double(j - n) / n;
      m.vertices.push_back(t <= 0 ? Vec3d(x, -t, 0) : Vec3d(x, t * std::cos(a), t * std::sin(a)));
    }
  auto id = [&](int i, int j) { return std::uint32_t(j * (n + 1) + i); };
  for (int j = 0; j < 2 * n; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  RemeshParams p;
  p.sphereDiameter = 0.1;
  const Checked c = remeshChecked(m, p);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.res.boundaryLoops, 1u);
  EXPECT_EQ(c.st.featureCorners, 4u + 2u); // the square's corners and the crease's ends
  EXPECT_LE(c.maxInToOut, 1.0 * p.sphereDiameter);
  // Both sides hold faces within 1.5 d of the crease.
  size_t nearA = 0, nearB = 0;
  for (const auto& f : c.out.faces) {
    const Vec3d g = (c.out.vertices[f[0]] + c.out.vertices[f[1]] + c.out.vertices[f[2]]) / 3.0;
    if (std::abs(g[2]) < 1e-12 && g[1] < 1.5 * p.sphereDiameter) ++nearA;
    if (g[2] > 1e-12 && g.Norm() > 0 && std::hypot(g[1], g[2]) < 1.5 * p.sphereDiameter) ++nearB;
  }
  EXPECT_GT(nearA, 10u);
  EXPECT_GT(nearB, 10u);
}

// A closed crease line without corners: the rims of a capped cylinder are packed as loops, and the
// rim circles lie on the output within the chord's sagitta.
TEST(RemeshFeatures, CylinderRimsAreClosedCreaseLoops) {
  MeshArrays m;
  const int n = 96, h = 20;
  const double pi = 3.14159265358979323846;
  for (int j = 0; j <= h; ++j)
    for (int i = 0; i < n; ++i)
      m.vertices.push_back(Vec3d(std::cos(2 * pi * i / n), std::sin(2 * pi * i / n), 1.0 * j / h));
  const std::uint32_t bottom = std::uint32_t(m.vertices.size()), top = bottom + 1;
  m.vertices.push_back(Vec3d(0, 0, 0));
  m.vertices.push_back(Vec3d(0, 0, 1));
  auto id = [&](int i, int j) { return std::uint32_t(j * n + (i + n) % n); };
  for (int j = 0; j < h; ++j)
    for (int i = 0; i < n; ++i) {
      m.faces.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      m.faces.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  for (int i = 0; i < n; ++i) {
    m.faces.push_back({bottom, id(i + 1, 0), id(i, 0)});
    m.faces.push_back({top, id(i, h), id(i + 1, h)});
  }
  RemeshParams p;
  p.sphereDiameter = 0.12;
  const Checked c = remeshChecked(m, p);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_EQ(c.res.genus, 0);
  EXPECT_EQ(c.st.featureCorners, 0u);
  EXPECT_EQ(c.st.creaseEdges, size_t(2 * n));
  const growth::MeshDistance toOut(c.out);
  double worst = 0;
  for (int k = 0; k < 1000; ++k)
    for (const double z : {0.0, 1.0})
      worst = std::max(worst, toOut.distance(Vec3d(std::cos(2 * pi * k / 1000), std::sin(2 * pi * k / 1000), z)));
  // The rims are sampled with chords of at most about 1.2 d on the 96-gon: sagitta (1.2 d)² / 8.
  EXPECT_LE(worst, 1.44 * p.sphereDiameter * p.sphereDiameter / 8 + 1e-3);
  EXPECT_LE(c.maxInToOut, 0.3 * p.sphereDiameter);
}

// A crease angle above every dihedral angle turns the features off: the cube's corners are then
// not vertices (the growth rounds the edges), which is what the features change.
TEST(RemeshFeatures, CreaseAngleTurnsFeaturesOff) {
  const MeshArrays b = cube(1.0, 12);
  RemeshParams p;
  p.sphereDiameter = 0.1;
  p.creaseAngleDeg = 180;
  const Checked c = remeshChecked(b, p);
  EXPECT_EQ(c.st.creaseEdges, 0u);
  size_t corners = 0;
  for (const Vec3d& v : c.out.vertices)
    for (int k = 0; k < 8; ++k) corners += v == Vec3d(k & 1, (k >> 1) & 1, (k >> 2) & 1) ? 1 : 0;
  EXPECT_LT(corners, 8u);
}

// A CAD export: the cube as 12 triangles. Its mean edge length (the cube's size) would allow no
// mesh; the default d gives about 1,000 vertices, with every corner exact and every edge kept.
TEST(RemeshFeatures, CoarseCadCubeAtTheDefaultD) {
  const MeshArrays b = cube(2.0, 1);
  ASSERT_EQ(b.faces.size(), 12u);
  const Checked c = remeshChecked(b, RemeshParams());
  const double d = c.st.sphereDiameter;
  EXPECT_NEAR(d, std::sqrt(24.0 / (0.86602540378443864676 * 1000)), 1e-12);
  EXPECT_GT(c.out.vertices.size(), 700u);
  EXPECT_LT(c.out.vertices.size(), 1300u);
  EXPECT_EQ(c.res.boundaryLoops, 0u);
  EXPECT_EQ(c.res.genus, 0);
  EXPECT_EQ(c.maxInToOut, 0.0); // the 8 corners are vertices
}

// Flat faces bounded by crease lines get a hexagonal packing, not a square one: the splits of
// border distance 1 to 3 share one level (kAlikeSplitDistance). With sec. 3.5's order as written
// the rows grown along the cube's edges lock into squares (two triangles of Q_t 0.87 each), and the
// mean Q_t of this cube is 0.89; IER gets about 0.94 on such parts.
TEST(RemeshFeatures, FlatFacesAreNearlyEquilateral) {
  for (const double d : {0.05, 0.037}) {
    const MeshArrays b = cube(1.0, 24);
    RemeshParams p;
    p.sphereDiameter = d;
    const Checked c = remeshChecked(b, p);
    EXPECT_EQ(c.res.boundaryLoops, 0u) << "d = " << d;
    EXPECT_EQ(c.res.genus, 0) << "d = " << d;
    EXPECT_GT(c.st.qualityAvg, 0.95) << "d = " << d;
    // Most faces are close to equilateral: Q_t above 0.95 (a right isosceles triangle has 0.87;
    // with the square lattice 16 % of the faces are above 0.95, here 79 %).
    size_t good = 0;
    for (double q : c.out.faceQuality) good += q > 0.95 ? 1 : 0;
    EXPECT_GT(double(good), 0.6 * double(c.out.faceQuality.size())) << "d = " << d;
  }
}

// The hole pass (closeHoles on the input surface): a flat ellipsoid whose rim turns within a few d
// leaves loops after the growth and the clean-up; the pass closes them with the packing's own
// vertices (every edge still >= d, no intersection: remeshChecked), and without it they stay.
TEST(Remesh, HolePassClosesTheLoopsOfAThinPart) {
  MeshArrays e = icosphere(5, 1.0);
  for (Vec3d& v : e.vertices) v = Vec3d(v[0], 0.7 * v[1], 0.1 * v[2]);
  RemeshParams p;
  p.sphereDiameter = 0.05;
  p.creaseAngleDeg = 180; // no crease: the rim is curved, not sharp
  const Checked with = remeshChecked(e, p);
  EXPECT_EQ(with.res.boundaryLoops, 0u);
  EXPECT_EQ(with.res.components, 1u);
  EXPECT_EQ(with.res.genus, 0);
  EXPECT_GT(with.st.holesClosed, 0u);
  p.closeHoles = false;
  const Checked without = remeshChecked(e, p);
  EXPECT_GT(without.res.boundaryLoops, 0u);
  EXPECT_EQ(without.st.holesClosed, 0u);
}

// A single triangle with a 45° corner: the first points of its two sides near that corner are
// closer than d, one is left out and the side joined across it, so the corner keeps its face.
TEST(RemeshFeatures, AcuteCornerOfASingleTriangle) {
  MeshArrays t;
  t.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  t.faces = {{0, 1, 2}};
  const Checked c = remeshChecked(t, RemeshParams());
  EXPECT_EQ(c.res.boundaryLoops, 1u);
  EXPECT_EQ(c.res.components, 1u);
  EXPECT_EQ(c.maxInToOut, 0.0);
}

TEST(Remesh, SameMeshTwice) {
  const MeshArrays t = torus(1.0, 0.35, 80, 30);
  RemeshParams p;
  p.sphereDiameter = 0.09;
  MeshArrays a, b;
  RemeshStat sa, sb;
  remesh(t, false, a, p, sa);
  remesh(t, false, b, p, sb);
  ASSERT_EQ(a.vertices.size(), b.vertices.size());
  ASSERT_EQ(a.faces, b.faces);
  for (size_t i = 0; i < a.vertices.size(); ++i) EXPECT_EQ(a.vertices[i], b.vertices[i]);
}

TEST(Remesh, InvariantsHoldAtEveryInsertion) {
  const MeshArrays s = icosphere(3, 1.0);
  RemeshParams p;
  p.sphereDiameter = 0.15;
  p.checkInvariants = true;
  MeshArrays out;
  RemeshStat st;
  EXPECT_NO_THROW(remesh(s, false, out, p, st));
}

TEST(Remesh, FloatStorageIsChecked) {
  // Near the origin, float rounding keeps every edge at d within 1e-6; 1000 away, it rounds by up
  // to 3e-5 per coordinate, and the mesh as stored comes with a warning.
  for (const double offset : {0.0, 1000.0}) {
    MeshArrays s = icosphere(3, 1.0);
    for (auto& v : s.vertices) v = v + Vec3d(offset, 0, 0);
    RemeshParams p;
    p.sphereDiameter = 0.15;
    MeshArrays out;
    RemeshStat st;
    remesh(s, true, out, p, st);
    if (offset == 0) {
      EXPECT_GT(st.smallestEdge, 0.15 * (1 - 1e-6));
      EXPECT_TRUE(st.warnings.empty());
    } else if (st.smallestEdge < 0.15 * (1 - 1e-4)) {
      ASSERT_FALSE(st.warnings.empty());
      EXPECT_NE(st.warnings[0].find("float"), std::string::npos);
    }
  }
}

// Bad input.
std::string errorOf(const MeshArrays& m, const RemeshParams& p = RemeshParams()) {
  MeshArrays out;
  RemeshStat st;
  try {
    remesh(m, false, out, p, st);
  } catch (const growth::Error& e) {
    EXPECT_TRUE(out.vertices.empty());
    return e.what();
  }
  return std::string();
}

TEST(RemeshBadInput, PointCloud) {
  MeshArrays m = icosphere(2, 1.0);
  m.faces.clear();
  EXPECT_NE(errorOf(m).find("no faces"), std::string::npos);
}

TEST(RemeshBadInput, NonManifoldEdgeSaysWhere) {
  MeshArrays m = icosphere(2, 1.0);
  const auto f = m.faces[0];
  m.vertices.push_back(Vec3d(0, 0, 3));
  m.faces.push_back({f[0], f[1], std::uint32_t(m.vertices.size() - 1)});
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("not manifold"), std::string::npos);
  EXPECT_NE(e.find("edge between vertices " + std::to_string(std::min(f[0], f[1]))), std::string::npos);
}

TEST(RemeshBadInput, NonManifoldVertexSaysWhere) {
  // Two tetrahedra sharing one corner.
  MeshArrays m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {-1, 0, 0}, {0, -1, 0}, {0, 0, -1}};
  m.faces = {{0, 2, 1}, {0, 1, 3}, {0, 3, 2}, {1, 2, 3}, {0, 4, 5}, {0, 6, 4}, {0, 5, 6}, {4, 6, 5}};
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("vertex 0 "), std::string::npos) << e;
  EXPECT_NE(e.find("2 separate fans"), std::string::npos) << e;
}

TEST(RemeshBadInput, ZeroAreaFace) {
  MeshArrays m = icosphere(2, 1.0);
  const auto f = m.faces[5];
  m.vertices[f[2]] = m.vertices[f[0]];
  const std::string e = errorOf(m);
  EXPECT_NE(e.find("Face 5 "), std::string::npos) << e;
  EXPECT_NE(e.find("zero area"), std::string::npos) << e;
}

// A sliver (what a CAD boolean leaves where it split an edge: a face of height about 1e-10) joins its
// neighbours but holds no vertex; on an edge of a cube the crease has a gap there, and the mesh is
// still closed, manifold, with every corner.
TEST(Remesh, SliversAreNoObstacle) {
  for (const bool onCrease : {false, true}) {
    MeshArrays b = cube(1.0, 12);
    // The faces a–b–c and b–a–e sharing the edge a–b; a–b on the cube's edge or inside a side.
    size_t f1 = 0, f2 = 0;
    bool found = false;
    for (size_t i = 0; i < b.faces.size() && !found; ++i)
      for (size_t j = i + 1; j < b.faces.size() && !found; ++j)
        for (int e = 0; e < 3 && !found; ++e)
          for (int k = 0; k < 3 && !found; ++k)
            if (b.faces[i][e] == b.faces[j][(k + 1) % 3] && b.faces[i][(e + 1) % 3] == b.faces[j][k]) {
              const Vec3d ni = (b.vertices[b.faces[i][1]] - b.vertices[b.faces[i][0]]) ^ (b.vertices[b.faces[i][2]] - b.vertices[b.faces[i][0]]);
              const Vec3d nj = (b.vertices[b.faces[j][1]] - b.vertices[b.faces[j][0]]) ^ (b.vertices[b.faces[j][2]] - b.vertices[b.faces[j][0]]);
              const bool crease = std::abs(ni * nj) < 1e-12;
              const Vec3d mid = (b.vertices[b.faces[i][e]] + b.vertices[b.faces[i][(e + 1) % 3]]) * 0.5;
              const bool awayFromCorners = mid[0] > 0.3 && mid[0] < 0.7 && mid[1] > 0.3 && mid[1] < 0.7;
              if (crease == onCrease && (awayFromCorners || onCrease)) {
                f1 = i;
                f2 = j;
                found = true;
                const std::uint32_t a = b.faces[i][e], bb = b.faces[i][(e + 1) % 3], c = b.faces[i][(e + 2) % 3];
                b.vertices.push_back(mid + Vec3d(1e-10, 1e-10, 1e-10));
                const std::uint32_t m = std::uint32_t(b.vertices.size() - 1);
                b.faces[f1] = {a, m, c};
                b.faces.push_back({m, bb, c});
                b.faces.push_back({a, bb, m});
              }
            }
    ASSERT_TRUE(found);
    (void)f2;
    RemeshParams p;
    p.sphereDiameter = 0.1;
    const Checked c = remeshChecked(b, p);
    EXPECT_EQ(c.st.inputSlivers, 1u);
    EXPECT_EQ(c.res.boundaryLoops, 0u);
    EXPECT_EQ(c.res.genus, 0);
    for (int corner = 0; corner < 8; ++corner) {
      const Vec3d x(corner & 1, (corner >> 1) & 1, (corner >> 2) & 1);
      bool hit = false;
      for (const Vec3d& v : c.out.vertices) hit = hit || v == x;
      EXPECT_TRUE(hit) << "corner " << corner;
    }
  }
}

TEST(RemeshBadInput, OnlySlivers) {
  MeshArrays m;
  m.vertices = {{0, 0, 0}, {1, 0, 0}, {2, 0, 0}, {3, 0, 0}};
  m.faces = {{0, 1, 2}, {1, 3, 2}};
  EXPECT_NE(errorOf(m).find("zero area"), std::string::npos);
}

TEST(RemeshBadInput, DiameterTooSmallOrTooLarge) {
  const MeshArrays m = icosphere(2, 1.0);
  RemeshParams p;
  p.sphereDiameter = 1e-5;
  EXPECT_NE(errorOf(m, p).find("too small"), std::string::npos);
  p.sphereDiameter = 5;
  EXPECT_NE(errorOf(m, p).find("too large"), std::string::npos);
}

TEST(RemeshBadInput, TheInputIsNotChanged) {
  const MeshArrays m = torus(1.0, 0.35, 40, 16);
  const MeshArrays copy = m;
  MeshArrays out;
  RemeshStat st;
  remesh(m, false, out, RemeshParams(), st);
  EXPECT_EQ(m.faces, copy.faces);
  for (size_t i = 0; i < m.vertices.size(); ++i) EXPECT_EQ(m.vertices[i], copy.vertices[i]);
}

} // namespace
