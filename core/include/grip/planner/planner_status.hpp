#pragma once
// What the planner's calls return: solve()'s status and why it stopped (OMPL's PlannerStatus),
// and the outcome of the allocation-free replanning calls (retain, restart, adopt_goal).

#include <string_view>

namespace grip {

enum class SolveStatus { kExactSolution, kApproximateSolution, kNoSolution };
enum class StopReason { kGoalReached, kTerminationCondition, kPoolExhausted };

std::string_view solve_status_name(SolveStatus s) noexcept;
std::string_view stop_reason_name(StopReason r) noexcept;

struct SolveResult {
  SolveStatus status = SolveStatus::kNoSolution;
  StopReason reason = StopReason::kTerminationCondition;
};

// Outcome of the allocation-free replanning calls (retain, restart, adopt_goal).
enum class RetainStatus {
  kOk,
  kUnsupportedSelection,  // retainment is GRIP's; the baselines are standalone planners
  kRootNotInTree,
  kRootInCollision,  // the new map puts the chassis at the new root in collision
  kInvalidState,     // NaN or outside the vehicle's limits
  kGoalOutsideGrid,
  kGoalWithoutFreeCell,
  kGoalNotCells,  // adopt_goal() with a disk: rho toward a disk is the planner's own
};
std::string_view retain_status_name(RetainStatus s) noexcept;

}  // namespace grip
