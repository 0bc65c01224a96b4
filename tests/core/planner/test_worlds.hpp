#pragma once
// Small hand-built worlds for planner tests.

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
inline OccupancyGrid room_with_wall() {
  OccupancyGrid grid = walled_room(12.0);
  grid.fill_rect(5.85, 0.0, 6.15, 8.0, Cell::kObstacle);
  return grid;
}

}  // namespace grip::test
