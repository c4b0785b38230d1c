// The sphere-packing remesher (remesher.h): the input mesh checked and indexed, the growth on its
// triangles, the regions with the input's boundary kept open, and the reconstruction's clean-up
// and output (packer_steps.h).
#include "remesher.h"

#include "feature_lines.h"

#include "candidates.h"
#include "crossing.h"
#include "packer_steps.h"
#include "region_triangulation.h"
#include "splats.h"
#include "stored_positions.h"
#include "vertex_grid.h"

#include <growth/bucket_queue.h>
#include <growth/error.h>
#include <growth/stopwatch.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <utility>

namespace growth {
namespace spherepack {

using namespace detail;

namespace {

constexpr std::uint32_t kNone = 0xffffffffu;
// A face whose height is below this share of its longest edge is a sliver (InputTriangle::sliver).
constexpr double kSliverHeight = 1e-8;
// Triangles whose normal makes an angle of more than 120° with a vertex's normal take no part in
// its candidates: the other side of a part thinner than d, not the surface around the vertex (a
// crease of up to 120° still joins its two sides).
constexpr double kMinFacingDot = -0.5;
// Vertices of two patches whose normals make more than 60° may be closer than d (MeshGrowth::keepsOff).
constexpr double kApartDot = 0.5;

// Whether the triangle (a, b, c) has an edge shorter than d (the growth's edges are d up to
// rounding: the test leaves a relative 1e-9 of d²).
bool hasEdgeBelow(const Vec3d& a, const Vec3d& b, const Vec3d& c, double d) {
  const double shortest = d * d * (1 - 1e-9);
  return (b - a).SquaredNorm() < shortest || (c - b).SquaredNorm() < shortest || (a - c).SquaredNorm() < shortest;
}

std::string vecText(const Vec3d& p) { return "(" + fmt(p[0]) + ", " + fmt(p[1]) + ", " + fmt(p[2]) + ")"; }

// An input triangle: its corners, unit normal and what the inside test needs.
struct InputTriangle {
  Vec3d a, e0, e1, n;     // corner a, edges e0 = b − a and e1 = c − a, unit normal
  double d00, d01, d11, inv; // Gram matrix of e0, e1 and the inverse of its determinant
  double area;
  Vec3d centre;  // the centroid and the largest distance of a corner from it: a bounding ball
  double radius;
  bool sliver;
  // Barycentric coordinates (u, v, w) of x (projected onto the plane): x ≈ a + v·e0 + w·e1.
  void barycentric(const Vec3d& x, double& u, double& v, double& w) const {
    const Vec3d p = x - a;
    const double d20 = p * e0, d21 = p * e1;
    v = (d11 * d20 - d01 * d21) * inv;
    w = (d00 * d21 - d01 * d20) * inv;
    u = 1 - v - w;
  }
  // The smallest barycentric coordinate: >= 0 inside.
  double insideness(const Vec3d& x) const {
    double u, v, w;
    barycentric(x, u, v, w);
    return std::min(u, std::min(v, w));
  }
};

// Closest point of triangle (a, b, c) to p (Ericson, Real-Time Collision Detection, 5.1.5), and its
// feature: 0 the interior, 1 + e the edge e (0: a–b, 1: b–c, 2: c–a), 4 + k the corner k.
Vec3d closestOnTriangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c, int& feature) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab * ap, d2 = ac * ap;
  if (d1 <= 0 && d2 <= 0) { feature = 4; return a; }
  const Vec3d bp = p - b;
  const double d3 = ab * bp, d4 = ac * bp;
  if (d3 >= 0 && d4 <= d3) { feature = 5; return b; }
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) { feature = 1; return a + ab * (d1 / (d1 - d3)); }
  const Vec3d cp = p - c;
  const double d5 = ab * cp, d6 = ac * cp;
  if (d6 >= 0 && d5 <= d6) { feature = 6; return c; }
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) { feature = 3; return a + ac * (d2 / (d2 - d6)); }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    feature = 2;
    return b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6)));
  }
  feature = 0;
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

// The input mesh, checked: triangles, which corners and edges lie on its boundary, its components.
struct InputMesh {
  std::vector<Vec3d> vertices;
  std::vector<Triangle> faces;
  std::vector<InputTriangle> tri;
  std::vector<std::uint8_t> boundaryEdges; // per face: bit e set when its edge e has no other face
  std::vector<char> boundaryVertex;
  size_t components = 0, boundaryEdgeCount = 0, slivers = 0;
  double meanEdge = 0, area = 0;
  Box3d box;
  // Features: the crease edges (two faces whose normals differ by more than the crease angle), each
  // with the mean of its faces' normals, and the boundary edges (f0 == f1), with their face's normal; per face its patch (the faces reached from it without
  // crossing a crease: the smallest face index of them); per vertex the angle-weighted normal.
  struct CreaseEdge {
    std::uint32_t u, v, f0, f1;
    Vec3d n;
  };
  std::vector<CreaseEdge> creases;
  std::vector<std::uint32_t> patch; // (until keepLongCreases: the union-find parents)
  std::vector<std::uint32_t> component; // per face: its edge-connected component (smallest face index)
  std::vector<Vec3d> vertexNormal;
};

struct EdgeRef {
  std::uint32_t lo, hi, face;
  std::uint8_t e;
  bool operator<(const EdgeRef& o) const {
    return lo != o.lo ? lo < o.lo : hi != o.hi ? hi < o.hi : face < o.face;
  }
};

std::uint32_t findRoot(std::vector<std::uint32_t>& parent, std::uint32_t x) {
  while (parent[x] != x) {
    parent[x] = parent[parent[x]];
    x = parent[x];
  }
  return x;
}

InputMesh readMesh(const MeshArrays& mesh, double creaseAngleDeg) {
  InputMesh in;
  if (mesh.faces.empty())
    throw Error("The layer has no faces: Remeshing: Sphere Packing needs a triangle mesh. For a point cloud "
                "(with normals) use Surface Reconstruction: Sphere Packing.");
  const size_t nv = mesh.vertices.size();
  for (size_t i = 0; i < nv; ++i) {
    const Vec3d& p = mesh.vertices[i];
    if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2]))
      throw Error("Vertex " + std::to_string(i) + " has a coordinate that is not a finite number.");
  }
  in.vertices = mesh.vertices;
  in.faces.reserve(mesh.faces.size());
  for (size_t f = 0; f < mesh.faces.size(); ++f) {
    const auto& t = mesh.faces[f];
    for (std::uint32_t v : t)
      if (v >= nv) throw Error("Face " + std::to_string(f) + " refers to a deleted or missing vertex.");
    in.faces.push_back(Triangle{t[0], t[1], t[2]});
  }
  // Triangles; a face of (nearly) zero area has no plane to place vertices on.
  in.tri.resize(in.faces.size());
  double edgeSum = 0;
  size_t edgeCount = 0;
  for (size_t f = 0; f < in.faces.size(); ++f) {
    const Triangle& t = in.faces[f];
    const Vec3d &a = in.vertices[t[0]], &b = in.vertices[t[1]], &c = in.vertices[t[2]];
    InputTriangle& T = in.tri[f];
    T.a = a;
    T.e0 = b - a;
    T.e1 = c - a;
    const Vec3d cr = T.e0 ^ T.e1;
    const double len2 = std::max(T.e0.SquaredNorm(), std::max(T.e1.SquaredNorm(), (c - b).SquaredNorm()));
    const double twiceArea = cr.Norm();
    const double shortest = std::min(T.e0.SquaredNorm(), std::min(T.e1.SquaredNorm(), (c - b).SquaredNorm()));
    if (t[0] == t[1] || t[1] == t[2] || t[0] == t[2] || !(shortest > 0))
      throw Error("Face " + std::to_string(f) + " (vertices " + std::to_string(t[0]) + ", " + std::to_string(t[1]) +
                  ", " + std::to_string(t[2]) + ", near " + vecText(a) + ") has zero area: two of its corners "
                  "coincide. Remove such faces first (Filters > Cleaning and Repairing > Merge Close Vertices, or "
                  "Remove Duplicate Vertices, then Remove Zero Area Faces).");
    // A sliver (height below kSliverHeight × its longest edge, down to three distinct corners on one
    // line: what a CAD boolean leaves where it split an edge) has no reliable plane: it joins its
    // neighbours but holds no vertex.
    T.sliver = !(twiceArea > kSliverHeight * len2);
    in.slivers += T.sliver ? 1 : 0;
    T.n = T.sliver ? Vec3d(0, 0, 0) : cr / twiceArea;
    T.area = 0.5 * twiceArea;
    T.centre = (a + b + c) / 3.0;
    T.radius = std::sqrt(std::max((a - T.centre).SquaredNorm(), std::max((b - T.centre).SquaredNorm(), (c - T.centre).SquaredNorm())));
    T.d00 = T.e0 * T.e0;
    T.d01 = T.e0 * T.e1;
    T.d11 = T.e1 * T.e1;
    T.inv = 1 / (T.d00 * T.d11 - T.d01 * T.d01);
    in.area += T.area;
    for (int k = 0; k < 3; ++k) in.box.Add(in.vertices[t[k]]);
  }
  // Edges: each with one face (boundary) or two; more is a non-manifold edge.
  std::vector<EdgeRef> edges;
  edges.reserve(3 * in.faces.size());
  for (std::uint32_t f = 0; f < in.faces.size(); ++f)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t u = in.faces[f][e], v = in.faces[f][(e + 1) % 3];
      edges.push_back(EdgeRef{std::min(u, v), std::max(u, v), f, std::uint8_t(e)});
    }
  std::sort(edges.begin(), edges.end());
  in.boundaryEdges.assign(in.faces.size(), 0);
  in.boundaryVertex.assign(nv, 0);
  std::vector<std::uint32_t> parent(in.faces.size()), patch(in.faces.size());
  std::iota(parent.begin(), parent.end(), 0u);
  std::iota(patch.begin(), patch.end(), 0u);
  const double creaseCos = std::cos(creaseAngleDeg * 3.14159265358979323846 / 180);
  std::vector<std::uint32_t> across(3 * in.faces.size(), kNone); // per face edge: the face on its other side
  auto addCrease = [&](std::uint32_t lo, std::uint32_t hi, std::uint32_t f0, std::uint32_t f1) {
    Vec3d n = in.tri[f0].n + in.tri[f1].n;
    const double len = n.Norm();
    n = len > 1e-12 ? n / len : in.tri[f0].n;
    in.creases.push_back(InputMesh::CreaseEdge{lo, hi, f0, f1, n});
  };
  auto joinPatches = [&](std::uint32_t f0, std::uint32_t f1) {
    const std::uint32_t px = findRoot(patch, f0), py = findRoot(patch, f1);
    if (px != py) patch[std::max(px, py)] = std::min(px, py);
  };
  for (size_t i = 0; i < edges.size();) {
    size_t j = i;
    while (j < edges.size() && edges[j].lo == edges[i].lo && edges[j].hi == edges[i].hi) ++j;
    const EdgeRef& r = edges[i];
    if (j - i > 2)
      throw Error("The mesh is not manifold: the edge between vertices " + std::to_string(r.lo) + " and " +
                  std::to_string(r.hi) + " (at " + vecText((in.vertices[r.lo] + in.vertices[r.hi]) * 0.5) +
                  ") has " + std::to_string(j - i) + " faces. Repair it first (Filters > Cleaning and Repairing > "
                  "Repair non Manifold Edges).");
    edgeSum += (in.vertices[r.lo] - in.vertices[r.hi]).Norm();
    ++edgeCount;
    if (j - i == 1) {
      in.boundaryEdges[r.face] |= std::uint8_t(1u << r.e);
      in.boundaryVertex[r.lo] = in.boundaryVertex[r.hi] = 1;
      ++in.boundaryEdgeCount;
      // The input's borders are feature lines too: the output's border then runs along them.
      if (!in.tri[r.face].sliver) in.creases.push_back(InputMesh::CreaseEdge{r.lo, r.hi, r.face, r.face, in.tri[r.face].n});
    } else {
      const std::uint32_t f0 = edges[i].face, f1 = edges[i + 1].face;
      across[3 * f0 + edges[i].e] = f1;
      across[3 * f1 + edges[i + 1].e] = f0;
      const std::uint32_t x = findRoot(parent, f0), y = findRoot(parent, f1);
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
      if (in.tri[f0].sliver || in.tri[f1].sliver) {
        // Decided below, through the sliver.
      } else if (in.tri[f0].n * in.tri[f1].n < creaseCos) {
        addCrease(r.lo, r.hi, f0, f1);
      } else {
        joinPatches(f0, f1);
      }
    }
    i = j;
  }
  // A sliver stands between the face across its longest edge and the faces across its two short
  // ones, which meet there as across one edge: each short edge is a crease between them or joins
  // their patches (a crease along a split edge keeps running). A sliver is a patch of its own.
  for (std::uint32_t f = 0; f < in.faces.size(); ++f) {
    if (!in.tri[f].sliver) continue;
    int longest = 0;
    double best = -1;
    for (int e = 0; e < 3; ++e) {
      const double len = (in.vertices[in.faces[f][e]] - in.vertices[in.faces[f][(e + 1) % 3]]).SquaredNorm();
      if (len > best) best = len, longest = e;
    }
    const std::uint32_t y = across[3 * f + longest];
    if (y == kNone || in.tri[y].sliver) continue;
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t x = across[3 * f + e];
      if (e == longest || x == kNone || in.tri[x].sliver) continue;
      const std::uint32_t u = in.faces[f][e], v = in.faces[f][(e + 1) % 3];
      if (in.tri[x].n * in.tri[y].n < creaseCos) addCrease(std::min(u, v), std::max(u, v), x, y);
      else joinPatches(x, y);
    }
  }
  in.component.resize(in.faces.size());
  for (std::uint32_t f = 0; f < in.faces.size(); ++f) {
    in.component[f] = findRoot(parent, f);
    in.components += in.component[f] == f ? 1 : 0;
  }
  in.patch = std::move(patch);
  in.vertexNormal.assign(nv, Vec3d(0, 0, 0));
  for (std::uint32_t f = 0; f < in.faces.size(); ++f)
    for (int k = 0; k < 3; ++k) {
      const Vec3d& p = in.vertices[in.faces[f][k]];
      Vec3d a = in.vertices[in.faces[f][(k + 1) % 3]] - p, b = in.vertices[in.faces[f][(k + 2) % 3]] - p;
      const double angle = std::atan2((a ^ b).Norm(), a * b);
      in.vertexNormal[in.faces[f][k]] += in.tri[f].n * angle;
    }
  for (Vec3d& n : in.vertexNormal) {
    const double len = n.Norm();
    if (len > 0) n /= len;
  }
  in.meanEdge = edgeCount > 0 ? edgeSum / double(edgeCount) : 0;
  // Vertices: the faces around each must form one fan (joined through the vertex's edges with two faces).
  std::vector<std::uint32_t> start(nv + 1, 0), around(3 * in.faces.size());
  for (const Triangle& t : in.faces)
    for (std::uint32_t v : t) ++start[v + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  {
    std::vector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (std::uint32_t f = 0; f < in.faces.size(); ++f)
      for (std::uint32_t v : in.faces[f]) around[fill[v]++] = f;
  }
  std::vector<std::pair<std::uint32_t, std::uint32_t>> spokes; // (other end of an edge at v, face)
  std::vector<std::uint32_t> fan;
  for (std::uint32_t v = 0; v < nv; ++v) {
    const std::uint32_t b = start[v], e = start[v + 1];
    if (e - b < 2) continue;
    spokes.clear();
    for (std::uint32_t k = b; k < e; ++k) {
      const Triangle& t = in.faces[around[k]];
      for (int c = 0; c < 3; ++c)
        if (t[c] == v) {
          spokes.emplace_back(t[(c + 1) % 3], k - b);
          spokes.emplace_back(t[(c + 2) % 3], k - b);
        }
    }
    std::sort(spokes.begin(), spokes.end());
    fan.resize(e - b);
    std::iota(fan.begin(), fan.end(), 0u);
    for (size_t i = 0; i + 1 < spokes.size(); ++i)
      if (spokes[i].first == spokes[i + 1].first) {
        const std::uint32_t x = findRoot(fan, spokes[i].second), y = findRoot(fan, spokes[i + 1].second);
        if (x != y) fan[std::max(x, y)] = std::min(x, y);
      }
    size_t fans = 0;
    for (std::uint32_t k = 0; k < fan.size(); ++k) fans += findRoot(fan, k) == k ? 1 : 0;
    if (fans > 1)
      throw Error("The mesh is not manifold: vertex " + std::to_string(v) + " (at " + vecText(in.vertices[v]) +
                  ") joins " + std::to_string(fans) + " separate fans of faces. Repair it first (Filters > "
                  "Cleaning and Repairing > Repair non Manifold Vertices by splitting).");
  }
  return in;
}

// Hash grid of cells of side d over the input triangles (slivers left out): a cell lists the triangles that meet the
// ball circumscribing it (radius √3/2·d around its centre), in triangle order. Every point of a
// triangle lies in a cell that lists it, so the triangles within d of x are all listed by the
// 3 × 3 × 3 cells around x's cell.
class TriangleGrid {
public:
  void build(const InputMesh& in, double d) {
    const Vec3d origin = in.box.min - Vec3d(d, d, d) * 2.0;
    index_ = BoxIndexer(origin, d);
    const double reach = 0.8660254037844386 * d * (1 + 1e-9);
    std::vector<std::pair<KeyHash::Key, std::uint32_t>> refs;
    refs.reserve(in.tri.size() * 8);
    for (std::uint32_t f = 0; f < in.tri.size(); ++f) {
      if (in.tri[f].sliver) continue; // no vertex lies on a sliver: no query needs it
      const Triangle& t = in.faces[f];
      const Vec3d &a = in.vertices[t[0]], &b = in.vertices[t[1]], &c = in.vertices[t[2]];
      std::int64_t lo[3], hi[3];
      for (int k = 0; k < 3; ++k) {
        const double mn = std::min(a[k], std::min(b[k], c[k])), mx = std::max(a[k], std::max(b[k], c[k]));
        lo[k] = index_.coord(mn - reach, k);
        hi[k] = index_.coord(mx + reach, k);
      }
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
            if (!BoxIndexer::valid(x, y, z)) continue;
            const Vec3d centre = index_.corner(x, y, z) + Vec3d(d, d, d) * 0.5;
            int feature = 0;
            if ((closestOnTriangle(centre, a, b, c, feature) - centre).SquaredNorm() <= reach * reach)
              refs.emplace_back(BoxIndexer::pack(x, y, z), f);
          }
    }
    std::sort(refs.begin(), refs.end());
    hash_.reset(refs.size() / 4 + 16);
    offsets_.clear();
    list_.resize(refs.size());
    for (size_t i = 0; i < refs.size(); ++i) {
      if (i == 0 || refs[i].first != refs[i - 1].first) {
        hash_.findOrInsert(refs[i].first, int(offsets_.size()));
        offsets_.push_back(std::uint32_t(i));
      }
      list_[i] = refs[i].second;
    }
    offsets_.push_back(std::uint32_t(refs.size()));
    stamp_.assign(in.tri.size(), 0);
    round_ = 0;
  }

  // Calls f(t) once for every triangle listed by the 3 × 3 × 3 cells around x's cell (a superset of
  // the triangles within d of x), in a fixed order.
  template <class F>
  void forEachNear(const Vec3d& x, F&& f) const {
    const std::int64_t cx = index_.coord(x[0], 0), cy = index_.coord(x[1], 1), cz = index_.coord(x[2], 2);
    visit(cx - 1, cx + 1, cy - 1, cy + 1, cz - 1, cz + 1, f);
  }
  // Calls f(t) once for every triangle listed by the cells that meet the box of half side r
  // around x (a superset of the triangles within r of x: a point of such a triangle lies in one of
  // these cells, which lists it), in a fixed order. For r = d/2 at most 2 × 2 × 2 cells.
  template <class F>
  void forEachWithin(const Vec3d& x, double r, F&& f) const {
    visit(index_.coord(x[0] - r, 0), index_.coord(x[0] + r, 0), index_.coord(x[1] - r, 1), index_.coord(x[1] + r, 1),
          index_.coord(x[2] - r, 2), index_.coord(x[2] + r, 2), f);
  }
  const BoxIndexer& indexer() const { return index_; }
  size_t references() const { return list_.size(); }

private:
  template <class F>
  void visit(std::int64_t x0, std::int64_t x1, std::int64_t y0, std::int64_t y1, std::int64_t z0, std::int64_t z1,
             F& f) const {
    if (++round_ == 0) {
      std::fill(stamp_.begin(), stamp_.end(), 0u);
      round_ = 1;
    }
    for (std::int64_t i = x0; i <= x1; ++i)
      for (std::int64_t j = y0; j <= y1; ++j)
        for (std::int64_t k = z0; k <= z1; ++k) {
          if (!BoxIndexer::valid(i, j, k)) continue;
          const int cell = hash_.find(BoxIndexer::pack(i, j, k));
          if (cell < 0) continue;
          for (std::uint32_t r = offsets_[size_t(cell)]; r < offsets_[size_t(cell) + 1]; ++r) {
            const std::uint32_t t = list_[r];
            if (stamp_[t] == round_) continue;
            stamp_[t] = round_;
            f(t);
          }
        }
  }

  BoxIndexer index_;
  KeyHash hash_;
  std::vector<std::uint32_t> offsets_, list_;
  mutable std::vector<std::uint32_t> stamp_;
  mutable std::uint32_t round_ = 0;
};

// The input surface near a point: distances, closest points, normals.
class Surface {
public:
  Surface(const InputMesh& in, const TriangleGrid& grid, double d) : in_(in), grid_(grid), d_(d) {}

  double squaredDistance(const Vec3d& x, std::uint32_t t, int* feature = nullptr) const {
    const Triangle& f = in_.faces[t];
    int ft = 0;
    const Vec3d q = closestOnTriangle(x, in_.vertices[f[0]], in_.vertices[f[1]], in_.vertices[f[2]], ft);
    if (feature != nullptr) *feature = ft;
    return (q - x).SquaredNorm();
  }
  // Whether triangle t is farther than r from x (squaredDistance(x, t) > r²), decided by its
  // bounding ball where it can be: most triangles a grid query lists are far.
  bool fartherThan(const Vec3d& x, std::uint32_t t, double r) const {
    const InputTriangle& T = in_.tri[t];
    const double reach = T.radius + r;
    const double c2 = (x - T.centre).SquaredNorm();
    if (c2 > reach * reach) return true;
    return squaredDistance(x, t) > r * r;
  }
  Vec3d closest(const Vec3d& x, std::uint32_t t, int& feature) const {
    const Triangle& f = in_.faces[t];
    return closestOnTriangle(x, in_.vertices[f[0]], in_.vertices[f[1]], in_.vertices[f[2]], feature);
  }

  // The mean normal of the triangles within d/2 of x that face the side of `side` (weights: their
  // area, at most d²/4), unit; `side` itself where there is none.
  // `patch`: only the triangles of that patch (kNone: any).
  Vec3d normalAt(const Vec3d& x, const Vec3d& side, std::uint32_t patch = kNone) const {
    Vec3d sum(0, 0, 0);
    const double cap = 0.25 * d_ * d_;
    grid_.forEachWithin(x, 0.5 * d_, [&](std::uint32_t t) {
      const InputTriangle& T = in_.tri[t];
      if (T.n * side <= 0) return;
      if (patch != kNone && in_.patch[t] != patch) return;
      if (fartherThan(x, t, 0.5 * d_)) return;
      sum += T.n * std::min(T.area, cap);
    });
    const double len = sum.Norm();
    return len > 0 ? sum / len : side;
  }

  // The closest point to x on the triangles within d of it that face the side of `side`; false when
  // there is none.
  bool project(const Vec3d& x, const Vec3d& side, std::uint32_t patch, Vec3d& out, std::uint32_t& tri) const {
    double best = d_ * d_;
    bool found = false;
    grid_.forEachNear(x, [&](std::uint32_t t) {
      if (in_.tri[t].n * side <= 0 || in_.patch[t] != patch) return;
      int feature = 0;
      const Vec3d q = closest(x, t, feature);
      const double d2 = (q - x).SquaredNorm();
      if (d2 < best || (d2 == best && found && t < tri)) {
        best = d2;
        out = q;
        tri = t;
        found = true;
      }
    });
    return found;
  }

  // The input triangle closest to x among those listed around it (kNone when none is), its squared
  // distance and the feature of its closest point (closestOnTriangle); ties go to the lower index.
  std::uint32_t closestTriangle(const Vec3d& x, double* squared = nullptr, int* feature = nullptr) const {
    double best = std::numeric_limits<double>::infinity();
    std::uint32_t bestT = kNone;
    int bestFeature = 0;
    grid_.forEachNear(x, [&](std::uint32_t t) {
      int ft = 0;
      const double d2 = squaredDistance(x, t, &ft);
      if (d2 < best || (d2 == best && t < bestT)) {
        best = d2;
        bestT = t;
        bestFeature = ft;
      }
    });
    if (squared != nullptr) *squared = best;
    if (feature != nullptr) *feature = bestFeature;
    return bestT;
  }

  // Whether x lies beyond the input's boundary: its closest input point (any side) is on a boundary
  // edge or corner and farther than kOutsideTolerancePerD·d, or no triangle is within d.
  bool beyondBoundary(const Vec3d& x) const {
    double best = 0;
    int bestFeature = 0;
    const std::uint32_t bestT = closestTriangle(x, &best, &bestFeature);
    if (bestT == kNone || best > d_ * d_) return true;
    const double tol = kOutsideTolerancePerD * d_;
    if (best <= tol * tol) return false;
    if (bestFeature == 0) return false;
    if (bestFeature <= 3) return (in_.boundaryEdges[bestT] >> (bestFeature - 1)) & 1u;
    return in_.boundaryVertex[in_.faces[bestT][bestFeature - 4]] != 0;
  }

private:
  const InputMesh& in_;
  const TriangleGrid& grid_;
  const double d_;
};

struct Candidate {
  std::uint32_t a, b, tri;
  std::uint8_t root;
};

// The disk growing of sec. 3.3–3.6 on the input's triangles (Growth in packer_growth.h on splats).
class MeshGrowth {
public:
  MeshGrowth(const InputMesh& in, const TriangleGrid& grid, const Surface& surface, double d, const RemeshParams& p,
             RemeshStat& st, Progress& progress, size_t expected)
      : in_(in), grid_(grid), surface_(surface), d_(d), d2_(d * d), w_(p.windowSize), params_(p), st_(st),
        progress_(progress), expected_(std::max<size_t>(expected, 16)),
        queue_(CandidatePriority::levels(p.windowSize)) {
    lists_.reset(in.tri.size());
    for (const std::uint32_t p : in.patch) multiPatch_ = multiPatch_ || p != in.patch[0];
    const size_t reserve = std::min<size_t>(expected_ + expected_ / 4, p.maxOutputVertices);
    vgrid_.reset(grid.indexer().origin(), crossingSearchRadius(d), reserve);
    graph_.reserve(reserve);
  }

  const BorderGraph& graph() const { return graph_; }
  bool reached(std::uint32_t t) const { return !lists_.empty(t); }
  // No vertex of `patch` (or feature vertex) closer than d to x: a start may go there.
  bool freeOnPatch(const Vec3d& x, std::uint32_t patch, const Vec3d& n) const {
    return !vgrid_.anyCloserThan(x, d_, graph_.positions(), kNone, kNone) ||
           (multiPatch_ && !closerOnPatch(x, patch, n, kNone, kNone));
  }
  bool anyVertexCloserThan(const Vec3d& x, double r) const {
    return vgrid_.anyCloserThan(x, r, graph_.positions(), kNone, kNone);
  }

  void start(const Vec3d& s1, std::uint32_t t1, const Vec3d& s2, std::uint32_t t2) {
    insertVertex(s1, in_.patch[t1], surface_.normalAt(s1, in_.tri[t1].n, in_.patch[t1]), false);
    insertVertex(s2, in_.patch[t2], surface_.normalAt(s2, in_.tri[t2].n, in_.patch[t2]), false);
  }

  // Sec. 3.3 with more than two starting vertices: a feature vertex (a corner or a point of a
  // crease) at x with normal n, unless a vertex is closer than d (then kNone). It belongs to every
  // patch; its candidates are enumerated by enumerateFeature() once all feature vertices and
  // edges are in.
  std::uint32_t addFeatureVertex(const Vec3d& x, const Vec3d& n) {
    if (anyVertexCloserThan(x, d_)) return kNone;
    return insertVertex(x, kNone, n, true);
  }
  // An edge of a crease line between two feature vertices.
  bool addFeatureEdge(std::uint32_t u, std::uint32_t v) {
    const auto& pos = graph_.positions();
    return graph_.addEdge(u, graph_.gapOf(u, pos[v]), v, graph_.gapOf(v, pos[u]));
  }
  void enumerateFeature(std::uint32_t v) { enumerate(v); }

  // The candidate's position, recomputed bit for bit as when it was found.
  bool position(const Candidate& cd, Vec3d& x) const {
    const auto& pos = graph_.positions();
    CirclePlaneMeet m;
    if (!circleMeetsPlane(parentCircle(pos[cd.a], pos[cd.b], d_), in_.tri[cd.tri].a, in_.tri[cd.tri].n, m))
      return false;
    x = m.root(cd.root);
    return true;
  }

  void run() {
    size_t pops = 0;
    // A face never joins two patches: a candidate is taken when each parent is a feature vertex or
    // lies on the candidate's patch (enumerate() queues no other; the check is kept for the
    // re-queued ones).
    std::vector<std::uint32_t> nearby;
    std::vector<double> nearbyD2;
    while (!queue_.empty()) {
      int popped = 0;
      const Candidate cd = queue_.pop(&popped);
      if ((++pops & 31) == 0) progress_.update(std::min(0.99, double(graph_.vertexCount()) / double(expected_)));
      Vec3d x;
      if (!position(cd, x)) continue;
      const auto& pos = graph_.positions();
      const std::uint32_t patch = in_.patch[cd.tri];
      if (vgrid_.anyCloserThan(x, d_, pos, cd.a, cd.b) &&
          (!multiPatch_ || closerOnPatch(x, patch, in_.tri[cd.tri].n, cd.a, cd.b))) {
        ++st_.rejectedTooClose;
        continue;
      }
      const int gapA = graph_.gapOf(cd.a, x), gapB = graph_.gapOf(cd.b, x);
      const int level = levelOf(cd.a, cd.b, gapA, gapB);
      if (level > popped) {
        queue_.push(level, cd);
        ++st_.requeued;
        ++st_.candidates;
        continue;
      }
      if (graph_.degree(cd.a) >= BorderGraph::kMaxDegree || graph_.degree(cd.b) >= BorderGraph::kMaxDegree) continue;
      if ((vpatch_[cd.a] != kNone && vpatch_[cd.a] != patch) || (vpatch_[cd.b] != kNone && vpatch_[cd.b] != patch))
        continue;
      const Vec3d n = surface_.normalAt(x, in_.tri[cd.tri].n, patch);
      nearby.clear();
      nearbyD2.clear();
      vgrid_.forEachInBall(x, crossingSearchRadius(d_), pos, [&](std::uint32_t v, double d2) {
        nearby.push_back(v);
        nearbyD2.push_back(d2);
      });
      // Edges on another patch are seen edge-on across the crease; the crease edges between them
      // (feature vertices) are what keeps the faces on their side.
      const auto samePatch = [&](std::uint32_t u) { return vpatch_[u] == kNone || vpatch_[u] == patch; };
      if (newEdgesCrossIf(graph_, x, cd.a, cd.b, n, d_, nearby,
                          [&](std::uint32_t u, std::uint32_t w) { return samePatch(u) && samePatch(w); })) {
        ++st_.rejectedCrossing;
        continue;
      }
      if (params_.rejectTwisted && (!graph_.gapContains(cd.a, gapA, x, n) || !graph_.gapContains(cd.b, gapB, x, n))) {
        ++st_.rejectedInconsistent;
        continue;
      }
      const std::uint32_t c = insertVertex(x, patch, n, true);
      if (!graph_.connect(c, cd.a, gapA, cd.b, gapB))
        throw std::logic_error("sphere packing remesher: could not connect a new vertex");
      if (params_.checkInvariants) checkInvariants(c, cd.a, cd.b);
      near_.clear();
      for (size_t k = 0; k < nearby.size(); ++k)
        if (nearbyD2[k] <= 4 * d2_) near_.push_back(nearby[k]);
      enumerate(c, true);
    }
  }

private:
  std::uint32_t insertVertex(const Vec3d& x, std::uint32_t patch, const Vec3d& normal, bool enumerateLater) {
    if (graph_.vertexCount() >= params_.maxOutputVertices)
      throw Error("The mesh grew past the limit of " + std::to_string(params_.maxOutputVertices) +
                  " vertices: use a larger sphere diameter d.");
    const std::uint32_t v = graph_.addVertex(x, normal);
    vgrid_.insert(v, x);
    vpatch_.push_back(patch);
    if (!enumerateLater) enumerate(v);
    return v;
  }

  // Vertices on two different patches whose normals differ by more than 60° (kApartDot) may be
  // closer than d: they are never joined (every face keeps to one patch), and both sides of a
  // concave crease sharper than 60° then hold vertices. Across gentler creases (a scan's noise
  // that the crease angle picks up) the packing keeps d, as everywhere. A feature vertex keeps d
  // from every vertex.
  bool onPatch(std::uint32_t v, std::uint32_t patch) const { return vpatch_[v] == kNone || vpatch_[v] == patch; }
  bool keepsOff(std::uint32_t v, std::uint32_t patch, const Vec3d& n) const {
    return onPatch(v, patch) || graph_.normal(v) * n > kApartDot;
  }
  bool closerOnPatch(const Vec3d& x, std::uint32_t patch, const Vec3d& n, std::uint32_t skipA,
                     std::uint32_t skipB) const {
    bool hit = false;
    vgrid_.forEachInBall(x, d_, graph_.positions(), [&](std::uint32_t u, double d2) {
      hit = hit || (u != skipA && u != skipB && d2 < d2_ && keepsOff(u, patch, n));
    });
    return hit;
  }

  // Sec. 3.5 priority, with the splits of distance 1 to kAlikeSplitDistance alike.
  int levelOf(std::uint32_t a, std::uint32_t b, const Vec3d& x) const {
    return CandidatePriority::of(graph_, a, b, x, w_, kAlikeSplitDistance);
  }
  int levelOf(std::uint32_t a, std::uint32_t b, int gapA, int gapB) const {
    return CandidatePriority::of(graph_, a, b, gapA, gapB, w_, kAlikeSplitDistance);
  }

  // Sec. 3.4/4.4 on triangles: for every triangle within d of v (facing v's side), the candidates
  // with the vertices already in its list, then v joins the list. A candidate y of parents v and u
  // on triangle t is within d of both, so both are in t's list: the later one finds it.
  void enumerate(std::uint32_t v, bool nearKnown = false) {
    const auto& pos = graph_.positions();
    const Vec3d x = pos[v];
    if (!nearKnown) {
      near_.clear();
      vgrid_.forEachInBall(x, 2 * d_, pos, [&](std::uint32_t u, double) { near_.push_back(u); });
    }
    found_.clear();
    const Vec3d nv = graph_.normal(v);
    tris_.clear();
    grid_.forEachNear(x, [&](std::uint32_t t) { tris_.push_back(t); });
    std::sort(tris_.begin(), tris_.end());
    const std::uint32_t vp = vpatch_[v];
    for (const std::uint32_t t : tris_) {
      const InputTriangle& T = in_.tri[t];
      if (T.n * nv < kMinFacingDot) continue;
      const std::uint32_t tp = in_.patch[t];
      if (vp != kNone && vp != tp) continue;
      if (surface_.fartherThan(x, t, d_)) continue;
      lists_.forEach(t, [&](std::uint32_t u) {
        if (vpatch_[u] != kNone && vpatch_[u] != tp) return;
        const ParentCircle c = parentCircle(x, pos[u], d_);
        if (!c.valid) return;
        CirclePlaneMeet m;
        if (!circleMeetsPlane(c, T.a, T.n, m)) return;
        for (int root = 0; root < 2; ++root) {
          const Vec3d y = m.root(root);
          if (root == 1 && m.t == 0) break; // tangent: one point
          const double inside = T.insideness(y);
          if (!(inside >= -kInsideTolerance)) continue;
          bool blocked = false;
          for (std::uint32_t w : near_)
            if (w != v && w != u && keepsOff(w, tp, T.n) && (pos[w] - y).SquaredNorm() < d2_) {
              blocked = true;
              break;
            }
          if (blocked) continue;
          const bool side = (((pos[u] - x) ^ (y - x)) * nv) >= 0;
          bool merged = false;
          for (Found& f : found_)
            if (f.u == u && f.side == side && (f.y - y).SquaredNorm() < 0.25 * d2_) {
              if (inside > f.score) f = Found{y, inside, u, t, std::uint8_t(root), side};
              merged = true;
              break;
            }
          if (!merged) found_.push_back(Found{y, inside, u, t, std::uint8_t(root), side});
        }
      });
      lists_.add(t, v);
    }
    for (const Found& f : found_) {
      queue_.push(levelOf(v, f.u, f.y), Candidate{v, f.u, f.tri, f.root});
      ++st_.candidates;
    }
  }
  struct Found {
    Vec3d y;
    double score;
    std::uint32_t u, tri;
    std::uint8_t root;
    bool side;
  };

  void checkInvariants(std::uint32_t c, std::uint32_t a, std::uint32_t b) const {
    const auto& pos = graph_.positions();
    for (std::uint32_t v = 0; v < c; ++v)
      if ((vpatch_[c] == kNone || keepsOff(v, vpatch_[c], graph_.normal(c))) && (pos[v] - pos[c]).Norm() < d_ * (1 - 1e-12))
        throw std::logic_error("sphere packing remesher invariant: vertices " + std::to_string(v) + " and " +
                               std::to_string(c) + " closer than d");
    for (std::uint32_t p : {a, b})
      if (std::abs((pos[p] - pos[c]).Norm() - d_) > 1e-9 * d_)
        throw std::logic_error("sphere packing remesher invariant: an edge is not d long");
  }

  const InputMesh& in_;
  const TriangleGrid& grid_;
  const Surface& surface_;
  const double d_, d2_;
  const int w_;
  const RemeshParams& params_;
  RemeshStat& st_;
  Progress& progress_;
  const size_t expected_;
  SplatVertexLists lists_;
  VertexGrid vgrid_;
  BorderGraph graph_;
  BucketQueue<Candidate> queue_;
  std::vector<std::uint32_t> near_, tris_;
  std::vector<std::uint32_t> vpatch_; // per vertex: its patch, kNone for a feature vertex
  bool multiPatch_ = false;           // the input has more than one patch
  std::vector<Found> found_;
};

// The feature lines: the crease and border edges split at the corners, input vertices where lines
// end or meet (not two feature edges) or turn by more than kCornerTurnDeg; a closed line without a
// corner starts at its lowest vertex. In the order of the corners, then of those starts.
constexpr double kCornerTurnDeg = 60;
struct FeatureLine {
  std::vector<std::uint32_t> vertices; // input vertices, from one end to the other (first == last: closed)
  std::vector<std::uint32_t> edges;    // indices into InputMesh::creases, one per step
  double length = 0;
};
struct FeatureLines {
  std::vector<char> corner;            // per input vertex
  std::vector<FeatureLine> lines;
};
FeatureLines traceFeatureLines(const InputMesh& in) {
  FeatureLines out;
  const size_t nv = in.vertices.size();
  std::vector<std::uint32_t> start(nv + 1, 0);
  for (const auto& e : in.creases) ++start[e.u + 1], ++start[e.v + 1];
  for (size_t v = 0; v < nv; ++v) start[v + 1] += start[v];
  std::vector<std::uint32_t> adj(start[nv]), fill(start.begin(), start.end() - 1);
  for (std::uint32_t k = 0; k < in.creases.size(); ++k) {
    adj[fill[in.creases[k].u]++] = k;
    adj[fill[in.creases[k].v]++] = k;
  }
  auto other = [&](std::uint32_t k, std::uint32_t v) { return in.creases[k].u == v ? in.creases[k].v : in.creases[k].u; };
  const double turnCos = std::cos(kCornerTurnDeg * 3.14159265358979323846 / 180);
  out.corner.assign(nv, 0);
  for (std::uint32_t v = 0; v < nv; ++v) {
    const std::uint32_t deg = start[v + 1] - start[v];
    if (deg == 0) continue;
    if (deg != 2) {
      out.corner[v] = 1;
      continue;
    }
    const Vec3d a = in.vertices[v] - in.vertices[other(adj[start[v]], v)];
    const Vec3d b = in.vertices[other(adj[start[v] + 1], v)] - in.vertices[v];
    out.corner[v] = (a * b) < turnCos * a.Norm() * b.Norm() ? 1 : 0;
  }
  std::vector<char> used(in.creases.size(), 0);
  auto trace = [&](std::uint32_t from, std::uint32_t k) {
    FeatureLine line;
    line.vertices.push_back(from);
    std::uint32_t v = from;
    for (;;) {
      used[k] = 1;
      line.edges.push_back(k);
      const std::uint32_t w = other(k, v);
      line.length += (in.vertices[w] - in.vertices[v]).Norm();
      v = w;
      line.vertices.push_back(v);
      if (out.corner[v] || v == from) break;
      std::uint32_t next = kNone;
      for (std::uint32_t j = start[v]; j < start[v + 1]; ++j)
        if (!used[adj[j]]) next = adj[j];
      if (next == kNone) break;
      k = next;
    }
    out.lines.push_back(std::move(line));
  };
  for (std::uint32_t v = 0; v < nv; ++v)
    if (out.corner[v])
      for (std::uint32_t j = start[v]; j < start[v + 1]; ++j)
        if (!used[adj[j]]) trace(v, adj[j]);
  for (std::uint32_t v = 0; v < nv; ++v)
    for (std::uint32_t j = start[v]; j < start[v + 1]; ++j)
      if (!used[adj[j]]) trace(v, adj[j]);
  return out;
}

// Feature lines shorter than kMinCreasePerD·d are not features: at the scale of d they are the
// noise of a scanned surface's triangulation (a network of short lines between many corners), or
// details smaller than d, not an edge of the shape (a cube's sides are lines from corner to corner).
// They are dropped, the corners recomputed, and again until every line is long enough; the faces
// along a dropped crease join one patch.
// A line must also be a crease at the scale of d: the surface's normals kSideOffsetPerD·d to
// either side of it (Surface::normalAt, the mean over d/2) must differ by more than the crease
// angle, on the mean over the line's length (border lines are always kept). Two faces of a scan's
// triangulation meet at any angle, but the surface d away from them does not turn with them;
// such lines split the surface into patches that the growth does not join.
constexpr double kMinCreasePerD = 2.0;
constexpr double kSideOffsetPerD = 0.75;
// Per crease edge: the cosine of the angle between the surface's normals kSideOffsetPerD·d to
// either side of its midpoint (a border edge: −1, always a feature).
std::vector<double> creaseCosAtD(const InputMesh& in, const Surface& surface, double d) {
  std::vector<double> out(in.creases.size(), -1);
  for (size_t k = 0; k < in.creases.size(); ++k) {
    const InputMesh::CreaseEdge& e = in.creases[k];
    if (e.f0 == e.f1) continue;
    const Vec3d p = (in.vertices[e.u] + in.vertices[e.v]) * 0.5;
    Vec3d t = in.vertices[e.v] - in.vertices[e.u];
    t /= t.Norm();
    Vec3d n[2];
    const std::uint32_t f[2] = {e.f0, e.f1};
    for (int s = 0; s < 2; ++s) {
      const Triangle& tri = in.faces[f[s]];
      Vec3d side = (in.vertices[tri[0]] + in.vertices[tri[1]] + in.vertices[tri[2]]) / 3.0 - p;
      side -= t * (side * t);
      const double len = side.Norm();
      n[s] = len > 0 ? surface.normalAt(p + side * (kSideOffsetPerD * d / len), in.tri[f[s]].n) : in.tri[f[s]].n;
    }
    out[k] = n[0] * n[1];
  }
  return out;
}

void keepLongCreases(InputMesh& in, double d, const Surface& surface, double creaseAngleDeg) {
  const double creaseCos = std::cos(creaseAngleDeg * 3.14159265358979323846 / 180);
  std::vector<double> cosAtD = creaseCosAtD(in, surface, d);
  for (;;) {
    const FeatureLines fl = traceFeatureLines(in);
    std::vector<char> drop(in.creases.size(), 0);
    bool any = false;
    for (const FeatureLine& line : fl.lines) {
      double sum = 0, length = 0;
      for (const std::uint32_t k : line.edges) {
        const double len = (in.vertices[in.creases[k].u] - in.vertices[in.creases[k].v]).Norm();
        sum += cosAtD[k] * len;
        length += len;
      }
      if (line.length < kMinCreasePerD * d || (length > 0 && sum / length >= creaseCos)) {
        for (const std::uint32_t k : line.edges) drop[k] = 1;
        any = true;
      }
    }
    if (!any) break;
    size_t w = 0;
    for (size_t k = 0; k < in.creases.size(); ++k) {
      const auto& e = in.creases[k];
      if (!drop[k]) {
        cosAtD[w] = cosAtD[k];
        in.creases[w++] = e;
        continue;
      }
      const std::uint32_t x = findRoot(in.patch, e.f0), y = findRoot(in.patch, e.f1);
      if (x != y) in.patch[std::max(x, y)] = std::min(x, y);
    }
    in.creases.resize(w);
    cosAtD.resize(w);
  }
  for (std::uint32_t f = 0; f < in.patch.size(); ++f) in.patch[f] = findRoot(in.patch, f);
}

// Item 2 of the features, sec. 3.3 with more than two starting vertices: the corners as vertices at
// their exact positions, then every feature line (traceFeatureLines) sampled at a chord spacing
// s >= d that ends exactly at its far end (sampleLine), joined by edges; then their candidates and
// the growth from them. A feature vertex closer than d to one placed before is left out (with the
// edges to it). The normal of a point of a crease is the mean of its two faces' normals, of a
// corner the angle-weighted mean of its faces' normals.
void placeFeatures(MeshGrowth& growth, const InputMesh& in, double d, RemeshStat& st) {
  if (in.creases.empty()) return;
  const FeatureLines fl = traceFeatureLines(in);
  const size_t nv = in.vertices.size();
  std::vector<std::uint32_t> vertexOf(nv, kNone);
  std::vector<std::uint32_t> placed;
  auto place = [&](const Vec3d& x, const Vec3d& n) {
    const std::uint32_t id = growth.addFeatureVertex(x, n);
    if (id != kNone) placed.push_back(id);
    else ++st.featureVerticesSkipped;
    return id;
  };
  for (std::uint32_t v = 0; v < nv; ++v)
    if (fl.corner[v]) {
      ++st.featureCorners;
      vertexOf[v] = place(in.vertices[v], in.vertexNormal[v]);
    }
  for (const FeatureLine& line : fl.lines) {
    const std::uint32_t from = line.vertices.front(), to = line.vertices.back();
    // A closed line without a corner starts at a vertex of its own.
    if (!fl.corner[from] && vertexOf[from] == kNone) vertexOf[from] = place(in.vertices[from], in.creases[line.edges[0]].n);
    std::vector<Vec3d> P;
    for (const std::uint32_t v : line.vertices) P.push_back(in.vertices[v]);
    // Consecutive placed points are joined; across a point left out (at a corner sharper than 60°,
    // the first points of two lines are closer than d) when they are at most 2.2 d apart: the
    // crossing check (sec. 3.6) sees an edge up to 2 (√5 − 1) d long.
    std::uint32_t prev = vertexOf[from];
    auto join = [&](std::uint32_t u, std::uint32_t v) {
      if (u != kNone && v != kNone && u != v &&
          (growth.graph().position(u) - growth.graph().position(v)).SquaredNorm() <= 2.2 * 2.2 * d * d)
        growth.addFeatureEdge(u, v);
    };
    for (const LinePoint& q : sampleLine(P, d)) {
      const std::uint32_t id = place(q.p, in.creases[line.edges[q.seg]].n);
      if (id == kNone) continue;
      join(prev, id);
      prev = id;
    }
    join(prev, vertexOf[to]);
  }
  st.creaseEdges = in.creases.size();
  st.featureVertices = placed.size();
  for (const std::uint32_t v : placed) growth.enumerateFeature(v);
  growth.run();
}

// Sec. 3.3 on every part of the input: in triangle order, every triangle no vertex has come within d
// of gets a starting pair: its centroid, and the projection onto the input of a point 1.5·d away in
// its plane (12 directions in turn) that lies between d and 2d from it; both at least d from every
// vertex. The growth runs after each.
void growEverywhere(MeshGrowth& growth, const InputMesh& in, const Surface& surface, double d, RemeshStat& st) {
  for (std::uint32_t t = 0; t < in.tri.size(); ++t) {
    if (growth.reached(t) || in.tri[t].sliver) continue;
    const Triangle& f = in.faces[t];
    const Vec3d s1 = (in.vertices[f[0]] + in.vertices[f[1]] + in.vertices[f[2]]) / 3.0;
    if (!growth.freeOnPatch(s1, in.patch[t], in.tri[t].n)) continue;
    Vec3d e1, e2;
    tangentFrame(in.tri[t].n, e1, e2);
    for (int k = 0; k < 12; ++k) {
      const double phi = 2 * 3.14159265358979323846 * k / 12;
      const Vec3d target = s1 + (e1 * std::cos(phi) + e2 * std::sin(phi)) * (1.5 * d);
      Vec3d s2;
      std::uint32_t t2 = kNone;
      if (!surface.project(target, in.tri[t].n, in.patch[t], s2, t2)) continue;
      const double dist = (s2 - s1).Norm();
      if (dist < d || dist > 2 * d || !growth.freeOnPatch(s2, in.patch[t], in.tri[t].n)) continue;
      growth.start(s1, t, s2, t2);
      growth.run();
      ++st.componentsStarted;
      break;
    }
  }
  for (std::uint32_t t = 0; t < in.tri.size(); ++t) st.unreachedFaces += growth.reached(t) || in.tri[t].sliver ? 0 : 1;
}

// Sec. 3.7, with the input's boundary kept open: each border up to the limit is triangulated on its
// own, and its faces are dropped again (the region left open) when at least half of their area has
// its centroids beyond the input's boundary.
constexpr size_t kShortRegion = 6;
std::vector<Triangle> triangulateKeepingBoundary(const BorderGraph& g, const Surface& surface, bool hasBorders,
                                                 const RemeshParams& params, bool floatStorage, RemeshStat& st) {
  EdgeSet edges(g.edgeCount() * 2 + 16);
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    for (int k = 0; k < g.degree(v); ++k)
      if (v < g.neighbour(v, k)) edges.insert(v, g.neighbour(v, k));
  std::vector<Triangle> faces, region;
  faces.reserve(2 * g.vertexCount() + 16);
  const auto& pos = g.positions();
  std::vector<std::vector<std::uint32_t>> one(1);
  for (auto& border : g.borders()) {
    if (border.size() > size_t(std::max(params.maxBorderLength, 0))) {
      ++st.holes;
      continue;
    }
    one[0] = std::move(border);
    region.clear();
    const RegionStats rs = triangulateRegions(one, pos, g.normals(), params.maxBorderLength, edges, region);
    double all = 0, outside = 0;
    // Without input borders a region can only lie off the input where no triangle is within d of
    // it, which takes a border longer than kShortRegion edges (d to 2d long each).
    const bool check = hasBorders || one[0].size() > kShortRegion;
    if (check)
      for (const Triangle& f : region) {
        const double a = ((pos[f[1]] - pos[f[0]]) ^ (pos[f[2]] - pos[f[0]])).Norm();
        all += a;
        if (surface.beyondBoundary((pos[f[0]] + pos[f[1]] + pos[f[2]]) / 3.0)) outside += a;
      }
    if (check && !region.empty() && outside >= 0.5 * all) {
      ++st.holes;
      ++st.regionsOutside;
      continue;
    }
    st.holes += rs.holes;
    faces.insert(faces.end(), region.begin(), region.end());
  }
  size_t w = 0;
  for (const Triangle& f : faces) {
    if (nearlyCollinear(asStored(pos[f[0]], floatStorage), asStored(pos[f[1]], floatStorage),
                        asStored(pos[f[2]], floatStorage)))
      ++st.flatFacesRemoved;
    else
      faces[w++] = f;
  }
  faces.resize(w);
  return faces;
}

// Pieces of the output (faces joined through shared vertices: after the clean-up, through edges)
// that are not the largest piece on their input component and have fewer than minFaces faces are
// dropped: fragments cut off by regions left open, where the input is narrower than d or its
// border ragged at the scale of d. Every input component keeps its largest piece. A piece's input
// component is that of the input triangle closest to its first vertex. Returns the pieces dropped.
size_t dropSmallPiecesKeepingParts(std::vector<Triangle>& faces, const BorderGraph& g, const InputMesh& in,
                                   const Surface& surface, size_t minFaces, size_t& facesDropped) {
  facesDropped = 0;
  if (minFaces <= 1 || faces.empty()) return 0;
  std::vector<std::uint32_t> parent(g.vertexCount());
  std::iota(parent.begin(), parent.end(), 0u);
  for (const Triangle& f : faces)
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t x = findRoot(parent, f[0]), y = findRoot(parent, f[k]);
      if (x != y) parent[std::max(x, y)] = std::min(x, y);
    }
  std::vector<std::uint32_t> size(g.vertexCount(), 0);
  for (const Triangle& f : faces) ++size[findRoot(parent, f[0])];
  // Per input component, the largest piece (the smallest root among equals).
  std::vector<std::uint32_t> owner(g.vertexCount(), kNone), largest(in.faces.size(), kNone);
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v) {
    if (size[v] == 0 || findRoot(parent, v) != v) continue;
    const std::uint32_t t = surface.closestTriangle(g.positions()[v]);
    if (t == kNone) continue;
    owner[v] = in.component[t];
    std::uint32_t& l = largest[owner[v]];
    if (l == kNone || size[v] > size[l]) l = v;
  }
  size_t dropped = 0;
  std::vector<char> drop(g.vertexCount(), 0);
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    if (size[v] > 0 && size[v] < minFaces && owner[v] != kNone && largest[owner[v]] != v) {
      drop[v] = 1;
      ++dropped;
    }
  size_t w = 0;
  for (const Triangle& f : faces) {
    if (drop[findRoot(parent, f[0])]) ++facesDropped;
    else faces[w++] = f;
  }
  faces.resize(w);
  return dropped;
}

} // namespace

double defaultDiameterOf(double meanEdge, double area) {
  return std::min(kDefaultRemeshDiameterPerEdge * meanEdge,
                  std::sqrt(area / (kTriangleAreaFactor * kMinDefaultVertices)));
}

double defaultRemeshDiameter(const MeshArrays& mesh) {
  // The mean over the unique edges (an inner edge counts once), as InputMesh::meanEdge.
  std::vector<std::pair<std::uint32_t, std::uint32_t>> edges;
  edges.reserve(3 * mesh.faces.size());
  for (const auto& f : mesh.faces)
    for (int e = 0; e < 3; ++e) {
      const std::uint32_t u = f[e], v = f[(e + 1) % 3];
      if (u >= mesh.vertices.size() || v >= mesh.vertices.size() || u == v) continue;
      edges.emplace_back(std::min(u, v), std::max(u, v));
    }
  std::sort(edges.begin(), edges.end());
  edges.erase(std::unique(edges.begin(), edges.end()), edges.end());
  double sum = 0, area = 0;
  size_t n = 0;
  for (const auto& e : edges) {
    const double len = (mesh.vertices[e.first] - mesh.vertices[e.second]).Norm();
    if (!std::isfinite(len)) continue;
    sum += len;
    ++n;
  }
  for (const auto& f : mesh.faces) {
    if (f[0] >= mesh.vertices.size() || f[1] >= mesh.vertices.size() || f[2] >= mesh.vertices.size()) continue;
    const double a = 0.5 * ((mesh.vertices[f[1]] - mesh.vertices[f[0]]) ^ (mesh.vertices[f[2]] - mesh.vertices[f[0]])).Norm();
    if (std::isfinite(a)) area += a;
  }
  return n > 0 ? defaultDiameterOf(sum / double(n), area) : 0.0;
}

void remesh(const MeshArrays& mesh, bool floatStorage, MeshArrays& out, const RemeshParams& params, RemeshStat& st,
            CallBackPos* cb) {
  Stopwatch watch;
  out = MeshArrays();
  st = RemeshStat();
  Progress progress(cb);
  progress.phase("Sphere packing remesh: reading the mesh", 0, 5);
  InputMesh in = readMesh(mesh, params.creaseAngleDeg);
  st.inputVertices = mesh.vertices.size();
  st.inputFaces = in.faces.size();
  st.inputComponents = in.components;
  st.inputBoundaryEdges = in.boundaryEdgeCount;
  st.inputSlivers = in.slivers;
  st.inputMeanEdge = in.meanEdge;
  st.inputArea = in.area;
  if (!(params.windowSize >= 0) || params.maxBorderLength < 0)
    throw Error("The window size and the border limit must not be negative.");
  double d = params.sphereDiameter;
  if (d > 0) {
    st.diameterReason = "given";
  } else {
    d = defaultDiameterOf(in.meanEdge, in.area);
    st.diameterReason = d < kDefaultRemeshDiameterPerEdge * in.meanEdge
                            ? "automatic: the d of about " + std::to_string(size_t(kMinDefaultVertices)) +
                                  " vertices, below the input's mean edge length " + fmt(in.meanEdge)
                            : std::string("automatic: the input's mean edge length");
  }
  if (in.slivers == in.faces.size())
    throw Error("Every face of the mesh has (nearly) zero area: there is no surface to place vertices on.");
  if (!(d > 0) || !std::isfinite(d)) throw Error("The sphere diameter d must be a positive length.");
  const double diag = (in.box.max - in.box.min).Norm();
  if (d > kMaxDiameterPerDiagonal * diag)
    throw Error("d = " + fmt(d) + " is too large for this mesh (bounding-box diagonal " + fmt(diag) +
                "): no triangle of side d fits on it. Use a d below " + fmt(kMaxDiameterPerDiagonal * diag) +
                ", or 0 for the automatic one (" + fmt(defaultDiameterOf(in.meanEdge, in.area)) + ").");
  const double expected = in.area / (kTriangleAreaFactor * d * d);
  if (expected > double(params.maxOutputVertices))
    throw Error("d = " + fmt(d) + " is too small for this mesh: the output would have about " + fmt(expected) +
                " vertices, beyond the limit of " + std::to_string(params.maxOutputVertices) + ". Use a larger d "
                "(the input's mean edge length is " + fmt(in.meanEdge) + ").");
  st.sphereDiameter = d;
  TriangleGrid grid;
  grid.build(in, d);
  const Surface surface(in, grid, d);
  keepLongCreases(in, d, surface, params.creaseAngleDeg);
  st.secondsInput = watch.lap();

  progress.phase("Sphere packing remesh: growing", 5, 90);
  MeshGrowth growth(in, grid, surface, d, params, st, progress, size_t(expected));
  placeFeatures(growth, in, d, st);
  growEverywhere(growth, in, surface, d, st);
  const BorderGraph& g = growth.graph();
  st.secondsGrowth = watch.lap();

  progress.phase("Sphere packing remesh: triangulating the regions", 90, 97);
  std::vector<Triangle> faces = triangulateKeepingBoundary(g, surface, in.boundaryEdgeCount > 0, params, floatStorage, st);
  // Vertices of two patches may be closer than d (MeshGrowth::onPatch); a region whose border
  // passes from one to the other where a crease point was left out could join them by a diagonal
  // shorter than d: such a face is left out, so that every edge stays at least d.
  {
    const auto& pos = g.positions();
    size_t w = 0;
    for (const Triangle& f : faces) {
      if (hasEdgeBelow(pos[f[0]], pos[f[1]], pos[f[2]], d)) ++st.shortEdgeFacesRemoved;
      else faces[w++] = f;
    }
    faces.resize(w);
  }
  st.secondsTriangulation = watch.lap();

  Params p;
  p.threads = params.threads;
  p.minComponentFaces = 0;
  Stat ps;
  ps.sphereDiameter = d;
  makeManifold(faces, g, p, floatStorage, ps);
  st.nonManifoldVerticesRemoved = ps.nonManifoldVerticesRemoved;
  st.selfIntersectionFacesRemoved = ps.selfIntersectionFacesRemoved;
  st.facesRemoved = ps.facesRemoved;
  st.piecesDropped =
      dropSmallPiecesKeepingParts(faces, g, in, surface, size_t(std::max(params.minPieceFaces, 0)), st.pieceFacesDropped);
  // The hole pass (packer_holes.cpp) on the input surface: a closure's face has every edge at least d
  // (vertices of two patches may be closer) and lies on the input: its centroid, the midpoints of its
  // edges and the points halfway from the centroid to its corners are not beyond the input's boundary
  // (Surface::beyondBoundary), so a hole of the input stays open.
  if (params.closeHoles)
    closeHoles(faces, g,
               [&](const Vec3d& a, const Vec3d& b, const Vec3d& c, double) {
                 if (hasEdgeBelow(a, b, c, d)) return false;
                 const Vec3d m = (a + b + c) / 3.0;
                 for (const Vec3d& x : {m, (a + b) * 0.5, (b + c) * 0.5, (c + a) * 0.5, (m + a) * 0.5, (m + b) * 0.5,
                                        (m + c) * 0.5})
                   if (surface.beyondBoundary(x)) return false;
                 return true;
               },
               floatStorage, ps);
  st.holesClosed = ps.holesClosed;
  st.holeFacesAdded = ps.holeFacesAdded;
  st.holeFacesRemoved = ps.holeFacesRemoved;
  st.holesOpen = {ps.holesTooLong, ps.holesNotTriangulable, ps.holesNotCovered, ps.holesFolded, ps.holesCrossing,
                  ps.holesOther};
  st.secondsCleanup = watch.lap();

  progress.phase("Sphere packing remesh: writing the mesh", 97, 100);
  if (faces.empty())
    throw Error("No triangle could be built: the growth stopped after " + std::to_string(g.vertexCount()) +
                " vertices. d = " + fmt(d) + " is too large for this mesh's parts; try a smaller d.");
  writeMesh(faces, g, floatStorage, out, ps);
  checkTopology(out, ps);
  if (ps.nonManifoldVertices > 0 || ps.nonManifoldEdges > 0)
    throw std::logic_error("sphere packing remesher: the output is not manifold after the clean-up");
  st.vertices = ps.vertices;
  st.faces = ps.faces;
  st.boundaryLoops = ps.boundaryLoops;
  st.smallestEdge = ps.smallestEdge;
  st.qualityAvg = ps.qualityAvg;
  st.warnings = ps.warnings;
  if (st.facesRemoved > 0)
    st.warnings.push_back(std::to_string(st.facesRemoved) + " faces were removed to keep the mesh manifold and "
                          "free of intersections, leaving holes: d = " + fmt(d) + " is too large for some parts "
                          "(thin parts, narrow gaps); try a smaller d.");
  if (st.unreachedFaces > 0)
    st.warnings.push_back(std::to_string(st.unreachedFaces) + " input faces have no output vertex within d: parts "
                          "too small to hold a triangle of side d = " + fmt(d) + ".");
  st.secondsOutput = watch.lap();
  st.seconds = watch.total();
  try {
    progress.update(1.0);
  } catch (const Cancelled&) {
    out = MeshArrays();
    throw;
  }
}

} // namespace spherepack
} // namespace growth
