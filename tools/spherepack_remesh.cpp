// spherepack_remesh: runs the sphere-packing remesher (remesher.h) outside MeshLab and prints its
// statistics and the measures of the result.
//   spherepack_remesh mesh.ply [--d D | --d-edges K (d = K · mean edge length)] [--w W] [--border B]
//                     [--crease DEG] [--min-piece-faces N] [--no-hole-pass] [--threads T] [--measure] [-o out.ply]
// --measure adds the topology and quality of the input and the output, and the distances between
// them both ways (largest and mean, over the vertices of one to the faces of the other).
// Prints one "key: value" per line. Time is the engine's own (RemeshStat::seconds).
#include "filter_spherepack_layer.h"

#include <growth/error.h>
#include <growth/meshlab/layer.h>
#include <growth/mesh_measures.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

#include <sys/resource.h>

#include <cstdio>
#include <cstdlib>
#include <string>

namespace {

long peakRssKiB() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return u.ru_maxrss;
}

void usage() {
  std::fprintf(stderr, "usage: spherepack_remesh mesh.ply [--d D | --d-edges K] [--w W] [--border B] [--crease DEG]\n"
                       "                         [--min-piece-faces N] [--no-hole-pass] [--threads T] [--measure] [-o out.ply]\n");
}

void distances(const growth::MeshArrays& from, const growth::MeshArrays& to, double& maxD, double& meanD) {
  const growth::MeshDistance index(to);
  maxD = 0;
  double sum = 0;
  int hint = -1;
  for (const auto& v : from.vertices) {
    const double x = index.distance(v, &hint);
    maxD = std::max(maxD, x);
    sum += x;
  }
  meanD = from.vertices.empty() ? 0 : sum / double(from.vertices.size());
}

void printMeasures(const char* prefix, const growth::MeshMeasures& m) {
  std::printf("%s_vertices: %zu\n%s_faces: %zu\n%s_e_avg: %.6g\n%s_e_min: %.8g\n%s_e_rms_percent: %.3f\n"
              "%s_q_avg: %.5f\n%s_q_min: %.5f\n%s_components: %zu\n%s_boundary_loops: %zu\n%s_genus: %d\n"
              "%s_non_manifold_edges: %zu\n%s_non_manifold_vertices: %zu\n%s_self_intersecting_pairs: %zu\n",
              prefix, m.vertices, prefix, m.faces, prefix, m.edgeMean, prefix, m.edgeMin, prefix, m.edgeRmsPercent,
              prefix, m.qualityMean, prefix, m.qualityMin, prefix, m.components, prefix, m.boundaryLoops, prefix,
              m.genus, prefix, m.nonManifoldEdges, prefix, m.nonManifoldVertices, prefix, m.selfIntersectingPairs);
}

} // namespace

int main(int argc, char** argv) {
  try {
    std::string in, out;
    growth::spherepack::RemeshParams params;
    double dEdges = 0;
    bool measure = false;
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw growth::Error("missing value after " + a);
        return argv[++i];
      };
      if (a == "--d") params.sphereDiameter = std::atof(value());
      else if (a == "--d-edges") dEdges = std::atof(value());
      else if (a == "--w") params.windowSize = std::atoi(value());
      else if (a == "--border") params.maxBorderLength = std::atoi(value());
      else if (a == "--crease") params.creaseAngleDeg = std::atof(value());
      else if (a == "--min-piece-faces") params.minPieceFaces = std::atoi(value());
      else if (a == "--threads") params.threads = std::atoi(value());
      else if (a == "--no-hole-pass") params.closeHoles = false;
      else if (a == "--measure") measure = true;
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
      else throw growth::Error("unknown argument " + a);
    }
    if (in.empty()) {
      usage();
      return 2;
    }
    CMeshO input;
    int mask = 0;
    const int err = vcg::tri::io::ImporterPLY<CMeshO>::Open(input, in.c_str(), mask);
    if (err != 0 && vcg::tri::io::ImporterPLY<CMeshO>::ErrorCritical(err))
      throw growth::Error(std::string("cannot read ") + in + ": " + vcg::tri::io::ImporterPLY<CMeshO>::ErrorMsg(err));
    if (dEdges > 0) {
      growth::MeasureOptions o;
      o.minVertexDistance = false;
      params.sphereDiameter = dEdges * growth::measure(growth::meshlab::meshArrays(input), nullptr, o).edgeMean;
    }

    CMeshO mesh;
    growth::spherepack::RemeshStat st;
    growth::spherepack::remesh(input, mesh, params, st, nullptr);
    std::printf("input_vertices: %zu\ninput_faces: %zu\ninput_components: %zu\ninput_boundary_edges: %zu\n"
                "input_mean_edge: %.6g\nd: %.6g\nd_reason: %s\n",
                st.inputVertices, st.inputFaces, st.inputComponents, st.inputBoundaryEdges, st.inputMeanEdge,
                st.sphereDiameter, st.diameterReason.c_str());
    std::printf("vertices: %zu\nfaces: %zu\nsmallest_edge: %.8g\nsmallest_edge_per_d: %.6f\nq_avg: %.5f\n"
                "boundary_loops: %zu\nholes_closed: %zu\nhole_faces_added: %zu\n"
                "holes_open_long_tri_cover_fold_cross_other: %zu %zu %zu %zu %zu %zu\n"
                "holes: %zu\nregions_outside: %zu\nflat_faces_removed: %zu\n"
                "short_edge_faces_removed: %zu\nfaces_removed: %zu\npieces_dropped: %zu\npiece_faces_dropped: %zu\n"
                "crease_edges: %zu\nfeature_corners: %zu\nfeature_vertices: %zu\nfeature_vertices_skipped: %zu\n"
                "components_started: %zu\nunreached_faces: %zu\ncandidates: %zu\nrequeued: %zu\n"
                "rejected_too_close: %zu\nrejected_crossing: %zu\nrejected_inconsistent: %zu\n",
                st.vertices, st.faces, st.smallestEdge, st.smallestEdge / st.sphereDiameter, st.qualityAvg,
                st.boundaryLoops, st.holesClosed, st.holeFacesAdded, st.holesOpen[0], st.holesOpen[1], st.holesOpen[2], st.holesOpen[3], st.holesOpen[4], st.holesOpen[5], st.holes, st.regionsOutside, st.flatFacesRemoved, st.shortEdgeFacesRemoved, st.facesRemoved, st.piecesDropped, st.pieceFacesDropped,
                st.creaseEdges, st.featureCorners, st.featureVertices, st.featureVerticesSkipped,
                st.componentsStarted, st.unreachedFaces, st.candidates, st.requeued, st.rejectedTooClose,
                st.rejectedCrossing, st.rejectedInconsistent);
    std::printf("seconds_input: %.4f\nseconds_growth: %.4f\nseconds_triangulation: %.4f\nseconds_cleanup: %.4f\n"
                "seconds_output: %.4f\nseconds: %.4f\npeak_rss_kib: %ld\n",
                st.secondsInput, st.secondsGrowth, st.secondsTriangulation, st.secondsCleanup, st.secondsOutput,
                st.seconds, peakRssKiB());
    for (const auto& w : st.warnings) std::printf("warning: %s\n", w.c_str());
    if (measure) {
      const growth::MeshArrays a = growth::meshlab::meshArrays(input), b = growth::meshlab::meshArrays(mesh);
      printMeasures("in", growth::measure(a));
      printMeasures("out", growth::measure(b));
      double mx, mean;
      distances(a, b, mx, mean);
      std::printf("input_to_output_max_per_d: %.5f\ninput_to_output_mean_per_d: %.5f\n", mx / st.sphereDiameter,
                  mean / st.sphereDiameter);
      distances(b, a, mx, mean);
      std::printf("output_to_input_max_per_d: %.3g\noutput_to_input_mean_per_d: %.3g\n", mx / st.sphereDiameter,
                  mean / st.sphereDiameter);
    }
    if (!out.empty()) {
      const int omask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_FACEQUALITY;
      if (vcg::tri::io::ExporterPLY<CMeshO>::Save(mesh, out.c_str(), true, omask) != 0)
        throw growth::Error("cannot write " + out);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spherepack_remesh: %s\n", e.what());
    return 2;
  }
  return 0;
}
