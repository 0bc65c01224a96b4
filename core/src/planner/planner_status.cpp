#include "grip/planner/planner_status.hpp"

#include <array>

#include "grip/common/enum_names.hpp"

namespace grip {

namespace {
constexpr std::array<NamedValue<SolveStatus>, 3> kSolveStatusNames{{
    {SolveStatus::kExactSolution, "exact"},
    {SolveStatus::kApproximateSolution, "approximate"},
    {SolveStatus::kNoSolution, "none"},
}};
constexpr std::array<NamedValue<RetainStatus>, 8> kRetainStatusNames{{
    {RetainStatus::kOk, "ok"},
    {RetainStatus::kUnsupportedSelection, "unsupported-selection"},
    {RetainStatus::kRootNotInTree, "root-not-in-tree"},
    {RetainStatus::kRootInCollision, "root-in-collision"},
    {RetainStatus::kInvalidState, "invalid-state"},
    {RetainStatus::kGoalOutsideGrid, "goal-outside-grid"},
    {RetainStatus::kGoalWithoutFreeCell, "goal-without-free-cell"},
    {RetainStatus::kGoalNotCells, "goal-not-cells"},
}};
constexpr std::array<NamedValue<StopReason>, 3> kStopReasonNames{{
    {StopReason::kGoalReached, "goal-reached"},
    {StopReason::kTerminationCondition, "terminated"},
    {StopReason::kPoolExhausted, "pool-exhausted"},
}};
}  // namespace

std::string_view solve_status_name(SolveStatus s) noexcept { return name_in(kSolveStatusNames, s); }
std::string_view retain_status_name(RetainStatus s) noexcept {
  return name_in(kRetainStatusNames, s);
}
std::string_view stop_reason_name(StopReason r) noexcept { return name_in(kStopReasonNames, r); }

}  // namespace grip
