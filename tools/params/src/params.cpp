// The ranges of the parameters, in one place: validate() reports them by key, and the file
// reader (read_params.cpp) adds the line and column of the key's value.

#include <cmath>
#include <string>

#include "fields.hpp"
#include "grip/link/topics.hpp"
#include "grip/planner/step_margin.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::params {

namespace detail {

namespace {

// Keeps the first rule broken; later checks are skipped once one failed.
class Rules {
 public:
  explicit Rules(const GripParams& params) : params_(params) {}

  template <typename T>
  void require(bool ok, const T& value, const std::string& rule) {
    if (ok || error_) return;
    const std::string key = key_of(params_, &value);
    GRIP_ASSERT(!key.empty());  // every rule is about a value of the file's tables
    error_ = RangeError{key, key + " must be " + rule + " (got " + text(value) + ")"};
  }
  // A check of core (a model's, the planner's, the frontier's), whose message starts with the
  // field's name after `core_prefix` ("car.", "frontier: "): the key is that name after
  // `section` ("vehicle", "exploration.frontier"). A message of another form is the section's.
  void require(const Status& core, std::string_view core_prefix, std::string_view section) {
    if (core.ok() || error_) return;
    const std::string& message = core.error().message;
    if (!message.starts_with(core_prefix)) {
      error_ = RangeError{std::string(section), std::string(section) + ": " + message};
      return;
    }
    const std::string keyed = std::string(section) + "." + message.substr(core_prefix.size());
    error_ = RangeError{keyed.substr(0, keyed.find(' ')), keyed};
  }
  bool failed() const { return error_.has_value(); }
  std::optional<RangeError> result() && { return std::move(error_); }

 private:
  static std::string text(double v) { return format_number(v); }
  static std::string text(unsigned v) { return std::to_string(v); }
  static std::string text(int v) { return std::to_string(v); }
  static std::string text(const std::string& v) { return "'" + v + "'"; }

  const GripParams& params_;
  std::optional<RangeError> error_;
};

bool finite_in(double v, double lo, double hi) { return std::isfinite(v) && v >= lo && v <= hi; }
bool finite_positive(double v) { return std::isfinite(v) && v > 0.0; }
bool finite_non_negative(double v) { return std::isfinite(v) && v >= 0.0; }

void check_planner(const PlannerParams& p, Rules& r) {
  r.require(finite_in(p.cycle_s, 0.001, 4.0), p.cycle_s, "in [0.001, 4]");
  r.require(finite_positive(p.budget_s) && p.budget_s < p.cycle_s, p.budget_s,
            "in (0, cycle_s = " + format_number(p.cycle_s) + ")");
  r.require(std::isfinite(p.margin_s) && p.margin_s < p.budget_s, p.margin_s,
            "below budget_s = " + format_number(p.budget_s) + ", or auto");
  if (r.failed()) return;  // the tuning's check needs the integration step of a valid cycle
  // The planner as the runtime configures it (rt/cycle_sizing.cpp): its integration step
  // follows from the cycle, and the step bounds the shortest plan.
  PlannerConfig config;
  config.integration_step_s = integration_step_for_cycle(p.cycle_s);
  p.tuning.apply_to(config);
  r.require(config.validate(), "planner.", "planner");
  r.require(p.max_edges == 0 || p.max_edges >= 100, p.max_edges, "auto (0) or at least 100");
  r.require(p.lockstep_edges >= 1 && p.lockstep_edges <= 200'000, p.lockstep_edges,
            "in [1, 200000]");
  r.require(p.max_map_cells >= 1 && p.max_map_cells <= OccupancyGrid::kMaxCells, p.max_map_cells,
            "in [1, " + std::to_string(OccupancyGrid::kMaxCells) + "]");
}

void check_exploration(const SensorParams& s, const ExplorationParams& e, const GripTuning& tuning,
                       Rules& r) {
  r.require(finite_non_negative(s.range_m), s.range_m, "finite and >= 0 (0: auto)");
  r.require(s.rays == 0 || (s.rays >= 16 && s.rays <= 100'000), s.rays,
            "auto (0) or in [16, 100000]");
  const PathWeightSettings& w = e.path_weight;
  r.require(finite_non_negative(w.sensing_radius_m), w.sensing_radius_m,
            "finite and >= 0 (0: auto)");
  r.require(finite_non_negative(w.length_weight_per_m), w.length_weight_per_m, "finite and >= 0");
  const auto auto_or_non_negative = [](double v) {
    return v == kPathWeightOfVehicle || finite_non_negative(v);
  };
  r.require(auto_or_non_negative(w.reference_speed_m_s), w.reference_speed_m_s,
            "auto or finite and >= 0");
  r.require(auto_or_non_negative(w.course_change_m), w.course_change_m, "auto or finite and >= 0");
  // The map's resolution is not known here: FrontierMap::create checks the approach range
  // against clearance_m plus a cell's diagonal once it is; this is that check for a cell of 0.
  // Frontiers are approached from the cells rho traverses (rt/exploration_driver.hpp).
  FrontierConfig frontier = e.frontier;
  frontier.clearance_m = tuning.rho_clearance_m;
  frontier.rho_cell_m = tuning.rho_cell_m;
  r.require(frontier.validate(0.0), "frontier: ", "exploration.frontier");
  r.require(finite_positive(e.give_up_s), e.give_up_s, "finite and > 0");
  r.require(finite_positive(e.give_up_reached_s), e.give_up_reached_s, "finite and > 0");
  r.require(finite_positive(e.rho_margin_m), e.rho_margin_m, "finite and > 0");
  r.require(e.target_refresh_cycles >= 1, e.target_refresh_cycles, "at least 1");
  r.require(finite_positive(e.stuck_after_s), e.stuck_after_s, "finite and > 0");
}

void check_link_and_runtime(const LinkParams& l, const RuntimeParams& rt, Rules& r) {
  r.require(l.domain <= kMaxDomainId, l.domain,
            "at most " + std::to_string(kMaxDomainId) + ", where the RTPS port mapping ends");
  // The link's own rule (link/topics.hpp): a file is refused as soon as it is read.
  r.require(link::check_topic_prefix(l.topic_prefix).ok(), l.topic_prefix,
            "empty or up to 64 of [A-Za-z0-9_], starting with a letter");
  // Below 10 ms a lease expires between two heartbeats of a loaded machine.
  r.require(std::isfinite(l.liveliness_lease_s) && l.liveliness_lease_s >= 0.01,
            l.liveliness_lease_s, "at least 0.01 s");
  r.require(rt.fifo_priority >= 1 && rt.fifo_priority <= 99, rt.fifo_priority, "in [1, 99]");
  r.require(rt.cpu >= -1 && rt.cpu <= 1023, rt.cpu, "auto (-1) or in [0, 1023]");
}

}  // namespace

std::optional<RangeError> first_range_error(const GripParams& params) {
  Rules rules(params);
  const std::string model = std::string(vehicle_name(vehicle_kind(params.vehicle))) + ".";
  rules.require(grip::validate(params.vehicle), model, "vehicle");
  check_planner(params.planner, rules);
  check_exploration(params.sensor, params.exploration, params.planner.tuning, rules);
  check_link_and_runtime(params.link, params.runtime, rules);
  return std::move(rules).result();
}

}  // namespace detail

GripParams default_params(VehicleKind kind) {
  GripParams params;
  params.vehicle = default_vehicle_params(kind);
  return params;
}

Status validate(const GripParams& params) {
  if (auto error = detail::first_range_error(params)) return invalid_argument(error->message);
  return Ok{};
}

}  // namespace grip::params
