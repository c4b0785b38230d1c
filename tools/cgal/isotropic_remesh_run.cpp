// isotropic_remesh_run: CGAL's isotropic remeshing (Botsch and Kobbelt's split / collapse / flip /
// tangential relaxation loop, CGAL 5.5 as Debian ships it in libcgal-dev) of a triangle mesh at a
// target edge length: the peer row "CGAL" of scripts/benchmark.sh --remesh. Used only by the
// benchmark (and its smoke test); nothing of the project links CGAL.
//
//   isotropic_remesh_run mesh.ply|mesh.off --target L [--iterations N] [--crease-angle DEG] [-o out.ply]
//
// Calls CGAL::Polygon_mesh_processing::isotropic_remeshing(faces(mesh), L, mesh,
// parameters::number_of_iterations(N)) with N = 3 by default (the three iterations of the
// comparison with MeshLab's Isotropic Explicit Remeshing) and the library's other defaults
// (protect_constraints false, relax_constraints false, one smoothing step per iteration). Creases
// are kept the way MeshLab's filter keeps them (its featuredeg, 30 by default): the edges whose
// dihedral angle exceeds --crease-angle (30 by default; 0 turns it off) are found by
// CGAL::Polygon_mesh_processing::detect_sharp_edges and passed as edge_is_constrained_map, so that
// they are split and collapsed only along themselves and never flipped.
//
// The input is read as a polygon soup (CGAL::IO::read_polygon_soup: PLY, OFF, OBJ, STL); a soup that
// is not a consistently oriented manifold mesh is oriented by orient_polygon_soup first (which
// duplicates the vertices of non-manifold corners) and "soup_repaired: 1" is printed. The output is
// written as binary little-endian PLY with float coordinates (like the project's other tools).
// Prints one "key: value" per line like build/g2s_run:
//   seconds          wall clock of the library calls of the method: detect_sharp_edges (when
//                    creases are kept) plus isotropic_remeshing (steady clock)
//   remesh_seconds   wall clock of the isotropic_remeshing call alone
//   cpu_seconds      process CPU time of the same calls as `seconds`
//   seconds_total    wall clock of the whole run: reading, remeshing, writing
//   load_rss_mib     the peak resident set size once the input is read and built (before the method)
//   peak_rss_mib     the process's peak resident set size (getrusage), reading and writing included
#include <CGAL/Exact_predicates_inexact_constructions_kernel.h>
#include <CGAL/IO/polygon_soup_io.h>
#include <CGAL/Polygon_mesh_processing/detect_features.h>
#include <CGAL/Polygon_mesh_processing/orient_polygon_soup.h>
#include <CGAL/Polygon_mesh_processing/polygon_soup_to_polygon_mesh.h>
#include <CGAL/Polygon_mesh_processing/remesh.h>
#include <CGAL/Surface_mesh.h>

#include <sys/resource.h>
#include <time.h>

#include <chrono>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <string>
#include <vector>

namespace {

using Clock = std::chrono::steady_clock;
using Kernel = CGAL::Exact_predicates_inexact_constructions_kernel;
using Point = Kernel::Point_3;
using Mesh = CGAL::Surface_mesh<Point>;
namespace PMP = CGAL::Polygon_mesh_processing;

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

void usage() {
  std::fprintf(stderr, "usage: isotropic_remesh_run mesh.ply|mesh.off --target L [--iterations N] [--crease-angle DEG] "
                       "[-o out.ply]\n");
}

// Binary little-endian PLY: float x y z, faces as uchar-counted int lists (vcglib reads it; so do
// MeshLab and PyMeshLab).
bool writePly(const std::string& path, const Mesh& mesh) {
  std::ofstream out(path, std::ios::binary);
  if (!out) return false;
  out << "ply\nformat binary_little_endian 1.0\nelement vertex " << mesh.number_of_vertices()
      << "\nproperty float x\nproperty float y\nproperty float z\nelement face " << mesh.number_of_faces()
      << "\nproperty list uchar int vertex_indices\nend_header\n";
  std::vector<std::int32_t> index(mesh.num_vertices(), -1);   // by vertex handle, garbage included
  std::int32_t next = 0;
  for (Mesh::Vertex_index v : mesh.vertices()) {
    index[size_t(v)] = next++;
    const Point& p = mesh.point(v);
    const float xyz[3] = {float(p.x()), float(p.y()), float(p.z())};
    out.write(reinterpret_cast<const char*>(xyz), sizeof xyz);
  }
  for (Mesh::Face_index f : mesh.faces()) {
    std::vector<std::int32_t> ids;
    for (Mesh::Vertex_index v : CGAL::vertices_around_face(mesh.halfedge(f), mesh)) ids.push_back(index[size_t(v)]);
    const unsigned char n = static_cast<unsigned char>(ids.size());
    out.write(reinterpret_cast<const char*>(&n), 1);
    out.write(reinterpret_cast<const char*>(ids.data()), std::streamsize(ids.size() * sizeof(std::int32_t)));
  }
  return bool(out);
}

} // namespace

int main(int argc, char** argv) {
  const Clock::time_point start = Clock::now();
  std::string in, out;
  double target = 0, creaseAngle = 30;
  unsigned iterations = 3;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "isotropic_remesh_run: missing value after %s\n", a.c_str());
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "-o") out = value();
    else if (a == "--target") target = std::atof(value());
    else if (a == "--iterations") iterations = unsigned(std::atoi(value()));
    else if (a == "--crease-angle") creaseAngle = std::atof(value());
    else if (a == "-h" || a == "--help") { usage(); return 0; }
    else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
    else { usage(); return 2; }
  }
  if (in.empty()) { usage(); return 2; }
  if (!(target > 0)) {
    std::fprintf(stderr, "isotropic_remesh_run: --target must be a positive length\n");
    return 2;
  }
  if (iterations < 1 || !(creaseAngle >= 0 && creaseAngle < 180)) {
    std::fprintf(stderr, "isotropic_remesh_run: --iterations must be >= 1 and --crease-angle in [0, 180)\n");
    return 2;
  }

  std::vector<Point> points;
  std::vector<std::vector<std::size_t>> polygons;
  if (!CGAL::IO::read_polygon_soup(in, points, polygons) || polygons.empty()) {
    std::fprintf(stderr, "isotropic_remesh_run: cannot read a mesh with faces from %s\n", in.c_str());
    return 1;
  }
  for (const auto& p : polygons)
    if (p.size() != 3) {
      std::fprintf(stderr, "isotropic_remesh_run: %s has a face of %zu vertices; a triangle mesh is needed\n", in.c_str(), p.size());
      return 1;
    }
  const size_t inputVertices = points.size(), inputFaces = polygons.size();
  bool repaired = false;
  if (!PMP::is_polygon_soup_a_polygon_mesh(polygons)) {
    PMP::orient_polygon_soup(points, polygons);
    repaired = true;
  }
  Mesh mesh;
  PMP::polygon_soup_to_polygon_mesh(points, polygons, mesh);
  if (!CGAL::is_triangle_mesh(mesh) || mesh.number_of_faces() != inputFaces) {
    std::fprintf(stderr, "isotropic_remesh_run: %s is not a triangle mesh CGAL accepts (%zu of %zu faces kept)\n", in.c_str(),
                 size_t(mesh.number_of_faces()), inputFaces);
    return 1;
  }

  const double loadRssMiB = double(peakRssKiB()) / 1024.0;
  const double c0 = cpuSeconds();
  const Clock::time_point t0 = Clock::now();
  auto constrained = mesh.add_property_map<Mesh::Edge_index, bool>("e:is_constrained", false).first;
  if (creaseAngle > 0) PMP::detect_sharp_edges(mesh, creaseAngle, constrained);
  const Clock::time_point t1 = Clock::now();
  PMP::isotropic_remeshing(faces(mesh), target, mesh,
                           CGAL::parameters::number_of_iterations(iterations).edge_is_constrained_map(constrained));
  const double seconds = since(t0), remeshSeconds = since(t1), cpu = cpuSeconds() - c0;
  size_t sharp = 0;
  for (Mesh::Edge_index e : mesh.edges()) sharp += constrained[e] ? 1 : 0;
  mesh.collect_garbage();

  if (!out.empty() && !writePly(out, mesh)) {
    std::fprintf(stderr, "isotropic_remesh_run: cannot write %s\n", out.c_str());
    return 1;
  }
  std::printf("input_vertices: %zu\n", inputVertices);
  std::printf("input_faces: %zu\n", inputFaces);
  std::printf("soup_repaired: %d\n", repaired ? 1 : 0);
  std::printf("target: %.9g\n", target);
  std::printf("iterations: %u\n", iterations);
  std::printf("crease_angle: %g\n", creaseAngle);
  std::printf("constrained_edges_after: %zu\n", sharp);
  std::printf("vertices: %zu\n", size_t(mesh.number_of_vertices()));
  std::printf("faces: %zu\n", size_t(mesh.number_of_faces()));
  std::printf("seconds: %.4f\n", seconds);
  std::printf("remesh_seconds: %.4f\n", remeshSeconds);
  std::printf("cpu_seconds: %.4f\n", cpu);
  std::printf("seconds_total: %.4f\n", since(start));
  std::printf("load_rss_mib: %.1f\n", loadRssMiB);
  std::printf("peak_rss_mib: %.1f\n", double(peakRssKiB()) / 1024.0);
  std::printf("cgal_version: %s\n", CGAL_VERSION_STR);
  if (!out.empty()) std::printf("saved: %s\n", out.c_str());
  return 0;
}
