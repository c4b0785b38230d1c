#pragma once
// A layer's points (CloudArrays) checked as a point cloud, with the input checks both filters share.
//
// The engines compute in double (MeshLab stores float): the glue copies the live vertices into
// double arrays once (growth/meshlab/layer.h). Bad input is refused with a growth::Error whose
// message says what is wrong and what to do in MeshLab.
#include <growth/mesh_arrays.h>
#include <growth/vec3.h>

#include <string>
#include <vector>

namespace growth {

struct InputCloud {
  std::vector<Vec3d> points;
  std::vector<Vec3d> normals;   // unit length (zero where unusable, with readNormals); empty
                                       // when normals were not asked for
  std::vector<int> vertexIndex;        // index of each point in the layer's vertex vector
  Box3d box;
  size_t duplicatesDropped = 0;        // exact repeats of an earlier point (first one kept)
  size_t layerFaces = 0;
};

struct CloudCheck {
  bool needNormals = false;            // refuse points without a usable normal
  bool readNormals = false;            // read the normals without needing them (zero where a
                                       // vertex has no usable one); needNormals reads them too
  bool normalsAsStored = false;        // with readNormals: the normals as stored, not made unit length
                                       // (zero where not finite or zero)
  bool allowFaces = false;             // refuse a layer that is already a mesh
  size_t minPoints = 3;
};

// Coordinates beyond ±kMaxAbsCoordinate are refused: far beyond any scan (a kilometre in
// nanometres is 1e12), and past it the engines' squared lengths, products of squared lengths and
// float sums of lengths would overflow (a cloud 1e38 across gives a NaN search centre in G2S).
constexpr double kMaxAbsCoordinate = 1e15;

// The distinct points of a layer's live vertices (taken over from `layer`); throws growth::Error
// (user-facing message) on: an empty layer, fewer than check.minPoints distinct points, NaN,
// infinite or huge coordinates, all points identical or on one line, faces when !allowFaces,
// missing/zero/NaN normals when needNormals.
InputCloud readCloud(CloudArrays layer, const CloudCheck& check);

} // namespace growth
