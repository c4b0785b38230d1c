// The hole pass: holes of the output that the cloud covers are closed with the packing's own
// vertices (packer_steps.h, docs/design/spherepack-holes.md).
#include "packer_steps.h"

#include <growth/point_grid.h>
#include <growth/self_intersections.h>
#include "stored_positions.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <unordered_map>

namespace growth {
namespace spherepack {
namespace detail {

CloudCover cloudCover(const std::vector<Vec3d>& points, const std::vector<float>& radius) {
  CloudCover c;
  c.xyz.resize(3 * points.size());
  for (size_t i = 0; i < points.size(); ++i)
    for (int k = 0; k < 3; ++k) c.xyz[3 * i + size_t(k)] = float(points[i][k]);
  c.radius = radius;
  for (float r : radius) c.largest = std::max(c.largest, r);
  return c;
}

namespace {

// The faces around each vertex (compressed rows).
struct VertexFaces {
  std::vector<std::uint32_t> first, face;
  VertexFaces(const std::vector<Triangle>& faces, size_t vertices) : first(vertices + 1, 0), face(3 * faces.size()) {
    for (const Triangle& f : faces)
      for (std::uint32_t v : f) ++first[size_t(v) + 1];
    for (size_t v = 0; v < vertices; ++v) first[v + 1] += first[v];
    std::vector<std::uint32_t> fill(first.begin(), first.end() - 1);
    for (size_t f = 0; f < faces.size(); ++f)
      for (std::uint32_t v : faces[f]) face[fill[v]++] = std::uint32_t(f);
  }
};

// Whether a face holds the half-edge a→b.
inline bool hasHalfEdge(const Triangle& f, std::uint32_t a, std::uint32_t b) {
  return (f[0] == a && f[1] == b) || (f[1] == a && f[2] == b) || (f[2] == a && f[0] == b);
}

// FacesAway: the loop faces the other way from the mesh along it (the outline of a piece that is a
// disk of its own, seen from outside).
enum class Refusal { None, NotTriangulable, NotCovered, Folded, FacesAway, Crossing, TooLong };

void count(Refusal why, Stat& st) {
  if (why == Refusal::TooLong) ++st.holesTooLong;
  else if (why == Refusal::NotCovered) ++st.holesNotCovered;
  else if (why == Refusal::Folded || why == Refusal::FacesAway) ++st.holesFolded;
  else if (why == Refusal::Crossing) ++st.holesCrossing;
  else ++st.holesNotTriangulable;
}

inline Vec3d faceNormal(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  Vec3d n = (b - a) ^ (c - a);
  const double l = n.Norm();
  return l > 0 ? n * (1.0 / l) : Vec3d(0, 0, 0);
}

// Cells of side h of a box, as integer ranges.
struct CellRange {
  std::int64_t lo[3], hi[3];
};
inline CellRange cellsOf(const Box3d& b, double h) {
  CellRange r;
  for (int k = 0; k < 3; ++k) {
    r.lo[k] = std::int64_t(std::floor(b.min[k] / h));
    r.hi[k] = std::int64_t(std::floor(b.max[k] / h));
  }
  return r;
}
// 21 bits per axis, wrapped: cells 2^21 cells apart share a key (a cell list then holds a few
// faces more, which the exact tests sort out).
inline std::uint64_t cellKey(std::int64_t x, std::int64_t y, std::int64_t z) {
  constexpr std::uint64_t m = (std::uint64_t(1) << 21) - 1;
  return ((std::uint64_t(x) & m) << 42) | ((std::uint64_t(y) & m) << 21) | (std::uint64_t(z) & m);
}
template <class F>
void forEachCell(const CellRange& r, F&& f) {
  for (std::int64_t x = r.lo[0]; x <= r.hi[0]; ++x)
    for (std::int64_t y = r.lo[1]; y <= r.hi[1]; ++y)
      for (std::int64_t z = r.lo[2]; z <= r.hi[2]; ++z) f(cellKey(x, y, z));
}
inline Box3d faceBox(const std::vector<Vec3d>& pos, const Triangle& f) {
  Box3d b;
  for (std::uint32_t v : f) b.Add(pos[v]);
  return b;
}

// The splats near the holes, indexed (only the points that can reach a loop's box are copied).
struct NearSplats {
  std::vector<Vec3d> points;
  std::vector<float> radius;
  PointGrid grid;
  double widen = 0; // added to the splat radii
  double wide = 0;  // the largest splat radius, widened
};

// Whether a face is where the cloud is: its centroid on a splat, widened, and thickened by
// `reach` along the face's normal (kCoverReachPerD, kCoverReachPerLoopRadius).
bool coveredAcross(const NearSplats& s, const Vec3d& a, const Vec3d& b, const Vec3d& c, double reach) {
  const Vec3d n = faceNormal(a, b, c);
  if (!(n.Norm() > 0)) return false;
  const Vec3d centre = (a + b + c) * (1.0 / 3);
  return !s.grid.forEachInBallWhile(centre, std::sqrt(reach * reach + s.wide * s.wide), [&](int i, double d2) {
    const double along = (s.points[size_t(i)] - centre) * n;
    const double r = double(s.radius[size_t(i)]) + s.widen;
    return !(std::abs(along) <= reach && d2 - along * along <= r * r);
  });
}

// How far along a closure's normals the cloud is looked for: the sagitta of a hole grows with its
// size.
double coverReach(const std::vector<std::uint32_t>& loop, const std::vector<Vec3d>& pos, double d) {
  Vec3d centre(0, 0, 0);
  for (std::uint32_t v : loop) centre += pos[v];
  centre = centre * (1.0 / double(loop.size()));
  double radius = 0;
  for (std::uint32_t v : loop) radius = std::max(radius, (pos[v] - centre).Norm());
  return std::max(kCoverReachPerD * d, kCoverReachPerLoopRadius * radius);
}

// Distance from p to the triangle abc (its closest point: inside, on an edge or at a corner).
double pointTriangleDistance(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab * ap, d2 = ac * ap;
  if (d1 <= 0 && d2 <= 0) return ap.Norm();
  const Vec3d bp = p - b;
  const double d3 = ab * bp, d4 = ac * bp;
  if (d3 >= 0 && d4 <= d3) return bp.Norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + ab * (d1 / (d1 - d3)))).Norm();
  const Vec3d cp = p - c;
  const double d5 = ab * cp, d6 = ac * cp;
  if (d6 >= 0 && d5 <= d6) return cp.Norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + ac * (d2 / (d2 - d6)))).Norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (c - b) * ((d4 - d3) / ((d4 - d3) + (d5 - d6))))).Norm();
  const double den = 1 / (va + vb + vc);
  return (p - (a + ab * (vb * den) + ac * (vc * den))).Norm();
}

// The checks a closure must pass on its own (the crossing test comes after, against the mesh):
// no (nearly) collinear face, the cloud across every face, and no fold back onto the mesh along
// the loop. `localOf`: the loop index of each vertex of the loop.
template <class Covered>
Refusal checkClosure(const std::vector<Triangle>& made, const std::vector<Vec3d>& pos,
                     const std::vector<Vec3d>& stored, const std::vector<std::uint32_t>& localOf,
                     const std::vector<Vec3d>& across, Covered&& covered, double reach) {
  const size_t n = across.size();
  bool flat = false, uncovered = false, folded = false;
  for (const Triangle& f : made) {
    if (nearlyCollinear(stored[f[0]], stored[f[1]], stored[f[2]])) flat = true;
    if (!covered(pos[f[0]], pos[f[1]], pos[f[2]], reach)) uncovered = true;
    const Vec3d nf = faceNormal(pos[f[0]], pos[f[1]], pos[f[2]]);
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t i = localOf[f[k]], j = localOf[f[(k + 1) % 3]];
      if (size_t(j) != (size_t(i) + 1) % n) continue; // not an edge of the loop
      if (nf * across[i] <= kCosMaxClosureBend) folded = true;
    }
  }
  if (uncovered) return Refusal::NotCovered;
  if (folded) return Refusal::Folded;
  if (flat) return Refusal::NotTriangulable;
  return Refusal::None;
}

// The triangulation of the loop (local indices, hole on the left) with the smallest largest bend
// between neighbouring faces (1 − cos of the angle between their normals; along the loop, against
// the mesh's faces `across`), and among those the least area: dynamic programming over the
// sub-polygons i..k, O(n³) (a polygon's triangulations all split it at a triangle on its edge
// i–k). Faces with (nearly) collinear vertices and edges the mesh has (`edges`) are not used.
// False when there is none. `made` gets local indices.
bool leastBendTriangulation(const std::vector<Vec3d>& lpos, const std::vector<Vec3d>& across, const EdgeSet& edges,
                            const std::vector<Vec3d>& stored, const std::vector<std::uint32_t>& loop,
                            std::vector<Triangle>& made) {
  const size_t n = lpos.size();
  if (n < 3) return false;
  const double kInf = std::numeric_limits<double>::infinity();
  std::vector<double> bend(n * n, kInf), area(n * n, kInf);
  std::vector<int> mid(n * n, -1);
  auto at = [n](size_t i, size_t k) { return i * n + k; };
  for (size_t i = 0; i + 1 < n; ++i) bend[at(i, i + 1)] = 0, area[at(i, i + 1)] = 0;
  auto turn = [](const Vec3d& a, const Vec3d& b) { return (a.Norm() > 0 && b.Norm() > 0) ? 1 - a * b : 0.0; };
  for (size_t len = 2; len < n; ++len)
    for (size_t i = 0; i + len < n; ++i) {
      const size_t k = i + len;
      const bool outer = i == 0 && k == n - 1; // i–k is the loop's last edge
      if (!outer && edges.contains(std::uint32_t(i), std::uint32_t(k))) continue;
      double bestBend = kInf, bestArea = kInf;
      int best = -1;
      for (size_t m = i + 1; m < k; ++m) {
        if (!std::isfinite(bend[at(i, m)]) || !std::isfinite(bend[at(m, k)])) continue;
        if (nearlyCollinear(stored[loop[i]], stored[loop[m]], stored[loop[k]])) continue;
        const Vec3d tn = faceNormal(lpos[i], lpos[m], lpos[k]);
        const Vec3d left = m == i + 1 ? across[i] : faceNormal(lpos[i], lpos[size_t(mid[at(i, m)])], lpos[m]);
        const Vec3d right = k == m + 1 ? across[m] : faceNormal(lpos[m], lpos[size_t(mid[at(m, k)])], lpos[k]);
        double b = std::max({bend[at(i, m)], bend[at(m, k)], turn(tn, left), turn(tn, right)});
        if (outer) b = std::max(b, turn(tn, across[n - 1]));
        const double a = area[at(i, m)] + area[at(m, k)] + 0.5 * ((lpos[m] - lpos[i]) ^ (lpos[k] - lpos[i])).Norm();
        if (b < bestBend || (b == bestBend && a < bestArea)) bestBend = b, bestArea = a, best = int(m);
      }
      if (best < 0) continue;
      bend[at(i, k)] = bestBend;
      area[at(i, k)] = bestArea;
      mid[at(i, k)] = best;
    }
  if (mid[at(0, n - 1)] < 0) return false;
  std::vector<std::pair<size_t, size_t>> stack{{0, n - 1}};
  while (!stack.empty()) {
    const size_t i = stack.back().first, k = stack.back().second;
    stack.pop_back();
    if (k < i + 2) continue;
    const size_t m = size_t(mid[at(i, k)]);
    made.push_back(Triangle{std::uint32_t(i), std::uint32_t(m), std::uint32_t(k)});
    stack.push_back({i, m});
    stack.push_back({m, k});
  }
  return made.size() == n - 2;
}

// Whether a face of `t` intersects a face of the mesh near it (listed in `cells`) or another face
// of `t`. A face reaching a cell that is not listed cannot be checked and counts as crossing.
template <class Counts>
bool crosses(const std::vector<Triangle>& t, const std::vector<Triangle>& faces, const std::vector<Vec3d>& stored,
             const std::unordered_map<std::uint64_t, std::vector<std::uint32_t>>& cells, double h,
             std::vector<std::uint32_t>& near, Counts&& counts) {
  for (size_t i = 0; i < t.size(); ++i) {
    near.clear();
    bool unlisted = false;
    forEachCell(cellsOf(faceBox(stored, t[i]), h), [&](std::uint64_t k) {
      auto it = cells.find(k);
      if (it != cells.end()) near.insert(near.end(), it->second.begin(), it->second.end());
      else unlisted = true;
    });
    if (unlisted) return true;
    std::sort(near.begin(), near.end());
    near.erase(std::unique(near.begin(), near.end()), near.end());
    for (std::uint32_t f : near)
      if (counts(f) && facesIntersect(stored, t[i], faces[f])) return true;
    for (size_t j = i + 1; j < t.size(); ++j)
      if (facesIntersect(stored, t[i], t[j])) return true;
  }
  return false;
}

} // namespace

// The pass on the boundary loops of `faces`; `makeCover(loops, pos)` gives the test of a closure's
// face, `covered(a, b, c, reach)`. `dropIslands`: islands (below) go.
template <class MakeCover>
void closeLoops(std::vector<Triangle>& faces, const BorderGraph& g, bool floatStorage, bool dropIslands, Stat& st,
                MakeCover&& makeCover) {
  if (faces.empty()) return;
  const size_t nv = g.vertexCount();
  const double d = st.sphereDiameter;
  const std::vector<Vec3d>& pos = g.positions();
  // The boundary: half-edges of a face whose twin no face holds. At a manifold vertex of the
  // boundary exactly one comes in; `from[x]` is its origin (the hole's loop goes x → from[x]).
  const VertexFaces vf(faces, nv);
  constexpr std::uint32_t kNone = std::uint32_t(-1), kMany = std::uint32_t(-2);
  std::vector<std::uint32_t> from(nv, kNone);
  for (const Triangle& f : faces)
    for (int k = 0; k < 3; ++k) {
      const std::uint32_t a = f[k], b = f[(k + 1) % 3];
      bool twin = false;
      for (std::uint32_t e = vf.first[b]; e < vf.first[size_t(b) + 1] && !twin; ++e)
        twin = hasHalfEdge(faces[vf.face[e]], b, a);
      if (!twin) from[b] = from[b] == kNone ? a : kMany;
    }
  // The loops, each with the hole on its left (the mesh's orientation continued).
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<char> seen(nv, 0);
  for (std::uint32_t s = 0; s < nv; ++s) {
    if (from[s] == kNone || seen[s]) continue;
    std::vector<std::uint32_t> loop;
    std::uint32_t v = s;
    bool ok = true;
    while (!seen[v]) {
      seen[v] = 1;
      if (from[v] == kMany) ok = false;
      loop.push_back(v);
      if (from[v] == kNone || from[v] == kMany) {
        ok = false;
        break;
      }
      v = from[v];
    }
    if (!ok || v != s) {
      ++st.holesOther;
      continue;
    }
    loops.push_back(std::move(loop));
  }
  if (loops.empty()) return;

  // The checks are made on the positions as the layer stores them (float in MeshLab 2020.09).
  const std::vector<Vec3d> stored = asStored(pos, floatStorage);
  const auto covered = makeCover(loops, pos);
  // Faces taken out (rings, below) are dead. Each open hole claims the vertices of its loop, and a
  // hole being closed those of its ring too: a ring that reaches another hole's vertex takes that
  // hole in.
  std::vector<char> dead(faces.size(), 0);
  std::vector<std::int32_t> claim(nv, -1);
  for (size_t l = 0; l < loops.size(); ++l)
    for (std::uint32_t v : loops[l]) claim[v] = std::int32_t(l);
  auto alive = [&](std::uint32_t f) { return !dead[f]; };
  // The faces of the closures made, around their vertices (the compressed rows hold the others).
  std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> madeAt;
  // Calls f for every alive face at v.
  auto forFacesAt = [&](std::uint32_t v, auto&& f) {
    for (std::uint32_t e = vf.first[v]; e < vf.first[size_t(v) + 1]; ++e)
      if (alive(vf.face[e])) f(vf.face[e]);
    auto it = madeAt.find(v);
    if (it != madeAt.end())
      for (std::uint32_t g : it->second)
        if (alive(g)) f(g);
  };
  // The alive face holding the half-edge a→b, or kNone.
  auto holder = [&](std::uint32_t a, std::uint32_t b) {
    std::uint32_t found = kNone;
    forFacesAt(a, [&](std::uint32_t f) {
      if (found == kNone && hasHalfEdge(faces[f], a, b)) found = f;
    });
    return found;
  };
  std::vector<std::uint32_t> localOf(nv, kNone);

  // No closure may intersect a face of the mesh or of a closure made before it: the faces near
  // the holes (as far as their rings reach), by cells of side 2d.
  const double h = 2 * d;
  std::unordered_map<std::uint64_t, std::vector<std::uint32_t>> cells;
  for (const auto& loop : loops) {
    if (loop.size() > size_t(kMaxHoleLoop)) continue;
    Box3d b;
    for (std::uint32_t v : loop) b.Add(stored[v]);
    b.Offset(kMaxHoleRings * kMaxEdgePerD * d);
    forEachCell(cellsOf(b, h), [&](std::uint64_t k) { cells[k]; });
  }
  for (size_t f = 0; f < faces.size(); ++f)
    forEachCell(cellsOf(faceBox(stored, faces[f]), h), [&](std::uint64_t k) {
      auto it = cells.find(k);
      if (it != cells.end()) it->second.push_back(std::uint32_t(f));
    });
  auto counts = [&](std::uint32_t f) { return !dead[f]; };
  std::vector<std::uint32_t> near;

  // The checks on a loop alone: its triangulations (ear cut, then least bend) that pass them go
  // to `tries`; the reason of the last refusal otherwise.
  auto attempt = [&](const std::vector<std::uint32_t>& loop, std::vector<std::vector<Triangle>>& tries) {
    const size_t n = loop.size();
    Vec3d normal(0, 0, 0), centre(0, 0, 0);
    for (std::uint32_t v : loop) centre += pos[v];
    centre = centre * (1.0 / double(n));
    for (size_t i = 0; i < n; ++i) normal += (pos[loop[i]] - centre) ^ (pos[loop[(i + 1) % n]] - centre);
    if (!(normal.Norm() > 0)) return Refusal::NotTriangulable;
    normal.Normalize();
    std::vector<Vec3d> lpos(n), lnrm(n, normal);
    std::vector<std::uint32_t> local(n);
    for (size_t i = 0; i < n; ++i) {
      localOf[loop[i]] = std::uint32_t(i);
      lpos[i] = pos[loop[i]];
      local[i] = std::uint32_t(i);
    }
    // The mesh's edges between two vertices of the loop: a closure must not add them again.
    EdgeSet edges(4 * n + 16);
    for (size_t i = 0; i < n; ++i) {
      const std::uint32_t v = loop[i];
      forFacesAt(v, [&](std::uint32_t f) {
        for (std::uint32_t x : faces[f])
          if (x != v && localOf[x] != kNone) edges.insert(std::uint32_t(i), localOf[x]);
      });
    }
    // The mesh's normal across each loop edge i → i+1 (its face holds loop[i+1] → loop[i]).
    std::vector<Vec3d> across(n);
    double agree = 0;
    for (size_t i = 0; i < n; ++i) {
      const std::uint32_t f = holder(loop[(i + 1) % n], loop[i]);
      if (f != kNone) across[i] = faceNormal(pos[faces[f][0]], pos[faces[f][1]], pos[faces[f][2]]);
      agree += across[i] * normal;
    }
    Refusal why = Refusal::NotTriangulable;
    // The loop does not face away from the mesh along it (kFacesAwayShare).
    if (!(agree > -kFacesAwayShare * double(n))) {
      why = Refusal::FacesAway;
    } else {
      for (int k = 0; k < 2; ++k) {
        std::vector<Triangle> made;
        bool triangulated;
        if (k == 0) {
          triangulated = triangulateLoop(local, lpos, lnrm, edges, made) && made.size() == n - 2;
        } else {
          if (n > size_t(kMaxLeastBendLoop)) break;
          triangulated = leastBendTriangulation(lpos, across, edges, stored, loop, made);
        }
        if (!triangulated) {
          why = Refusal::NotTriangulable;
          continue;
        }
        for (Triangle& f : made)
          for (std::uint32_t& v : f) v = loop[v];
        why = checkClosure(made, pos, stored, localOf, across, covered, coverReach(loop, pos, d));
        if (why == Refusal::None && crosses(made, faces, stored, cells, h, near, counts)) why = Refusal::Crossing;
        if (why == Refusal::None) {
          tries.push_back(std::move(made));
          break;
        }
      }
    }
    for (std::uint32_t v : loop) localOf[v] = kNone;
    return tries.empty() ? why : Refusal::None;
  };

  // Each loop's outcome: open (why), closed, taken into another's closure, or the outline of an
  // island dropped.
  enum class Outcome { Open, Closed, Merged, Island };
  std::vector<Outcome> outcome(loops.size(), Outcome::Open);
  std::vector<Refusal> reason(loops.size(), Refusal::NotTriangulable);
  // A ring: the alive faces around the loop taken out, so that the hole grows by one ring of faces
  // (the faces next to a hole are often the folded ones that kept it open). Another open hole the
  // ring touches is taken in whole (`absorbed`); a hole too long to close is not. Only when the
  // grown hole is still bounded by one simple loop (a disk), which replaces `loop`.
  auto growRing = [&](std::int32_t id, std::vector<std::uint32_t>& loop, std::vector<std::uint32_t>& ring,
                      std::vector<std::int32_t>& absorbed) {
    std::vector<std::uint32_t> add;
    for (std::uint32_t v : loop) forFacesAt(v, [&](std::uint32_t f) { add.push_back(f); });
    std::sort(add.begin(), add.end());
    add.erase(std::unique(add.begin(), add.end()), add.end());
    if (add.empty()) return false;
    // A ring may take in another hole that is still open (the two become one).
    std::vector<std::int32_t> taken;
    // The grown hole's loop: the half-edges of the ring whose twins stay in the mesh. Where it
    // pinches (a vertex it passes twice) or splits (an island of faces left inside), the faces
    // around those vertices join the ring, a few times at most.
    std::vector<std::uint32_t> grown;
    bool simple = false;
    for (int fix = 0; fix <= kMaxRingFixes && !simple; ++fix) {
      // A hole the ring touches is taken in whole: the faces around its loop join the ring.
      bool more = false;
      for (size_t i = 0; i < add.size(); ++i)
        for (std::uint32_t v : faces[add[i]]) {
          const std::int32_t c = claim[v];
          if (c < 0 || c == id || std::find(taken.begin(), taken.end(), c) != taken.end()) continue;
          if (loops[size_t(c)].size() > size_t(kMaxHoleLoop)) {
            for (std::uint32_t g : add) dead[g] = 0;
            return false;
          }
          taken.push_back(c);
          for (std::uint32_t u : loops[size_t(c)]) forFacesAt(u, [&](std::uint32_t f) { add.push_back(f); });
          more = true;
        }
      if (more) {
        std::sort(add.begin(), add.end());
        add.erase(std::unique(add.begin(), add.end()), add.end());
        continue;
      }
      for (std::uint32_t f : add) dead[f] = 1;
      std::unordered_map<std::uint32_t, std::uint32_t> next;
      std::vector<std::uint32_t> bad;
      for (std::uint32_t f : add)
        for (int k = 0; k < 3; ++k) {
          const std::uint32_t a = faces[f][k], b = faces[f][(k + 1) % 3];
          if (holder(b, a) == kNone) continue; // inside the grown hole, or on its old loop
          if (!next.emplace(a, b).second) bad.push_back(a);
        }
      grown.clear();
      if (bad.empty() && !next.empty()) {
        // The cycles; all but the longest bound islands.
        std::unordered_map<std::uint32_t, char> done;
        std::vector<std::vector<std::uint32_t>> cycles;
        for (const auto& e : next) {
          if (done.count(e.first)) continue;
          std::vector<std::uint32_t> cyc;
          std::uint32_t v = e.first;
          while (!done.count(v)) {
            done[v] = 1;
            cyc.push_back(v);
            auto it = next.find(v);
            if (it == next.end()) break;
            v = it->second;
          }
          cycles.push_back(std::move(cyc));
        }
        std::sort(cycles.begin(), cycles.end(), [](const std::vector<std::uint32_t>& x, const std::vector<std::uint32_t>& y) {
          return x.size() != y.size() ? x.size() > y.size() : x < y;
        });
        for (size_t c = 1; c < cycles.size(); ++c) bad.insert(bad.end(), cycles[c].begin(), cycles[c].end());
        if (cycles.size() == 1) {
          // In loop order from its smallest vertex (deterministic whatever the hash's order).
          const auto& cyc = cycles.front();
          const size_t at = size_t(std::min_element(cyc.begin(), cyc.end()) - cyc.begin());
          for (size_t k = 0; k < cyc.size(); ++k) grown.push_back(cyc[(at + k) % cyc.size()]);
          simple = grown.size() >= 3;
        }
      }
      if (simple) break;
      const size_t before = add.size();
      for (std::uint32_t v : bad) forFacesAt(v, [&](std::uint32_t f) { add.push_back(f); });
      std::sort(add.begin(), add.end());
      add.erase(std::unique(add.begin(), add.end()), add.end());
      if (add.size() == before) break;
    }
    if (!simple) {
      for (std::uint32_t f : add) dead[f] = 0;
      return false;
    }
    for (std::uint32_t f : add) {
      ring.push_back(f);
      for (std::uint32_t v : faces[f]) claim[v] = id;
    }
    for (std::int32_t c : taken) {
      for (std::uint32_t v : loops[size_t(c)]) claim[v] = id;
      absorbed.push_back(c);
    }
    std::sort(absorbed.begin(), absorbed.end());
    absorbed.erase(std::unique(absorbed.begin(), absorbed.end()), absorbed.end());
    loop.swap(grown);
    return true;
  };

  // A second sweep retries the holes the first left open (but for the cloud's refusals): closures
  // made after them may have freed their neighbourhood.
  for (int sweep = 0; sweep < 2; ++sweep)
  for (size_t l = 0; l < loops.size(); ++l) {
    if (outcome[l] != Outcome::Open) continue; // closed, or taken into an earlier closure
    if (sweep > 0 && (reason[l] == Refusal::NotCovered || reason[l] == Refusal::TooLong)) continue;
    std::vector<std::uint32_t> loop = loops[l];
    if (loop.size() > size_t(kMaxHoleLoop)) {
      reason[l] = Refusal::TooLong;
      continue;
    }
    std::vector<std::vector<Triangle>> tries;
    std::vector<std::uint32_t> ring;
    std::vector<std::int32_t> absorbed;
    Refusal why = attempt(loop, tries);
    for (int round = 0; why != Refusal::None && why != Refusal::NotCovered && round < kMaxHoleRings; ++round) {
      if (!growRing(std::int32_t(l), loop, ring, absorbed) || loop.size() > size_t(kMaxHoleLoop)) break;
      why = attempt(loop, tries);
    }
    if (why != Refusal::None) {
      // The ring comes back; its vertices are free again but for the loops' own.
      for (std::uint32_t f : ring) {
        dead[f] = 0;
        for (std::uint32_t v : faces[f]) claim[v] = -1;
      }
      for (std::uint32_t v : loops[l]) claim[v] = std::int32_t(l);
      for (std::int32_t c : absorbed)
        for (std::uint32_t v : loops[size_t(c)]) claim[v] = c;
      reason[l] = why;
      continue;
    }
    outcome[l] = Outcome::Closed;
    for (std::int32_t c : absorbed) outcome[size_t(c)] = Outcome::Merged;
    st.holeFacesRemoved += ring.size();
    // The hole is mesh now: its vertices are free for the rings of the holes after it.
    for (std::uint32_t f : ring)
      for (std::uint32_t v : faces[f]) claim[v] = -1;
    for (std::uint32_t v : loop) claim[v] = -1;
    for (const Triangle& f : tries.front()) {
      const std::uint32_t id = std::uint32_t(faces.size());
      faces.push_back(f);
      dead.push_back(0);
      for (std::uint32_t v : f) madeAt[v].push_back(id);
      forEachCell(cellsOf(faceBox(stored, f), h), [&](std::uint64_t k) {
        auto it = cells.find(k);
        if (it != cells.end()) it->second.push_back(id);
      });
    }
    st.holeFacesAdded += tries.front().size();
  }
  // Islands: a piece bounded by one loop that faces away, lying on the rest of the mesh (every
  // vertex within the loop's cover reach of its faces, as a closure's faces must lie within it of
  // the cloud): a second layer left inside a hole that has been closed under it (the clean-up cut
  // it off, or the growth started it apart). It goes.
  if (dropIslands) {
    std::vector<std::uint32_t> root(nv);
    for (std::uint32_t v = 0; v < nv; ++v) root[v] = v;
    auto find = [&](std::uint32_t v) {
      while (root[v] != v) v = root[v] = root[root[v]];
      return v;
    };
    for (size_t f = 0; f < faces.size(); ++f)
      if (!dead[f])
        for (int k = 1; k < 3; ++k) {
          const std::uint32_t a = find(faces[f][0]), b = find(faces[f][k]);
          if (a != b) root[std::max(a, b)] = std::min(a, b);
        }
    std::unordered_map<std::uint32_t, size_t> pieceFaces, pieceLoops;
    for (size_t f = 0; f < faces.size(); ++f)
      if (!dead[f]) ++pieceFaces[find(faces[f][0])];
    size_t largest = 0;
    for (const auto& e : pieceFaces) largest = std::max(largest, e.second);
    for (size_t l = 0; l < loops.size(); ++l)
      if (outcome[l] == Outcome::Open) ++pieceLoops[find(loops[l][0])];
    for (size_t l = 0; l < loops.size(); ++l) {
      if (outcome[l] != Outcome::Open || reason[l] != Refusal::FacesAway) continue;
      const std::uint32_t piece = find(loops[l][0]);
      if (pieceLoops[piece] != 1 || pieceFaces[piece] >= largest) continue;
      std::vector<std::uint32_t> own;
      for (size_t f = 0; f < faces.size(); ++f)
        if (!dead[f] && find(faces[f][0]) == piece) own.push_back(std::uint32_t(f));
      const double reach = coverReach(loops[l], pos, d);
      bool lying = true;
      for (size_t i = 0; i < own.size() && lying; ++i)
        for (std::uint32_t v : faces[own[i]]) {
          const Vec3d& p = stored[v];
          bool near = false; // faces in cells not gathered are not seen: the piece then stays
          Box3d b;
          b.Add(p);
          b.Offset(reach);
          forEachCell(cellsOf(b, h), [&](std::uint64_t k) {
            auto it = cells.find(k);
            if (it == cells.end()) return;
            for (std::uint32_t f : it->second)
              if (!near && !dead[f] && find(faces[f][0]) != piece &&
                  pointTriangleDistance(p, stored[faces[f][0]], stored[faces[f][1]], stored[faces[f][2]]) <= reach)
                near = true;
          });
          if (!near) {
            lying = false;
            break;
          }
        }
      if (!lying) continue;
      for (std::uint32_t f : own) dead[f] = 1;
      outcome[l] = Outcome::Island;
      ++st.holeIslandsDropped;
      st.holeFacesRemoved += own.size();
    }
  }
  for (size_t l = 0; l < loops.size(); ++l) {
    if (outcome[l] == Outcome::Open) count(reason[l], st);
    else if (outcome[l] == Outcome::Closed || outcome[l] == Outcome::Merged) ++st.holesClosed;
  }
  // The rings of the closures accepted go.
  size_t w = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    if (!dead[f]) faces[w++] = faces[f];
  faces.resize(w);
}

void closeHoles(std::vector<Triangle>& faces, const BorderGraph& g, const CloudCover& cover, const Params& params,
                bool floatStorage, Stat& st) {
  if (!params.closeHoles) return;
  const double d = st.sphereDiameter;
  NearSplats splats;
  closeLoops(faces, g, floatStorage, true, st, [&](const std::vector<std::vector<std::uint32_t>>& loops,
                                             const std::vector<Vec3d>& pos) {
    // The splats that can reach a loop's box.
    splats.widen = kCoverWidenPerD * d;
    splats.wide = double(cover.largest) + splats.widen;
    {
      const double g = 4 * d;
      const double rings = kMaxHoleRings * kMaxEdgePerD * d; // how far rings can grow a hole
      std::unordered_map<std::uint64_t, char> marked;
      for (const auto& loop : loops) {
        if (loop.size() > size_t(kMaxHoleLoop)) continue;
        Box3d b;
        for (std::uint32_t v : loop) b.Add(pos[v]);
        const double reach = coverReach(loop, pos, d) + kCoverReachPerLoopRadius * rings;
        b.Offset(std::sqrt(reach * reach + splats.wide * splats.wide) + rings);
        forEachCell(cellsOf(b, g), [&](std::uint64_t k) { marked[k] = 1; });
      }
      const size_t points = cover.radius.size();
      for (size_t i = 0; i < points; ++i) {
        const Vec3d p(cover.xyz[3 * i], cover.xyz[3 * i + 1], cover.xyz[3 * i + 2]);
        const std::uint64_t key = cellKey(std::int64_t(std::floor(p[0] / g)), std::int64_t(std::floor(p[1] / g)),
                                          std::int64_t(std::floor(p[2] / g)));
        if (marked.count(key) == 0) continue;
        splats.points.push_back(p);
        splats.radius.push_back(cover.radius[i]);
      }
      splats.grid.build(splats.points, d);
    }
    return [&splats](const Vec3d& a, const Vec3d& b, const Vec3d& c, double reach) {
      return coveredAcross(splats, a, b, c, reach);
    };
  });
}

void closeHoles(std::vector<Triangle>& faces, const BorderGraph& g, const CoverTest& covered, bool floatStorage,
                Stat& st) {
  closeLoops(faces, g, floatStorage, false, st,
             [&](const std::vector<std::vector<std::uint32_t>>&, const std::vector<Vec3d>&) { return covered; });
}

} // namespace detail
} // namespace spherepack
} // namespace growth
