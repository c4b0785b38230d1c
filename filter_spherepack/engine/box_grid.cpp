#include "box_grid.h"

#include <stdexcept>
#include <growth/error.h>
#include <growth/parallel.h>
#include <growth/progress.h>

#include <algorithm>
#include <limits>
#include <queue>
#include <sstream>

namespace growth {

// ---------------------------------------------------------------------------------------------
// Sphere sampling

SphereSampling::SphereSampling(int level) : level_(std::max(0, std::min(level, 8))) {
  auto tables = std::make_shared<Tables>();
  size_t total = 0;
  for (int depth = 0; depth < level_; ++depth) {
    tables->offset.push_back(total);
    total += size_t(6) << (2 * depth);
  }
  // The tables are written whole: made resident in one call each (huge_pages.h).
  reserveHuge(tables->cell, total, /*populate=*/true);
  tables->cell.resize(total);
  tables_ = tables; // cellIndex() reads the offsets
  for (int depth = 0; depth < level_; ++depth) {
    const std::uint32_t m = std::uint32_t(1) << depth;
    const double size = 2.0 / double(m);
    for (int face = 0; face < 6; ++face)
      for (std::uint32_t y = 0; y < m; ++y)
        for (std::uint32_t x = 0; x < m; ++x) {
          const double u0 = -1.0 + double(x) * size, v0 = -1.0 + double(y) * size;
          const Vec3d c = faceDirection(face, u0 + 0.5 * size, v0 + 0.5 * size);
          double minCos = 1;
          for (int k = 0; k < 4; ++k)
              minCos = std::min(minCos, faceDirection(face, u0 + (k & 1) * size, v0 + (k >> 1) * size) * c);
          CellInfo& info = tables->cell[cellIndex(face, depth, x, y)];
          info.centre = c;
          info.cosAlpha = minCos;
          info.sinAlpha = std::sqrt(std::max(0.0, 1.0 - minCos * minCos));
        }
  }
}

Vec3d SphereSampling::faceDirection(int face, double u, double v) const {
  const int axis = face / 2;
  const double sign = (face % 2 == 0) ? 1.0 : -1.0;
  Vec3d d;
  d[axis] = sign;
  d[(axis + 1) % 3] = u;
  d[(axis + 2) % 3] = v;
  return d / d.Norm();
}

Vec3d SphereSampling::leafCentre(int face, std::uint32_t col, std::uint32_t row) const {
  const double m = double(std::uint32_t(1) << level_);
  return faceDirection(face, -1.0 + (2.0 * double(col) + 1.0) / m, -1.0 + (2.0 * double(row) + 1.0) / m);
}

constexpr std::uint16_t SphereSampling::kUpCode; // (odr-used: tests compare with it)

std::uint16_t SphereSampling::code(const Vec3d& dir) const {
  // The leaf whose centre dir is: found as sumLeaf finds the leaf of a direction (a centre lies
  // half a cell from its leaf's edges), then checked bit for bit.
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(dir[a]) > std::abs(dir[axis])) axis = a;
  if (std::abs(dir[axis]) > 0 && level_ <= 6) {
    const int face = 2 * axis + (dir[axis] > 0 ? 0 : 1);
    const double inv = 1.0 / std::abs(dir[axis]);
    const std::uint32_t cells = std::uint32_t(1) << level_;
    auto leaf = [&](double t) {
      const double f = (t * inv + 1.0) * 0.5 * double(cells);
      return static_cast<std::uint32_t>(std::min(double(cells - 1), std::max(0.0, std::floor(f))));
    };
    const std::uint32_t col = leaf(dir[(axis + 1) % 3]), row = leaf(dir[(axis + 2) % 3]);
    if (leafCentre(face, col, row) == dir)
      return static_cast<std::uint16_t>((std::uint32_t(face) << (2 * level_)) | (row << level_) | col);
  }
  if (dir == Vec3d(0, 0, 1)) return kUpCode;
  throw std::logic_error("box normal: not a direction of the sphere sampling");
}

Vec3d SphereSampling::decode(std::uint16_t code) const {
  if (code == kUpCode) return Vec3d(0, 0, 1);
  const std::uint32_t mask = (std::uint32_t(1) << level_) - 1;
  return leafCentre(int(code >> (2 * level_)), code & mask, (std::uint32_t(code) >> level_) & mask);
}

Vec3d SphereSampling::direction(size_t i) const {
  const size_t m = size_t(1) << level_;
  const int face = static_cast<int>(i / (m * m));
  const size_t r = i % (m * m);
  const size_t row = r / m, col = r % m;
  const double u = -1.0 + (2.0 * double(col) + 1.0) / double(m);
  const double v = -1.0 + (2.0 * double(row) + 1.0) / double(m);
  return faceDirection(face, u, v);
}

namespace {
// min_k <normals[idx[k]], n>, stopping early once the running minimum is <= cutoff (the caller
// then knows the value cannot matter).
double minDot(const std::vector<Vec3d>& normals, const std::uint32_t* idx, size_t count,
              const Vec3d& n, double cutoff) {
  double m = std::numeric_limits<double>::infinity();
  for (size_t k = 0; k < count; ++k) {
    const Vec3d& q = normals[idx[k]];
    const double s = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
    if (s < m) {
      m = s;
      if (m <= cutoff) return m;
    }
  }
  return m;
}
} // namespace

Vec3d SphereSampling::maxMinDirectionBruteForce(const std::vector<Vec3d>& normals,
                                                       const std::uint32_t* idx, size_t count,
                                                       double* minDotOut) const {
  double best = -std::numeric_limits<double>::infinity();
  Vec3d bestDir(0, 0, 1);
  for (size_t i = 0; i < size(); ++i) {
    const Vec3d n = direction(i);
    const double m = minDot(normals, idx, count, n, -std::numeric_limits<double>::infinity());
    if (m > best) best = m, bestDir = n;
  }
  if (minDotOut != nullptr) *minDotOut = best;
  return bestDir;
}

Vec3d SphereSampling::maxMinDirection(const std::vector<Vec3d>& normals, const std::uint32_t* idx,
                                             size_t count, double* minDotOut) const {
  // Active set: with f_A(n) = min over a subset A of the normals, f <= f_A everywhere; so when the
  // argmax c of f_A over S_F has f(c) = f_A(c), c is the argmax of f as well. Start from the
  // normal least aligned with the mean, add the normals that are worse at c, repeat. The search
  // over S_F then runs on a handful of normals instead of all of the box's.
  if (count == 0) {
    if (minDotOut != nullptr) *minDotOut = 1;
    return Vec3d(0, 0, 1);
  }
  if (count <= 8) return branchAndBound(normals, idx, count, minDotOut, nullptr);
  std::vector<std::uint32_t>& active = active_;
  active.clear();
  Vec3d mean(0, 0, 0);
  for (size_t k = 0; k < count; ++k) mean += normals[idx[k]];
  // Seed the active set with three far-apart normals: the one least aligned with the mean, the
  // one least aligned with it, and the one least aligned with those two (a guess at the normals
  // that span the optimal cap; the loop below adds whatever else is needed).
  auto leastAligned = [&](const Vec3d& dir) {
    size_t best = 0;
    double bestDot = normals[idx[0]] * dir;
    for (size_t k = 1; k < count; ++k) {
      const double dot = normals[idx[k]] * dir;
      if (dot < bestDot) bestDot = dot, best = k;
    }
    return idx[best];
  };
  const std::uint32_t a = leastAligned(mean);
  const std::uint32_t b = leastAligned(normals[a]);
  const std::uint32_t c3 = leastAligned(normals[a] + normals[b]);
  active.push_back(a);
  if (b != a) active.push_back(b);
  if (c3 != a && c3 != b) active.push_back(c3);
  Vec3d c(0, 0, 0);
  for (bool warm = false;; warm = true) {
    double v = 0;
    c = branchAndBound(normals, active.data(), active.size(), &v, warm ? &c : nullptr);
    // The (at most 3) normals of the box that are worse than v at c.
    std::uint32_t worst[3];
    double worstDot[3];
    int nWorst = 0;
    for (size_t k = 0; k < count; ++k) {
      const double dot = normals[idx[k]] * c;
      if (!(dot < v)) continue;
      int pos = nWorst < 3 ? nWorst++ : 3;
      while (pos > 0 && worstDot[pos - 1] > dot) {
        if (pos < 3) worst[pos] = worst[pos - 1], worstDot[pos] = worstDot[pos - 1];
        --pos;
      }
      if (pos < 3) worst[pos] = idx[k], worstDot[pos] = dot;
    }
    if (nWorst == 0) {
      if (minDotOut != nullptr) *minDotOut = v;
      return c;
    }
    for (int k = 0; k < nWorst; ++k) active.push_back(worst[k]);
  }
}

bool SphereSampling::sumLeaf(const std::vector<Vec3d>& normals, const std::uint32_t* idx, size_t count,
                             Vec3d& dir) const {
  Vec3d m(0, 0, 0);
  for (size_t k = 0; k < count; ++k) m += normals[idx[k]];
  int axis = 0;
  for (int a = 1; a < 3; ++a)
    if (std::abs(m[a]) > std::abs(m[axis])) axis = a;
  if (!(std::abs(m[axis]) > 0)) return false;
  const int face = 2 * axis + (m[axis] > 0 ? 0 : 1);
  const double inv = 1.0 / std::abs(m[axis]);
  const std::uint32_t cells = std::uint32_t(1) << level_;
  auto leaf = [&](double t) {
    const double f = (t * inv + 1.0) * 0.5 * double(cells);
    return static_cast<std::uint32_t>(std::min(double(cells - 1), std::max(0.0, std::floor(f))));
  };
  dir = leafCentre(face, leaf(m[(axis + 1) % 3]), leaf(m[(axis + 2) % 3]));
  return true;
}

double SphereSampling::quickLowerBound(const std::vector<Vec3d>& normals, const std::uint32_t* idx,
                                       size_t count) const {
  if (count == 0) return 1; // maxMinDirection's value for no normals
  Vec3d c;
  if (!sumLeaf(normals, idx, count, c)) return -std::numeric_limits<double>::infinity();
  return minDot(normals, idx, count, c, -std::numeric_limits<double>::infinity());
}

Vec3d SphereSampling::branchAndBound(const std::vector<Vec3d>& normals, const std::uint32_t* idx,
                                            size_t count, double* minDotOut, const Vec3d* warm) const {
  // Best-first branch and bound over the quadtree of each cube face. For a cell with centre
  // direction c, every direction n of the cell is within the angle α of c (the largest angle
  // from c to the cell's corners: the angle to c is quasi-convex over the square, so its maximum
  // is at a corner). With θ = angle(n_k, c) for the normal n_k worst at c (<n_k, c> = value(c)),
  // angle(n_k, n) >= θ − α, hence min_k <n_k, n> <= cos(max(0, θ − α)) for every n of the cell:
  // a bound that is tight near the optimum, so few cells per level survive. Exact over S_F.
  std::vector<Cell>& heap = heap_;
  heap.clear();
  double best = -std::numeric_limits<double>::infinity();
  Vec3d bestDir(0, 0, 1);
  // The normal that decided the last evaluation is tried first: it usually decides the next one
  // too, so the cut-off is hit after a few products.
  size_t hint = 0;
  auto value = [&](const Vec3d& n, double cutoff) {
    const Vec3d& q0 = normals[idx[hint]];
    double m = q0[0] * n[0] + q0[1] * n[1] + q0[2] * n[2];
    if (m <= cutoff) return m;
    for (size_t k = 0; k < count; ++k) {
      const Vec3d& q = normals[idx[k]];
      const double s = q[0] * n[0] + q[1] * n[1] + q[2] * n[2];
      if (s < m) {
        m = s;
        hint = k;
        if (m <= cutoff) return m;
      }
    }
    return m;
  };

  // A good first guess: the leaf holding the direction of the summed normals.
  {
    Vec3d c;
    if (sumLeaf(normals, idx, count, c)) {
      best = value(c, -std::numeric_limits<double>::infinity());
      bestDir = c;
    }
  }
  // The caller's guess (the previous answer of the active-set loop), when it is better.
  if (warm != nullptr) {
    const double v = value(*warm, best);
    if (v > best) best = v, bestDir = *warm;
  }

  double sinBestOf = std::numeric_limits<double>::quiet_NaN(), sinBest = 0; // sqrt(1 − best²), cached
  auto push = [&](int face, int depth, std::uint32_t x, std::uint32_t y) {
    const bool leaf = depth == level_;
    const CellInfo* info = leaf ? nullptr : &tables_->cell[cellIndex(face, depth, x, y)];
    const Vec3d c = leaf ? leafCentre(face, x, y) : info->centre;
    const double ca = leaf ? 1.0 : info->cosAlpha, sa = leaf ? 0.0 : info->sinAlpha;
    // value(c) <= cutoff = cos(min(π, acos(best) + α)) means cos(max(0, θ − α)) <= best.
    if (best != sinBestOf) sinBestOf = best, sinBest = std::sqrt(std::max(0.0, 1 - best * best));
    double cutoff;
    if (best >= 1) cutoff = 2.0;
    else if (best < -ca) cutoff = -1.0; // acos(best) + α > π
    else cutoff = best * ca - sinBest * sa;
    const double v = value(c, cutoff);
    if (v <= cutoff) return;
    if (depth == level_) {
      if (v > best) best = v, bestDir = c;
      return;
    }
    const double bound = v >= ca ? 1.0 : v * ca + std::sqrt(std::max(0.0, 1 - v * v)) * sa; // cos(θ − α)
    heap.push_back(Cell{bound, face, depth, x, y});
    std::push_heap(heap.begin(), heap.end());
  };

  for (int f = 0; f < 6; ++f) push(f, 0, 0, 0);
  while (!heap.empty()) {
    std::pop_heap(heap.begin(), heap.end());
    const Cell cell = heap.back();
    heap.pop_back();
    if (cell.bound <= best) break; // best-first: nothing left can improve
    for (int k = 0; k < 4; ++k)
      push(cell.face, cell.depth + 1, 2 * cell.x + std::uint32_t(k & 1), 2 * cell.y + std::uint32_t(k >> 1));
  }
  if (minDotOut != nullptr) *minDotOut = best;
  return bestDir;
}

// ---------------------------------------------------------------------------------------------
// Normal filter (sec. 4.1)

namespace {
// The points whose normals face `dir` (<n_p, dir> >= 0) moved to the front of idx, in order;
// the others after them, in order, when `rest` is given (else dropped). Returns how many face it.
size_t keepFacing(const std::vector<Vec3d>& normals, std::uint32_t* idx, size_t count, const Vec3d& dir,
                  std::vector<std::uint32_t>* rest) {
  if (rest != nullptr) rest->clear();
  size_t w = 0;
  for (size_t k = 0; k < count; ++k) {
    if (normals[idx[k]] * dir >= 0) idx[w++] = idx[k];
    else if (rest != nullptr) rest->push_back(idx[k]);
  }
  if (rest != nullptr) std::copy(rest->begin(), rest->end(), idx + w);
  return w;
}
} // namespace

size_t filterBoxNormals(const std::vector<Vec3d>& normals, std::uint32_t* idx, size_t count,
                        double threshold) {
  Vec3d sum(0, 0, 0);
  for (size_t k = 0; k < count; ++k) sum += normals[idx[k]];
  if (sum.Norm() < threshold) return count;
  return keepFacing(normals, idx, count, sum, nullptr);
}

BoxLayers filterOrSplitBox(const std::vector<Vec3d>& normals, std::uint32_t* idx, size_t count,
                           std::vector<std::uint32_t>& scratch, double threshold) {
  BoxLayers r;
  r.firstEnd = count;
  Vec3d sum(0, 0, 0);
  for (size_t k = 0; k < count; ++k) sum += normals[idx[k]];
  Vec3d dir = sum;
  const bool cancel = sum.Norm() < threshold;
  if (cancel) {
    // The normals cancel: the axis they spread along most (power iteration on Σ n nᵀ, from the
    // coordinate axis of its largest diagonal entry).
    double m[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
    for (size_t k = 0; k < count; ++k) {
      const Vec3d& n = normals[idx[k]];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) m[i][j] += n[i] * n[j];
    }
    int a = 0;
    for (int i = 1; i < 3; ++i)
      if (m[i][i] > m[a][a]) a = i;
    dir = Vec3d(0, 0, 0);
    dir[a] = 1;
    for (int it = 0; it < 16; ++it) {
      Vec3d next(0, 0, 0);
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) next[i] += m[i][j] * dir[j];
      const double len = next.Norm();
      if (!(len > 0)) return r; // no normals: all kept
      dir = next / len;
    }
  }
  size_t other = 0;
  for (size_t k = 0; k < count; ++k) other += normals[idx[k]] * dir < 0 ? 1 : 0;
  r.twoSided = other >= kTwoSidedMinPoints && double(other) >= BoxGrid::kOpposedShare * double(count);
  if (other == 0 || (cancel && !r.twoSided)) return r; // nothing to drop, or the paper keeps all
  r.firstEnd = keepFacing(normals, idx, count, dir, r.twoSided ? &scratch : nullptr);
  r.split = dir;
  return r;
}

// ---------------------------------------------------------------------------------------------
// Box grid

namespace {
// The S_F of the box normals, built once per process (its tables take about a millisecond);
// every build copies it (sharing the tables) for its own scratch.
const SphereSampling& boxNormalSampling() {
  static const SphereSampling sampling(6);
  return sampling;
}
} // namespace

size_t BoxGrid::memoryBytes() const {
  return hash_.memoryBytes() + start_.capacity() * sizeof(std::uint32_t) +
         points_.capacity() * sizeof(std::uint32_t) + normalCode_.capacity() * sizeof(std::uint16_t) +
         minDot_.capacity() * sizeof(float) + normalCode_.size() * sizeof(std::atomic<std::uint8_t>) + pending_.capacity() * sizeof(std::uint32_t) +
         twin_.capacity() * sizeof(std::int32_t) + split_.capacity() * sizeof(Vec3d) +
         pendingCorner_.capacity() * sizeof(Vec3d) + flags_.capacity() +
         ownStart_.capacity() * sizeof(std::uint32_t) + ownPoints_.capacity() * sizeof(std::uint32_t) +
         far_.capacity() * sizeof(far_[0]) +
         gatheredIds_.memoryBytes() + gathered_.capacity() * sizeof(Gathered) + gatheredReferences_ * sizeof(std::uint32_t);
}

void BoxGrid::release() {
  stopNormals();
  hash_ = BoxIdIndex();
  std::vector<std::uint32_t>().swap(start_);
  HugeVector<std::uint32_t>().swap(points_);
  std::vector<std::int32_t>().swap(twin_);
  std::vector<Vec3d>().swap(split_);
  layerBoxes_ = 0;
  std::vector<std::uint16_t>().swap(normalCode_);
  std::vector<float>().swap(minDot_);
  state_.reset();
  std::vector<std::uint8_t>().swap(flags_);
  std::vector<std::uint32_t>().swap(pending_);
  std::vector<Vec3d>().swap(pendingCorner_);
  std::vector<std::uint32_t>().swap(ownStart_);
  HugeVector<std::uint32_t>().swap(ownPoints_);
  listOrder_ = nullptr;
  std::vector<std::pair<std::uint32_t, double>>().swap(far_);
  gatheredIds_ = KeyHash();
  std::vector<Gathered>().swap(gathered_);
  gatheredReferences_ = 0;
  built_ = 0;
  lazy_ = false;
}

bool BoxGrid::refers(const Vec3d& p, double reach, std::int64_t x, std::int64_t y, std::int64_t z) const {
  const double side = index_.side(), r2 = reach == side ? side * side : reach * reach;
  const std::int64_t c[3] = {x, y, z};
  double sq[3];
  for (int a = 0; a < 3; ++a) {
    const std::int64_t lo = index_.coord(p[a] - reach, a);
    const std::int64_t hi = std::min(index_.coord(p[a] + reach, a), lo + kSpan - 1);
    if (c[a] < lo || c[a] > hi) return false;
    const double l = index_.origin()[a] + double(c[a]) * side;
    const double v = p[a] < l ? l - p[a] : (p[a] > l + side ? p[a] - l - side : 0.0);
    sq[a] = v * v;
  }
  const double sxy = sq[0] + sq[1];
  return !(sxy > r2) && !(sxy + sq[2] > r2);
}

int BoxGrid::gatheredBox(KeyHash::Key k) const {
  const int known = gatheredIds_.find(k);
  if (known >= 0) return known == kNoBox ? -1 : known;
  const std::int64_t mask = BoxIndexer::kMax;
  const std::int64_t x = std::int64_t(k >> (2 * BoxIndexer::kBits)) & mask,
                     y = std::int64_t(k >> BoxIndexer::kBits) & mask, z = std::int64_t(k) & mask;
  // The points that refer to the box: those of reach `side` lie in the own boxes within two of it
  // (one, but for rounding at the faces), those of a larger reach are tried one by one.
  std::vector<std::uint32_t> found; // list positions
  auto pointAt = [&](std::uint32_t t) { return listOrder_ != nullptr ? (*listOrder_)[t] : t; };
  for (std::int64_t ox = x - 2; ox <= x + 2; ++ox)
    for (std::int64_t oy = y - 2; oy <= y + 2; ++oy)
      for (std::int64_t oz = z - 2; oz <= z + 2; ++oz) {
        if (!BoxIndexer::valid(ox, oy, oz)) continue;
        const int o = hash_.find(BoxIndexer::pack(ox, oy, oz));
        if (o < 0 || size_t(o) + 1 >= ownStart_.size()) continue;
        for (std::uint32_t j = ownStart_[size_t(o)]; j < ownStart_[size_t(o) + 1]; ++j)
          if (refers((*points3_)[pointAt(ownPoints_[j])], index_.side(), x, y, z)) found.push_back(ownPoints_[j]);
      }
  for (const auto& f : far_)
    if (refers((*points3_)[pointAt(f.first)], f.second, x, y, z)) found.push_back(f.first);
  if (found.empty()) {
    gatheredIds_.findOrInsert(k, kNoBox);
    return -1;
  }
  std::sort(found.begin(), found.end());
  std::vector<std::uint32_t> idx(found.size()), scratch;
  for (size_t j = 0; j < found.size(); ++j) idx[j] = pointAt(found[j]);
  // Sec. 4.1 as build() does it: the filter or the two layers, each layer's normal.
  const BoxLayers layers = filterOrSplitBox(*normals_, idx.data(), idx.size(), scratch);
  const int id = int(built_ + gathered_.size());
  auto addLayer = [&](size_t begin, size_t end) {
    Gathered g;
    g.points.assign(idx.begin() + std::ptrdiff_t(begin), idx.begin() + std::ptrdiff_t(end));
    double minDot = 0;
    const Vec3d n = sampling_.maxMinDirection(*normals_, g.points.data(), g.points.size(), &minDot);
    g.normalCode = sampling_.code(n);
    g.minDot = float(minDot);
    if (minDot < 0 && !(g.minDot < 0)) g.minDot = -std::numeric_limits<float>::denorm_min();
    g.flags = layers.twoSided && begin == 0 ? kOpposed : 0; // as build(): the first layer only
    gatheredReferences_ += g.points.size();
    gathered_.push_back(std::move(g));
  };
  addLayer(0, layers.firstEnd);
  if (layers.twoSided) {
    addLayer(layers.firstEnd, idx.size());
    gathered_[size_t(id) - built_].twin = id + 1;
    gathered_[size_t(id) + 1 - built_].twin = id;
    gathered_[size_t(id) + 1 - built_].split = layers.split;
  }
  gatheredIds_.findOrInsert(k, id);
  return id;
}

void BoxGrid::storeNormal(size_t b, const Vec3d& normal, double minDot) const {
  normalCode_[b] = sampling_.code(normal);
  float m = float(minDot);
  if (minDot < 0 && !(m < 0)) m = -std::numeric_limits<float>::denorm_min();
  minDot_[b] = m;
}

void BoxGrid::computeNormal(int box, const SphereSampling& sampling) const {
  const size_t b = size_t(box);
  std::uint8_t expected = kNone;
  if (state_[b].compare_exchange_strong(expected, kBusy, std::memory_order_acq_rel)) {
    double minDot = 0;
    const Vec3d n = sampling.maxMinDirection(*normals_, pointsBegin(box), pointCount(box), &minDot);
    storeNormal(b, n, minDot);
    if (flags_[b] == kCounted && minDot < 0) ++dTooLargeCount_;
    state_[b].store(kDone, std::memory_order_release);
    return;
  }
  while (state_[b].load(std::memory_order_acquire) != kDone) std::this_thread::yield(); // the other thread's
}

void BoxGrid::startNormals(int threads, const Vec3d& from) {
  stopNormals();
  if (pending_.empty() || parallelParts(pending_.size(), threads, 64) < 2) return;
  // Nearest boxes first (by their lower corners; ties by id).
  {
    std::vector<std::pair<double, std::uint32_t>> order(pending_.size());
    for (size_t k = 0; k < pending_.size(); ++k) order[k] = {(pendingCorner_[k] - from).SquaredNorm(), pending_[k]};
    std::sort(order.begin(), order.end());
    for (size_t k = 0; k < order.size(); ++k) pending_[k] = order[k].second;
    std::vector<Vec3d>().swap(pendingCorner_);
  }
  // The copy (own scratch) is made here: once started, the caller may use sampling_.
  // After the deferred boxes, the others in id order until finishNormals() stops it: the caller
  // asks for some of them too (the boxes without a point that the surface passes through: a
  // quarter of the normals the growth needed on the 30k torus at 2.5 spacings), and this thread
  // has nothing else to do meanwhile.
  background_ = std::thread([this, sampling = SphereSampling(sampling_)] {
    for (const std::uint32_t b : pending_) {
      if (stop_.load(std::memory_order_relaxed)) return;
      if (state_[b].load(std::memory_order_acquire) == kNone) computeNormal(int(b), sampling);
    }
    for (size_t b = 0; b < normalCode_.size(); ++b) {
      if (stop_.load(std::memory_order_relaxed)) return;
      if (state_[b].load(std::memory_order_acquire) == kNone) computeNormal(int(b), sampling);
    }
  });
}

void BoxGrid::stopNormals() {
  if (!background_.joinable()) return;
  stop_ = true;
  background_.join();
  stop_ = false; // a later startNormals() runs again
}

void BoxGrid::finishNormals() {
  stopNormals(); // the deferred boxes it has not done yet are done here
  for (const std::uint32_t b : pending_)
    if (state_[b].load(std::memory_order_acquire) != kDone) computeNormal(int(b), sampling_);
  std::vector<std::uint32_t>().swap(pending_);
  std::vector<Vec3d>().swap(pendingCorner_);
}

// build()'s passes over the points and the boxes, with their working arrays.
class BoxGrid::Builder {
public:
  Builder(BoxGrid& g, const std::vector<Vec3d>& pts, const std::vector<Vec3d>& normals, double side,
          Progress* progress, int threads, const std::vector<std::uint32_t>* listOrder,
          const std::vector<float>* extraReach, const std::vector<float>* splatRadius)
      : g_(g), pts_(pts), normals_(normals), side_(side), d2_(side * side), n_(pts.size()), progress_(progress),
        threads_(threads), listOrder_(listOrder), extraReach_(extraReach), splatRadius_(splatRadius) {}
  // The index's origin and box side, checked against the cloud's extent.
  void placeIndex();
  // The own box of every point, with its coordinates.
  void ownBoxes();
  // Pass 0: the boxes within reach of each point, as a mask of its own box's 27 neighbours.
  void reachMasks();
  // Pass 1: the ids of the boxes built, in order of first appearance.
  void assignIds();
  // Pass 2: references to them counted per part, CSR offsets.
  void countReferences();
  // The index of the points by their own boxes, for the boxes gathered later (lazy grids).
  void keepOwnIndex();
  // Pass 3: the references filled in, points in list order inside each box.
  void fillReferences();
  // Sec. 4.1: the normal filter and the box normals, per box; then the lists compacted.
  void filterAndNormals(const std::vector<Vec3d>& normals, bool deferNormals);
  // The boxes holding input points, their normals left for startNormals() / finishNormals().
  void deferOwnBoxes();

private:
  static constexpr std::uint32_t kBeyond = std::uint32_t(1) << 31;
  // The reach of point i: side, or side + extraReach[i] (at most kMaxExtraReach·side more).
  double reachOf(size_t i) const {
    if (extraReach_ == nullptr || !((*extraReach_)[i] > 0)) return side_;
    return side_ + std::min(double((*extraReach_)[i]), kMaxExtraReach * side_);
  }
  // Per axis the boxes within reach of p and the squared distance of p to each slab (the terms
  // of squaredDistanceToBox, in the same order, so the test is the same to the last bit).
  void slabs(const Vec3d& p, double reach, std::int64_t lo[3], std::int64_t hi[3], double sq[3][kSpan]) const {
    for (int a = 0; a < 3; ++a) {
      lo[a] = g_.index_.coord(p[a] - reach, a);
      hi[a] = std::min(g_.index_.coord(p[a] + reach, a), lo[a] + kSpan - 1);
      for (std::int64_t c = lo[a]; c <= hi[a]; ++c) {
        const double l = g_.index_.origin()[a] + double(c) * side_;
        const double v = p[a] < l ? l - p[a] : (p[a] > l + side_ ? p[a] - l - side_ : 0.0);
        sq[a][c - lo[a]] = v * v;
      }
    }
  }
  // The boxes within distance reachOf(i) of point i: every box of the slabs' block whose
  // distance is within reach, in the order x, y, z. Calls f(x, y, z) for each (at most 27 for
  // reach = side).
  template <class F>
  void forBoxesWithin(size_t i, F&& f) const {
    std::int64_t lo[3], hi[3];
    double sq[3][kSpan];
    const double reach = reachOf(i), r2 = reach == side_ ? d2_ : reach * reach;
    slabs(pts_[i], reach, lo, hi, sq);
    for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
      for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
        const double sxy = sq[0][x - lo[0]] + sq[1][y - lo[1]];
        if (sxy > r2) continue;
        for (std::int64_t z = lo[2]; z <= hi[2]; ++z)
          if (!(sxy + sq[2][z - lo[2]] > r2)) f(x, y, z);
      }
  }
  size_t listed(size_t t) const { return listOrder_ != nullptr ? size_t((*listOrder_)[t]) : t; }
  // Whether point i's splat (its disk) meets box (x, y, z): the box within the splat's radius of
  // the point and across its plane, with a margin for rounding (a box a disk only grazes may be
  // built or gathered: the same either way). Every box when the grid is not lazy.
  bool touches(size_t i, std::int64_t x, std::int64_t y, std::int64_t z) const {
    if (splatRadius_ == nullptr) return true;
    const double r = std::min(double((*splatRadius_)[i]), reachOf(i));
    const Vec3d lo = g_.index_.corner(x, y, z);
    if (squaredDistanceToBox(pts_[i], lo, side_) > r * r * (1 + 1e-9) + kTouchMargin * side_ * side_) return false;
    const Vec3d& n = normals_[i];
    // The disk's bounding box: r·sqrt(1 − n_a²) from p along axis a.
    for (int a = 0; a < 3; ++a) {
      const double e = r * std::sqrt(std::max(0.0, 1 - n[a] * n[a])) * (1 + 1e-9) + kTouchMargin * side_;
      if (lo[a] > pts_[i][a] + e || lo[a] + side_ < pts_[i][a] - e) return false;
    }
    const Vec3d c = lo + Vec3d(0.5 * side_, 0.5 * side_, 0.5 * side_);
    const double h = std::abs((c - pts_[i]) * n);
    return h <= 0.5 * side_ * (std::abs(n[0]) + std::abs(n[1]) + std::abs(n[2])) * (1 + 1e-9) + kTouchMargin * side_;
  }
  static constexpr double kTouchMargin = 1e-7;
  static constexpr std::int32_t kNotBuilt = -2; // a near_ slot of a box within reach not built

  BoxGrid& g_;
  const std::vector<Vec3d>& pts_;
  const std::vector<Vec3d>& normals_;
  const double side_, d2_;
  const size_t n_;
  Progress* const progress_;
  const int threads_;
  const std::vector<std::uint32_t>* const listOrder_;
  const std::vector<float>* const extraReach_;
  const std::vector<float>* const splatRadius_;
  std::vector<std::uint32_t> ownOf_;  // own box of each point (by list position after pass 0)
  HugeVector<std::uint32_t> touch_;   // pass 0's masks of the boxes the splats meet (lazy grids)
  std::vector<std::int64_t> ownCoord_; // 3 per own box
  std::vector<std::int32_t> near_;     // box ids of the 27 neighbours of each own box, lazily
  HugeVector<std::uint32_t> mask_;    // pass 0's masks, by list position
  int fillParts_ = 1;
  std::vector<std::vector<std::uint32_t>> count_; // [part][box]
  size_t boxes_ = 0;
  std::vector<std::uint8_t> eager_;  // boxes holding an input point: normals computed first
  std::vector<std::int32_t> ownBox_; // box id of each own box
};

void BoxGrid::Builder::placeIndex() {
  Vec3d lo = pts_[0], hi = pts_[0];
  for (const auto& p : pts_)
    for (int a = 0; a < 3; ++a) lo[a] = std::min(lo[a], p[a]), hi[a] = std::max(hi[a], p[a]);
  const double extent = std::max(hi[0] - lo[0], std::max(hi[1] - lo[1], hi[2] - lo[2]));
  if (extent > maxExtent(side_)) {
    // The sphere packer leaves far points out before (leaveOutFarPoints), so only a direct caller
    // gets here.
    std::ostringstream s;
    s << "The sphere diameter d = " << side_ << " is too small for points spread over " << extent
      << ": the box grid indexes at most " << BoxIndexer::kMax << " boxes of side d per axis (this needs "
      << extent / side_ << "); d must be at least " << extent / (maxExtent(side_) / side_) << " here.";
    throw Error(s.str());
  }
  // A margin of whole boxes below the points: the farthest reach (side + kMaxExtraReach·side)
  // stays at non-negative box coordinates.
  const double margin = (kMaxExtraReach + 2) * side_;
  g_.index_ = BoxIndexer(lo - Vec3d(margin, margin, margin), side_);
}

void BoxGrid::Builder::ownBoxes() {
  // The boxes near a point are its own box and its 26 neighbours: their ids are looked up once per
  // own box (shared by the ~(d/spacing)² points in it), not once per point.
  KeyHash own(pts_.size() / 16 + 16);
  // The working arrays below are written whole soon after they are allocated: they are made
  // resident in one call each (assignHuge, huge_pages.h), not page by page.
  assignHuge(ownOf_, pts_.size(), 0u);
  for (size_t i = 0; i < pts_.size(); ++i) {
    const std::int64_t x = g_.index_.coord(pts_[i][0], 0), y = g_.index_.coord(pts_[i][1], 1),
                       z = g_.index_.coord(pts_[i][2], 2);
    const int id = own.findOrInsert(BoxIndexer::pack(x, y, z), static_cast<int>(ownCoord_.size() / 3));
    if (size_t(id) * 3 == ownCoord_.size()) ownCoord_.insert(ownCoord_.end(), {x, y, z});
    ownOf_[i] = static_cast<std::uint32_t>(id);
  }
  assignHuge(near_, ownCoord_.size() / 3 * 27, std::int32_t(-1));
}

// Per point, on threads taking chunks: bit (dx + 1)·9 + (dy + 1)·3 + (dz + 1) of the mask for the
// offsets -1..1 from the point's own box, so increasing bits are the order x, y, z; kBeyond when
// the boxes in reach are not all in that block (rounding at a box face: such points take the
// general path below). The same slabs and tests as forBoxesWithin. Both are stored at the point's
// position in the list order (passes 1 and 2 read them in that order, sequentially).
void BoxGrid::Builder::reachMasks() {
  const size_t n = n_;
  const std::vector<std::uint32_t>* listOrder = listOrder_;
  mask_.resize(n);
  if (splatRadius_ != nullptr) touch_.resize(n);
  HugeVector<std::uint32_t> listPos;
  if (listOrder != nullptr) {
    listPos.resize(n);
    for (size_t t = 0; t < n; ++t) listPos[(*listOrder)[t]] = static_cast<std::uint32_t>(t);
  }
  std::vector<std::uint32_t> ownAt; // own box, by list position
  assignHuge(ownAt, listOrder != nullptr ? n : 0, 0u);
  parallelChunks(n, parallelParts(n, threads_, 8192), 1024, [&](size_t i0, size_t i1, int) {
    for (size_t i = i0; i < i1; ++i) {
      const size_t at = listOrder != nullptr ? listPos[i] : i;
      if (listOrder != nullptr) ownAt[at] = ownOf_[i];
      const std::int64_t* oc = &ownCoord_[size_t(ownOf_[i]) * 3];
      if (reachOf(i) != side_) { // a large splat: the general path
        mask_[at] = kBeyond;
        continue;
      }
      std::int64_t lo[3], hi[3];
      double sq[3][kSpan];
      slabs(pts_[i], side_, lo, hi, sq);
      bool inBlock = true;
      for (int a = 0; a < 3; ++a) inBlock = inBlock && lo[a] >= oc[a] - 1 && hi[a] <= oc[a] + 1;
      if (!inBlock) {
        mask_[at] = kBeyond;
        continue;
      }
      // The disk test of touches(), by axis: the box's slab against the disk's bounding box, its
      // share of the centre's height over the plane, and the distance terms above.
      bool ok[3][3] = {{true, true, true}, {true, true, true}, {true, true, true}};
      double hterm[3][3] = {{0, 0, 0}, {0, 0, 0}, {0, 0, 0}};
      double r2 = 0, hb = 0;
      if (splatRadius_ != nullptr) {
        const double r = std::min(double((*splatRadius_)[i]), side_);
        const Vec3d& nn = normals_[i];
        r2 = r * r * (1 + 1e-9) + kTouchMargin * side_ * side_;
        hb = 0.5 * side_ * (std::abs(nn[0]) + std::abs(nn[1]) + std::abs(nn[2])) * (1 + 1e-9) + kTouchMargin * side_;
        for (int a = 0; a < 3; ++a) {
          const double e = r * std::sqrt(std::max(0.0, 1 - nn[a] * nn[a])) * (1 + 1e-9) + kTouchMargin * side_;
          for (std::int64_t k = lo[a]; k <= hi[a]; ++k) {
            const double l = g_.index_.origin()[a] + double(k) * side_;
            ok[a][k - lo[a]] = !(l > pts_[i][a] + e || l + side_ < pts_[i][a] - e);
            hterm[a][k - lo[a]] = nn[a] * (l + 0.5 * side_ - pts_[i][a]);
          }
        }
      }
      std::uint32_t m = 0, touched = 0;
      for (std::int64_t x = lo[0]; x <= hi[0]; ++x)
        for (std::int64_t y = lo[1]; y <= hi[1]; ++y) {
          const double sxy = sq[0][x - lo[0]] + sq[1][y - lo[1]];
          if (sxy > d2_) continue;
          const int base = int((x - oc[0] + 1) * 9 + (y - oc[1] + 1) * 3 - oc[2] + 1);
          const bool okxy = ok[0][x - lo[0]] && ok[1][y - lo[1]];
          const double hxy = hterm[0][x - lo[0]] + hterm[1][y - lo[1]];
          for (std::int64_t z = lo[2]; z <= hi[2]; ++z) {
            const double s = sxy + sq[2][z - lo[2]];
            if (s > d2_) continue;
            m |= std::uint32_t(1) << (base + int(z));
            if (splatRadius_ != nullptr && okxy && ok[2][z - lo[2]] && s <= r2 && std::abs(hxy + hterm[2][z - lo[2]]) <= hb)
              touched |= std::uint32_t(1) << (base + int(z));
          }
        }
      mask_[at] = m;
      if (splatRadius_ != nullptr) touch_[at] = touched;
    }
  });
  if (listOrder != nullptr) {
    ownOf_.swap(ownAt);
    std::vector<std::uint32_t>().swap(ownAt);
  }
}

// In list order: the ids of the boxes built (all boxes within reach of a point, or of a lazy grid
// those a splat meets) in order of first appearance (deterministic). The ids of the 27 boxes around
// an own box are kept (near_), so the hash is asked once per own box and offset, not once per point.
void BoxGrid::Builder::assignIds() {
  const size_t n = n_;
  for (size_t i = 0; i < n; ++i) g_.facePoints_ += (mask_[i] & kBeyond) ? 1 : 0;
  int boxes = 0;
  auto newId = [&](std::int64_t x, std::int64_t y, std::int64_t z) {
    const int id = g_.hash_.findOrInsert(BoxIndexer::pack(x, y, z), boxes);
    if (id == boxes) ++boxes;
    return id;
  };
  // Sized for five boxes per own box (3-6 on scans and generated clouds at the usual d, more where
  // splats reach far; about two where only the boxes the splats meet are built): growing the table
  // moves every box to a random slot again, which on large clouds costs more than the counting.
  g_.hash_.reset((splatRadius_ != nullptr ? 2 : 5) * (ownCoord_.size() / 3) + 16);
  for (size_t t = 0; t < n; ++t) {
    const std::uint32_t o = ownOf_[t];
    const std::int64_t* oc = &ownCoord_[size_t(o) * 3];
    std::int32_t* slots = &near_[size_t(o) * 27];
    if (mask_[t] & kBeyond) {
      const size_t i = listed(t);
      forBoxesWithin(i, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
        if (!touches(i, x, y, z)) return;
        const std::int64_t dx = x - oc[0], dy = y - oc[1], dz = z - oc[2];
        std::int32_t* slot = nullptr;
        if (dx >= -1 && dx <= 1 && dy >= -1 && dy <= 1 && dz >= -1 && dz <= 1)
          slot = &slots[(dx + 1) * 9 + (dy + 1) * 3 + (dz + 1)];
        if (slot == nullptr || *slot < 0) {
          const int id = newId(x, y, z);
          if (slot != nullptr) *slot = id;
        }
      });
    } else {
      for (std::uint32_t m = splatRadius_ != nullptr ? touch_[t] : mask_[t]; m != 0; m &= m - 1) {
        const int bit = __builtin_ctz(m);
        if (slots[bit] < 0) slots[bit] = newId(oc[0] + bit / 9 - 1, oc[1] + (bit / 3) % 3 - 1, oc[2] + bit % 3 - 1);
      }
    }
    if (progress_ != nullptr && (t & 16383) == 0) progress_->advanceTo(0.15 * double(t) / double(n));
  }
  boxes_ = size_t(boxes);
  HugeVector<std::uint32_t>().swap(touch_);
  // The other slots around each own box: the id of the box when it is built, else kNotBuilt (the
  // passes after this one then only read the slots, and run on threads).
  const size_t owns = ownCoord_.size() / 3;
  parallelChunks(owns, parallelParts(owns, threads_, 4096), 1024, [&](size_t o0, size_t o1, int) {
    for (size_t o = o0; o < o1; ++o) {
      const std::int64_t* oc = &ownCoord_[o * 3];
      std::int32_t* slots = &near_[o * 27];
      for (int bit = 0; bit < 27; ++bit)
        if (slots[bit] == -1) {
          const int id = g_.hash_.find(BoxIndexer::pack(oc[0] + bit / 9 - 1, oc[1] + (bit / 3) % 3 - 1, oc[2] + bit % 3 - 1));
          slots[bit] = id < 0 ? kNotBuilt : id;
        }
    }
  });
}

void BoxGrid::Builder::keepOwnIndex() {
  if (splatRadius_ == nullptr) return;
  g_.lazy_ = true;
  g_.points3_ = &pts_;
  g_.listOrder_ = listOrder_;
  // By the id of each own box (a point's own box is always built: its splat meets it), the list
  // positions of its points of reach `side`; the others (and any point whose own box was not
  // built) are tried one by one.
  const size_t n = n_;
  auto ownId = [&](size_t t) { return near_[size_t(ownOf_[t]) * 27 + 13]; };
  auto general = [&](size_t t) { return reachOf(listed(t)) != side_ || ownId(t) < 0; };
  g_.ownStart_.assign(boxes_ + 1, 0);
  for (size_t t = 0; t < n; ++t)
    if (general(t)) g_.far_.emplace_back(std::uint32_t(t), reachOf(listed(t)));
    else ++g_.ownStart_[size_t(ownId(t)) + 1];
  for (size_t b = 0; b < boxes_; ++b) g_.ownStart_[b + 1] += g_.ownStart_[b];
  g_.ownPoints_.resize(g_.ownStart_[boxes_]);
  std::vector<std::uint32_t> at(g_.ownStart_.begin(), g_.ownStart_.end() - 1);
  for (size_t t = 0; t < n; ++t)
    if (!general(t)) g_.ownPoints_[at[size_t(ownId(t))]++] = std::uint32_t(t);
}

// Per part of the points of pass 3 (in list order), on threads: the references to the boxes built
// counted.
void BoxGrid::Builder::countReferences() {
  const size_t n = n_;
  fillParts_ = parallelParts(n, threads_, 8192);
  auto& count = count_;
  count.assign(static_cast<size_t>(fillParts_), std::vector<std::uint32_t>(boxes_, 0));
  parallelFor(n, fillParts_, [&](size_t t0, size_t t1, int part) {
    std::vector<std::uint32_t>& cnt = count[size_t(part)];
    for (size_t t = t0; t < t1; ++t) {
      const std::uint32_t o = ownOf_[t];
      const std::int32_t* slots = &near_[size_t(o) * 27];
      if (mask_[t] & kBeyond) {
        const std::int64_t* oc = &ownCoord_[size_t(o) * 3];
        forBoxesWithin(listed(t), [&](std::int64_t x, std::int64_t y, std::int64_t z) {
          const std::int64_t dx = x - oc[0], dy = y - oc[1], dz = z - oc[2];
          const int id = dx >= -1 && dx <= 1 && dy >= -1 && dy <= 1 && dz >= -1 && dz <= 1
                             ? slots[(dx + 1) * 9 + (dy + 1) * 3 + (dz + 1)]
                             : g_.hash_.find(BoxIndexer::pack(x, y, z));
          if (id >= 0) ++cnt[size_t(id)];
        });
      } else {
        for (std::uint32_t m = mask_[t]; m != 0; m &= m - 1) {
          const int id = slots[__builtin_ctz(m)];
          if (id >= 0) ++cnt[size_t(id)];
        }
      }
      if (part == 0 && progress_ != nullptr && ((t - t0) & 16383) == 0)
        progress_->advanceTo(0.15 + 0.15 * double(t - t0) / double(t1 - t0));
    }
  });
  boxes_ = count[0].size();
  // CSR offsets; count[part][b] becomes where part `part` writes its first reference in box b.
  assignHuge(g_.start_, boxes_ + 1, 0u);
  for (size_t b = 0; b < boxes_; ++b) {
    std::uint32_t at = g_.start_[b];
    for (auto& c : count) {
      const std::uint32_t k = c[b];
      c[b] = at;
      at += k;
    }
    g_.start_[b + 1] = at;
  }
}

// Per part of the points, on threads (the parts are in list order and write to consecutive ranges
// of each box).
void BoxGrid::Builder::fillReferences() {
  g_.points_.assign(g_.start_[boxes_], 0);
  parallelFor(n_, fillParts_, [&](size_t t0, size_t t1, int part) {
    std::vector<std::uint32_t>& at = count_[size_t(part)];
    for (size_t t = t0; t < t1; ++t) {
      const size_t i = listed(t);
      const std::int32_t* slots = &near_[size_t(ownOf_[t]) * 27];
      const std::uint32_t value = static_cast<std::uint32_t>(i);
      if (mask_[t] & kBeyond) {
        const std::int64_t* oc = &ownCoord_[size_t(ownOf_[t]) * 3];
        forBoxesWithin(i, [&](std::int64_t x, std::int64_t y, std::int64_t z) {
          const std::int64_t dx = x - oc[0], dy = y - oc[1], dz = z - oc[2];
          const int id = dx >= -1 && dx <= 1 && dy >= -1 && dy <= 1 && dz >= -1 && dz <= 1
                             ? slots[(dx + 1) * 9 + (dy + 1) * 3 + (dz + 1)]
                             : g_.hash_.find(BoxIndexer::pack(x, y, z));
          if (id >= 0) g_.points_[at[size_t(id)]++] = value;
        });
      } else {
        for (std::uint32_t m = mask_[t]; m != 0; m &= m - 1) {
          const int id = slots[__builtin_ctz(m)];
          if (id >= 0) g_.points_[at[size_t(id)]++] = value;
        }
      }
      if (part == 0 && progress_ != nullptr && ((t - t0) & 16383) == 0)
        progress_->advanceTo(0.3 + 0.3 * double(t - t0) / double(t1 - t0));
    }
  });
  keepOwnIndex();
  std::vector<std::uint32_t>().swap(ownOf_);
  HugeVector<std::uint32_t>().swap(mask_);
  std::vector<std::vector<std::uint32_t>>().swap(count_);
}

// Independent per box: the boxes are cut into one contiguous part per thread, each box filtered in
// place inside its own CSR range, its kept count, normal and minimum written to its own slots (so
// the result does not depend on the threads). Then the CSR arrays are compacted in box order.
// The box normal is computed here only for the boxes that contain an input point (the vertices
// of the mesh lie on splats, so near the points: nearly all box normals the growth asks for are
// of those boxes), and for the boxes the quick test below cannot clear of "d too large"; the
// others are computed when first asked for (boxNormal()), with the same result.
void BoxGrid::Builder::filterAndNormals(const std::vector<Vec3d>& normals, bool deferNormals) {
  const size_t boxes = boxes_;
  Progress* progress = progress_;
  std::vector<std::uint32_t>& start = g_.start_;
  HugeVector<std::uint32_t>& points = g_.points_;
  assignHuge(g_.normalCode_, boxes, std::uint16_t(SphereSampling::kUpCode));
  assignHuge(g_.minDot_, boxes, std::numeric_limits<float>::quiet_NaN());
  g_.state_.reset(new std::atomic<std::uint8_t>[boxes]);
  prefault(g_.state_.get(), boxes * sizeof(std::atomic<std::uint8_t>));
  for (size_t b = 0; b < boxes; ++b) g_.state_[b].store(kNone, std::memory_order_relaxed);
  assignHuge(g_.flags_, boxes, std::uint8_t(0));
  std::vector<std::uint8_t>& eager = eager_;
  assignHuge(eager, boxes, std::uint8_t(0));
  assignHuge(ownBox_, ownCoord_.size() / 3, 0); // box id of each own box: offset (0, 0, 0)
  for (size_t o = 0; o < ownBox_.size(); ++o) eager[size_t(ownBox_[o] = near_[o * 27 + 13])] = 1;
  std::vector<std::int32_t>().swap(near_);
  std::vector<std::uint32_t> kept;
  assignHuge(kept, boxes, 0u);
  // A box costs a few microseconds: below a few hundred boxes one thread is faster.
  const int workers = parallelParts(boxes, threads_, 256);
  std::vector<size_t> workerDropped(size_t(workers), 0), workerTooLarge(size_t(workers), 0);
  g_.sampling_ = boxNormalSampling(); // shares the tables
  struct Worker {
    SphereSampling sampling;
    char pad[64]; // no cache line shared with the next thread's scratch
  };
  std::vector<Worker> samplings(size_t(workers), Worker{g_.sampling_, {}}); // own scratch each
  struct Split { // a two-sided box, the end of its first layer, its splitting direction
    std::uint32_t box, firstEnd;
    Vec3d dir;
  };
  std::vector<std::vector<Split>> splits(static_cast<size_t>(workers));
  parallelChunks(boxes, workers, 32, [&](size_t b0, size_t b1, int worker) {
    const SphereSampling& sampling = samplings[size_t(worker)].sampling;
    size_t dropped = 0, tooLarge = 0;
    std::vector<std::uint32_t> scratch;
    for (size_t b = b0; b < b1; ++b) {
      const size_t begin = start[b], n = start[b + 1] - begin;
      std::uint32_t* idx = &points[begin];
      // Sec. 4.1's check is on every point registered in the box: a point the filter drops has a
      // normal against the box's summed normal, hence (the box normal is taken from the points
      // kept) almost surely against the box normal too. When they are a real share of the box
      // (kOpposedShare, at least kTwoSidedMinPoints points), or when the normals cancel and split
      // into two such groups along their main axis, the box sees two sides of the surface: d is
      // too large there for one box normal (thin parts, folds, a region of flipped normals),
      // counted once here. Where the paper drops the smaller side, both are kept, as two layers
      // of the box (BoxGrid::boxOf with a normal): a vertex on either side finds its own side's
      // splats and normal. A lone flipped normal among many, which estimated normals of real scans
      // show in most boxes somewhere, is what the filter is for and is dropped.
      const BoxLayers layers = filterOrSplitBox(normals, idx, n, scratch);
      const size_t k = layers.firstEnd;
      if (layers.twoSided) {
        splits[size_t(worker)].push_back(Split{std::uint32_t(b), std::uint32_t(k), layers.split});
        g_.flags_[b] |= kOpposed;
        ++tooLarge;
      } else {
        dropped += n - k;
      }
      kept[b] = static_cast<std::uint32_t>(k);
      // Not "d too large" when some direction of S_F has a positive minimum: the maximum found by
      // maxMinDirection is at least that (up to rounding, hence the margin).
      if (eager[b] || !(sampling.quickLowerBound(normals, idx, k) > 1e-9)) {
        g_.flags_[b] |= kCounted;
        if (eager[b] && deferNormals) continue; // computed later, on the compacted lists
        double minDot = 0;
        const Vec3d n = sampling.maxMinDirection(normals, idx, k, &minDot);
        g_.storeNormal(b, n, minDot);
        g_.state_[b].store(kDone, std::memory_order_relaxed);
        if (minDot < 0 && !(g_.flags_[b] & kOpposed)) ++tooLarge;
      }
    }
    workerDropped[size_t(worker)] += dropped;
    workerTooLarge[size_t(worker)] += tooLarge;
    if (worker == 0 && progress != nullptr) progress->advanceTo(0.6 + 0.4 * double(b1) / double(boxes));
  });
  if (progress != nullptr) progress->advanceTo(1.0);
  for (int k = 0; k < workers; ++k)
    g_.dropped_ += workerDropped[size_t(k)], g_.dTooLargeCount_ += workerTooLarge[size_t(k)];
  // The second layers of the two-sided boxes, in box order, before the compaction overwrites them.
  std::vector<Split> split;
  for (auto& part : splits) split.insert(split.end(), part.begin(), part.end());
  std::sort(split.begin(), split.end(), [](const Split& a, const Split& b) { return a.box < b.box; });
  std::vector<std::uint32_t> twinOf, twinPoints, twinStart(1, 0);
  for (const auto& e : split) {
    const size_t b = e.box;
    twinOf.push_back(std::uint32_t(b));
    twinPoints.insert(twinPoints.end(), points.begin() + std::ptrdiff_t(start[b] + e.firstEnd),
                      points.begin() + std::ptrdiff_t(start[b + 1]));
    twinStart.push_back(std::uint32_t(twinPoints.size()));
  }
  size_t w = 0;
  for (size_t b = 0; b < boxes; ++b) {
    const size_t begin = start[b];
    start[b] = static_cast<std::uint32_t>(w);
    if (w != begin) std::copy(points.begin() + std::ptrdiff_t(begin), points.begin() + std::ptrdiff_t(begin + kept[b]),
                              points.begin() + std::ptrdiff_t(w)); // w <= begin: a forward copy is safe
    w += kept[b];
  }
  start[boxes] = static_cast<std::uint32_t>(w);
  points.resize(w); // (no shrink_to_fit: it would copy, doubling the peak, to save the few
                     // references the filter dropped)
  if (twinOf.empty()) return;
  // The second layers get the ids from boxCount() on (reached through boxOf with a normal);
  // their normals are computed on first use.
  const size_t twins = twinOf.size(), all = boxes + twins;
  points.insert(points.end(), twinPoints.begin(), twinPoints.end());
  start.resize(all + 1);
  for (size_t t = 0; t < twins; ++t) start[boxes + t + 1] = static_cast<std::uint32_t>(w + twinStart[t + 1]);
  g_.twin_.assign(all, -1);
  g_.split_.resize(twins);
  for (size_t t = 0; t < twins; ++t) {
    g_.twin_[twinOf[t]] = static_cast<std::int32_t>(boxes + t);
    g_.twin_[boxes + t] = static_cast<std::int32_t>(twinOf[t]);
    g_.split_[t] = split[t].dir;
  }
  g_.normalCode_.resize(all, std::uint16_t(SphereSampling::kUpCode));
  g_.minDot_.resize(all, std::numeric_limits<float>::quiet_NaN());
  std::unique_ptr<std::atomic<std::uint8_t>[]> state(new std::atomic<std::uint8_t>[all]);
  for (size_t b = 0; b < all; ++b)
    state[b].store(b < boxes ? g_.state_[b].load(std::memory_order_relaxed) : kNone, std::memory_order_relaxed);
  g_.state_.swap(state);
  g_.flags_.resize(all, 0);
  g_.layerBoxes_ = boxes;
}

void BoxGrid::Builder::deferOwnBoxes() {
  std::vector<std::int32_t> ownOfBox;
  assignHuge(ownOfBox, boxes_, std::int32_t(-1));
  for (size_t o = 0; o < ownCoord_.size() / 3; ++o) ownOfBox[size_t(ownBox_[o])] = static_cast<std::int32_t>(o);
  for (size_t b = 0; b < boxes_; ++b)
    if (eager_[b]) {
      const std::int64_t* c = &ownCoord_[size_t(ownOfBox[b]) * 3];
      g_.pending_.push_back(static_cast<std::uint32_t>(b));
      g_.pendingCorner_.push_back(g_.index_.corner(c[0], c[1], c[2]));
    }
}

void BoxGrid::build(const std::vector<Vec3d>& pts, const std::vector<Vec3d>& normals, double side,
                    Progress* progress, int threads, bool deferNormals,
                    const std::vector<std::uint32_t>* listOrder, const std::vector<float>* extraReach,
                    const std::vector<float>* splatRadius) {
  release();
  start_.assign(1, 0);
  points_.clear();
  normalCode_.clear();
  minDot_.clear();
  state_.reset();
  flags_.clear();
  twin_.clear();
  split_.clear();
  layerBoxes_ = 0;
  pending_.clear();
  pendingCorner_.clear();
  normals_ = &normals;
  dTooLargeCount_ = 0;
  dropped_ = facePoints_ = 0;
  hash_.reset(16);
  if (pts.empty() || !(side > 0) || !std::isfinite(side)) return;
  Builder b(*this, pts, normals, side, progress, threads, listOrder, extraReach, splatRadius);
  // The index's origin, below the points by the farthest reach.
  b.placeIndex();
  // The own box of each point.
  b.ownBoxes();
  // Pass 0: the boxes within reach of each point.
  b.reachMasks();
  // Pass 1: box ids.
  b.assignIds();
  // Pass 2: reference counts.
  b.countReferences();
  // Pass 3: the references.
  b.fillReferences();
  // Sec. 4.1: the normal filter and the box normals.
  b.filterAndNormals(normals, deferNormals);
  built_ = normalCode_.size();
  // The box normals left for startNormals() / finishNormals().
  if (deferNormals) b.deferOwnBoxes();
}

} // namespace growth
