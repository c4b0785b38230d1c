#pragma once
// The engines' point and box in double: the member API of vcglib's Point3d and Box3d that the
// code uses, with the same order of operations (so the results are the same bit for bit), but no
// vcglib, so the engines are compiled once for every MeshLab SDK.
#include <cmath>

namespace growth {

class Vec3d {
public:
  using ScalarType = double;

  Vec3d() {} // left uninitialised, as vcglib's
  Vec3d(double x, double y, double z) : v_{x, y, z} {}
  // From any indexable triple (a layer's float or double point).
  template <class P>
  static Vec3d Construct(const P& p) {
    return Vec3d(double(p[0]), double(p[1]), double(p[2]));
  }
  static Vec3d Zero() { return Vec3d(0, 0, 0); }

  double& operator[](int i) { return v_[i]; }
  const double& operator[](int i) const { return v_[i]; }
  double& X() { return v_[0]; }
  double& Y() { return v_[1]; }
  double& Z() { return v_[2]; }
  const double& X() const { return v_[0]; }
  const double& Y() const { return v_[1]; }
  const double& Z() const { return v_[2]; }
  double* V() { return v_; }
  const double* V() const { return v_; }
  double& V(int i) { return v_[i]; }
  const double& V(int i) const { return v_[i]; }
  void SetZero() { v_[0] = v_[1] = v_[2] = 0; }

  Vec3d operator+(const Vec3d& p) const { return Vec3d(v_[0] + p.v_[0], v_[1] + p.v_[1], v_[2] + p.v_[2]); }
  Vec3d operator-(const Vec3d& p) const { return Vec3d(v_[0] - p.v_[0], v_[1] - p.v_[1], v_[2] - p.v_[2]); }
  Vec3d operator-() const { return Vec3d(-v_[0], -v_[1], -v_[2]); }
  Vec3d operator*(double s) const { return Vec3d(v_[0] * s, v_[1] * s, v_[2] * s); }
  Vec3d operator/(double s) const { return Vec3d(v_[0] / s, v_[1] / s, v_[2] / s); }
  // Dot product, summed left to right.
  double operator*(const Vec3d& p) const { return v_[0] * p.v_[0] + v_[1] * p.v_[1] + v_[2] * p.v_[2]; }
  double dot(const Vec3d& p) const { return *this * p; }
  // Cross product.
  Vec3d operator^(const Vec3d& p) const {
    return Vec3d(v_[1] * p.v_[2] - v_[2] * p.v_[1], v_[2] * p.v_[0] - v_[0] * p.v_[2],
                 v_[0] * p.v_[1] - v_[1] * p.v_[0]);
  }
  Vec3d& operator+=(const Vec3d& p) {
    v_[0] += p.v_[0], v_[1] += p.v_[1], v_[2] += p.v_[2];
    return *this;
  }
  Vec3d& operator-=(const Vec3d& p) {
    v_[0] -= p.v_[0], v_[1] -= p.v_[1], v_[2] -= p.v_[2];
    return *this;
  }
  Vec3d& operator*=(double s) {
    v_[0] *= s, v_[1] *= s, v_[2] *= s;
    return *this;
  }
  Vec3d& operator/=(double s) {
    v_[0] /= s, v_[1] /= s, v_[2] /= s;
    return *this;
  }

  double SquaredNorm() const { return v_[0] * v_[0] + v_[1] * v_[1] + v_[2] * v_[2]; }
  double Norm() const { return std::sqrt(SquaredNorm()); }
  // Divides by the norm where it is positive (a zero vector stays zero).
  Vec3d& Normalize() {
    const double n = Norm();
    if (n > 0) v_[0] /= n, v_[1] /= n, v_[2] /= n;
    return *this;
  }

  bool operator==(const Vec3d& p) const { return v_[0] == p.v_[0] && v_[1] == p.v_[1] && v_[2] == p.v_[2]; }
  bool operator!=(const Vec3d& p) const { return !(*this == p); }
  // z first, then y, then x.
  bool operator<(const Vec3d& p) const {
    if (v_[2] != p.v_[2]) return v_[2] < p.v_[2];
    if (v_[1] != p.v_[1]) return v_[1] < p.v_[1];
    return v_[0] < p.v_[0];
  }

private:
  double v_[3];
};

inline double Norm(const Vec3d& p) { return p.Norm(); }
inline double SquaredNorm(const Vec3d& p) { return p.SquaredNorm(); }
inline double Distance(const Vec3d& a, const Vec3d& b) { return (a - b).Norm(); }
inline double SquaredDistance(const Vec3d& a, const Vec3d& b) { return (a - b).SquaredNorm(); }

// An axis-aligned box; null (min above max) until a point is added.
class Box3d {
public:
  Vec3d min, max;

  Box3d() { SetNull(); }
  Box3d(const Vec3d& lo, const Vec3d& hi) : min(lo), max(hi) {}

  void SetNull() {
    min = Vec3d(1, 1, 1);
    max = Vec3d(-1, -1, -1);
  }
  bool IsNull() const { return min[0] > max[0] || min[1] > max[1] || min[2] > max[2]; }
  bool IsEmpty() const { return min == max; }
  void Set(const Vec3d& p) { min = max = p; }
  void Add(const Vec3d& p) {
    if (IsNull()) {
      Set(p);
      return;
    }
    for (int k = 0; k < 3; ++k) {
      if (min[k] > p[k]) min[k] = p[k];
      if (max[k] < p[k]) max[k] = p[k];
    }
  }
  void Add(const Box3d& b) {
    if (b.IsNull()) return;
    if (IsNull()) {
      *this = b;
      return;
    }
    for (int k = 0; k < 3; ++k) {
      if (min[k] > b.min[k]) min[k] = b.min[k];
      if (max[k] < b.max[k]) max[k] = b.max[k];
    }
  }
  void Offset(double s) { Offset(Vec3d(s, s, s)); }
  void Offset(const Vec3d& delta) {
    min -= delta;
    max += delta;
  }
  // Closed box.
  bool IsIn(const Vec3d& p) const {
    return min[0] <= p[0] && p[0] <= max[0] && min[1] <= p[1] && p[1] <= max[1] && min[2] <= p[2] && p[2] <= max[2];
  }
  bool Collide(const Box3d& b) const {
    return b.min[0] < max[0] && b.max[0] > min[0] && b.min[1] < max[1] && b.max[1] > min[1] &&
           b.min[2] < max[2] && b.max[2] > min[2];
  }
  double Diag() const { return Distance(min, max); }
  double SquaredDiag() const { return SquaredDistance(min, max); }
  Vec3d Center() const { return (min + max) / 2; }
  Vec3d Dim() const { return max - min; }
  double DimX() const { return max[0] - min[0]; }
  double DimY() const { return max[1] - min[1]; }
  double DimZ() const { return max[2] - min[2]; }
  double Volume() const { return DimX() * DimY() * DimZ(); }
};

} // namespace growth
