// libFuzzer target: arbitrary bytes as the recipe of a cloud and of both engines' parameters
// (harness.h, growth::fuzz::runCloud).
#include "harness.h"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, size_t size) {
  growth::fuzz::runCloud(data, size);
  return 0;
}
