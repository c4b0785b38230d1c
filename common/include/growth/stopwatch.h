#pragma once
// Wall-clock timing of an engine's phases (Stat::seconds*): lap() gives the seconds since the
// previous lap (or the start), total() the seconds since the start. Steady clock: immune to
// changes of the system time.
#include <chrono>

namespace growth {

class Stopwatch {
public:
  using Clock = std::chrono::steady_clock;

  Stopwatch() : start_(Clock::now()), last_(start_) {}

  double lap() {
    const Clock::time_point now = Clock::now();
    const double s = std::chrono::duration<double>(now - last_).count();
    last_ = now;
    return s;
  }

  double total() const { return std::chrono::duration<double>(Clock::now() - start_).count(); }

private:
  Clock::time_point start_, last_;
};

} // namespace growth
