#pragma once
// The planning thread's timeline: released every period on an absolute timeline
// (clock_nanosleep TIMER_ABSTIME on CLOCK_MONOTONIC), it runs one cycle body per release and
// hands one record per cycle to an ordinary thread through a bounded lock-free ring, so that it
// never waits for anyone. Beside it, a reference timer thread with the same policy and period
// does nothing but wake up and measure its latency the same way (a cyclictest-like baseline):
// what the machine gives a thread, against what the planner gets.

#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>

#include "grip/common/result.hpp"
#include "grip/platform/memory.hpp"
#include "grip/platform/thread.hpp"
#include "grip/rt/latency_histogram.hpp"
#include "grip/rt/replanning_cycle.hpp"
#include "grip/rt/spsc_ring.hpp"

namespace grip::rt {

struct CycleRecord {
  std::uint64_t cycle = 0;
  std::int64_t release_ns = 0;       // absolute (CLOCK_MONOTONIC)
  std::int64_t wake_latency_ns = 0;  // wake-up minus release
  std::int64_t compute_ns = 0;       // wake-up to the end of the cycle body
  std::int64_t lateness_ns = 0;      // end of the body minus the deadline (negative: early)
  bool missed = false;               // ended after its deadline
  bool skipped = false;  // woken when the next release was already due: no body ran (missed)
  CycleOutcome outcome;
};

struct PeriodicLoopConfig {
  std::string name = "grip-planner";
  std::chrono::nanoseconds period{50'000'000};
  std::chrono::nanoseconds budget{25'000'000};  // the deadline after each release
  platform::PolicyRequest policy = platform::PolicyRequest::kAuto;
  int fifo_priority = 80;  // under SCHED_FIFO
  int cpu = -1;            // pinned to this CPU (never under SCHED_DEADLINE); -1: any
  std::uint64_t cycles = 100;
  bool lock_memory = true;
  // Cycles before the allocation and page-fault counts start (caches, first-touch of the
  // planner's working set are start-up).
  std::uint64_t warmup_cycles = 5;
  bool reference_timer = true;
};

// Filled in by the threads, read after join().
struct PeriodicLoopResult {
  platform::RealtimeThreadInfo planner_thread;
  std::uint64_t cycles = 0;
  std::uint64_t misses = 0;
  std::uint64_t records_dropped = 0;  // the consumer fell behind (the planner never waits)
  bool allocations_counted = false;   // the interposed allocator is in use (not ASan/TSan)
  std::uint64_t heap_allocations_in_loop = 0;
  platform::ThreadUsage usage_in_loop{};  // planning thread, after the warm-up cycles
  std::optional<platform::RealtimeThreadInfo> reference_thread;
  LatencyHistogram reference_wake_latency;
};

class PeriodicLoop {
 public:
  // body(release_ns, deadline_ns) runs on the planning thread once per release (except a release
  // woken only when the next was already due: skipped, see CycleRecord); it must not
  // allocate, block or throw.
  using Body = std::function<CycleOutcome(std::int64_t, std::int64_t)>;
  static constexpr std::size_t kRingCapacity = 4096;

  // Validates the timing (0 < budget < period), starts the reference timer and the planning
  // thread (threads are created here, before either runs SCHED_DEADLINE).
  static Result<std::unique_ptr<PeriodicLoop>> start(const PeriodicLoopConfig& config, Body body);
  ~PeriodicLoop();

  // Consumer side (one ordinary thread): the next cycle record, if any.
  bool poll(CycleRecord& out) noexcept { return ring_.try_pop(out); }
  bool finished() const noexcept { return finished_.load(std::memory_order_acquire); }
  void request_stop() noexcept { stop_.store(true, std::memory_order_release); }
  // Waits for both threads; the result is complete afterwards.
  const PeriodicLoopResult& join();

 private:
  PeriodicLoop(const PeriodicLoopConfig& config, Body body);
  void planner_main(const platform::RealtimeThreadInfo& info) noexcept;
  void reference_main(const platform::RealtimeThreadInfo& info) noexcept;

  PeriodicLoopConfig config_;
  Body body_;
  std::int64_t first_release_ns_ = 0;
  SpscRing<CycleRecord, kRingCapacity> ring_;
  std::atomic<bool> stop_{false};
  std::atomic<bool> finished_{false};
  PeriodicLoopResult result_;
  std::optional<platform::RealtimeThread> planner_;
  std::optional<platform::RealtimeThread> reference_;
};

}  // namespace grip::rt
