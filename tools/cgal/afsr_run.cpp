// afsr_run: CGAL's Advancing Front Surface Reconstruction (Cohen-Steiner and Da, CGAL 5.5 as Debian
// ships it in libcgal-dev) on a PLY point cloud, with the library's defaults: the peer row
// "cgal-afsr" of scripts/benchmark.sh. Used only by the benchmark (and its optional smoke test);
// nothing of the project links CGAL.
//
//   afsr_run cloud.ply [-o mesh.ply]
//
// Reads the positions of the cloud (vcglib's PLY importer, as the other tools; faces and every other
// property are ignored), calls CGAL::advancing_front_surface_reconstruction(points, output iterator
// of index triples) with its default radius_ratio_bound = 5 and beta = 0.52 (the 3D Delaunay
// triangulation is built inside that call and is part of its time), and writes the mesh as binary
// PLY with the points no face uses left out. Prints one "key: value" per line like build/g2s_run:
//   seconds         wall clock of the reconstruction call alone (steady clock)
//   seconds_total   wall clock of the whole run: reading, reconstruction, writing
//   cpu_seconds     process CPU time of the reconstruction call
#include <CGAL/Advancing_front_surface_reconstruction.h>
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

#include <sys/resource.h>
#include <time.h>

#include <array>
#include <chrono>
#include <cstdio>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;

double since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

long peakRssKiB() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

void usage() { std::fprintf(stderr, "usage: afsr_run cloud.ply [-o mesh.ply]\n"); }

} // namespace

int main(int argc, char** argv) {
  const Clock::time_point start = Clock::now();
  std::string in, out;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "-o" && i + 1 < argc) out = argv[++i];
    else if (a == "-h" || a == "--help") { usage(); return 0; }
    else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
    else { usage(); return 2; }
  }
  if (in.empty()) { usage(); return 2; }

  CMeshO cloud;
  int mask = 0;
  const int err = vcg::tri::io::ImporterPLY<CMeshO>::Open(cloud, in.c_str(), mask);
  if (err != 0 && vcg::tri::io::ImporterPLY<CMeshO>::ErrorCritical(err)) {
    std::fprintf(stderr, "afsr_run: cannot read %s: %s\n", in.c_str(), vcg::tri::io::ImporterPLY<CMeshO>::ErrorMsg(err));
    return 1;
  }
  std::vector<Kernel::Point_3> points;
  points.reserve(cloud.vert.size());
  for (const auto& v : cloud.vert)
    if (!v.IsD()) points.emplace_back(double(v.cP()[0]), double(v.cP()[1]), double(v.cP()[2]));
  if (points.size() < 3) {
    std::fprintf(stderr, "afsr_run: %s has %zu points, fewer than 3\n", in.c_str(), points.size());
    return 1;
  }

  std::vector<std::array<std::size_t, 3>> triples;
  const double c0 = cpuSeconds();
  const Clock::time_point t0 = Clock::now();
  CGAL::advancing_front_surface_reconstruction(points.begin(), points.end(), std::back_inserter(triples));
  const double seconds = since(t0), cpu = cpuSeconds() - c0;

  // The mesh: only the points some face uses, in input order.
  std::vector<int> newIndex(points.size(), -1);
  size_t used = 0;
  for (const auto& t : triples)
    for (std::size_t k : t)
      if (newIndex[k] < 0) newIndex[k] = int(used++);
  CMeshO mesh;
  auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(mesh, used);
  for (size_t i = 0; i < points.size(); ++i)
    if (newIndex[i] >= 0) {
      const Kernel::Point_3& p = points[i];
      vi[newIndex[i]].P() = CMeshO::CoordType(CMeshO::ScalarType(p.x()), CMeshO::ScalarType(p.y()), CMeshO::ScalarType(p.z()));
    }
  auto fi = vcg::tri::Allocator<CMeshO>::AddFaces(mesh, triples.size());
  for (const auto& t : triples) {
    for (int k = 0; k < 3; ++k) fi->V(k) = &mesh.vert[size_t(newIndex[t[size_t(k)]])];
    ++fi;
  }
  if (!out.empty() &&
      vcg::tri::io::ExporterPLY<CMeshO>::Save(mesh, out.c_str(), vcg::tri::io::Mask::IOM_NONE, true) != 0) {
    std::fprintf(stderr, "afsr_run: cannot write %s\n", out.c_str());
    return 1;
  }

  std::printf("points: %zu\n", points.size());
  std::printf("faces: %zu\n", triples.size());
  std::printf("vertices: %zu\n", used);
  std::printf("unused_points: %zu\n", points.size() - used);
  std::printf("seconds: %.4f\n", seconds);
  std::printf("cpu_seconds: %.4f\n", cpu);
  std::printf("triangles_per_second: %.0f\n", seconds > 0 ? double(triples.size()) / seconds : 0.0);
  std::printf("seconds_total: %.4f\n", since(start));
  std::printf("peak_rss_mib: %.1f\n", double(peakRssKiB()) / 1024.0);
  std::printf("cgal_version: %s\n", CGAL_VERSION_STR);
  if (!out.empty()) std::printf("saved: %s\n", out.c_str());
  return 0;
}
