#pragma once
// The simulator as a DDS participant (`grip sim`, and the simulator half of `grip explore`): it
// stands exactly where a vehicle controller would. It holds the ground truth, executes the plans
// it receives with the vehicle model at a fixed rate against simulated time (PlanExecutor),
// senses with the range sensor, and publishes the vehicle's state and the sensed map's updates
// (answering map requests with snapshots). When the planner goes silent past its lease it drops
// its plans and brakes. Collisions are counted and kept with time and place, never hidden.
//
// Real-time mode: simulated time runs time_scale times faster than the wall clock; ticks are
// released on an absolute wall-clock timeline. Lockstep mode: the states say so, and each one
// waits for the plan made for it before the vehicle runs the next T (the planner then grows a
// fixed number of edges per cycle), so a seed reproduces a run exactly, at the speed the
// machine allows. It ends when the planner reports that no reachable frontier remains (the
// verdict: exploration_verdict.hpp), at max_sim_time_s (timeout), when for stuck_after_s of
// simulated time coverage has not grown and the vehicle has got no nearer to unsensed ground
// (stuck), or when stopped.
//
// The verdict is the ground truth's, not the planner's word: `complete` only at a coverage of
// at least kCompleteCoverage; a vehicle that drove less than kNeverMovedM is `never-moved`
// (unless complete anyway).

#include <array>
#include <atomic>
#include <chrono>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "grip/common/result.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/sim/exploration_verdict.hpp"
#include "grip/sim/plan_executor.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "grip/world/occupancy_grid.hpp"
#include "plan.h"
#include "planner_status.h"

namespace grip::sim {

// A vehicle that drove less than this [m] never moved.
inline constexpr double kNeverMovedM = 0.01;

struct SimRunConfig {
  platform::dds::DomainId domain = 0;
  std::string dds_config;  // empty: the built-in loopback-only configuration
  std::optional<platform::dds::SecurityFiles> security;  // DDS Security; none: unauthenticated
  std::string topic_prefix;  // empty: the topics' own names (link/topics.hpp)
  // The vehicle simulated: its limits bound the plans it executes, its footprint the collisions,
  // and it describes itself to the planner with them (link/vehicle_description.hpp).
  VehicleParams vehicle = CarParams{};
  std::string world;  // the scene name or map file, for the report
  double start_x_m = 0.0;
  double start_y_m = 0.0;
  double start_theta_rad = 0.0;
  double time_scale = 1.0;  // simulated seconds per wall-clock second (not in lockstep)
  bool lockstep = false;
  double cycle_s = 0.05;          // the planner's T, for the QoS deadlines
  double sensor_radius_m = 0.0;   // 0: a tenth of the map's larger side
  std::uint32_t sensor_rays = 0;  // 0: enough that no cell in range slips between rays
  double max_sim_time_s = 600.0;
  // No coverage gained and no metre nearer to unsensed ground (through the free space, by the
  // ground truth) for this long: stuck. A vehicle crossing a maze to its last frontier keeps
  // getting nearer; a planner that makes no progress gives its target up sooner (60 s).
  double stuck_after_s = 300.0;
  std::chrono::nanoseconds liveliness_lease{std::chrono::milliseconds(500)};
  // How long the vehicle waits for a plan before the run ends as an error: the first (the
  // planner's start-up: a map in sync, a secured handshake; 0: for ever), and in lockstep each
  // one after it (a planner gone).
  std::chrono::nanoseconds first_plan_wait{std::chrono::seconds(30)};
  std::chrono::nanoseconds planner_wait{std::chrono::seconds(30)};
  // Fault injection: each plan received is lost with this probability before the controller
  // sees it (a stand-in for a plan that came too late), drawn from a stream seeded by
  // drop_seed, so that a lockstep run still reproduces. The planner must notice from the
  // vehicle's states that it does not follow the plans it was sent.
  double drop_plans = 0.0;
  std::uint64_t drop_seed = 1;
  // Called once the run has ended, before the simulator leaves DDS: a planner in the same
  // process can be stopped first, rather than report the vehicle lost.
  std::function<void()> on_finished;
};

struct SimCollision {
  double time_s;
  double x_m;
  double y_m;
  double theta_rad;
};

struct SimProgress {
  double sim_time_s = 0.0;
  double coverage = 0.0;
  double speed_m_s = 0.0;
  std::uint64_t planner_cycle = 0;
  std::uint64_t planner_misses = 0;
  std::uint64_t collisions = 0;
};

struct SimRunReport {
  std::string result;     // complete, done-early, never-moved, timeout, stuck, error
  std::string reason;     // for error (and a word on the others)
  double coverage = 0.0;  // sensed fraction of the free space the vehicle can reach from the start
  std::uint64_t collisions = 0;
  std::vector<SimCollision> collision_events;
  std::uint64_t cycles = 0;           // the planner's, from its status
  std::uint64_t deadline_misses = 0;  // the planner's, from its status
  double sim_time_s = 0.0;
  double distance_m = 0.0;
  // Of distance_m, the fraction driven again over ground driven before (retraced_distance(),
  // squares of a quarter of the sensor radius, entered again at least a sensor radius later).
  double retraced_fraction = 0.0;
  double mean_speed_fraction = 0.0;
  // Since the first plan, as mean_speed_fraction: the mean of the speed braking within the
  // sensed region allows on the route driven (sim/braking_bound.hpp) over the top speed (1 for
  // a vehicle that stops at once), and the share of ticks the vehicle braked or stood for want
  // of a plan (the last plan ran out or the planner fell silent). turning_bound_fraction: the
  // same bound within what the route's turns allow (sim/turning_bound.hpp).
  double braking_bound_fraction = 0.0;
  double turning_bound_fraction = 0.0;
  double without_plan_fraction = 0.0;
  // Since the first plan, the share of ticks the vehicle backed up (sim/reversing.hpp).
  double reversing_fraction = 0.0;
  std::uint64_t plans_received = 0;
  std::uint64_t plans_rejected = 0;
  std::uint64_t plans_dropped = 0;  // lost on purpose (SimRunConfig::drop_plans)
  std::uint64_t contingency_stops = 0;
  std::uint64_t empty_plans = 0;       // plans without steps: the planner had nothing new
  std::uint64_t start_mismatches = 0;  // plans refused at their start: not where the vehicle was
  double max_start_error_m = 0.0;      // the largest of those position differences
  std::uint64_t planner_losses = 0;
  // One plan source (link/vehicle_link.hpp): valid plans of a planner not followed, rejected;
  // times a standby planner was taken over after the one followed went silent.
  std::uint64_t plans_from_other_planner = 0;
  std::uint64_t planner_failovers = 0;
  double wall_time_s = 0.0;
  std::vector<std::array<double, 2>> trajectory;     // (x, y) per tick
  std::vector<std::array<double, 2>> speed_profile;  // (t, |v|) per tick
  // (t, coverage) whenever coverage grew (looked at every 20 ticks), from the start's.
  std::vector<std::array<double, 2>> coverage_profile;
  std::vector<double> braking_bound_profile;  // [m/s] per tick; empty: stops at once
  std::vector<double> turning_bound_profile;  // [m/s] per tick; empty: stops at once
  double max_speed_m_s = 0.0;
  std::optional<OccupancyGrid> known;  // what was sensed
  std::optional<grip_msg_PlannerStatus> last_status;
};

// A plan from the wire as a controller takes it: without steps, nothing new from its start
// time; else its steps from its start time, from the state it predicts there, tagged with its
// cycle (the vehicle's state reports it while it is executed). `steps` is scratch memory.
template <VehicleModel V>
PlanVerdict submit_wire_plan(PlanExecutor<V>& executor, const grip_msg_Plan& plan,
                             std::vector<PlanStep>& steps) noexcept {
  const auto start_ns = static_cast<std::int64_t>(plan.start_time_ns);
  if (plan.steps._length == 0) return executor.submit_empty(start_ns);
  steps.clear();
  for (std::uint32_t i = 0; i < plan.steps._length; ++i) {
    const grip_msg_PlanStep& s = plan.steps._buffer[i];
    steps.push_back(PlanStep{{s.control[0], s.control[1]}, s.duration_s});
  }
  typename V::State predicted;
  for (int i = 0; i < V::kStateDim; ++i) predicted[i] = plan.start_state[i];
  return executor.submit(steps, start_ns, predicted, plan.cycle);
}

// Runs until the end conditions above or `stop`. The truth must have the start free.
Result<SimRunReport> run_simulation(const SimRunConfig& config, const OccupancyGrid& truth,
                                    const std::atomic<bool>& stop,
                                    const std::function<void(const SimProgress&)>& progress = {});

}  // namespace grip::sim
