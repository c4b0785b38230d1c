#include <growth/progress.h>

#include <gtest/gtest.h>

#include <vector>

namespace {
std::vector<int> calls;
int stopAt = -1;
bool record(const int pos, const char*) {
  calls.push_back(pos);
  return stopAt < 0 || pos < stopAt;
}
} // namespace

TEST(Progress, ThrottlesToPercentChanges) {
  calls.clear();
  stopAt = -1;
  growth::Progress p(&record);
  p.phase("work", 0, 100);
  for (size_t i = 0; i < 1000000; ++i) p.tick(i, 1000000, 1);
  EXPECT_LE(calls.size(), 101u);
  EXPECT_GE(calls.size(), 90u);
  for (size_t i = 1; i < calls.size(); ++i) EXPECT_GT(calls[i], calls[i - 1]);
}

TEST(Progress, PhasesMapIntoTheirRange) {
  calls.clear();
  stopAt = -1;
  growth::Progress p(&record);
  p.phase("second half", 50, 100);
  p.update(0.5);
  p.update(2.0); // clamped
  ASSERT_EQ(calls.size(), 3u);
  EXPECT_EQ(calls[0], 50);
  EXPECT_EQ(calls[1], 75);
  EXPECT_EQ(calls[2], 100);
}

TEST(Progress, FalseFromTheCallbackCancels) {
  calls.clear();
  stopAt = 30;
  growth::Progress p(&record);
  p.phase("work", 0, 100);
  EXPECT_THROW(
      {
        for (int i = 0; i <= 100; ++i) p.update(i / 100.0);
      },
      growth::Cancelled);
  EXPECT_EQ(calls.back(), 30);
}

TEST(Progress, NoCallbackIsANoOp) {
  growth::Progress p(nullptr);
  p.phase("x", 0, 100);
  EXPECT_NO_THROW(p.update(0.5));
}

// advanceTo() reports every percentage up to the new fraction once, in order, so the callbacks
// do not depend on which fractions the calls hit (work shared by threads).
TEST(Progress, AdvanceToReportsEveryPercentOnce) {
  for (const std::vector<double>& fractions :
       {std::vector<double>{0.1, 0.55, 1.0}, std::vector<double>{0.0, 0.02, 0.3, 0.3, 0.29, 0.9, 1.0},
        std::vector<double>{1.0}}) {
    calls.clear();
    stopAt = -1;
    growth::Progress p(&record);
    p.phase("threads", 20, 40);
    for (double f : fractions) p.advanceTo(f);
    ASSERT_EQ(calls.size(), 21u); // 20 from phase(), then 21 .. 40
    for (int k = 0; k <= 20; ++k) EXPECT_EQ(calls[size_t(k)], 20 + k);
  }
  calls.clear();
  stopAt = 27;
  growth::Progress p(&record);
  p.phase("threads", 20, 40);
  EXPECT_THROW(p.advanceTo(1.0), growth::Cancelled);
  EXPECT_EQ(calls.back(), 27);
}
