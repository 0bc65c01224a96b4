#pragma once
// The verdict on a run whose planner said exploration was over, from the ground truth rather
// than the planner's word: `complete` when at least kCompleteCoverage of the reachable free space
// was sensed; short of that `stuck` when the planner left frontier groups it gave up on or
// cannot reach at its turning radius (they hid reachable ground), `done-early` when it left none.
//
// Why the same coverage with frontiers left as without: a sensor leaves cells it cannot resolve
// (a crack between racks its rays do not enter), and a planner that stood beside them gives
// them up; a run that sensed all but those has explored what it could reach. The reason names
// what was left and how much reachable free space stayed unsensed.

#include <cstddef>
#include <cstdint>
#include <string>

namespace grip::sim {

// The fraction of the reachable free space a run must have sensed to be `complete`; every
// verdict of completeness (this, `grip bench explore`'s targets) uses it.
inline constexpr double kCompleteCoverage = 0.97;

struct ExplorationVerdict {
  std::string result;  // "complete", "stuck" or "done-early"
  std::string reason;  // empty for a complete run that left nothing
};

// sensed_cells of reachable_cells (sensed_cells <= reachable_cells); the planner's count of the
// groups it gave up on and of those out of its vehicle's turning reach.
ExplorationVerdict verdict_when_planner_done(std::size_t sensed_cells, std::size_t reachable_cells,
                                             std::uint32_t groups_given_up,
                                             std::uint32_t groups_unreachable);

}  // namespace grip::sim
