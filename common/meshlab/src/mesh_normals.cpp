#include <growth/mesh_normals.h>
#include <growth/vec3.h>

#include <algorithm>
#include <cmath>

namespace growth {

namespace {

constexpr double kPi = 3.14159265358979323846;

// The angle atan2(y, x) in [0, π] for y >= 0, within 1e-5 rad: the octant reduction to a ratio in
// [0, 1] and the polynomial of Abramowitz and Stegun 4.4.49 for atan on it. The angles only weight
// the face normals, so this is as good as the exact angle for a unit normal in float, and it costs
// a division instead of a call of atan2 (which dominated the time here).
double cornerAngle(double y, double x) {
  const double ax = std::abs(x);
  const double hi = std::max(y, ax), lo = std::min(y, ax);
  if (!(hi > 0)) return 0;
  const double r = lo / hi, r2 = r * r;
  double a = r * (0.9998660 + r2 * (-0.3302995 + r2 * (0.1801410 + r2 * (-0.0851330 + r2 * 0.0208351))));
  if (y > ax) a = 0.5 * kPi - a;
  return x < 0 ? kPi - a : a;
}

// A vertex normal in the layer's scalar, rounded from double per coordinate.
CVertexO::NormalType toNormal(const Vec3d& n) { return CVertexO::NormalType(n[0], n[1], n[2]); }

} // namespace

void updateNormals(CMeshO& mesh) {
  using P3 = Vec3d;
  for (CVertexO& v : mesh.vert) v.N() = CVertexO::NormalType(0, 0, 0);
  // Accumulated in the vertices' float normals, as vcglib does: a vertex has about six faces, so
  // the float sum loses nothing that shows in a unit normal.
  for (CFaceO& f : mesh.face) {
    if (f.IsD()) continue;
    const P3 a = P3::Construct(f.cP(0)), b = P3::Construct(f.cP(1)), c = P3::Construct(f.cP(2));
    const P3 ab = b - a, ac = c - a, bc = c - b;
    const P3 n = ab ^ ac;
    const double len = n.Norm();
    if (!(len > 0)) {
      f.N() = CFaceO::NormalType(0, 0, 0);
      continue;
    }
    const P3 unit = n / len;
    f.N() = CFaceO::NormalType(unit[0], unit[1], unit[2]);
    // Corner angles from |ab × ac| = |ba × bc| = |n| (twice the area) and the dot products.
    const double angleA = cornerAngle(len, ab * ac);
    const double angleB = cornerAngle(len, -(ab * bc));
    const double angleC = std::max(0.0, kPi - angleA - angleB);
    f.V(0)->N() += toNormal(unit * angleA);
    f.V(1)->N() += toNormal(unit * angleB);
    f.V(2)->N() += toNormal(unit * angleC);
  }
  for (CVertexO& v : mesh.vert) {
    if (v.IsD()) continue;
    const P3 n = P3::Construct(v.N());
    const double len = n.Norm();
    if (len > 0) v.N() = toNormal(n / len);
  }
}

} // namespace growth
