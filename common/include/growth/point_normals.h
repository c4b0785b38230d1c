#pragma once
// Normals estimated from the points alone, as MeshLab's "Compute normals for point sets" gives
// them to a user whose cloud has none: for the tests and measurements that must see the normals a
// MeshLab user feeds the filters, not the generator's exact ones.
//
// Each normal is the direction of least variance of the point's k nearest points (the point
// included): the eigenvector of the smallest eigenvalue of their covariance (principal component
// analysis). Its sign is then propagated over the graph of the k nearest neighbours, most parallel
// neighbours first (a maximum spanning tree of |n_i · n_j|, Hoppe et al. 1992): each point not yet
// reached takes the sign that agrees with the neighbour it is reached from. Every piece of that
// graph starts at its lowest-index point with the sign the eigen solver gave, so a closed surface
// may come out pointing inwards, and where the propagation crosses a thin part or a sharp fold the
// signs of a patch can flip: the orientation is not always consistent, as in MeshLab's.
//
// Deterministic: the same points give the same normals on every run and any number of threads.
#include <growth/vec3.h>

#include <vector>

namespace growth {

// Unit normals of `points` from their k nearest points (k >= 3; fewer points: what there is).
// `threads`: for the per-point fits (0 = automatic); the result is the same for any number.
std::vector<Vec3d> estimateNormals(const std::vector<Vec3d>& points, int k, int threads = 0);

} // namespace growth
