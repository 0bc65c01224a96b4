// A standalone plan with grip's installed planner core: a differential drive in a 12 m room
// whose wall it must go around. Exit 0 when the plan reaches the goal, 1 otherwise.

#include <cstdio>

#include "grip/planner/planner.hpp"
#include "grip/world/occupancy_grid.hpp"

int main() {
  using namespace grip;
  OccupancyGrid grid = OccupancyGrid::create(120, 120, 0.1, 0.0, 0.0, Cell::kFree).value();
  grid.fill_rect(0.0, 0.0, 12.0, 0.3, Cell::kObstacle);
  grid.fill_rect(0.0, 11.7, 12.0, 12.0, Cell::kObstacle);
  grid.fill_rect(0.0, 0.0, 0.3, 12.0, Cell::kObstacle);
  grid.fill_rect(11.7, 0.0, 12.0, 12.0, Cell::kObstacle);
  grid.fill_rect(5.85, 0.0, 6.15, 8.0, Cell::kObstacle);

  const Result<DdVelocity> vehicle = DdVelocity::create({});
  if (!vehicle) return 1;
  Result<Planner<DdVelocity>> planner = Planner<DdVelocity>::create(*vehicle, grid, {});
  if (!planner) {
    std::fprintf(stderr, "planner: %s\n", planner.error().message.c_str());
    return 1;
  }
  const Status problem =
      planner->set_problem(vehicle->rest_state(2.0, 2.0, 0.0), Goal::disk(10.0, 2.0, 1.0));
  if (!problem) {
    std::fprintf(stderr, "problem: %s\n", problem.error().message.c_str());
    return 1;
  }
  const SolveResult result = planner->solve([] { return false; });
  std::printf("%s after %llu edges\n", solve_status_name(result.status).data(),
              static_cast<unsigned long long>(planner->stats().edges_added));
  return result.status == SolveStatus::kExactSolution ? 0 : 1;
}
