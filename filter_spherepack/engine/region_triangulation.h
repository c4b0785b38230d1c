#pragma once
// Triangulation of the regions of G (Lipschütz et al., sec. 3.7).
//
// After the growth, every border of length at most ∂max is triangulated by iteratively cutting
// away the smallest inner angle ("as this leads to triangles close to equilateral ones"); inner
// angles are measured in the projection onto the plane orthogonal to the vertex normal, so they
// may exceed 180° where a region is not convex. Borders longer than ∂max stay holes (partial
// scans keep their boundary).
//
// Borders arrive as half-edge cycles with the region on their left (borders.h), so a cut ear
// u→v→w gives the triangle (u, v, w), counter-clockwise seen from the normals: all faces are
// oriented consistently, every edge is used once in each direction.
//
// Where the paper is silent we add the checks that keep the output a manifold (they never fire on
// a region that is a convex polygon in projection, the usual case of length ~4, sec. 3.7):
//  - a border that passes through a vertex twice (a region pinched at that vertex, a dangling
//    spike, or borders twisted where noise defeats the projections) is first split there into
//    simple loops, each triangulated on its own; loops shorter than 3 (spikes) give no face, and
//    spikes u→v→u met while cutting are dropped the same way;
//  - an ear is cut only when its angle is below 180°, its diagonal u–w is not an edge yet (of G or
//    of a triangle already made) and no other vertex of the loop lies inside it in projection;
//    when no ear qualifies, the smallest angle below 180° whose diagonal is new is cut anyway;
//    when none is left, the rest of the loop stays open and counts as a hole.
#include "box_grid.h"

#include <growth/vec3.h>

#include <array>
#include <cstdint>
#include <vector>

namespace growth {

// Undirected edges as a hash set.
class EdgeSet {
public:
  explicit EdgeSet(size_t expected = 16) : hash_(expected) {}
  static KeyHash::Key key(std::uint32_t u, std::uint32_t v) {
    return u < v ? (KeyHash::Key(u) << 32) | v : (KeyHash::Key(v) << 32) | u;
  }
  bool contains(std::uint32_t u, std::uint32_t v) const { return hash_.find(key(u, v)) >= 0; }
  void insert(std::uint32_t u, std::uint32_t v) { hash_.findOrInsert(key(u, v), 1); }
  size_t size() const { return hash_.size(); }

private:
  KeyHash hash_;
};

using Triangle = std::array<std::uint32_t, 3>;

// Inner angle of the region at v between the incoming edge from u and the outgoing edge to w
// (region on the left), measured counter-clockwise in the plane orthogonal to the unit normal n
// of v; in [0, 2π).
double innerAngle(const Vec3d& u, const Vec3d& v, const Vec3d& w, const Vec3d& n);

// Splits a closed border at the vertices it visits more than once into simple loops (each in
// border order). Loops of fewer than 3 vertices are kept (the caller skips them).
std::vector<std::vector<std::uint32_t>> splitAtRepeatedVertices(const std::vector<std::uint32_t>& border);

// Triangulates one simple loop (region on the left) by cutting the smallest inner angle first.
// Adds the triangles to `faces` and the new diagonals to `edges` (which must hold the edges of
// G). Returns false when part of the loop had to be left open.
bool triangulateLoop(const std::vector<std::uint32_t>& loop, const std::vector<Vec3d>& pos,
                     const std::vector<Vec3d>& nrm, EdgeSet& edges, std::vector<Triangle>& faces);

// A face whose vertices (nearly) lie on a line: its largest angle exceeds kMaxFaceAngleDeg, or two
// of its vertices coincide. Such a face has (about) zero area and no usable normal; the packer
// leaves it out (a hole of three edges and no area) instead of writing it. It arises where the
// growth placed a vertex at the midpoint of an edge of length 2d (both spheres of radius d around
// its ends meet only there), and the three edges then bound a region of their own.
constexpr double kMaxFaceAngleDeg = 179.0;
bool nearlyCollinear(const Vec3d& a, const Vec3d& b, const Vec3d& c);

struct RegionStats {
  size_t borders = 0;        // borders with at least one half-edge
  size_t triangulated = 0;   // borders closed completely
  size_t holes = 0;          // borders left open: longer than ∂max, or (partly) untriangulable
  size_t longBorders = 0;    // of which longer than ∂max
  size_t longestBorder = 0;
  size_t borderEdges = 0;    // sum of the border lengths (the mean is ~4 on closed surfaces, sec. 3.7)
};

// Sec. 3.7 on all borders.
RegionStats triangulateRegions(const std::vector<std::vector<std::uint32_t>>& borders,
                               const std::vector<Vec3d>& pos, const std::vector<Vec3d>& nrm,
                               int maxBorderLength, EdgeSet& edges, std::vector<Triangle>& faces);

} // namespace growth
