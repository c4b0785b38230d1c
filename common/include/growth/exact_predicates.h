#pragma once
// Exact orientation predicates on double coordinates: orient2d and orient3d return the exact sign
// of their determinant, so decisions built on them (does this triangle touch that one?) never
// depend on rounding.
//
// Each predicate first evaluates its determinant in floating point together with a bound on the
// rounding error (a "filter"); the sign is returned at once when the value is farther from zero
// than the bound, which is almost always. Otherwise the determinant is evaluated again without any
// error, as a floating-point expansion: a number held as a sum of doubles of increasing magnitude
// that do not overlap bit-wise, built with error-free transformations (Knuth's two-sum; Dekker's
// two-product with Veltkamp's split), whose sign is the sign of its largest component.
//
// Error bounds (u = 2^-53, the unit roundoff). orient2d's value, (ax−cx)(by−cy) − (ay−cy)(bx−cx),
// passes each of its monomials through 4 roundings (two differences, a product, the subtraction),
// so its error is at most γ4·P, γ4 = 4u/(1−4u), P the sum of the monomials' magnitudes; P computed
// in floating point is at least (1−u)^4·P, hence the bound 5u·P_computed. orient3d's value goes
// through 8 roundings per monomial (three differences, two products, the inner subtraction, two
// additions): γ8·P <= 10u·P_computed. Below a computed P of 1e-270 (> 2^-900; products could
// lose bits to underflow there) the filter is skipped.
//
// Exactness of the fallback needs every product of two or three coordinates to be representable
// without underflow or overflow: it holds for finite coordinates with every nonzero magnitude in
// [2^-300, 2^300] (every float qualifies). Non-finite coordinates give meaningless signs.
#include <growth/vec3.h>

#include <cfloat>
#include <cmath>

namespace growth {

// The exact evaluations alone (no filter): what the predicates fall back on. Exposed for tests.
int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy);
int orient3dExact(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d);

// Sign (+1, 0, −1) of det[a−c; b−c] = (ax−cx)(by−cy) − (ay−cy)(bx−cx): +1 when a, b, c turn
// counterclockwise, 0 when they are collinear.
inline int orient2d(double ax, double ay, double bx, double by, double cx, double cy) {
  constexpr double kBound = 5.0 * (DBL_EPSILON / 2);
  constexpr double kMinPermanent = 1e-270; // > 2^-900
  const double acx = ax - cx, bcy = by - cy, acy = ay - cy, bcx = bx - cx;
  const double left = acx * bcy, right = acy * bcx;
  const double det = left - right;
  const double permanent = std::abs(left) + std::abs(right);
  if (permanent >= kMinPermanent) {
    const double bound = kBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  return orient2dExact(ax, ay, bx, by, cx, cy);
}

// Sign of det[a−d; b−d; c−d]: +1 when d lies below the plane through a, b, c, these seen
// counterclockwise from above (on the side opposite to the normal (b−a)×(c−a)); 0 when the four
// points are coplanar.
inline int orient3d(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  constexpr double kBound = 10.0 * (DBL_EPSILON / 2);
  constexpr double kMinPermanent = 1e-270; // > 2^-900
  const double adx = a[0] - d[0], ady = a[1] - d[1], adz = a[2] - d[2];
  const double bdx = b[0] - d[0], bdy = b[1] - d[1], bdz = b[2] - d[2];
  const double cdx = c[0] - d[0], cdy = c[1] - d[1], cdz = c[2] - d[2];
  const double bycz = bdy * cdz, bzcy = bdz * cdy;
  const double cyaz = cdy * adz, czay = cdz * ady;
  const double aybz = ady * bdz, azby = adz * bdy;
  const double det = adx * (bycz - bzcy) + bdx * (cyaz - czay) + cdx * (aybz - azby);
  const double permanent = std::abs(adx) * (std::abs(bycz) + std::abs(bzcy)) +
                           std::abs(bdx) * (std::abs(cyaz) + std::abs(czay)) +
                           std::abs(cdx) * (std::abs(aybz) + std::abs(azby));
  if (permanent >= kMinPermanent) {
    const double bound = kBound * permanent;
    if (det > bound) return 1;
    if (-det > bound) return -1;
  }
  return orient3dExact(a, b, c, d);
}

} // namespace growth
