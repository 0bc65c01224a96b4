#include "params_options.hpp"

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <string>

#include "dds_config.hpp"

namespace grip::tools {

void add_vehicle_options(CLI::App& command, ParamsOptions& o) {
  command.add_option("--params", o.file,
                     "The vehicle's parameter file (YAML: vehicle, planner, sensor, exploration, "
                     "link, runtime; `grip params` prints one)");
  command.add_option(
      "--robot", o.robot,
      "A built-in vehicle instead: dd-vel, dd-accel or car (default: " + o.default_robot + ")");
}

void add_domain_option(CLI::App& command, ParamsOptions& o) {
  command.add_option("--domain", o.domain, "DDS domain id (default: the parameters' link.domain)")
      ->check(CLI::Range(0U, kMaxDomainId));
  add_topic_prefix_option(command, o.topic_prefix, "the parameters' link.topic_prefix");
}

void add_security_option(CLI::App& command, ParamsOptions& o) {
  add_security_option(command, o.security_dir,
                      "the parameters' link.security_dir; none: unauthenticated");
}

void add_lockstep_options(CLI::App& command, ParamsOptions& o) {
  command
      .add_option("--lockstep-edges", o.lockstep_edges,
                  "Edges the planner grows per cycle when the vehicle runs in lockstep "
                  "(planner.lockstep_edges)")
      ->check(CLI::Range(1U, 200'000U));
  command.add_flag("--no-safety", o.no_safety,
                   "The paper's ablation: plans are not checked for a safe braking maneuver");
}

void add_sensor_option(CLI::App& command, ParamsOptions& o) {
  command.add_option("--sensor-range", o.sensor_range_m,
                     "The range sensor's reach [m] (sensor.range_m; default: the parameters', "
                     "whose auto is a tenth of the map's larger side)");
}

void add_startup_timeout_option(CLI::App& command, double& seconds) {
  command
      .add_option("--startup-timeout", seconds,
                  "Give up if the map, the vehicle's state and description (and a goal, where "
                  "one is needed) are not there after this many seconds (0: wait); a map of "
                  "millions of cells takes seconds to sync")
      ->capture_default_str();
}

Result<std::chrono::nanoseconds> startup_timeout(double seconds) {
  constexpr double kDay = 86'400.0;
  if (!(seconds >= 0.0 && seconds <= kDay)) {  // NaN too
    return invalid_argument("--startup-timeout must be in [0, 86400] s (got " +
                            std::to_string(seconds) + ")");
  }
  return std::chrono::nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
}

void add_cycle_options(CLI::App& command, ParamsOptions& o) {
  command.add_option("--period-ms", o.period_ms, "Cycle T in vehicle time [ms] (planner.cycle_s)");
  command.add_option("--budget-ms", o.budget_ms,
                     "Planning time per cycle in vehicle time [ms] (planner.budget_s)");
  command.add_option("--margin-ms", o.margin_ms,
                     "Growth stops this long before the deadline [ms]; < 0: a fifth of the "
                     "budget (planner.margin_s)");
  command.add_option("--max-edges", o.max_edges,
                     "Edge pool; 0: 400 per ms of budget (planner.max_edges)");
  command.add_option("--policy", o.policy, "auto, deadline, fifo or other (runtime.policy)");
  command.add_option("--lease-ms", o.lease_ms,
                     "Liveliness lease of every endpoint [ms] (link.liveliness_lease_s)");
}

namespace {

Result<params::GripParams> base_params(const ParamsOptions& o) {
  if (o.file.empty()) {
    auto kind = vehicle_kind_from_name(o.robot.value_or(o.default_robot));
    if (!kind) return kind.error();
    return params::default_params(*kind);
  }
  auto loaded = params::load_params(o.file);
  if (!loaded) return loaded.error();
  // A file the parameters name is found beside them, as with any configuration file.
  for (std::string* path : {&loaded->link.dds_config, &loaded->link.security_dir}) {
    if (!path->empty() && path->front() != '/') {
      *path = (std::filesystem::path(o.file).parent_path() / *path).string();
    }
  }
  if (o.robot) {
    const std::string_view model = vehicle_name(vehicle_kind(loaded->vehicle));
    if (*o.robot != model) {
      return invalid_argument("--robot " + *o.robot + " contradicts " + o.file +
                              ", whose vehicle.model is " + std::string(model) +
                              ": give one of them");
    }
  }
  return loaded;
}

// Where a refused value came from, for a message that starts with its key: the option that
// overrode it, else the file.
std::string where_set(const ParamsOptions& o, const std::string& message) {
  struct Override {
    const char* key;
    bool given;
    const char* option;
  };
  const Override overrides[] = {
      {"link.domain", o.domain.has_value(), "--domain"},
      {"planner.cycle_s", o.period_ms.has_value(), "--period-ms"},
      {"planner.budget_s", o.budget_ms.has_value(), "--budget-ms"},
      {"planner.margin_s", o.margin_ms.has_value(), "--margin-ms"},
      {"planner.max_edges", o.max_edges.has_value(), "--max-edges"},
      {"planner.lockstep_edges", o.lockstep_edges.has_value(), "--lockstep-edges"},
      {"link.liveliness_lease_s", o.lease_ms.has_value(), "--lease-ms"},
      {"link.topic_prefix", o.topic_prefix.has_value(), "--topic-prefix"},
      {"sensor.range_m", o.sensor_range_m.has_value(), "--sensor-range"},
  };
  for (const Override& override : overrides) {
    if (override.given && message.starts_with(override.key)) {
      return std::string(" (set by ") + override.option + ")";
    }
  }
  return o.file.empty() ? "" : " (" + o.file + ")";
}

}  // namespace

Result<params::GripParams> effective_params(const ParamsOptions& o) {
  auto p = base_params(o);
  if (!p) return p.error();
  if (o.domain) p->link.domain = *o.domain;
  if (o.topic_prefix) p->link.topic_prefix = *o.topic_prefix;
  if (o.security_dir) p->link.security_dir = *o.security_dir;
  if (o.period_ms) p->planner.cycle_s = *o.period_ms / 1e3;
  if (o.budget_ms) p->planner.budget_s = *o.budget_ms / 1e3;
  if (o.margin_ms) p->planner.margin_s = *o.margin_ms < 0.0 ? -1.0 : *o.margin_ms / 1e3;
  if (o.max_edges) p->planner.max_edges = *o.max_edges;
  if (o.lockstep_edges) p->planner.lockstep_edges = *o.lockstep_edges;
  if (o.no_safety) p->planner.safety = false;
  if (o.lease_ms) p->link.liveliness_lease_s = *o.lease_ms / 1e3;
  if (o.sensor_range_m) p->sensor.range_m = *o.sensor_range_m;
  if (o.policy) {
    auto policy = platform::parse_policy_request(*o.policy);
    if (!policy) return policy.error();
    p->runtime.policy = *policy;
  }
  if (Status s = params::validate(*p); !s) {
    return invalid_argument(s.error().message + where_set(o, s.error().message));
  }
  return p;
}

namespace {
std::chrono::nanoseconds ns_of(double seconds) {
  return std::chrono::nanoseconds(static_cast<std::int64_t>(seconds * 1e9));
}
}  // namespace

rt::dds::PlannerParticipantConfig planner_participant_config(const params::GripParams& p) {
  rt::dds::PlannerParticipantConfig c;
  c.domain = p.link.domain;
  c.topic_prefix = p.link.topic_prefix;
  c.vehicle = p.vehicle;
  c.cycle_s = p.planner.cycle_s;
  c.budget_s = p.planner.budget_s;
  c.margin_s = p.planner.margin_s;
  c.max_edges = p.planner.max_edges;
  c.lockstep_edges = p.planner.lockstep_edges;
  c.tuning = p.planner.tuning;
  c.max_map_cells = p.planner.max_map_cells;
  c.no_safety = !p.planner.safety;
  // The path weight's d_max is what the sensor sees, unless the parameters say otherwise.
  c.path_weight = p.exploration.path_weight;
  if (c.path_weight.sensing_radius_m == 0.0) c.path_weight.sensing_radius_m = p.sensor.range_m;
  c.frontier = p.exploration.frontier;
  c.frontier_give_up_s = p.exploration.give_up_s;
  c.frontier_give_up_reached_s = p.exploration.give_up_reached_s;
  c.frontier_rho_margin_m = p.exploration.rho_margin_m;
  c.target_refresh_cycles = p.exploration.target_refresh_cycles;
  c.liveliness_lease = ns_of(p.link.liveliness_lease_s);
  c.policy = p.runtime.policy;
  c.fifo_priority = p.runtime.fifo_priority;
  c.cpu = p.runtime.cpu;
  c.lock_memory = p.runtime.lock_memory;
  return c;
}

sim::SimRunConfig sim_run_config(const params::GripParams& p) {
  sim::SimRunConfig c;
  c.domain = p.link.domain;
  c.topic_prefix = p.link.topic_prefix;
  c.vehicle = p.vehicle;
  c.cycle_s = p.planner.cycle_s;
  c.sensor_radius_m = p.sensor.range_m;
  c.sensor_rays = p.sensor.rays;
  c.stuck_after_s = p.exploration.stuck_after_s;
  c.liveliness_lease = ns_of(p.link.liveliness_lease_s);
  return c;
}

}  // namespace grip::tools
