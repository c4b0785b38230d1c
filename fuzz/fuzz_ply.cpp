// libFuzzer target: arbitrary bytes as a PLY file into both engines (harness.h, growth::fuzz::runPly).
#include "harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  growth::fuzz::runPly(data, size);
  return 0;
}
