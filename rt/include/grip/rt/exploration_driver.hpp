#pragma once
// Exploration (Bekris & Kavraki 2007, Sec. IV) as a replanning run drives it: the frontier
// target is chosen again every refresh_cycles cycles from where the next plan starts (the robot
// moves even when the map does not change), and the plan leads to the tree state of least
// visibility/length weight toward it (PathSelector).
//
// The choice (ExplorationTarget: wavefronts of milliseconds) runs on another thread while the
// planning thread goes on growing toward the previous target; a later cycle takes it over. The
// hand-over is one atomic stage: kIdle (the planning thread owns the target: it copies its map
// in and notes where the robot will be), kRequested (due), kChoosing (the target thread
// chooses), kChosen (the planning thread takes the choice over, then kIdle). In real time the
// first cycle after the choice takes it over. In lockstep the last cycle before the next request
// does (the one after the request when that is every cycle), waiting for the choice if it is not
// made yet (or making it, if the target thread has not begun): a seed reproduces a run, and the
// choice runs beside the growth of the cycles in between, as it runs beside the cycles' periods in
// real time, rather than holding up the next cycle.
//
// create() allocates; everything else never allocates and never throws.

#include <atomic>
#include <cstdint>

#include "grip/common/result.hpp"
#include "grip/exploration/exploration_target.hpp"
#include "grip/exploration/path_selector.hpp"
#include "grip/exploration/target_sight.hpp"
#include "grip/rt/map_changes.hpp"
#include "grip/rt/replanning_cycle.hpp"

namespace grip::rt {

struct ExplorationDriverConfig {
  ExplorationTargetConfig target;
  // The target is chosen again every this many cycles (1: every cycle). A new target costs the
  // target thread its wavefronts and its sight (TargetSight), and the tree, which needs that
  // time to grow, is carried over in between.
  std::uint32_t refresh_cycles = 5;
  PathWeightSettings path_weight;  // its vehicle's values resolved by create()
};

template <VehicleModel V>
class ExplorationDriver {
 public:
  // For the planner's grid (its geometry) and pools (max_edges); rho's inflation and cells are
  // the planner's (PlannerConfig::rho_clearance_m, rho_cell_m). A vehicle with a minimum turning
  // radius gets targets its kinematics can reach (ExplorationTargetConfig::kinematics, from its
  // chassis).
  static Result<ExplorationDriver> create(const V& vehicle, const OccupancyGrid& grid,
                                          const ExplorationDriverConfig& config,
                                          const PlannerConfig& planner);

  // Planning thread, before every cycle while exploring: takes over a chosen target (lockstep:
  // the cycle before the next request is due, once chosen), or requests a new one when it is due
  // and returns true (wake the target thread). `changes`: what this cycle wrote into `grid`.
  bool update(ReplanningCycle<V>& cycle, const OccupancyGrid& grid, std::uint64_t plan_start_ns,
              const MapChanges& changes, bool lockstep) noexcept;
  // Planning thread: chooses a target now and heads the cycle for it (the first target).
  void choose_now(ReplanningCycle<V>& cycle, const OccupancyGrid& grid,
                  std::uint64_t plan_start_ns) noexcept;
  // Target thread (or, in lockstep, the planning thread): chooses the requested target; false
  // when none was requested or another thread is choosing it.
  bool serve_request() noexcept;

  // The state the plan leads to: the path selector's choice, or the root once explored.
  // `course`: the end of the plan committed last (ReplanningCycle::committed).
  TreeState choose_plan_end(const Planner<V>& planner, std::uint32_t cycle_steps,
                            TreeState course) noexcept;
  // This cycle's target and choice of the plan's end (none before choose_plan_end, which a
  // cycle that could not keep its tree does not call).
  ExplorationRecord record() const noexcept;

  ExplorationDriver(ExplorationDriver&& other) noexcept;  // start-up only: not while in use
  ExplorationDriver& operator=(ExplorationDriver&&) = delete;

  // The path weight in use: the configuration's, the vehicle's where it said "auto".
  const PathSelectionConfig& path_weight() const noexcept { return selector_.config(); }

  // Exploration ended: no reachable frontier remained.
  bool explored() const noexcept { return explored_; }
  std::uint32_t groups() const noexcept { return groups_; }
  std::uint32_t groups_given_up() const noexcept { return groups_given_up_; }
  // Groups the vehicle's turning radius cannot reach (ExplorationTarget::unreachable_groups).
  std::uint32_t groups_unreachable() const noexcept { return groups_unreachable_; }
  // The last target taken over, if any: its centre (the group's cell nearest the robot).
  bool has_target() const noexcept { return has_target_; }
  double target_x_m() const noexcept { return target_x_m_; }
  double target_y_m() const noexcept { return target_y_m_; }

 private:
  enum Stage : std::uint8_t { kIdle, kRequested, kChoosing, kChosen };

  ExplorationDriver(const ExplorationDriverConfig& config, ExplorationTarget target,
                    TargetSight chosen_sight, PathSelector selector, TargetSight sight)
      : config_(config),
        target_(std::move(target)),
        chosen_sight_(std::move(chosen_sight)),
        selector_(std::move(selector)),
        sight_(std::move(sight)) {}
  void request(const ReplanningCycle<V>& cycle, const OccupancyGrid& grid,
               std::uint64_t plan_start_ns) noexcept;
  void choose() noexcept;
  void take_over(ReplanningCycle<V>& cycle) noexcept;

  ExplorationDriverConfig config_;
  std::atomic<std::uint8_t> stage_{kIdle};
  ExplorationTarget target_;
  TargetSight chosen_sight_;  // what sees target_'s choice, on the map it was chosen on
  double robot_x_m_ = 0.0;    // the request: where the robot will be, and when
  double robot_y_m_ = 0.0;
  double robot_theta_ = 0.0;
  std::int64_t robot_ns_ = 0;
  // Planning thread only.
  PathSelector selector_;
  TargetSight sight_;       // what sees the target taken over
  bool requested_ = false;  // a target has been requested at least once
  std::uint32_t cycles_since_request_ = 0;
  // Where the grid was written since target_ last copied it in (the first copy: all of it).
  CellBox written_since_request_{0, 0, OccupancyGrid::kMaxSideCells, OccupancyGrid::kMaxSideCells};
  bool explored_ = false;
  std::uint32_t groups_ = 0;
  std::uint32_t groups_given_up_ = 0;
  std::uint32_t groups_unreachable_ = 0;
  bool has_target_ = false;
  double target_x_m_ = 0.0;
  double target_y_m_ = 0.0;
  PathChoice choice_;  // this cycle's, once chosen
};

extern template class ExplorationDriver<DdVelocity>;
extern template class ExplorationDriver<DdAcceleration>;
extern template class ExplorationDriver<Car>;

}  // namespace grip::rt
