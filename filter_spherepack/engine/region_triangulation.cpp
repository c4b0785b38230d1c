#include "region_triangulation.h"
#include "splats.h"

#include <algorithm>
#include <cmath>

namespace growth {

namespace {
constexpr double kPi = 3.14159265358979323846;

// 2D coordinates of x in the plane through v orthogonal to n.
struct Frame {
  Vec3d o, e1, e2;
  Frame(const Vec3d& origin, const Vec3d& n) : o(origin) { tangentFrame(n, e1, e2); }
  void project(const Vec3d& x, double& px, double& py) const {
    const Vec3d t = x - o;
    px = t * e1;
    py = t * e2;
  }
};

inline double orient2(double ax, double ay, double bx, double by, double cx, double cy) {
  return (bx - ax) * (cy - ay) - (by - ay) * (cx - ax);
}
} // namespace

double innerAngle(const Vec3d& u, const Vec3d& v, const Vec3d& w, const Vec3d& n) {
  const Frame f(v, n);
  double ux, uy, wx, wy;
  f.project(u, ux, uy);
  f.project(w, wx, wy);
  double t = std::atan2(uy, ux) - std::atan2(wy, wx); // counter-clockwise from w to u
  while (t < 0) t += 2 * kPi;
  while (t >= 2 * kPi) t -= 2 * kPi;
  return t;
}

bool nearlyCollinear(const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  static const double cosMax = std::cos(kMaxFaceAngleDeg * kPi / 180.0);
  const Vec3d p[3] = {a, b, c};
  for (int k = 0; k < 3; ++k) {
    const Vec3d e1 = p[(k + 1) % 3] - p[k], e2 = p[(k + 2) % 3] - p[k];
    const double l1 = e1.Norm(), l2 = e2.Norm();
    if (!(l1 > 0) || !(l2 > 0)) return true;
    if ((e1 * e2) / (l1 * l2) < cosMax) return true;
  }
  return false;
}

std::vector<std::vector<std::uint32_t>> splitAtRepeatedVertices(const std::vector<std::uint32_t>& border) {
  std::vector<std::vector<std::uint32_t>> loops;
  std::vector<std::uint32_t> stack;
  for (std::uint32_t v : border) {
    auto it = std::find(stack.begin(), stack.end(), v);
    if (it != stack.end()) {
      // v closes the loop that left it: stack[it .. end) in order.
      loops.emplace_back(it, stack.end());
      stack.erase(it + 1, stack.end());
    } else {
      stack.push_back(v);
    }
  }
  if (!stack.empty()) loops.push_back(std::move(stack));
  return loops;
}

namespace {
using Loop = std::vector<std::uint32_t>;

// The inner angle of the loop at its index i, in the tangent plane of the vertex.
double angleAt(const Loop& loop, size_t i, const std::vector<Vec3d>& pos, const std::vector<Vec3d>& nrm) {
  const size_t n = loop.size();
  return innerAngle(pos[loop[(i + n - 1) % n]], pos[loop[i]], pos[loop[(i + 1) % n]], nrm[loop[i]]);
}

// Spikes u→v→u enclose no area (a dangling edge, or what is left of a lobe of a region pinched
// at u once that lobe is filled): drop v and the second u, without a face.
void removeSpikes(Loop& loop) {
  bool removed = true;
  while (removed && loop.size() >= 3) {
    removed = false;
    const size_t n = loop.size();
    for (size_t i = 0; i < n; ++i) {
      if (loop[(i + n - 1) % n] != loop[(i + 1) % n]) continue;
      const size_t j = (i + 1) % n; // the second u
      loop.erase(loop.begin() + std::ptrdiff_t(std::max(i, j)));
      loop.erase(loop.begin() + std::ptrdiff_t(std::min(i, j)));
      removed = true;
      break;
    }
  }
}

// Is a vertex of the loop (other than u, v, w themselves, wherever they repeat) inside or on
// the ear (u, v, w) at index i, projected on v's plane?
bool earContainsVertex(const Loop& loop, size_t i, const std::vector<Vec3d>& pos,
                       const std::vector<Vec3d>& nrm) {
  const size_t n = loop.size();
  const std::uint32_t u = loop[(i + n - 1) % n], v = loop[i], w = loop[(i + 1) % n];
  const Frame f(pos[v], nrm[v]);
  double ux, uy, wx, wy;
  f.project(pos[u], ux, uy);
  f.project(pos[w], wx, wy);
  for (size_t k = 0; k < n; ++k) {
    const std::uint32_t x = loop[k];
    if (x == u || x == v || x == w) continue;
    double px, py;
    f.project(pos[x], px, py);
    // Counter-clockwise triangle (u, v = origin, w): inside or on it when all three >= 0.
    if (orient2(ux, uy, 0, 0, px, py) >= 0 && orient2(0, 0, wx, wy, px, py) >= 0 &&
        orient2(wx, wy, ux, uy, px, py) >= 0)
      return true;
  }
  return false;
}

// The ear to cut: smallest angle first (below π); the strict ear rules first (no loop vertex
// inside), then the relaxed ones. The new edge u–w must be new. loop.size() when there is none.
size_t pickEar(const Loop& loop, const std::vector<double>& angle, std::vector<size_t>& order, const EdgeSet& edges,
               const std::vector<Vec3d>& pos, const std::vector<Vec3d>& nrm) {
  const size_t n = loop.size();
  order.resize(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::sort(order.begin(), order.end(),
            [&](size_t a, size_t b) { return angle[a] != angle[b] ? angle[a] < angle[b] : a < b; });
  size_t pick = n;
  for (int strict = 1; strict >= 0 && pick == n; --strict)
    for (size_t i : order) {
      if (!(angle[i] < kPi)) break;
      const std::uint32_t u = loop[(i + n - 1) % n], w = loop[(i + 1) % n];
      if (u == w || edges.contains(u, w)) continue;
      if (strict && earContainsVertex(loop, i, pos, nrm)) continue;
      pick = i;
      break;
    }
  return pick;
}

// The ear at `pick` cut off into faces and edges, then the spikes it leaves removed and the
// angles updated (all of them after a spike, else the two at the new edge).
void cutEar(Loop& loop, std::vector<double>& angle, size_t pick, const std::vector<Vec3d>& pos,
            const std::vector<Vec3d>& nrm, EdgeSet& edges, std::vector<Triangle>& faces) {
  const size_t n = loop.size();
  const std::uint32_t u = loop[(pick + n - 1) % n], v = loop[pick], w = loop[(pick + 1) % n];
  faces.push_back(Triangle{u, v, w});
  edges.insert(u, w);
  loop.erase(loop.begin() + std::ptrdiff_t(pick));
  const size_t before = loop.size();
  removeSpikes(loop);
  if (loop.size() != before) {
    angle.resize(loop.size());
    for (size_t i = 0; i < loop.size(); ++i) angle[i] = angleAt(loop, i, pos, nrm);
  } else {
    angle.erase(angle.begin() + std::ptrdiff_t(pick));
    const size_t k = loop.size();
    const size_t iu = (pick + k - 1) % k, iw = pick % k;
    angle[iu] = angleAt(loop, iu, pos, nrm);
    angle[iw] = angleAt(loop, iw, pos, nrm);
  }
}
} // namespace

bool triangulateLoop(const std::vector<std::uint32_t>& loopIn, const std::vector<Vec3d>& pos,
                     const std::vector<Vec3d>& nrm, EdgeSet& edges, std::vector<Triangle>& faces) {
  Loop loop = loopIn;
  // The loop without its spikes, with its inner angles.
  removeSpikes(loop);
  std::vector<double> angle(loop.size());
  for (size_t i = 0; i < loop.size(); ++i) angle[i] = angleAt(loop, i, pos, nrm);
  // Ears cut, smallest angle first, down to the last triangle.
  std::vector<size_t> order;
  while (loop.size() > 3) {
    const size_t pick = pickEar(loop, angle, order, edges, pos, nrm);
    if (pick == loop.size()) return false;
    cutEar(loop, angle, pick, pos, nrm, edges, faces);
  }
  if (loop.size() == 3 && loop[0] != loop[1] && loop[1] != loop[2] && loop[0] != loop[2])
    faces.push_back(Triangle{loop[0], loop[1], loop[2]});
  return true;
}

RegionStats triangulateRegions(const std::vector<std::vector<std::uint32_t>>& borders,
                               const std::vector<Vec3d>& pos, const std::vector<Vec3d>& nrm,
                               int maxBorderLength, EdgeSet& edges, std::vector<Triangle>& faces) {
  RegionStats st;
  for (const auto& b : borders) {
    ++st.borders;
    st.longestBorder = std::max(st.longestBorder, b.size());
    st.borderEdges += b.size();
    if (b.size() > size_t(std::max(0, maxBorderLength))) {
      ++st.holes;
      ++st.longBorders;
      continue;
    }
    if (b.size() == 3 && b[0] != b[1] && b[1] != b[2] && b[0] != b[2]) {
      // A triangle, as triangulateLoop() would give it (about half the regions of a packing).
      faces.push_back(Triangle{b[0], b[1], b[2]});
      ++st.triangulated;
      continue;
    }
    bool ok = true;
    for (const auto& loop : splitAtRepeatedVertices(b))
      if (loop.size() >= 3 && !triangulateLoop(loop, pos, nrm, edges, faces)) ok = false;
    if (ok) {
      ++st.triangulated;
    } else {
      ++st.holes;
    }
  }
  return st;
}

} // namespace growth
