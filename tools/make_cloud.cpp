// make_cloud: writes a seeded point cloud with exact normals as binary PLY.
//   make_cloud --shape sphere|torus|patch|genus2|latlong|hollowball|slab|scan --points N [--seed S]
//              [--nonuniform [--density-ratio R]] [--noise NU] [--gauss SIGMA | --gauss-spacings F]
//              [--outliers FRACTION] [--cluster FRACTION] [--far-points N] [--flip-normals FRACTION]
//              [--parts K (scan)] [--estimate-normals K] -o out.ply
// --estimate-normals K: the normals estimated from the points (PCA over the K nearest, signs
// propagated over the neighbour graph, growth/point_normals.h) instead of the exact ones, as
// MeshLab's "Compute normals for point sets" gives them (its default K is 10).
// --gauss-spacings F: Gaussian noise of sigma F * sqrt(area / N), a fraction of the sampling's
// spacing whatever the size. A scan-like cloud of ten million points:
//   make_cloud --shape scan --parts 6 --points 9803922 --gauss-spacings 0.1 --outliers 0.02
//     --flip-normals 0.01 -o scan10m.ply
#include <growth/cloud_generator.h>
#include <growth/error.h>
#include <growth/point_normals.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

static void usage() {
  std::fprintf(stderr,
               "usage: make_cloud --shape sphere|torus|patch|genus2|latlong|hollowball|slab|scan --points N [--seed S]\n"
               "                  [--nonuniform [--density-ratio R]] [--noise NU] [--gauss SIGMA | --gauss-spacings F]\n"
               "                  [--outliers FRACTION] [--cluster FRACTION] [--far-points N]\n"
               "                  [--flip-normals FRACTION] [--parts K (scan)] [--thickness T (slab)]\n"
               "                  [--estimate-normals K] -o out.ply\n");
}

int main(int argc, char** argv) {
  growth::CloudSpec spec;
  std::string out;
  double gaussSpacings = 0;
  int estimateK = 0;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw growth::Error("missing value after " + a);
        return argv[++i];
      };
      if (a == "--shape") spec.shape = growth::parseShape(value());
      else if (a == "--points") spec.count = std::strtoull(value(), nullptr, 10);
      else if (a == "--seed") spec.seed = std::strtoull(value(), nullptr, 10);
      else if (a == "--nonuniform") spec.nonUniform = true;
      else if (a == "--density-ratio") spec.densityRatio = std::atof(value());
      else if (a == "--noise") spec.noiseBound = std::atof(value());
      else if (a == "--gauss") spec.gaussianSigma = std::atof(value());
      else if (a == "--outliers") spec.outlierFraction = std::atof(value());
      else if (a == "--cluster") spec.clusterFraction = std::atof(value());
      else if (a == "--far-points") spec.farPoints = std::strtoull(value(), nullptr, 10);
      else if (a == "--thickness") spec.slabThickness = std::atof(value());
      else if (a == "--gauss-spacings") gaussSpacings = std::atof(value());
      else if (a == "--flip-normals") spec.flippedNormals = std::atof(value());
      else if (a == "--parts") spec.scanParts = std::atoi(value());
      else if (a == "--estimate-normals") estimateK = std::atoi(value());
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else throw growth::Error("unknown argument " + a);
    }
    if (out.empty()) throw growth::Error("no output file (-o out.ply)");
    if (gaussSpacings > 0) {
      if (spec.gaussianSigma > 0) throw growth::Error("--gauss and --gauss-spacings exclude each other");
      if (spec.count == 0) throw growth::Error("a cloud needs at least one point");
      spec.gaussianSigma = gaussSpacings * std::sqrt(growth::shapeArea(spec) / double(spec.count));
    }
    growth::Cloud c = growth::generateCloud(spec);
    if (estimateK != 0) c.normals = growth::estimateNormals(c.points, estimateK);
    growth::writePly(out, c);
    std::printf("%s: %zu points (%s)\n", out.c_str(), c.points.size(), growth::shapeName(spec.shape));
    if (spec.gaussianSigma > 0) std::printf("gaussian sigma: %.9g\n", spec.gaussianSigma);
    // A scan's parts, for the checks that each is meshed: its ball (centre, radius) and area.
    if (spec.shape == growth::Shape::Scan) {
      const std::vector<growth::ScanPart> parts = growth::scanParts(spec);
      for (size_t i = 0; i < parts.size(); ++i)
        std::printf("part %zu: %s centre %.9g %.9g %.9g radius %.9g area %.9g\n", i, growth::shapeName(parts[i].spec.shape),
                    parts[i].offset[0], parts[i].offset[1], parts[i].offset[2], parts[i].radius, parts[i].area);
    }
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_cloud: %s\n", e.what());
    usage();
    return 2;
  }
  return 0;
}
