#pragma once
// Normals for a freshly built mesh layer, as MeshLab expects them after a filter that creates one
// (its own creation filters call MeshModel::UpdateBoxAndNormals).
//
// updateNormals gives what vcglib's UpdateNormal::PerFaceNormalized, PerVertexAngleWeighted and
// NormalizePerVertex give together: unit face normals, and unit vertex normals that are the sum of
// the normals of the faces around the vertex, each weighted by the face's angle at the vertex
// (Thürmer and Wüthrich 1998). It takes one pass over the faces and one over the vertices instead
// of four, computes in double, and gets a corner's angle as atan2(|n|, e·e') from the face's
// normal n (twice its area), with atan2 within 1e-5 rad by a polynomial, instead of normalising
// the edges and taking acos; the third angle is π minus the other two. Deleted faces and vertices
// are skipped. A degenerate face (zero area) has a zero normal and adds nothing; a vertex with no
// face, or whose weighted normals cancel, keeps a zero normal. tools/normals_time.cpp times it
// against vcglib's.
#include <common/ml_mesh_type.h>

namespace growth {

void updateNormals(CMeshO& mesh);

} // namespace growth
