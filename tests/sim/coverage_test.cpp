// Coverage counts the free space the vehicle can reach: every free cell of an open room, down
// to the walls; nothing behind a gap narrower than the vehicle or inside a dotted outline.

#include "grip/sim/coverage.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace grip::sim {
namespace {

const Footprint kChassis{0.25, 0.25, 0.2};  // 0.4 m wide

// Two rooms of 4 m x 4 m side by side (0.1 m cells), joined by a gap `gap_m` wide.
OccupancyGrid two_rooms(double gap_m) {
  OccupancyGrid grid = OccupancyGrid::create(82, 40, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.0, 0.0, 4.0, 4.0, Cell::kFree);
  grid.fill_rect(4.2, 0.0, 8.2, 4.0, Cell::kFree);
  grid.fill_rect(4.0, 2.0, 4.2, 2.0 + gap_m, Cell::kFree);
  return grid;
}

std::size_t free_cells_where(const OccupancyGrid& grid, bool (*pick)(double x)) {
  std::size_t n = 0;
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) {
    if (grid.at(c) == Cell::kFree && pick(grid.cell_center_x(grid.cell_x(c)))) ++n;
  }
  return n;
}

bool in_left_room(double x) { return x < 4.0; }
bool deep_in_right_room(double x) { return x > 4.8; }

TEST(Coverage, EveryFreeCellOfARoomTheVehicleDrivesThroughCountsDownToTheWalls) {
  const OccupancyGrid grid = two_rooms(1.0);
  const auto cells = reachable_free_cells(grid, 1.0, 1.0, kChassis).value();
  std::size_t free = 0;
  for (std::uint32_t c = 0; c < grid.cell_count(); ++c) free += grid.at(c) == Cell::kFree ? 1U : 0U;
  EXPECT_EQ(cells.size(), free);
}

TEST(Coverage, ARoomBehindAGapNarrowerThanTheVehicleDoesNotCount) {
  const OccupancyGrid grid = two_rooms(0.3);
  const auto cells = reachable_free_cells(grid, 1.0, 1.0, kChassis).value();
  std::size_t left = 0;
  for (const std::uint32_t c : cells) {
    const double x = grid.cell_center_x(grid.cell_x(c));
    EXPECT_LE(x, 4.8) << "cell at x = " << x << " behind the gap";
    left += x < 4.0 ? 1U : 0U;
  }
  EXPECT_EQ(left, free_cells_where(grid, in_left_room));
  EXPECT_GT(free_cells_where(grid, deep_in_right_room), 1000U);
}

TEST(Coverage, APocketInsideADottedOutlineDoesNotCount) {
  OccupancyGrid grid = OccupancyGrid::create(60, 60, 0.1, 0.0, 0.0, Cell::kFree).value();
  // A 2 m square rack outline with a free cell every other cell, free inside.
  for (int i = 20; i <= 40; ++i) {
    const Cell c = i % 2 == 0 ? Cell::kObstacle : Cell::kFree;
    grid.set(i, 20, c);
    grid.set(i, 40, c);
    grid.set(20, i, c);
    grid.set(40, i, c);
  }
  const auto cells = reachable_free_cells(grid, 0.5, 0.5, kChassis).value();
  for (const std::uint32_t c : cells) {
    const int x = grid.cell_x(c);
    const int y = grid.cell_y(c);
    EXPECT_FALSE(x > 22 && x < 38 && y > 22 && y < 38) << "cell (" << x << ", " << y << ")";
  }
  EXPECT_GT(cells.size(), 2000U);
}

TEST(Coverage, AStartTooCloseToAWallCountsEveryConnectedFreeCell) {
  const OccupancyGrid grid = two_rooms(0.3);
  const auto cells = reachable_free_cells(grid, 0.05, 0.05, kChassis).value();  // in the corner
  EXPECT_EQ(cells.size(),
            free_cells_where(grid, [](double) { return true; }));  // the gap is 3 cells wide
}

TEST(Coverage, AStartOutsideTheMapIsAnError) {
  const auto cells = reachable_free_cells(two_rooms(1.0), -1.0, 1.0, kChassis);
  ASSERT_FALSE(cells.ok());
  EXPECT_NE(cells.error().message.find("outside"), std::string::npos);
}

TEST(Coverage, IsTheSensedFractionOfTheReachableCells) {
  const OccupancyGrid grid = two_rooms(1.0);
  OccupancyGrid known = OccupancyGrid::create(82, 40, 0.1, 0.0, 0.0, Cell::kUnknown).value();
  const std::vector<std::uint32_t> cells{grid.index(1, 1), grid.index(2, 1), grid.index(3, 1),
                                         grid.index(4, 1)};
  known.set(1, 1, Cell::kFree);
  known.set(2, 1, Cell::kObstacle);  // sensed is sensed, whatever it holds
  EXPECT_DOUBLE_EQ(coverage_of(known, cells), 0.5);
  EXPECT_DOUBLE_EQ(coverage_of(known, {}), 1.0);
}

// The way to unsensed ground, through the free space: a vehicle on its way to the far end of
// a corridor gets nearer while it senses nothing new.
TEST(UnsensedDistance, IsTheWayThroughFreeSpaceToTheNearestReachableCellNotSensed) {
  const OccupancyGrid truth = two_rooms(1.0);
  const auto reachable = reachable_free_cells(truth, 1.0, 1.0, kChassis).value();
  auto to_unsensed = UnsensedDistance::create(truth, reachable).value();
  // Everything sensed but the right room beyond x = 6 m.
  OccupancyGrid known = truth;
  known.fill_rect(6.0, 0.0, 8.2, 4.0, Cell::kUnknown);
  // From the left room's centre line (y = 2.45 m, through the gap at 2.0-3.0 m): straight east.
  EXPECT_NEAR(to_unsensed.from(known, 1.05, 2.45), 5.0, 0.11);
  EXPECT_NEAR(to_unsensed.from(known, 3.05, 2.45), 3.0, 0.11);
  // From a corner of the left room the way bends through the gap (8-connected steps, as the
  // planner's rho: 3.7 m east and 1.7 m north to the gap's first cell, then 2 m east).
  const double from_corner = to_unsensed.from(known, 0.35, 0.35);
  EXPECT_GT(from_corner, 6.0 - 0.35);
  EXPECT_NEAR(from_corner, (3.7 - 1.7) + 1.7 * std::sqrt(2.0) + 2.0, 0.02);
  // Standing on unsensed ground: nothing to go.
  EXPECT_NEAR(to_unsensed.from(known, 7.05, 2.05), 0.0, 1e-9);
}

TEST(UnsensedDistance, IsInfiniteWhenEverythingReachableIsSensedOrTheWayIsClosed) {
  const OccupancyGrid truth = two_rooms(0.3);  // the right room is out of reach
  const auto reachable = reachable_free_cells(truth, 1.0, 1.0, kChassis).value();
  auto to_unsensed = UnsensedDistance::create(truth, reachable).value();
  // Unsensed cells only where the vehicle cannot go: nothing reachable is left.
  OccupancyGrid known = truth;
  known.fill_rect(5.0, 0.0, 8.2, 4.0, Cell::kUnknown);
  EXPECT_EQ(to_unsensed.from(known, 1.05, 1.05), std::numeric_limits<double>::infinity());
  EXPECT_EQ(to_unsensed.from(truth, 1.05, 1.05), std::numeric_limits<double>::infinity());
  // Outside the map.
  known.fill_rect(0.0, 0.0, 1.0, 1.0, Cell::kUnknown);
  EXPECT_EQ(to_unsensed.from(known, -5.0, 1.0), std::numeric_limits<double>::infinity());
  EXPECT_LT(to_unsensed.from(known, 2.05, 2.05), 2.0);
}

}  // namespace
}  // namespace grip::sim
