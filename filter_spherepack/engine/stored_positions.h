#pragma once
// Positions as a MeshLab layer stores them (its scalar: float in MeshLab 2020.09 and the GUI,
// double in PyMeshLab), for checks that must hold on the output as it is saved, not only on the
// engine's doubles: two faces that nearly touch in double can intersect once rounded to float.
//
// The rounding is kept through an empty asm statement: GCC 12 at -O2 and -O3 can fold
// double(float(x)) back to x in vectorised loops.
#include <growth/vec3.h>

#include <vector>

namespace growth {

template <class Scalar>
inline double asStored(double x) {
  Scalar s = static_cast<Scalar>(x);
#if defined(__GNUC__) && (defined(__x86_64__) || defined(__i386__))
  __asm__("" : "+x"(s));
#else
  volatile Scalar keep = s;
  s = keep;
#endif
  return static_cast<double>(s);
}

template <class Scalar>
inline Vec3d asStored(const Vec3d& p) {
  return Vec3d(asStored<Scalar>(p[0]), asStored<Scalar>(p[1]), asStored<Scalar>(p[2]));
}

template <class Scalar>
std::vector<Vec3d> asStored(const std::vector<Vec3d>& pos) {
  std::vector<Vec3d> out(pos.size());
  for (size_t i = 0; i < pos.size(); ++i) out[i] = asStored<Scalar>(pos[i]);
  return out;
}

// As stored by a layer of float (CloudArrays::floatStorage) or double coordinates.
inline Vec3d asStored(const Vec3d& p, bool floatStorage) { return floatStorage ? asStored<float>(p) : p; }
inline std::vector<Vec3d> asStored(const std::vector<Vec3d>& pos, bool floatStorage) {
  return floatStorage ? asStored<float>(pos) : pos;
}

} // namespace growth
