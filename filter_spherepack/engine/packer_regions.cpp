// Sec. 3.7: the regions triangulated; then the clean-up that makes sec. 3.1's guarantee
// unconditional, and the small pieces dropped (packer_steps.h).
#include "packer_steps.h"

#include <growth/manifold_cleanup.h>
#include <growth/self_intersections.h>
#include "stored_positions.h"


#include <algorithm>

namespace growth {
namespace spherepack {
namespace detail {

// Sec. 3.7: the regions the borders enclose, triangulated (up to Params::maxBorderLength edges;
// longer borders are left as holes).
std::vector<Triangle> triangulate(const BorderGraph& g, const Params& params, bool floatStorage, Stat& st) {
  EdgeSet edges(g.edgeCount() * 2 + 16);
  for (std::uint32_t v = 0; v < g.vertexCount(); ++v)
    for (int k = 0; k < g.degree(v); ++k)
      if (v < g.neighbour(v, k)) edges.insert(v, g.neighbour(v, k));
  std::vector<Triangle> faces;
  faces.reserve(2 * g.vertexCount() + 16);
  const RegionStats rs = triangulateRegions(g.borders(), g.positions(), g.normals(), params.maxBorderLength, edges, faces);
  st.regionsLeftOpen = rs.holes;
  st.longestBorder = rs.longestBorder;
  st.meanBorderLength = rs.borders > 0 ? double(rs.borderEdges) / double(rs.borders) : 0;
  // No face with (nearly) collinear vertices is output (region_triangulation.h, nearlyCollinear),
  // judged on the positions as the layer stores them: the three edges stay a hole of no area.
  // makeManifold() then takes care of a vertex whose fan this splits.
  size_t w = 0;
  for (const Triangle& f : faces) {
    const Vec3d a = asStored(g.position(f[0]), floatStorage),
                       b = asStored(g.position(f[1]), floatStorage),
                       c = asStored(g.position(f[2]), floatStorage);
    if (nearlyCollinear(a, b, c)) ++st.flatFacesRemoved;
    else faces[w++] = f;
  }
  faces.resize(w);
  return faces;
}

// Sec. 3.1's manifold guarantee made unconditional: it holds for a suitable d on a cloud sampling a
// manifold; elsewhere (noise beyond d/2, thin parts, misregistered scans, flipped normals) the
// growth's checks and the ear cut of sec. 3.7 can leave a vertex with two fans of faces or an edge
// with three. The fewest faces are removed: the extra fans of every non-manifold vertex (Robust
// G2S, sec. 4.2: growth/manifold_cleanup.h), which removes every face beyond two at an edge too.
// Every edge left is still an edge of the packing (>= d). Then no two faces may intersect (two
// sheets of a thin part or of misregistered scans meshed through each other, a fold of the ear
// cut): of each intersecting pair, faces are removed greedily (the one in most pairs first,
// growth/self_intersections.h), and the fans that this leaves at a vertex are cleaned up again.
void makeManifold(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, bool floatStorage,
                  Stat& st) {
  std::vector<char> alive(faces.size(), 1);
  ManifoldCleanupStat mc = removeNonManifoldVertices(faces, g.vertexCount(), alive);
  st.nonManifoldVerticesRemoved = mc.nonManifoldVertices;
  st.facesRemoved = mc.facesRemoved;
  // On the positions as the output stores them (float in MeshLab 2020.09): rounding must not make
  // faces that nearly touch intersect.
  st.selfIntersectionFacesRemoved =
      removeSelfIntersections(asStored(g.positions(), floatStorage), faces, alive, params.threads);
  if (st.selfIntersectionFacesRemoved > 0) {
    mc = removeNonManifoldVertices(faces, g.vertexCount(), alive);
    st.nonManifoldVerticesRemoved += mc.nonManifoldVertices;
    st.facesRemoved += mc.facesRemoved + st.selfIntersectionFacesRemoved;
  }
  if (st.facesRemoved > 0) {
    size_t w = 0;
    for (size_t f = 0; f < faces.size(); ++f)
      if (alive[f]) faces[w++] = faces[f];
    faces.resize(w);
  }
}

namespace {

// Drops the connected pieces of `faces` with fewer than minFaces faces, except the largest
// (growth::dropSmallComponents). The order of the faces kept is unchanged. Returns the number of
// pieces dropped.
size_t dropSmallComponents(std::vector<Triangle>& faces, size_t vertexCount, size_t minFaces,
                           size_t& facesDropped) {
  std::vector<char> alive(faces.size(), 1);
  const size_t dropped = growth::dropSmallComponents(faces, vertexCount, alive, minFaces, facesDropped);
  if (dropped == 0) return 0;
  size_t w = 0;
  for (size_t f = 0; f < faces.size(); ++f)
    if (alive[f]) faces[w++] = faces[f];
  faces.resize(w);
  return dropped;
}

} // namespace

// Pieces too small to be a part of the surface: flaps grown onto a misregistered second scan
// layer, cut off from the mesh by the regions left open between the layers, and bits of stray
// points (docs/design/small-pieces.md). Whole pieces go, so the rest keeps every guarantee.
void dropSmallPieces(std::vector<Triangle>& faces, const BorderGraph& g, const Params& params, Stat& st) {
  if (params.minComponentFaces > 1)
    st.componentsDropped = dropSmallComponents(faces, g.vertexCount(), size_t(params.minComponentFaces),
                                               st.componentFacesDropped);
}

} // namespace detail
} // namespace spherepack
} // namespace growth
