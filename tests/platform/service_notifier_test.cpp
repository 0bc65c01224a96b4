// The service manager's notifications: nothing without NOTIFY_SOCKET; with it, each call is one
// datagram in sd_notify's format, and the watchdog timeout is the manager's when it names us.

#include "grip/platform/service_notifier.hpp"

#include <gtest/gtest.h>
#include <stdlib.h>
#include <unistd.h>

#include <string>

#include "notify_socket.hpp"

namespace {

using grip::platform::ServiceNotifier;
using grip::testing::NotifySocket;
using namespace std::chrono_literals;

// Sets the service manager's variables for one test and unsets them after it.
class ServiceNotifierTest : public ::testing::Test {
 protected:
  void TearDown() override {
    unsetenv("NOTIFY_SOCKET");
    unsetenv("WATCHDOG_USEC");
    unsetenv("WATCHDOG_PID");
  }
  NotifySocket socket_{::testing::TempDir() + "grip-notify-" + std::to_string(getpid())};
};

TEST_F(ServiceNotifierTest, WithoutANotifySocketEveryCallIsANoOp) {
  unsetenv("NOTIFY_SOCKET");
  setenv("WATCHDOG_USEC", "500000", 1);
  const ServiceNotifier n = ServiceNotifier::from_environment();
  EXPECT_FALSE(n.enabled());
  EXPECT_EQ(n.watchdog_timeout(), 0us);
  EXPECT_TRUE(n.ready("x").ok());
  EXPECT_TRUE(n.watchdog().ok());
}

TEST_F(ServiceNotifierTest, EachCallSendsItsMessageToTheSocket) {
  ASSERT_FALSE(socket_.path().empty());
  setenv("NOTIFY_SOCKET", socket_.path().c_str(), 1);
  const ServiceNotifier n = ServiceNotifier::from_environment();
  ASSERT_TRUE(n.enabled());
  ASSERT_TRUE(n.ready("planning").ok());
  EXPECT_EQ(socket_.receive(5s), "READY=1\nSTATUS=planning");
  ASSERT_TRUE(n.status("cycles 3").ok());
  EXPECT_EQ(socket_.receive(5s), "STATUS=cycles 3");
  ASSERT_TRUE(n.watchdog().ok());
  EXPECT_EQ(socket_.receive(5s), "WATCHDOG=1");
  ASSERT_TRUE(n.stopping().ok());
  EXPECT_EQ(socket_.receive(5s), "STOPPING=1");
}

TEST_F(ServiceNotifierTest, TheWatchdogTimeoutIsTheManagersOnlyWhenItNamesThisProcess) {
  setenv("NOTIFY_SOCKET", socket_.path().c_str(), 1);
  setenv("WATCHDOG_USEC", "500000", 1);
  EXPECT_EQ(ServiceNotifier::from_environment().watchdog_timeout(), 500ms);
  setenv("WATCHDOG_PID", std::to_string(getpid()).c_str(), 1);
  EXPECT_EQ(ServiceNotifier::from_environment().watchdog_timeout(), 500ms);
  setenv("WATCHDOG_PID", std::to_string(getpid() + 1).c_str(), 1);
  EXPECT_EQ(ServiceNotifier::from_environment().watchdog_timeout(), 0us);
}

TEST_F(ServiceNotifierTest, AMissingSocketIsReportedAsAnError) {
  setenv("NOTIFY_SOCKET", (::testing::TempDir() + "grip-no-such-socket").c_str(), 1);
  const grip::Status s = ServiceNotifier::from_environment().watchdog();
  ASSERT_FALSE(s.ok());
  EXPECT_NE(s.error().message.find("sd_notify"), std::string::npos) << s.error().message;
}

}  // namespace
