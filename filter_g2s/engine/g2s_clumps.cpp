// Robust G2S: dense clumps meshed as one point (Mesher::mergeClumps, see kClumpNeighbours).
// (In a file of its own: beside the growth it changes the compiler's inlining of the growth's
// queries, which then cost more than the clump search itself.)
#include "g2s_mesher.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace growth {
namespace g2s {

namespace {

// Step 1, a cheap filter, linear and local: every cell of the grid is divided into m^3 fine cells
// of side h = cell / m >= 2r (m <= 1024). A core point's ball of radius r (it and its
// kClumpNeighbours >= 8 neighbours, 9 points at least) spans at most two fine cells per axis,
// eight in all, so one of them holds two points or more ("crowded"). On a clean cloud few points
// have another within 2r·√3 (0.17 spacings), so few fine cells are crowded. (A point on a fine
// cell's border may be rounded into its neighbour: a clump can then go unnoticed, and is meshed
// as it is, never worse.) Gives the centres of the crowded fine cells.
void crowdedFineCells(const MortonGrid& grid, double m, double h, std::vector<P3>& crowded) {
  const double invH = m / grid.cellSize();
  std::vector<std::uint32_t> keys;
  grid.forEachCell([&](std::uint32_t begin, std::uint32_t end) {
    if (end - begin < 2) return;
    const P3 corner = grid.cellCorner(begin);
    keys.clear();
    for (std::uint32_t i = begin; i < end; ++i) {
      std::uint32_t key = 0;
      for (int a = 0; a < 3; ++a) {
        const double f = std::min(m - 1.0, std::max(0.0, (grid.point(i)[a] - corner[a]) * invH));
        key = key << 10 | std::uint32_t(f);
      }
      keys.push_back(key);
    }
    std::sort(keys.begin(), keys.end());
    for (size_t j = 1; j < keys.size(); ++j)
      if (keys[j] == keys[j - 1] && (j == 1 || keys[j - 1] != keys[j - 2]))
        crowded.push_back(P3(corner[0] + (double(keys[j] >> 20) + 0.5) * h,
                             corner[1] + (double((keys[j] >> 10) & 1023) + 0.5) * h,
                             corner[2] + (double(keys[j] & 1023) + 0.5) * h));
  });
}

// Step 2, the exact test on the points near a crowded fine cell: a core point (kClumpNeighbours
// others within r) lies in a 2×2×2 block of fine cells with a crowded one, so within 1.5·h·√3 of
// that one's centre. Sets core[q] = 1 for each and gives their number.
size_t markCorePoints(const MortonGrid& grid, const std::vector<P3>& crowded, double h, double r,
                      std::uint32_t neighbours, std::vector<char>& core) {
  const size_t n = grid.size();
  core.assign(n, 0);
  std::vector<char> tested(n, 0);
  std::vector<std::uint32_t> near;
  auto isCore = [&](std::uint32_t q) {
    std::uint32_t others = 0;
    return grid.anyInBall(grid.point(q), r, [&](std::uint32_t i, double) {
      return i != q && ++others >= neighbours;
    });
  };
  size_t cores = 0;
  for (const P3& c : crowded) {
    near.clear();
    grid.forEachInBall(c, 1.5 * h * 1.7320508075688772 * (1 + 1e-9), [&](std::uint32_t i, double) { near.push_back(i); });
    if (near.size() <= neighbours) continue;
    for (std::uint32_t q : near) {
      if (tested[q]) continue;
      tested[q] = 1;
      if (isCore(q)) {
        core[q] = 1;
        ++cores;
      }
    }
  }
  return cores;
}

// Step 3, the clumps, from the core points in index order (deterministic): a core point's points
// within 1.25r join its clump, and the core ones among them carry it on, except those within r/4
// of it (core = 2: their own points within r are within its 1.25r). So a point joins when it is
// within r of a core point (and never farther than 1.25r from one), and the expanded points are
// r/4 apart: a clump of m points far smaller than r costs O(m), where expanding every core point
// would cost O(m^2). In each clump the member nearest the centroid stays
// (ties: the lower caller index); drop[q] = 1 for the others. Adds to `clumps` and `merged`.
void groupClumps(const MortonGrid& grid, double r, std::vector<char>& core, std::vector<char>& drop, size_t& clumps,
                 size_t& merged) {
  const size_t n = grid.size();
  constexpr std::uint32_t kNone = ~0u;
  const double reach = 1.25 * r, near2 = 0.0625 * r * r;
  std::vector<std::uint32_t> clumpOf(n, kNone), stack, members;
  drop.assign(n, 0);
  for (std::uint32_t s = 0; s < n; ++s) {
    if (!core[s] || clumpOf[s] != kNone) continue;
    const std::uint32_t id = std::uint32_t(clumps++);
    members.clear();
    stack.assign(1, s);
    clumpOf[s] = id;
    while (!stack.empty()) {
      const std::uint32_t q = stack.back();
      stack.pop_back();
      members.push_back(q);
      if (core[q] != 1) continue;
      core[q] = 2;
      grid.forEachInBall(grid.point(q), reach, [&](std::uint32_t i, double d2) {
        if (d2 <= near2 && core[i] == 1) core[i] = 2;
        if (clumpOf[i] == kNone) {
          clumpOf[i] = id;
          stack.push_back(i);
        }
      });
    }
    P3 centroid(0, 0, 0);
    for (std::uint32_t q : members) centroid += grid.point(q);
    centroid /= double(members.size());
    std::uint32_t keep = members[0];
    double best = std::numeric_limits<double>::infinity();
    for (std::uint32_t q : members) {
      const double d2 = (grid.point(q) - centroid).SquaredNorm();
      if (d2 < best || (d2 == best && grid.order()[q] < grid.order()[keep])) {
        best = d2;
        keep = q;
      }
    }
    for (std::uint32_t q : members) drop[q] = q != keep;
    merged += members.size() - 1;
  }
}

// Step 4, the grid rebuilt from the points not dropped, in index order; order() composed back to
// the caller's.
void rebuildWithout(MortonGrid& grid, const std::vector<char>& drop, size_t merged) {
  const size_t n = grid.size();
  const double cell = grid.cellSize();
  std::vector<P3> kept;
  std::vector<std::uint32_t> keptOrder;
  kept.reserve(n - merged);
  keptOrder.reserve(n - merged);
  for (std::uint32_t i = 0; i < n; ++i)
    if (!drop[i]) {
      kept.push_back(grid.point(i));
      keptOrder.push_back(grid.order()[i]);
    }
  grid.build(std::move(kept), cell);
  std::vector<std::uint32_t> composed(keptOrder.size());
  for (size_t i = 0; i < composed.size(); ++i) composed[i] = keptOrder[grid.order()[i]];
  grid.setOrder(std::move(composed));
}

} // namespace

void Mesher::mergeClumps() {
  const double r = kClumpRadius * spacing_;
  const size_t n = grid_.size();
  if (!(r > 0) || n <= kClumpNeighbours) return;
  // Fine cells of side h >= 2r, m per grid cell.
  const double cell = grid_.cellSize();
  const double m = std::max(1.0, std::min(1024.0, std::floor(cell / (2.0 * r))));
  const double h = cell / m;
  // 1. The crowded fine cells (two points or more).
  std::vector<P3> crowded;
  crowdedFineCells(grid_, m, h, crowded);
  if (crowded.empty()) return;
  // 2. The core points near them.
  std::vector<char> core;
  if (markCorePoints(grid_, crowded, h, r, kClumpNeighbours, core) == 0) return;
  // 3. The clumps grown from the core points, one point kept in each.
  std::vector<char> drop;
  groupClumps(grid_, r, core, drop, clumps_, clumpPointsMerged_);
  // 4. The grid without the others.
  rebuildWithout(grid_, drop, clumpPointsMerged_);
}

} // namespace g2s
} // namespace growth
