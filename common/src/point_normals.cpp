#include <growth/point_normals.h>

#include <growth/cloud_scale.h>
#include <growth/error.h>
#include <growth/parallel.h>
#include <growth/point_grid.h>

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <queue>
#include <utility>

namespace growth {

namespace {

// The k nearest points of points[i] (itself included), nearest first, ties by index: a ball
// search whose radius doubles until it holds k points.
void nearestK(const PointGrid& grid, const std::vector<Vec3d>& points, size_t i, size_t k, double radius,
              std::vector<std::pair<double, std::uint32_t>>& out) {
  const size_t want = std::min(k, points.size());
  for (;;) {
    out.clear();
    grid.forEachInBall(points[i], radius, [&](int j, double d2) { out.emplace_back(d2, std::uint32_t(j)); });
    if (out.size() >= want || !std::isfinite(radius)) break;
    radius *= 2;
  }
  const size_t m = std::min(want, out.size());
  std::partial_sort(out.begin(), out.begin() + std::ptrdiff_t(m), out.end());
  out.resize(m);
}

} // namespace

std::vector<Vec3d> estimateNormals(const std::vector<Vec3d>& points, int k, int threads) {
  if (k < 3) throw Error("estimateNormals: k must be at least 3");
  const size_t n = points.size();
  std::vector<Vec3d> normals(n, Vec3d(0, 0, 1));
  if (n < 3) return normals;
  const double spacing = meanSpacing(points);
  const double cell = spacing > 0 ? 2 * spacing : 1.0;
  PointGrid grid;
  grid.build(points, cell);
  const size_t kk = size_t(k);
  std::vector<std::uint32_t> nb(n * kk, std::uint32_t(-1));
  parallelFor(n, parallelParts(n, threads, 4096), [&](size_t begin, size_t end, int) {
    std::vector<std::pair<double, std::uint32_t>> near;
    for (size_t i = begin; i < end; ++i) {
      nearestK(grid, points, i, kk, cell, near);
      Eigen::Vector3d mean = Eigen::Vector3d::Zero();
      for (const auto& e : near) mean += Eigen::Vector3d(points[e.second][0], points[e.second][1], points[e.second][2]);
      mean /= double(near.size());
      Eigen::Matrix3d cov = Eigen::Matrix3d::Zero();
      for (const auto& e : near) {
        const Eigen::Vector3d q = Eigen::Vector3d(points[e.second][0], points[e.second][1], points[e.second][2]) - mean;
        cov += q * q.transpose();
      }
      Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig(cov);
      const Eigen::Vector3d v = eig.eigenvectors().col(0);
      normals[i] = Vec3d(v[0], v[1], v[2]).Normalize();
      for (size_t j = 0; j < near.size(); ++j) nb[i * kk + j] = near[j].second;
    }
  });
  // The symmetric neighbour graph, as adjacency lists (i's own k, plus every j that has i among its k).
  std::vector<std::uint32_t> degree(n + 1, 0);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < kk; ++j) {
      const std::uint32_t o = nb[i * kk + j];
      if (o == std::uint32_t(-1) || o == i) continue;
      ++degree[i + 1];
      ++degree[size_t(o) + 1];
    }
  for (size_t i = 0; i < n; ++i) degree[i + 1] += degree[i];
  std::vector<std::uint32_t> adj(degree[n]);
  std::vector<std::uint32_t> fill(degree.begin(), degree.end() - 1);
  for (size_t i = 0; i < n; ++i)
    for (size_t j = 0; j < kk; ++j) {
      const std::uint32_t o = nb[i * kk + j];
      if (o == std::uint32_t(-1) || o == i) continue;
      adj[fill[i]++] = o;
      adj[fill[o]++] = std::uint32_t(i);
    }
  // Sign propagation along a maximum spanning tree of |n_i · n_j| (Prim, ties by index).
  std::vector<char> reached(n, 0);
  using Arc = std::pair<double, std::pair<std::uint32_t, std::uint32_t>>; // weight, (to, from)
  auto cmp = [](const Arc& a, const Arc& b) {
    if (a.first != b.first) return a.first < b.first;
    return a.second > b.second;
  };
  std::priority_queue<Arc, std::vector<Arc>, decltype(cmp)> heap(cmp);
  auto push = [&](std::uint32_t from) {
    for (std::uint32_t e = degree[from]; e < degree[from + 1]; ++e) {
      const std::uint32_t to = adj[e];
      if (!reached[to]) heap.push(Arc(std::abs(normals[from] * normals[to]), {to, from}));
    }
  };
  for (size_t seed = 0; seed < n; ++seed) {
    if (reached[seed]) continue;
    reached[seed] = 1;
    push(std::uint32_t(seed));
    while (!heap.empty()) {
      const Arc a = heap.top();
      heap.pop();
      const std::uint32_t to = a.second.first, from = a.second.second;
      if (reached[to]) continue;
      reached[to] = 1;
      if (normals[to] * normals[from] < 0) normals[to] = -normals[to];
      push(to);
    }
  }
  return normals;
}

} // namespace growth
