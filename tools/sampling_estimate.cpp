// sampling_estimate: growth::estimateSampling on a cloud, with its time, the mean spacing for
// comparison and, for a generated cloud, the values it should find.
//
//   sampling_estimate cloud.ply [options]              a PLY point cloud (binary or ASCII)
//   sampling_estimate --shape sphere|torus|patch|genus2 --points N [--seed S]
//                     [--nonuniform [--density-ratio R]] [--noise NU_IN_SPACINGS]
//                     [--gauss SIGMA_IN_SPACINGS] [--outliers FRACTION] [--far] [options]
// options: --k K (neighbours)  --threads T  --repeat R (best of R runs)
// --noise and --gauss are in units of the clean cloud's estimated spacing (computed first);
// --far appends one point 10^4 times the cloud's size away.
// Prints one "key: value" per line; times are the fastest of the repeats, wall clock (ms) and
// process CPU time (cpu_ms, less sensitive to other load on the machine); *_ratio lines compare
// with the expected values: the area per point with area / points, the spacing with the Poisson
// median 0.4697 sqrt(area / points), the noise with the generator's bound (nu) or sigma.
#include <growth/meshlab/layer.h>
#include <growth/cloud_generator.h>
#include <growth/cloud_scale.h>
#include <growth/error.h>
#include <growth/input_cloud.h>

#include <common/ml_mesh_type.h>
#include <wrap/io_trimesh/import_ply.h>

#include <time.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <string>

static void usage() {
  std::fprintf(stderr,
               "usage: sampling_estimate <cloud.ply> | --shape sphere|torus|patch|genus2 --points N [--seed S]\n"
               "                         [--nonuniform [--density-ratio R]] [--noise NU_IN_SPACINGS]\n"
               "                         [--gauss SIGMA_IN_SPACINGS] [--outliers FRACTION] [--far]\n"
               "                         [--k K] [--threads T] [--repeat R]\n");
}

static double seconds(clockid_t clock) {
  timespec t;
  clock_gettime(clock, &t);
  return double(t.tv_sec) + 1e-9 * double(t.tv_nsec);
}

int main(int argc, char** argv) {
  std::string in;
  growth::CloudSpec spec;
  growth::SamplingOptions options;
  bool generated = false, far = false;
  double noiseSpacings = 0, gaussSpacings = 0;
  int threads = 0, repeat = 1;
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
      else if (a == "--noise") noiseSpacings = std::atof(value());
      else if (a == "--gauss") gaussSpacings = std::atof(value());
      else if (a == "--outliers") spec.outlierFraction = std::atof(value());
      else if (a == "--far") far = true;
      else if (a == "--k") options.neighbours = std::atoi(value());
      else if (a == "--threads") threads = std::atoi(value());
      else if (a == "--repeat") repeat = std::max(1, std::atoi(value()));
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else if (!a.empty() && a[0] != '-' && in.empty()) in = a;
      else throw growth::Error("unknown argument " + a);
    }
    if (in.empty() && !generated) throw growth::Error("no input (a PLY file or --shape)");

    std::vector<growth::Vec3d> points;
    if (generated) {
      if (noiseSpacings > 0 || gaussSpacings > 0) {
        growth::CloudSpec clean = spec;
        clean.outlierFraction = 0;
        const double spacing = growth::estimateSampling(growth::generateCloud(clean).points, options, threads).medianSpacing;
        spec.noiseBound = noiseSpacings * spacing;
        spec.gaussianSigma = gaussSpacings * spacing;
      }
      points = growth::generateCloud(spec).points;
    } else {
      CMeshO m;
      int mask = 0;
      const int err = vcg::tri::io::ImporterPLY<CMeshO>::Open(m, in.c_str(), mask);
      if (err != 0 && vcg::tri::io::ImporterPLY<CMeshO>::ErrorCritical(err))
        throw growth::Error(std::string("cannot read ") + in + ": " + vcg::tri::io::ImporterPLY<CMeshO>::ErrorMsg(err));
      for (const auto& v : m.vert)
        if (!v.IsD()) points.push_back(growth::Vec3d::Construct(v.cP()));
    }
    if (far && !points.empty()) {
      growth::Box3d box;
      for (const auto& p : points) box.Add(p);
      points.push_back(box.max + growth::Vec3d(1, 1, 1) * (1e4 * box.Diag()));
    }

    growth::SamplingEstimate e;
    double best = 1e300, bestCpu = 1e300, bestMean = 1e300, bestMeanCpu = 1e300, mean = 0;
    for (int r = 0; r < repeat; ++r) {
      double t = seconds(CLOCK_MONOTONIC), c = seconds(CLOCK_PROCESS_CPUTIME_ID);
      e = growth::estimateSampling(points, options, threads);
      best = std::min(best, seconds(CLOCK_MONOTONIC) - t);
      bestCpu = std::min(bestCpu, seconds(CLOCK_PROCESS_CPUTIME_ID) - c);
      t = seconds(CLOCK_MONOTONIC), c = seconds(CLOCK_PROCESS_CPUTIME_ID);
      mean = growth::meanSpacing(points, growth::kMeanSpacingSamples, threads);
      bestMean = std::min(bestMean, seconds(CLOCK_MONOTONIC) - t);
      bestMeanCpu = std::min(bestMeanCpu, seconds(CLOCK_PROCESS_CPUTIME_ID) - c);
    }
    std::printf("points: %zu\nk: %d\nspacing: %.6g\narea_per_point: %.6g\narea_spacing: %.6g\n", points.size(),
                options.neighbours, e.medianSpacing, e.areaPerPoint, std::sqrt(e.areaPerPoint));
    std::printf("noise_sigma: %.6g\nnoise: %.6g\nnoise_over_spacing: %.4f\n", e.noiseSigma, e.noise,
                e.medianSpacing > 0 ? e.noise / e.medianSpacing : 0.0);
    std::printf("samples: %zu\nisolated: %zu\nnoise_samples: %zu\n", e.samples, e.isolated, e.noiseSamples);
    std::printf("ms: %.2f\ncpu_ms: %.2f\nmean_spacing: %.6g\nmean_spacing_ms: %.2f\nmean_spacing_cpu_ms: %.2f\n",
                1e3 * best, 1e3 * bestCpu, mean, 1e3 * bestMean, 1e3 * bestMeanCpu);
    if (generated) {
      const double a = growth::shapeArea(spec) / double(spec.count);
      std::printf("area_ratio: %.4f\nspacing_ratio: %.4f\n", e.areaPerPoint / a,
                  e.medianSpacing / std::sqrt(a * std::log(2.0) / 3.14159265358979323846));
      if (spec.noiseBound > 0) std::printf("noise_ratio: %.4f\n", e.noise / spec.noiseBound);
      if (spec.gaussianSigma > 0) std::printf("sigma_ratio: %.4f\n", e.noiseSigma / spec.gaussianSigma);
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "sampling_estimate: %s\n", ex.what());
    usage();
    return 2;
  }
  return 0;
}
