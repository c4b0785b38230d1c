// g2s_run: runs the Robust G2S engine outside MeshLab and prints faces, defects, time and rate.
//
//   g2s_run cloud.ply [options]                      a PLY point cloud (binary or ASCII)
//   g2s_run --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N [--seed S] [--nonuniform]
//           [--gauss SIGMA_IN_SPACINGS] [--outliers FRACTION] [--cluster FRACTION] [--far-points N]
//           [--rings R --segments S] [--inner-radius r] [--thickness T] [options]   a generated cloud
// adversarial addition to either: --near-triples K (K points of the cloud each get two more within a
// few float rounding steps: seeds of almost no size)
// options: --k K  --max-radius F  --n N  --m M  --no-cleanup  --holes E (close holes of <= E edges; 0 off)  --keep-handles
//          --min-component-faces F (drop pieces with fewer faces; 0 keeps all)
//          --random-seed S  --threads T (crossing-face test; 0 = automatic)
//          --no-thin-rules (the paper's candidate choice at thin parts: g2s::Params::thinPartRules)
//          --no-loop-closures (no ear or four-edge loop closure in the growth: g2s::Params::loopClosures)
//          --no-clump-merge (dense clumps meshed point by point: g2s::Params::mergeClumps)
//          --repeat R (best of R runs)  --measure (topology and quality of the result)
//          -o out.ply (save the mesh)
// Prints one "key: value" per line. Time is the engine's own (g2s::Stat::seconds, wall clock);
// cpu_seconds is the process CPU time spent in the engine (less sensitive to other load);
// engine_page_faults_first_run counts the minor page faults of the first run (each costs several
// microseconds of kernel time on a virtual machine).
#include "filter_g2s_layer.h"
#include "g2s_near.h"

#include <growth/meshlab/layer.h>
#include <growth/cloud_scale.h>
#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/input_cloud.h>
#include <growth/mesh_measures.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/export_ply.h>
#include <wrap/io_trimesh/import_ply.h>

#include <sys/resource.h>
#include <time.h>

#include <cstdio>
#include <cstdlib>
#include <cmath>
#include <cstring>
#include <string>
#include <vector>

static void usage() {
  std::fprintf(stderr,
               "usage: g2s_run <cloud.ply> | --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N\n"
               "               [--seed S] [--nonuniform] [--gauss SIGMA_IN_SPACINGS] [--outliers FRACTION]\n"
               "               [--rings R --segments S] [--inner-radius r] [--thickness T]\n"
               "       [--near-triples K]\n"
               "       [--k K] [--max-radius F] [--n N] [--m M] [--no-cleanup] [--holes E] [--keep-handles] [--min-component-faces F] [--random-seed S] [--threads T] [--no-thin-rules]\n"
               "       [--no-loop-closures] [--no-clump-merge]\n"
               "       [--repeat R] [--measure] [-o out.ply]\n");
}

static double cpuSeconds() {
  timespec t;
  clock_gettime(CLOCK_PROCESS_CPUTIME_ID, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

static long minorFaults() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_minflt;
}

static long peakRssKiB() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

int main(int argc, char** argv) {
  std::string in, out;
  growth::CloudSpec spec;
  bool generated = false, measure = false;
  double gaussSpacings = 0;
  int repeat = 1;
  int nearTriples = 0;
  growth::g2s::Params params;
  params.maxSearchRadiusFactor = 0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw growth::Error("missing value after " + a);
        return argv[++i];
      };
      if (a == "--shape") spec.shape = growth::parseShape(value()), generated = true;
      else if (a == "--points") spec.count = std::strtoull(value(), nullptr, 10);
      else if (a == "--seed") spec.seed = std::strtoull(value(), nullptr, 10);
      else if (a == "--nonuniform") spec.nonUniform = true;
      else if (a == "--gauss") gaussSpacings = std::atof(value());
      else if (a == "--outliers") spec.outlierFraction = std::atof(value());
      else if (a == "--cluster") spec.clusterFraction = std::atof(value());
      else if (a == "--far-points") spec.farPoints = std::strtoull(value(), nullptr, 10);
      else if (a == "--rings") spec.latitudeRings = std::atoi(value());
      else if (a == "--segments") spec.longitudeSegments = std::atoi(value());
      else if (a == "--inner-radius") spec.innerRadius = std::atof(value());
      else if (a == "--thickness") spec.slabThickness = std::atof(value());
      else if (a == "--near-triples") nearTriples = std::atoi(value());
      else if (a == "--k") params.seedSearchFactor = std::atof(value());
      else if (a == "--max-radius") params.maxSearchRadiusFactor = std::atof(value());
      else if (a == "--n") params.sizeLevels = std::atoi(value());
      else if (a == "--m") params.flatnessLevels = std::atoi(value());
      else if (a == "--no-cleanup") params.removeNonManifoldVertices = false;
      else if (a == "--holes") params.maxHoleEdges = std::atoi(value());
      else if (a == "--keep-handles") params.removeSmallHandles = false;
      else if (a == "--min-component-faces") params.minComponentFaces = std::atoi(value());
      else if (a == "--no-thin-rules") params.thinPartRules = false;
      else if (a == "--no-loop-closures") params.loopClosures = false;
      else if (a == "--no-clump-merge") params.mergeClumps = false;
      else if (a == "--threads") params.threads = std::atoi(value());
      else if (a == "--random-seed") params.randomSeed = std::strtoull(value(), nullptr, 10);
      else if (a == "--repeat") repeat = std::max(1, std::atoi(value()));
      else if (a == "--measure") measure = true;
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
      else throw growth::Error("unknown argument " + a);
    }
    if (in.empty() == !generated) { usage(); return 2; }

    CMeshO cloud;
    if (generated) {
      if (gaussSpacings > 0) {
        // Noise in units of the clean cloud's mean spacing (Robust G2S, sec. 5.2).
        growth::CloudSpec clean = spec;
        clean.outlierFraction = 0;
        spec.gaussianSigma = gaussSpacings * growth::meanSpacing(growth::generateCloud(clean).points);
      }
      growth::toMesh(growth::generateCloud(spec), cloud);
    } else {
      int mask = 0;
      if (vcg::tri::io::ImporterPLY<CMeshO>::Open(cloud, in.c_str(), mask) != 0) {
        std::fprintf(stderr, "g2s_run: cannot read %s\n", in.c_str());
        return 1;
      }
      // Only the points are meshed.
      if (cloud.fn > 0) {
        for (auto& f : cloud.face) f.SetD();
        cloud.fn = 0;
      }
    }
    if (nearTriples > 0 && cloud.vn > 0) {
      // Every (vn / K)-th point gets two companions a few float steps away along x and y.
      const size_t n = cloud.vert.size(), stride = std::max<size_t>(1, n / size_t(nearTriples));
      std::vector<vcg::Point3f> extra;
      for (size_t i = 0; i < n && extra.size() < 2 * size_t(nearTriples); i += stride) {
        const vcg::Point3f p = cloud.vert[i].cP();
        vcg::Point3f q = p, r = p;
        for (int k = 0; k < 3; ++k) q[0] = std::nextafter(q[0], 1e30f);
        for (int k = 0; k < 3; ++k) r[1] = std::nextafter(r[1], 1e30f);
        extra.push_back(q);
        extra.push_back(r);
      }
      auto vi = vcg::tri::Allocator<CMeshO>::AddVertices(cloud, extra.size());
      for (const auto& p : extra) (vi++)->P() = p;
    }

    CMeshO mesh;
    growth::g2s::Stat st;
    double best = 1e300, bestCpu = 1e300;
    long faults = 0;
    for (int r = 0; r < repeat; ++r) {
      const double c0 = cpuSeconds();
      const long f0 = minorFaults();
      growth::g2s::build(cloud, mesh, params, st);
      bestCpu = std::min(bestCpu, cpuSeconds() - c0);
      if (r == 0) faults = minorFaults() - f0;
      best = std::min(best, st.seconds);
    }
    std::printf("points: %zu\n", st.inputPoints);
    std::printf("duplicates_dropped: %zu\n", st.duplicatesDropped);
    std::printf("clumps: %zu\nclump_points_merged: %zu\n", st.clumps, st.clumpPointsMerged);
    std::printf("spacing: %.6g\n", st.spacing);
    std::printf("faces: %zu\n", st.faces);
    std::printf("faces_per_point: %.4f\n", double(st.faces) / double(st.inputPoints));
    std::printf("vertices: %zu\n", st.vertices);
    std::printf("unused_points: %zu\n", st.unusedPoints);
    std::printf("boundary_edges: %zu\n", st.boundaryEdges);
    std::printf("holes: %zu\n", st.holes);
    std::printf("seeds: %zu\n", st.seeds);
    std::printf("seed_attempts: %zu\ncylinder_queries: %zu\n", st.seedAttempts, st.cylinderQueries);
    std::printf("points_visited: %llu\n", static_cast<unsigned long long>(st.pointsVisited));
    std::printf("candidate_searches: %llu\n", static_cast<unsigned long long>(st.candidateSearches));
    std::printf("non_manifold_vertices_removed: %zu\n", st.nonManifoldVerticesRemoved);
    std::printf("faces_removed: %zu\n", st.facesRemoved);
    std::printf("non_manifold_vertices_left: %zu\n", st.nonManifoldVertices);
    std::printf("self_intersection_faces_removed: %zu\n", st.selfIntersectionFacesRemoved);
    std::printf("holes_closed: %zu\nhole_faces_added: %zu\nhole_faces_replaced: %zu\nhole_spikes_removed: %zu\n",
                st.holesClosed, st.holeFacesAdded, st.holeFacesReplaced, st.holeSpikes);
    std::printf("holes_widened: %zu\nhole_faces_widened: %zu\nholes_regrown: %zu\n", st.holesWidened,
                st.holeFacesWidened, st.holesRegrown);
    std::printf("handles_cut: %zu\nhandle_faces_removed: %zu\nhandle_faces_added: %zu\nhandles: %zu\n", st.handlesCut,
                st.handleFacesRemoved, st.handleFacesAdded, st.handles);
    std::printf("pieces_dropped: %zu\npiece_faces_dropped: %zu\n", st.componentsDropped, st.componentFacesDropped);
    std::printf("pieces: %zu\npieces_flipped: %zu\n", st.components, st.componentsFlipped);
    std::printf("edges_left_at_full_points: %zu\n", st.edgesLeftAtFullPoints);
    std::printf("thin_part_refusals: %zu\n", st.thinPartRefusals);
    std::printf("seconds: %.4f\n", best);
    std::printf("seconds_phases: setup %.4f growth %.4f cleanup %.4f output %.4f\n", st.secondsSetup,
                st.secondsGrowth, st.secondsCleanup, st.secondsOutput);
    for (const auto& pass : st.passes)
      std::printf("pass: %s | faces out %zu | faces in %zu | seconds %.4f\n", pass.name.c_str(), pass.facesRemoved,
                  pass.facesAdded, pass.seconds);
    std::printf("triangles_per_second: %.0f\n", double(st.faces) / best);
    std::printf("cpu_seconds: %.4f\n", bestCpu);
    std::printf("simd: %s\n", growth::g2s::simdLevelName(growth::g2s::simdLevel()));
    std::printf("triangles_per_cpu_second: %.0f\n", double(st.faces) / bestCpu);
    std::printf("engine_page_faults_first_run: %ld\n", faults);
    std::printf("working_bytes_per_point: %.1f\n", double(st.workingBytes) / double(st.inputPoints));
    std::printf("peak_rss_mib: %.1f\n", double(peakRssKiB()) / 1024.0);
    for (const auto& w : st.warnings) std::printf("warning: %s\n", w.c_str());
    if (measure) {
      growth::CloudCheck check;
      const growth::InputCloud ic = growth::readCloud(cloud, check);
      growth::MeasureOptions mo;
      mo.minVertexDistance = false;
      const growth::MeshMeasures mm = growth::measure(mesh, &ic.points, mo);
      std::printf("measures: %s\n", mm.toJson().c_str());
    }
    if (!out.empty()) {
      vcg::tri::io::ExporterPLY<CMeshO>::Save(mesh, out.c_str(), vcg::tri::io::Mask::IOM_FACEQUALITY, true);
      std::printf("saved: %s\n", out.c_str());
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "g2s_run: %s\n", e.what());
    return 1;
  }
  return 0;
}
