#include "fields.hpp"

#include <algorithm>
#include <array>

namespace grip::params::detail {

namespace {

// The value reached from GripParams through a chain of members (planner, tuning, score_base_a).
template <auto... Members>
ValueRef member(GripParams& p) {
  return &(p.*....*Members);
}
// The same from the vehicle's parameters, for the model V that GripParams::vehicle holds.
template <typename V, auto... Members>
ValueRef vehicle_member(GripParams& p) {
  return &(std::get<V>(p.vehicle).*....*Members);
}

// The tables of several models share rows: one table from several.
template <std::size_t... N>
constexpr std::array<Field, (N + ...)> join(const std::array<Field, N>&... parts) {
  std::array<Field, (N + ...)> out{};
  std::size_t i = 0;
  const auto append = [&](const auto& part) {
    for (const Field& f : part) out[i++] = f;
  };
  (append(parts), ...);
  return out;
}

// Both differential drives.
template <typename V>
constexpr auto kWheels = std::to_array<Field>({
    {"max_wheel_speed_m_s", vehicle_member<V, &V::max_wheel_speed_m_s>, "|wheel rim speed|"},
    {"max_turn_rate_rad_s", vehicle_member<V, &V::max_turn_rate_rad_s>, "|theta'|"},
    {"half_axle_m", vehicle_member<V, &V::half_axle_m>,
     "L: axle centre (the reference point) to a wheel"},
});

// The acceleration-controlled models: dd-accel and car.
template <typename V>
constexpr auto kBraking = std::to_array<Field>({
    {"braking_decel_m_s2", vehicle_member<V, &V::braking_decel_m_s2>,
     "the braking contingency's deceleration"},
});
template <typename V>
constexpr auto kVelocityTarget = std::to_array<Field>({
    {"velocity_target_share", vehicle_member<V, &V::velocity_target_share>,
     "share of sampled controls aimed at a random velocity, in [0, 1]"},
});

template <typename V>
constexpr auto kFootprint = std::to_array<Field>({
    {"footprint", nullptr, "the chassis: a rectangle around the reference point"},
    {"footprint.front_m", vehicle_member<V, &V::footprint, &Footprint::front_m>,
     "reference point to the front edge"},
    {"footprint.rear_m", vehicle_member<V, &V::footprint, &Footprint::rear_m>,
     "reference point to the rear edge"},
    {"footprint.half_width_m", vehicle_member<V, &V::footprint, &Footprint::half_width_m>,
     "centre line to either side"},
});

using Dv = DdVelocityParams;
constexpr auto kDdVelocity = join(kWheels<Dv>,
                                  std::to_array<Field>({
                                      {"top_speed_share", vehicle_member<Dv, &Dv::top_speed_share>,
                                       "share of sampled controls with the faster wheel at its "
                                       "limit, in [0, 1]"},
                                  }),
                                  kFootprint<Dv>);

using Da = DdAccelerationParams;
constexpr auto kDdAcceleration =
    join(kWheels<Da>,
         std::to_array<Field>({
             {"max_wheel_accel_m_s2", vehicle_member<Da, &Da::max_wheel_accel_m_s2>,
              "|wheel acceleration| of the sampled controls"},
         }),
         kBraking<Da>, kVelocityTarget<Da>, kFootprint<Da>);

using Ca = CarParams;
constexpr auto kCar = join(
    std::to_array<Field>({
        {"max_speed_m_s", vehicle_member<Ca, &Ca::max_speed_m_s>, "forward"},
        {"min_speed_m_s", vehicle_member<Ca, &Ca::min_speed_m_s>, "reverse, <= 0"},
        {"max_accel_m_s2", vehicle_member<Ca, &Ca::max_accel_m_s2>,
         "|acceleration| of the sampled controls"},
    }),
    kBraking<Ca>,
    std::to_array<Field>({
        {"max_steer_rad", vehicle_member<Ca, &Ca::max_steer_rad>, "|steering angle|, below pi/2"},
        {"max_steer_rate_rad_s", vehicle_member<Ca, &Ca::max_steer_rate_rad_s>,
         "|steering angle rate|"},
        {"wheelbase_m", vehicle_member<Ca, &Ca::wheelbase_m>,
         "L: rear axle (the reference point) to front axle"},
    }),
    kVelocityTarget<Ca>, kFootprint<Ca>);

using G = GripParams;
using Pl = PlannerParams;
using Tu = GripTuning;
constexpr auto kPlanner = std::to_array<Field>({
    {"cycle_s", member<&G::planner, &Pl::cycle_s>, "T, the replanning period"},
    {"budget_s", member<&G::planner, &Pl::budget_s>, "planning time per cycle, below cycle_s"},
    {"margin_s", member<&G::planner, &Pl::margin_s>,
     "growth stops this long before the deadline; auto: a fifth of the budget", -1.0},
    {"score_base_a", member<&G::planner, &Pl::tuning, &Tu::score_base_a>,
     "a > 1 of the score a^p rho: greed against the priority counters"},
    {"min_plan_duration_s", member<&G::planner, &Pl::tuning, &Tu::min_plan_duration_s>,
     "a random plan holds its control at least this long"},
    {"max_plan_duration_s", member<&G::planner, &Pl::tuning, &Tu::max_plan_duration_s>,
     "and at most this long"},
    {"rho_clearance_m", member<&G::planner, &Pl::tuning, &Tu::rho_clearance_m>,
     "rho keeps this clear of walls and unknown space, where frontiers are approached from"},
    {"rho_cell_m", member<&G::planner, &Pl::tuning, &Tu::rho_cell_m>,
     "rho's wavefront on blocks at most this large (and rho_clearance_m / 2); 0: map cells"},
    {"max_edges", member<&G::planner, &Pl::max_edges>,
     "the edge pool; auto: 400 per ms of budget (lockstep: 4 cycles' growth)", 0.0},
    {"lockstep_edges", member<&G::planner, &Pl::lockstep_edges>,
     "edges per cycle when the vehicle waits for each plan (a simulator)"},
    {"max_map_cells", member<&G::planner, &Pl::max_map_cells>,
     "the largest map accepted from the link"},
    {"safety", member<&G::planner, &Pl::safety>,
     "false: the paper's ablation without the contingency check"},
});

constexpr auto kSensor = std::to_array<Field>({
    {"range_m", member<&G::sensor, &SensorParams::range_m>,
     "auto: a tenth of the map's larger side", 0.0},
    {"rays", member<&G::sensor, &SensorParams::rays>,
     "auto: enough that no cell in range slips between two rays", 0.0},
});

using Ex = ExplorationParams;
using Fr = FrontierConfig;
using Pw = PathWeightSettings;
constexpr auto kExploration = std::to_array<Field>({
    {"sensing_radius_m", member<&G::exploration, &Ex::path_weight, &Pw::sensing_radius_m>,
     "d_max of the path weight; auto: sensor.range_m", 0.0},
    {"path_weight", nullptr, "w = d exp(lambda l) of the trajectory the plan follows"},
    {"path_weight.length_weight_per_m",
     member<&G::exploration, &Ex::path_weight, &Pw::length_weight_per_m>,
     "lambda: l longer by 1 / lambda weighs e times as much"},
    {"path_weight.reference_speed_m_s",
     member<&G::exploration, &Ex::path_weight, &Pw::reference_speed_m_s>,
     "l is the duration at this speed; 0: the length; auto: 2/3 of top speed for dd-accel, else 0",
     kPathWeightOfVehicle},
    {"path_weight.course_change_m", member<&G::exploration, &Ex::path_weight, &Pw::course_change_m>,
     "leaving the last plan's course weighs as this much longer; auto: 2 for dd-accel, else 0",
     kPathWeightOfVehicle},
    {"frontier", nullptr, "grouping and scoring of the frontier cells"},
    {"frontier.approach_range_m", member<&G::exploration, &Ex::frontier, &Fr::approach_range_m>,
     "how close the reference point must come to a frontier cell"},
    {"frontier.size_weight", member<&G::exploration, &Ex::frontier, &Fr::size_weight>,
     "score = rho + size_weight * min(group length, size_cap_m)"},
    {"frontier.size_cap_m", member<&G::exploration, &Ex::frontier, &Fr::size_cap_m>,
     "longer frontiers weigh the same"},
    {"frontier.min_group_cells", member<&G::exploration, &Ex::frontier, &Fr::min_group_cells>,
     "smaller groups are ignored"},
    {"frontier.give_up_radius_m", member<&G::exploration, &Ex::frontier, &Fr::give_up_radius_m>,
     "a group given up sets aside the frontier cells this close to it"},
    {"give_up_s", member<&G::exploration, &Ex::give_up_s>,
     "a target not approached for this long is given up"},
    {"give_up_reached_s", member<&G::exploration, &Ex::give_up_reached_s>,
     "a target reached and still not sensed this long is given up"},
    {"rho_margin_m", member<&G::exploration, &Ex::rho_margin_m>,
     "rho toward the target reaches this far past the vehicle's own"},
    {"target_refresh_cycles", member<&G::exploration, &Ex::target_refresh_cycles>,
     "the target is chosen again every this many cycles"},
    {"stuck_after_s", member<&G::exploration, &Ex::stuck_after_s>,
     "the simulator ends a run without coverage or progress for this long"},
});

constexpr auto kLink = std::to_array<Field>({
    {"domain", member<&G::link, &LinkParams::domain>, "DDS domain id, 0..232"},
    {"dds_config", member<&G::link, &LinkParams::dds_config>,
     "a Cyclone XML file; empty: loopback only"},
    {"topic_prefix", member<&G::link, &LinkParams::topic_prefix>,
     "before every topic name, so that vehicles can share a domain; empty: none"},
    {"liveliness_lease_s", member<&G::link, &LinkParams::liveliness_lease_s>,
     "a side that gives no sign of life for this long counts as lost"},
    {"security_dir", member<&G::link, &LinkParams::security_dir>,
     "DDS Security keys (grip keys init); empty: unauthenticated, unencrypted"},
});

constexpr auto kRuntime = std::to_array<Field>({
    {"policy", member<&G::runtime, &RuntimeParams::policy>,
     "auto (deadline, else fifo, else other) | deadline | fifo | other"},
    {"fifo_priority", member<&G::runtime, &RuntimeParams::fifo_priority>,
     "SCHED_FIFO priority, 1..99"},
    {"cpu", member<&G::runtime, &RuntimeParams::cpu>,
     "pinned to this CPU under fifo or other; auto: any", -1.0},
    {"lock_memory", member<&G::runtime, &RuntimeParams::lock_memory>,
     "lock the process's memory (mlockall) at start-up"},
});

constexpr auto kOtherSections = std::to_array<Section>({
    {"planner", "GRIP's replanning cycle; times in vehicle time", kPlanner},
    {"sensor", "the simulated range sensor", kSensor},
    {"exploration", "frontier exploration, when no goal is given", kExploration},
    {"link", "the DDS link between the planner and the vehicle", kLink},
    {"runtime", "the planning thread", kRuntime},
});

const void* address(const ValueRef& ref) {
  return std::visit([](auto* p) -> const void* { return p; }, ref);
}

std::string find_key(std::string_view section, std::span<const Field> fields, GripParams& params,
                     const void* wanted) {
  for (const Field& f : fields) {
    if (f.value != nullptr && address(f.value(params)) == wanted) {
      return std::string(section) + "." + std::string(f.key);
    }
  }
  return {};
}

}  // namespace

std::span<const Field> vehicle_fields(VehicleKind kind) noexcept {
  switch (kind) {
    case VehicleKind::kDdVelocity:
      return kDdVelocity;
    case VehicleKind::kDdAcceleration:
      return kDdAcceleration;
    case VehicleKind::kCar:
      break;
  }
  return kCar;
}

std::span<const Section> other_sections() noexcept { return kOtherSections; }

std::string key_of(const GripParams& params, const void* address) {
  // The accessors only take addresses: nothing is written through the cast.
  auto& p = const_cast<GripParams&>(params);
  std::string key = find_key("vehicle", vehicle_fields(vehicle_kind(p.vehicle)), p, address);
  for (const Section& s : kOtherSections) {
    if (key.empty()) key = find_key(s.key, s.fields, p, address);
  }
  return key;
}

}  // namespace grip::params::detail
