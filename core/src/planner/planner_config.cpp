#include "grip/planner/planner_config.hpp"

#include <array>
#include <cmath>
#include <string>

#include "grip/common/enum_names.hpp"
#include "grip/common/saturating_cast.hpp"

namespace grip {

namespace {
constexpr std::array<NamedValue<Selection>, 4> kSelectionNames{{
    {Selection::kGrip, "grip"},
    {Selection::kRandom, "random"},
    {Selection::kRrt, "rrt"},
    {Selection::kRrtBias, "rrt-bias"},
}};
}  // namespace

std::string_view selection_name(Selection s) noexcept { return name_in(kSelectionNames, s); }

Result<Selection> selection_from_name(std::string_view name) {
  return value_named(kSelectionNames, name, "planner");
}

std::uint32_t PlannerConfig::states_per_trajectory() const noexcept {
  return saturating_cast<std::uint32_t>(std::ceil(max_plan_duration_s / record_step_s() - 1e-9),
                                        0U) +
         1U;
}

namespace {
Status positive(const char* name, double v) {
  if (!std::isfinite(v) || v <= 0.0) {
    return invalid_argument(std::string("planner.") + name + " must be a finite number > 0 (got " +
                            std::to_string(v) + ")");
  }
  return Ok{};
}
}  // namespace

Status PlannerConfig::validate() const {
  if (max_edges < 3) {
    return invalid_argument("planner.max_edges must be >= 3 (got " + std::to_string(max_edges) +
                            ")");
  }
  if (max_trajectories < 2) {
    return invalid_argument("planner.max_trajectories must be >= 2 (got " +
                            std::to_string(max_trajectories) + ")");
  }
  if (auto s = positive("integration_step_s", integration_step_s); !s) return s;
  if (steps_per_record == 0) {
    return invalid_argument("planner.steps_per_record must be >= 1 (got 0)");
  }
  if (auto s = positive("min_plan_duration_s", min_plan_duration_s); !s) return s;
  if (auto s = positive("max_plan_duration_s", max_plan_duration_s); !s) return s;
  if (min_plan_duration_s > max_plan_duration_s) {
    return invalid_argument("planner.min_plan_duration_s (" + std::to_string(min_plan_duration_s) +
                            ") exceeds max_plan_duration_s (" +
                            std::to_string(max_plan_duration_s) + ")");
  }
  if (max_plan_duration_s < record_step_s()) {
    return invalid_argument("planner.max_plan_duration_s (" + std::to_string(max_plan_duration_s) +
                            ") is shorter than one record step (" +
                            std::to_string(record_step_s()) + " s)");
  }
  if (states_per_trajectory() > 65535) {
    return invalid_argument("planner.max_plan_duration_s / record step exceeds 65534 states");
  }
  if (!std::isfinite(min_edge_duration_s) || min_edge_duration_s < 0.0 ||
      min_edge_duration_s > max_plan_duration_s) {
    return invalid_argument(
        "planner.min_edge_duration_s must be in [0, max_plan_duration_s] (got " +
        std::to_string(min_edge_duration_s) + ")");
  }
  if (!std::isfinite(score_base_a) || score_base_a <= 1.0) {
    return invalid_argument("planner.score_base_a must be a finite number > 1 (got " +
                            std::to_string(score_base_a) + ")");
  }
  if (auto s = positive("safety_horizon_s", safety_horizon_s); !s) return s;
  if (!std::isfinite(rho_clearance_m) || rho_clearance_m < 0.0) {
    return invalid_argument("planner.rho_clearance_m must be finite and >= 0 (got " +
                            std::to_string(rho_clearance_m) + ")");
  }
  if (!std::isfinite(rho_cell_m) || rho_cell_m < 0.0) {
    return invalid_argument("planner.rho_cell_m must be finite and >= 0 (got " +
                            std::to_string(rho_cell_m) + ")");
  }
  if (auto s = positive("rho_floor_m", rho_floor_m); !s) return s;
  if (!std::isfinite(braking_control_fraction) || braking_control_fraction < 0.0 ||
      braking_control_fraction > 1.0) {
    return invalid_argument("planner.braking_control_fraction must be in [0, 1] (got " +
                            std::to_string(braking_control_fraction) + ")");
  }
  if (!std::isfinite(rrt_goal_bias) || rrt_goal_bias < 0.0 || rrt_goal_bias > 1.0) {
    return invalid_argument("planner.rrt_goal_bias must be in [0, 1] (got " +
                            std::to_string(rrt_goal_bias) + ")");
  }
  return Ok{};
}

}  // namespace grip
