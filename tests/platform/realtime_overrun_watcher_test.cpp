#include "grip/platform/overrun_watcher.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <signal.h>
#include <unistd.h>

#include <chrono>
#include <cstdint>
#include <iostream>
#include <semaphore>
#include <string>
#include <thread>
#include <type_traits>

#include "grip/platform/clock.hpp"
#include "grip/platform/scheduling.hpp"
#include "grip/platform/thread.hpp"

// The watcher must start before any thread that does not block SIGXCPU. In this binary every
// other test joins its threads, so when a test here starts a watcher the main thread is alone;
// a watcher leaves SIGXCPU blocked in the main thread, and later threads inherit that.

namespace grip::platform {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

static_assert(!std::is_copy_constructible_v<OverrunWatcher>);
static_assert(std::is_nothrow_move_constructible_v<OverrunWatcher>);

constexpr TimePoint kMillisecond = 1'000'000;

// Signal delivery and the watcher's read are asynchronous: wait (bounded) for the count.
std::uint64_t wait_for_count(const OverrunWatcher& watcher, std::uint64_t at_least) {
  const TimePoint give_up = now_ns() + 5000 * kMillisecond;
  while (watcher.overruns() < at_least && now_ns() < give_up) {
    sleep_until_ns(now_ns() + kMillisecond);
  }
  return watcher.overruns();
}

bool deadline_possible() {
  const SchedulingPrivileges privileges = scheduling_privileges();
  return privileges.cap_sys_nice && privileges.affinity_spans_online_cpus;
}

// Another test process (ctest -j) may hold the deadline bandwidth for a moment (the admission
// control test in realtime_scheduling_test.cpp): a start that met EBUSY is retried for a second.
template <typename Body>
Result<RealtimeThread> start_when_bandwidth_free(const RealtimeThreadConfig& c, Body body) {
  for (int attempt = 1;; ++attempt) {
    Result<RealtimeThread> thread = RealtimeThread::start(c, body);
    const std::string& said =
        thread.ok() ? thread->info().scheduling.fallback_reason : thread.error().message;
    if (said.find("EBUSY") == std::string::npos || attempt == 100) return thread;
    if (thread.ok()) thread->join();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

TEST(RealtimeOverrunWatcher, CountsAProcessDirectedSigxcpuInsteadOfDying) {
  // GIVEN a started watcher
  Result<OverrunWatcher> watcher = OverrunWatcher::start();
  ASSERT_TRUE(watcher.ok()) << watcher.error().message;
  const std::uint64_t before = watcher->overruns();  // a SIGXCPU left pending earlier counts too

  // WHEN SIGXCPU is sent to the process, as the kernel sends a deadline overrun
  ASSERT_EQ(kill(getpid(), SIGXCPU), 0);

  // THEN it is counted, and the process (this test) is still alive
  EXPECT_GE(wait_for_count(*watcher, before + 1), before + 1);

  // AND after stop() the count is kept and the signal stays blocked (a later one is harmless)
  watcher->stop();
  const std::uint64_t counted = watcher->overruns();
  watcher->stop();  // idempotent
  EXPECT_EQ(watcher->overruns(), counted);
  sigset_t mask;
  ASSERT_EQ(pthread_sigmask(SIG_BLOCK, nullptr, &mask), 0);
  EXPECT_EQ(sigismember(&mask, SIGXCPU), 1);
}

TEST(RealtimeOverrunWatcher, RefusesToStartWhileAnotherThreadDoesNotBlockSigxcpu) {
  // While another thread accepts SIGXCPU a pending one would kill the process: ignore it for the
  // duration of this test (an ignored signal is discarded, not delivered).
  struct sigaction ignore {};
  ignore.sa_handler = SIG_IGN;
  sigemptyset(&ignore.sa_mask);
  struct sigaction previous {};
  ASSERT_EQ(sigaction(SIGXCPU, &ignore, &previous), 0);

  // GIVEN a thread that unblocks SIGXCPU
  std::binary_semaphore unblocked(0);
  std::binary_semaphore done(0);
  std::thread careless([&] {
    sigset_t sigxcpu;
    sigemptyset(&sigxcpu);
    sigaddset(&sigxcpu, SIGXCPU);
    pthread_sigmask(SIG_UNBLOCK, &sigxcpu, nullptr);
    pthread_setname_np(pthread_self(), "careless");
    unblocked.release();
    done.acquire();
  });
  unblocked.acquire();

  // WHEN a watcher is started THEN it refuses and names that thread
  const Result<OverrunWatcher> watcher = OverrunWatcher::start();
  done.release();
  careless.join();
  sigaction(SIGXCPU, &previous, nullptr);
  ASSERT_FALSE(watcher.ok());
  EXPECT_EQ(watcher.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(watcher.error().message.find("(careless) does not block SIGXCPU"), std::string::npos)
      << watcher.error().message;
}

TEST(RealtimeOverrunWatcher, ADeadlineThreadThatExceedsItsRuntimeIsCounted) {
  // GIVEN a watcher, then a thread with a 100 us runtime every 10 ms
  Result<OverrunWatcher> watcher = OverrunWatcher::start();
  ASSERT_TRUE(watcher.ok()) << watcher.error().message;
  const std::uint64_t before = watcher->overruns();
  RealtimeThreadConfig config;
  config.name = "grip-overrun-t";
  config.scheduling.request = PolicyRequest::kAuto;
  config.scheduling.runtime = microseconds(100);
  config.scheduling.deadline = milliseconds(10);
  config.scheduling.period = milliseconds(10);
  config.lock_memory = false;

  // WHEN it busy-loops for 20 ms of wall time
  Result<RealtimeThread> thread = start_when_bandwidth_free(config, [](const RealtimeThreadInfo&) {
    const TimePoint end = now_ns() + 20 * kMillisecond;
    while (now_ns() < end) {
    }
  });
  ASSERT_TRUE(thread.ok()) << thread.error().message;
  thread->join();
  const SchedulingOutcome& outcome = thread->info().scheduling;

  // THEN under SCHED_DEADLINE the kernel raised SIGXCPU and the watcher counted it. Without
  // SCHED_DEADLINE nothing enforces a runtime, so there is nothing to count: check instead that
  // the thread says why it did not get SCHED_DEADLINE.
  if (outcome.policy == SchedPolicy::kDeadline) {
    const std::uint64_t counted = wait_for_count(*watcher, before + 1) - before;
    std::cout << "20 ms busy loop with a 100 us / 10 ms reservation: " << counted
              << " overrun signal(s) counted\n";
    EXPECT_GE(counted, 1U);
  } else {
    EXPECT_FALSE(deadline_possible()) << "SCHED_DEADLINE should have been granted here";
    EXPECT_NE(outcome.fallback_reason.find("SCHED_DEADLINE refused"), std::string::npos)
        << outcome.fallback_reason;
  }
}

TEST(RealtimeOverrunWatcher, AMovedWatcherKeepsCountingAndTheOldOneReadsZero) {
  Result<OverrunWatcher> started = OverrunWatcher::start();
  ASSERT_TRUE(started.ok()) << started.error().message;
  OverrunWatcher watcher = std::move(started).value();
  const std::uint64_t before = watcher.overruns();
  ASSERT_EQ(kill(getpid(), SIGXCPU), 0);
  EXPECT_GE(wait_for_count(watcher, before + 1), before + 1);
  OverrunWatcher taken = std::move(watcher);
  EXPECT_EQ(watcher.overruns(), 0U);  // NOLINT(bugprone-use-after-move): the moved-from state
  EXPECT_GE(taken.overruns(), before + 1);
}

}  // namespace
}  // namespace grip::platform
