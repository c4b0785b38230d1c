#pragma once
// Seeded triangle meshes for the remeshing benchmark and its tests: CAD parts with creases and
// corners, and an open curved sheet with holes, each triangulated irregularly.
//
// The CAD parts are orthogonal prisms: a cross-section of cells of a rectilinear grid extruded along
// z. Box (1 × 0.8 × 0.6), L-prism (an L of 1 × 1 with a 0.55 × 0.55 notch, 0.4 high), holed box
// (1 × 1 × 0.5 with a square 0.3 × 0.3 hole through it: genus 1) and open box (the box without its
// top face: one boundary loop along four creases). The cylinder (radius 0.5, height 1) has
// flat caps triangulated in concentric rings of about equal spacing, stitched to each other and
// to the side by a zipper (the next triangle takes the vertex of smaller angle). The sheet is a
// height field z = 0.06 sin(2πx) cos(πy) over [0, 1]² with three round holes (four boundary loops,
// no crease).
//
// Irregular, not a regular grid: the grid lines of each span between features are spaced unevenly
// (random weights in [0.5, 1.5]), each quad takes a random diagonal, and every vertex is moved at
// random along each axis in which it may move without leaving its faces' planes (so faces stay
// flat and creases stay straight: a vertex on one crease slides along it, a corner stays fixed); the
// move is at most `jitter` × the shorter neighbouring spacing on that axis. Vertices are shared
// (no T-junctions): every mesh is a manifold, consistently oriented (normals outward), without
// degenerate faces. The face count is close to `faces` (the spacing is fitted to it).
#include <growth/mesh_arrays.h>

#include <cstdint>
#include <string>

namespace growth {

enum class MeshShape { Box, Cylinder, LPrism, HoledBox, OpenBox, Sheet };

struct MeshSpec {
  MeshShape shape = MeshShape::Box;
  size_t faces = 20000;       // wanted face count (the result is within about 10 % of it)
  std::uint64_t seed = 1;     // spacing weights, diagonals and moves
  double jitter = 0.3;        // largest move, in units of the shorter neighbouring spacing; in [0, 0.45]
};

// What the shape's surface is: edge-connected components, boundary loops and genus.
struct MeshShapeTopology {
  size_t components = 1;
  size_t boundaryLoops = 0;
  int genus = 0;
  bool hasCreases = true;     // dihedral angles of 90° (all shapes but the sheet)
};

MeshArrays generateMesh(const MeshSpec& spec);
MeshShapeTopology shapeTopology(MeshShape shape);

// Parses "box", "cylinder", "lprism", "holedbox", "openbox", "sheet"; throws growth::Error otherwise.
MeshShape parseMeshShape(const std::string& name);
const char* meshShapeName(MeshShape shape);

// Binary little-endian PLY: float x y z, faces as uchar-counted int lists (MeshLab, PyMeshLab and
// CGAL read it).
void writeMeshPly(const std::string& path, const MeshArrays& mesh);

} // namespace growth
