#include <growth/cloud_generator.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>
#include <growth/cloud_scale.h>
#include <growth/morton.h>
#include <growth/point_grid.h>
#include <growth/self_intersections.h>


#include <algorithm>
#include <cfloat>
#include <cmath>
#include <cstdint>
#include <iomanip>
#include <numeric>
#include <sstream>

namespace growth {

namespace {

constexpr double kPi = 3.14159265358979323846;

// Union–find with path halving and union by size.
class DisjointSets {
public:
  explicit DisjointSets(size_t n) {
    reserveHuge(parent_, n, /*populate=*/true); // written whole: resident in one call each
    parent_.resize(n);
    std::iota(parent_.begin(), parent_.end(), 0u);
    assignHuge(size_, n, 1u);
  }
  std::uint32_t find(std::uint32_t x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(std::uint32_t a, std::uint32_t b) {
    a = find(a);
    b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

private:
  std::vector<std::uint32_t> parent_;
  std::vector<std::uint32_t> size_;
};

// The mesh in compact double arrays: live vertices renumbered 0..n-1, live faces in order.
struct Compact {
  std::vector<Vec3d> vert;
  std::vector<std::array<int, 3>> face;   // all live faces
  std::vector<char> proper;               // face has three distinct vertices
};

Compact compact(const MeshArrays& mesh) {
  Compact c;
  c.vert = mesh.vertices;
  const size_t n = c.vert.size();
  // The arrays are written whole: made resident in one call each (huge_pages.h), not page by page.
  reserveHuge(c.face, mesh.faces.size(), /*populate=*/true);
  reserveHuge(c.proper, mesh.faces.size(), /*populate=*/true);
  for (const auto& f : mesh.faces) {
    std::array<int, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = f[k] < n ? static_cast<int>(f[k]) : -1; // (a deleted vertex)
    c.face.push_back(t);
    c.proper.push_back(t[0] != t[1] && t[1] != t[2] && t[2] != t[0] && t[0] >= 0 && t[1] >= 0 && t[2] >= 0);
  }
  return c;
}

// Zero height up to float storage: the mesh came from float coordinates, so a height below a few
// float ulps of the coordinates' magnitude is rounding, not geometry.
bool zeroArea(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double twiceArea = ((b - a) ^ (c - a)).Norm();
  const double lmax = std::max({(b - a).Norm(), (c - b).Norm(), (a - c).Norm()});
  double mag = 0;
  for (const auto* p : {&a, &b, &c})
    for (int k = 0; k < 3; ++k) mag = std::max(mag, std::abs((*p)[k]));
  if (!(lmax > 0)) return true;
  return twiceArea / lmax <= 4.0 * double(FLT_EPSILON) * mag;
}

// Edge structure of the proper faces: unique undirected edges with their incident half-edges.
struct Edges {
  // Half-edge h = 3·f + k runs face[f][k] → face[f][(k+1)%3]; heEdge[h] is its edge (or -1 for
  // faces that are not proper).
  std::vector<int> heEdge;
  std::vector<std::array<int, 2>> ends;   // edge endpoints, ends[e][0] < ends[e][1]
  std::vector<int> start;                 // CSR: half-edges of edge e are he[start[e] .. start[e+1])
  std::vector<int> he;
  size_t faceCount(int e) const { return size_t(start[e + 1] - start[e]); }
};

Edges buildEdges(const Compact& c) {
  struct Rec {
    int u, v, h;
  };
  std::vector<Rec> recs;
  reserveHuge(recs, 3 * c.face.size(), /*populate=*/true); // (all but the few improper faces')
  for (size_t f = 0; f < c.face.size(); ++f) {
    if (!c.proper[f]) continue;
    for (int k = 0; k < 3; ++k) {
      const int a = c.face[f][k], b = c.face[f][(k + 1) % 3];
      recs.push_back({std::min(a, b), std::max(a, b), int(3 * f) + k});
    }
  }
  std::sort(recs.begin(), recs.end(), [](const Rec& x, const Rec& y) {
    return x.u != y.u ? x.u < y.u : x.v != y.v ? x.v < y.v : x.h < y.h;
  });
  Edges e;
  assignHuge(e.heEdge, 3 * c.face.size(), -1);
  reserveHuge(e.he, recs.size(), /*populate=*/true);
  size_t edges = 0;
  for (size_t i = 0; i < recs.size(); ++i)
    edges += (i == 0 || recs[i].u != recs[i - 1].u || recs[i].v != recs[i - 1].v) ? 1 : 0;
  reserveHuge(e.start, edges + 1, /*populate=*/true);
  reserveHuge(e.ends, edges, /*populate=*/true);
  for (size_t i = 0; i < recs.size(); ++i) {
    if (i == 0 || recs[i].u != recs[i - 1].u || recs[i].v != recs[i - 1].v) {
      e.start.push_back(int(i));
      e.ends.push_back({recs[i].u, recs[i].v});
    }
    e.heEdge[size_t(recs[i].h)] = int(e.ends.size()) - 1;
    e.he.push_back(recs[i].h);
  }
  e.start.push_back(int(recs.size()));
  return e;
}

int heFrom(const Compact& c, int h) { return c.face[size_t(h / 3)][h % 3]; }
int heTo(const Compact& c, int h) { return c.face[size_t(h / 3)][(h % 3 + 1) % 3]; }

// Index (0..2) of vertex v in face f.
int cornerOf(const Compact& c, size_t f, int v) {
  return c.face[f][0] == v ? 0 : c.face[f][1] == v ? 1 : 2;
}

// Among the two edges of proper face f incident to vertex v, the one that is not `edge`.
int otherEdgeAt(const Compact& c, const Edges& e, size_t f, int v, int edge) {
  const int k = cornerOf(c, f, v);
  const int in = e.heEdge[3 * f + size_t((k + 2) % 3)];   // edge ending at v
  const int out = e.heEdge[3 * f + size_t(k)];            // edge starting at v
  return in == edge ? out : in;
}

// The components' faces, vertices, edges, boundary loops, Euler characteristic and genus, largest
// (most faces) first. `faces` holds the edge-connected face sets.
void componentCounts(const Compact& c, const Edges& e, const MeshTopology& t, DisjointSets& faces,
                     const std::vector<std::uint32_t>& loopFaces, std::vector<ComponentTopology>& out) {
  out.clear();
  std::vector<std::uint32_t> slot;   // face set root -> component index, in the order of first face
  assignHuge(slot, c.face.size(), UINT32_MAX);
  std::vector<std::pair<std::uint32_t, std::uint32_t>> cornerPairs;   // (component, vertex)
  reserveHuge(cornerPairs, 3 * c.face.size(), /*populate=*/true);
  for (size_t f = 0; f < c.face.size(); ++f) {
    if (!c.proper[f]) continue;
    std::uint32_t& s = slot[faces.find(std::uint32_t(f))];
    if (s == UINT32_MAX) {
      s = std::uint32_t(out.size());
      out.emplace_back();
    }
    ++out[s].faces;
    for (int k = 0; k < 3; ++k) cornerPairs.push_back({s, std::uint32_t(c.face[f][k])});
  }
  std::sort(cornerPairs.begin(), cornerPairs.end());
  for (size_t i = 0; i < cornerPairs.size(); ++i)
    if (i == 0 || cornerPairs[i] != cornerPairs[i - 1]) ++out[cornerPairs[i].first].vertices;
  for (size_t ei = 0; ei < e.ends.size(); ++ei) ++out[slot[faces.find(std::uint32_t(e.he[size_t(e.start[ei])] / 3))]].edges;
  for (std::uint32_t f : loopFaces) ++out[slot[faces.find(f)]].boundaryLoops;
  // The genus is defined on orientable manifolds: the same conditions as MeshMeasures::genus.
  const bool surface = t.nonManifoldEdges == 0 && t.nonManifoldVertices == 0 && t.inconsistentEdges == 0 && t.duplicateFaces == 0 &&
                       std::all_of(c.proper.begin(), c.proper.end(), [](char p) { return p != 0; });
  for (ComponentTopology& k : out) {
    k.eulerCharacteristic = int(k.vertices) - int(k.edges) + int(k.faces);
    const long twiceGenus = 2 - long(k.eulerCharacteristic) - long(k.boundaryLoops);
    k.genus = surface && twiceGenus >= 0 && twiceGenus % 2 == 0 ? int(twiceGenus / 2) : -1;
  }
  std::stable_sort(out.begin(), out.end(), [](const ComponentTopology& a, const ComponentTopology& b) { return a.faces > b.faces; });
}

// `perComponent` (optional): the components' own counts, largest first (see componentTopology).
MeshTopology topology(const Compact& c, const Edges& e, std::vector<ComponentTopology>* perComponent = nullptr) {
  MeshTopology t;
  std::vector<std::uint32_t> loopFaces;   // a face of each boundary loop (for perComponent)
  t.edges = e.ends.size();
  const size_t nf = c.face.size();

  std::vector<char> referenced;
  assignHuge(referenced, c.vert.size(), char(0));
  for (size_t f = 0; f < nf; ++f)
    for (int k = 0; k < 3; ++k)
      if (c.face[f][k] >= 0) referenced[size_t(c.face[f][k])] = 1;
  t.unreferencedVertices = size_t(std::count(referenced.begin(), referenced.end(), 0));

  // Degenerate and duplicate faces.
  std::vector<std::pair<std::array<int, 3>, size_t>> sorted;
  reserveHuge(sorted, nf, /*populate=*/true);
  for (size_t f = 0; f < nf; ++f) {
    const auto& v = c.face[f];
    if (!c.proper[f] || zeroArea(c.vert[size_t(v[0])], c.vert[size_t(v[1])], c.vert[size_t(v[2])]))
      ++t.degenerateFaces;
    std::array<int, 3> s = v;
    std::sort(s.begin(), s.end());
    sorted.push_back({s, f});
  }
  std::sort(sorted.begin(), sorted.end());
  for (size_t i = 1; i < sorted.size(); ++i)
    if (sorted[i].first == sorted[i - 1].first) ++t.duplicateFaces;

  // Per edge: boundary, non-manifold, orientation; fans (corner sets) and components (face sets).
  DisjointSets corners(3 * nf), faces(nf);
  for (size_t ei = 0; ei < e.ends.size(); ++ei) {
    const int n = int(e.faceCount(int(ei)));
    const int* h = &e.he[size_t(e.start[ei])];
    if (n == 1) ++t.boundaryEdges;
    if (n > 2) ++t.nonManifoldEdges;
    for (int j = 1; j < n; ++j) faces.unite(std::uint32_t(h[0] / 3), std::uint32_t(h[j] / 3));
    if (n != 2) continue;
    if (heFrom(c, h[0]) == heFrom(c, h[1])) ++t.inconsistentEdges;
    const size_t f = size_t(h[0] / 3), g = size_t(h[1] / 3);
    for (int v : e.ends[ei])
      corners.unite(std::uint32_t(3 * f + size_t(cornerOf(c, f, v))), std::uint32_t(3 * g + size_t(cornerOf(c, g, v))));
  }
  // A fan is a set of corners at one vertex joined across two-face edges (unions only ever join
  // corners of the same vertex), so the roots at a vertex count its fans.
  std::vector<std::uint32_t> fans;
  assignHuge(fans, c.vert.size(), 0u);
  for (size_t f = 0; f < nf; ++f) {
    if (!c.proper[f]) continue;
    if (faces.find(std::uint32_t(f)) == f) ++t.components;
    for (int k = 0; k < 3; ++k)
      if (corners.find(std::uint32_t(3 * f + size_t(k))) == 3 * f + size_t(k)) ++fans[size_t(c.face[f][k])];
  }
  t.nonManifoldVertices = size_t(std::count_if(fans.begin(), fans.end(), [](std::uint32_t n) { return n > 1; }));

  // Boundary loops: from a boundary edge arriving at v, the next one is found by walking through
  // the faces around v across two-face edges (so the loops of a bow-tie stay apart). A walk that
  // meets a non-manifold edge ends the loop there.
  std::vector<std::uint32_t> degree;
  assignHuge(degree, c.vert.size(), 0u);
  for (size_t f = 0; f < nf; ++f)
    if (c.proper[f])
      for (int k = 0; k < 3; ++k) ++degree[size_t(c.face[f][k])];
  std::vector<char> visited;
  assignHuge(visited, e.ends.size(), char(0));
  for (size_t e0 = 0; e0 < e.ends.size(); ++e0) {
    if (e.faceCount(int(e0)) != 1 || visited[e0]) continue;
    ++t.boundaryLoops;
    visited[e0] = 1;
    loopFaces.push_back(std::uint32_t(e.he[size_t(e.start[e0])] / 3));
    int edge = int(e0);
    const int h0 = e.he[size_t(e.start[e0])];
    int v = heTo(c, h0);   // walk along the orientation of the boundary face
    size_t f = size_t(h0 / 3);
    for (;;) {
      // Walk around v from face f, starting across `edge`, to the next boundary edge.
      int next = -1;
      for (std::uint32_t steps = 0; steps <= degree[size_t(v)]; ++steps) {
        const int cand = otherEdgeAt(c, e, f, v, edge);
        const size_t n = e.faceCount(cand);
        if (n == 1) {
          next = cand;
          break;
        }
        if (n != 2) break;
        const int* h = &e.he[size_t(e.start[size_t(cand)])];
        f = size_t(h[0] / 3) == f ? size_t(h[1] / 3) : size_t(h[0] / 3);
        edge = cand;
      }
      if (next < 0 || visited[size_t(next)]) break;
      visited[size_t(next)] = 1;
      edge = next;
      f = size_t(e.he[size_t(e.start[size_t(next)])] / 3);
      v = e.ends[size_t(next)][0] == v ? e.ends[size_t(next)][1] : e.ends[size_t(next)][0];
    }
  }
  if (perComponent) componentCounts(c, e, t, faces, loopFaces, *perComponent);
  return t;
}

// Self-intersecting pairs among the proper faces (exact, growth/self_intersections.h).
size_t selfIntersectingPairs(const Compact& c) {
  std::vector<Triangle> faces(c.face.size(), Triangle{{0, 0, 0}});
  std::vector<char> alive(c.face.size(), 0);
  for (size_t f = 0; f < c.face.size(); ++f) {
    if (!c.proper[f]) continue;
    for (int k = 0; k < 3; ++k) faces[f][size_t(k)] = std::uint32_t(c.face[f][size_t(k)]);
    alive[f] = 1;
  }
  return findSelfIntersections(c.vert, faces, &alive).size();
}

double angleBetween(const Vec3d& u, const Vec3d& w) {
  return std::atan2((u ^ w).Norm(), u * w);
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s << std::setprecision(10) << v;
  return s.str();
}

} // namespace

// --- Histogram ---

void Histogram::add(double v) {
  if (counts.empty()) return;
  if (std::isnan(v)) {
    ++above;
    return;
  }
  if (v < lo) {
    ++below;
    return;
  }
  if (v > hi || !(hi > lo)) {
    ++above;
    return;
  }
  const size_t bin = std::min(counts.size() - 1, static_cast<size_t>((v - lo) / (hi - lo) * double(counts.size())));
  ++counts[bin];
}

size_t Histogram::total() const {
  return std::accumulate(counts.begin(), counts.end(), size_t(0)) + below + above;
}

// --- Single triangles ---

double triangleQuality(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double sum = (b - a).SquaredNorm() + (c - b).SquaredNorm() + (a - c).SquaredNorm();
  if (!(sum > 0)) return 0;
  const double area = 0.5 * ((b - a) ^ (c - a)).Norm();
  return 4.0 * std::sqrt(3.0) * area / sum;
}

double triangleQF(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const double d1 = (b - a).Norm(), d2 = (c - b).Norm(), d3 = (a - c).Norm();
  const double p = 0.5 * (d1 + d2 + d3), dmax = std::max({d1, d2, d3});
  if (!(p > 0) || !(dmax > 0)) return 0;
  // Heron: sqrt((p-d1)(p-d2)(p-d3)/p) = A/p; the cross product gives A without cancellation.
  const double area = 0.5 * ((b - a) ^ (c - a)).Norm();
  return std::sqrt(12.0) * area / (p * dmax);
}

// --- Topology ---

MeshTopology measureTopology(const MeshArrays& mesh) {
  const Compact c = compact(mesh);
  return topology(c, buildEdges(c));
}

std::vector<ComponentTopology> componentTopology(const MeshArrays& mesh) {
  const Compact c = compact(mesh);
  std::vector<ComponentTopology> out;
  topology(c, buildEdges(c), &out);
  return out;
}

size_t countBoundaryEdges(const MeshArrays& m) { return measureTopology(m).boundaryEdges; }
size_t countNonManifoldEdges(const MeshArrays& m) { return measureTopology(m).nonManifoldEdges; }
size_t countNonManifoldVertices(const MeshArrays& m) { return measureTopology(m).nonManifoldVertices; }
size_t countBoundaryLoops(const MeshArrays& m) { return measureTopology(m).boundaryLoops; }
size_t countComponents(const MeshArrays& m) { return measureTopology(m).components; }
size_t countInconsistentEdges(const MeshArrays& m) { return measureTopology(m).inconsistentEdges; }
bool isConsistentlyOriented(const MeshArrays& m) { return measureTopology(m).inconsistentEdges == 0; }
size_t countDegenerateFaces(const MeshArrays& m) { return measureTopology(m).degenerateFaces; }
size_t countDuplicateFaces(const MeshArrays& m) { return measureTopology(m).duplicateFaces; }
size_t countSelfIntersections(const MeshArrays& m) { return selfIntersectingPairs(compact(m)); }

// --- Distance of points to the mesh ---

MeshDistance::MeshDistance(const MeshArrays& mesh) {
  Compact c = compact(mesh);
  vert_ = std::move(c.vert);
  std::vector<Item> items;
  items.reserve(c.face.size());
  for (size_t f = 0; f < c.face.size(); ++f) {
    const auto& t = c.face[f];
    if (t[0] < 0 || t[1] < 0 || t[2] < 0) continue;
    items.push_back({(vert_[size_t(t[0])] + vert_[size_t(t[1])] + vert_[size_t(t[2])]) / 3.0, int(f)});
  }
  if (items.empty()) return;
  nodes_.reserve(items.size() / 2 + 1);
  nodes_.push_back(Node());
  build(0, 0, int(items.size()), items);
  tri_.reserve(items.size());
  for (const Item& it : items) tri_.push_back(c.face[size_t(it.face)]);
  // Boxes bottom-up: children are always stored after their parent.
  for (size_t i = nodes_.size(); i-- > 0;) {
    Node& n = nodes_[i];
    for (int k = 0; k < 3; ++k) {
      n.lo[k] = std::numeric_limits<double>::infinity();
      n.hi[k] = -std::numeric_limits<double>::infinity();
    }
    if (n.count > 0) {
      for (int t = n.first; t < n.first + n.count; ++t)
        for (int j = 0; j < 3; ++j) {
          const Vec3d& p = vert_[size_t(tri_[size_t(t)][j])];
          for (int k = 0; k < 3; ++k) {
            n.lo[k] = std::min(n.lo[k], p[k]);
            n.hi[k] = std::max(n.hi[k], p[k]);
          }
        }
    } else {
      for (const Node* child : {&nodes_[size_t(n.first)], &nodes_[size_t(n.first + 1)]})
        for (int k = 0; k < 3; ++k) {
          n.lo[k] = std::min(n.lo[k], child->lo[k]);
          n.hi[k] = std::max(n.hi[k], child->hi[k]);
        }
    }
  }
}

// Median split of the centroids along their longest extent, in place (the items of a subtree stay
// contiguous, so the leaves refer to ranges of the final triangle order).
void MeshDistance::build(int node, int begin, int end, std::vector<Item>& items) {
  constexpr int kLeafSize = 4;
  if (end - begin <= kLeafSize) {
    nodes_[size_t(node)].first = begin;
    nodes_[size_t(node)].count = end - begin;
    return;
  }
  Box3d cbox;
  for (int i = begin; i < end; ++i) cbox.Add(items[size_t(i)].centroid);
  const Vec3d ext = cbox.Dim();
  const int axis = ext[0] >= ext[1] && ext[0] >= ext[2] ? 0 : ext[1] >= ext[2] ? 1 : 2;
  const int mid = begin + (end - begin) / 2;
  std::nth_element(items.begin() + begin, items.begin() + mid, items.begin() + end, [axis](const Item& a, const Item& b) {
    const double ca = a.centroid[axis], cb = b.centroid[axis];
    return ca != cb ? ca < cb : a.face < b.face;
  });
  const int left = int(nodes_.size());
  nodes_[size_t(node)].first = left;
  nodes_[size_t(node)].count = 0;
  nodes_.push_back(Node());
  nodes_.push_back(Node());
  build(left, begin, mid, items);
  build(left + 1, mid, end, items);
}

namespace {
double squaredSegmentDistance(const Vec3d& p, const Vec3d& a, const Vec3d& b) {
  const Vec3d ab = b - a;
  const double len2 = ab.SquaredNorm();
  double t = len2 > 0 ? ((p - a) * ab) / len2 : 0;
  t = std::min(1.0, std::max(0.0, t));
  return (p - (a + ab * t)).SquaredNorm();
}

double squaredBoxDistance(const Vec3d& p, const double lo[3], const double hi[3]) {
  double d2 = 0;
  for (int k = 0; k < 3; ++k) {
    const double d = p[k] < lo[k] ? lo[k] - p[k] : p[k] > hi[k] ? p[k] - hi[k] : 0.0;
    d2 += d * d;
  }
  return d2;
}
} // namespace

// Closest point on a triangle by Voronoi regions (Ericson, Real-Time Collision Detection, 5.1.5);
// triangles without area (within double precision) are measured as their three segments.
double MeshDistance::squaredDistanceToTriangle(const Vec3d& p, int t) const {
  const Vec3d& a = vert_[size_t(tri_[size_t(t)][0])];
  const Vec3d& b = vert_[size_t(tri_[size_t(t)][1])];
  const Vec3d& c = vert_[size_t(tri_[size_t(t)][2])];
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  if (!((ab ^ ac).SquaredNorm() > 1e-24 * ab.SquaredNorm() * ac.SquaredNorm()))
    return std::min({squaredSegmentDistance(p, a, b), squaredSegmentDistance(p, b, c), squaredSegmentDistance(p, c, a)});
  const double d1 = ab * ap, d2 = ac * ap;
  if (d1 <= 0 && d2 <= 0) return ap.SquaredNorm();
  const Vec3d bp = p - b;
  const double d3 = ab * bp, d4 = ac * bp;
  if (d3 >= 0 && d4 <= d3) return bp.SquaredNorm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return (p - (a + ab * v)).SquaredNorm();
  }
  const Vec3d cp = p - c;
  const double d5 = ab * cp, d6 = ac * cp;
  if (d6 >= 0 && d5 <= d6) return cp.SquaredNorm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return (p - (a + ac * w)).SquaredNorm();
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return (p - (b + (c - b) * w)).SquaredNorm();
  }
  const double denom = va + vb + vc;
  const double v = vb / denom, w = vc / denom;
  return (p - (a + ab * v + ac * w)).SquaredNorm();
}

double MeshDistance::distance(const Vec3d& p, int* hint) const {
  if (nodes_.empty()) return std::numeric_limits<double>::infinity();
  // A triangle near p (the previous query's answer, for queries in spatial order) bounds the search
  // from the start, so most of the tree is pruned at once.
  int bestTri = hint && *hint >= 0 && *hint < int(tri_.size()) ? *hint : -1;
  double best = bestTri >= 0 ? squaredDistanceToTriangle(p, bestTri) : std::numeric_limits<double>::infinity();
  int stack[128];
  int top = 0;
  stack[top++] = 0;
  while (top > 0) {
    const Node& n = nodes_[size_t(stack[--top])];
    if (squaredBoxDistance(p, n.lo, n.hi) >= best) continue;
    if (n.count > 0) {
      for (int t = n.first; t < n.first + n.count; ++t) {
        const double d2 = squaredDistanceToTriangle(p, t);
        if (d2 < best) {
          best = d2;
          bestTri = t;
        }
      }
      continue;
    }
    // Visit the nearer child first: push it last.
    const Node& l = nodes_[size_t(n.first)];
    const Node& r = nodes_[size_t(n.first + 1)];
    const double dl = squaredBoxDistance(p, l.lo, l.hi), dr = squaredBoxDistance(p, r.lo, r.hi);
    if (dl <= dr) {
      if (dr < best) stack[top++] = n.first + 1;
      if (dl < best) stack[top++] = n.first;
    } else {
      if (dl < best) stack[top++] = n.first;
      if (dr < best) stack[top++] = n.first + 1;
    }
  }
  if (hint) *hint = bestTri;
  return std::sqrt(best);
}

namespace {
// Distance of every point to the index's mesh, in the points' order. The queries run in Morton order,
// each starting from the previous answer (a near triangle bounds the search from the start).
std::vector<double> distancesTo(const MeshDistance& index, const std::vector<Vec3d>& points) {
  Box3d box;
  for (const auto& p : points) box.Add(p);
  const Vec3d dim = box.Dim();
  const double scale = double((1 << 21) - 1) / std::max({dim[0], dim[1], dim[2], 1e-300});
  std::vector<std::pair<std::uint64_t, std::uint32_t>> order(points.size());
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec3d q = (points[i] - box.min) * scale;
    auto cell = [](double v) { return std::uint64_t(std::isfinite(v) ? std::min(std::max(v, 0.0), double((1 << 21) - 1)) : 0.0); };
    order[i] = {mortonCode(cell(q[0]), cell(q[1]), cell(q[2])), std::uint32_t(i)};
  }
  std::sort(order.begin(), order.end());
  std::vector<double> dist(points.size());
  int hint = -1;
  for (const auto& o : order) dist[o.second] = index.distance(points[o.second], &hint);
  return dist;
}
} // namespace

void measureCloudDistance(const MeshArrays& mesh, const std::vector<Vec3d>& cloud, MeshMeasures& out) {
  out.hasCloud = true;
  out.cloudPoints = cloud.size();
  out.cloudSpacing = cloud.size() >= 2 ? meanSpacing(cloud) : MeshMeasures::kNaN;
  out.pointsFartherThanSpacing = 0;
  const MeshDistance index(mesh);
  if (index.empty() || cloud.empty()) {
    out.distanceMean = out.distanceMax = out.muDPercent = MeshMeasures::kNaN;
    return;
  }
  // The sum is taken in the cloud's own order, so the result does not depend on the visiting order.
  const std::vector<double> dist = distancesTo(index, cloud);
  double sum = 0, maxDist = 0;
  for (double d : dist) {
    sum += d;
    maxDist = std::max(maxDist, d);
    if (d > out.cloudSpacing) ++out.pointsFartherThanSpacing;
  }
  out.distanceMean = sum / double(cloud.size());
  out.distanceMax = maxDist;
  out.muDPercent = out.cloudSpacing > 0 ? 100.0 * out.distanceMean / out.cloudSpacing : MeshMeasures::kNaN;
}

// --- Distance between two surfaces ---

std::vector<Vec3d> sampleSurface(const MeshArrays& mesh, size_t extra, std::uint64_t seed, size_t* vertexSamples) {
  const Compact c = compact(mesh);
  std::vector<char> used(c.vert.size(), 0);
  std::vector<double> cumulative;   // running sum of the proper faces' areas
  std::vector<size_t> faceOf;
  double total = 0;
  for (size_t f = 0; f < c.face.size(); ++f) {
    if (!c.proper[f]) continue;
    for (int k = 0; k < 3; ++k) used[size_t(c.face[f][k])] = 1;
    const Vec3d& a = c.vert[size_t(c.face[f][0])];
    total += 0.5 * ((c.vert[size_t(c.face[f][1])] - a) ^ (c.vert[size_t(c.face[f][2])] - a)).Norm();
    cumulative.push_back(total);
    faceOf.push_back(f);
  }
  std::vector<Vec3d> out;
  for (size_t v = 0; v < c.vert.size(); ++v)
    if (used[v]) out.push_back(c.vert[v]);
  if (vertexSamples) *vertexSamples = out.size();
  if (!(total > 0)) return out;
  Random rng(seed);
  out.reserve(out.size() + extra);
  for (size_t i = 0; i < extra; ++i) {
    const double at = rng.uniform() * total;
    const size_t j = std::min(size_t(std::upper_bound(cumulative.begin(), cumulative.end(), at) - cumulative.begin()), faceOf.size() - 1);
    const auto& t = c.face[faceOf[j]];
    // Uniform in the triangle: barycentric (1 − √r1, √r1 (1 − r2), √r1 r2).
    const double r1 = std::sqrt(rng.uniform()), r2 = rng.uniform();
    out.push_back(c.vert[size_t(t[0])] * (1 - r1) + c.vert[size_t(t[1])] * (r1 * (1 - r2)) + c.vert[size_t(t[2])] * (r1 * r2));
  }
  return out;
}

SurfaceDistance surfaceDistance(const MeshArrays& from, const MeshArrays& to, std::uint64_t seed) {
  SurfaceDistance s;
  const MeshDistance index(to);
  const std::vector<Vec3d> samples = sampleSurface(from, from.faces.size(), seed, &s.vertexSamples);
  s.samples = samples.size();
  if (index.empty() || samples.empty()) return s;
  const std::vector<double> dist = distancesTo(index, samples);
  double sum = 0;
  s.max = s.vertexMax = 0;
  for (size_t i = 0; i < dist.size(); ++i) {
    sum += dist[i];
    s.max = std::max(s.max, dist[i]);
    if (i < s.vertexSamples) s.vertexMax = std::max(s.vertexMax, dist[i]);
  }
  s.mean = sum / double(dist.size());
  return s;
}

// --- Everything ---

MeshMeasures measure(const MeshArrays& mesh, const std::vector<Vec3d>* cloud, const MeasureOptions& options) {
  MeshMeasures m;
  const Compact c = compact(mesh);
  const Edges e = buildEdges(c);
  const MeshTopology t = topology(c, e, &m.perComponent);
  m.vertices = c.vert.size();
  m.faces = c.face.size();
  if (!c.vert.empty()) {
    Box3d box;
    for (const auto& p : c.vert) box.Add(p);
    m.boxDiagonal = box.Diag();
  }
  m.unreferencedVertices = t.unreferencedVertices;
  m.edges = t.edges;
  m.boundaryEdges = t.boundaryEdges;
  m.nonManifoldEdges = t.nonManifoldEdges;
  m.nonManifoldVertices = t.nonManifoldVertices;
  m.boundaryLoops = t.boundaryLoops;
  m.components = t.components;
  m.inconsistentEdges = t.inconsistentEdges;
  m.degenerateFaces = t.degenerateFaces;
  m.duplicateFaces = t.duplicateFaces;
  m.selfIntersectingPairs = selfIntersectingPairs(c);
  const size_t properFaces = size_t(std::count(c.proper.begin(), c.proper.end(), 1));
  m.eulerCharacteristic = int(m.vertices - m.unreferencedVertices) - int(m.edges) + int(properFaces);
  // An orientable surface of genus g with b boundary loops has χ = 2 − 2g − b, per component. A face
  // of zero area is still a face of the surface; one with a repeated vertex is not.
  if (m.manifold() && m.consistentlyOriented() && properFaces == m.faces && m.duplicateFaces == 0) {
    const long twiceGenus = 2 * long(m.components) - long(m.eulerCharacteristic) - long(m.boundaryLoops);
    if (twiceGenus >= 0 && twiceGenus % 2 == 0) m.genus = int(twiceGenus / 2);
  }

  // Edge lengths.
  std::vector<double> len(e.ends.size());
  for (size_t i = 0; i < len.size(); ++i) len[i] = (c.vert[size_t(e.ends[i][0])] - c.vert[size_t(e.ends[i][1])]).Norm();
  if (!len.empty()) {
    double sum = 0;
    m.edgeMin = m.edgeMax = len[0];
    for (double l : len) {
      sum += l;
      m.edgeMin = std::min(m.edgeMin, l);
      m.edgeMax = std::max(m.edgeMax, l);
    }
    m.edgeMean = sum / double(len.size());
    double dev = 0;
    for (double l : len) dev += (l - m.edgeMean) * (l - m.edgeMean);
    m.edgeRmsPercent = m.edgeMean > 0 ? 100.0 * std::sqrt(dev / double(len.size())) / m.edgeMean : MeshMeasures::kNaN;
  }
  const double edgeHistMax = options.edgeHistogramMax > 0 ? options.edgeHistogramMax
                             : m.edgeMean > 0           ? 3.0 * m.edgeMean
                                                        : 1.0;
  m.edgeHistogram = Histogram(0, edgeHistMax, options.edgeBins);
  for (double l : len) m.edgeHistogram.add(l);

  // Triangle shape.
  m.angleHistogram = Histogram(0, 180, options.angleBins);
  m.qualityHistogram = Histogram(0, 1, options.qualityBins);
  std::vector<double> q;
  q.reserve(properFaces);
  double qfSum = 0, minAngle = std::numeric_limits<double>::infinity(), maxAngle = -minAngle;
  for (size_t f = 0; f < c.face.size(); ++f) {
    if (!c.proper[f]) continue;
    const Vec3d& a = c.vert[size_t(c.face[f][0])];
    const Vec3d& b = c.vert[size_t(c.face[f][1])];
    const Vec3d& d = c.vert[size_t(c.face[f][2])];
    q.push_back(triangleQuality(a, b, d));
    m.qualityHistogram.add(q.back());
    qfSum += triangleQF(a, b, d);
    if ((b - a).SquaredNorm() > 0 && (d - b).SquaredNorm() > 0 && (a - d).SquaredNorm() > 0) {
      const double deg = 180.0 / kPi;
      for (double ang : {angleBetween(b - a, d - a), angleBetween(a - b, d - b), angleBetween(a - d, b - d)}) {
        minAngle = std::min(minAngle, ang * deg);
        maxAngle = std::max(maxAngle, ang * deg);
        m.angleHistogram.add(ang * deg);
      }
    }
  }
  if (!q.empty()) {
    double sum = 0;
    m.qualityMin = q[0];
    for (double v : q) {
      sum += v;
      m.qualityMin = std::min(m.qualityMin, v);
    }
    m.qualityMean = sum / double(q.size());
    double dev = 0;
    for (double v : q) dev += (v - m.qualityMean) * (v - m.qualityMean);
    m.qualityRmsPercent = m.qualityMean > 0 ? 100.0 * std::sqrt(dev / double(q.size())) / m.qualityMean : MeshMeasures::kNaN;
    m.qfMean = qfSum / double(q.size());
  }
  if (std::isfinite(minAngle)) {
    m.minAngleDeg = minAngle;
    m.maxAngleDeg = maxAngle;
  }

  // Smallest distance between two vertices (the sphere packer guarantees d).
  if (options.minVertexDistance && c.vert.size() >= 2) {
    Box3d box;
    for (const auto& p : c.vert) box.Add(p);
    PointGrid grid;
    const double cell = m.edgeMean > 0 ? m.edgeMean : roughSpacing(box, c.vert.size());
    grid.build(c.vert, std::max(cell, 1e-12 * (1.0 + box.Diag())));
    double best = std::numeric_limits<double>::infinity();
    for (size_t i = 0; i < c.vert.size(); ++i) {
      double d2 = 0;
      if (grid.nearest(c.vert[i], &d2, int(i)) >= 0) best = std::min(best, d2);
    }
    if (std::isfinite(best)) m.minVertexDistance = std::sqrt(best);
  }

  if (cloud) measureCloudDistance(mesh, *cloud, m);
  return m;
}

std::string MeshMeasures::toJson() const {
  std::ostringstream s;
  auto field = [&](const char* name, const std::string& value, bool last = false) {
    s << "  \"" << name << "\": " << value << (last ? "\n" : ",\n");
  };
  auto count = [](size_t v) { return std::to_string(v); };
  s << "{\n";
  field("vertices", count(vertices));
  field("faces", count(faces));
  field("unreferenced_vertices", count(unreferencedVertices));
  field("edges", count(edges));
  field("box_diagonal", number(boxDiagonal));
  field("edge_mean", number(edgeMean));
  field("edge_rms_percent", number(edgeRmsPercent));
  field("edge_min", number(edgeMin));
  field("edge_max", number(edgeMax));
  field("min_vertex_distance", number(minVertexDistance));
  field("quality_mean", number(qualityMean));
  field("quality_rms_percent", number(qualityRmsPercent));
  field("quality_min", number(qualityMin));
  field("qf_mean", number(qfMean));
  field("min_angle_deg", number(minAngleDeg));
  field("max_angle_deg", number(maxAngleDeg));
  field("boundary_edges", count(boundaryEdges));
  field("boundary_loops", count(boundaryLoops));
  field("non_manifold_edges", count(nonManifoldEdges));
  field("non_manifold_vertices", count(nonManifoldVertices));
  field("components", count(components));
  field("inconsistent_edges", count(inconsistentEdges));
  field("degenerate_faces", count(degenerateFaces));
  field("duplicate_faces", count(duplicateFaces));
  field("self_intersecting_pairs", count(selfIntersectingPairs));
  field("euler_characteristic", std::to_string(eulerCharacteristic));
  field("genus", std::to_string(genus));
  {
    // The largest components' genus and boundary loops (at most 20 of each; the sum is above).
    std::string g = "[", b = "[";
    for (size_t i = 0; i < perComponent.size() && i < 20; ++i) {
      g += (i ? ", " : "") + std::to_string(perComponent[i].genus);
      b += (i ? ", " : "") + std::to_string(perComponent[i].boundaryLoops);
    }
    field("genus_per_component", g + "]");
    field("boundary_loops_per_component", b + "]");
  }
  if (hasCloud) {
    field("cloud_points", count(cloudPoints));
    field("cloud_spacing", number(cloudSpacing));
    field("distance_mean", number(distanceMean));
    field("distance_max", number(distanceMax));
    field("mu_d_percent", number(muDPercent));
    field("points_farther_than_spacing", count(pointsFartherThanSpacing));
  }
  field("consistently_oriented", consistentlyOriented() ? "true" : "false");
  field("manifold", manifold() ? "true" : "false", true);
  s << "}\n";
  return s.str();
}

} // namespace growth
