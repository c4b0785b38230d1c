// make_mesh: writes a seeded, irregularly triangulated mesh (growth/mesh_generator.h) as binary PLY:
// CAD parts with creases and corners, and an open sheet with holes, for the remeshing benchmark.
//   make_mesh --shape box|cylinder|lprism|holedbox|openbox|sheet [--faces N] [--seed S] [--jitter J] -o out.ply
// Prints the face and vertex counts and the shape's components, boundary loops and genus.
#include <growth/error.h>
#include <growth/mesh_generator.h>

#include <cstdio>
#include <cstdlib>
#include <string>

static void usage() {
  std::fprintf(stderr, "usage: make_mesh --shape box|cylinder|lprism|holedbox|openbox|sheet [--faces N] [--seed S] "
                       "[--jitter J] -o out.ply\n");
}

int main(int argc, char** argv) {
  growth::MeshSpec spec;
  std::string out;
  try {
    for (int i = 1; i < argc; ++i) {
      const std::string a = argv[i];
      auto value = [&]() -> const char* {
        if (i + 1 >= argc) throw growth::Error("missing value after " + a);
        return argv[++i];
      };
      if (a == "--shape") spec.shape = growth::parseMeshShape(value());
      else if (a == "--faces") spec.faces = std::strtoull(value(), nullptr, 10);
      else if (a == "--seed") spec.seed = std::strtoull(value(), nullptr, 10);
      else if (a == "--jitter") spec.jitter = std::atof(value());
      else if (a == "-o") out = value();
      else if (a == "-h" || a == "--help") { usage(); return 0; }
      else throw growth::Error("unknown argument " + a);
    }
    if (out.empty()) throw growth::Error("no output file (-o out.ply)");
    const growth::MeshArrays mesh = growth::generateMesh(spec);
    growth::writeMeshPly(out, mesh);
    const growth::MeshShapeTopology t = growth::shapeTopology(spec.shape);
    std::printf("%s: %zu faces, %zu vertices (%s)\n", out.c_str(), mesh.faces.size(), mesh.vertices.size(),
                growth::meshShapeName(spec.shape));
    std::printf("components: %zu\nboundary_loops: %zu\ngenus: %d\n", t.components, t.boundaryLoops, t.genus);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "make_mesh: %s\n", e.what());
    usage();
    return 2;
  }
  return 0;
}
