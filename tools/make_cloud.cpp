// make_cloud: writes a seeded point cloud with exact normals as binary PLY.
//   make_cloud --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N [--seed S]
//              [--nonuniform [--density-ratio R]] [--noise NU] [--gauss SIGMA] [--outliers FRACTION] [--cluster FRACTION] [--far-points N] -o out.ply
#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

static void usage() {
  std::fprintf(stderr,
               "usage: make_cloud --shape sphere|torus|patch|genus2|latlong|hollowball|slab --points N [--seed S]\n"
               "                  [--nonuniform [--density-ratio R]] [--noise NU] [--gauss SIGMA]\n"
               "                  [--outliers FRACTION] [--thickness T (slab)] -o out.ply\n");
}

int main(int argc, char** argv) {
  growth::CloudSpec spec;
  std::string out;
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
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else throw growth::Error("unknown argument " + a);
    }
    if (out.empty()) throw growth::Error("no output file (-o out.ply)");
    const growth::Cloud c = growth::generateCloud(spec);
    growth::writePly(out, c);
    std::printf("%s: %zu points (%s)\n", out.c_str(), c.points.size(), growth::shapeName(spec.shape));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_cloud: %s\n", e.what());
    usage();
    return 2;
  }
  return 0;
}
