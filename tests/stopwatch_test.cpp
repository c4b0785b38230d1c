// growth::Stopwatch: laps partition the elapsed time, and neither laps nor the total go backwards.
#include <growth/stopwatch.h>

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

namespace {

TEST(Stopwatch, LapsAreNonNegativeAndAddUpToAtMostTheTotal) {
  growth::Stopwatch watch;
  std::this_thread::sleep_for(std::chrono::milliseconds(20));
  const double first = watch.lap();
  std::this_thread::sleep_for(std::chrono::milliseconds(5));
  const double second = watch.lap();
  const double total = watch.total();
  EXPECT_GE(first, 0.019); // slept at least 20 ms (steady clock, 1 ms of rounding allowed)
  EXPECT_GE(second, 0.004);
  EXPECT_LE(first + second, total);
}

TEST(Stopwatch, LapMeasuresFromThePreviousLapNotFromTheStart) {
  growth::Stopwatch watch;
  std::this_thread::sleep_for(std::chrono::milliseconds(30));
  watch.lap();
  const double quick = watch.lap(); // nothing happened since the previous lap
  EXPECT_LT(quick, 0.025);
  EXPECT_GE(watch.total(), 0.029);
}

} // namespace
