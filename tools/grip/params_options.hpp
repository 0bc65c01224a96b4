#pragma once
// What a command that plans or simulates is given to run with: a vehicle's parameter file
// (--params), or a built-in vehicle (--robot), and the command-line options that override one
// value of it. The effective set is what runs, and what the command's report records.

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>

#include "grip/common/result.hpp"
#include "grip/params/params.hpp"
#include "grip/rt/dds/planner_participant.hpp"
#include "grip/sim/sim_participant.hpp"

namespace grip::tools {

struct ParamsOptions {
  explicit ParamsOptions(std::string built_in) : default_robot(std::move(built_in)) {}

  std::string default_robot;         // the built-in vehicle without --params or --robot
  std::string file;                  // --params
  std::optional<std::string> robot;  // --robot
  // Overrides; unset: the parameters' value.
  std::optional<unsigned> domain;
  std::optional<std::string> topic_prefix;
  std::optional<std::string> security_dir;
  std::optional<double> period_ms;
  std::optional<double> budget_ms;
  std::optional<double> margin_ms;
  std::optional<std::uint32_t> max_edges;
  std::optional<std::uint32_t> lockstep_edges;
  std::optional<std::string> policy;
  std::optional<double> lease_ms;
  std::optional<double> sensor_range_m;
  bool no_safety = false;
};

// --params FILE and --robot R.
void add_vehicle_options(CLI::App& command, ParamsOptions& o);
// --domain and --topic-prefix: where the vehicle's topics are.
void add_domain_option(CLI::App& command, ParamsOptions& o);
// --security DIR: DDS Security (link.security_dir).
void add_security_option(CLI::App& command, ParamsOptions& o);
// --lockstep-edges and --no-safety.
void add_lockstep_options(CLI::App& command, ParamsOptions& o);
// --sensor-range: the range sensor's reach (sensor.range_m), which also sets the path weight's
// d_max unless the parameters give exploration.sensing_radius_m.
void add_sensor_option(CLI::App& command, ParamsOptions& o);
// --period-ms, --budget-ms, --margin-ms, --max-edges, --policy and --lease-ms.
void add_cycle_options(CLI::App& command, ParamsOptions& o);
// --startup-timeout [s]: how long a planner waits for the map in sync, the vehicle's state and
// description (and a goal, where it needs one) before it gives up; 0: for ever. The option's
// value as the planner's configuration takes it, or an error naming the option (not in
// [0, 1 day]).
void add_startup_timeout_option(CLI::App& command, double& seconds);
Result<std::chrono::nanoseconds> startup_timeout(double seconds);

// The file's parameters (or the built-in vehicle's) with the overrides applied, checked. Every
// error is the user's (exit 2): a bad file names file:line:column, a bad override its option.
Result<params::GripParams> effective_params(const ParamsOptions& o);

// The planner participant and the simulator as the parameters describe them; the caller adds
// what belongs to a run (seed, callbacks, the DDS configuration, the world).
rt::dds::PlannerParticipantConfig planner_participant_config(const params::GripParams& p);
sim::SimRunConfig sim_run_config(const params::GripParams& p);

}  // namespace grip::tools
