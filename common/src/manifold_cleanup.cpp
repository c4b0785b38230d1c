#include <growth/huge_pages.h>
#include <growth/manifold_cleanup.h>

#include <algorithm>
#include <utility>

namespace growth {

namespace {

// Vertex → incident triangles (compressed rows), built once; dead triangles are skipped on use.
struct Incidence {
  HugeVector<std::uint32_t> start; // vertexCount + 1
  HugeVector<std::uint32_t> face;

  Incidence(const std::vector<Triangle>& faces, size_t vertexCount, const std::vector<char>& alive) {
    assignHuge(start, vertexCount + 1, 0u);
    for (size_t f = 0; f < faces.size(); ++f)
      if (alive[f])
        for (std::uint32_t v : faces[f]) ++start[v + 1];
    for (size_t v = 0; v < vertexCount; ++v) start[v + 1] += start[v];
    assignHuge(face, size_t(start[vertexCount]), 0u);
    HugeVector<std::uint32_t> fill(start.begin(), start.end() - 1);
    for (size_t f = 0; f < faces.size(); ++f)
      if (alive[f])
        for (std::uint32_t v : faces[f]) face[fill[v]++] = static_cast<std::uint32_t>(f);
  }
};

// The fans of one vertex: a union–find over its alive triangles, joined across every edge at the
// vertex that has exactly two of them. Scratch arrays are reused from vertex to vertex.
class FanFinder {
public:
  explicit FanFinder(const std::vector<Triangle>& faces) : faces_(faces) {}

  // Analyses vertex v; returns its number of fans (0 for a vertex of no alive triangle).
  int analyse(std::uint32_t v, const Incidence& inc, const std::vector<char>& alive) {
    local_.clear();
    for (std::uint32_t k = inc.start[v]; k < inc.start[v + 1]; ++k)
      if (alive[inc.face[k]]) local_.push_back(inc.face[k]);
    const size_t d = local_.size();
    if (d == 0) return 0;
    if (singleFan(v)) return 1; // the usual answer, found without sorting
    return countFans(v);
  }

  // After analyse() found several fans: the local indices of the triangles outside the kept fan.
  void extraFans(std::vector<std::uint32_t>& removeFaces);

private:
  // A quick proof that v's triangles local_ form one fan, for the common case of at most eight
  // consistently oriented triangles (false: not proved, countFans decides). Triangle (v, w, x)
  // links w to x; when the w's are distinct and the x's are distinct (every half-edge at v used
  // once), the links form disjoint paths and cycles, and two triangles share a two-triangle edge
  // at v exactly when one's x is the other's w, so the fans are the components of the links: one
  // fan is one path or one cycle through all of them.
  bool singleFan(std::uint32_t v) const {
    const size_t d = local_.size();
    if (d > 8) return false;
    std::uint32_t w[8], x[8];
    for (size_t i = 0; i < d; ++i) {
      const Triangle& t = faces_[local_[i]];
      const int at = t[0] == v ? 0 : (t[1] == v ? 1 : 2);
      w[i] = t[(at + 1) % 3];
      x[i] = t[(at + 2) % 3];
    }
    int next[8];
    unsigned hasPrevious = 0;
    bool distinct = true;
    for (size_t i = 0; i < d; ++i) {
      int j = -1;
      for (size_t k = 0; k < d; ++k) {
        j = w[k] == x[i] ? int(k) : j;
        distinct &= k <= i || (w[k] != w[i] && x[k] != x[i]);
      }
      next[i] = j;
      hasPrevious |= (j >= 0 ? 1u : 0u) << (j >= 0 ? j : 0);
    }
    if (!distinct) return false;
    // Paths start where no link arrives; a single path or, with none, a single cycle.
    const unsigned all = (1u << d) - 1u, starts = all & ~hasPrevious;
    if (starts != 0 && (starts & (starts - 1)) != 0) return false; // two paths or more
    int cur = starts != 0 ? __builtin_ctz(starts) : 0;
    size_t length = 1;
    while (next[cur] >= 0 && length <= d) {
      cur = next[cur];
      if (starts == 0 && cur == 0) break; // back at the cycle's start
      ++length;
    }
    return length == d && (starts != 0 ? next[cur] < 0 : next[cur] >= 0);
  }

  // The fans of v's triangles local_, by the union-find below (any orientation, any valence).
  int countFans(std::uint32_t v) {
    const size_t d = local_.size();
    keyed_.clear();
    for (size_t i = 0; i < d; ++i) {
      const Triangle& t = faces_[local_[i]];
      for (std::uint32_t w : t)
        if (w != v) keyed_.emplace_back(w, static_cast<std::uint32_t>(i));
    }
    std::sort(keyed_.begin(), keyed_.end());
    parent_.resize(d);
    open_.assign(d, 0);
    for (size_t i = 0; i < d; ++i) parent_[i] = static_cast<std::uint32_t>(i);
    int fans = static_cast<int>(d);
    for (size_t g = 0; g < keyed_.size();) {
      size_t h = g + 1;
      while (h < keyed_.size() && keyed_[h].first == keyed_[g].first) ++h;
      if (h - g == 2) {
        const std::uint32_t ra = root(keyed_[g].second), rb = root(keyed_[g + 1].second);
        if (ra != rb) {
          parent_[std::max(ra, rb)] = std::min(ra, rb);
          --fans;
        }
      } else {
        // A boundary edge (one triangle) or a non-manifold edge (three or more): the triangles
        // on it are not joined there, and their fans are open.
        for (size_t k = g; k < h; ++k) open_[keyed_[k].second] = 1;
      }
      g = h;
    }
    return fans;
  }

  std::uint32_t root(std::uint32_t i) {
    while (parent_[i] != i) {
      parent_[i] = parent_[parent_[i]];
      i = parent_[i];
    }
    return i;
  }

  const std::vector<Triangle>& faces_;
  std::vector<std::uint32_t> local_, parent_, size_, lowest_;
  std::vector<std::pair<std::uint32_t, std::uint32_t>> keyed_;
  std::vector<char> open_, fanOpen_;
};

void FanFinder::extraFans(std::vector<std::uint32_t>& removeFaces) {
  const size_t d = local_.size();
  // Per root: triangle count, open flag, lowest triangle index.
  size_.assign(d, 0);
  fanOpen_.assign(d, 0);
  lowest_.assign(d, ~0u);
  for (size_t i = 0; i < d; ++i) {
    const std::uint32_t r = root(static_cast<std::uint32_t>(i));
    ++size_[r];
    fanOpen_[r] |= open_[i];
    lowest_[r] = std::min(lowest_[r], local_[i]);
  }
  std::uint32_t keep = ~0u;
  for (size_t r = 0; r < d; ++r) {
    if (size_[r] == 0) continue;
    if (keep == ~0u) {
      keep = static_cast<std::uint32_t>(r);
      continue;
    }
    const bool closedR = !fanOpen_[r], closedK = !fanOpen_[keep];
    if (closedR != closedK) {
      if (closedR) keep = static_cast<std::uint32_t>(r);
    } else if (size_[r] != size_[keep]) {
      if (size_[r] > size_[keep]) keep = static_cast<std::uint32_t>(r);
    } else if (lowest_[r] < lowest_[keep]) {
      keep = static_cast<std::uint32_t>(r);
    }
  }
  removeFaces.clear();
  for (size_t i = 0; i < d; ++i)
    if (root(static_cast<std::uint32_t>(i)) != keep) removeFaces.push_back(local_[i]);
}

bool degenerate(const Triangle& t) { return t[0] == t[1] || t[1] == t[2] || t[2] == t[0]; }

} // namespace

ManifoldCleanupStat removeNonManifoldVertices(const std::vector<Triangle>& faces, size_t vertexCount,
                                              std::vector<char>& alive, const std::vector<std::uint32_t>* suspects) {
  ManifoldCleanupStat st;
  alive.resize(faces.size(), 1);
  for (size_t f = 0; f < faces.size(); ++f)
    if (alive[f] && degenerate(faces[f])) {
      alive[f] = 0;
      ++st.facesRemoved;
    }
  FanFinder fans(faces);

  // Work list: every vertex (or suspect) once, then every vertex of a removed triangle again.
  std::vector<std::uint32_t> work;
  HugeVector<char> queued(vertexCount, 0), counted(vertexCount, 0);
  if (suspects != nullptr) {
    for (std::uint32_t v : *suspects)
      if (v < vertexCount && !queued[v]) {
        queued[v] = 1;
        work.push_back(v);
      }
  } else {
    work.resize(vertexCount);
    for (size_t v = 0; v < vertexCount; ++v) work[v] = static_cast<std::uint32_t>(v);
    std::fill(queued.begin(), queued.end(), 1);
  }
  // (Rows for all triangles at once: rows for the suspects only, rebuilt when the work reaches a
  // vertex of a removed triangle, cost more on merged scans, which rebuild them several times.)
  const Incidence inc(faces, vertexCount, alive);
  std::vector<std::uint32_t> removeFaces;
  for (size_t head = 0; head < work.size(); ++head) {
    const std::uint32_t v = work[head];
    queued[v] = 0;
    if (fans.analyse(v, inc, alive) <= 1) continue;
    if (!counted[v]) {
      counted[v] = 1;
      ++st.nonManifoldVertices;
    }
    fans.extraFans(removeFaces);
    for (std::uint32_t f : removeFaces) {
      alive[f] = 0;
      ++st.facesRemoved;
      for (std::uint32_t u : faces[f])
        if (u != v && !queued[u]) {
          queued[u] = 1;
          work.push_back(u);
        }
    }
  }
  return st;
}

size_t countNonManifoldVertices(const std::vector<Triangle>& faces, size_t vertexCount,
                                const std::vector<char>& alive) {
  std::vector<char> live(alive);
  live.resize(faces.size(), 1);
  for (size_t f = 0; f < faces.size(); ++f)
    if (live[f] && degenerate(faces[f])) live[f] = 0;
  const Incidence inc(faces, vertexCount, live);
  FanFinder fans(faces);
  size_t n = 0;
  for (size_t v = 0; v < vertexCount; ++v)
    if (fans.analyse(static_cast<std::uint32_t>(v), inc, live) > 1) ++n;
  return n;
}

size_t dropSmallComponents(const std::vector<Triangle>& faces, size_t vertexCount, std::vector<char>& alive,
                           size_t minFaces, size_t& facesDropped) {
  facesDropped = 0;
  if (minFaces <= 1 || faces.empty()) return 0;
  std::vector<std::uint32_t> parent(vertexCount);
  for (std::uint32_t v = 0; v < vertexCount; ++v) parent[v] = v;
  auto find = [&](std::uint32_t v) {
    while (parent[v] != v) v = parent[v] = parent[parent[v]];
    return v;
  };
  auto unite = [&](std::uint32_t a, std::uint32_t b) {
    a = find(a), b = find(b);
    if (a != b) parent[std::max(a, b)] = std::min(a, b);
  };
  size_t firstAlive = faces.size();
  for (size_t f = 0; f < faces.size(); ++f)
    if (alive[f]) {
      unite(faces[f][0], faces[f][1]), unite(faces[f][1], faces[f][2]);
      firstAlive = std::min(firstAlive, f);
    }
  if (firstAlive == faces.size()) return 0;
  std::vector<std::uint32_t> count(vertexCount, 0);
  std::uint32_t largest = find(faces[firstAlive][0]);
  for (size_t f = firstAlive; f < faces.size(); ++f) {
    if (!alive[f]) continue;
    const std::uint32_t r = find(faces[f][0]);
    if (++count[r] > count[largest]) largest = r;
  }
  size_t dropped = 0;
  for (std::uint32_t v = 0; v < vertexCount; ++v)
    dropped += parent[v] == v && count[v] > 0 && count[v] < minFaces && v != largest ? 1 : 0;
  if (dropped == 0) return 0;
  for (size_t f = firstAlive; f < faces.size(); ++f) {
    if (!alive[f]) continue;
    const std::uint32_t r = find(faces[f][0]);
    if (count[r] < minFaces && r != largest) {
      alive[f] = 0;
      ++facesDropped;
    }
  }
  return dropped;
}

} // namespace growth
