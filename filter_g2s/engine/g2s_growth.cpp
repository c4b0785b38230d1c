// Robust G2S's growth (Di Angelo, Di Stefano, Giaccari, sec. 3.1-4.1): seeds, the front's
// candidate search by the G2S criterion, the priority queue, and the named options that act during
// it (g2s::Params::thinPartRules, loopClosures). The rest of the Mesher (set-up, sec. 4.2,
// orientation, results) is in g2s_mesher.cpp; the passes after the growth in g2s_repair.cpp,
// g2s_handles.cpp and g2s_thin.cpp.
#include "g2s_mesher.h"

#include <growth/cloud_generator.h> // growth::Random

#include <algorithm>
#include <cmath>
#include <limits>
#include <type_traits>

namespace growth {
namespace g2s {

namespace {
// At most this many third points are tried per seed attempt (by increasing circumradius): a
// point whose tightest triangles all fail is not a good place for a seed anyway, and outliers
// would otherwise test every point of a large ball.
constexpr size_t kMaxSeedTriangles = 32;
// findSeedTriangle: a third point is "near the line pq" within kSeedLineBand·|pq| of it; when all
// are, the seed sphere is searched again kSeedWiden times as wide.
constexpr double kSeedLineBand = 0.25;
constexpr double kSeedWiden = 2.0;
constexpr size_t kSeedLinePoints = 2; // (at least: two points of p's line besides q, not a chance one)
// A seed triangle's circumradius is at most this many seed edges (not in the paper): a sliver's
// ball and cylinder reach far (three points of one ring of a cylinder sampled in rings have the
// ring as their circle, an empty ball and a cylinder through the whole cloud: each test scanned
// half the cloud), and its growth dies at once.
constexpr double kSeedMaxCircumradius = 3.0;

// The cylinder test walks at most this many slabs (each two circumradii high) on each side of the
// seed triangle: its reach is 2048 circumradii, about 1200 local spacings, so the whole cylinder
// through a clean cloud of up to a few million points is still seen, while a far point (which
// stretches the bounding box) or a seed of almost no size (a few float steps across) costs at most
// 2 x 1024 ball queries per seed attempt instead of box size / circumradius.
constexpr long kMaxCylinderSlabs = 1024;

// Thin parts (not in the paper, whose analysis assumes a surface locally flat at the scale of its
// G2S balls; docs/design/g2s-thin-parts.md). Where a closed part is a few spacings thick, a search
// sphere and a G2S ball can reach the part's other sheet: the front then crosses the material, and
// the sheet grown on from the crossing is the other sheet seen from inside, inside out. The rules
// are set for closed slabs 3-4 mean nearest-neighbour spacings thick (tests/g2s_build_test.cpp,
// ThinSlab*):
// - kSheetGap: a point this many spacings (growth::meanSpacing) or more off the front triangle's
//   plane may lie on another sheet; sampling noise stays well below it (the noisy test clouds have
//   sigma <= 0.25 spacings);
// - fold: a candidate folding by beta >= 40 degrees, kFoldGap spacings or more behind the front
//   triangle (against its normal: into the material, where the component faces out, as a new
//   component's seed does, see orientSeed), is refused when its search sphere also holds a point
//   farther ahead within 10 degrees of the front's plane (the sheet goes on flat, beyond a gap of
//   its sampling, and the fold would cross to the other sheet); on a part's rim nothing lies flat
//   ahead, and the fold is the surface. Folds in front of the front triangle, or less than
//   kFoldGap behind it, are left alone: in merged scans that is where the front steps between
//   layers of one surface a spacing or two apart (misregistration), and refusing those steps
//   opens holes, while a thin part's other sheet lies a whole thickness (3 spacings or more,
//   where the rule is needed) behind;
// - other sheet in a G2S ball: for a flat candidate (beta < 30 degrees), points inside its G2S
//   ball farther from its plane than R / sqrt 2, kSheetGap spacings and the local mesh edge length
//   do not make it fail: on a smooth, well-sampled sheet no point of the sheet lies there, so they
//   are the other sheet, which would leave a hole wherever a sheet's sampling has a gap wider than
//   the part's thickness.
constexpr double kSheetGap = 1.5;
constexpr double kFoldGap = 2.0;
const double kFoldCos = std::cos(40.0 * 3.14159265358979323846 / 180.0);
const double kFlatAheadCos = std::cos(10.0 * 3.14159265358979323846 / 180.0);
// - fold across a gap: a candidate folding by beta >= 30 degrees (kGapFoldCos), single point of
//   its search region or not, kFoldGap spacings or more behind the front triangle, whose point lies
//   on a sheet parallel to the front's (kGapSheetPoints points near it in that plane), is refused
//   when the front's sheet goes on flat beyond it (a wider ball than the search sphere: in a gap of
//   the sheet, the search sphere can hold the other sheet's point alone). kGapSheetReach is 4
//   spacings, not 3: within 3, about 7 points of a sheet are expected (the mean spacing is the
//   mean nearest-neighbour distance, about half the edge length), but under the gap the front
//   looks through, the other sheet's sampling can be sparse too, with as few as 3 there.
const double kGapFoldCos = std::cos(30.0 * 3.14159265358979323846 / 180.0);
constexpr int kGapSheetPoints = 5;
constexpr double kGapSheetReach = 4.0;
const double kOtherSheetFlatCos = std::cos(30.0 * 3.14159265358979323846 / 180.0);
// - under a sheet (rims): a candidate kUnderGap spacings or more behind the front
//   triangle, on a surface, is refused when a point of the mesh lies in front of the new triangle
//   (in the cylinder over its circumcircle, kSheetGap spacings to kUnderReach circumradii along its
//   normal, and kUnderFrontGap spacings or more in front of the front triangle's plane), with at
//   least kUnderSheetEdges edges and its triangle facing the same way (cosine above
//   kUnderSameWayCos): the new triangle would lie in the material under that sheet. It catches
//   what the fold rules above leave alone at a plate's rim: a front triangle across the top-side
//   corner continuing to a bottom point less than kFoldGap behind it, through the corner of the
//   material, from which the bottom would grow inside out.
constexpr double kUnderGap = 0.5;
constexpr double kUnderReach = 3.0;
constexpr double kUnderFrontGap = 1.0;
constexpr std::uint32_t kUnderSheetEdges = 4;
constexpr double kUnderSameWayCos = 0.25;
// - after a crossing: the triangles grown on from a candidate kUnderGap or more
//   behind its front triangle, for Mesher::kCrossingMark generations (marked on their points), are
//   refused when they lie under a sheet of the mesh facing the same way beyond an empty layer: a
//   point with kUnderSheetEdges edges and its triangle facing the same way, within kChildNarrow
//   spacings of the axis through the new triangle's centroid (or its circumradius, if smaller),
//   kChildGap to kChildReach spacings in front of it (and kUnderFrontGap in front of the front
//   triangle), with no point nearer in front than that one minus kChildMargin (from kChildMargin
//   on) within kChildWide spacings of the axis. Where a crossing triangle (a chamfer at a plate's
//   rim, 1.5-2 spacings into the material, with no sheet meshed in front of it yet, or a triangle
//   down through a gap of the top sheet's sampling) leads the front onto the other sheet, the
//   sheet it would grow there is the other sheet inside out, under the sheet already meshed: its
//   first triangles are refused, and the front reaches that sheet elsewhere the right way round.
//   The empty layer keeps a noisy sheet's own upper points (noise of sigma 0.5 spacings puts points
//   2-4 spacings above a triangle at the bottom of the spread) from counting as a sheet, and the
//   narrow axis keeps slivers' wide circumcircles from reaching far. kChildGap is 2.5 rather than
//   2: as good on thin plates, and fewer points of a merged scan's second layers are left out.
//   (The crossing is Mesher::kCrossingGap = kUnderGap spacings behind.)
constexpr double kChildGap = 2.5;
constexpr double kChildReach = 4.0;
constexpr double kChildMargin = 0.5;
constexpr double kChildNarrow = 1.5;
constexpr double kChildWide = 2.0;

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

void Mesher::gather(const P3& centre, double radius) {
  grid_.gatherNear(centre, radius, near_);
  nearCentre_ = centre;
  nearRadius_ = radius;
}

template <class F> bool Mesher::anyInBall(const P3& c, double radius, F&& stop) const {
  // Within the gathered ball, its list holds every point of this one (and others, which the
  // exact distance leaves out as the grid's scan does): the same points, fewer visited.
  if (!((c - nearCentre_).Norm() + radius <= nearRadius_ * (1.0 - 1e-12))) return grid_.anyInBall(c, radius, stop);
  const double r2 = radius * radius;
  for (size_t k = 0; k < near_.size; ++k) {
    const std::uint32_t i = near_.id[k];
    const P3& p = pts_[i];
    const double dx = p[0] - c[0], dy = p[1] - c[1], dz = p[2] - c[2];
    const double d2 = dx * dx + dy * dy + dz * dz;
    if (d2 <= r2 && stop(i, d2)) return true;
  }
  return false;
}

bool Mesher::emptyBall(const Ball& ball, double gatherRadius, const P3& gatherCentre, std::uint32_t a,
                       std::uint32_t b, std::uint32_t c) const {
  // The point found inside the last ball tested first: the balls tested one after another are
  // mostly those of one edge's candidates, which overlap, so a point inside one is often inside
  // the next. The same exact test as below, so the same answer.
  {
    const std::uint32_t w = lastInside_;
    if (w != a && w != b && w != c && w < grid_.size() && strictlyInside((pts_[w] - ball.centre).SquaredNorm(), ball.radius2))
      return false;
  }
  // Gathered points: decided in float where they are farther than the float error from the
  // sphere, exactly otherwise (the three points on the sphere always go the exact way).
  float cf[3];
  grid_.toFloat(ball.centre, cf);
  const double radius = std::sqrt(ball.radius2), slack = 2.0 * grid_.floatSlack(cf, radius);
  const float inner = !(slack < radius) ? 0.f : float((radius - slack) * (radius - slack) * (1.0 - 1e-6));
  const float outer = float((radius + slack) * (radius + slack) * (1.0 + 1e-6));
  // Each point within the float error of the sphere (or inside) is decided: inside by more than
  // that error in float, otherwise exactly in double.
  const std::uint32_t skip[3] = {a, b, c};
  size_t borderline = 0;
  // When not empty: lastInside_ is a point inside.
  if (near_.insideOrBorderline(cf, inner, outer, skip, near_.hit.data(), &borderline)) {
    lastInside_ = near_.id[near_.hit[0]];
    return false;
  }
  for (size_t h = 0; h < borderline; ++h) {
    const std::uint32_t i = near_.id[near_.hit[h]];
    if (strictlyInside((pts_[i] - ball.centre).SquaredNorm(), ball.radius2)) {
      lastInside_ = i;
      return false;
    }
  }
  // The gathered ball contains the whole test ball: the check above was complete.
  if ((ball.centre - gatherCentre).Norm() + radius <= gatherRadius * (1.0 - 1e-12)) return true;
  return !grid_.anyInBall(ball.centre, radius, [&](std::uint32_t i, double d2) {
    return i != a && i != b && i != c && strictlyInside(d2, ball.radius2) && (lastInside_ = i, true);
  });
}

bool Mesher::isGabriel(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  Ball ball;
  if (!circumBall(pts_[a], pts_[b], pts_[c], ball)) return false;
  const double radius = std::sqrt(ball.radius2);
  return !grid_.anyInBall(ball.centre, radius, [&](std::uint32_t i, double d2) {
    return i != a && i != b && i != c && strictlyInside(d2, ball.radius2);
  });
}

bool Mesher::passesCylinderTest(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  const P3 &A = pts_[a], &B = pts_[b], &C = pts_[c];
  Ball ball;
  if (!circumBall(A, B, C, ball)) return false;
  const P3 n = unitNormal(A, B, C);
  if (isZero(n)) return false;
  const double radius = std::sqrt(ball.radius2);
  const double eps = 1e-6 * radius; // a point this close to the plane is on it (coplanar clouds)
  // The infinite cylinder is walked in slabs of height 2R along its axis, each covered by a ball
  // of radius R·√2, from the triangle outwards in both directions until the slabs leave the
  // cloud's bounding box or kMaxCylinderSlabs were walked (the bound on the work, see there); the
  // walk stops as soon as points on both sides were seen.
  const double step = 2.0 * radius, queryRadius = radius * std::sqrt(2.0);
  Box3d bb = grid_.box();
  bb.Offset(queryRadius);
  bool above = false, below = false;
  auto bothSides = [&](std::uint32_t i, double) {
    if (i == a || i == b || i == c) return false;
    const P3 d = pts_[i] - ball.centre;
    const double h = d * n;
    if (!strictlyInside(d.SquaredNorm() - h * h, ball.radius2)) return false;
    if (h > eps) above = true;
    else if (h < -eps) below = true;
    return above && below;
  };
  for (int side : {1, -1}) {
    for (long j = side > 0 ? 0 : 1; j < kMaxCylinderSlabs; ++j) {
      const P3 centre = ball.centre + n * (double(side) * double(j) * step);
      if (!bb.IsIn(centre)) break;
      ++cylinderQueries_;
      if (grid_.anyInBall(centre, queryRadius, bothSides)) return false;
    }
  }
  return true;
}

bool Mesher::topologyAllows(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t p) const {
  if (p == a || p == b || p == c) return false;
  // No edge at p yet: nothing can conflict. New triangle (b, a, p): half-edges b→a (free by
  // construction), a→p and p→b must be unused.
  const bool allowed = isolated(p) || (!interior(p) && !pem_.used(a, p) && !pem_.used(p, b));
  // The new edges need room at their points (PointEdgeMap::capacity): asked only once some point
  // is near full; where one is full, the edge stays open (counted by queueEdge).
  if (!allowed || !nearFullPoint_ || pem_.hasRoom(b, a, p)) return allowed;
  roomRefused_ = true;
  return false;
}

Candidate Mesher::findCandidate(std::uint32_t a, std::uint32_t b, std::uint32_t c, bool ears) {
  Candidate none;
  const P3 &A = pts_[a], &B = pts_[b], &C = pts_[c];
  const double edge2 = (B - A).SquaredNorm(), edge = std::sqrt(edge2);
  if (!(edge > 0)) return none;
  const P3 dir = growingDirection(A, B, C);
  if (isZero(dir)) return none;
  const P3 frontNormal = (B - A) ^ (C - A);
  const double frontNorm = frontNormal.Norm();
  // A free edge that closes a loop of three free edges (a→b, b→p, p→a all used one way only):
  // the triangle (b, a, p) is the only one that can ever be placed there, so it is the candidate,
  // G2S or not. On a curved or noisy surface the G2S ball of such a triangle can hold a vertex of
  // a neighbouring triangle barely inside (the Gabriel test is not symmetric across an edge as
  // the 2D Delaunay circle test is), which would otherwise leave a three-edge hole.
  if (ears && params_.loopClosures && freeEdges_[b] >= 2) {
    std::int64_t ear = -1;
    pem_.anyOutOnly(b, [&](std::uint32_t p) {
      if (p != a && p != c && pem_.used(p, a) && !pem_.used(a, p)) ear = p;
      return ear >= 0;
    });
    // (The ear must pass the topology tests too, as every candidate does: else grow would
    // requeue the edge, find the same ear and requeue it for ever. Counts at a point that are
    // off would do that; the growth keeps them right, a regrowth's fixed faces are checked.)
    if (ear >= 0 && topologyAllows(a, b, c, std::uint32_t(ear))) {
      const P3& E = pts_[ear];
      Candidate cand;
      cand.point = ear;
      cand.sizeLevel = 1;
      const P3 earNormal = (A - B) ^ (E - B);
      cand.cosBeta = (frontNormal * earNormal) / (frontNorm * earNormal.Norm());
      cand.flatLevel = flatnessLevelOfCos(cand.cosBeta);
      cand.closesLoop = true;
      return cand;
    }
  }
  const Candidate grown = search(a, b, c, dir, frontNormal, frontNorm);
  if (grown.valid() || !params_.loopClosures || freeEdges_[b] < 2 || freeEdges_[a] < 2) return grown;
  return quadClosure(a, b, c, frontNormal, frontNorm);
}

Candidate Mesher::quadClosure(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& frontNormal,
                              double frontNorm) const {
  // The free edge a→b on a loop of four free edges a→b→p→q→a: a hole no search spans (on a
  // curved surface the G2S balls of both its triangulations can hold a neighbouring vertex). It
  // is closed by the diagonal whose two triangles have the larger smallest angle (grow() checks
  // each of them for an unused point inside, as for any loop); the edge is queued last (size
  // level n, flatness m), so it closes only if the growth around it did not.
  std::int64_t p = -1, q = -1;
  pem_.forEachEdge(b, [&](std::uint32_t x, bool out, bool in) {
    if (q >= 0 || !out || in || x == a || x == c) return;
    pem_.forEachEdge(x, [&](std::uint32_t y, bool out2, bool in2) {
      if (q >= 0 || !out2 || in2 || y == a || y == b) return;
      if (pem_.used(y, a) && !pem_.used(a, y)) {
        p = x;
        q = y;
      }
    });
  });
  if (q < 0) return Candidate();
  const auto P = static_cast<std::uint32_t>(p), Q = static_cast<std::uint32_t>(q);
  // Diagonal b–q: triangles (b, a, q) and (b, q, p); diagonal a–p: (b, a, p) and (a, q, p).
  auto minSine = [&](std::uint32_t u, std::uint32_t v, std::uint32_t w) {
    const P3 &U = pts_[u], &V = pts_[v], &W = pts_[w];
    const double twiceArea = ((V - U) ^ (W - U)).Norm();
    const double l2 = std::max({(V - U).SquaredNorm(), (W - V).SquaredNorm(), (U - W).SquaredNorm()});
    return l2 > 0 ? twiceArea / l2 : 0.0; // grows with the smallest angle
  };
  const double viaQ = std::min(minSine(b, a, Q), minSine(b, Q, P));
  const double viaP = std::min(minSine(b, a, P), minSine(a, Q, P));
  const std::uint32_t first = viaQ >= viaP ? Q : P, second = viaQ >= viaP ? P : Q;
  for (std::uint32_t x : {first, second}) {
    if (!topologyAllows(a, b, c, x)) continue;
    const P3 newNormal = (pts_[a] - pts_[b]) ^ (pts_[x] - pts_[b]);
    Candidate cand;
    cand.point = x;
    cand.sizeLevel = params_.sizeLevels;
    cand.cosBeta = (frontNormal * newNormal) / (frontNorm * newNormal.Norm());
    cand.flatLevel = params_.flatnessLevels;
    cand.closesLoop = true;
    return cand;
  }
  return Candidate();
}

bool Mesher::unusedPointInside(std::uint32_t a, std::uint32_t b, std::uint32_t c) const {
  // An unused point whose projection on the plane of (a, b, c) falls inside the triangle, at most
  // r from the plane, r the radius of the triangle's smallest enclosing ball (the circumball, or
  // for an obtuse triangle the ball on its longest edge): the query stays at the triangle's own
  // scale even for a sliver, whose circumball can be huge.
  const P3 &A = pts_[a], &B = pts_[b], &C = pts_[c];
  const P3 n = (B - A) ^ (C - A);
  const double n2 = n.SquaredNorm();
  if (!(n2 > 0)) return false;
  Ball ball;
  if (!smallestEnclosingBall(A, B, C, ball)) return false;
  const P3& centre = ball.centre;
  const double r2 = ball.radius2;
  return grid_.anyInBall(centre, std::sqrt(2.0 * r2), [&](std::uint32_t i, double) {
    if (!isolated(i)) return false;
    const P3& X = pts_[i];
    const double h = (X - A) * n;
    if (h * h > r2 * n2) return false;
    // Inside the prism over the triangle: on the inner side of its three edges' planes along n.
    return ((B - A) ^ (X - A)) * n > 0 && ((C - B) ^ (X - B)) * n > 0 && ((A - C) ^ (X - C)) * n > 0;
  });
}

// The candidate search's steps are inlined into their one caller, findCandidate: they run for
// every front edge, where a call per step shows in the growth's time.
#if defined(__GNUC__)
#define GROWTH_G2S_INLINE __attribute__((always_inline)) inline
#else
#define GROWTH_G2S_INLINE inline
#endif

GROWTH_G2S_INLINE size_t Mesher::spherePoints(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& A, const P3& B,
                                              double edge2, const P3& centre, double radius, double r2,
                                              const P3& previousCentre, double previousR2, size_t& found,
                                              std::int64_t& seenBefore) {
  found = 0;
  seenBefore = -1; // a found point skipped as a candidate of the previous level
  float cf[3];
  grid_.toFloat(centre, cf);
  const double slack = 2.0 * grid_.floatSlack(cf, radius);
  const float outer = float((radius + slack) * (radius + slack) * (1.0 + 1e-6));
  const std::uint32_t front[3] = {a, b, c};
  const size_t hits = near_.collectWithin(cf, outer, front, near_.hit.data());
  // Each hit point q (within the float error of the sphere, or inside) is decided exactly, and
  // taken without branches on the outcome.
  // scored_ is a buffer here: its first `count` entries are this level's candidates.
  if (scored_.size() < hits + 1) scored_.resize(hits + 1);
  size_t count = 0;
  const P3 AB = A - B;
  const double collinear = 1e-20 * edge2;
  // (Two instances of the loop: at the first level, where most searches end, there is no
  // previous sphere to test the points against. At the later ones, many of the hits lay in it:
  // the new candidates are listed first, over the hits, in order, and ranked in a second loop.)
  std::uint32_t* const hit = near_.hit.data();
  size_t fresh = 0;
  auto rank = [&](std::uint32_t id, const P3& q) {
    // Not collinear with the edge, so a triangle; R² its squared circumradius.
    const double n2 = (AB ^ (q - B)).SquaredNorm();
    const double aq2 = (q - A).SquaredNorm(), bq2 = (q - B).SquaredNorm();
    scored_[count] = Scored{0, edge2 * aq2 * bq2 / (4.0 * n2), id, 0};
    return n2 > collinear * aq2;
  };
  auto scan = [&](auto withPrevious) {
    for (size_t h = 0; h < hits; ++h) {
      const std::uint32_t id = hit[h];
      const P3& q = pts_[id];
      // In the search sphere.
      const bool in = !((q - centre).SquaredNorm() > r2);
      found += in;
      // An interior point counts as found and for G2S balls, never as a candidate.
      const bool candidate = in & !interior(id);
      // A point of the previous level's sphere was a candidate there and was rejected by the
      // topological or the G2S test; both depend on the point, the edge and the mesh only, which
      // have not changed since, so the G2S ranking below would reject it again. Only the points
      // new at this level are ranked: among them the order is that of the whole list, so the
      // choice is the same. (The same exact test as at that level decides membership.) It still
      // counts as found, and when it is the only point found it is taken directly below, as the
      // single point of the region (the spheres are nested on the growing side only, so a level
      // can hold fewer points than the one before).
      if (decltype(withPrevious)::value) {
        const bool previous = (q - previousCentre).SquaredNorm() <= previousR2;
        const std::int64_t last = -std::int64_t(candidate & previous); // all ones or zero, no branch
        seenBefore = (last & std::int64_t(id)) | (~last & seenBefore);
        hit[fresh] = id;
        fresh += candidate & !previous;
      } else {
        count += candidate & rank(id, q);
      }
    }
  };
  if (previousR2 >= 0) {
    scan(std::true_type());
    for (size_t h = 0; h < fresh; ++h) count += rank(hit[h], pts_[hit[h]]);
  } else {
    scan(std::false_type());
  }
  return count;
}

GROWTH_G2S_INLINE Candidate Mesher::accepted(const P3& A, const P3& B, std::uint32_t id, int level, const P3& frontNormal,
                                             double frontNorm, bool single) const {
  const P3 newNormal = (A - B) ^ (pts_[id] - B);
  Candidate cand;
  cand.point = id;
  cand.sizeLevel = level;
  cand.cosBeta = (frontNormal * newNormal) / (frontNorm * newNormal.Norm());
  cand.flatLevel = flatnessLevelOfCos(cand.cosBeta);
  cand.single = single;
  return cand;
}

GROWTH_G2S_INLINE Candidate Mesher::g2sPoint(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& A, const P3& B,
                                             size_t count, int level, const P3& dir, const P3& frontNormal,
                                             double frontNorm, double radius, double local, double gatherRadius,
                                             const P3& gatherCentre) {
  // Several points: the reference point is the one whose smallest sphere through it and the
  // edge's endpoints is empty. Where several are (the G2S triangulation is not unique off the
  // plane), the one with the smallest such sphere: the point a sphere growing from the edge
  // meets first, as in the planar Delaunay case. (Rather than "flattest class first": on merged
  // scans and noisy clouds it leaves fewer holes, boundary edges and non-manifold vertices, with
  // fewer G2S tests; the flatness still orders the queue, sec. 4.1.) They are
  // tested in that order, skipping the points the topological tests reject.
  // The list is ordered lazily: the first kLazyPicks are selected one by one, the next smallest
  // (R², id) among the untested candidates (the first one or two are usually taken, so most of a
  // sort would be wasted), and only a list that gets that far is sorted, the rest of it at once
  // (bounding the work on long lists). Either way the order, and so the choice, is that of the
  // sorted list: (R², id) is a strict order, the ids being distinct.
  // (Evaluated without short-circuit branches: the selection is a chain of conditional moves.)
  auto before = [](const Scored& x, const Scored& y) {
    return (x.radius2 < y.radius2) | ((x.radius2 == y.radius2) & (x.id < y.id));
  };
  constexpr size_t kLazyPicks = 4;
  for (size_t done = 0; done < count; ++done) {
    if (done < kLazyPicks) {
      size_t best = done;
      for (size_t j = done + 1; j < count; ++j) best = before(scored_[j], scored_[best]) ? j : best;
      std::swap(scored_[done], scored_[best]);
    } else if (done == kLazyPicks) {
      std::sort(scored_.begin() + std::ptrdiff_t(done), scored_.begin() + std::ptrdiff_t(count), before);
    }
    const std::uint32_t id = scored_[done].id;
    if (!topologyAllows(a, b, c, id)) continue;
    Ball ball;
    if (!circumBall(B, A, pts_[id], ball)) continue;
    if (!emptyBall(ball, gatherRadius, gatherCentre, a, b, id) &&
        // (A G2S ball can hold another sheet's points only beyond kSheetGap spacings and the
        // local edge length.)
        !(thin_ && __builtin_expect(ball.radius2 > std::max(kSheetGap * kSheetGap * spacing_ * spacing_, local * local), 0) &&
          emptyButOtherSheet(ball, a, b, id, lastInside_, frontNormal, frontNorm, local, gatherRadius, gatherCentre)))
      continue;
    const Candidate cand = accepted(A, B, id, level, frontNormal, frontNorm, false);
    if (!thin_) return cand;
    if ((__builtin_expect(cand.cosBeta < kGapFoldCos, 0) &&
         ((cand.cosBeta < kFoldCos && foldsAcrossThePart(a, b, c, id, dir, frontNormal, frontNorm, radius)) ||
          foldsAcrossAGap(a, b, id, dir, frontNormal, frontNorm))) ||
        (__builtin_expect((pts_[id] - A) * frontNormal <= -kUnderGap * spacing_ * frontNorm, 0) &&
         growsUnderASheet(a, b, id, frontNormal, frontNorm))) {
      ++foldsRefused_;
      continue;
    }
    if (refusedAfterCrossing(a, b, id, frontNormal, frontNorm)) {
      ++foldsRefused_;
      continue;
    }
    return cand;
  }
  return Candidate();
}

GROWTH_G2S_INLINE Candidate Mesher::search(std::uint32_t a, std::uint32_t b, std::uint32_t c, const P3& dir,
                                           const P3& frontNormal, double frontNorm) {
  Candidate none;
  const P3 &A = pts_[a], &B = pts_[b];
  const double edge2 = (B - A).SquaredNorm(), edge = std::sqrt(edge2);
  const P3 mid = (A + B) * 0.5;
  // Maximum search radius: a multiple of the local spacing, here the mean length of the mesh
  // edges already at a and b (sec. 3.2 leaves its choice open; edge lengths of the growing mesh
  // follow the local density, so non-uniform clouds get a radius that fits each region).
  const double local = 0.5 * (localSpacing(a) + localSpacing(b));
  const double maxRadius = std::max(edge, params_.maxSearchRadiusFactor * local);
  const int n = params_.sizeLevels;
  // The gathered ball of a level covers its search sphere (which reaches from t − r > −|ab|/2
  // to t + r along the growing direction, t its centre's distance from the edge) and the region
  // half an edge behind the edge, where the G2S balls of well-shaped candidates reach (a candidate
  // seeing ab under at least 30° has a G2S ball of radius <= |ab| within [−|ab|/2, t + r]), so
  // most G2S tests need no second grid query. These balls are nested (all tangent at the point
  // half an edge behind the edge), so the first level gets its own gather and all further levels
  // share the gather of the last one: at most two grid queries per edge.
  auto gatherBall = [&](double radius, P3& centre, double& gatherRadius) {
    const double t = std::sqrt(std::max(radius * radius - 0.25 * edge * edge, 0.0));
    gatherRadius = 0.5 * (t + radius + 0.5 * edge);
    centre = mid + dir * (0.5 * (t + radius - 0.5 * edge));
  };
  P3 gatherCentre;
  double gatherRadius = 0;
  bool gatheredFirst = false, gatheredLast = false;
  double previous = -1;
  // The search sphere of the previous level, whose candidates were all tested and rejected.
  P3 previousCentre(0, 0, 0);
  double previousR2 = -1;
  for (int level = 1; level <= n; ++level) {
    const double radius = searchRadius(level, n, edge, maxRadius);
    if (radius <= previous) continue;
    previous = radius;
    // The level's gathered ball (first level, then the last one's for all others).
    if (!gatheredFirst) {
      gatherBall(radius, gatherCentre, gatherRadius);
      gather(gatherCentre, gatherRadius);
      gatheredFirst = true;
    } else if (!gatheredLast) {
      gatherBall(searchRadius(n, n, edge, maxRadius), gatherCentre, gatherRadius);
      gather(gatherCentre, gatherRadius);
      gatheredLast = true;
    }
    // Sec. 3.2 step 4.1: the points of the level's search sphere, ranked by circumradius.
    const P3 centre = searchCentre(A, B, dir, radius);
    const double r2 = radius * radius * (1.0 + 1e-12);
    size_t found;
    std::int64_t seenBefore;
    size_t count = spherePoints(a, b, c, A, B, edge2, centre, radius, r2, previousCentre, previousR2, found, seenBefore);
    previousCentre = centre;
    previousR2 = r2;
    if (found == 1 && seenBefore >= 0) {
      // The single point of the region is one ranked at the previous level: as in the original
      // order, it is taken directly when it spans a triangle with the edge and the topological
      // tests allow it.
      const std::uint32_t id = static_cast<std::uint32_t>(seenBefore);
      const P3& q = pts_[id];
      const double n2 = ((A - B) ^ (q - B)).SquaredNorm();
      if (n2 > 1e-20 * edge2 * (q - A).SquaredNorm()) scored_[count++] = Scored{0, 0.0, id, 0};
    }
    if (count == 0) continue;
    // Sec. 3.2 step 4.2: a single point in the search region is taken directly (when the
    // topological tests allow it).
    if (found == 1) {
      if (!topologyAllows(a, b, c, scored_[0].id)) continue;
      const Candidate cand = accepted(A, B, scored_[0].id, level, frontNormal, frontNorm, true);
      if (!thin_) return cand;
      if ((__builtin_expect(cand.cosBeta < kGapFoldCos, 0) && foldsAcrossAGap(a, b, scored_[0].id, dir, frontNormal, frontNorm)) ||
          (__builtin_expect((pts_[scored_[0].id] - A) * frontNormal <= -kUnderGap * spacing_ * frontNorm, 0) &&
           growsUnderASheet(a, b, scored_[0].id, frontNormal, frontNorm))) {
        ++foldsRefused_;
        continue;
      }
      if (refusedAfterCrossing(a, b, scored_[0].id, frontNormal, frontNorm)) {
        ++foldsRefused_;
        continue;
      }
      return cand;
    }
    // Several points: the G2S point among them, in order of circumradius.
    const Candidate cand =
        g2sPoint(a, b, c, A, B, count, level, dir, frontNormal, frontNorm, radius, local, gatherRadius, gatherCentre);
    if (cand.valid()) return cand;
    // Points were found but none spans an empty sphere with the edge: the G2S point lies farther
    // out, so the radius grows on (the paper grows it when no point is found; a region holding
    // only non-G2S points has not reached the G2S point yet).
  }
  return none;
}

bool Mesher::emptyButOtherSheet(const Ball& ball, std::uint32_t a, std::uint32_t b, std::uint32_t p,
                                std::uint32_t inside, const P3& frontNormal, double frontNorm, double local,
                                double gatherRadius, const P3& gatherCentre) {
  // Flat candidates only: a fold is no gap-closing triangle of the sheet.
  const P3 n = (pts_[a] - pts_[b]) ^ (pts_[p] - pts_[b]);
  const double len = n.Norm();
  if (!(len > 0) || !((frontNormal * n) > kOtherSheetFlatCos * frontNorm * len)) return false;
  const P3 unit = n / len;
  const double radius = std::sqrt(ball.radius2);
  // Farther than the local edge length too: where the sampling is that coarse, the surface itself
  // (a tube of a few edges across) can lie there.
  const double far = std::max({radius * std::sqrt(0.5), kSheetGap * spacing_, local});
  // The point that failed the emptiness test lies near the plane (on a clean cloud, nearly
  // always): the ball is spoiled by its own sheet, without another query.
  if (std::abs((pts_[inside] - ball.centre) * unit) <= far) return false;
  auto spoils = [&](std::uint32_t i, double d2) {
    return i != a && i != b && i != p && strictlyInside(d2, ball.radius2) &&
           std::abs((pts_[i] - ball.centre) * unit) <= far;
  };
  // The gathered points first: a point of them that spoils the ball decides it (its own sheet,
  // near the front, nearly always does); where they hold the whole ball (gatherNear keeps a float
  // margin) none spoiling it decides it too; only otherwise the grid is asked. The same answer
  // as the grid's query alone, from far fewer points.
  bool spoiled = false;
  for (size_t k = 0; k < near_.size && !spoiled; ++k) {
    const std::uint32_t i = near_.id[k];
    spoiled = spoils(i, (pts_[i] - ball.centre).SquaredNorm());
  }
  if (!spoiled && !((ball.centre - gatherCentre).Norm() + radius <= gatherRadius * (1.0 - 1e-12)))
    spoiled = grid_.anyInBall(ball.centre, radius, spoils);
  otherSheetBalls_ += !spoiled;
  return !spoiled;
}

bool Mesher::foldsAcrossThePart(std::uint32_t a, std::uint32_t b, std::uint32_t c, std::uint32_t p, const P3& dir,
                                const P3& frontNormal, double frontNorm, double radius) const {
  const P3 &A = pts_[a], &B = pts_[b], &Q = pts_[p];
  // Behind the front triangle, kFoldGap spacings or more: into the material.
  if (!((Q - A) * frontNormal <= -kFoldGap * spacing_ * frontNorm)) return false;
  const P3 mid = (A + B) * 0.5;
  const double ahead = (Q - mid) * dir;
  // The points of the search sphere again (the G2S tests since have overwritten the list; the
  // sphere is set up again as in search, which then need not keep it).
  const P3 centre = searchCentre(A, B, dir, radius);
  const double r2 = radius * radius * (1.0 + 1e-12);
  float cf[3];
  grid_.toFloat(centre, cf);
  const double slack = 2.0 * grid_.floatSlack(centre, radius);
  const float outer = float((radius + slack) * (radius + slack) * (1.0 + 1e-6));
  const std::uint32_t front[3] = {a, b, c};
  foldHits_.resize(near_.size + kNearPad);
  const size_t hits = near_.collectWithin(cf, outer, front, foldHits_.data());
  for (size_t h = 0; h < hits; ++h) {
    const P3& X = pts_[foldHits_[h]];
    if ((X - centre).SquaredNorm() > r2 || (X - mid) * dir <= ahead) continue;
    const P3 n = (A - B) ^ (X - B);
    const double len = n.Norm();
    if (len > 0 && (frontNormal * n) > kFlatAheadCos * frontNorm * len) return true;
  }
  return false;
}

bool Mesher::onASurface(std::uint32_t p) const {
  // (A property of the points alone: asked once per point.)
  if (onSurface_[p] != 0) return onSurface_[p] == 1;
  int near = 0;
  anyInBall(pts_[p], kGapSheetReach * spacing_, [&](std::uint32_t i, double) {
    near += i != p;
    return near >= kGapSheetPoints;
  });
  onSurface_[p] = near >= kGapSheetPoints ? 1 : 2;
  return near >= kGapSheetPoints;
}

bool Mesher::facesTheSameWay(std::uint32_t i, const P3& n) const {
  std::array<std::uint32_t, 3> t;
  if (!triangleAt(i, t)) return false;
  const P3 m = (pts_[t[1]] - pts_[t[0]]) ^ (pts_[t[2]] - pts_[t[0]]);
  return m * n > kUnderSameWayCos * m.Norm();
}

bool Mesher::growsUnderASheet(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& frontNormal,
                              double frontNorm) const {
  const P3 &A = pts_[a], &B = pts_[b], &Q = pts_[p];
  // p is a point of a surface (kGapSheetPoints others within kGapSheetReach spacings), not a
  // stray one: where outliers float about a surface, their candidates are left to the G2S rules.
  if (!onASurface(p)) return false;
  // The new triangle (b, a, p), its circumball and unit normal (outwards, as the component).
  Ball ball;
  if (!circumBall(B, A, Q, ball)) return false;
  const P3 n = unitNormal(B, A, Q);
  if (isZero(n)) return false;
  const double reach = kUnderReach * std::sqrt(ball.radius2);
  const double gapNew = kSheetGap * spacing_, gapFront = kUnderFrontGap * spacing_ * frontNorm;
  // A point of the mesh inside the cylinder over the triangle's circumcircle, in front of it by
  // kSheetGap spacings up to kUnderReach circumradii, and in front of the front triangle too,
  // whose (last) triangle faces the same way: the triangle lies under a sheet of the mesh, in the
  // material, and would grow the other sheet inside out. Two surfaces facing each other across
  // the air face opposite ways; the point's own sheet, seen past a tilted triangle, lies about the
  // front triangle's plane; the points of a stray triangle have fewer than kUnderSheetEdges edges.
  // (The ball around that section of the cylinder; a slightly larger one, (1 + 1e-9): the
  // predicates decide membership.)
  if (!(reach >= gapNew)) return false;
  const double half = 0.5 * (reach - gapNew);
  return anyInBall(ball.centre + n * (0.5 * (gapNew + reach)), std::sqrt(ball.radius2 + half * half) * (1 + 1e-9),
                   [&](std::uint32_t i, double) {
    if (i == a || i == b || i == p || edgeCount_[i] < kUnderSheetEdges) return false;
    const P3 d = pts_[i] - ball.centre;
    const double h = d * n;
    if (h < gapNew || h > reach || !strictlyInside(d.SquaredNorm() - h * h, ball.radius2)) return false;
    return (pts_[i] - A) * frontNormal >= gapFront && facesTheSameWay(i, n);
  });
}

bool Mesher::underASheetAfterCrossing(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& frontNormal,
                                      double frontNorm) const {
  const P3 &A = pts_[a], &B = pts_[b], &Q = pts_[p];
  Ball ball;
  if (!circumBall(B, A, Q, ball)) return false;
  const P3 n = unitNormal(B, A, Q); // the new triangle (b, a, p), outwards as its component
  if (isZero(n)) return false;
  const double margin = kChildMargin * spacing_, gap = kChildGap * spacing_;
  const double reach = std::min(kUnderReach * std::sqrt(ball.radius2), kChildReach * spacing_);
  if (!(reach >= gap)) return false;
  const double wide2 = kChildWide * kChildWide * spacing_ * spacing_;
  const double narrow2 = std::min(ball.radius2, kChildNarrow * kChildNarrow * spacing_ * spacing_);
  const P3 centroid = (A + B + Q) / 3.0;
  // Called for most accepted candidates near the crossings of a noisy scan, so in two small
  // queries rather than one over the whole wide cylinder: first the nearest qualifying point in
  // the narrow cylinder from gap to reach (the ball around that section), then any point below it
  // in the wide one (the ball around that section, stopping at the first). (A slightly larger
  // ball, (1 + 1e-9): the predicates decide membership.)
  double lowest = std::numeric_limits<double>::infinity();
  const double half = 0.5 * (reach - gap);
  anyInBall(centroid + n * (0.5 * (gap + reach)), std::sqrt(half * half + narrow2) * (1 + 1e-9),
                  [&](std::uint32_t i, double) {
                    if (i == a || i == b || i == p || edgeCount_[i] < kUnderSheetEdges) return false;
                    const P3 d = pts_[i] - centroid;
                    const double h = d * n;
                    if (h < gap || h > reach || h >= lowest || !strictlyInside(d.SquaredNorm() - h * h, narrow2))
                      return false;
                    if ((pts_[i] - A) * frontNormal >= kUnderFrontGap * spacing_ * frontNorm && facesTheSameWay(i, n))
                      lowest = h;
                    return false;
                  });
  if (!(lowest <= reach)) return false;
  if (!onASurface(p)) return false; // as for growsUnderASheet
  // No point nearer in front, from margin up to lowest - margin, within the wide cylinder: an
  // empty layer, not the triangle's own (noisy) sheet.
  const double top = lowest - margin, mid = 0.5 * (margin + top), span = 0.5 * (top - margin);
  if (!(top > margin)) return true;
  return !anyInBall(centroid + n * mid, std::sqrt(span * span + wide2) * (1 + 1e-9), [&](std::uint32_t i, double) {
    if (i == a || i == b || i == p) return false;
    const P3 d = pts_[i] - centroid;
    const double h = d * n;
    return h > margin && h < top && strictlyInside(d.SquaredNorm() - h * h, wide2);
  });
}

bool Mesher::foldsAcrossAGap(std::uint32_t a, std::uint32_t b, std::uint32_t p, const P3& dir, const P3& frontNormal,
                             double frontNorm) const {
  const P3 &A = pts_[a], &B = pts_[b], &Q = pts_[p];
  // Behind the front triangle, kFoldGap spacings or more: into the material.
  if (!((Q - A) * frontNormal <= -kFoldGap * spacing_ * frontNorm)) return false;
  // On a sheet parallel to the front's: kGapSheetPoints other points within kGapSheetReach spacings
  // of p lie within half a spacing of the plane through p parallel to the front triangle's (not an
  // outlier, nor a point of noise off its own sheet).
  const P3 unit = frontNormal / frontNorm;
  int sheet = 0;
  anyInBall(Q, kGapSheetReach * spacing_, [&](std::uint32_t i, double) {
    sheet += i != p && std::abs((pts_[i] - Q) * unit) <= 0.5 * spacing_;
    return sheet >= kGapSheetPoints;
  });
  if (sheet < kGapSheetPoints) return false;
  // The front's own sheet goes on beyond p: a point farther ahead than p within 10 degrees of the
  // front's plane (seen from the edge), in the ball about the edge's midpoint through twice p's
  // distance. (At a rim nothing lies ahead in the front's plane: the rim is the surface.)
  const P3 mid = (A + B) * 0.5;
  const double ahead = (Q - mid) * dir;
  return anyInBall(mid, 2.0 * (Q - mid).Norm(), [&](std::uint32_t i, double) {
    const P3& X = pts_[i];
    if ((X - mid) * dir <= ahead) return false;
    const P3 n = (A - B) ^ (X - B);
    const double len = n.Norm();
    return len > 0 && (frontNormal * n) > kFlatAheadCos * frontNorm * len;
  });
}

void Mesher::addTriangle(std::uint32_t u, std::uint32_t v, std::uint32_t w) {
  const std::uint32_t t[3] = {u, v, w};
  bool wasUsed[3];
  for (int k = 0; k < 3; ++k) {
    wasUsed[k] = !isolated(t[k]);
    usedPoints_ += !wasUsed[k];
  }
  const unsigned fresh = pem_.addTriangle(u, v, w);
  for (int k = 0; k < 3; ++k) faceAt_[t[k]] = static_cast<std::uint32_t>(tri_.size());
  tri_.push_back(Triangle{u, v, w});
  for (int k = 0; k < 3; ++k) {
    const std::uint32_t x = t[k], y = t[(k + 1) % 3];
    if ((fresh & (1u << k)) != 0) {
      const float len = float((pts_[x] - pts_[y]).Norm());
      edgeLengthSum_[x] += len;
      edgeLengthSum_[y] += len;
      // One entry per neighbour in the point-edge map (no triangle is removed while growing), so
      // these are its entry counts: at most its capacity.
      ++edgeCount_[x];
      ++edgeCount_[y];
      nearFullPoint_ |= std::max(edgeCount_[x], edgeCount_[y]) + 2u > pem_.capacity();
      ++freeEdges_[x];
      ++freeEdges_[y];
    } else {
      --freeEdges_[x]; // the edge now has its second triangle
      --freeEdges_[y];
    }
  }
  // A used vertex whose two edges in the new triangle are both new got a second fan: it may end
  // non-manifold unless later triangles join the fans (sec. 4.2 examines it).
  for (int k = 0; k < 3; ++k)
    if (wasUsed[k] && (fresh & (1u << k)) != 0 && (fresh & (1u << ((k + 2) % 3))) != 0)
      joinedAtVertex_.push_back(t[k]);
  // Every new edge is a free edge of the front, queued for its candidate search (sec. 4.1; see
  // grow for when that search is made).
  for (int k = 0; k < 3; ++k)
    if ((fresh & (1u << k)) != 0) queue_.push(0, FrontEdge{t[k], t[(k + 1) % 3], t[(k + 2) % 3], FrontEdge::kDeferred});
}

bool Mesher::choose(FrontEdge& e, int& level) {
  ++searches_;
  roomRefused_ = false;
  const Candidate cand = findCandidate(e.a, e.b, e.c);
  // No candidate up to the maximum radius: a boundary edge (sec. 3.2 step 4.2); it stays free.
  if (!cand.valid()) {
    edgesLeftAtFullPoints_ += roomRefused_;
    return false;
  }
  level = cand.priority(params_.flatnessLevels) - 1;
  e.p = static_cast<std::uint32_t>(cand.point) | (cand.closesLoop ? std::uint32_t{FrontEdge::kLoop} : 0u);
  return true;
}

void Mesher::queueEdge(std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  FrontEdge e{a, b, c, 0};
  int level;
  if (choose(e, level)) queue_.push(level, e);
}

void Mesher::grow(Progress* progress) {
  size_t tick = 0;
  while (!queue_.empty()) {
    if (popBudget_ == 0) { // (a regrowth's bound on its work)
      queue_.clear();
      budgetExhausted_ = true;
      break;
    }
    --popBudget_;
    FrontEdge e = queue_.pop();
    // Closed from the other side since it was queued: no longer a free edge.
    if (pem_.used(e.b, e.a)) continue;
    if (e.p == FrontEdge::kDeferred) {
      // A new edge waits at the most urgent level for its candidate search, which is made when
      // the queue reaches it. The order is the paper's (sec. 4.1): an edge whose candidate has the
      // most urgent priority is taken at the place it was queued, the others move to their
      // level. But a third of the new edges (on a clean surface, one of the two edges of each
      // ear) are closed from the other side while they wait, and are never searched.
      int level;
      if (!choose(e, level)) continue;
      if (level > 0) {
        queue_.push(level, e);
        continue;
      }
    }
    const bool loop = (e.p & FrontEdge::kLoop) != 0;
    e.p &= ~FrontEdge::kLoop;
    if (!topologyAllows(e.a, e.b, e.c, e.p)) {
      // The mesh changed around the edge since its candidate was chosen: choose again among the
      // points that pass the tests now, at the priority that gives (or make it a boundary edge).
      queueEdge(e.a, e.b, e.c);
      continue;
    }
    // The triangle closes a loop of free edges (findCandidate's closesLoop). An unused point
    // inside it would be skipped for good: the edge grows to it by the ordinary search instead
    // (sec. 3.2), and the loop closes only if that search finds nothing, so it is never left
    // open. Checked here, once per loop, rather than for each of the loop's edges when queued.
    if (loop && unusedPointInside(e.b, e.a, e.p)) {
      const Candidate grown = findCandidate(e.a, e.b, e.c, /*ears=*/false);
      if (grown.valid() && grown.point != e.p && !grown.closesLoop) {
        queue_.push(grown.priority(params_.flatnessLevels) - 1,
                    FrontEdge{e.a, e.b, e.c, static_cast<std::uint32_t>(grown.point)});
        continue;
      }
    }
    if (loop) {
      loopFaces_.push_back(Triangle{e.b, e.a, e.p});
      // An ear folded back over its front triangle (by more than 90 degrees) can lie across the
      // faces at its points even where the surface closes: removeSelfIntersections then looks.
      const P3 &A = pts_[e.a], &B = pts_[e.b];
      foldedEars_ += ((B - A) ^ (pts_[e.c] - A)) * ((A - B) ^ (pts_[e.p] - B)) < 0;
    }
    addTriangle(e.b, e.a, e.p);
    if (progress != nullptr && (++tick & 1023) == 0)
      progress->update(double(usedPoints_) / double(grid_.size()));
  }
}

bool Mesher::triangleAt(std::uint32_t v, std::array<std::uint32_t, 3>& tri) const {
  // The last triangle added at v (none is removed while growing). The point-edge map alone cannot
  // tell which triangles there are: around an interior vertex v, the used half-edges v→w, w→x and
  // x→v can belong to three different triangles, and (v, w, x) is then the reverse of a triangle,
  // so that a seed copying its orientation took the wrong one.
  const std::uint32_t f = faceAt_.empty() ? kNoFace : faceAt_[v];
  if (f == kNoFace) return false;
  tri = {tri_[f][0], tri_[f][1], tri_[f][2]};
  return true;
}

void Mesher::orientSeed(std::array<std::uint32_t, 3>& tri) const {
  const P3 &A = pts_[tri[0]], &B = pts_[tri[1]], &C = pts_[tri[2]];
  const P3 n = (B - A) ^ (C - A);
  const P3 centroid = (A + B + C) / 3.0;
  // Next to an existing part of the same sheet (a seed inside a hole), agree with its
  // orientation so that the two fronts can join (sec. 3.2: edges are shared only with consistent
  // orientation). A triangle of another sheet (the far side of a thin part) must not be copied:
  // its orientation is the opposite one. The reference is the nearest triangle that lies in the
  // seed's plane as seen from both: the normals within 60° of parallel (either sign), and the
  // offset between the two triangles within 30° of both planes.
  double best = std::numeric_limits<double>::infinity();
  std::array<std::uint32_t, 3> ref{};
  bool haveRef = false;
  const double nNorm = n.Norm();
  auto sameSheet = [&](const std::array<std::uint32_t, 3>& t) {
    const P3 &X = pts_[t[0]], &Y = pts_[t[1]], &Z = pts_[t[2]];
    const P3 m = (Y - X) ^ (Z - X);
    const double mNorm = m.Norm();
    if (!(mNorm > 0) || !(nNorm > 0)) return false;
    if (std::abs(m * n) < 0.5 * mNorm * nNorm) return false;
    const P3 offset = centroid - (X + Y + Z) / 3.0;
    const double len = offset.Norm();
    return std::abs(offset * m) <= 0.5 * len * mNorm && std::abs(offset * n) <= 0.5 * len * nNorm;
  };
  for (size_t k = 0; k < near_.size; ++k) {
    const std::uint32_t id = near_.id[k];
    const double d2 = (pts_[id] - centroid).SquaredNorm();
    if (d2 >= best || isolated(id)) continue;
    std::array<std::uint32_t, 3> t;
    if (triangleAt(id, t) && sameSheet(t)) {
      best = d2;
      ref = t;
      haveRef = true;
    }
  }
  double side;
  if (haveRef)
    side = n * ((pts_[ref[1]] - pts_[ref[0]]) ^ (pts_[ref[2]] - pts_[ref[0]]));
  else
    side = n * (centroid - grid_.box().Center()); // a new component: outwards from the cloud's centre
  if (side < 0) std::swap(tri[1], tri[2]);
}

bool Mesher::findSeedTriangle(std::uint32_t p, std::array<std::uint32_t, 3>& tri) {
  ++seedAttempts_;
  if (!isolated(p)) return false;
  double d2 = 0;
  const std::int64_t nearest = grid_.nearest(pts_[p], p, seedMaxEdge_, &d2);
  if (nearest < 0) return false;
  const auto q = static_cast<std::uint32_t>(nearest);
  if (!isolated(q)) return false;
  const double edge = std::sqrt(d2);
  if (!(edge > 0)) return false;
  const P3 &P = pts_[p], &Q = pts_[q];
  const P3 mid = (P + Q) * 0.5;
  double radius = params_.seedSearchFactor * edge;
  // Scan-line sampling (a LiDAR or structured-light scan: points dense along lines that lie
  // several spacings apart) puts only p's own line within k·|pq|: every third point is then near
  // the line pq and every triangle a sliver. The sphere is searched once more, kSeedWiden times as
  // wide (not in the paper; on a surface sampled alike in all directions the first sphere always
  // holds points off the line).
  for (int pass = 0; pass < 2; ++pass) {
    gather(mid, radius);
    scored_.clear();
    bool offLine = false;
    size_t inSphere = 0;
    for (size_t k = 0; k < near_.size; ++k) {
      const std::uint32_t id = near_.id[k];
      if (id == p || id == q || !isolated(id) || (pts_[id] - mid).SquaredNorm() > radius * radius) continue;
      ++inSphere;
      offLine = offLine || ((pts_[id] - P) ^ (Q - P)).SquaredNorm() > kSeedLineBand * kSeedLineBand * d2 * d2;
      Ball ball;
      if (!circumBall(P, Q, pts_[id], ball)) continue;
      scored_.push_back(Scored{0, ball.radius2, id, 1});
    }
    if (offLine || inSphere < kSeedLinePoints) break;
    radius *= kSeedWiden;
  }
  std::sort(scored_.begin(), scored_.end(), [](const Scored& x, const Scored& y) {
    return x.radius2 != y.radius2 ? x.radius2 < y.radius2 : x.id < y.id;
  });
  const size_t tries = std::min(scored_.size(), kMaxSeedTriangles);
  for (size_t k = 0; k < tries; ++k) {
    const Scored s = scored_[k];
    // (By increasing circumradius: the rest are slivers too.)
    if (s.radius2 > kSeedMaxCircumradius * kSeedMaxCircumradius * d2) break;
    Ball ball;
    if (!circumBall(P, Q, pts_[s.id], ball)) continue;
    if (!emptyBall(ball, radius, mid, p, q, s.id)) continue;
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
  const size_t n = grid_.size();
  if (n < 3) return;
  // Seed points in a seeded pseudo-random order (sec. 3.1 step 3.1): start + i·stride mod n with
  // the stride coprime to n visits every point once, without storing a permutation. Every unused
  // point is tried once, after the fronts before it died: a failed attempt cannot succeed later
  // (its G2S and cylinder tests do not change and points only ever become used), so one sweep
  // leaves no valid seed behind.
  Random rng(params_.randomSeed);
  const std::uint64_t start = rng.next() % n;
  std::uint64_t stride = 1 + rng.next() % (n - 1);
  while (gcd(stride, n) != 1) stride = stride % (n - 1) + 1;
  std::array<std::uint32_t, 3> tri;
  for (std::uint64_t i = 0; i < n; ++i) {
    const auto p = static_cast<std::uint32_t>((start + i * stride) % n);
    if (progress != nullptr && (i & 1023) == 0)
      progress->update(std::max(double(usedPoints_), double(i)) / double(n));
    if (!isolated(p)) continue;
    if (!findSeedTriangle(p, tri)) continue;
    addSeed(tri);
    grow(progress);
  }
  // Thin parts (kSheetGap): their rims stay open in loops of a few edges (g2s_thin.cpp).
  if (__builtin_expect(foldsRefused_ + otherSheetBalls_ > 0, 0)) closeRimLoops();
  grownTriangles_ = tri_.size();
}

} // namespace g2s
} // namespace growth
