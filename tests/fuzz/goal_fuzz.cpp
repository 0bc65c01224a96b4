// libFuzzer target: a received Goal, validated against the planner's map as the planner does,
// and when valid applied: the planner's target set (the goal's cells) is built from it.

#include <cstdint>
#include <cstdlib>
#include <optional>

#include "fuzz_bytes.hpp"
#include "grip/link/messages.hpp"
#include "grip/planner/target_set.hpp"
#include "samples.hpp"

namespace {

// The planner's map: 10 m x 6 m at 0.1 m, free inside a wall, off the origin.
const grip::OccupancyGrid& planner_map() {
  static const grip::OccupancyGrid grid = [] {
    auto g = grip::OccupancyGrid::create(100, 60, 0.1, -3.0, 2.0, grip::Cell::kFree).value();
    for (int x = 0; x < g.width(); ++x) {
      g.set(x, 0, grip::Cell::kObstacle);
      g.set(x, g.height() - 1, grip::Cell::kObstacle);
    }
    return g;
  }();
  return grid;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  const grip_msg_Goal msg = grip::fuzz::goal_from(in);
  const grip::OccupancyGrid& grid = planner_map();
  const grip::link::Verdict verdict = grip::link::check_goal(msg, grid);
  if (!verdict.ok()) return 0;
  static grip::TargetSet targets(grid);
  const grip::Goal goal = grip::link::goal_from_wire(msg);
  static_cast<void>(targets.assign(goal));
  static_cast<void>(targets.contains(msg.x_m, msg.y_m));
  for (const std::uint32_t cell : targets.cells()) {
    if (cell >= grid.cell_count()) std::abort();
  }
  return 0;
}
