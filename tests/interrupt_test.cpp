// Ctrl-C as a cancel (growth/meshlab/interrupt.h): while the guard lives, SIGINT makes the
// callback return false instead of acting; afterwards the host's own SIGINT action is back and an
// interrupt that arrived is raised again for it; a host that ignores SIGINT keeps ignoring it.
#include <growth/meshlab/interrupt.h>

#include "filter_spherepack_layer.h"

#include <growth/cloud_generator.h>
#include <growth/error.h>

#include <gtest/gtest.h>

#include <csignal>
#include <signal.h>

using growth::meshlab::InterruptToCancel;

namespace {

volatile std::sig_atomic_t g_hostInterrupts = 0;
void hostHandler(int) { g_hostInterrupts = g_hostInterrupts + 1; }
int g_hostCalls = 0;
bool hostCallback(int, const char*) {
  ++g_hostCalls;
  return true;
}

// Installs `handler` for SIGINT for the test's scope, and puts back what was there.
struct HostAction {
  explicit HostAction(void (*handler)(int)) {
    struct sigaction sa {};
    sa.sa_handler = handler;
    sigemptyset(&sa.sa_mask);
    sigaction(SIGINT, &sa, &saved);
    g_hostInterrupts = 0;
    g_hostCalls = 0;
  }
  ~HostAction() { sigaction(SIGINT, &saved, nullptr); }
  struct sigaction saved {};
};

} // namespace

TEST(InterruptToCancel, CtrlCTurnsTheCallbackFalseThenReachesTheHost) {
  HostAction host(&hostHandler);
  {
    InterruptToCancel guard(&hostCallback);
    EXPECT_TRUE(InterruptToCancel::callback()(10, "phase"));
    EXPECT_EQ(g_hostCalls, 1) << "the host's callback is still called";
    std::raise(SIGINT);
    EXPECT_EQ(g_hostInterrupts, 0) << "taken over while the filter runs";
    EXPECT_TRUE(InterruptToCancel::interrupted());
    EXPECT_FALSE(InterruptToCancel::callback()(11, "phase"));
    EXPECT_EQ(g_hostCalls, 1);
  }
  EXPECT_EQ(g_hostInterrupts, 1) << "raised again for the host once the filter ends";
  std::raise(SIGINT);
  EXPECT_EQ(g_hostInterrupts, 2) << "the host's action is back";
}

TEST(InterruptToCancel, WithoutAnInterruptNothingReachesTheHost) {
  HostAction host(&hostHandler);
  {
    InterruptToCancel guard(nullptr); // a host without a callback
    EXPECT_TRUE(InterruptToCancel::callback()(50, "phase"));
    EXPECT_FALSE(InterruptToCancel::interrupted());
  }
  EXPECT_EQ(g_hostInterrupts, 0);
  std::raise(SIGINT);
  EXPECT_EQ(g_hostInterrupts, 1);
}

TEST(InterruptToCancel, AHostThatIgnoresSigintKeepsIgnoringIt) {
  HostAction host(SIG_IGN);
  {
    InterruptToCancel guard(&hostCallback);
    std::raise(SIGINT); // ignored: the process goes on, the filter too
    EXPECT_FALSE(InterruptToCancel::interrupted());
    EXPECT_TRUE(InterruptToCancel::callback()(10, "phase"));
  }
  struct sigaction now {};
  sigaction(SIGINT, nullptr, &now);
  EXPECT_EQ(now.sa_handler, SIG_IGN);
}

// End to end: a Ctrl-C during the sphere packer's run (sent from within its progress) stops it
// with growth::Cancelled and nothing built.
namespace {
int g_reports = 0;
bool interruptAtTheFifthReport(int, const char*) {
  if (++g_reports == 5) std::raise(SIGINT);
  return true;
}
} // namespace

TEST(InterruptToCancel, ACtrlCStopsTheSpherePacker) {
  HostAction host(&hostHandler);
  growth::CloudSpec spec;
  spec.shape = growth::Shape::Sphere;
  spec.count = 20000;
  spec.seed = 1;
  CMeshO cloud, out;
  growth::toMesh(growth::generateCloud(spec), cloud);
  growth::spherepack::Stat st;
  g_reports = 0;
  {
    InterruptToCancel guard(&interruptAtTheFifthReport);
    EXPECT_THROW(growth::spherepack::build(cloud, out, growth::spherepack::Params(), st, InterruptToCancel::callback()),
                 growth::Cancelled);
  }
  EXPECT_EQ(g_reports, 5) << "no report after the interrupt";
  EXPECT_EQ(out.vn, 0);
  EXPECT_EQ(g_hostInterrupts, 1);
}
