// Replays every input the fuzzers kept (fuzz/regressions/<target>/: inputs that once crashed or
// broke a post-condition, each named after the finding it fixed) and the seed corpora
// (fuzz/corpus/<target>/) through the fuzz targets' own entry points (fuzz/harness.h). Runs in the
// normal suite and, with the sanitizers, in scripts/sanitize.sh.
#include <harness.h>

#include <gtest/gtest.h>

#include <dirent.h>

#include <algorithm>
#include <cstdint>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

namespace {

const std::string kFuzzDir = GROWTH_FUZZ_DIR;

// The regular files of a folder, sorted by name; none when it does not exist.
std::vector<std::string> filesIn(const std::string& dir) {
  std::vector<std::string> names;
  if (DIR* d = opendir(dir.c_str())) {
    while (const dirent* e = readdir(d))
      if (e->d_name[0] != '.') names.push_back(dir + "/" + e->d_name);
    closedir(d);
  }
  std::sort(names.begin(), names.end());
  return names;
}

std::vector<std::uint8_t> bytesOf(const std::string& path) {
  std::ifstream f(path, std::ios::binary);
  return std::vector<std::uint8_t>(std::istreambuf_iterator<char>(f), std::istreambuf_iterator<char>());
}

// Runs every file of `dir` through `run`; returns how many.
template <class Run>
size_t replay(const std::string& dir, Run run) {
  const std::vector<std::string> files = filesIn(dir);
  for (const std::string& path : files) {
    SCOPED_TRACE(path);
    const std::vector<std::uint8_t> bytes = bytesOf(path);
    EXPECT_NO_THROW(run(bytes.data(), bytes.size()));
  }
  return files.size();
}

} // namespace

TEST(FuzzRegressions, PlyInputs) { replay(kFuzzDir + "/regressions/ply", growth::fuzz::runPly); }

TEST(FuzzRegressions, CloudInputs) { replay(kFuzzDir + "/regressions/cloud", growth::fuzz::runCloud); }

TEST(FuzzCorpus, PlySeeds) { EXPECT_GT(replay(kFuzzDir + "/corpus/ply", growth::fuzz::runPly), 0u); }

TEST(FuzzCorpus, CloudSeeds) { EXPECT_GT(replay(kFuzzDir + "/corpus/cloud", growth::fuzz::runCloud), 0u); }

// The harness itself: an empty input and a few short ones are valid recipes and refused PLY files.
TEST(FuzzHarness, ShortInputs) {
  const std::uint8_t bytes[4] = {0, 1, 2, 255};
  for (size_t n = 0; n <= sizeof bytes; ++n) {
    EXPECT_NO_THROW(growth::fuzz::runPly(bytes, n));
    EXPECT_NO_THROW(growth::fuzz::runCloud(bytes, n));
  }
}
