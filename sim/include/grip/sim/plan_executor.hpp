#pragma once
// Executes the planner's plans with the vehicle model against simulated time, as the vehicle's
// controller would (the paper's Sec. II and III-C), and watches the chassis against the ground
// truth.
//
// Time: nanoseconds, integer, so that plan switches happen exactly when they should. The
// executor advances in ticks of step_s (default 0.05 s, the planner's integration_step_s) with
// the model's own step(), the routine the planner predicts with: a plan that starts on a tick
// boundary and whose pieces last whole ticks executes exactly as predicted. A piece boundary or
// a plan start that falls inside a tick splits the tick there (the model integrates both parts),
// so no switch is ever early or late.
//
// Plans: submit() queues a plan that starts at its start time (not before the current time);
// submit_empty() queues an empty plan: the planner has nothing new from its start time.
// The most recent plan governs from its start time on: a submitted plan replaces every queued
// plan starting at or after it, and at its start time it replaces the plan being executed
// (unless it is refused there: ExecutorConfig::refuse_start_mismatch). An empty plan replaces
// queued plans the same way but never the executed one: the vehicle drives that to its end,
// where the planner checked its braking (the paper's Sec. III-C); braking anywhere else was never
// checked (cutting plans short, a car braked into a door frame).
// When the executed plan runs out with nothing queued, or abandon_plans() is called (the
// planner fell silent past its lease), the vehicle performs the model's braking contingency
// (braking_control / brake_step) until it rests, then stays at rest until the next plan starts.
//
// Collisions: after every tick the exact chassis (CollisionChecker, margin 0: no inflation) is
// checked against the ground truth; touching or overlapping an obstacle cell, or leaving the
// grid, is a collision. A collision event is the step from free into collision; each is counted
// and recorded with time and pose; the ticks spent in collision are counted too. Nothing is
// hidden: the counts stay exact when the event log is full.
//
// Capacity is fixed at creation; submit(), abandon_plans(), step() and run_until() never
// allocate and never throw (a rejected plan returns a verdict, not a message).

#include <cstdint>
#include <optional>
#include <span>
#include <string_view>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/planner/plan_following.hpp"
#include "grip/planner/planner.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip::sim {

struct ExecutorConfig {
  double step_s = 0.05;                 // integration tick; keep equal to the planner's
  std::uint32_t max_plan_steps = 1024;  // msg::kMaxPlanSteps
  // Plans waiting for their start time: over a slow link the planner sends plans up to
  // rt::PlanLead::kMaxLeadCycles cycles ahead.
  std::uint32_t max_queued_plans = 16;
  std::uint32_t max_collision_events = 1024;  // recorded in detail; all are counted
  std::uint32_t max_speed_samples = 72'000;   // one per tick: an hour at 20 Hz
  // A plan whose predicted start differs from the vehicle's state is refused at its start time:
  // its controls would drive the vehicle from a state nobody checked. The vehicle carries on
  // with what it was doing, the rest of its plan (which ends in the braking the planner checked
  // when it committed it) or its braking, as if the plan had never come.
  bool refuse_start_mismatch = false;

  Status validate() const;
};

enum class PlanVerdict : std::uint8_t {
  kAccepted,
  kEmpty,            // no steps
  kTooManySteps,     // more than max_plan_steps
  kBadDuration,      // a duration not finite or <= 0, or rounding to 0 ns
  kBadControl,       // a control not finite or outside the model's limits
  kStartsInThePast,  // start time before the executor's current time
  kQueueFull,        // max_queued_plans plans already wait for earlier start times
};
std::string_view plan_verdict_name(PlanVerdict v) noexcept;

// kAtRest: initially, and after a contingency completed; kExecuting: until a tick begins after
// the plan's last piece ended; kBraking: the contingency maneuver.
using ExecutorMode = ControllerMode;
std::string_view executor_mode_name(ExecutorMode m) noexcept;

struct CollisionEvent {
  std::int64_t time_ns;  // end of the first tick found in collision
  double x_m;
  double y_m;
  double theta_rad;
};

struct SpeedSample {
  std::int64_t time_ns;
  double speed_m_s;
};

struct ExecutorStats {
  std::uint64_t ticks = 0;
  std::uint64_t collisions = 0;  // collision events (entering collision)
  std::uint64_t ticks_in_collision = 0;
  std::uint64_t contingencies = 0;    // switches from a plan to the braking contingency
  std::uint64_t plans_ran_out = 0;    // ... because the plan ended with nothing queued
  std::uint64_t plans_abandoned = 0;  // ... because abandon_plans() was called
  std::uint64_t plans_accepted = 0;
  std::uint64_t plans_rejected = 0;
  std::uint64_t plans_started = 0;
  std::uint64_t plans_superseded = 0;  // queued plans replaced before they started
  std::uint64_t start_mismatches = 0;  // plans whose predicted start differed (!states_match)
  std::uint64_t plans_refused = 0;     // ... and were not executed (refuse_start_mismatch)
  double max_start_position_error_m = 0.0;
  double max_start_heading_error_rad = 0.0;
  double distance_m = 0.0;     // sum of the reference point's chords per sub-step
  double speed_sum_m_s = 0.0;  // over ticks since the first plan started
  std::uint64_t speed_ticks = 0;
  std::uint64_t speed_samples_dropped = 0;
  std::uint64_t collision_events_dropped = 0;
};

template <VehicleModel V>
class PlanExecutor {
 public:
  using State = typename V::State;
  using Control = typename V::Control;

  // The vehicle starts at rest in `start` at time start_time_ns. Errors: a config that fails
  // validate(), a start state the model rejects, a start whose chassis collides with the ground
  // truth (kInvalidArgument naming the pose). `truth` must outlive the executor, unmoved.
  static Result<PlanExecutor> create(const V& vehicle, const OccupancyGrid& truth,
                                     const State& start, std::int64_t start_time_ns,
                                     const ExecutorConfig& config = {});

  // Queues a plan (see the top of this file). `predicted_start`, when given, is the state the
  // planner expected at start_time_ns: the difference from the actual state at that time is
  // recorded in stats(), and with refuse_start_mismatch a mismatching plan is not executed.
  // `tag` names the plan while it is executed (executing_tag(); the planner's cycle).
  PlanVerdict submit(std::span<const PlanStep> steps, std::int64_t start_time_ns,
                     const std::optional<State>& predicted_start = std::nullopt,
                     std::uint64_t tag = 0) noexcept;

  // An empty plan (the planner had no plan for a cycle): it supersedes the queued plans
  // starting at or after start_time_ns, and the vehicle goes on with the plan it executes then.
  // kStartsInThePast, kQueueFull as for a plan.
  PlanVerdict submit_empty(std::int64_t start_time_ns) noexcept;

  // The planner is silent past its lease: drops the executed and queued plans and brakes.
  void abandon_plans() noexcept;

  // Advances one tick.
  void step() noexcept;
  // Advances whole ticks while a full tick fits before or at t_ns.
  void run_until(std::int64_t t_ns) noexcept;

  const State& state() const noexcept { return state_; }
  std::int64_t now_ns() const noexcept { return now_ns_; }
  std::int64_t step_ns() const noexcept { return step_ns_; }
  ExecutorMode mode() const noexcept { return mode_; }
  bool in_collision() const noexcept { return in_collision_; }
  // The control held during the last sub-step (the braking control while braking, zero at rest).
  const Control& control() const noexcept { return control_; }
  // |velocity| of the reference point now [m/s] (for a velocity-controlled robot, from the
  // control held).
  double speed_m_s() const noexcept;
  std::size_t queued_plans() const noexcept { return queue_size_; }
  // The tag of the plan being executed; 0 when braking or at rest.
  std::uint64_t executing_tag() const noexcept {
    return mode_ == ExecutorMode::kExecuting ? slots_[current_].tag : 0;
  }

  const ExecutorStats& stats() const noexcept { return stats_; }
  // Mean speed since the first plan started over the model's maximum speed; 0 before.
  double mean_speed_fraction() const noexcept;
  std::span<const CollisionEvent> collision_events() const noexcept { return events_; }
  std::span<const SpeedSample> speed_samples() const noexcept { return speeds_; }
  const V& vehicle() const noexcept { return vehicle_; }

 private:
  struct PlanSlot {
    std::vector<PlanStep> steps;       // capacity max_plan_steps, reserved at creation
    std::vector<std::int64_t> end_ns;  // absolute end time of each step
    std::int64_t start_ns = 0;
    std::optional<State> predicted_start;
    std::uint64_t tag = 0;
  };

  PlanExecutor(const V& vehicle, CollisionChecker checker, const State& start,
               std::int64_t start_time_ns, const ExecutorConfig& config);

  enum class ContingencyCause : std::uint8_t { kRanOut, kAbandoned };

  PlanVerdict enqueue(std::span<const PlanStep> steps, std::int64_t start_time_ns,
                      const std::optional<State>& predicted_start, std::uint64_t tag) noexcept;
  void start_queued_plan() noexcept;
  void begin_contingency(ContingencyCause cause) noexcept;
  void integrate(std::int64_t until_ns) noexcept;
  void after_tick() noexcept;

  V vehicle_;
  CollisionChecker checker_;  // exact chassis against the ground truth
  ExecutorConfig config_;
  std::int64_t step_ns_;
  State state_;
  Control control_;
  std::int64_t now_ns_;
  ExecutorMode mode_ = ExecutorMode::kAtRest;
  bool in_collision_ = false;
  bool speed_started_ = false;

  std::vector<PlanSlot> slots_;  // max_queued_plans + 1
  std::size_t current_ = 0;      // slot executed when mode_ == kExecuting
  std::size_t piece_ = 0;        // step of the current plan being executed
  // The queue, in start order: indices into slots_ of the queued plans.
  std::vector<std::size_t> queue_;
  std::size_t queue_size_ = 0;

  ExecutorStats stats_;
  std::vector<CollisionEvent> events_;
  std::vector<SpeedSample> speeds_;
};

extern template class PlanExecutor<DdVelocity>;
extern template class PlanExecutor<DdAcceleration>;
extern template class PlanExecutor<Car>;

}  // namespace grip::sim
