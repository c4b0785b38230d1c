// mesh_measures: prints the quality measures of a mesh (growth/mesh_measures.h) as JSON.
//   mesh_measures mesh.ply [--cloud cloud.ply] [--reference input.ply] [--target D] [--histograms PREFIX]
//                 [--edge-max L] [--no-min-vertex-distance]
// --reference (a remeshed mesh against its input) adds the distance between the two surfaces both
// ways (growth::surfaceDistance: each surface sampled at its vertices and at as many area-weighted
// random points, seed 1, as it has faces; exact distance to the other's nearest triangle):
// "to_reference_*" from this mesh to the input, "from_reference_*" from the input to this mesh
// ("from_reference_vertex_max": the input's vertices alone), and "hausdorff" the larger maximum.
// --target D adds "shortest_edge_over_d" (E_min / D) and "edges_below_d", the edges shorter than
// D by more than float storage of their ends can explain: each coordinate rounded by up to half a
// float step, at most |x|·2^-24, so an edge by up to 2·√3·m·2^-24 (m the largest coordinate of its
// ends), plus 1e-9·D.
// Files are read in double precision (a double PLY, as PyMeshLab and the double MeshLab builds
// save, is measured as stored: rounded to float, a double mesh can gain intersections and edges
// shorter than d that the file does not have).
// --cloud adds the distance of the cloud's points to the mesh and μd %; --histograms writes
// PREFIX_angles.csv (degrees), PREFIX_edges.csv and PREFIX_quality.csv (Q_t) as "lo,hi,count";
// --edge-max fixes the edge histogram's range to [0, L] (default 3·E_avg) so that several meshes
// can be compared bin by bin.
#include <growth/mesh_measures.h>

#include <vcg/complex/complex.h>
#include <wrap/io_trimesh/import_ply.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cstdint>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

namespace {

void usage() {
  std::fprintf(stderr,
               "usage: mesh_measures mesh.ply [--cloud cloud.ply] [--histograms PREFIX] [--edge-max L]\n"
               "                     [--no-min-vertex-distance]\n");
}

// A vcglib mesh with double coordinates, only to read the PLY files.
class DVertex;
class DFace;
struct DTypes : public vcg::UsedTypes<vcg::Use<DVertex>::AsVertexType, vcg::Use<DFace>::AsFaceType> {};
class DVertex : public vcg::Vertex<DTypes, vcg::vertex::Coord3d, vcg::vertex::BitFlags> {};
class DFace : public vcg::Face<DTypes, vcg::face::VertexRef, vcg::face::BitFlags> {};
class DMesh : public vcg::tri::TriMesh<std::vector<DVertex>, std::vector<DFace>> {};

// The live vertices and faces of a PLY file, in double.
bool load(const std::string& path, growth::MeshArrays& out) {
  DMesh m;
  int mask = 0;
  const int err = vcg::tri::io::ImporterPLY<DMesh>::Open(m, path.c_str(), mask);
  if (err != 0 && vcg::tri::io::ImporterPLY<DMesh>::ErrorCritical(err)) {
    std::fprintf(stderr, "mesh_measures: cannot read %s: %s\n", path.c_str(), vcg::tri::io::ImporterPLY<DMesh>::ErrorMsg(err));
    return false;
  }
  out = growth::MeshArrays();
  std::vector<std::uint32_t> index(m.vert.size(), ~0u);
  for (size_t i = 0; i < m.vert.size(); ++i) {
    if (m.vert[i].IsD()) continue;
    index[i] = std::uint32_t(out.vertices.size());
    const auto& p = m.vert[i].cP();
    out.vertices.push_back(growth::Vec3d(p[0], p[1], p[2]));
  }
  for (const auto& f : m.face) {
    if (f.IsD()) continue;
    std::array<std::uint32_t, 3> t;
    for (int k = 0; k < 3; ++k) t[k] = index[vcg::tri::Index(m, f.cV(k))];
    out.faces.push_back(t);
  }
  return true;
}

std::string number(double v) {
  if (!std::isfinite(v)) return "null";
  std::ostringstream s;
  s.precision(10);
  s << v;
  return s.str();
}

bool writeHistogram(const std::string& path, const growth::Histogram& h) {
  std::ofstream out(path);
  if (!out) return false;
  out << "lo,hi,count\n";
  const double w = h.binWidth();
  for (size_t i = 0; i < h.counts.size(); ++i) out << h.lo + w * double(i) << ',' << h.lo + w * double(i + 1) << ',' << h.counts[i] << '\n';
  return bool(out);
}

std::string histogramJson(const char* name, const growth::Histogram& h) {
  std::ostringstream s;
  s << "  \"histogram_" << name << "\": {\"lo\": " << h.lo << ", \"hi\": " << h.hi << ", \"bins\": " << h.counts.size()
    << ", \"below\": " << h.below << ", \"above\": " << h.above << "},\n";
  return s.str();
}

} // namespace

int main(int argc, char** argv) {
  std::string meshPath, cloudPath, histPrefix, referencePath;
  double target = 0;
  growth::MeasureOptions options;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto value = [&]() -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "mesh_measures: missing value after %s\n", a.c_str());
        usage();
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--cloud") cloudPath = value();
    else if (a == "--histograms") histPrefix = value();
    else if (a == "--reference") referencePath = value();
    else if (a == "--target") target = std::atof(value());
    else if (a == "--edge-max") options.edgeHistogramMax = std::atof(value());
    else if (a == "--no-min-vertex-distance") options.minVertexDistance = false;
    else if (a == "-h" || a == "--help") {
      usage();
      return 0;
    } else if (!a.empty() && a[0] == '-') {
      std::fprintf(stderr, "mesh_measures: unknown argument %s\n", a.c_str());
      usage();
      return 2;
    } else if (meshPath.empty()) meshPath = a;
    else {
      std::fprintf(stderr, "mesh_measures: more than one mesh given (%s)\n", a.c_str());
      usage();
      return 2;
    }
  }
  if (meshPath.empty()) {
    usage();
    return 2;
  }

  growth::MeshArrays mesh;
  if (!load(meshPath, mesh)) return 1;
  std::vector<growth::Vec3d> cloud;
  if (!cloudPath.empty()) {
    growth::MeshArrays c;
    if (!load(cloudPath, c)) return 1;
    cloud.reserve(c.vertices.size());
    for (const growth::Vec3d& p : c.vertices)
      if (std::isfinite(p[0]) && std::isfinite(p[1]) && std::isfinite(p[2])) cloud.push_back(p);
  }

  const auto t0 = std::chrono::steady_clock::now();
  const growth::MeshMeasures m = growth::measure(mesh, cloudPath.empty() ? nullptr : &cloud, options);
  std::ostringstream remesh;
  if (target > 0) {
    const growth::MeshArrays& arrays = mesh;
    // The unique edges shorter than D, each counted once whatever the faces' orientation.
    std::vector<std::pair<std::uint32_t, std::uint32_t>> shortEdges;
    for (const auto& f : arrays.faces)
      for (int k = 0; k < 3; ++k) {
        const std::uint32_t a = f[k], b = f[(k + 1) % 3];
        if (a == b) continue;
        double m = 0;
        for (int i = 0; i < 3; ++i)
          m = std::max({m, std::abs(arrays.vertices[a][i]), std::abs(arrays.vertices[b][i])});
        const double margin = 2 * std::sqrt(3.0) * std::ldexp(m, -24) + 1e-9 * target;
        if ((arrays.vertices[a] - arrays.vertices[b]).Norm() < target - margin)
          shortEdges.push_back({std::min(a, b), std::max(a, b)});
      }
    std::sort(shortEdges.begin(), shortEdges.end());
    const size_t below = size_t(std::unique(shortEdges.begin(), shortEdges.end()) - shortEdges.begin());
    remesh << "  \"target\": " << number(target) << ",\n  \"shortest_edge_over_d\": " << number(m.edgeMin / target) << ",\n";
    remesh << "  \"edges_below_d\": " << below << ",\n";
  }
  if (!referencePath.empty()) {
    growth::MeshArrays in;
    if (!load(referencePath, in)) return 1;
    const growth::SurfaceDistance to = growth::surfaceDistance(mesh, in), from = growth::surfaceDistance(in, mesh);
    remesh << "  \"to_reference_mean\": " << number(to.mean) << ",\n  \"to_reference_max\": " << number(to.max)
           << ",\n  \"to_reference_samples\": " << to.samples << ",\n  \"from_reference_mean\": " << number(from.mean)
           << ",\n  \"from_reference_max\": " << number(from.max) << ",\n  \"from_reference_vertex_max\": "
           << number(from.vertexMax) << ",\n  \"from_reference_samples\": " << from.samples << ",\n  \"hausdorff\": "
           << number(std::max(to.max, from.max)) << ",\n";
  }
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  if (!histPrefix.empty()) {
    const bool ok = writeHistogram(histPrefix + "_angles.csv", m.angleHistogram) &&
                    writeHistogram(histPrefix + "_edges.csv", m.edgeHistogram) &&
                    writeHistogram(histPrefix + "_quality.csv", m.qualityHistogram);
    if (!ok) {
      std::fprintf(stderr, "mesh_measures: cannot write the histograms %s_*.csv\n", histPrefix.c_str());
      return 1;
    }
  }

  // The measures' JSON object, with the file, the histogram ranges and the time appended.
  std::string json = m.toJson();
  const size_t close = json.rfind('}');
  std::ostringstream extra;
  extra << ",\n" << remesh.str() << histogramJson("angles", m.angleHistogram) << histogramJson("edges", m.edgeHistogram)
        << histogramJson("quality", m.qualityHistogram) << "  \"measure_seconds\": " << seconds << ",\n  \"mesh\": \"";
  for (char ch : meshPath) {
    if (ch == '"' || ch == '\\') extra << '\\';
    extra << ch;
  }
  extra << "\"\n";
  // Replace the final "\n}" with the extra fields and a new closing brace.
  const size_t lastField = json.rfind('\n', close - 1);
  json = json.substr(0, lastField) + extra.str() + "}\n";
  std::fputs(json.c_str(), stdout);
  return 0;
}
