#pragma once
// One vehicle's parameter file: the vehicle, the planner, the sensor, exploration, the DDS link
// and the runtime, the same file for the planner and the vehicle side. Read at start-up only
// (yaml-cpp); the planning path sees the configurations made from it.
//
// Values are SI units with the unit in the key (max_speed_m_s). "auto" stands for a value
// derived at start-up (the edge pool from the budget, the sensor range from the map); in the
// structs below it is the zero (or negative) value the runtime already reads that way.

#include <cstdint>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"
#include "grip/exploration/exploration_target.hpp"
#include "grip/exploration/frontier.hpp"
#include "grip/exploration/path_selection_config.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/platform/scheduling.hpp"
#include "grip/vehicles/vehicle_params.hpp"

namespace grip::params {

struct PlannerParams {
  double cycle_s = 0.05;        // T, in vehicle time
  double budget_s = 0.025;      // planning time per cycle, in vehicle time
  double margin_s = -1.0;       // growth stops this long before the deadline; < 0: "auto"
  GripTuning tuning;            // a, the plan duration range
  std::uint32_t max_edges = 0;  // the edge pool; 0: "auto" (from the budget)
  std::uint32_t lockstep_edges = 1000;
  std::uint32_t max_map_cells = 1U << 22;
  bool safety = true;  // false: the paper's ablation without the contingency check

  bool operator==(const PlannerParams&) const = default;
};

struct SensorParams {
  double range_m = 0.0;    // 0: "auto", a tenth of the map's larger side
  std::uint32_t rays = 0;  // 0: "auto", enough that no cell in range slips between two rays

  bool operator==(const SensorParams&) const = default;
};

struct ExplorationParams {
  // The path weight w = d exp(lambda l) (exploration/path_selector.hpp): d_max as the key
  // sensing_radius_m (0: "auto", sensor.range_m), the rest under "path_weight": lambda, l's
  // reference speed (0: l is the length), the cost of leaving the last plan's course;
  // kPathWeightOfVehicle: "auto", the vehicle's (rt::ExplorationDriver).
  PathWeightSettings path_weight;
  // Grouping and scoring of frontier cells; clearance_m and rho_cell_m are the planner's
  // (planner.rho_clearance_m, planner.rho_cell_m) and not parameters here.
  FrontierConfig frontier;
  double give_up_s = 60.0;         // a frontier target not approached for this long is given up
  double give_up_reached_s = 3.0;  // a target reached and still a frontier this long is given up
  double rho_margin_m = ExplorationTargetConfig{}.rho_margin_m;
  std::uint32_t target_refresh_cycles = 5;
  double stuck_after_s = 300.0;  // the simulator: no coverage or progress for this long

  bool operator==(const ExplorationParams&) const = default;
};

// The largest DDS domain id: the RTPS port mapping (7400 + 250 x domain + ...) leaves UDP ports
// for domains 0 to 232 (the `grip` command's --domain options stop there too).
inline constexpr unsigned kMaxDomainId = 232;

struct LinkParams {
  unsigned domain = 0;     // 0..kMaxDomainId
  std::string dds_config;  // a Cyclone XML file; empty: the loopback-only built-in
  // Prepended to every topic name, so that two vehicles can share a domain; empty: none.
  std::string topic_prefix;
  double liveliness_lease_s = 0.5;
  // A DDS Security folder (platform/dds/security.hpp, made by `grip keys init`); relative to the
  // parameter file; empty: the link is neither authenticated nor encrypted.
  std::string security_dir;

  bool operator==(const LinkParams&) const = default;
};

struct RuntimeParams {
  platform::PolicyRequest policy = platform::PolicyRequest::kAuto;
  int fifo_priority = 80;  // SCHED_FIFO, 1..99
  int cpu = -1;            // the planning thread's CPU under fifo or other; -1: "any"
  bool lock_memory = true;

  bool operator==(const RuntimeParams&) const = default;
};

struct GripParams {
  VehicleParams vehicle = DdVelocityParams{};
  PlannerParams planner;
  SensorParams sensor;
  ExplorationParams exploration;
  LinkParams link;
  RuntimeParams runtime;

  // Field by field (doubles by value): what a file read back from to_yaml() compares equal to.
  bool operator==(const GripParams&) const = default;
};

// The built-in vehicle of `kind` (the paper's), with every other section at its default.
GripParams default_params(VehicleKind kind);

// A parameter file. Errors (kInvalidArgument), each naming "file:line:column", the key and what
// is allowed: malformed YAML, an unknown key, a duplicated key, a missing vehicle.model, a wrong
// type (a non-finite number too), a value out of range (validate()'s rules, at the value's place
// when the file gives it, else at its section's). Keys left out keep the defaults of
// vehicle.model. A path that cannot be opened, is not a regular file (a directory, /dev/zero, a
// FIFO: refused before a byte is read) or holds more than 1 MiB is refused naming the path.
Result<GripParams> load_params(const std::string& path);
// The same from text; `name` stands for the file in messages.
Result<GripParams> parse_params(std::string_view text, std::string_view name);

// Every parameter in a fixed order, commented, as YAML that parse_params reads back to the same
// values (numbers in their shortest exact text; "auto" for a derived value).
std::string to_yaml(const GripParams& params);

// Ok, or the first value out of range, by its key ("planner.budget_s must be in (0, cycle_s =
// 0.05) (got 0.06)"): the rules parse_params applies, for a set built in code. The frontier's
// approach range is checked against a cell of 0 m: FrontierMap::create checks it again with the
// map's resolution.
Status validate(const GripParams& params);

}  // namespace grip::params
