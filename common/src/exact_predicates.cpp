// The exact fallbacks of the orientation predicates (growth/exact_predicates.h).
//
// Both determinants are written as sums of products of the input coordinates themselves (not of
// their differences, which would be rounded): orient2d as the 3×3 determinant with a column of
// ones (6 products of two coordinates), orient3d as the 4×4 one expanded along that column (24
// products of three). A product of two doubles is exactly the sum of two doubles (two-product),
// so a product of three is exactly the sum of four; these 12 or 96 doubles are added one by one
// into an expansion without any rounding (grow-expansion with two-sum, zero components dropped),
// and the sign of the exact sum is the sign of the expansion's largest component.
//
// This file must be compiled without contraction of a*b+c into a fused multiply-add (the split
// and the error terms rely on every product and sum being rounded on its own): common/CMakeLists.txt
// sets -ffp-contract=off for it.
#include <growth/exact_predicates.h>

namespace growth {

namespace {

// a + b = sum + err exactly (Knuth's two-sum, no condition on the magnitudes).
inline void twoSum(double a, double b, double& sum, double& err) {
  sum = a + b;
  const double bPart = sum - a;
  const double aPart = sum - bPart;
  err = (a - aPart) + (b - bPart);
}

// a = hi + lo with hi and lo of at most 26 significant bits each (Veltkamp's split).
inline void split(double a, double& hi, double& lo) {
  constexpr double kSplitter = 134217729.0; // 2^27 + 1
  const double scaled = kSplitter * a;
  const double big = scaled - a;
  hi = scaled - big;
  lo = a - hi;
}

// a · b = product + err exactly (Dekker's two-product): the four partial products of the halves
// are exact, and so is every subtraction of them from the rounded product.
inline void twoProduct(double a, double b, double& product, double& err) {
  product = a * b;
  double aHi, aLo, bHi, bLo;
  split(a, aHi, aLo);
  split(b, bHi, bLo);
  err = ((aHi * bHi - product) + aHi * bLo + aLo * bHi) + aLo * bLo;
}

// An exact sum of doubles, kept as a non-overlapping expansion: components of increasing
// magnitude, each smaller than the lowest set bit of the next, so the largest one carries the
// sign of the whole. Adding a double runs it up through the components with two-sum (each step's
// error becomes a component, its sum carries on), which keeps these properties.
class ExactSum {
public:
  void add(double b) {
    double carry = b;
    int kept = 0;
    for (int i = 0; i < size_; ++i) {
      double sum, err;
      twoSum(carry, part_[i], sum, err);
      if (err != 0) part_[kept++] = err; // kept <= i: part_[i] has been read
      carry = sum;
    }
    if (carry != 0) part_[kept++] = carry;
    size_ = kept;
  }

  // Adds sign·x·y exactly (two doubles).
  void addProduct(double x, double y, bool negate) {
    double p, e;
    twoProduct(x, y, p, e);
    add(negate ? -e : e);
    add(negate ? -p : p);
  }

  // Adds sign·x·y·z exactly (four doubles).
  void addProduct(double x, double y, double z, bool negate) {
    double p, e, pp, pe, ep, ee;
    twoProduct(x, y, p, e);
    twoProduct(e, z, ep, ee);
    twoProduct(p, z, pp, pe);
    add(negate ? -ee : ee);
    add(negate ? -ep : ep);
    add(negate ? -pe : pe);
    add(negate ? -pp : pp);
  }

  int sign() const { return size_ == 0 ? 0 : (part_[size_ - 1] > 0 ? 1 : -1); }

private:
  // At most one component per double added (96 for orient3d), fewer in practice.
  static constexpr int kCapacity = 96;
  double part_[kCapacity];
  int size_ = 0;
};

// Adds sign·det[p; q; r] (rows of three coordinates) to `sum`: the six products of the cofactor
// expansion along the first row.
void addDet3(ExactSum& sum, const Vec3d& p, const Vec3d& q, const Vec3d& r, bool negate) {
  sum.addProduct(p[0], q[1], r[2], negate);
  sum.addProduct(p[0], q[2], r[1], !negate);
  sum.addProduct(p[1], q[2], r[0], negate);
  sum.addProduct(p[1], q[0], r[2], !negate);
  sum.addProduct(p[2], q[0], r[1], negate);
  sum.addProduct(p[2], q[1], r[0], !negate);
}

} // namespace

int orient2dExact(double ax, double ay, double bx, double by, double cx, double cy) {
  // det[a−c; b−c] = det[a 1; b 1; c 1] = (ax·by − ay·bx) + (bx·cy − by·cx) + (cx·ay − cy·ax).
  ExactSum sum;
  sum.addProduct(ax, by, false);
  sum.addProduct(ay, bx, true);
  sum.addProduct(bx, cy, false);
  sum.addProduct(by, cx, true);
  sum.addProduct(cx, ay, false);
  sum.addProduct(cy, ax, true);
  return sum.sign();
}

int orient3dExact(const Vec3d& a, const Vec3d& b, const Vec3d& c, const Vec3d& d) {
  // det[a−d; b−d; c−d] = det of the 4×4 matrix with rows (a, 1), (b, 1), (c, 1), (d, 1); along
  // its last column: det(a,b,c) − det(a,b,d) + det(a,c,d) − det(b,c,d).
  ExactSum sum;
  addDet3(sum, a, b, c, false);
  addDet3(sum, a, b, d, true);
  addDet3(sum, a, c, d, false);
  addDet3(sum, b, c, d, true);
  return sum.sign();
}

} // namespace growth
