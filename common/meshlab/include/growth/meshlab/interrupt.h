#pragma once
// Ctrl-C cancels a running filter. MeshLab's hosts never cancel through the progress callback
// (meshlabserver's and PyMeshLab's callbacks always return true), and PyMeshLab holds a Ctrl-C
// until the filter has finished. While an InterruptToCancel is alive, SIGINT only sets a flag; the
// callback returned by callback() then returns false at the engine's next progress report, which
// ends the run with growth::Cancelled (the filter adds no layer). On destruction the host's own
// SIGINT action comes back, and an interrupt that arrived is raised again for it: PyMeshLab then
// raises KeyboardInterrupt, meshlabserver ends as it would have.
#include <atomic>
#include <csignal>

#if defined(__unix__) || defined(__APPLE__)
#include <signal.h>
#define GROWTH_HAVE_SIGACTION 1
#endif

namespace growth {
namespace meshlab {

class InterruptToCancel {
public:
  using CallBack = bool (*)(int, const char*);
  explicit InterruptToCancel(CallBack host) {
    host_() = host;
    interrupted_().store(false);
#ifdef GROWTH_HAVE_SIGACTION
    // A host that ignores SIGINT (a background job) keeps ignoring it.
    if (sigaction(SIGINT, nullptr, &previous_) != 0 || previous_.sa_handler == SIG_IGN) return;
    struct sigaction sa {};
    sa.sa_handler = &onInterrupt;
    sigemptyset(&sa.sa_mask);
    installed_ = sigaction(SIGINT, &sa, &previous_) == 0;
#endif
  }
  ~InterruptToCancel() {
#ifdef GROWTH_HAVE_SIGACTION
    if (installed_) {
      sigaction(SIGINT, &previous_, nullptr);
      if (interrupted_().load()) std::raise(SIGINT);
    }
#endif
    host_() = nullptr;
  }
  InterruptToCancel(const InterruptToCancel&) = delete;
  InterruptToCancel& operator=(const InterruptToCancel&) = delete;

  // The callback to give the engine: the host's (when it has one), and false once interrupted.
  static CallBack callback() { return &report; }
  static bool interrupted() { return interrupted_().load(); }

private:
  static void onInterrupt(int) { interrupted_().store(true); } // (async-signal-safe: a lock-free store)
  static bool report(int percent, const char* label) {
    if (interrupted_().load()) return false;
    const CallBack host = host_();
    return host == nullptr || host(percent, label);
  }
  static std::atomic<bool>& interrupted_() {
    static std::atomic<bool> flag{false};
    return flag;
  }
  static CallBack& host_() {
    static CallBack cb = nullptr;
    return cb;
  }
#ifdef GROWTH_HAVE_SIGACTION
  struct sigaction previous_ {};
  bool installed_ = false;
#endif
};

} // namespace meshlab
} // namespace growth
