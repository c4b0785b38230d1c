#pragma once
// Throttled progress reporting through a host's callback (CallBackPos).
//
// Long loops call `update(fraction)` as often as they like; the callback itself is invoked only
// when the integer percentage inside the phase's range changes (at most ~100 times per phase), so a
// host's UI is not flooded. A callback returning false cancels: update() throws growth::Cancelled.
#include <growth/error.h>

#include <algorithm>
#include <string>

namespace growth {

// A host's progress callback: the percentage and a label; false asks to stop. The same signature
// as vcglib's CallBackPos, so MeshLab's callback is passed straight through.
using CallBackPos = bool(int, const char*);

class Progress {
public:
  explicit Progress(CallBackPos* cb) : cb_(cb) {}

  // Starts a phase that covers percentages [from, to] of the whole run.
  void phase(const std::string& label, int from, int to) {
    label_ = label;
    from_ = from;
    to_ = to;
    last_ = -1;
    update(0.0);
  }

  // Reports progress inside the current phase; fraction in [0, 1].
  void update(double fraction) {
    if (cb_ == nullptr) return;
    if (fraction < 0.0) fraction = 0.0;
    if (fraction > 1.0) fraction = 1.0;
    const int percent = from_ + static_cast<int>(fraction * (to_ - from_));
    if (percent == last_) return;
    last_ = percent;
    if (!cb_(percent, label_.c_str())) throw Cancelled();
  }

  // Like update(), but reports every integer percentage between the last reported one and the
  // new one, each once and in order: the sequence of callbacks then depends only on how far the
  // phase got, not on which fractions the calls happened to hit. For work handed out to threads
  // (parallel.h), where the calling thread sees a scheduling-dependent subset of the fractions;
  // call advanceTo(1) when the work is done.
  void advanceTo(double fraction) {
    if (cb_ == nullptr) return;
    if (fraction < 0.0) fraction = 0.0;
    if (fraction > 1.0) fraction = 1.0;
    const int percent = from_ + static_cast<int>(fraction * (to_ - from_));
    for (int p = std::max(last_ + 1, from_); p <= percent; ++p) {
      last_ = p;
      if (!cb_(p, label_.c_str())) throw Cancelled();
    }
  }

  // Cheap check for hot loops: call update() only every `stride` iterations.
  void tick(size_t i, size_t n, size_t stride = 4096) {
    if (cb_ != nullptr && n > 0 && i % stride == 0) update(double(i) / double(n));
  }

private:
  CallBackPos* cb_;
  std::string label_;
  int from_ = 0;
  int to_ = 100;
  int last_ = -1;
};

} // namespace growth
