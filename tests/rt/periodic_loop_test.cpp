// rt::PeriodicLoop: releases on one absolute timeline, one record per cycle in order, and the
// SCHED_DEADLINE reservation the kernel actually holds for the planning thread. Nothing about
// how late a thread wakes is asserted (the machines are shared); that is measured by
// `grip stress` and the cycle trace.

#include "grip/rt/periodic_loop.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <string>
#include <thread>
#include <vector>

#include "grip/platform/scheduling.hpp"

namespace grip::rt {
namespace {

using std::chrono::milliseconds;

bool deadline_possible() {
  const platform::SchedulingPrivileges privileges = platform::scheduling_privileges();
  return geteuid() == 0 && privileges.cap_sys_nice && privileges.affinity_spans_online_cpus;
}

PeriodicLoopConfig config(platform::PolicyRequest policy, std::uint64_t cycles) {
  PeriodicLoopConfig c;
  c.name = "grip-test-loop";
  c.period = milliseconds(10);
  c.budget = milliseconds(2);
  c.policy = policy;
  c.cycles = cycles;
  c.lock_memory = false;
  c.reference_timer = false;
  return c;
}

// Another test process (ctest -j) may hold the deadline bandwidth for a moment: a start refused
// with EBUSY is retried for a second.
Result<std::unique_ptr<PeriodicLoop>> start_when_bandwidth_free(const PeriodicLoopConfig& c,
                                                                const PeriodicLoop::Body& body) {
  for (int attempt = 1;; ++attempt) {
    auto loop = PeriodicLoop::start(c, body);
    if (loop.ok() || loop.error().message.find("EBUSY") == std::string::npos || attempt == 100) {
      return loop;
    }
    std::this_thread::sleep_for(milliseconds(10));
  }
}

std::vector<CycleRecord> drain(PeriodicLoop& loop) {
  std::vector<CycleRecord> records;
  CycleRecord record;
  while (!loop.finished()) {
    while (loop.poll(record)) records.push_back(record);
    std::this_thread::sleep_for(milliseconds(5));
  }
  loop.join();
  while (loop.poll(record)) records.push_back(record);
  return records;
}

TEST(PeriodicLoop, RefusesABudgetThatDoesNotFitThePeriod) {
  PeriodicLoopConfig c = config(platform::PolicyRequest::kOther, 1);
  c.budget = c.period;
  auto loop = PeriodicLoop::start(c, [](std::int64_t, std::int64_t) { return CycleOutcome{}; });
  ASSERT_FALSE(loop.ok());
  EXPECT_NE(loop.error().message.find("budget < period"), std::string::npos)
      << loop.error().message;
}

TEST(PeriodicLoop, ReleasesEveryCycleOnOneTimelineAndRecordsEachInOrder) {
  // GIVEN a loop of 12 cycles whose body notes its release and deadline
  const PeriodicLoopConfig c = config(platform::PolicyRequest::kOther, 12);
  std::vector<std::int64_t> releases;
  std::vector<std::int64_t> deadlines;
  releases.reserve(12);
  deadlines.reserve(12);
  auto loop = PeriodicLoop::start(c, [&](std::int64_t release, std::int64_t deadline) {
    releases.push_back(release);
    deadlines.push_back(deadline);
    CycleOutcome out;
    out.edges_added = releases.size();
    return out;
  });
  ASSERT_TRUE(loop.ok()) << loop.error().message;
  const std::vector<CycleRecord> records = drain(**loop);

  // THEN there is a record per release, in order, one period apart; the body ran for every
  // release not skipped (only a stall longer than a period skips one), with the budget as its
  // deadline, and each record carries that run's outcome
  ASSERT_EQ(records.size(), 12U);
  std::size_t ran = 0;
  for (std::size_t k = 0; k < records.size(); ++k) {
    EXPECT_EQ(records[k].cycle, k);
    EXPECT_GE(records[k].wake_latency_ns, 0) << "woke before its release";
    if (k > 0) {
      EXPECT_EQ(records[k].release_ns - records[k - 1].release_ns, c.period.count());
    }
    if (records[k].skipped) continue;
    ASSERT_LT(ran, releases.size());
    EXPECT_EQ(records[k].release_ns, releases[ran]);
    EXPECT_EQ(deadlines[ran], releases[ran] + c.budget.count());
    EXPECT_EQ(records[k].outcome.edges_added, ran + 1);
    ++ran;
  }
  EXPECT_EQ(ran, releases.size());
}

TEST(PeriodicLoop, AReleaseWokenWhenTheNextIsDueIsSkippedAndCountedAsMissed) {
  // GIVEN a loop whose body stalls for three and a half periods on its third run
  const PeriodicLoopConfig c = config(platform::PolicyRequest::kOther, 10);
  std::vector<std::int64_t> releases;
  releases.reserve(10);
  auto loop = PeriodicLoop::start(c, [&](std::int64_t release, std::int64_t) {
    releases.push_back(release);
    if (releases.size() == 3) std::this_thread::sleep_for(c.period * 7 / 2);
    return CycleOutcome{};
  });
  ASSERT_TRUE(loop.ok()) << loop.error().message;
  const std::vector<CycleRecord> records = drain(**loop);
  ASSERT_EQ(records.size(), 10U);
  ASSERT_GE(releases.size(), 3U);
  std::size_t stalled = 0;
  while (stalled < records.size() && records[stalled].release_ns != releases[2]) ++stalled;
  ASSERT_LT(stalled + 2, records.size());

  // THEN the stalled cycle missed, and the two releases whose successors were due when the
  // thread woke are skipped: missed, without a body; every other record is of a body that ran
  // at its own release
  EXPECT_TRUE(records[stalled].missed);
  for (const std::size_t k : {stalled + 1, stalled + 2}) {
    EXPECT_TRUE(records[k].skipped) << k;
    EXPECT_TRUE(records[k].missed) << k;
  }
  std::size_t ran = 0;
  for (const CycleRecord& r : records) {
    const auto runs = std::count(releases.begin(), releases.end(), r.release_ns);
    EXPECT_EQ(runs, r.skipped ? 0 : 1) << r.cycle;
    ran += r.skipped ? 0 : 1;
  }
  EXPECT_EQ(ran, releases.size());
}

TEST(PeriodicLoop, TheKernelHoldsThePlanningThreadToAnImplicitDeadlineReservation) {
  // GIVEN a loop that asks for SCHED_DEADLINE (where the machine grants it)
  if (!deadline_possible()) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  std::atomic<bool> read{false};
  platform::DeadlineReservation seen;
  platform::SchedPolicy policy = platform::SchedPolicy::kOther;
  const PeriodicLoopConfig c = config(platform::PolicyRequest::kDeadline, 3);
  auto loop = start_when_bandwidth_free(c, [&](std::int64_t, std::int64_t) {
    if (!read.exchange(true)) {
      policy = platform::current_policy();
      seen = platform::current_deadline_reservation();
    }
    return CycleOutcome{};
  });
  ASSERT_TRUE(loop.ok()) << loop.error().message;
  drain(**loop);

  // THEN the reservation gives the budget as runtime every period, with the period as the
  // kernel's deadline: a deadline below the period would make the kernel throttle a thread
  // that wakes after it until a period that starts where the thread last woke, so wake-up
  // latencies would add up from cycle to cycle
  ASSERT_EQ(policy, platform::SchedPolicy::kDeadline);
  EXPECT_EQ(seen.runtime, c.budget);
  EXPECT_EQ(seen.deadline, c.period);
  EXPECT_EQ(seen.period, c.period);
}

}  // namespace
}  // namespace grip::rt
