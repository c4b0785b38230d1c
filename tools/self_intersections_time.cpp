// Times growth::findSelfIntersections on a mesh with 1 and 2 threads, or T (fastest of `repeat` runs
// each, wall clock and process CPU time: on a loaded machine the CPU time of the one-thread run
// is the steadier figure), prints the number of intersecting pairs, and with --remove the faces
// removeSelfIntersections takes out and the faces removeNonManifoldVertices takes out after it.
// The run times quoted in the commits come from this tool, on meshes written by
// `g2s_run ... -o mesh.ply`.
//
//   self_intersections_time <mesh.ply> [--repeat R] [--threads T] [--remove]
#include <cstring> // (vcglib's headers use strcpy without including it)

#include <growth/meshlab/layer.h>
#include <growth/manifold_cleanup.h>
#include <growth/self_intersections.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/import_ply.h>

#include <time.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <string>
#include <vector>

int main(int argc, char** argv) {
  std::string path;
  int repeat = 5;
  std::vector<int> threadCounts{1, 2};
  bool remove = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--repeat" && i + 1 < argc) repeat = std::max(1, std::atoi(argv[++i]));
    else if (a == "--threads" && i + 1 < argc) threadCounts = {std::max(1, std::atoi(argv[++i]))};
    else if (a == "--remove") remove = true;
    else if (path.empty() && !a.empty() && a[0] != '-') path = a;
    else {
      std::fprintf(stderr, "usage: self_intersections_time <mesh.ply> [--repeat R] [--threads T] [--remove]\n");
      return 2;
    }
  }
  CMeshO m;
  int mask = 0;
  if (path.empty() || vcg::tri::io::ImporterPLY<CMeshO>::Open(m, path.c_str(), mask) != 0 || m.fn == 0) {
    std::fprintf(stderr, "self_intersections_time: cannot read a mesh with faces from %s\n", path.c_str());
    return 1;
  }
  // Live vertices and faces, renumbered.
  std::vector<growth::Vec3d> pos;
  std::vector<int> index(m.vert.size(), -1);
  for (size_t i = 0; i < m.vert.size(); ++i)
    if (!m.vert[i].IsD()) {
      index[i] = int(pos.size());
      pos.push_back(growth::Vec3d::Construct(m.vert[i].cP()));
    }
  std::vector<growth::Triangle> faces;
  for (const CFaceO& f : m.face) {
    if (f.IsD()) continue;
    growth::Triangle t;
    bool ok = true;
    for (int k = 0; k < 3; ++k) {
      const int v = index[size_t(vcg::tri::Index(m, f.cV(k)))];
      ok &= v >= 0;
      t[size_t(k)] = std::uint32_t(std::max(v, 0));
    }
    if (ok) faces.push_back(t);
  }

  using Clock = std::chrono::steady_clock;
  auto cpuSeconds = []() {
    timespec t;
    clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
    return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
  };
  size_t pairs = 0;
  for (int threads : threadCounts) {
    double best = 1e300, bestCpu = 1e300;
    for (int r = 0; r < repeat; ++r) {
      const auto t0 = Clock::now();
      const double c0 = cpuSeconds();
      pairs = growth::findSelfIntersections(pos, faces, nullptr, threads).size();
      bestCpu = std::min(bestCpu, cpuSeconds() - c0);
      best = std::min(best, std::chrono::duration<double>(Clock::now() - t0).count());
    }
    std::printf("threads %d: %.4f s wall, %.4f s cpu (fastest of %d)\n", threads, best, bestCpu, repeat);
  }
  std::printf("faces: %zu\nintersecting_pairs: %zu\n", faces.size(), pairs);
  if (remove) {
    std::vector<char> alive(faces.size(), 1);
    const auto t0 = Clock::now();
    const size_t removed = growth::removeSelfIntersections(pos, faces, alive);
    const double seconds = std::chrono::duration<double>(Clock::now() - t0).count();
    const growth::ManifoldCleanupStat st = growth::removeNonManifoldVertices(faces, pos.size(), alive);
    std::printf("removed: %zu (%.4f s)\nthen_non_manifold_vertices: %zu\nthen_faces_removed: %zu\n", removed, seconds,
                st.nonManifoldVertices, st.facesRemoved);
    std::printf("pairs_left: %zu\n", growth::findSelfIntersections(pos, faces, &alive).size());
  }
  return 0;
}
