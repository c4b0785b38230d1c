#include <growth/error.h>
#include <growth/huge_pages.h>
#include <growth/input_cloud.h>
#include <growth/point_grid.h>

#include <algorithm>
#include <cstdint>
#include <cstring>
#include <cmath>
#include <limits>
#include <numeric>
#include <sstream>

namespace growth {

namespace {
bool finite3(const Vec3d& p) { return std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2]); }
} // namespace

InputCloud readCloud(CloudArrays layer, const CloudCheck& check) {
  InputCloud c;
  const size_t vn = layer.points.size();
  c.layerFaces = layer.layerFaces;
  if (vn == 0)
    throw Error("The current layer has no vertices: load or select a point cloud layer first.");
  if (layer.layerFaces > 0 && !check.allowFaces) {
    std::ostringstream s;
    s << "The current layer is a mesh (" << layer.layerFaces << " faces), not a point cloud. This filter "
      << "reconstructs a surface from points: run it on a point cloud layer, or remove the faces "
      << "first (Filters > Selection > Select All, then Filters > Selection > Delete Selected Faces).";
    throw Error(s.str());
  }

  // The layer's arrays are filtered in place (finite points kept, normals checked).
  size_t nonFinite = 0, huge = 0, badNormals = 0;
  c.points = std::move(layer.points);
  c.vertexIndex = std::move(layer.vertexIndex);
  if (c.vertexIndex.empty()) {
    reserveHuge(c.vertexIndex, vn, true);
    for (size_t i = 0; i < vn; ++i) c.vertexIndex.push_back(static_cast<int>(i));
  }
  const bool withNormals = check.needNormals || check.readNormals;
  if (withNormals) {
    c.normals = std::move(layer.normals);
    if (c.normals.size() != vn) c.normals.assign(vn, Vec3d(0, 0, 0));
  }
  size_t w = 0;
  for (size_t i = 0; i < vn; ++i) {
    const Vec3d p = c.points[i];
    if (!finite3(p)) {
      ++nonFinite;
      continue;
    }
    if (std::abs(p[0]) > kMaxAbsCoordinate || std::abs(p[1]) > kMaxAbsCoordinate || std::abs(p[2]) > kMaxAbsCoordinate)
      ++huge;
    if (withNormals) {
      Vec3d n = c.normals[i];
      if (check.normalsAsStored && !check.needNormals) {
        if (!finite3(n) || !(n.SquaredNorm() > 0)) {
          ++badNormals;
          n = Vec3d(0, 0, 0);
        }
      } else {
        const double len = n.Norm();
        if (!finite3(n) || !(len > 1e-12)) {
          ++badNormals;
          n = Vec3d(0, 0, 0);
        } else {
          n /= len;
        }
      }
      c.normals[w] = n;
    }
    c.points[w] = p;
    c.vertexIndex[w] = c.vertexIndex[i];
    ++w;
  }
  c.points.resize(w);
  c.vertexIndex.resize(w);
  if (withNormals) c.normals.resize(w);
  if (nonFinite > 0) {
    std::ostringstream s;
    s << nonFinite << " of " << vn << " vertices have NaN or infinite coordinates. Delete them "
      << "first (select them with Filters > Selection > Conditional Vertex Selection, e.g. "
      << "'x!=x || y!=y || z!=z', then Filters > Selection > Delete Selected Vertices) and run the "
      << "filter again.";
    throw Error(s.str());
  }
  if (huge > 0) {
    std::ostringstream s;
    s << huge << " of " << vn << " vertices have a coordinate beyond +-" << kMaxAbsCoordinate
      << ", which this filter cannot mesh. Scale the layer down (Filters > Normals, Curvatures and "
      << "Orientation > Transform: Scale, Normalize) or delete those vertices, and run the filter again.";
    throw Error(s.str());
  }
  if (check.needNormals && badNormals > 0) {
    std::ostringstream s;
    if (badNormals == c.points.size())
      s << "The layer has no per-vertex normals. This filter needs oriented normals: compute them "
        << "with Filters > Normals, Curvatures and Orientation > Compute normals for point sets, and "
        << "run the filter again.";
    else
      s << badNormals << " of " << c.points.size() << " vertices have a zero or invalid normal. "
        << "Recompute the normals with Filters > Normals, Curvatures and Orientation > Compute normals "
        << "for point sets (or delete those vertices) and run the filter again.";
    throw Error(s.str());
  }

  // Exact duplicates: keep the first occurrence (in vertex order) of every position. One pass
  // with an open-addressing hash of the coordinates (linear time; −0.0 counts as 0.0, as ==
  // does); the table holds indices of kept points, so no order of anything depends on hashing.
  {
    const size_t n = c.points.size();
    size_t cap = 16;
    while (cap < 2 * n) cap *= 2;
    HugeVector<std::uint32_t> table(cap, 0); // kept index + 1; 0 = free
    auto bits = [](double v) {
      v += 0.0; // −0.0 → +0.0
      std::uint64_t b;
      std::memcpy(&b, &v, sizeof b);
      return b;
    };
    size_t w = 0;
    for (size_t i = 0; i < n; ++i) {
      const Vec3d p = c.points[i];
      std::uint64_t h = bits(p[0]) * 0x9E3779B97F4A7C15ull;
      h = (h ^ (h >> 29) ^ bits(p[1])) * 0xBF58476D1CE4E5B9ull;
      h = (h ^ (h >> 31) ^ bits(p[2])) * 0x94D049BB133111EBull;
      size_t slot = static_cast<size_t>(h >> 17) & (cap - 1);
      bool duplicate = false;
      while (table[slot] != 0) {
        if (c.points[table[slot] - 1] == p) {
          duplicate = true;
          break;
        }
        slot = (slot + 1) & (cap - 1);
      }
      if (duplicate) continue;
      c.points[w] = p;
      if (withNormals) c.normals[w] = c.normals[i];
      c.vertexIndex[w] = c.vertexIndex[i];
      table[slot] = static_cast<std::uint32_t>(w + 1);
      ++w;
    }
    c.duplicatesDropped = n - w;
    c.points.resize(w);
    if (withNormals) c.normals.resize(w);
    c.vertexIndex.resize(w);
  }

  if (c.points.size() < check.minPoints) {
    std::ostringstream s;
    if (c.points.size() == 1 && vn == 1)
      s << "The layer has only 1 point; at least " << check.minPoints << " are needed to reconstruct a surface.";
    else if (c.points.size() == 1)
      s << "All " << vn << " points of the layer are identical: there is no surface to reconstruct.";
    else
      s << "The layer has only " << c.points.size() << " distinct points; at least " << check.minPoints
        << " are needed to reconstruct a surface.";
    throw Error(s.str());
  }

  c.box.SetNull();
  for (const auto& p : c.points) c.box.Add(p);

  // All points on one line: no surface either. Up to float storage (MeshLab's coordinates): the
  // points of a line written in float are off it by up to half a unit in the last place of the
  // largest coordinate, about 6e-8 of it, far more than any tolerance relative to the box.
  {
    double magnitude = 0; // the largest |coordinate|, from the box
    for (int k = 0; k < 3; ++k) magnitude = std::max({magnitude, std::abs(c.box.min[k]), std::abs(c.box.max[k])});
    const Vec3d a = c.points[0];
    size_t far = 0;
    double best = -1;
    for (size_t i = 1; i < c.points.size(); ++i) {
      const double d = (c.points[i] - a).SquaredNorm();
      if (d > best) best = d, far = i;
    }
    const Vec3d dir = (c.points[far] - a).Normalize();
    const double tol = std::max(1e-9 * c.box.Diag(), 4.0 * double(std::numeric_limits<float>::epsilon()) * magnitude);
    bool collinear = true;
    for (const auto& p : c.points) {
      if (((p - a) ^ dir).Norm() > tol) {
        collinear = false;
        break;
      }
    }
    if (collinear)
      throw Error("All points of the layer lie on one straight line: there is no surface to reconstruct.");
  }
  return c;
}

} // namespace growth
