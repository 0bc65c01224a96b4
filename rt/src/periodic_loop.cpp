#include "grip/rt/periodic_loop.hpp"

#include <string>

#include "grip/platform/alloc_counter.hpp"
#include "grip/platform/clock.hpp"

namespace grip::rt {

namespace {
// The reference timer only wakes up, but under memory pressure even that can take hundreds of
// microseconds; a reservation it overruns would throttle it and report the throttling as
// latency. 1 ms per period is still 2% of a 50 ms cycle.
constexpr std::chrono::nanoseconds kReferenceRuntime{1'000'000};
}  // namespace

Result<std::unique_ptr<PeriodicLoop>> PeriodicLoop::start(const PeriodicLoopConfig& config,
                                                          Body body) {
  if (config.period.count() <= 0 || config.budget.count() <= 0 || config.budget >= config.period) {
    using Ms = std::chrono::duration<double, std::milli>;
    std::string message = "timing: need 0 < budget < period (got budget ";
    message += std::to_string(Ms(config.budget).count());
    message += " ms, period ";
    message += std::to_string(Ms(config.period).count());
    message += " ms)";
    return invalid_argument(std::move(message));
  }
  if (!body) return invalid_argument("periodic loop: no cycle body");
  std::unique_ptr<PeriodicLoop> loop(new PeriodicLoop(config, std::move(body)));
  // Memory is locked before the timeline is set: mlockall faults in every page of the process
  // and took over a second on a loaded machine here, so that the first releases had passed
  // before the thread existed.
  const platform::MemoryLockOutcome memory =
      config.lock_memory ? platform::lock_process_memory()
                         : platform::MemoryLockOutcome{false, "not requested"};
  // Both threads share one absolute timeline, starting after their set-up.
  loop->first_release_ns_ = platform::now_ns() + 200'000'000;

  platform::RealtimeThreadConfig planner_config;
  planner_config.name = config.name;
  planner_config.lock_memory = false;  // done above
  planner_config.scheduling.request = config.policy;
  planner_config.scheduling.fifo_priority = config.fifo_priority;
  planner_config.scheduling.cpu = config.cpu;
  // The reservation's deadline is the period (an implicit deadline), not the budget: the budget
  // is this loop's deadline, measured against its own timeline. A constrained deadline (below
  // the period) makes the kernel throttle a thread that wakes after its deadline but before the
  // next period (kernel commit df8eac8c, 4.11), and that period begins where the thread last
  // woke, not at its release: every wake-up latency would then carry into the next cycle and
  // add up over hundreds of cycles until the tree has no time left to grow. With an implicit
  // deadline, a thread that wakes with runtime to spare is replenished at once, on its own
  // timeline.
  planner_config.scheduling.runtime = config.budget;
  planner_config.scheduling.deadline = config.period;
  planner_config.scheduling.period = config.period;

  if (config.reference_timer) {
    platform::RealtimeThreadConfig reference_config = planner_config;
    reference_config.name = "grip-reference";
    reference_config.scheduling.runtime = std::min(kReferenceRuntime, config.budget);
    auto reference = platform::RealtimeThread::start(
        reference_config, [raw = loop.get()](const platform::RealtimeThreadInfo& info) {
          raw->reference_main(info);
        });
    if (!reference) return reference.error();
    loop->reference_.emplace(std::move(reference).value());
    loop->result_.reference_thread = loop->reference_->info();
    loop->result_.reference_thread->memory = memory;
  }
  auto planner = platform::RealtimeThread::start(
      planner_config,
      [raw = loop.get()](const platform::RealtimeThreadInfo& info) { raw->planner_main(info); });
  if (!planner) {
    loop->request_stop();
    return planner.error();
  }
  loop->planner_.emplace(std::move(planner).value());
  loop->result_.planner_thread = loop->planner_->info();
  loop->result_.planner_thread.memory = memory;
  return loop;
}

PeriodicLoop::PeriodicLoop(const PeriodicLoopConfig& config, Body body)
    : config_(config), body_(std::move(body)) {}

PeriodicLoop::~PeriodicLoop() {
  request_stop();
  join();
}

void PeriodicLoop::planner_main(const platform::RealtimeThreadInfo& /*info*/) noexcept {
  const std::int64_t period = config_.period.count();
  const std::int64_t budget = config_.budget.count();
  platform::ThreadUsage usage_at_warmup{};
  std::uint64_t k = 0;
  for (; k < config_.cycles && !stop_.load(std::memory_order_acquire); ++k) {
    const std::int64_t release = first_release_ns_ + static_cast<std::int64_t>(k) * period;
    platform::sleep_until_ns(release);
    const std::int64_t wake = platform::now_ns();
    if (k == config_.warmup_cycles) {
      usage_at_warmup = platform::thread_usage();
      alloc_counter::arm();
    }
    CycleRecord record;
    // Woken after the next release is already due (a stall longer than a period): this cycle's
    // work could only serve a time that has passed. It is skipped, and counted as missed, so
    // that the loop is back on its timeline at the next release instead of running one hurried
    // cycle after another.
    record.skipped = wake >= release + period;
    if (!record.skipped) record.outcome = body_(release, release + budget);
    const std::int64_t end = platform::now_ns();
    record.cycle = k;
    record.release_ns = release;
    record.wake_latency_ns = wake - release;
    record.compute_ns = end - wake;
    record.lateness_ns = end - (release + budget);
    record.missed = record.lateness_ns > 0;
    result_.misses += record.missed ? 1 : 0;
    (void)ring_.push_or_count_drop(record);
  }
  alloc_counter::disarm();
  const platform::ThreadUsage end_usage = platform::thread_usage();
  result_.cycles = k;
  if (k > config_.warmup_cycles) {
    result_.allocations_counted = alloc_counter::interposed();
    const alloc_counter::Counts counts = alloc_counter::counts();
    result_.heap_allocations_in_loop = counts.allocations + counts.deallocations;
    result_.usage_in_loop.minor_faults = end_usage.minor_faults - usage_at_warmup.minor_faults;
    result_.usage_in_loop.major_faults = end_usage.major_faults - usage_at_warmup.major_faults;
    result_.usage_in_loop.voluntary_switches =
        end_usage.voluntary_switches - usage_at_warmup.voluntary_switches;
    result_.usage_in_loop.involuntary_switches =
        end_usage.involuntary_switches - usage_at_warmup.involuntary_switches;
  }
  result_.records_dropped = ring_.dropped();
  finished_.store(true, std::memory_order_release);
}

void PeriodicLoop::reference_main(const platform::RealtimeThreadInfo& /*info*/) noexcept {
  const std::int64_t period = config_.period.count();
  for (std::uint64_t k = 0; k < config_.cycles && !stop_.load(std::memory_order_acquire); ++k) {
    // Released half a period after the planner, so that the two never compete for a wake-up.
    const std::int64_t release =
        first_release_ns_ + static_cast<std::int64_t>(k) * period + period / 2;
    platform::sleep_until_ns(release);
    result_.reference_wake_latency.record(platform::now_ns() - release);
  }
}

const PeriodicLoopResult& PeriodicLoop::join() {
  if (planner_ && planner_->joinable()) planner_->join();
  if (reference_ && reference_->joinable()) reference_->join();
  return result_;
}

}  // namespace grip::rt
