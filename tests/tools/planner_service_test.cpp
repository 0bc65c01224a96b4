// `grip planner` as a systemd service sees it: through the notification socket it says READY=1
// once planning started, sends WATCHDOG=1 while planning cycles complete, stops sending it when
// planning stalls (a lockstep vehicle that died sends no more states, so no cycle completes),
// and says STOPPING=1 on SIGTERM; in real time, where the planning thread cycles on its own, it
// feeds the watchdog too. Timeouts are generous: nothing here measures time.

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <optional>
#include <string>

#include "child_process.hpp"
#include "grip_command.hpp"
#include "notify_socket.hpp"

namespace {

using grip::testing::ChildProcess;
using grip::testing::kGrip;
using grip::testing::NotifySocket;
using namespace std::chrono_literals;

const std::string kDomain = "93";  // no other test uses these two
const std::string kRealTimeDomain = "94";

// How many WATCHDOG=1 came during `span`, the other messages skipped.
int watchdog_pings_during(const NotifySocket& socket, std::chrono::milliseconds span) {
  int pings = 0;
  const auto until = std::chrono::steady_clock::now() + span;
  for (auto now = std::chrono::steady_clock::now(); now < until;
       now = std::chrono::steady_clock::now()) {
    const auto m =
        socket.receive(std::chrono::duration_cast<std::chrono::milliseconds>(until - now));
    if (m && m->find("WATCHDOG=1") != std::string::npos) ++pings;
  }
  return pings;
}

TEST(PlannerService, ReadyThenWatchdogWhilePlanningNoneOnceTheVehicleDiedAndStoppingOnSigterm) {
  const NotifySocket socket(::testing::TempDir() + "grip-planner-notify-" +
                            std::to_string(getpid()));
  ASSERT_FALSE(socket.path().empty());
  // Keep-alives every 250 ms at most; WATCHDOG_PID unset (as if the manager did not say).
  auto planner = ChildProcess::spawn(
      {kGrip, "planner", "--robot", "dd-vel", "--domain", kDomain, "--startup-timeout", "60"},
      {"NOTIFY_SOCKET=" + socket.path(), "WATCHDOG_USEC=500000", "WATCHDOG_PID"});
  ASSERT_TRUE(planner.has_value());
  std::optional<ChildProcess> vehicle =
      ChildProcess::spawn({kGrip, "sim", "--lockstep", "--scene", "rooms", "--robot", "dd-vel",
                           "--domain", kDomain, "--max-sim-time", "600"});
  ASSERT_TRUE(vehicle.has_value());

  ASSERT_TRUE(socket.wait_for("READY=1", 90s)) << "the planner never said it was ready";
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(socket.wait_for("WATCHDOG=1", 30s)) << "keep-alive " << i << " did not come";
  }

  vehicle->kill(SIGKILL);
  vehicle->wait();
  vehicle.reset();
  static_cast<void>(watchdog_pings_during(socket, 2s));  // the cycle under way may complete
  EXPECT_EQ(watchdog_pings_during(socket, 3s), 0) << "keep-alives without planning cycles";

  planner->kill(SIGTERM);
  EXPECT_TRUE(socket.wait_for("STOPPING=1", 30s));
  const int status = planner->wait();
  EXPECT_TRUE(WIFEXITED(status)) << "the planner did not stop cleanly on SIGTERM";
}

TEST(PlannerService, InRealTimeTheWatchdogIsFedFromThePlanningThreadsCycles) {
  const NotifySocket socket(::testing::TempDir() + "grip-planner-rt-notify-" +
                            std::to_string(getpid()));
  ASSERT_FALSE(socket.path().empty());
  auto planner = ChildProcess::spawn(
      {kGrip, "planner", "--robot", "dd-vel", "--domain", kRealTimeDomain, "--startup-timeout",
       "60"},
      {"NOTIFY_SOCKET=" + socket.path(), "WATCHDOG_USEC=500000", "WATCHDOG_PID"});
  ASSERT_TRUE(planner.has_value());
  auto vehicle = ChildProcess::spawn({kGrip, "sim", "--scene", "rooms", "--robot", "dd-vel",
                                      "--domain", kRealTimeDomain, "--max-sim-time", "600"});
  ASSERT_TRUE(vehicle.has_value());

  ASSERT_TRUE(socket.wait_for("READY=1", 90s)) << "the planner never said it was ready";
  for (int i = 0; i < 3; ++i) {
    ASSERT_TRUE(socket.wait_for("WATCHDOG=1", 30s)) << "keep-alive " << i << " did not come";
  }
  planner->kill(SIGTERM);
  EXPECT_TRUE(socket.wait_for("STOPPING=1", 30s));
  EXPECT_TRUE(WIFEXITED(planner->wait())) << "the planner did not stop cleanly on SIGTERM";
}

}  // namespace
