#pragma once
// What the engines take and give: a point cloud and a triangle mesh as plain arrays in double. The
// MeshLab glue copies a layer into a CloudArrays and a MeshArrays into a new layer
// (growth/meshlab/layer.h), once per run.
#include <growth/vec3.h>

#include <array>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace growth {

struct CloudArrays {
  std::vector<Vec3d> points;     // the layer's live vertices
  std::vector<Vec3d> normals;    // their normals as stored (the same size), or empty: none
  std::vector<int> vertexIndex;  // each point's index in the layer's vertex vector; empty: 0, 1, ...
  size_t layerFaces = 0;         // faces of the layer (a mesh is refused unless CloudCheck::allowFaces)
  bool floatStorage = true;      // the layer stores float coordinates (MeshLab 2020.09 and the 2025.07
                                 // GUI; PyMeshLab stores double), as an output written back is rounded
};

struct MeshArrays {
  std::vector<Vec3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> faces;  // vertex indices, counter-clockwise seen from outside
  std::vector<double> faceQuality;                  // Q_t per face, or empty
};

} // namespace growth
