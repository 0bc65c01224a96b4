#include "grip/rt/exploration_driver.hpp"

#include <utility>

namespace grip::rt {

namespace {
// Unless the configuration says otherwise, an acceleration-limited vehicle that turns in place
// weighs a trajectory by its duration at this share of its top speed
// (PathSelectionConfig::reference_speed_m_s): about the speed braking within its sensor's range
// allows, so a trajectory that keeps that speed weighs what its length would. It keeps its
// course too (course_change_m). A car drove faster with either but explored no sooner: it went
// further and over more of its own track.
constexpr double kReferenceSpeedShare = 2.0 / 3.0;
constexpr double kCourseChangeM = 2.0;
}  // namespace

template <VehicleModel V>
Result<ExplorationDriver<V>> ExplorationDriver<V>::create(const V& vehicle,
                                                          const OccupancyGrid& grid,
                                                          const ExplorationDriverConfig& config,
                                                          const PlannerConfig& planner) {
  ExplorationTargetConfig target_config = config.target;
  target_config.frontier.clearance_m = planner.rho_clearance_m;
  target_config.frontier.rho_cell_m = planner.rho_cell_m;
  if (vehicle.min_turning_radius_m() > 0.0) {
    KinematicReachConfig kinematics;
    kinematics.turning_radius_m = vehicle.min_turning_radius_m();
    kinematics.footprint = vehicle.footprint();
    target_config.kinematics = kinematics;
  }
  auto target = ExplorationTarget::create(grid, target_config);
  if (!target) return target.error();
  const PathWeightSettings& weight = config.path_weight;
  PathSelectionConfig selection;
  selection.length_weight_per_m = weight.length_weight_per_m;
  selection.reference_speed_m_s = weight.reference_speed_m_s;
  selection.course_change_m = weight.course_change_m;
  bool turns_in_place_at_bounded_acceleration = false;
  if constexpr (LimitsAcceleration<V>) {
    turns_in_place_at_bounded_acceleration = vehicle.min_turning_radius_m() == 0.0;
  }
  if (selection.reference_speed_m_s == kPathWeightOfVehicle) {
    selection.reference_speed_m_s = turns_in_place_at_bounded_acceleration
                                        ? kReferenceSpeedShare * vehicle.max_speed_m_s()
                                        : 0.0;
  }
  if (selection.course_change_m == kPathWeightOfVehicle) {
    selection.course_change_m = turns_in_place_at_bounded_acceleration ? kCourseChangeM : 0.0;
  }
  selection.sensing_radius_m =
      weight.sensing_radius_m > 0.0 ? weight.sensing_radius_m : grid.width_m() / 10.0;
  auto selector = PathSelector::create(grid.width(), grid.height(), grid.resolution(),
                                       planner.max_edges, selection);
  if (!selector) return selector.error();
  auto sight = selector->create_sight();
  if (!sight) return sight.error();
  auto chosen_sight = selector->create_sight();
  if (!chosen_sight) return chosen_sight.error();
  return ExplorationDriver(config, std::move(target).value(), std::move(chosen_sight).value(),
                           std::move(selector).value(), std::move(sight).value());
}

template <VehicleModel V>
ExplorationDriver<V>::ExplorationDriver(ExplorationDriver&& other) noexcept
    : config_(other.config_),
      stage_(other.stage_.load(std::memory_order_acquire)),
      target_(std::move(other.target_)),
      chosen_sight_(std::move(other.chosen_sight_)),
      robot_x_m_(other.robot_x_m_),
      robot_y_m_(other.robot_y_m_),
      robot_theta_(other.robot_theta_),
      robot_ns_(other.robot_ns_),
      selector_(std::move(other.selector_)),
      sight_(std::move(other.sight_)),
      requested_(other.requested_),
      cycles_since_request_(other.cycles_since_request_),
      written_since_request_(other.written_since_request_),
      explored_(other.explored_),
      groups_(other.groups_),
      groups_given_up_(other.groups_given_up_),
      groups_unreachable_(other.groups_unreachable_),
      has_target_(other.has_target_),
      target_x_m_(other.target_x_m_),
      target_y_m_(other.target_y_m_),
      choice_(other.choice_) {}

template <VehicleModel V>
bool ExplorationDriver<V>::update(ReplanningCycle<V>& cycle, const OccupancyGrid& grid,
                                  std::uint64_t plan_start_ns, const MapChanges& changes,
                                  bool lockstep) noexcept {
  written_since_request_.add(changes.written);
  choice_ = PathChoice{};
  if (requested_) ++cycles_since_request_;
  std::uint8_t stage = stage_.load(std::memory_order_acquire);
  if (lockstep && stage != kIdle) {
    // The last cycle before the next request takes the choice over, whenever it was made.
    if (cycles_since_request_ + 1 < config_.refresh_cycles) return false;
    static_cast<void>(serve_request());  // not begun by the target thread: chosen here
    while ((stage = stage_.load(std::memory_order_acquire)) == kChoosing) {
      stage_.wait(kChoosing, std::memory_order_acquire);
    }
  }
  if (stage == kChosen) {
    take_over(cycle);
    stage = kIdle;
    stage_.store(kIdle, std::memory_order_release);
  }
  if (stage == kIdle && (!requested_ || cycles_since_request_ >= config_.refresh_cycles)) {
    request(cycle, grid, plan_start_ns);
    stage_.store(kRequested, std::memory_order_release);
    return true;
  }
  return false;
}

template <VehicleModel V>
void ExplorationDriver<V>::choose_now(ReplanningCycle<V>& cycle, const OccupancyGrid& grid,
                                      std::uint64_t plan_start_ns) noexcept {
  request(cycle, grid, plan_start_ns);
  choose();
  take_over(cycle);
}

template <VehicleModel V>
bool ExplorationDriver<V>::serve_request() noexcept {
  std::uint8_t requested = kRequested;
  if (!stage_.compare_exchange_strong(requested, kChoosing, std::memory_order_acquire)) {
    return false;
  }
  choose();
  stage_.store(kChosen, std::memory_order_release);
  stage_.notify_one();  // a lockstep planning thread may wait for it
  return true;
}

// The thread that owns target_ (kChoosing, or kIdle in choose_now): the target, and what sees it
// on the map it was chosen on.
template <VehicleModel V>
void ExplorationDriver<V>::choose() noexcept {
  target_.choose(robot_x_m_, robot_y_m_, robot_theta_, robot_ns_);
  if (target_.status() == ExplorationStatus::kTarget) {
    chosen_sight_.set_target(target_.map(), target_.target_cells());
  }
}

template <VehicleModel V>
TreeState ExplorationDriver<V>::choose_plan_end(const Planner<V>& planner,
                                                std::uint32_t cycle_steps,
                                                TreeState course) noexcept {
  if (explored_) return planner.root_state();
  choice_ = selector_.select(planner, sight_, cycle_steps, course);
  return choice_.state;
}

template <VehicleModel V>
ExplorationRecord ExplorationDriver<V>::record() const noexcept {
  ExplorationRecord r;
  r.exploring = true;
  r.has_target = has_target_;
  r.target_x_m = target_x_m_;
  r.target_y_m = target_y_m_;
  r.root_rho_m = choice_.root_rho_m;
  r.chosen = choice_.state.edge != kNoHandle;
  r.sees_target = choice_.sees_target;
  r.d_m = choice_.d_m;
  r.length_m = choice_.length_m;
  return r;
}

// The planning thread, with target_ its own (kIdle).
template <VehicleModel V>
void ExplorationDriver<V>::request(const ReplanningCycle<V>& cycle, const OccupancyGrid& grid,
                                   std::uint64_t plan_start_ns) noexcept {
  requested_ = true;
  cycles_since_request_ = 0;
  target_.copy_map(grid, std::exchange(written_since_request_, CellBox{}));
  const typename V::State& here = cycle.plan_start();
  robot_x_m_ = state_x(here);
  robot_y_m_ = state_y(here);
  robot_theta_ = state_theta(here);
  robot_ns_ = static_cast<std::int64_t>(plan_start_ns);
}

// The planning thread, with target_ its own (kChosen, or kIdle in choose_now).
template <VehicleModel V>
void ExplorationDriver<V>::take_over(ReplanningCycle<V>& cycle) noexcept {
  groups_ = target_.groups();
  groups_given_up_ = target_.given_up_groups();
  groups_unreachable_ = target_.unreachable_groups();
  const ExplorationStatus status = target_.status();
  if (status != ExplorationStatus::kTarget) {
    // No reachable frontier is left (or the robot is off the map): stop where it stands.
    explored_ = status == ExplorationStatus::kComplete;
    const typename V::State& here = cycle.plan_start();
    cycle.set_goal(Goal::disk(state_x(here), state_y(here), 0.5));
    return;
  }
  explored_ = false;
  has_target_ = true;
  target_x_m_ = target_.target_x_m();
  target_y_m_ = target_.target_y_m();
  cycle.set_goal(Goal::cells(target_.approach_cells()), &target_.rho());
  std::swap(sight_, chosen_sight_);
}

template class ExplorationDriver<DdVelocity>;
template class ExplorationDriver<DdAcceleration>;
template class ExplorationDriver<Car>;

}  // namespace grip::rt
