// The Wakeup between the real-time thread and a service thread: a signal is never lost (one
// sent before the wait is consumed by it), a wait without one lasts at least its timeout, to
// and a signal from another thread ends a long wait.

#include "grip/platform/wakeup.hpp"

#include <gtest/gtest.h>

#include <chrono>
#include <thread>

#include "grip/platform/clock.hpp"

namespace grip::platform {
namespace {

TEST(Wakeup, ASignalSentBeforeTheWaitIsConsumedByItOnce) {
  auto wakeup = Wakeup::create();
  ASSERT_TRUE(wakeup.ok()) << wakeup.error().message;
  wakeup->signal();
  wakeup->signal();  // signals add up to one wake-up
  EXPECT_TRUE(wakeup->wait(std::chrono::seconds(5)));
  EXPECT_FALSE(wakeup->wait(std::chrono::nanoseconds(0)));
}

TEST(Wakeup, AWaitWithoutASignalLastsAtLeastItsTimeout) {
  auto wakeup = Wakeup::create();
  ASSERT_TRUE(wakeup.ok()) << wakeup.error().message;
  // 1.5 ms: a timeout rounded to whole milliseconds would be 1 or 2 ms.
  for (int i = 0; i < 5; ++i) {
    const std::int64_t start = now_ns();
    EXPECT_FALSE(wakeup->wait(std::chrono::microseconds(1500)));
    EXPECT_GE(now_ns() - start, 1'500'000);
  }
}

TEST(Wakeup, ASignalFromAnotherThreadEndsALongWait) {
  auto wakeup = Wakeup::create();
  ASSERT_TRUE(wakeup.ok()) << wakeup.error().message;
  std::thread signaller([&] {
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
    wakeup->signal();
  });
  const std::int64_t start = now_ns();
  EXPECT_TRUE(wakeup->wait(std::chrono::seconds(60)));
  EXPECT_LT(now_ns() - start, 30'000'000'000);  // woken by the signal, not the timeout
  signaller.join();
}

}  // namespace
}  // namespace grip::platform
