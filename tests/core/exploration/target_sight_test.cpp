// What sees the exploration target: cells in range and in sight of a target cell, not those
// behind a wall, beyond d_max or in unknown space; long frontiers subsampled evenly; on a fine
// map, sight decided on blocks of cells; and a sight cast on one map copy, moved, reads the same.

#include "grip/exploration/target_sight.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <utility>
#include <vector>

namespace grip {
namespace {

// A hall of 10 m x 6 m; a wall from the bottom up to y = 2.5 at x = 5; the top-left corner
// unknown.
OccupancyGrid walled_hall() {
  OccupancyGrid grid = OccupancyGrid::create(100, 60, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 9.7, 5.7, Cell::kFree);
  grid.fill_rect(4.85, 0.0, 5.15, 2.5, Cell::kObstacle);
  grid.fill_rect(0.31, 4.51, 2.49, 5.69, Cell::kUnknown);
  return grid;
}

std::uint32_t seen_at(const TargetSight& sight, const OccupancyGrid& grid, double x, double y) {
  int cx = 0;
  int cy = 0;
  const std::uint32_t by_cell =
      grid.to_cell(x, y, cx, cy) ? sight.seen_from(grid.index(cx, cy)) : 0U;
  EXPECT_EQ(sight.seen_at(x, y), by_cell) << "at (" << x << ", " << y << ")";
  return by_cell;
}

TEST(TargetSight, CellsSeeATargetOnlyInRangeAndInSight) {
  const OccupancyGrid grid = walled_hall();
  auto sight = TargetSight::create(100, 60, 0.1, 3.0).value();
  EXPECT_EQ(sight.sight_block(), 1);
  const std::uint32_t target = grid.index(60, 16);  // right of the wall, x = 6.05, y = 1.65
  const std::uint32_t cells[] = {target};
  sight.set_target(grid, cells);
  ASSERT_EQ(sight.target_cells().size(), 1U);
  EXPECT_DOUBLE_EQ(sight.target_x_m(0), 6.05);
  EXPECT_DOUBLE_EQ(sight.target_y_m(0), 1.65);
  EXPECT_EQ(seen_at(sight, grid, 6.05, 3.0), 1U);  // open space above, 1.35 m
  EXPECT_EQ(seen_at(sight, grid, 4.5, 3.5), 1U);   // over the wall's end, 2.5 m
  EXPECT_EQ(seen_at(sight, grid, 4.0, 1.6), 0U);   // behind the wall, 2 m
  EXPECT_EQ(seen_at(sight, grid, 6.05, 5.5), 0U);  // in sight but 3.85 m away: beyond d_max
  EXPECT_EQ(seen_at(sight, grid, -1.0, 1.0), 0U);  // off the map
  // A new target forgets the old one; unknown space is not seen into.
  const std::uint32_t other[] = {grid.index(30, 35)};  // (3.05, 3.55)
  sight.set_target(grid, other);
  EXPECT_EQ(seen_at(sight, grid, 6.05, 3.0), 0U);
  EXPECT_EQ(seen_at(sight, grid, 3.05, 4.4), 1U);
  EXPECT_EQ(seen_at(sight, grid, 1.5, 5.0), 0U);  // in the unknown corner
}

TEST(TargetSight, LongFrontiersAreSubsampledEvenly) {
  const OccupancyGrid grid = walled_hall();
  auto sight = TargetSight::create(100, 60, 0.1, 3.0).value();
  std::vector<std::uint32_t> cells;
  for (int x = 3; x < 97; ++x) cells.push_back(grid.index(x, 56));
  sight.set_target(grid, cells);
  const auto targets = sight.target_cells();
  ASSERT_EQ(targets.size(), TargetSight::kMaxTargetCells);
  EXPECT_LT(grid.cell_x(targets.front()), 6);
  EXPECT_GT(grid.cell_x(targets.back()), 93);
  for (std::size_t i = 1; i < targets.size(); ++i) {
    EXPECT_GT(grid.cell_x(targets[i]), grid.cell_x(targets[i - 1]));
  }
  // Every target sees its own cell, and each one's bit is its own.
  for (std::uint32_t i = 0; i < targets.size(); ++i) {
    EXPECT_NE(sight.seen_from(targets[i]) & (1U << i), 0U) << "target " << i;
  }
}

// The exploration driver casts a sight beside the planning thread and swaps it in: a moved
// sight answers as the one it was moved from, and the one swapped out is cast afresh.
TEST(TargetSight, ASwappedSightAnswersAsTheOneCast) {
  const OccupancyGrid grid = walled_hall();
  auto read = TargetSight::create(100, 60, 0.1, 3.0).value();
  auto cast = TargetSight::create(100, 60, 0.1, 3.0).value();
  const std::uint32_t first[] = {grid.index(60, 16)};
  const std::uint32_t second[] = {grid.index(30, 35)};
  read.set_target(grid, first);
  cast.set_target(grid, second);
  std::swap(read, cast);
  EXPECT_EQ(read.seen_from(grid.index(30, 44)), 1U);  // second's
  EXPECT_EQ(read.seen_from(grid.index(60, 30)), 0U);
  cast.set_target(grid, second);  // the old one's marks are cleared
  EXPECT_EQ(cast.seen_from(grid.index(60, 30)), 0U);
  EXPECT_EQ(cast.seen_from(grid.index(30, 44)), 1U);
}

// A map finer than d_max / kMaxSightRadius: sight is decided on blocks of map cells. 12 m x 6 m
// at 2 cm, d_max 4 m (200 cells: blocks of 4), a wall at x = 6 m from the bottom to y = 4 m,
// the target at (7, 1) right of it. Open space in range on the target's side is seen, the
// wall's shadow is not, nor is anything beyond d_max.
TEST(TargetSight, OnAFineMapSightOnBlocksStopsAtWallsAndAtTheRange) {
  const double res = 0.02;
  OccupancyGrid grid = OccupancyGrid::create(600, 300, res, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.1, 0.1, 11.9, 5.9, Cell::kFree);
  grid.fill_rect(5.95, 0.0, 6.05, 4.0, Cell::kObstacle);
  auto sight = TargetSight::create(600, 300, res, 4.0).value();
  EXPECT_EQ(sight.sight_block(), 4);
  int tx = 0;
  int ty = 0;
  ASSERT_TRUE(grid.to_cell(7.0, 1.0, tx, ty));
  const std::uint32_t target[] = {grid.index(tx, ty)};
  sight.set_target(grid, target);
  int seen_open = 0;
  int shadow = 0;
  int beyond = 0;
  for (int y = 0; y < grid.height(); ++y) {
    for (int x = 0; x < grid.width(); ++x) {
      const double cx = grid.cell_center_x(x);
      const double cy = grid.cell_center_y(y);
      const double d = std::hypot(cx - 7.0, cy - 1.0);
      const bool seen = sight.seen_from(grid.index(x, y)) != 0;
      if (cx > 6.4 && cx < 11.6 && cy > 0.4 && cy < 5.6 && d < 3.8) {
        EXPECT_TRUE(seen) << "open cell (" << cx << ", " << cy << ") not seen";
        seen_open += seen ? 1 : 0;
      } else if (cx < 5.7 && cy < 3.5) {
        EXPECT_FALSE(seen) << "cell (" << cx << ", " << cy << ") behind the wall seen";
        ++shadow;
      } else if (d > 4.2) {
        EXPECT_FALSE(seen) << "cell (" << cx << ", " << cy << ") beyond d_max seen";
        ++beyond;
      }
    }
  }
  EXPECT_GT(seen_open, 10'000);
  EXPECT_GT(shadow, 10'000);
  EXPECT_GT(beyond, 1'000);
}

TEST(TargetSight, BadValuesAreRefusedByName) {
  const auto radius = TargetSight::create(10, 10, 0.1, 0.0);
  ASSERT_FALSE(radius.ok());
  EXPECT_NE(radius.error().message.find("sensing_radius_m"), std::string::npos);
  const auto nan = TargetSight::create(10, 10, 0.1, std::nan(""));
  ASSERT_FALSE(nan.ok());
  EXPECT_NE(nan.error().message.find("sensing_radius_m"), std::string::npos);
  const auto size = TargetSight::create(0, 10, 0.1, 1.0);
  ASSERT_FALSE(size.ok());
  EXPECT_NE(size.error().message.find("width_cells"), std::string::npos);
}

}  // namespace
}  // namespace grip
