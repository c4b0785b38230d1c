#include "borders.h"
#include "splats.h"

#include <cmath>

namespace growth {

void BorderGraph::clear() {
  pos_.clear();
  nrm_.clear();
  rot_.clear();
  edges_ = 0;
}

void BorderGraph::releaseAdjacency() {
  std::vector<Rotation>().swap(rot_);
  std::vector<Vec3d>().swap(nrm_);
  edges_ = 0;
}

void BorderGraph::reserve(size_t n) {
  pos_.reserve(n);
  nrm_.reserve(n);
  rot_.reserve(n);
}

std::uint32_t BorderGraph::addVertex(const Vec3d& position, const Vec3d& normal) {
  pos_.push_back(position);
  nrm_.push_back(normal);
  rot_.emplace_back();
  return static_cast<std::uint32_t>(pos_.size() - 1);
}

namespace {
// A monotonic function of the polar angle of (x, y), in [0, 4) (a full turn is 4): the same
// cyclic order as atan2, which only orders are taken from, without the trigonometry.
inline double pseudoAngle(double x, double y) {
  if (x == 0 && y == 0) return 0;
  if (y >= 0) return x >= 0 ? y / (x + y) : 1 - x / (y - x);
  return x < 0 ? 2 - y / (-x - y) : 3 + x / (x - y);
}
constexpr double kTurn = 4;
// Counter-clockwise turn from angle a to angle b, in [0, kTurn).
inline double ccw(double a, double b) {
  double t = b - a;
  while (t < 0) t += kTurn;
  while (t >= kTurn) t -= kTurn;
  return t;
}
} // namespace

double BorderGraph::angleAt(std::uint32_t v, const Vec3d& x) const {
  // The tangent frame is recomputed (the same bits every time): keeping it cost 48 bytes a vertex.
  Vec3d e1, e2;
  tangentFrame(nrm_[v], e1, e2);
  const Vec3d t = x - pos_[v];
  return pseudoAngle(t * e1, t * e2);
}

int BorderGraph::gapOf(std::uint32_t v, const Vec3d& target) const {
  const Rotation& r = rot_[v];
  if (r.degree == 0) return -1;
  if (r.degree == 1) return 0;
  // The neighbours' angles are recomputed (the same bits every time) rather than kept: 96 bytes a
  // vertex, a third of the growth's memory, for a few percent of its time.
  Vec3d e1, e2;
  tangentFrame(nrm_[v], e1, e2);
  const Vec3d& o = pos_[v];
  auto angle = [&](const Vec3d& x) {
    const Vec3d t = x - o;
    return pseudoAngle(t * e1, t * e2);
  };
  const double th = angle(target);
  double a[kMaxDegree];
  for (int k = 0; k < r.degree; ++k) a[k] = angle(pos_[r.nb[k]]);
  // The gap k runs counter-clockwise from neighbour k to neighbour k+1.
  int best = 0;
  double bestSlack = -kTurn - 1;
  for (int k = 0; k < r.degree; ++k) {
    const double span = ccw(a[k], a[(k + 1) % r.degree]);
    const double into = ccw(a[k], th);
    if (into < span) return k;
    // Rounding may leave a direction in no gap at all (neighbours at almost the same angle):
    // fall back to the gap it misses by the least.
    const double slack = span - into;
    if (slack > bestSlack) bestSlack = slack, best = k;
  }
  return best;
}

bool BorderGraph::gapContains(std::uint32_t v, int gap, const Vec3d& target, const Vec3d& n) const {
  const Rotation& r = rot_[v];
  if (r.degree < 2) return true;
  Vec3d e1, e2;
  tangentFrame(n, e1, e2);
  auto angle = [&](const Vec3d& x) {
    const Vec3d t = x - pos_[v];
    return pseudoAngle(t * e1, t * e2);
  };
  const double a0 = angle(pos_[r.nb[gap]]), a1 = angle(pos_[r.nb[(gap + 1) % r.degree]]);
  return ccw(a0, angle(target)) < ccw(a0, a1);
}

HalfEdge BorderGraph::next(HalfEdge h) const {
  const std::uint32_t u = h.v, v = rot_[u].nb[h.slot];
  const int j = slotOf(v, u);
  const int deg = rot_[v].degree;
  return HalfEdge{v, (j + deg - 1) % deg};
}

HalfEdge BorderGraph::prev(HalfEdge h) const {
  // prev(v→w) = u→v with u the neighbour of v just counter-clockwise of w.
  const std::uint32_t v = h.v;
  const int deg = rot_[v].degree;
  const std::uint32_t u = rot_[v].nb[(h.slot + 1) % deg];
  return HalfEdge{u, slotOf(u, v)};
}

int BorderGraph::borderDistance(std::uint32_t a, int gapA, std::uint32_t b, int gapB, int w) const {
  const HalfEdge start{a, gapA}, goal{b, gapB};
  HalfEdge f = start, r = start;
  for (int step = 1; step <= w; ++step) {
    f = next(f);
    if (f == goal) return step;
    r = prev(r);
    if (r == goal) return step;
    if (f == start) return 0; // the whole (short) border seen: b is not on it
  }
  return 0;
}

void BorderGraph::insertAt(std::uint32_t v, int pos, std::uint32_t u) {
  Rotation& r = rot_[v];
  for (int k = r.degree; k > pos; --k) r.nb[k] = r.nb[k - 1];
  r.nb[pos] = u;
  ++r.degree;
}

bool BorderGraph::addEdge(std::uint32_t u, int gapU, std::uint32_t v, int gapV) {
  if (u == v || u >= rot_.size() || v >= rot_.size()) return false;
  if (rot_[u].degree >= kMaxDegree || rot_[v].degree >= kMaxDegree || hasEdge(u, v)) return false;
  if ((rot_[u].degree > 0 && (gapU < 0 || gapU >= rot_[u].degree)) ||
      (rot_[v].degree > 0 && (gapV < 0 || gapV >= rot_[v].degree)))
    return false;
  insertAt(u, rot_[u].degree == 0 ? 0 : gapU + 1, v);
  insertAt(v, rot_[v].degree == 0 ? 0 : gapV + 1, u);
  ++edges_;
  return true;
}

bool BorderGraph::connect(std::uint32_t c, std::uint32_t a, int gapA, std::uint32_t b, int gapB) {
  if (a == b || c == a || c == b || c >= rot_.size() || rot_[c].degree != 0) return false;
  if (a >= rot_.size() || b >= rot_.size() || rot_[a].degree >= kMaxDegree || rot_[b].degree >= kMaxDegree)
    return false;
  if (!addEdge(c, -1, a, gapA)) return false;
  // c has the single edge to a: its only gap is 0, and b goes after a in its rotation.
  if (!addEdge(c, 0, b, gapB)) {
    rot_[c].degree = 0;
    const int k = slotOf(a, c);
    for (int j = k; j + 1 < rot_[a].degree; ++j) rot_[a].nb[j] = rot_[a].nb[j + 1];
    --rot_[a].degree;
    --edges_;
    return false;
  }
  return true;
}

std::vector<std::vector<std::uint32_t>> BorderGraph::borders() const {
  std::vector<std::vector<std::uint32_t>> out;
  std::vector<std::uint16_t> seen(rot_.size(), 0);
  for (std::uint32_t v = 0; v < rot_.size(); ++v)
    for (int k = 0; k < rot_[v].degree; ++k) {
      if (seen[v] & (1u << k)) continue;
      std::vector<std::uint32_t> cycle;
      HalfEdge h{v, k};
      do {
        seen[h.v] = static_cast<std::uint16_t>(seen[h.v] | (1u << h.slot));
        cycle.push_back(h.v);
        h = next(h);
      } while (!(h == HalfEdge{v, k}));
      out.push_back(std::move(cycle));
    }
  return out;
}

size_t BorderGraph::loneVertices() const {
  size_t n = 0;
  for (const auto& r : rot_) n += r.degree == 0 ? 1 : 0;
  return n;
}

size_t BorderGraph::memoryBytes() const {
  // In use: the reserve beyond (BorderGraph::reserve) is address space that is never written.
  return pos_.size() * sizeof(Vec3d) + nrm_.size() * sizeof(Vec3d) + rot_.size() * sizeof(Rotation);
}

} // namespace growth
