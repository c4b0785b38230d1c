#include "g2s_mesher.h"

#include <growth/cloud_generator.h> // growth::Random
#include <growth/input_cloud.h>     // growth::roughSpacing

#include <algorithm>
#include <cmath>
#include <limits>

namespace growth {
namespace g2s {

namespace {
// At most this many third points are tried per seed attempt (by increasing circumradius): a
// point whose tightest triangles all fail is not a good place for a seed anyway, and outliers
// would otherwise test every point of a large ball.
constexpr size_t kMaxSeedTriangles = 32;

bool isZero(const P3& v) { return v[0] == 0 && v[1] == 0 && v[2] == 0; }

std::uint64_t gcd(std::uint64_t a, std::uint64_t b) {
  while (b != 0) {
    const std::uint64_t t = a % b;
    a = b;
    b = t;
  }
  return a;
}
} // namespace

Mesher::Mesher(std::vector<P3> points, const Params& params, double spacing)
    : params_(params), spacing_(spacing), points_(std::move(points)),
      queue_(std::max(1, params.sizeLevels * params.flatnessLevels)) {
  box_.SetNull();
  for (const P3& p : points_) box_.Add(p);
  if (!(spacing_ > 0)) spacing_ = std::max(roughSpacing(box_, points_.size()), 1e-12 * (1.0 + box_.Diag()));
  // Cells of twice the mean spacing: a typical query ball (radius about 2 spacings, see
  // findCandidate) then touches 8–27 cells holding a handful of points each.
  grid_.build(points_, 2.0 * spacing_);
  pem_.reset(points_.size());
  edgeLengthSum_.assign(points_.size(), 0.f);
  edgeCount_.assign(points_.size(), 0);
  // A seed edge joins a point to its nearest neighbour; farther than this it is an isolated
  // point (an outlier), which starts no surface.
  seedMaxEdge_ = 2.0 * std::max(1.0, params_.maxSearchRadiusFactor) * spacing_;
}

double Mesher::localSpacing(std::uint32_t v) const {
  return edgeCount_[v] > 0 ? double(edgeLengthSum_[v]) / double(edgeCount_[v]) : 0.0;
}

void Mesher::gather(const P3& centre, double radius) {
  near_.clear();
  grid_.forEachInBall(centre, radius, [&](int i, double) {
    near_.push_back(Near{static_cast<std::uint32_t>(i), points_[static_cast<size_t>(i)]});
  });
}

bool Mesher::emptyBall(const Ball& ball, double gatherRadius, const P3& gatherCentre, std::uint32_t a,
                       std::uint32_t b, std::uint32_t c) {
  for (const Near& q : near_)
    if (q.id != a && q.id != b && q.id != c && strictlyInside((q.p - ball.centre).SquaredNorm(), ball.radius2))
      return false;
  const double radius = std::sqrt(ball.radius2);
  // The gathered ball contains the whole test ball: the check above was complete.
  if ((ball.centre - gatherCentre).Norm() + radius <= gatherRadius * (1.0 - 1e-12)) return true;
  bool empty = true;
  grid_.forEachInBall(ball.centre, radius, [&](int i, double d2) {
    const auto id = static_cast<std::uint32_t>(i);
    if (empty && id != a && id != b && id != c && strictlyInside(d2, ball.radius2)) empty = false;
  });
  return empty;
}

bool Mesher::isGabriel(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Ball ball;
  if (!circumBall(points_[a], points_[b], points_[c], ball)) return false;
  near_.clear();
  return emptyBall(ball, 0.0, ball.centre, a, b, c);
}

bool Mesher::passesCylinderTest(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const P3 &A = points_[a], &B = points_[b], &C = points_[c];
  Ball ball;
  if (!circumBall(A, B, C, ball)) return false;
  const P3 n = unitNormal(A, B, C);
  if (isZero(n)) return false;
  const double radius = std::sqrt(ball.radius2);
  const double eps = 1e-6 * radius; // a point this close to the plane is on it (coplanar clouds)
  // The infinite cylinder is walked in slabs of height 2R along its axis, each covered by a ball
  // of radius R·√2, from the triangle outwards in both directions until the slabs leave the
  // cloud's bounding box; the walk stops as soon as points on both sides were seen.
  const double step = 2.0 * radius, queryRadius = radius * std::sqrt(2.0);
  vcg::Box3d bb = box_;
  bb.Offset(queryRadius);
  bool above = false, below = false;
  auto visit = [&](int i, double) {
    const auto id = static_cast<std::uint32_t>(i);
    if (id == a || id == b || id == c) return;
    const P3 d = points_[id] - ball.centre;
    const double h = d * n;
    if (!strictlyInside(d.SquaredNorm() - h * h, ball.radius2)) return;
    if (h > eps) above = true;
    else if (h < -eps) below = true;
  };
  for (int side : {1, -1}) {
    for (long j = side > 0 ? 0 : 1;; ++j) {
      const P3 centre = ball.centre + n * (double(side) * double(j) * step);
      if (!bb.IsIn(centre)) break;
      grid_.forEachInBall(centre, queryRadius, visit);
      if (above && below) return false;
    }
  }
  return true;
}

bool Mesher::topologyAllows(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t p) const {
  if (p == a || p == b || p == c) return false;
  // New triangle (b, a, p): half-edges b→a (free by construction), a→p and p→b must be unused.
  if (pem_.used(a, p) || pem_.used(p, b)) return false;
  return !pem_.closed(p);
}

Candidate Mesher::findCandidate(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  Candidate none;
  const P3 &A = points_[a], &B = points_[b], &C = points_[c];
  const double edge = (B - A).Norm();
  if (!(edge > 0)) return none;
  const P3 dir = growingDirection(A, B, C);
  if (isZero(dir)) return none;
  const P3 frontNormal = (B - A) ^ (C - A);
  // A free edge that closes a loop of three free edges (a→b, b→p, p→a all used one way only):
  // the triangle (b, a, p) is the only one that can ever be placed there, so it is the candidate,
  // G2S or not. On a curved or noisy surface the G2S ball of such a triangle can hold a vertex of
  // a neighbouring triangle barely inside (the Gabriel test is not symmetric across an edge as
  // the 2D Delaunay circle test is), which would otherwise leave a three-edge hole.
  {
    std::int64_t ear = -1;
    pem_.forEachEdge(b, [&](std::uint32_t p, bool out, bool in) {
      if (ear < 0 && out && !in && p != a && p != c && pem_.used(p, a) && !pem_.used(a, p)) ear = p;
    });
    if (ear >= 0) {
      const P3& E = points_[static_cast<size_t>(ear)];
      Candidate cand;
      cand.point = ear;
      cand.sizeLevel = 1;
      cand.betaRad = angleBetween(frontNormal, (A - B) ^ (E - B));
      cand.flatLevel = flatnessLevel(cand.betaRad, params_.flatnessLevels);
      cand.closesLoop = true;
      return cand;
    }
  }
  const P3 mid = (A + B) * 0.5;
  // Maximum search radius: a multiple of the local spacing, here the mean length of the mesh
  // edges already at a and b (sec. 3.2 leaves its choice open; edge lengths of the growing mesh
  // follow the local density, so non-uniform clouds get a radius that fits each region).
  const double local = 0.5 * (localSpacing(a) + localSpacing(b));
  const double maxRadius = std::max(edge, params_.maxSearchRadiusFactor * local);
  const int n = params_.sizeLevels, m = params_.flatnessLevels;
  double previous = -1;
  for (int level = 1; level <= n; ++level) {
    const double radius = searchRadius(level, n, edge, maxRadius);
    if (radius <= previous) continue;
    previous = radius;
    const P3 centre = searchCentre(A, B, dir, radius);
    // One gather covers the search sphere and, around the edge's midpoint, the G2S balls of the
    // well-shaped candidates, so most G2S tests need no second grid query.
    const double gatherRadius = (centre - mid).Norm() + radius;
    gather(mid, gatherRadius);
    const double r2 = radius * radius * (1.0 + 1e-12);
    size_t found = 0;
    scored_.clear();
    for (const Near& q : near_) {
      if (q.id == a || q.id == b || q.id == c) continue;
      if ((q.p - centre).SquaredNorm() > r2) continue;
      ++found;
      if (!topologyAllows(a, b, c, q.id)) continue;
      Ball ball;
      if (!circumBall(B, A, q.p, ball)) continue; // collinear with the edge: no triangle
      const double beta = angleBetween(frontNormal, (A - B) ^ (q.p - B));
      scored_.push_back(Scored{double(flatnessLevel(beta, m)), ball.radius2, q.id, ball, beta});
    }
    if (scored_.empty()) continue;
    if (found == 1) {
      // Sec. 3.2 step 4.2: a single point in the search region is taken directly.
      const Scored& s = scored_.front();
      Candidate cand;
      cand.point = s.id;
      cand.sizeLevel = level;
      cand.flatLevel = int(s.key1);
      cand.betaRad = s.beta;
      cand.single = true;
      return cand;
    }
    // Several points: the reference point is the one whose smallest sphere through it and the
    // edge's endpoints is empty. Where several are (the G2S triangulation is not unique off the
    // plane), the flattest class first and then the smallest sphere: sec. 4.1's aim of growing
    // where the surface continues most flatly, and the tightest triangle within a class.
    std::sort(scored_.begin(), scored_.end(), [](const Scored& x, const Scored& y) {
      if (x.key1 != y.key1) return x.key1 < y.key1;
      if (x.key2 != y.key2) return x.key2 < y.key2;
      return x.id < y.id;
    });
    for (const Scored& s : scored_) {
      if (!emptyBall(s.ball, gatherRadius, mid, a, b, s.id)) continue;
      Candidate cand;
      cand.point = s.id;
      cand.sizeLevel = level;
      cand.flatLevel = int(s.key1);
      cand.betaRad = s.beta;
      return cand;
    }
    // Points were found but none spans an empty sphere with the edge: the G2S point lies farther
    // out, so the radius grows on (the paper grows it when no point is found; a region holding
    // only non-G2S points has not reached the G2S point yet).
  }
  return none;
}

void Mesher::addTriangle(std::uint32_t u, std::uint32_t v, std::uint32_t w) {
  const std::uint32_t t[3] = {u, v, w};
  for (std::uint32_t x : t)
    if (pem_.isolated(x)) ++usedPoints_;
  const unsigned fresh = pem_.addTriangle(u, v, w);
  tri_.push_back(Triangle{u, v, w});
  for (int k = 0; k < 3; ++k) {
    if ((fresh & (1u << k)) == 0) continue;
    const std::uint32_t x = t[k], y = t[(k + 1) % 3];
    const float len = float((points_[x] - points_[y]).Norm());
    edgeLengthSum_[x] += len;
    edgeLengthSum_[y] += len;
    if (edgeCount_[x] < 65535) ++edgeCount_[x];
    if (edgeCount_[y] < 65535) ++edgeCount_[y];
  }
  // Every new edge is a free edge of the front: find its candidate and queue it (sec. 4.1).
  for (int k = 0; k < 3; ++k)
    if ((fresh & (1u << k)) != 0) queueEdge(t[k], t[(k + 1) % 3], t[(k + 2) % 3]);
}

void Mesher::queueEdge(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const Candidate cand = findCandidate(a, b, c);
  // No candidate up to the maximum radius: a boundary edge (sec. 3.2 step 4.2); it stays free.
  if (!cand.valid()) return;
  queue_.push(cand.priority(params_.flatnessLevels) - 1,
              FrontEdge{a, b, c, static_cast<std::uint32_t>(cand.point)});
}

void Mesher::grow(Progress* progress) {
  size_t tick = 0;
  while (!queue_.empty()) {
    const FrontEdge e = queue_.pop();
    // Closed from the other side since it was queued: no longer a free edge.
    if (!pem_.used(e.a, e.b) || pem_.used(e.b, e.a)) continue;
    if (!topologyAllows(e.a, e.b, e.c, e.p)) {
      // The mesh changed around the edge since its candidate was chosen: choose again among the
      // points that pass the tests now, at the priority that gives (or make it a boundary edge).
      queueEdge(e.a, e.b, e.c);
      continue;
    }
    addTriangle(e.b, e.a, e.p);
    if (progress != nullptr && (++tick & 1023) == 0)
      progress->update(double(usedPoints_) / double(points_.size()));
  }
}

bool Mesher::triangleAt(std::uint32_t v, std::array<std::uint32_t, 3>& tri) const {
  bool found = false;
  pem_.forEachEdge(v, [&](std::uint32_t w, bool out, bool) {
    if (found || !out) return;
    pem_.forEachEdge(v, [&](std::uint32_t x, bool, bool in) {
      if (found || !in || x == w) return;
      if (pem_.used(w, x)) {
        tri = {v, w, x};
        found = true;
      }
    });
  });
  return found;
}

void Mesher::orientSeed(std::array<std::uint32_t, 3>& tri) {
  const P3 &A = points_[tri[0]], &B = points_[tri[1]], &C = points_[tri[2]];
  const P3 n = (B - A) ^ (C - A);
  const P3 centroid = (A + B + C) / 3.0;
  // Next to an existing part of the mesh (a seed inside a hole), agree with its orientation so
  // that the two fronts can join (sec. 3.2: edges are shared only with consistent orientation).
  double best = std::numeric_limits<double>::infinity();
  std::array<std::uint32_t, 3> ref{};
  bool haveRef = false;
  for (const Near& q : near_) {
    const double d2 = (q.p - centroid).SquaredNorm();
    if (d2 >= best || pem_.isolated(q.id)) continue;
    std::array<std::uint32_t, 3> t;
    if (triangleAt(q.id, t)) {
      best = d2;
      ref = t;
      haveRef = true;
    }
  }
  double side;
  if (haveRef)
    side = n * ((points_[ref[1]] - points_[ref[0]]) ^ (points_[ref[2]] - points_[ref[0]]));
  else
    side = n * (centroid - box_.Center()); // a new component: outwards from the cloud's centre
  if (side < 0) std::swap(tri[1], tri[2]);
}

bool Mesher::findSeedTriangle(std::uint32_t p, std::array<std::uint32_t, 3>& tri) {
  ++seedAttempts_;
  if (!pem_.isolated(p)) return false;
  double d2 = 0;
  const int nearest = grid_.nearest(points_[p], &d2, static_cast<int>(p), seedMaxEdge_);
  if (nearest < 0) return false;
  const auto q = static_cast<std::uint32_t>(nearest);
  if (!pem_.isolated(q)) return false;
  const double edge = std::sqrt(d2);
  if (!(edge > 0)) return false;
  const P3 &P = points_[p], &Q = points_[q];
  const P3 mid = (P + Q) * 0.5;
  const double radius = params_.seedSearchFactor * edge;
  gather(mid, radius);
  scored_.clear();
  for (const Near& x : near_) {
    if (x.id == p || x.id == q || !pem_.isolated(x.id)) continue;
    Ball ball;
    if (!circumBall(P, Q, x.p, ball)) continue;
    scored_.push_back(Scored{ball.radius2, 0, x.id, ball, 0});
  }
  std::sort(scored_.begin(), scored_.end(), [](const Scored& x, const Scored& y) {
    return x.key1 != y.key1 ? x.key1 < y.key1 : x.id < y.id;
  });
  const size_t tries = std::min(scored_.size(), kMaxSeedTriangles);
  for (size_t k = 0; k < tries; ++k) {
    const Scored s = scored_[k];
    if (!emptyBall(s.ball, radius, mid, p, q, s.id)) continue;
    if (!passesCylinderTest(p, q, s.id)) continue;
    tri = {p, q, s.id};
    orientSeed(tri);
    return true;
  }
  return false;
}

void Mesher::addSeed(const std::array<std::uint32_t, 3>& tri) {
  ++seeds_;
  addTriangle(tri[0], tri[1], tri[2]);
}

void Mesher::meshAll(Progress* progress) {
  const size_t n = points_.size();
  if (n < 3) return;
  // Seed points in a seeded pseudo-random order (sec. 3.1 step 3.1): start + i·stride mod n with
  // the stride coprime to n visits every point once, without storing a permutation. Every unused
  // point is tried once, after the fronts before it died: a failed attempt cannot succeed later
  // (its G2S and cylinder tests do not change and points only ever become used), so one sweep
  // leaves no valid seed behind.
  Random rng(params_.randomSeed);
  const std::uint64_t start = rng.next() % n;
  std::uint64_t stride = n > 2 ? 1 + rng.next() % (n - 1) : 1;
  while (gcd(stride, n) != 1) stride = stride % (n - 1) + 1;
  std::array<std::uint32_t, 3> tri;
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto p = static_cast<std::uint32_t>((start + i * stride) % n);
    if (progress != nullptr && (i & 1023) == 0)
      progress->update(std::max(double(usedPoints_), double(i)) / double(n));
    if (!pem_.isolated(p)) continue;
    if (!findSeedTriangle(p, tri)) continue;
    addSeed(tri);
    grow(progress);
  }
}

ManifoldCleanupStat Mesher::removeNonManifoldVertices() {
  alive_.assign(tri_.size(), 1);
  const ManifoldCleanupStat st = growth::removeNonManifoldVertices(tri_, points_.size(), alive_);
  for (size_t f = 0; f < tri_.size(); ++f)
    if (!alive_[f]) pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
  return st;
}

void Mesher::orientComponents() {
  const size_t n = points_.size();
  if (alive_.size() != tri_.size()) alive_.assign(tri_.size(), 1);
  std::vector<std::uint32_t> parent(n);
  for (size_t i = 0; i < n; ++i) parent[i] = static_cast<std::uint32_t>(i);
  auto root = [&](std::uint32_t i) {
    while (parent[i] != i) {
      parent[i] = parent[parent[i]];
      i = parent[i];
    }
    return i;
  };
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    for (int k = 1; k < 3; ++k) {
      const std::uint32_t r0 = root(tri_[f][0]), r1 = root(tri_[f][k]);
      if (r0 != r1) parent[std::max(r0, r1)] = std::min(r0, r1);
    }
  }
  // Centroid of each component's face corners, then its signed volume about that centroid.
  std::vector<P3> centre(n, P3(0, 0, 0));
  std::vector<double> volume(n, 0.0);
  std::vector<std::uint32_t> corners(n, 0);
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    const std::uint32_t r = root(tri_[f][0]);
    for (std::uint32_t v : tri_[f]) centre[r] += points_[v];
    corners[r] += 3;
  }
  for (size_t r = 0; r < n; ++r)
    if (corners[r] > 0) centre[r] /= double(corners[r]);
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f]) continue;
    const std::uint32_t r = root(tri_[f][0]);
    const P3 a = points_[tri_[f][0]] - centre[r], b = points_[tri_[f][1]] - centre[r],
             c = points_[tri_[f][2]] - centre[r];
    volume[r] += a * (b ^ c);
  }
  for (size_t f = 0; f < tri_.size(); ++f) {
    if (!alive_[f] || !(volume[root(tri_[f][0])] < 0)) continue;
    pem_.removeTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
    std::swap(tri_[f][1], tri_[f][2]);
  }
  for (size_t f = 0; f < tri_.size(); ++f)
    if (alive_[f] && volume[root(tri_[f][0])] < 0) pem_.addTriangle(tri_[f][0], tri_[f][1], tri_[f][2]);
}

size_t Mesher::liveTriangles() const {
  if (alive_.size() != tri_.size()) return tri_.size();
  return static_cast<size_t>(std::count(alive_.begin(), alive_.end(), char(1)));
}

size_t Mesher::boundaryEdges() const {
  size_t n = 0;
  for (std::uint32_t v = 0; v < points_.size(); ++v)
    pem_.forEachEdge(v, [&](std::uint32_t, bool out, bool in) { n += out && !in; });
  return n;
}

size_t Mesher::boundaryLoops() {
  // Each boundary half-edge v→w (used, w→v unused) is followed by a boundary half-edge leaving w;
  // at a manifold vertex there is exactly one, so every walk traces one loop (one hole).
  size_t loops = 0;
  auto nextFrom = [&](std::uint32_t v, std::uint32_t& w) {
    bool found = false;
    pem_.forEachEdge(v, [&](std::uint32_t x, bool out, bool in) {
      if (!found && out && !in && !pem_.marked(v, x)) {
        w = x;
        found = true;
      }
    });
    return found;
  };
  for (std::uint32_t v = 0; v < points_.size(); ++v) {
    std::uint32_t w;
    while (nextFrom(v, w)) {
      ++loops;
      std::uint32_t cur = v;
      do {
        pem_.setMark(cur, w, true);
        cur = w;
      } while (nextFrom(cur, w));
    }
  }
  pem_.clearMarks(); // leave the map as it was
  return loops;
}

size_t Mesher::memoryBytes() const {
  return points_.capacity() * sizeof(P3) + grid_.memoryBytes() + pem_.memoryBytes() +
         edgeLengthSum_.capacity() * sizeof(float) + edgeCount_.capacity() * sizeof(std::uint16_t) +
         tri_.capacity() * sizeof(Triangle) + alive_.capacity();
}

} // namespace g2s
} // namespace growth
