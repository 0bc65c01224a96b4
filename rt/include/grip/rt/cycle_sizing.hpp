#pragma once
// The one rule that turns a cycle's time budget into the planner's capacity and the cycle's
// margins, for every caller that runs replanning cycles (`grip planner`, `grip explore`,
// `grip stress`). Start-up code: it allocates nothing but may refuse a budget.

#include <cstdint>

#include "grip/common/result.hpp"
#include "grip/planner/planner_config.hpp"
#include "grip/rt/replanning_cycle.hpp"

namespace grip::rt {

struct CycleBudget {
  double cycle_s = 0.05;    // T, in vehicle time
  double budget_ms = 25.0;  // planning time per cycle, wall clock
  double margin_ms =
      -1.0;  // growth stops this long before the deadline; < 0: a fifth of the budget
  std::uint32_t max_edges = 0;  // the edge pool; 0: kEdgesPerBudgetMs per ms of budget
  // Lockstep (> 0): every cycle grows this many edges whatever the time; the pools then hold
  // four cycles' growth, and there is no deadline to leave a margin before.
  std::uint32_t lockstep_edges = 0;
  std::uint64_t seed = 1;
  bool safety = true;  // false: the paper's ablation without the contingency check
  GripTuning tuning;
};

// Retaining a tree costs time in proportion to its size (it is re-timed, re-checked and
// re-scored every cycle): this many edges per millisecond of budget keeps a full tree's
// retainment near a quarter of the budget. Pools stay within [kMinEdges, kMaxEdges].
inline constexpr double kEdgesPerBudgetMs = 400.0;
inline constexpr double kMinEdges = 2'000.0;
inline constexpr double kMaxEdges = 200'000.0;

// A fifth of the budget, for the caller's work after the cycle and the smaller delays of a shared
// machine; the commit has its own reserve (CommitReserve). No floor of a few milliseconds: a
// short budget could not spare it and would leave no time to grow; a cycle stalled longer than
// its margin misses, and says so.
double default_safety_margin_ms(double budget_ms) noexcept;

struct CycleSizing {
  PlannerConfig planner;
  CycleConfig cycle;
  double margin_ms = 0.0;  // the margin in force, wall clock
};

// kInvalidArgument when, outside lockstep, the margin leaves the budget no time to grow.
Result<CycleSizing> size_cycle(const CycleBudget& budget);

}  // namespace grip::rt
