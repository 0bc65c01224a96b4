#pragma once
// The replanning runtime as a DDS participant (`grip planner`): it subscribes to vehicle state,
// map updates and goals, and publishes plans and its status.
//
// A thin module around the DDS-free runtime (PX4's way): the replanning session and the
// exploration driver (rt/) do the planning; the participant owns the DDS entities, its threads
// (rt/dds/src/participant_threads.hpp: receive, planning, publish, target) and its two run
// loops. The receive side validates every sample and keeps the map in sync, the planning side
// runs one cycle per period (SCHED_DEADLINE where granted) and never calls into DDS, the publish
// side writes plans and status; everything crossing between them goes through bounded,
// lock-free hand-offs (rt/dds/src/handoff.hpp).
//
// Lockstep (a simulator that waits for each plan says so in its states): no periodic thread;
// run()'s thread plans one cycle for each state, once the map has every update sensed before
// it (VehicleState.map_sequence), growing a fixed number of edges: a seed reproduces a run.
//
// Start-up (run()): the planner waits for the vehicle's description (grip_vehicle_description)
// to match its own vehicle parameters, the map to be in sync, a vehicle state and a goal, then
// builds the planner (all allocation happens here) and starts the planning thread. A vehicle
// described otherwise is refused: run() returns the difference (kInvalidArgument), and nothing
// is planned or published; one that describes itself otherwise later (a new incarnation) stops
// planning the same way, with a warning. A vehicle side that restarts (a new incarnation in its
// states: idl/README.md) is planned for anew: start-up again, with what was learned from the
// old one forgotten. A map the planner cannot plan on is rejected and counted; start-up waits.
// Topics carry `topic_prefix` (link/topics.hpp), so that two vehicles can share a domain.
// Losing the vehicle (its liveliness lease expires) does not stop planning: the planner keeps
// planning on its last map and state, and says so in its status; the controller, for its part,
// falls back to the contingency maneuver that ends every plan.

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/exploration/exploration_target.hpp"
#include "grip/exploration/frontier.hpp"
#include "grip/exploration/path_selection_config.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/memory.hpp"
#include "grip/platform/scheduling.hpp"
#include "grip/rt/latency_histogram.hpp"
#include "grip/rt/periodic_loop.hpp"
#include "grip/vehicles/vehicle_params.hpp"

namespace grip::rt::dds {

struct PlannerParticipantConfig {
  platform::dds::DomainId domain = 0;
  std::string dds_config;  // Cyclone XML or file:// URI; empty: the built-in loopback-only one
  std::optional<platform::dds::SecurityFiles> security;  // DDS Security; none: unauthenticated
  std::string topic_prefix;  // empty: the topics' own names; checked by create()
  // What the planner plans with, checked by create(); the vehicle must describe itself the same.
  VehicleParams vehicle = CarParams{};
  double cycle_s = 0.05;    // T, in vehicle time
  double budget_s = 0.025;  // planning time per cycle, in vehicle time
  double margin_s = -1.0;   // growth stops this long before the deadline; < 0: wall-clock
                            // default_safety_margin_ms(budget)
  platform::PolicyRequest policy = platform::PolicyRequest::kAuto;
  int fifo_priority = 80;       // the planning thread's, under SCHED_FIFO
  int cpu = -1;                 // the planning thread pinned to this CPU (fifo or other); -1: any
  std::uint32_t max_edges = 0;  // 0: 400 per millisecond of wall-clock budget (lockstep: 4 cycles)
  // Lockstep (the vehicle's states ask for it: a simulator that waits for each plan): one cycle
  // per state, growing this many edges whatever the time, so that a seed reproduces a run.
  // 1000 is about what 2.5 ms of growth adds on a current x86 core.
  std::uint32_t lockstep_edges = 1000;
  GripTuning tuning;  // GRIP's a and plan durations
  std::uint32_t max_map_cells = 1U << 22;
  std::uint64_t seed = 1;
  std::chrono::nanoseconds liveliness_lease{std::chrono::milliseconds(500)};
  std::chrono::nanoseconds startup_timeout{0};  // 0: wait for ever
  double duration_s = 0.0;                      // wall clock; 0: until request_stop()
  // Without a goal the planner explores (the paper's Sec. IV): its target is the frontier group
  // chosen every cycle and its plan the trajectory of least visibility/length weight. A goal
  // that arrives later takes over. A goal is waited for this long after the map is in sync.
  bool explore_without_goal = true;
  std::chrono::nanoseconds goal_grace{std::chrono::seconds(1)};
  PathWeightSettings path_weight;  // as ExplorationDriverConfig's
  // A frontier target the vehicle gets no closer to (by rho_A*, 0.5 m) for this long, in
  // vehicle time, is given up (FrontierMap::give_up) and the next one chosen.
  double frontier_give_up_s = 60.0;
  // A target the vehicle stands within the approach range of (ExplorationTarget) that is still a
  // frontier after this long is given up: the sensor does not resolve it from there.
  double frontier_give_up_reached_s = 3.0;
  // rho toward the target is computed out to the vehicle's own plus this (ExplorationTarget).
  double frontier_rho_margin_m = ExplorationTargetConfig{}.rho_margin_m;
  // How frontier cells are grouped and groups scored; its clearance_m is the planner's own.
  FrontierConfig frontier;
  // The frontier target is chosen again every this many cycles (1: every cycle). In real time the
  // choice runs on the target thread, but taking it over still costs the planning thread rho
  // toward the new target and the path selector's rays (whole-map passes, 0.5 to 1 ms on the
  // built-in scenes), and the tree, which needs that time to grow, is carried over in between.
  std::uint32_t target_refresh_cycles = 5;
  bool no_safety = false;  // the paper's ablation: no contingency check (plans may end unsafe)
  bool lock_memory = true;
  // Called about every 250 ms from run()'s thread with a one-line summary (progress display).
  std::function<void(const std::string&)> on_progress;
  // Called from run()'s thread with every cycle's record, soon after the cycle (a cycle trace).
  // In lockstep there is no release or deadline: the record's release is the cycle's start.
  std::function<void(const CycleRecord&)> on_cycle;
  // Called once from run()'s thread when start-up succeeded, with a one-line summary (a
  // service's readiness).
  std::function<void(const std::string&)> on_ready;
  // Called from run()'s thread at most every `alive_interval` (zero: never), and only when
  // cycles completed since the last call (rt/liveness_beat.hpp): a service's watchdog, which a
  // stalled planning loop stops feeding. Never from the planning thread.
  std::chrono::nanoseconds alive_interval{0};
  std::function<void()> on_alive;
  // Warnings (rejected samples, map gaps, a lost vehicle), one line each without a trailing
  // newline, from the receive thread. Unset: printed to stderr.
  std::function<void(const std::string&)> on_warning;
};

struct PlannerParticipantReport {
  std::string policy;           // the planning thread's scheduling policy
  std::string policy_fallback;  // why a stronger policy was refused, empty if none
  std::string publish_policy;   // the publish thread's: "fifo", or "other (why)"
  double time_scale = 1.0;
  std::uint64_t cycles = 0;
  std::uint64_t misses = 0;
  std::uint64_t plans_committed = 0;  // cycles that handed a plan to the publish thread
  std::uint64_t plans_published = 0;
  std::uint64_t plans_superseded = 0;  // replaced by a newer plan before the writer took them
  std::uint64_t write_failures = 0;
  std::uint64_t plans_rewritten = 0;  // written again for a lockstep vehicle that still waited
  std::uint64_t rejected_vehicle_state = 0;
  std::uint64_t rejected_map_update = 0;
  std::uint64_t rejected_goal = 0;
  std::uint64_t map_gaps = 0;
  std::uint64_t map_heals = 0;
  std::uint64_t map_sequence = 0;    // last update the planning thread applied
  std::uint64_t map_checksum = 0;    // of the planning thread's map at the end
  std::uint64_t vehicle_losses = 0;  // times the vehicle's liveliness was lost
  // Times a new vehicle incarnation replaced the one planned for (a restarted vehicle side);
  // the report's other figures are of the planning for the last one.
  std::uint64_t vehicle_restarts = 0;
  // [s] From the beginning of start-up (run()) to the map first in sync, and to planning
  // (sizing the planner included): a large map's cost before the first plan.
  double map_sync_s = 0.0;
  double startup_s = 0.0;
  bool explored = false;      // exploration ended: no reachable frontier remained
  std::uint64_t resyncs = 0;  // fresh trees from where a vehicle off the tree will be
  bool allocations_counted = false;
  std::uint64_t heap_allocations_in_loop = 0;  // planning thread, after warm-up
  platform::ThreadUsage usage_in_loop{};
  // Release to wake-up (lockstep: the state's arrival to the map holding every update sensed
  // up to it), and wake-up to the end of the cycle.
  LatencyHistogram wake_latency;
  LatencyHistogram compute;
  // Each published plan's way out, on the publish thread: from its commit on the planning
  // thread to the start of its write (the hand-off), and the write (dds_write) itself.
  LatencyHistogram plan_handoff;
  LatencyHistogram plan_write;
};

// The planner's last tree and committed plan in the plane, for pictures.
struct PlannerTreePicture {
  std::vector<std::vector<std::array<double, 2>>> edges;  // each edge's states (x, y) [m]
  std::vector<std::array<double, 2>> plan;                // from the plan's start to its end
};

class PlannerParticipant {
 public:
  // Creates the participant, its readers and writers, and starts the receive thread.
  static Result<std::unique_ptr<PlannerParticipant>> create(const PlannerParticipantConfig& config);
  virtual ~PlannerParticipant() = default;

  // Start-up, then planning until duration_s passes or request_stop(). An error when start-up
  // fails (timeout: names what is missing), the planning thread cannot start, or the vehicle
  // describes itself otherwise than `vehicle` (kInvalidArgument naming the field).
  virtual Result<PlannerParticipantReport> run() = 0;
  // After run() has returned (allocates): empty when planning never started.
  virtual PlannerTreePicture last_tree() const = 0;
  // Any thread (a signal handler's forwarding thread included).
  void request_stop() noexcept { stop_.store(true, std::memory_order_release); }

 protected:
  PlannerParticipant() = default;
  std::atomic<bool> stop_{false};
};

}  // namespace grip::rt::dds
