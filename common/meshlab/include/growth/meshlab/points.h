#pragma once
// The engines' Vec3d as a MeshLab point (vcglib's Point3 of any scalar), rounded per coordinate.
#include <growth/vec3.h>

#include <vcg/space/point3.h>

namespace growth {
namespace meshlab {

template <class P>
P toPoint(const Vec3d& p) {
  using S = typename P::ScalarType;
  return P(S(p[0]), S(p[1]), S(p[2]));
}

inline vcg::Point3f toPoint3f(const Vec3d& p) { return toPoint<vcg::Point3f>(p); }

} // namespace meshlab
} // namespace growth
