#pragma once
// Non-manifold vertex elimination (Robust G2S, sec. 4.2).
//
// A vertex is non-manifold when its incident triangles form more than one fan, a fan being a
// sequence of triangles around the vertex in which consecutive triangles share an edge at the
// vertex that has exactly these two triangles (boundary vertices included: two open fans touching
// at a vertex make it non-manifold, fig. 5). The elimination keeps one fan per vertex and removes
// the triangles of the others. Removing a triangle can cut a neighbouring vertex's open fan in two
// and make *that* vertex non-manifold, so every vertex of a removed triangle is examined again,
// until no non-manifold vertex is left.
//
// The paper walks an edge queue (deq) and a per-vertex front/back table (ptt) to grow each vertex's
// triangle loop; here each vertex's fans are found directly by a union–find over its incident
// triangles joined across its two-triangle edges — the same result (the fans and which triangles
// lie outside the kept one) in time linear in the mesh: every vertex is examined once plus once
// per removal of one of its triangles, at O(d log d) for a vertex of valence d.
//
// Which fan is kept (the paper keeps the loop it closed first): a closed fan (a full disk around
// the vertex) before an open one, then the one with more triangles, then the one holding the
// lowest triangle index — removing as little surface as possible, deterministically.
#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace growth {

using Triangle = std::array<std::uint32_t, 3>;

struct ManifoldCleanupStat {
  size_t nonManifoldVertices = 0; // distinct vertices found with more than one fan
  size_t facesRemoved = 0;
};

// Removes the extra fans of every non-manifold vertex of the triangles with alive[f] != 0 (alive
// has one entry per triangle and is updated in place; removed triangles get 0). Vertex indices
// must be < vertexCount. Triangles with a repeated vertex are removed as degenerate first.
// `suspects`: when given, only these vertices can be non-manifold to begin with (a mesher that
// knows where fans were started knows them); they and the vertices of removed triangles are
// examined, instead of every vertex.
ManifoldCleanupStat removeNonManifoldVertices(const std::vector<Triangle>& faces, size_t vertexCount,
                                              std::vector<char>& alive,
                                              const std::vector<std::uint32_t>* suspects = nullptr);

// Drops the connected pieces of the alive triangles that have fewer than minFaces triangles, except
// the largest piece (of equal ones, the one that reached that size first in triangle order):
// their triangles get alive[f] = 0. Pieces are joined through shared vertices; once every vertex
// is manifold these are the edge-connected pieces (mesh_measures.h). minFaces <= 1 drops nothing.
// Returns the number of pieces dropped; `facesDropped` gets their triangles.
size_t dropSmallComponents(const std::vector<Triangle>& faces, size_t vertexCount, std::vector<char>& alive,
                           size_t minFaces, size_t& facesDropped);

// Number of vertices of the alive triangles whose incident triangles form more than one fan.
size_t countNonManifoldVertices(const std::vector<Triangle>& faces, size_t vertexCount,
                                const std::vector<char>& alive);

} // namespace growth
