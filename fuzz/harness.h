#pragma once
// What the fuzz targets feed both engines (growth::spherepack::build, growth::g2s::build), in a
// library of its own so that the libFuzzer targets (fuzz_ply.cpp, fuzz_cloud.cpp) and the
// regression test (tests/fuzz_regressions_test.cpp, which replays fuzz/regressions/) run the same
// code.
//
// Contract checked on every input: each engine either builds a mesh that passes checkOutput, or
// refuses the input with growth::Error (a non-empty message), or stops with growth::Cancelled
// when the harness's progress callback asked it to, leaving its output empty. Anything else (a
// crash, another exception, a broken post-condition, and in sanitizer builds UB or a leak) is a
// finding. A broken post-condition throws std::logic_error; other exceptions pass through.
//
// Work per input is bounded by the harness, not by the engines: at most kMaxPoints points (larger
// inputs are skipped) and at most kMaxOutputVertices output vertices for the sphere packer
// (Params::maxOutputVertices), so that every input runs in well under a second.
#include <cstddef>
#include <cstdint>

class CMeshO;

namespace growth {
namespace fuzz {

constexpr size_t kMaxPoints = 3000;
constexpr size_t kMaxOutputVertices = 10000;
// PLY inputs whose header declares more elements than this are skipped before vcglib's importer
// allocates them (it reserves what the header says, whatever the file's size).
constexpr size_t kMaxPlyElements = 20000;

// The bytes as a PLY file, read by vcglib's importer into a CMeshO as the tools do, then both
// engines with their defaults (single-threaded).
void runPly(const std::uint8_t* data, size_t size);

// The bytes as a recipe: a cloud (shape, count, noise, outliers, duplicates, degenerate layouts,
// NaN/inf, huge or tiny coordinates, bad normals) and parameters for both engines (d, s, window,
// border limit, G2S levels and radii, 1 or 2 threads, cancelling). Missing bytes read as zeros,
// so every byte string is a recipe.
void runCloud(const std::uint8_t* data, size_t size);

// The post-conditions of a built mesh: vertices and faces counted as the statistics say, every
// face's corners distinct live vertices of `out`, every coordinate finite.
void checkOutput(const CMeshO& out, size_t statVertices, size_t statFaces, const char* engine);

} // namespace fuzz
} // namespace growth
