#include "publish_side.hpp"

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <iterator>

#include "grip/link/messages.hpp"
#include "grip/platform/clock.hpp"
#include "grip/platform/scheduling.hpp"
#include "grip/platform/thread.hpp"
#include "participant_threads.hpp"

namespace grip::rt::dds {

void PublishSide::run(const std::atomic<bool>& stop_threads) {
  platform::SchedulingRequest request;
  request.request = kPublishThread.policy;
  request.fifo_priority = kPublishThread.fifo_priority;
  const auto applied = platform::apply_scheduling(request);
  policy_ = applied.ok() ? "fifo" : "other (" + applied.error().message + ")";
  policy_set_.store(true, std::memory_order_release);
  // A plan is announced (Handoffs::plan_coming) once its end is settled, before it is extracted
  // and handed over: the thread's wake-up latency then overlaps that work instead of adding to
  // the plan's delivery, and the thread, running, watches the hand-off for the plan, at most
  // kPlanComingWatchNs (the extraction takes tens of microseconds).
  constexpr std::int64_t kPlanComingWatchNs = 1'000'000;
  PublishTiming timing;
  while (!stop_threads.load(std::memory_order_acquire)) {
    static_cast<void>(wakeup_.wait(std::chrono::milliseconds(100)));
    if (handoffs_.plan_coming.exchange(false, std::memory_order_acquire)) {
      const std::int64_t watch_until = platform::now_ns() + kPlanComingWatchNs;
      while (!handoffs_.plans->fresh() && platform::now_ns() < watch_until) platform::cpu_relax();
    }
    const std::uint64_t wanted = handoffs_.plan_wanted_for.exchange(0, std::memory_order_acquire);
    if (handoffs_.plans->update()) {
      publish_plan(handoffs_.plans->read_buffer(), timing);
      handoffs_.publish_timing->write(timing);
    } else if (wanted != 0 && handoffs_.plans->read_buffer().state_sequence == wanted) {
      // A failed write is tried again at the vehicle's next repeat.
      if (write_plan(handoffs_.plans->read_buffer())) {
        rewritten_.fetch_add(1, std::memory_order_relaxed);
      }
    }
    if (handoffs_.statuses->update()) publish_status(handoffs_.statuses->read_buffer());
  }
}

PublishCounts PublishSide::counts() const {
  PublishCounts counts;
  if (policy_set_.load(std::memory_order_acquire)) counts.policy = policy_;
  counts.published = published_.load();
  counts.rewritten = rewritten_.load();
  counts.write_failures = write_failures_.load();
  return counts;
}

void PublishSide::publish_plan(const PlanSlot& slot, PublishTiming& timing) {
  const std::int64_t write_start = platform::now_ns();
  const bool written = write_plan(slot);
  const std::int64_t write_end = platform::now_ns();
  if (written) {
    timing.handoff.record(write_start - static_cast<std::int64_t>(slot.committed_monotonic_ns));
    timing.write.record(write_end - write_start);
    published_.fetch_add(1, std::memory_order_relaxed);
  } else {
    write_failures_.fetch_add(1, std::memory_order_relaxed);
  }
}

bool PublishSide::write_plan(const PlanSlot& slot) {
  grip_msg_Plan msg{};
  msg.cycle = slot.cycle;
  msg.start_time_ns = slot.start_time_ns;
  std::copy(slot.start_state.begin(), slot.start_state.end(), std::begin(msg.start_state));
  msg.state_dim = slot.state_dim;
  msg.state_sequence = slot.state_sequence;
  msg.committed_monotonic_ns = slot.committed_monotonic_ns;
  msg.kind = link::to_wire(kind_);
  msg.contingency = link::contingency_of(kind_);
  msg.incarnation = incarnation_;
  msg.vehicle_incarnation = slot.vehicle_incarnation;
  // Borrowed, not copied: DDS serialises during dds_write.
  msg.steps._buffer = const_cast<grip_msg_PlanStep*>(slot.step.data());
  msg.steps._length = slot.steps;
  msg.steps._maximum = slot.steps;
  msg.steps._release = false;
  return dds_.plans.write(msg).ok();
}

void PublishSide::publish_status(const CycleStatus& s) {
  grip_msg_PlannerStatus msg{};
  msg.cycle = s.cycle;
  msg.stamp_ns = static_cast<std::uint64_t>(
      clock_.vehicle_ns(platform::now_ns(), time_scale_.load(std::memory_order_relaxed)));
  std::snprintf(msg.policy, sizeof msg.policy, "%s", "grip at T, contingency at T");
  msg.misses = s.misses;
  msg.tree_edges = s.tree_edges;
  msg.edges_added = s.edges_added;
  msg.cycle_time_s = s.cycle_time_s;
  msg.rejected_vehicle_state = counters_.rejected_vehicle_state.load(std::memory_order_relaxed);
  msg.rejected_map_update = counters_.rejected_map_update.load(std::memory_order_relaxed);
  msg.rejected_goal = counters_.rejected_goal.load(std::memory_order_relaxed);
  msg.map_gaps = counters_.map_gaps.load(std::memory_order_relaxed);
  msg.map_heals = counters_.map_heals.load(std::memory_order_relaxed);
  msg.map_sequence = s.map_sequence;
  msg.map_checksum = s.map_checksum;
  msg.map_in_sync = s.map_in_sync;
  msg.plans_published = published_.load(std::memory_order_relaxed);
  msg.plans_dropped = write_failures_.load(std::memory_order_relaxed);
  const auto matched = dds_.plans.publication_matched();
  msg.plan_subscribers = matched.ok() ? matched->current_count : 0;
  msg.vehicle_alive = counters_.vehicle_alive.load(std::memory_order_relaxed);
  msg.exploring = s.exploring;
  msg.exploration_complete = s.exploration_complete;
  msg.frontier_groups = s.frontier_groups;
  msg.frontier_groups_given_up = s.frontier_groups_given_up;
  msg.frontier_groups_unreachable = s.frontier_groups_unreachable;
  msg.target_x_m = s.target_x_m;
  msg.target_y_m = s.target_y_m;
  msg.incarnation = incarnation_;
  msg.vehicle_incarnation = s.vehicle_incarnation;
  msg.vehicle_restarts =
      static_cast<std::uint32_t>(counters_.vehicle_restarts.load(std::memory_order_relaxed));
  static_cast<void>(dds_.status.write(msg));
}

}  // namespace grip::rt::dds
