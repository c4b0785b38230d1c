// spherepack_run: runs the sphere-packing engine outside MeshLab and prints its statistics.
//
//   spherepack_run cloud.ply [options]                  a PLY point cloud with normals
//   spherepack_run --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N [--seed S] [--nonuniform] [--noise NU]
//                  [--outliers FRACTION] [--cluster FRACTION] [--far-points N] [--thickness T (slab)] [options]      a generated cloud
// options: --d D (absolute)  --d-spacings K (d = K · mean spacing)  --s S  --s-d F (s = F · d)
//          --global-splats  --keep-twisted (no twisted-candidate rejection)  --no-hole-pass (holes left as they are)  --w W  --border B  --threads T (0 = automatic)
//          --min-component-faces F (drop pieces with fewer faces; 0 keeps all)
//          --spatial-order-min N (renumber the points spatially from N points on; the same mesh)
//          --repeat R (best of R runs; each phase time is that phase's best)
//          --measure (topology and quality of the result)  --points-only (drop the faces of a mesh)
//          --keep-features [--crease-angle DEG] (crease lines and corners kept)
//          -o out.ply (save the mesh)
// Prints one "key: value" per line. Time is the engine's own (Stat::seconds).
#include "filter_spherepack_layer.h"

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

#include <cstdio>
#include <cstdlib>
#include <string>

static void usage() {
  std::fprintf(stderr,
               "usage: spherepack_run <cloud.ply> | --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N [--seed S] [--nonuniform]\n"
               "                      [--noise NU] [--outliers FRACTION] [--thickness T]\n"
               "       [--d D | --d-spacings K] [--s S | --s-d F] [--global-splats] [--keep-twisted] [--no-hole-pass]\n"
               "       [--w W] [--border B] [--threads T]\n"
               "       [--min-component-faces F]\n"
               "       [--spatial-order-min N]\n"
               "       [--keep-features] [--crease-angle DEG]\n"
               "       [--repeat R] [--measure] [--points-only] [-o out.ply]\n");
}

static long peakRssKiB() {
  struct rusage ru;
  getrusage(RUSAGE_SELF, &ru);
  return ru.ru_maxrss;
}

int main(int argc, char** argv) {
  std::string in, out;
  growth::CloudSpec spec;
  bool generated = false, measure = false, pointsOnly = false;
  double dSpacings = 0, sOverD = 0;
  int repeat = 1;
  growth::spherepack::Params params;
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
      else if (a == "--density-ratio") spec.densityRatio = std::atof(value());
      else if (a == "--noise") spec.noiseBound = std::atof(value());
      else if (a == "--outliers") spec.outlierFraction = std::atof(value());
      else if (a == "--cluster") spec.clusterFraction = std::atof(value());
      else if (a == "--far-points") spec.farPoints = std::strtoull(value(), nullptr, 10);
      else if (a == "--thickness") spec.slabThickness = std::atof(value());
      else if (a == "--d") params.sphereDiameter = std::atof(value());
      else if (a == "--d-spacings") dSpacings = std::atof(value());
      else if (a == "--s") params.splatSize = std::atof(value());
      else if (a == "--s-d") sOverD = std::atof(value());
      else if (a == "--global-splats") params.localSplatSizes = false;
      else if (a == "--keep-twisted") params.rejectTwisted = false;
      else if (a == "--no-hole-pass") params.closeHoles = false;
      else if (a == "--keep-features") params.keepFeatures = true;
      else if (a == "--crease-angle") params.creaseAngleDeg = std::atof(value());
      else if (a == "--w") params.windowSize = std::atoi(value());
      else if (a == "--border") params.maxBorderLength = std::atoi(value());
      else if (a == "--min-component-faces") params.minComponentFaces = std::atoi(value());
      else if (a == "--threads") params.threads = std::atoi(value());
      else if (a == "--spatial-order-min") params.spatialOrderMinPoints = std::strtoull(value(), nullptr, 10);
      else if (a == "--repeat") repeat = std::max(1, std::atoi(value()));
      else if (a == "--measure") measure = true;
      else if (a == "--points-only") pointsOnly = true;
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
      else throw growth::Error("unknown argument " + a);
    }
    if (in.empty() && !generated) throw growth::Error("no input (a PLY file or --shape)");

    CMeshO cloud;
    if (generated) {
      growth::toMesh(growth::generateCloud(spec), cloud);
    } else {
      int mask = 0;
      const int err = vcg::tri::io::ImporterPLY<CMeshO>::Open(cloud, in.c_str(), mask);
      if (err != 0 && vcg::tri::io::ImporterPLY<CMeshO>::ErrorCritical(err))
        throw growth::Error(std::string("cannot read ") + in + ": " + vcg::tri::io::ImporterPLY<CMeshO>::ErrorMsg(err));
      if (pointsOnly) {
        for (auto& f : cloud.face) f.SetD();
        cloud.fn = 0;
        cloud.face.clear();
      }
    }
    if (dSpacings > 0 || sOverD > 0) {
      growth::CloudCheck check;
      check.allowFaces = true;
      // K mean spacings (growth::meanSpacing, the unit of the benchmark and of mesh_measures).
      const auto points = growth::readCloud(cloud, check).points;
      if (dSpacings > 0) params.sphereDiameter = dSpacings * growth::meanSpacing(points);
      if (sOverD > 0) {
        const double d = params.sphereDiameter > 0 ? params.sphereDiameter
                                                   : growth::spherepack::defaultDiameter(growth::spherepack::cloudScale(points));
        params.splatSize = sOverD * d;
      }
    }

    const long rssBefore = peakRssKiB();
    CMeshO mesh;
    growth::spherepack::Stat st;
    double best = 1e300;
    double phase[7] = {1e300, 1e300, 1e300, 1e300, 1e300, 1e300, 1e300}; // each phase's best over the repeats
    for (int r = 0; r < repeat; ++r) {
      growth::spherepack::build(cloud, mesh, params, st, nullptr);
      best = std::min(best, st.seconds);
      const double t[7] = {st.secondsInput, st.secondsBoxGrid, st.secondsSplats, st.secondsGrowth,
                           st.secondsTriangulation, st.secondsCleanup, st.secondsOutput};
      for (int k = 0; k < 7; ++k) phase[k] = std::min(phase[k], t[k]);
    }
    std::printf("spacing: %.6g\n", st.scale.spacing);
    std::printf("median_spacing: %.6g\narea_spacing: %.6g\nnoise: %.6g\nd_reason: %s\n", st.scale.medianSpacing,
                st.scale.areaSpacing, st.scale.noise, st.diameterReason.c_str());
    std::printf("thin_share: %.4f\nsheet_gap: %.6g\n", st.scale.thinShare, st.scale.sheetGap);
    std::printf("points: %zu\nd: %.6g\ns: %.6g\nmean_splat_radius: %.6g\nsplats_unbounded: %zu\nsplats_clamped: %zu\n",
                st.inputPoints, st.sphereDiameter, st.splatSize, st.meanSplatRadius, st.splatsUnbounded, st.splatsClamped);
    std::printf("far_points_left_out: %zu\nflat_faces_removed: %zu\n", st.farPointsLeftOut, st.flatFacesRemoved);
    if (st.farPointsLeftOut > 0) std::printf("far_points_gap: %.6g\n", st.farPointsGap);
    std::printf("boundary_loops_output: %zu\n", st.boundaryLoops);
    std::printf("vertices: %zu\nfaces: %zu\nholes: %zu\nlongest_border: %zu\nmean_border_length: %.3f\nsmallest_edge: %.8g\nq_avg: %.5f\n",
                st.vertices, st.faces, st.holes, st.longestBorder, st.meanBorderLength, st.smallestEdge, st.qualityAvg);
    std::printf("boxes_two_sided: %zu\n", st.boxesTwoSided);
    std::printf("box_references: %zu\n", st.boxReferences);
    std::printf("regions_left_open: %zu\nholes_closed: %zu\nhole_faces_added: %zu\nholes_too_long: %zu\n"
                "holes_not_triangulable: %zu\nholes_not_covered: %zu\nholes_folded: %zu\nholes_crossing: %zu\n"
                "holes_other: %zu\nhole_faces_removed: %zu\nhole_islands_dropped: %zu\n",
                st.regionsLeftOpen, st.holesClosed, st.holeFacesAdded, st.holesTooLong, st.holesNotTriangulable,
                st.holesNotCovered, st.holesFolded, st.holesCrossing, st.holesOther, st.holeFacesRemoved, st.holeIslandsDropped);
    if (params.keepFeatures)
      std::printf("feature_crease_points: %zu\nfeature_lines: %zu\nfeature_corners: %zu\nfeature_vertices: %zu\n"
                  "feature_patches: %zu\n",
                  st.featureCreasePoints, st.featureLines, st.featureCorners, st.featureVertices, st.featurePatches);
    std::printf("boxes: %zu\nboxes_d_too_large: %zu\ncandidates: %zu\nrequeued: %zu\nrejected_too_close: %zu\n"
                "rejected_crossing: %zu\nrejected_inconsistent: %zu\nunreached_points: %zu\ncomponents_started: %zu\nstarts_refused_near_mesh: %zu\ncomponents_dropped: %zu\ncomponent_faces_dropped: %zu\nnon_manifold_vertices_removed: %zu\nself_intersection_faces_removed: %zu\nfaces_removed: %zu\nnon_manifold_vertices: %zu\n",
                st.boxes, st.boxesDTooLarge, st.candidates, st.requeued, st.rejectedTooClose, st.rejectedCrossing,
                st.rejectedInconsistent, st.unreachedPoints, st.componentsStarted, st.startsRefusedNearMesh, st.componentsDropped, st.componentFacesDropped, st.nonManifoldVerticesRemoved,
                st.selfIntersectionFacesRemoved, st.facesRemoved, st.nonManifoldVertices);
    std::printf("seconds_input: %.4f\nseconds_box_grid: %.4f\nseconds_splats: %.4f\nseconds_growth: %.4f\n"
                "seconds_triangulation: %.4f\nseconds_cleanup: %.4f\nseconds_output: %.4f\n",
                phase[0], phase[1], phase[2], phase[3], phase[4], phase[5], phase[6]);
    std::printf("seconds: %.4f\nvertices_per_second: %.0f\npeak_rss_kib: %ld\nbytes_per_point_rss: %.1f\n"
                "peak_rss_before_build_kib: %ld\nbytes_per_point_engine: %.1f\n",
                best, double(st.vertices) / best, peakRssKiB(), 1024.0 * double(peakRssKiB()) / double(st.inputPoints),
                rssBefore, 1024.0 * double(peakRssKiB() - rssBefore) / double(st.inputPoints));
    std::printf("memory_estimate_bytes: %zu\nmemory_peak_bytes: %zu\nmemory_bytes_per_point: %.1f\nmemory_input_bytes: %zu\nmemory_box_grid_bytes: %zu\n"
                "memory_growth_bytes: %zu\nmemory_faces_bytes: %zu\nmemory_output_bytes: %zu\n",
                st.memory.estimate, st.memory.peak, double(st.memory.peak) / double(std::max<size_t>(st.inputPoints, 1)), st.memory.input,
                st.memory.boxGrid, st.memory.growth, st.memory.faces, st.memory.output);
    for (const auto& w : st.warnings) std::printf("warning: %s\n", w.c_str());
    if (measure) {
      const growth::MeshMeasures m = growth::measure(mesh);
      std::printf("e_avg: %.6g\ne_rms_percent: %.3f\ne_min: %.8g\nq_rms_percent: %.3f\nmin_vertex_distance: %.8g\n",
                  m.edgeMean, m.edgeRmsPercent, m.edgeMin, m.qualityRmsPercent, m.minVertexDistance);
      std::printf("boundary_edges: %zu\nboundary_loops: %zu\nnon_manifold_edges: %zu\nnon_manifold_vertices_measured: %zu\n"
                  "inconsistent_edges: %zu\ncomponents: %zu\nunreferenced: %zu\neuler: %d\nself_intersecting_pairs: %zu\n",
                  m.boundaryEdges, m.boundaryLoops, m.nonManifoldEdges, m.nonManifoldVertices, m.inconsistentEdges,
                  m.components, m.unreferencedVertices, m.eulerCharacteristic, m.selfIntersectingPairs);
      if (generated) {
        double worst = 0;
        for (const auto& v : mesh.vert) worst = std::max(worst, growth::distanceToShape(spec, growth::Vec3d::Construct(v.cP())));
        std::printf("max_distance_to_shape: %.6g\n", worst);
      }
    }
    if (!out.empty()) {
      const int mask = vcg::tri::io::Mask::IOM_VERTNORMAL | vcg::tri::io::Mask::IOM_FACEQUALITY;
      if (vcg::tri::io::ExporterPLY<CMeshO>::Save(mesh, out.c_str(), true, mask) != 0)
        throw growth::Error("cannot write " + out);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "spherepack_run: %s\n", e.what());
    return 2;
  }
  return 0;
}
