// g2s_grid_bench: measures the spatial indexes available to Robust G2S on its own query pattern —
// small balls (about 2.7 mean spacings, the mesher's gather radius) centred near the surface —
// and nearest-neighbour queries: the G2S MortonGrid (filter_g2s/engine/g2s_grid.h) at several cell
// sizes, growth::PointGrid, and vcglib's GridStaticPtr and KdTree.
//
//   g2s_grid_bench [cloud.ply] [--points N] [--queries Q] [--random]
//
// Prints build time, nanoseconds per query and the number of hits (equal hit counts show that
// the indexes agree). Timings are wall clock, best of 3.
#include "g2s_grid.h"

#include <growth/meshlab/layer.h>
#include <growth/meshlab/points.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/input_cloud.h>
#include <growth/point_grid.h>

#include <common/ml_mesh_type.h>
#include <vcg/complex/algorithms/closest.h>
#include <vcg/space/index/grid_static_ptr.h>
#include <vcg/space/index/kdtree/kdtree.h>
#include <wrap/io_trimesh/import_ply.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <string>
#include <vector>

using P3 = growth::Vec3d;

namespace {
double seconds(const std::function<void()>& f, int repeat = 3) {
  double best = 1e300;
  for (int r = 0; r < repeat; ++r) {
    const auto t0 = std::chrono::steady_clock::now();
    f();
    best = std::min(best, std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());
  }
  return best;
}
} // namespace

int main(int argc, char** argv) {
  std::string in;
  size_t n = 361489, queries = 200000;
  bool randomOrder = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--points" && i + 1 < argc) n = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--queries" && i + 1 < argc) queries = std::strtoull(argv[++i], nullptr, 10);
    else if (a == "--random") randomOrder = true;
    else if (a[0] != '-') in = a;
    else {
      std::fprintf(stderr, "usage: g2s_grid_bench [cloud.ply] [--points N] [--queries Q] [--random]\n");
      return 2;
    }
  }
  CMeshO mesh;
  if (!in.empty()) {
    int mask = 0;
    if (vcg::tri::io::ImporterPLY<CMeshO>::Open(mesh, in.c_str(), mask) != 0) {
      std::fprintf(stderr, "cannot read %s\n", in.c_str());
      return 1;
    }
  } else {
    growth::CloudSpec spec;
    spec.shape = growth::Shape::Sphere;
    spec.count = n;
    growth::toMesh(growth::generateCloud(spec), mesh);
  }
  std::vector<P3> pts;
  for (const auto& v : mesh.vert) pts.push_back(P3::Construct(v.cP()));
  const double mu = growth::meanSpacing(pts);
  const double radius = 2.7 * mu;
  // Query centres: points moved by up to 1.5 spacings, at a fixed stride (deterministic); then
  // put in the grid's Morton order, like the mesher's advancing front visits space coherently.
  // --random keeps the scattered order (cache-bound).
  growth::Random rng(7);
  std::vector<P3> centre(queries);
  for (size_t q = 0; q < queries; ++q) centre[q] = pts[(q * 7919) % pts.size()] + rng.inBall(1.5 * mu);
  if (!randomOrder) {
    growth::g2s::MortonGrid order;
    order.build(centre, 6 * mu);
    centre = order.points();
  }
  std::printf("points %zu, mean spacing %.4g, ball radius %.2f spacings, %zu ball queries, %zu nearest queries\n",
              pts.size(), mu, radius / mu, queries, queries / 4);
  std::printf("%-28s %10s %12s %12s %12s\n", "index", "build ms", "ball ns/q", "hits/query", "nearest ns/q");

  for (double cells : {3.0, 4.0, 6.0, 8.0}) {
    growth::g2s::MortonGrid g;
    const double tb = seconds([&] { g.build(pts, cells * mu); });
    size_t hits = 0;
    const double tq = seconds([&] {
      hits = 0;
      for (const P3& c : centre) g.forEachInBall(c, radius, [&](std::uint32_t, double) { ++hits; });
    });
    const double tn = seconds([&] {
      for (size_t q = 0; q < queries / 4; ++q) g.nearest(centre[q]);
    });
    char name[64];
    std::snprintf(name, sizeof name, "g2s MortonGrid, cell %.0f mu", cells);
    std::printf("%-28s %10.1f %12.1f %12.2f %12.1f\n", name, tb * 1e3, tq * 1e9 / double(queries),
                double(hits) / double(queries), tn * 1e9 / double(queries / 4));
  }
  for (double cells : {2.0, 4.0, 6.0}) {
    growth::PointGrid g;
    const double tb = seconds([&] { g.build(pts, cells * mu); });
    size_t hits = 0;
    const double tq = seconds([&] {
      hits = 0;
      for (const P3& c : centre) g.forEachInBall(c, radius, [&](int, double) { ++hits; });
    });
    const double tn = seconds([&] {
      for (size_t q = 0; q < queries / 4; ++q) g.nearest(centre[q]);
    });
    char name[64];
    std::snprintf(name, sizeof name, "growth::PointGrid, cell %.0f mu", cells);
    std::printf("%-28s %10.1f %12.1f %12.2f %12.1f\n", name, tb * 1e3, tq * 1e9 / double(queries),
                double(hits) / double(queries), tn * 1e9 / double(queries / 4));
  }
  {
    vcg::GridStaticPtr<CVertexO, CMeshO::ScalarType> g;
    const double tb = seconds([&] { g.Set(mesh.vert.begin(), mesh.vert.end()); });
    std::vector<CVertexO*> found;
    std::vector<CMeshO::ScalarType> dist;
    std::vector<CMeshO::CoordType> where;
    size_t hits = 0;
    const double tq = seconds([&] {
      hits = 0;
      for (const P3& c : centre) {
        vcg::tri::GetInSphereVertex(mesh, g, growth::meshlab::toPoint<CMeshO::CoordType>(c), CMeshO::ScalarType(radius), found, dist, where);
        hits += found.size();
      }
    });
    const double tn = seconds([&] {
      for (size_t q = 0; q < queries / 4; ++q) {
        CMeshO::ScalarType d = std::numeric_limits<CMeshO::ScalarType>::max();
        vcg::tri::GetClosestVertex(mesh, g, growth::meshlab::toPoint<CMeshO::CoordType>(centre[q]), d, d);
      }
    });
    std::printf("%-28s %10.1f %12.1f %12.2f %12.1f\n", "vcg GridStaticPtr (float)", tb * 1e3,
                tq * 1e9 / double(queries), double(hits) / double(queries), tn * 1e9 / double(queries / 4));
  }
  {
    std::vector<vcg::Point3f> fp;
    for (const P3& p : pts) fp.push_back(growth::meshlab::toPoint3f(p));
    std::unique_ptr<vcg::KdTree<float>> tree;
    const double tb = seconds([&] { tree.reset(new vcg::KdTree<float>(vcg::ConstDataWrapper<vcg::Point3f>(&fp[0], fp.size()))); });
    std::vector<unsigned int> idx;
    std::vector<float> d2;
    size_t hits = 0;
    const double tq = seconds([&] {
      hits = 0;
      for (const P3& c : centre) {
        idx.clear();
        d2.clear();
        tree->doQueryDist(growth::meshlab::toPoint3f(c), float(radius), idx, d2);
        hits += idx.size();
      }
    });
    const double tn = seconds([&] {
      for (size_t q = 0; q < queries / 4; ++q) {
        unsigned int i;
        float d;
        tree->doQueryClosest(growth::meshlab::toPoint3f(centre[q]), i, d);
      }
    });
    std::printf("%-28s %10.1f %12.1f %12.2f %12.1f\n", "vcg KdTree (float)", tb * 1e3, tq * 1e9 / double(queries),
                double(hits) / double(queries), tn * 1e9 / double(queries / 4));
  }
  return 0;
}
