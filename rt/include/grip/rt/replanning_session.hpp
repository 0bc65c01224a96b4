#pragma once
// A planner's run against one vehicle, without the transport: the planner's grid, the
// replanning cycle sized for the run, the plans sent (PlanLedger) and the chain of their start
// times. The DDS participant (rt/dds) is a thin module around it; tests drive it directly.
//
// Each cycle (Bekris & Kavraki 2007, Sec. III, Fig. 2) plans during (t[i-1], t[i]) for execution
// from t[i]. The session keeps t[i] on the vehicle's clock, consecutive plans exactly T apart on
// the vehicle's integration grid, and forecasts from the last measured state and the plans sent
// since where the vehicle will be at t[i]; when that is not where the tree puts the plan's start
// (a plan came late or was refused, the vehicle brakes off its plans), the cycle starts a fresh
// tree there, or every plan it sent would be refused.
//
// Start-up (create, create_cycle, start) allocates; everything after never allocates and never
// throws. One thread at a time (start-up, then the planning thread).

#include <array>
#include <cmath>
#include <cstdint>
#include <optional>
#include <span>

#include "grip/common/function_ref.hpp"
#include "grip/common/result.hpp"
#include "grip/rt/cycle_sizing.hpp"
#include "grip/rt/map_changes.hpp"
#include "grip/rt/plan_lead.hpp"
#include "grip/rt/plan_ledger.hpp"
#include "grip/rt/replanning_cycle.hpp"
#include "grip/rt/vehicle_clock.hpp"

namespace grip::rt {

// A measured state of the vehicle, as its controller reports it.
struct VehicleSample {
  std::array<double, 5> state{};  // the model's state, first V::kStateDim entries
  std::uint64_t stamp_ns = 0;     // vehicle time
  std::uint64_t sequence_number = 0;
  std::uint64_t plan_cycle = 0;    // the plan it executes (0: none)
  std::uint64_t map_sequence = 0;  // the last map update sensed before it
  double time_scale = 1.0;         // vehicle time per wall-clock time
  bool lockstep = false;           // it waits for a plan for each state
  std::uint64_t incarnation = 0;   // the vehicle side's (VehicleState.incarnation); 0: unknown
  // How early this planner's plan plan_arrival_cycle reached the vehicle (0: no report).
  std::uint64_t plan_arrival_cycle = 0;
  std::int64_t plan_arrival_margin_ns = 0;
};

struct SessionConfig {
  double cycle_s = 0.05;        // T, in vehicle time
  double budget_s = 0.025;      // planning time per cycle, in vehicle time
  double margin_s = -1.0;       // growth stops this long before the deadline; < 0: the default
  std::uint32_t max_edges = 0;  // 0: from the budget (cycle_sizing.hpp)
  std::uint32_t lockstep_edges = 1000;  // edges grown per cycle in lockstep
  std::uint64_t seed = 1;
  bool no_safety = false;               // the paper's ablation: no contingency check
  std::uint32_t max_plan_steps = 1024;  // pieces a sent plan may have
  // Exploring, rho comes with each frontier target, chosen every this many cycles.
  std::uint32_t target_refresh_cycles = 5;
  GripTuning tuning;
};

// A cycle's plan, as sent (an empty plan when the cycle has none).
template <VehicleModel V>
struct SentPlan {
  std::uint64_t cycle = 0;           // its number, from 1
  std::uint64_t start_ns = 0;        // t[i], vehicle time
  typename V::State from;            // the state it starts from
  std::uint64_t state_sequence = 0;  // the last measured state when it was planned
  std::span<const PlanStep> steps;   // valid until the next cycle
};

template <VehicleModel V>
class ReplanningSession {
 public:
  using State = typename V::State;

  // `grid` is the planner's map from now on, written through MapChanges.
  static Result<ReplanningSession> create(const V& vehicle, OccupancyGrid grid,
                                          const SessionConfig& config);

  OccupancyGrid& grid() noexcept { return grid_; }
  const OccupancyGrid& grid() const noexcept { return grid_; }

  // Start-up, once: sizes the cycle for the vehicle's time scale and mode. Exploring, the commit
  // chooses the plan by a pass over the whole tree, so growth leaves it a reserve from the start.
  Status create_cycle(double time_scale, bool lockstep, bool explore);
  bool has_cycle() const noexcept { return cycle_.has_value(); }
  // Start-up: the first tree at the measured state toward `goal`; refused, for example, while
  // the start is not known free. The state is the last measured one from now on.
  Status start(const VehicleSample& state, const Goal& goal);

  // A measured state (each cycle that has a new one, before the plan's start is set).
  void note_state(const VehicleSample& state) noexcept;
  // Real time: t[i] at or after the release that follows `release_ns`, on the chain of start
  // times (the cycle released at release_ns plans for execution from the next release).
  void chain_plan_start(std::int64_t release_ns, const VehicleClock& clock) noexcept;
  // Lockstep: t[i] is the measured state's time + T.
  void set_plan_start_after(const VehicleSample& state) noexcept;
  // The plan of this cycle starts where the vehicle will be at t[i] (see the file comment).
  void check_vehicle_follows() noexcept { follow_forecast(plan_start_ns_); }

  void note_map_changes(const MapChanges& changes) noexcept {
    rt::note_map_changes(*cycle_, changes);
  }
  // Grows the tree until the deadline (real time) or by lockstep_edges (lockstep), then commits;
  // `choose` picks the state the plan should lead to, `plan_chosen` is called once the plan's end
  // is settled (ReplanningCycle::run). Real time: a cycle that ends after the deadline is missed.
  CycleOutcome run(FunctionRef<std::int64_t()> now_ns, std::int64_t deadline_ns,
                   FunctionRef<TreeState(const Planner<V>&)> choose,
                   FunctionRef<void()> plan_chosen) noexcept;
  // The plan of the cycle just run, recorded as sent; without one, an empty plan, and the next
  // cycle starts where the plan the vehicle goes on with leads.
  SentPlan<V> send_plan(const CycleOutcome& outcome) noexcept;
  // Real time: releases the periodic loop skipped after a stall were missed too.
  void note_release(std::int64_t release_ns) noexcept;

  ReplanningCycle<V>& cycle() noexcept { return *cycle_; }
  const ReplanningCycle<V>& cycle() const noexcept { return *cycle_; }
  const Planner<V>& planner() const noexcept { return cycle_->planner(); }
  const V& vehicle() const noexcept { return vehicle_; }
  std::uint64_t plan_start_ns() const noexcept { return plan_start_ns_; }
  // Real time: how much later than one cycle ahead plans start, for the link's delay.
  std::int64_t plan_lead_ns() const noexcept { return lead_.lead_ns(); }
  std::uint64_t cycles() const noexcept { return cycles_; }
  std::uint64_t misses() const noexcept { return misses_; }
  std::uint64_t plans_committed() const noexcept { return plans_committed_; }
  std::uint64_t resyncs() const noexcept { return resyncs_; }
  double time_scale() const noexcept { return time_scale_; }
  bool lockstep() const noexcept { return lockstep_; }
  std::int64_t period_wall_ns() const noexcept { return period_wall_ns_; }
  std::uint32_t max_edges() const noexcept { return max_edges_; }
  const CycleSizing& sizing() const noexcept { return sizing_; }

 private:
  ReplanningSession(const V& vehicle, OccupancyGrid grid, const SessionConfig& config)
      : vehicle_(vehicle),
        grid_(std::move(grid)),
        config_(config),
        lead_(static_cast<std::int64_t>(std::llround(config.cycle_s * 1e9))) {}
  void follow_forecast(std::uint64_t until_ns) noexcept;

  V vehicle_;
  OccupancyGrid grid_;
  SessionConfig config_;
  CycleSizing sizing_;
  std::optional<ReplanningCycle<V>> cycle_;
  std::optional<PlanLedger<V>> ledger_;
  double time_scale_ = 1.0;
  bool lockstep_ = false;
  std::int64_t period_wall_ns_ = 0;
  std::uint32_t max_edges_ = 0;
  std::optional<VehicleSample> last_state_;
  std::uint64_t plan_start_ns_ = 0;  // t[i], vehicle time
  PlanLead lead_;
  std::uint64_t cycles_ = 0;
  std::uint64_t misses_ = 0;  // cycles that ended after their deadline, or were skipped
  std::int64_t last_release_ns_ = 0;
  std::uint64_t plans_committed_ = 0;
  std::uint64_t resyncs_ = 0;  // fresh trees where the vehicle will be, off the tree
};

extern template class ReplanningSession<DdVelocity>;
extern template class ReplanningSession<DdAcceleration>;
extern template class ReplanningSession<Car>;

}  // namespace grip::rt
