#include "grip/platform/clock.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <time.h>

#include <atomic>
#include <thread>

// No test asserts an upper bound on a sleep: CI machines are noisy. What must hold everywhere is
// that a sleep never ends before its deadline.

namespace grip::platform {
namespace {

constexpr TimePoint kMillisecond = 1'000'000;

TimePoint monotonic_directly() {
  timespec now{};
  clock_gettime(CLOCK_MONOTONIC, &now);
  return static_cast<TimePoint>(now.tv_sec) * 1'000'000'000 + now.tv_nsec;
}

TEST(RealtimeClock, NowIsClockMonotonicInNanoseconds) {
  const TimePoint before = monotonic_directly();
  const TimePoint now = now_ns();
  const TimePoint after = monotonic_directly();
  EXPECT_LE(before, now);
  EXPECT_LE(now, after);
  TimePoint previous = now_ns();
  for (int i = 0; i < 1000; ++i) {
    const TimePoint next = now_ns();
    ASSERT_GE(next, previous);
    previous = next;
  }
}

TEST(RealtimeClock, SleepUntilNeverWakesBeforeTheDeadline) {
  TimePoint deadline = now_ns();
  for (int cycle = 0; cycle < 20; ++cycle) {
    deadline += kMillisecond;
    sleep_until_ns(deadline);
    ASSERT_GE(now_ns(), deadline) << "cycle " << cycle;
  }
}

TEST(RealtimeClock, DeadlinesInThePastReturnAtOnce) {
  sleep_until_ns(now_ns() - 1000 * kMillisecond);
  sleep_until_ns(0);
  sleep_until_ns(-5);  // before the epoch: clamped, not an EINVAL
  SUCCEED() << "returned";
}

std::atomic<int> g_signals_handled{0};
void count_signal(int) { g_signals_handled.fetch_add(1); }

// A signal handler interrupts clock_nanosleep with EINTR; the sleep must resume, not return.
TEST(RealtimeClock, SleepUntilResumesAfterASignalAndStillWaitsForTheDeadline) {
  // GIVEN a SIGUSR1 handler without SA_RESTART, so the sleep really sees EINTR
  struct sigaction action {};
  action.sa_handler = &count_signal;
  sigemptyset(&action.sa_mask);
  action.sa_flags = 0;
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGUSR1, &action, &previous), 0);
  g_signals_handled = 0;

  // WHEN another thread signals the sleeper repeatedly during a 50 ms sleep
  const pthread_t sleeper = pthread_self();
  const TimePoint deadline = now_ns() + 50 * kMillisecond;
  std::thread signaller([&] {
    for (int i = 0; i < 5; ++i) {
      sleep_until_ns(now_ns() + 2 * kMillisecond);
      pthread_kill(sleeper, SIGUSR1);
    }
  });
  sleep_until_ns(deadline);
  const TimePoint woke = now_ns();
  signaller.join();
  sigaction(SIGUSR1, &previous, nullptr);

  // THEN the handler ran and the sleep still lasted until the deadline
  EXPECT_GE(g_signals_handled.load(), 1);
  EXPECT_GE(woke, deadline);
}

}  // namespace
}  // namespace grip::platform
