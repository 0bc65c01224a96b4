#pragma once
// The planner participant's planning thread (participant_threads.hpp; run()'s thread during
// start-up and in lockstep): applies the map tiles the receive thread hands over, runs one cycle
// of the replanning session (rt::ReplanningSession) toward the goal or, exploring, toward the
// frontier target (rt::ExplorationDriver), and hands the plan and the status to the publish
// thread (handoff.hpp). It never calls DDS, never allocates after start-up and never blocks.

#include <atomic>
#include <cstdint>
#include <memory>
#include <optional>

#include "grip/common/result.hpp"
#include "grip/link/messages.hpp"
#include "grip/platform/wakeup.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "grip/rt/exploration_driver.hpp"
#include "grip/rt/replanning_session.hpp"
#include "handoff.hpp"

namespace grip::rt::dds {

template <VehicleModel V>
class PlanningSide {
 public:
  PlanningSide(const PlannerParticipantConfig& config, const V& vehicle, Handoffs& handoffs,
               platform::Wakeup& publish_wakeup, platform::Wakeup& target_wanted,
               const VehicleClock& clock)
      : config_(config),
        vehicle_(vehicle),
        handoffs_(handoffs),
        publish_wakeup_(publish_wakeup),
        target_wanted_(target_wanted),
        clock_(clock) {}

  // Start-up: the vehicle incarnation planned for (link/incarnation.hpp): tiles and states of
  // another are ignored; 0 until one is known.
  void set_vehicle(std::uint64_t incarnation) noexcept { vehicle_incarnation_ = incarnation; }
  std::uint64_t vehicle_incarnation() const noexcept { return vehicle_incarnation_; }
  // Start-up: the planner's map, unknown everywhere, once the geometry is known.
  Status create_map(const link::MapGeometry& geometry);
  bool has_map() const noexcept { return session_.has_value(); }
  // Writes the tiles handed over since the last call into the planner's map.
  void apply_tiles(MapChanges& changes) noexcept;
  bool map_in_sync() const noexcept { return map_in_sync_; }
  std::uint64_t map_sequence() const noexcept { return map_sequence_; }

  // Start-up, once: the cycle sized for the vehicle's time scale and mode (from its state), and
  // exploration's fixed memory (also with a goal: a goal may never come).
  Status prepare(const VehicleSample& state, bool explore);
  bool prepared() const noexcept { return driver_.has_value(); }
  // Start-up: the first tree, toward `goal` or, without one, exploring; again until accepted
  // (the start may not be known free yet).
  Status start(const VehicleSample& state, const std::optional<Goal>& goal);
  bool lockstep() const noexcept { return session_->lockstep(); }
  double time_scale() const noexcept { return session_->time_scale(); }
  std::int64_t period_wall_ns() const noexcept { return session_->period_wall_ns(); }
  // Exploring: the first target, before the first cycle (which would otherwise plan
  // toward the start while the target thread chooses).
  void choose_first_target() noexcept;

  // Real time: one cycle per period, growth until the deadline.
  CycleOutcome cycle_body(std::int64_t release_ns, std::int64_t deadline_ns) noexcept;
  // Lockstep: a cycle for `state`, its map updates applied (`changes`), started at start_ns.
  CycleOutcome lockstep_cycle(const VehicleSample& state, const MapChanges& changes,
                              std::int64_t start_ns) noexcept;
  // The target thread: chooses a requested frontier target; false when none was requested.
  bool serve_target_request() noexcept {
    return driver_ready_.load(std::memory_order_acquire) && driver_->serve_request();
  }

  // After the run.
  void fill_report(PlannerParticipantReport& report) const;
  PlannerTreePicture tree_picture() const;

 private:
  CycleOutcome plan_cycle(std::int64_t start_ns, const MapChanges& changes,
                          std::int64_t deadline_ns) noexcept;
  void hand_over_plan(const CycleOutcome& outcome) noexcept;
  void hand_over_status(const CycleOutcome& outcome, std::int64_t start_ns) noexcept;

  PlannerParticipantConfig config_;
  V vehicle_;
  Handoffs& handoffs_;
  platform::Wakeup& publish_wakeup_;
  platform::Wakeup& target_wanted_;  // real time: a frontier target was requested
  const VehicleClock& clock_;
  std::optional<ReplanningSession<V>> session_;
  std::optional<ExplorationDriver<V>> driver_;  // created at start-up: a goal may never come
  // driver_ exists: published by prepare() to the target thread, which polls from the start.
  std::atomic<bool> driver_ready_{false};
  bool exploring_ = false;    // no goal was given (yet)
  double heading_x_m_ = 0.0;  // the goal, or the frontier target
  double heading_y_m_ = 0.0;
  std::unique_ptr<MapTile> tile_ = std::make_unique<MapTile>();
  std::uint64_t map_sequence_ = 0;      // the last update applied
  std::uint64_t map_checksum_ = 0;      // of the map after the last complete hand-over
  std::uint64_t running_checksum_ = 0;  // of the map as it is (link::map_checksum)
  bool map_in_sync_ = false;
  std::uint64_t vehicle_incarnation_ = 0;
};

extern template class PlanningSide<DdVelocity>;
extern template class PlanningSide<DdAcceleration>;
extern template class PlanningSide<Car>;

}  // namespace grip::rt::dds
