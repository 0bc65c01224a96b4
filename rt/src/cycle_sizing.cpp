#include "grip/rt/cycle_sizing.hpp"

#include <algorithm>
#include <string>

#include "grip/planner/step_margin.hpp"

namespace grip::rt {

double default_safety_margin_ms(double budget_ms) noexcept { return budget_ms / 5.0; }

Result<CycleSizing> size_cycle(const CycleBudget& budget) {
  const bool lockstep = budget.lockstep_edges > 0;
  CycleSizing sizing;
  PlannerConfig& planner = sizing.planner;
  // Whole fractions of T, at most 50 ms per integration step.
  planner.integration_step_s = integration_step_for_cycle(budget.cycle_s);
  planner.seed = budget.seed;
  if (!budget.safety) planner.safety = SafetyCheck::kNone;
  budget.tuning.apply_to(planner);
  const double default_edges = lockstep ? 4.0 * static_cast<double>(budget.lockstep_edges)
                                        : kEdgesPerBudgetMs * budget.budget_ms;
  planner.max_edges =
      budget.max_edges != 0
          ? budget.max_edges
          : static_cast<std::uint32_t>(std::clamp(default_edges, kMinEdges, kMaxEdges));
  planner.max_trajectories = planner.max_edges / 2;

  sizing.margin_ms =
      budget.margin_ms >= 0.0 ? budget.margin_ms : default_safety_margin_ms(budget.budget_ms);
  if (sizing.margin_ms >= budget.budget_ms && !lockstep) {
    return invalid_argument(
        "the budget (" + std::to_string(budget.budget_ms) +
        " ms of wall clock) leaves no time to grow the tree after a margin of " +
        std::to_string(sizing.margin_ms) + " ms");
  }
  sizing.cycle.cycle_s = budget.cycle_s;
  sizing.cycle.safety_margin_ns = static_cast<std::int64_t>(sizing.margin_ms * 1e6);
  return sizing;
}

}  // namespace grip::rt
