#include "grip/sim/sim_participant.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <iterator>
#include <limits>
#include <random>
#include <thread>

#include "grip/common/saturating_cast.hpp"
#include "grip/link/vehicle_link.hpp"
#include "grip/platform/clock.hpp"
#include "grip/sim/braking_bound.hpp"
#include "grip/sim/coverage.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/sim/range_sensor.hpp"
#include "grip/sim/retraced_distance.hpp"
#include "grip/sim/reversing.hpp"
#include "grip/sim/turning_bound.hpp"
#include "grip/vehicles/vehicle_params.hpp"

namespace grip::sim {

namespace {

// Simulated time on the wire starts here rather than at 0: a stamp of 0 reads as "never".
constexpr std::int64_t kEpochNs = 1'000'000'000;

// The limits on how fast the vehicle drives a route for the way it turns.
template <VehicleModel V>
TurningLimits turning_limits_of(const V& vehicle) {
  TurningLimits limits;
  if constexpr (V::kKind == VehicleKind::kCar) {
    limits.wheelbase_m = vehicle.params().wheelbase_m;
    limits.max_steer_rate_rad_s = vehicle.params().max_steer_rate_rad_s;
  } else if constexpr (V::kKind == VehicleKind::kDdAcceleration) {
    limits.max_turn_rate_rad_s = vehicle.max_turn_rate_rad_s();
    limits.half_track_m = vehicle.params().half_axle_m;
    limits.max_wheel_speed_m_s = vehicle.params().max_wheel_speed_m_s;
    limits.wheel_accel_m_s2 = vehicle.accel_bound_m_s2();
  }
  return limits;
}

// Per tick, for a vehicle that brakes at a bounded rate (none for one that stops at once): the
// braking bound, and the braking bound within what its turns allow.
struct SpeedBounds {
  std::vector<double> braking;
  std::vector<double> turning;
};

template <VehicleModel V>
Result<SpeedBounds> speed_bounds_of(const V& vehicle, std::span<const std::array<double, 2>> route,
                                    std::span<const double> headings, const OccupancyGrid& grid,
                                    const SensedTicks& sensed, double step_s) {
  SpeedBounds bounds;
  if constexpr (LimitsAcceleration<V>) {
    const SpeedLimits limits{vehicle.max_speed_m_s(), vehicle.max_reverse_speed_m_s(),
                             vehicle.accel_bound_m_s2(), vehicle.braking_decel_m_s2()};
    auto braking = braking_bound_m_s(route, headings, grid, sensed.ticks(), vehicle.footprint(),
                                     limits, step_s);
    if (!braking) return braking.error();
    auto caps = turning_caps_m_s(route, headings, turning_limits_of(vehicle));
    if (!caps) return caps.error();
    auto turning = braking_bound_m_s(route, headings, grid, sensed.ticks(), vehicle.footprint(),
                                     limits, step_s, *caps);
    if (!turning) return turning.error();
    bounds.braking = std::move(braking).value();
    bounds.turning = std::move(turning).value();
  }
  return bounds;
}

// The mean of `profile` over its last `ticks` ticks, over top speed; 1 without a profile.
double bound_fraction(const std::vector<double>& profile, std::uint64_t ticks, double top_m_s) {
  if (profile.empty() || ticks == 0) return 1.0;
  double sum = 0.0;
  for (auto it = profile.end() - static_cast<std::ptrdiff_t>(ticks); it != profile.end(); ++it) {
    sum += *it;
  }
  return sum / static_cast<double>(ticks) / top_m_s;
}

template <VehicleModel V>
Result<SimRunReport> run_with(const V& vehicle, const SimRunConfig& config,
                              const OccupancyGrid& truth, const std::atomic<bool>& stop,
                              const std::function<void(const SimProgress&)>& progress) {
  using State = typename V::State;
  if (!(config.time_scale > 0.0 && config.time_scale <= 1000.0)) {
    return invalid_argument("time scale must be in (0, 1000] (got " +
                            std::to_string(config.time_scale) + ")");
  }
  auto reachable =
      reachable_free_cells(truth, config.start_x_m, config.start_y_m, vehicle.footprint());
  if (!reachable) return reachable.error();
  auto known = OccupancyGrid::create(truth.width(), truth.height(), truth.resolution(),
                                     truth.origin_x(), truth.origin_y(), Cell::kUnknown);
  if (!known) return known.error();

  link::VehicleLinkConfig link_config;
  link_config.domain = config.domain;
  link_config.dds_config = config.dds_config;
  link_config.security = config.security;
  link_config.topic_prefix = config.topic_prefix;
  link_config.vehicle = config.vehicle;  // described to the planner, which refuses another
  link_config.timing.cycle = std::chrono::nanoseconds(std::llround(config.cycle_s * 1e9));
  link_config.timing.time_scale = config.time_scale;
  link_config.timing.liveliness_lease = config.liveliness_lease;
  auto link = link::VehicleLink::create(link_config, std::move(known).value());
  if (!link) return link.error();
  OccupancyGrid& sensed = (*link)->map();

  const double radius =
      config.sensor_radius_m > 0.0 ? config.sensor_radius_m : RangeSensor::default_radius_m(truth);
  auto sensor = RangeSensor::create(truth, radius, config.sensor_rays);
  if (!sensor) return sensor.error();
  const State start =
      vehicle.rest_state(config.start_x_m, config.start_y_m, config.start_theta_rad);
  ExecutorConfig executor_config;
  executor_config.refuse_start_mismatch = true;
  auto executor = PlanExecutor<V>::create(vehicle, truth, start, kEpochNs, executor_config);
  if (!executor) return executor.error();
  const double dt = static_cast<double>(executor->step_ns()) * 1e-9;

  SimRunReport report;
  report.result = "error";
  const auto t_sim = [&] { return static_cast<double>(executor->now_ns() - kEpochNs) * 1e-9; };
  std::vector<PlanStep> steps;
  steps.reserve(grip_msg_kMaxPlanSteps);
  grip_msg_VehicleState state_msg{};  // the last state published
  const auto publish_state = [&] {
    state_msg.stamp_ns = static_cast<std::uint64_t>(executor->now_ns());
    ++state_msg.sequence_number;
    state_msg.kind = link::to_wire(V::kKind);
    link::state_to_wire<V>(executor->state(), state_msg.state, state_msg.state_dim);
    state_msg.time_scale = config.lockstep ? 1.0 : config.time_scale;
    state_msg.lockstep = config.lockstep;
    // The plan executed in the tick that ended now (plans starting now have not started yet).
    state_msg.plan_cycle = executor->executing_tag();
    state_msg.map_sequence = (*link)->map_sender().last_sequence();
    static_cast<void>((*link)->publish_state(state_msg));
  };
  SensedTicks sensed_ticks(sensed);
  std::uint64_t tick = 0;
  const auto sense = [&] {
    const State& q = executor->state();
    const SenseResult seen = sensor->sense(state_x(q), state_y(q), sensed);
    sensed_ticks.mark(seen.changed_cells, static_cast<std::uint32_t>(tick));
    if (!seen.changed.empty()) {
      (*link)->publish_map_updates(seen.changed, static_cast<std::uint64_t>(executor->now_ns()));
    }
  };
  sense();
  publish_state();

  // A plan as the controller takes it: from its start time, from the state it predicts there.
  std::mt19937_64 drop_stream(config.drop_seed);
  std::bernoulli_distribution drop(config.drop_plans);
  const auto submit = [&](const grip_msg_Plan& plan) {
    if (config.drop_plans > 0.0 && drop(drop_stream)) {
      ++report.plans_dropped;
      return;
    }
    // How early it came (the planner leads its start times by what a late one missed by).
    state_msg.plan_arrival_cycle = plan.cycle;
    state_msg.plan_arrival_margin_ns = saturating_cast<std::int64_t>(
        static_cast<double>(plan.start_time_ns) - static_cast<double>(executor->now_ns()));
    if (submit_wire_plan(*executor, plan, steps) != PlanVerdict::kAccepted) {
      ++report.plans_rejected;
      return;
    }
    if (plan.steps._length == 0) ++report.empty_plans;
    ++report.plans_received;
  };
  double best_coverage = coverage_of(sensed, *reachable);
  report.coverage_profile.push_back({t_sim(), best_coverage});
  // Progress: coverage gained, or, while none is, the way to unsensed ground shortened by a
  // metre (checked once a simulated second after 10 s without coverage). A vehicle driving to
  // the last frontier of a maze senses nothing new for minutes and is not stuck; one circling
  // short of a frontier it cannot reach gets no nearer.
  auto to_unsensed = UnsensedDistance::create(truth, *reachable);
  if (!to_unsensed) return to_unsensed.error();
  constexpr double kNearerM = 1.0;
  constexpr double kLookAfterS = 10.0;
  double progress_at = 0.0;
  double nearest_unsensed_m = std::numeric_limits<double>::infinity();
  const auto ticks_per_second = static_cast<std::uint64_t>(std::max(1L, std::lround(1.0 / dt)));
  bool planner_seen = false;
  bool planner_alive = false;
  std::optional<grip_msg_PlannerStatus> status;
  const std::int64_t wall0 = platform::now_ns();
  std::uint64_t ticks_without_plan = 0;
  std::vector<double> headings;  // the chassis's, per tick as report.trajectory
  // One integration step of the vehicle: plans take effect, it moves, senses, is recorded.
  const auto advance = [&] {
    ++tick;
    executor->step();
    if (executor->stats().plans_started > 0 && executor->mode() != ExecutorMode::kExecuting) {
      ++ticks_without_plan;
    }
    sense();
    const State& q = executor->state();
    report.trajectory.push_back({state_x(q), state_y(q)});
    headings.push_back(state_theta(q));
    report.speed_profile.push_back({t_sim(), executor->speed_m_s()});
    if (tick % 20 == 0) {
      const double coverage = coverage_of(sensed, *reachable);
      if (coverage > best_coverage + 1e-9) {
        best_coverage = coverage;
        report.coverage_profile.push_back({t_sim(), coverage});
        progress_at = t_sim();
        nearest_unsensed_m = std::numeric_limits<double>::infinity();
      }
    }
    if (tick % ticks_per_second == 0 && t_sim() - progress_at >= kLookAfterS) {
      const double d = to_unsensed->from(sensed, state_x(q), state_y(q));
      if (d < nearest_unsensed_m - kNearerM) {
        // The first look sets the mark; only getting nearer than it counts.
        if (nearest_unsensed_m < std::numeric_limits<double>::infinity()) progress_at = t_sim();
        nearest_unsensed_m = d;
      }
    }
  };
  const auto watch_planner = [&] {
    const bool alive = (*link)->planner_alive();
    if (planner_alive && !alive) {
      executor->abandon_plans();  // the planner went silent past its lease
      ++report.planner_losses;
    }
    planner_alive = alive;
  };
  std::int64_t next_progress = wall0;
  const auto show_progress = [&] {
    if (progress && platform::now_ns() >= next_progress) {
      next_progress += 250'000'000;
      progress(SimProgress{t_sim(), best_coverage, executor->speed_m_s(),
                           status ? status->cycle : 0, status ? status->misses : 0,
                           executor->stats().collisions});
    }
  };
  // Whether the run is over: the planner says no reachable frontier remains, or sim time ran
  // out, or coverage stopped growing.
  const auto finished = [&] {
    if (status && status->exploration_complete) {
      ExplorationVerdict verdict = verdict_when_planner_done(
          sensed_cells(sensed, *reachable), reachable->size(), status->frontier_groups_given_up,
          status->frontier_groups_unreachable);
      report.result = std::move(verdict.result);
      report.reason = std::move(verdict.reason);
    } else if (t_sim() >= config.max_sim_time_s) {
      report.result = "timeout";
    } else if (t_sim() - progress_at >= config.stuck_after_s) {
      report.result = "stuck";
      char reason[96];
      std::snprintf(reason, sizeof reason,
                    "no coverage gained and no nearer to unsensed ground for %.0f s",
                    config.stuck_after_s);
      report.reason = reason;
    }
    return report.result != "error";
  };
  // The wait for the next plan, 0 for ever.
  const auto plan_wait_ns = [&] {
    return (planner_seen ? config.planner_wait : config.first_plan_wait).count();
  };
  const auto waited_too_long = [&](std::int64_t since_ns) {
    return plan_wait_ns() > 0 && platform::now_ns() - since_ns > plan_wait_ns();
  };
  const auto no_planner = [&] {
    char reason[64];
    std::snprintf(reason, sizeof reason, "no plan from a planner within %g s",
                  static_cast<double>(plan_wait_ns()) * 1e-9);
    report.reason = reason;
  };

  if (config.lockstep) {
    // Each state waits for the plan made for it (and the status that goes with it), then the
    // vehicle runs T: the planner's cycle, however long it took, costs no simulated time.
    const auto ticks_per_cycle =
        static_cast<std::uint64_t>(std::max(1L, std::lround(config.cycle_s / dt)));
    while (!stop.load(std::memory_order_acquire)) {
      const std::int64_t asked = platform::now_ns();
      std::int64_t repeated = asked;
      const grip_msg_Plan* plan = nullptr;
      while (plan == nullptr && !stop.load(std::memory_order_acquire)) {
        if (waited_too_long(asked)) break;
        const std::int64_t now = platform::now_ns();
        if (now - repeated > 250'000'000) {
          // A planner that joined late never saw it; one that answered it writes its plan
          // again (it may have been written before this reader matched).
          static_cast<void>((*link)->publish_state(state_msg));
          repeated = now;
        }
        (*link)->wait_for_plan_or_request(std::chrono::milliseconds(50));
        (*link)->answer_map_requests(state_msg.stamp_ns);
        plan = (*link)->take_plan();
        if (plan != nullptr && plan->state_sequence < state_msg.sequence_number) plan = nullptr;
      }
      if (plan == nullptr) {
        if (!stop.load()) no_planner();
        break;
      }
      planner_seen = true;
      submit(*plan);
      if (auto s = (*link)->wait_for_status(plan->cycle, std::chrono::seconds(1))) status = s;
      watch_planner();
      if (finished()) break;
      for (std::uint64_t i = 0; i < ticks_per_cycle; ++i) advance();
      publish_state();
      show_progress();
    }
  } else {
    // Real time: ticks released on an absolute wall-clock timeline, time_scale times faster.
    const auto wall_of_tick = [&](std::uint64_t n) {
      return wall0 +
             static_cast<std::int64_t>(static_cast<double>(n) * dt * 1e9 / config.time_scale);
    };
    while (!stop.load(std::memory_order_acquire)) {
      if (!planner_seen && waited_too_long(wall0)) {
        no_planner();
        break;
      }
      platform::sleep_until_ns(wall_of_tick(tick + 1));
      advance();
      // Every plan, oldest first: after a late wake-up two may be waiting, and the first
      // governs until the second starts. Taken before the state is published, so that the
      // state names the plan that governs from now on.
      if ((*link)->take_plans(submit) > 0) planner_seen = true;
      publish_state();
      (*link)->answer_map_requests(static_cast<std::uint64_t>(executor->now_ns()));
      if (auto s = (*link)->take_status()) status = s;
      watch_planner();
      show_progress();
      if (finished()) break;
    }
  }
  if (stop.load() && report.result == "error") report.reason = "stopped";
  if (config.on_finished) config.on_finished();

  const ExecutorStats& stats = executor->stats();
  report.coverage = coverage_of(sensed, *reachable);
  if (report.coverage > report.coverage_profile.back()[1]) {
    report.coverage_profile.push_back({t_sim(), report.coverage});
  }
  report.collisions = stats.collisions;
  for (const CollisionEvent& e : executor->collision_events()) {
    report.collision_events.push_back(
        SimCollision{static_cast<double>(e.time_ns - kEpochNs) * 1e-9, e.x_m, e.y_m, e.theta_rad});
  }
  report.cycles = status ? status->cycle : 0;
  report.deadline_misses = status ? status->misses : 0;
  report.sim_time_s = t_sim();
  report.distance_m = stats.distance_m;
  report.retraced_fraction = retraced_distance(report.trajectory, radius / 4.0, radius).fraction();
  report.mean_speed_fraction = executor->mean_speed_fraction();
  if (stats.speed_ticks > 0) {
    report.without_plan_fraction =
        static_cast<double>(ticks_without_plan) / static_cast<double>(stats.speed_ticks);
  }
  auto reversing = reversing_fraction(report.trajectory, headings, stats.speed_ticks);
  if (!reversing) return reversing.error();
  report.reversing_fraction = *reversing;
  auto bounds = speed_bounds_of(vehicle, report.trajectory, headings, sensed, sensed_ticks, dt);
  if (!bounds) return bounds.error();
  // Over the ticks since the first plan, as the mean speed.
  report.braking_bound_fraction =
      bound_fraction(bounds->braking, stats.speed_ticks, vehicle.max_speed_m_s());
  report.turning_bound_fraction =
      bound_fraction(bounds->turning, stats.speed_ticks, vehicle.max_speed_m_s());
  report.braking_bound_profile = std::move(bounds->braking);
  report.turning_bound_profile = std::move(bounds->turning);
  report.contingency_stops = stats.contingencies;
  report.start_mismatches = stats.plans_refused;
  report.max_start_error_m = stats.max_start_position_error_m;
  report.wall_time_s = static_cast<double>(platform::now_ns() - wall0) * 1e-9;
  report.plans_from_other_planner = (*link)->plans_from_other_planner();
  report.planner_failovers = (*link)->planner_failovers();
  if (report.result != "complete" && report.result != "error" && report.distance_m < kNeverMovedM) {
    report.reason = report.result + (report.reason.empty() ? "" : ": " + report.reason);
    report.result = "never-moved";
  }
  report.max_speed_m_s = vehicle.max_speed_m_s();
  report.known.emplace(sensed);
  report.last_status = status;
  return report;
}

}  // namespace

Result<SimRunReport> run_simulation(const SimRunConfig& config, const OccupancyGrid& truth,
                                    const std::atomic<bool>& stop,
                                    const std::function<void(const SimProgress&)>& progress) {
  if (Status s = validate(config.vehicle); !s) return s.error();
  return with_vehicle(config.vehicle, [&](const auto& vehicle) {
    return run_with(vehicle, config, truth, stop, progress);
  });
}

}  // namespace grip::sim
