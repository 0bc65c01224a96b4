#pragma once
// The planner participant's publish thread (participant_threads.hpp): writes the plans and the
// status the planning thread hands over (handoff.hpp). A reliable writer that blocks in
// dds_write (up to max_blocking_time) delays only this thread; the planning thread meanwhile
// replaces the pending plan by a newer one, and the replaced one is counted as superseded.
// Woken when a plan's end is chosen, the thread is running by the time the plan is handed over,
// so that a plan's write does not wait for a thread's wake-up.

#include <atomic>
#include <cstdint>
#include <string>

#include "grip/platform/dds/writer.hpp"
#include "grip/platform/wakeup.hpp"
#include "grip/rt/vehicle_clock.hpp"
#include "grip/vehicles/vehicle.hpp"
#include "handoff.hpp"
#include "plan.h"
#include "planner_status.h"
#include "receive_side.hpp"

namespace grip::rt::dds {

struct PublishEntities {
  platform::dds::Writer<grip_msg_Plan>& plans;
  platform::dds::Writer<grip_msg_PlannerStatus>& status;
};

// What the publish thread did, for the report (after the run).
struct PublishCounts {
  std::string policy;  // the thread's scheduling: "fifo", or "other (why)"
  std::uint64_t published = 0;
  std::uint64_t rewritten = 0;  // plans written again for a lockstep vehicle still waiting
  std::uint64_t write_failures = 0;
};

class PublishSide {
 public:
  // `incarnation`: the planner's (link/incarnation.hpp), on every plan and status.
  PublishSide(VehicleKind kind, std::uint64_t incarnation, PublishEntities entities,
              Handoffs& handoffs, platform::Wakeup& wakeup, const ReceiveCounters& counters,
              const VehicleClock& clock)
      : kind_(kind),
        incarnation_(incarnation),
        dds_(entities),
        handoffs_(handoffs),
        wakeup_(wakeup),
        counters_(counters),
        clock_(clock) {}

  // The publish thread's body, until `stop_threads`.
  void run(const std::atomic<bool>& stop_threads);
  // Start-up: the vehicle's time scale, for the status' stamps.
  void set_time_scale(double scale) noexcept {
    time_scale_.store(scale, std::memory_order_relaxed);
  }

  std::uint64_t published() const noexcept { return published_.load(std::memory_order_relaxed); }
  PublishCounts counts() const;

 private:
  void publish_plan(const PlanSlot& slot, PublishTiming& timing);
  bool write_plan(const PlanSlot& slot);
  void publish_status(const CycleStatus& status);

  VehicleKind kind_;
  std::uint64_t incarnation_;
  PublishEntities dds_;
  Handoffs& handoffs_;
  platform::Wakeup& wakeup_;
  const ReceiveCounters& counters_;
  const VehicleClock& clock_;
  std::atomic<double> time_scale_{1.0};
  std::atomic<std::uint64_t> published_{0};
  std::atomic<std::uint64_t> write_failures_{0};
  std::atomic<std::uint64_t> rewritten_{0};
  std::string policy_;  // written by the publish thread before policy_set_
  std::atomic<bool> policy_set_{false};
};

}  // namespace grip::rt::dds
