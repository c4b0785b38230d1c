#pragma once
// Self-intersecting face pairs of a triangle mesh, decided exactly, and their removal.
//
// Which pairs intersect (the definition of CGAL's Polygon_mesh_processing::self_intersections),
// for two faces with three distinct vertex indices each, by the vertex indices they share:
// - none: their closed triangles have a point in common (touching at a single point counts);
// - exactly one, v: they have a point in common other than v;
// - two, an edge u–w: they overlap beyond that edge — coplanar, with their third vertices on the
//   same side of the edge (a fold-over). Faces meeting at an edge at any dihedral angle, or flat
//   on opposite sides of it, do not intersect;
// - all three (duplicate faces, in either orientation): always.
// Sharing is by vertex index: two vertices at the same position are different vertices, so the
// faces of an unwelded mesh that touch along their borders intersect, and the faces around a
// non-manifold edge are tested in pairs like any two faces sharing an edge. A face whose vertices are
// distinct but collinear (a zero-area sliver) is the segment or point it covers and is tested
// like any other face with that point set (CGAL instead reports it paired with itself and tests
// it against nothing). Faces with a repeated vertex index, dead faces (alive[f] == 0) and faces
// with a non-finite coordinate take no part.
//
// Every decision is exact: it uses only the signs of orient3d and of orient2d in a coordinate
// plane (growth/exact_predicates.h) and comparisons of coordinates, never a constructed point.
// Exact for finite coordinates with nonzero magnitudes in [2^-300, 2^300] (all float meshes).
//
// Broad phase: a uniform grid over the faces' bounding boxes, cells 1.5 mean edge lengths wide,
// listing each face in the cells its box covers; a pair is tested only in the cell holding the
// lowest corner of the overlap of the two boxes, so each pair is tested once. Long faces (boxes
// more than 4 cells long) are not listed but look up the cells their box covers, or scan all
// boxes when their box covers more cells than there are faces; when that work would exceed 4
// passes over the faces, the cells grow (see self_intersections.cpp). Time is linear in the faces
// when their sizes are alike; tools/self_intersections_time.cpp measures it on a mesh.
#include <growth/manifold_cleanup.h>

#include <growth/vec3.h>

#include <cstddef>
#include <cstdint>
#include <utility>
#include <vector>

namespace growth {

// The pair test findSelfIntersections applies to faces a and b of a mesh with vertex positions
// `pos`, as defined above (false when a or b has a repeated vertex index). Vertex indices must be
// < pos.size() and the coordinates finite.
bool facesIntersect(const std::vector<Vec3d>& pos, const Triangle& a, const Triangle& b);

// Every pair (i, j), i < j, of faces that intersect as defined above, once each, sorted. `alive`:
// when given, one entry per face, and faces with alive[f] == 0 are ignored. `threads`: 0 for
// automatic (growth/parallel.h); the result does not depend on it. Vertex indices must be
// < pos.size() (growth::Error otherwise).
std::vector<std::pair<std::uint32_t, std::uint32_t>> findSelfIntersections(const std::vector<Vec3d>& pos,
                                                                          const std::vector<Triangle>& faces,
                                                                          const std::vector<char>* alive = nullptr,
                                                                          int threads = 0);

// Removes faces (alive[f] = 0) until findSelfIntersections finds no pair, removing as few as it
// reasonably can: greedily the face in most remaining pairs, ties to the lowest index (so the
// result is deterministic), until no pair is left (removing faces never creates a pair). Returns
// the number of faces removed. `alive` must have one entry per face (growth::Error otherwise).
// Removal can leave non-manifold vertices (two fans meeting at a vertex where a face was taken
// out) and holes: run removeNonManifoldVertices (growth/manifold_cleanup.h) afterwards.
size_t removeSelfIntersections(const std::vector<Vec3d>& pos, const std::vector<Triangle>& faces,
                               std::vector<char>& alive, int threads = 0);

} // namespace growth
