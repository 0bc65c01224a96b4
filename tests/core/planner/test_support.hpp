#pragma once
// Small hand-built worlds for planner tests, and the replay check of a solution.

#include <gtest/gtest.h>

#include <cmath>

#include "grip/planner/planner.hpp"
#include "grip/world/occupancy_grid.hpp"

namespace grip::test {

// A free square room of side `size_m` with a 0.3 m border wall.
inline OccupancyGrid walled_room(double size_m, double resolution_m = 0.1) {
  const int cells = static_cast<int>(size_m / resolution_m + 0.5);
  OccupancyGrid grid =
      OccupancyGrid::create(cells, cells, resolution_m, 0.0, 0.0, Cell::kFree).value();
  grid.fill_rect(0.0, 0.0, size_m, 0.3, Cell::kObstacle);
  grid.fill_rect(0.0, size_m - 0.3, size_m, size_m, Cell::kObstacle);
  grid.fill_rect(0.0, 0.0, 0.3, size_m, Cell::kObstacle);
  grid.fill_rect(size_m - 0.3, 0.0, size_m, size_m, Cell::kObstacle);
  return grid;
}

// A 12 m room split by a wall from x = 6 up to y = 8, so the way from bottom-left to
// bottom-right goes around its top end.
inline OccupancyGrid room_with_wall(double resolution_m = 0.1) {
  OccupancyGrid grid = walled_room(12.0, resolution_m);
  grid.fill_rect(5.85, 0.0, 6.15, 8.0, Cell::kObstacle);
  return grid;
}

// Replays the planner's solution through the vehicle model from `start`: every integration step
// must be collision-free and the last state must lie in the goal region.
template <VehicleModel V>
void expect_solution_replays_into_goal(const Planner<V>& planner, const typename V::State& start,
                                       const Goal& goal) {
  ASSERT_TRUE(planner.solved());
  BoundedVector<PlanStep> plan(4096);
  ASSERT_TRUE(planner.extract_plan(planner.best_state(), plan));
  ASSERT_GT(plan.size(), 0U);
  const V& vehicle = planner.vehicle();
  const double dt = planner.config().integration_step_s;
  auto q = start;
  for (const PlanStep& step : plan) {
    ASSERT_GT(step.duration_s, 0.0);
    const typename V::Control u(step.control[0], step.control[1]);
    const long steps = std::lround(step.duration_s / dt);
    for (long i = 0; i < steps; ++i) {
      q = vehicle.step(q, u, dt);
      ASSERT_TRUE(planner.chassis_free(q)) << "collision at (" << q[0] << ", " << q[1] << ")";
    }
  }
  EXPECT_TRUE(goal.contains(q[0], q[1])) << "ended at (" << q[0] << ", " << q[1] << ")";
}

}  // namespace grip::test
