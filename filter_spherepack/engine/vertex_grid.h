#pragma once
// Dynamic hash grid of the mesh vertices of the sphere packer, for the insertion checks of
// sec. 3.6 (no vertex closer than d to a candidate; existing edges near a candidate) and the
// neighbourhoods of sec. 4.4. Cells of a given side (the sphere packer uses 2d); only occupied
// cells are stored (KeyHash), each a linked list through one `next` index per vertex. Vertices are
// at least d apart, so a cell holds a bounded number of them and a query costs a constant. (The
// paper keeps the vertices in its boxes, sec. 4.4; a separate grid keeps the box lists compact.)
#include "box_grid.h"

#include <growth/vec3.h>

#include <cstdint>
#include <vector>

namespace growth {

class VertexGrid {
public:
  // Cells of side `cell`, anchored at `origin` (coordinates up to 2^20 cells away either side).
  void reset(const Vec3d& origin, double cell, size_t expectedVertices = 16) {
    index_ = BoxIndexer(origin, cell);
    // Cells hold several vertices each (about 6 on a surface with cells of √5·d): the table is
    // sized for a quarter as many cells as vertices, and grows when needed.
    hash_.reset(expectedVertices / 4);
    next_.clear();
    next_.reserve(expectedVertices);
  }
  double cellSize() const { return index_.side(); }

  // Adds vertex `id` (ids must be inserted as 0, 1, 2, ...) at p. False when p is outside the
  // indexable range (the vertex is then not found by queries).
  bool insert(std::uint32_t id, const Vec3d& p) {
    if (next_.size() <= id) next_.resize(size_t(id) + 1, -1);
    std::int64_t c[3];
    if (!cellOf(p, c)) return false;
    const KeyHash::Key k = BoxIndexer::pack(c[0], c[1], c[2]);
    const int head = hash_.find(k);
    next_[id] = head;
    if (head < 0) hash_.findOrInsert(k, int(id));
    else hash_.set(k, int(id));
    return true;
  }

  // Calls f(id, squaredDistance) for every vertex with |pos[id] − c| <= radius.
  template <class F>
  void forEachInBall(const Vec3d& c, double radius, const std::vector<Vec3d>& pos, F&& f) const {
    const double r2 = radius * radius;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = index_.coord(c[a] - radius, a) + kBias;
      hi[a] = index_.coord(c[a] + radius, a) + kBias;
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          if (!BoxIndexer::valid(x, y, z)) continue;
          if (squaredDistanceToBox(c, index_.corner(x - kBias, y - kBias, z - kBias), index_.side()) > r2) continue;
          for (int v = hash_.find(BoxIndexer::pack(x, y, z)); v >= 0; v = next_[size_t(v)]) {
            const double d2 = (pos[size_t(v)] - c).SquaredNorm();
            if (d2 <= r2) f(std::uint32_t(v), d2);
          }
        }
  }

  // True when some vertex other than skipA and skipB is strictly closer than `radius` to c.
  bool anyCloserThan(const Vec3d& c, double radius, const std::vector<Vec3d>& pos,
                     std::uint32_t skipA, std::uint32_t skipB) const {
    const double r2 = radius * radius;
    std::int64_t lo[3], hi[3];
    for (int a = 0; a < 3; ++a) {
      lo[a] = index_.coord(c[a] - radius, a) + kBias;
      hi[a] = index_.coord(c[a] + radius, a) + kBias;
    }
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y)
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
          if (!BoxIndexer::valid(x, y, z)) continue;
          if (squaredDistanceToBox(c, index_.corner(x - kBias, y - kBias, z - kBias), index_.side()) >= r2) continue;
          for (int v = hash_.find(BoxIndexer::pack(x, y, z)); v >= 0; v = next_[size_t(v)]) {
            if (std::uint32_t(v) == skipA || std::uint32_t(v) == skipB) continue;
            if ((pos[size_t(v)] - c).SquaredNorm() < r2) return true;
          }
        }
    return false;
  }

  size_t memoryBytes() const { return hash_.memoryBytes() + next_.size() * sizeof(int); } // (the reserve: address space)

private:
  static constexpr std::int64_t kBias = std::int64_t(1) << (BoxIndexer::kBits - 1);
  bool cellOf(const Vec3d& p, std::int64_t c[3]) const {
    for (int a = 0; a < 3; ++a) c[a] = index_.coord(p[a], a) + kBias;
    return BoxIndexer::valid(c[0], c[1], c[2]);
  }
  BoxIndexer index_;
  KeyHash hash_;
  std::vector<int> next_;
};

} // namespace growth
