// Frontier detection, grouping by flood fill, reachability for the chassis and the choice of
// the target group, on small hand-made grids (0.1 m cells).

#include "grip/exploration/frontier.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "grip/common/random.hpp"
#include "grip/world/line_of_sight.hpp"

namespace grip {
namespace {

class FrontierTest : public ::testing::Test {
 protected:
  std::optional<OccupancyGrid> grid;
  std::optional<ClearanceMap> clearance;
  std::optional<FrontierMap> frontiers;
  FrontierConfig config;

  void make_grid(int width, int height, Cell fill) {
    grid.emplace(OccupancyGrid::create(width, height, 0.1, 0.0, 0.0, fill).value());
  }
  ExplorationStatus update(double robot_x, double robot_y) {
    if (!frontiers) {
      frontiers.emplace(FrontierMap::create(grid->width(), grid->height(), 0.1, config).value());
    }
    clearance.emplace(ClearanceMap::create_for(*grid).value());
    return frontiers->update(*grid, *clearance, robot_x, robot_y);
  }
  std::uint32_t group_size(std::uint32_t g) const { return frontiers->groups()[g].size; }
  // A room of free space walled by obstacles, inside an unknown grid.
  void walled_room(double x0, double y0, double x1, double y1) {
    grid->fill_rect(x0, y0, x1, y1, Cell::kObstacle);
    grid->fill_rect(x0 + 0.3, y0 + 0.3, x1 - 0.3, y1 - 0.3, Cell::kFree);
  }
};

TEST_F(FrontierTest, FreeCellsBesideUnknownFormOneGroupPerConnectedStretch) {
  // GIVEN known free space below y = 2.5 and unknown above, with an obstacle on the border
  // between x = 3 and 4.5 that splits the frontier in two.
  make_grid(80, 40, Cell::kUnknown);
  grid->fill_rect(0.0, 0.0, 8.0, 2.5, Cell::kFree);
  grid->fill_rect(2.98, 2.32, 4.52, 2.6, Cell::kObstacle);
  // WHEN the frontier is computed
  ASSERT_EQ(update(1.0, 1.0), ExplorationStatus::kTarget);
  // THEN the top free row left and right of the obstacle are two groups.
  ASSERT_EQ(frontiers->groups().size(), 2U);
  EXPECT_EQ(group_size(0), 30U);
  EXPECT_EQ(group_size(1), 35U);
  for (const std::uint32_t c : frontiers->group_cells(0)) {
    EXPECT_EQ(grid->cell_y(c), 24);
    EXPECT_LT(grid->cell_x(c), 30);
  }
  EXPECT_EQ(frontiers->frontier_cells().size(), 65U);
}

TEST_F(FrontierTest, ADiagonalStaircaseIsOneGroupAndCornerContactIsNoFrontier) {
  // Free where x + y < 15: the boundary cells touch each other only at corners.
  make_grid(20, 20, Cell::kUnknown);
  for (int y = 0; y < 20; ++y) {
    for (int x = 0; x < 20; ++x) {
      if (x + y < 15) grid->set(x, y, Cell::kFree);
    }
  }
  (void)update(0.05, 0.05);
  ASSERT_EQ(frontiers->groups().size(), 1U);
  EXPECT_EQ(group_size(0), 15U);  // x + y == 14; x + y == 13 touches unknown at a corner only
  for (const std::uint32_t c : frontiers->frontier_cells()) {
    EXPECT_EQ(grid->cell_x(c) + grid->cell_y(c), 14);
  }
}

TEST_F(FrontierTest, AFullyKnownMapIsCompleteAndSaysSo) {
  make_grid(60, 60, Cell::kObstacle);
  walled_room(0.0, 0.0, 6.0, 6.0);
  EXPECT_EQ(update(3.0, 3.0), ExplorationStatus::kComplete);
  EXPECT_EQ(frontiers->status(), ExplorationStatus::kComplete);
  EXPECT_TRUE(frontiers->groups().empty());
  EXPECT_EQ(frontiers->target(), FrontierMap::kNoGroup);
  EXPECT_TRUE(frontiers->approach_cells().empty());
  EXPECT_TRUE(frontiers->target_cells().empty());
}

TEST_F(FrontierTest, AFrontierBehindAClosedWallIsNotReachable) {
  // The robot's room, and beyond its right wall free space seen through it, open to unknown.
  make_grid(100, 60, Cell::kUnknown);
  walled_room(0.0, 0.0, 5.0, 6.0);
  grid->fill_rect(5.0, 0.3, 8.0, 5.7, Cell::kFree);
  ASSERT_FALSE(frontiers.has_value());
  EXPECT_EQ(update(2.0, 3.0), ExplorationStatus::kComplete);
  ASSERT_FALSE(frontiers->groups().empty());
  for (const FrontierGroup& g : frontiers->groups()) EXPECT_FALSE(g.reachable());
}

TEST_F(FrontierTest, AFrontierBehindAGapTooNarrowForTheChassisIsNotReachable) {
  const auto with_gap = [this](double gap_m) {
    make_grid(100, 60, Cell::kUnknown);
    walled_room(0.0, 0.0, 5.0, 6.0);
    grid->fill_rect(5.0, 0.3, 8.0, 5.7, Cell::kFree);
    grid->fill_rect(4.65, 3.0 - gap_m / 2, 5.05, 3.0 + gap_m / 2, Cell::kFree);
    return update(2.0, 3.0);
  };
  // 0.4 m: the reference point needs 0.3 m of clearance on both sides.
  EXPECT_EQ(with_gap(0.4), ExplorationStatus::kComplete);
  // 1.2 m: through.
  ASSERT_EQ(with_gap(1.2), ExplorationStatus::kTarget);
  const FrontierGroup& target = frontiers->groups()[frontiers->target()];
  EXPECT_GT(target.rho_m, 3.0);  // from x = 2 through the gap at x = 4.85
  EXPECT_LT(target.rho_m, 7.5);
  EXPECT_GE(grid->cell_x(target.nearest_cell), 50);  // beyond the wall
}

class FrontierApproachTest : public FrontierTest, public ::testing::WithParamInterface<bool> {};

TEST_P(FrontierApproachTest, ApproachCellsAreChassisCellsNearTheTargetAndReachable) {
  // With the parameter, the robot's wavefront runs on blocks of 2 x 2 cells (a clearance of
  // 0.4 m allows 0.2 m): a reached block's cells include some that are not chassis cells.
  if (GetParam()) {
    config.clearance_m = 0.4;
    config.approach_range_m = 0.6;
    config.rho_cell_m = 0.2;
  }
  make_grid(100, 60, Cell::kObstacle);
  walled_room(0.0, 0.0, 10.0, 6.0);
  grid->fill_rect(7.0, 2.0, 7.5, 3.0, Cell::kUnknown);    // an unknown pocket in the room
  grid->fill_rect(7.6, 2.0, 7.65, 3.0, Cell::kObstacle);  // and a post beside it
  ASSERT_EQ(update(1.5, 3.0), ExplorationStatus::kTarget);
  ASSERT_EQ(frontiers->robot_field().block(), GetParam() ? 2 : 1);
  ASSERT_FALSE(frontiers->approach_cells().empty());
  const std::span<const std::uint32_t> target = frontiers->target_cells();
  for (const std::uint32_t a : frontiers->approach_cells()) {
    EXPECT_TRUE(frontiers->robot_field().reachable(a));
    EXPECT_EQ(grid->at(a), Cell::kFree);
    EXPECT_GE(clearance->clearance_m(a), config.clearance_m);
    double nearest = 1e9;
    for (const std::uint32_t c : target) {
      nearest = std::min(nearest, std::hypot(grid->cell_x(a) - grid->cell_x(c),
                                             grid->cell_y(a) - grid->cell_y(c)));
    }
    EXPECT_LE(nearest * 0.1, config.approach_range_m + 1e-9);
  }
  // Each once.
  std::vector<std::uint32_t> sorted(frontiers->approach_cells().begin(),
                                    frontiers->approach_cells().end());
  std::sort(sorted.begin(), sorted.end());
  EXPECT_EQ(std::adjacent_find(sorted.begin(), sorted.end()), sorted.end());
}

INSTANTIATE_TEST_SUITE_P(CellsAndBlocks, FrontierApproachTest, ::testing::Bool(),
                         [](const auto& param_info) {
                           return param_info.param ? "Blocks" : "Cells";
                         });

class FrontierTargetTest : public FrontierTest {
 protected:
  // A 10 m x 6 m walled room, fully known but for unknown blocks: a block of a x b cells is
  // ringed by 2 (a + b) frontier cells, one group.
  void room() {
    make_grid(100, 60, Cell::kObstacle);
    walled_room(0.0, 0.0, 10.0, 6.0);
  }
  void unknown_block(double x, double y, double w, double h) {
    grid->fill_rect(x + 0.01, y + 0.01, x + w - 0.01, y + h - 0.01, Cell::kUnknown);
  }
  std::uint32_t target_size() const { return group_size(frontiers->target()); }
};

TEST_F(FrontierTargetTest, ACloseSmallGroupIsPreferredOverAFarBigOne) {
  room();
  unknown_block(3.0, 2.9, 0.2, 0.2);  // 8 frontier cells, 1.5 m from the robot
  unknown_block(8.0, 1.0, 1.0, 2.0);  // 60 frontier cells, 6.5 m away
  ASSERT_EQ(update(1.5, 3.0), ExplorationStatus::kTarget);
  ASSERT_EQ(frontiers->groups().size(), 2U);
  EXPECT_EQ(target_size(), 8U);
}

TEST_F(FrontierTargetTest, ASmallGroupAlittleFartherStillWinsUnlessSizeIsIgnored) {
  room();
  unknown_block(6.0, 2.9, 0.2, 0.2);  // small, about 4 m away
  unknown_block(4.0, 1.0, 1.0, 2.0);  // big, about 2 m away
  ASSERT_EQ(update(1.5, 3.0), ExplorationStatus::kTarget);
  EXPECT_EQ(target_size(), 8U);
  const auto& groups = frontiers->groups();
  const FrontierGroup& small = groups[0].size == 8 ? groups[0] : groups[1];
  const FrontierGroup& big = groups[0].size == 8 ? groups[1] : groups[0];
  EXPECT_GT(small.rho_m, big.rho_m);
  EXPECT_LT(small.score_m, big.score_m);

  // Without the size term the nearer, bigger group wins.
  config.size_weight = 0.0;
  frontiers.reset();
  ASSERT_EQ(update(1.5, 3.0), ExplorationStatus::kTarget);
  EXPECT_EQ(target_size(), 60U);
}

TEST_F(FrontierTargetTest, TiesGoToTheGroupWithTheLowestCellIndex) {
  room();
  // Mirror images about the robot's column: same size, same distance.
  unknown_block(3.0, 2.0, 0.2, 0.2);
  unknown_block(6.9, 2.0, 0.2, 0.2);
  for (int run = 0; run < 2; ++run) {
    ASSERT_EQ(update(5.05, 3.0), ExplorationStatus::kTarget);
    ASSERT_EQ(frontiers->groups().size(), 2U);
    EXPECT_DOUBLE_EQ(frontiers->groups()[0].score_m, frontiers->groups()[1].score_m);
    EXPECT_EQ(frontiers->target(), 0U);
    EXPECT_LT(grid->cell_x(frontiers->target_cells()[0]), 50);
  }
}

TEST_F(FrontierTargetTest, GroupsBelowTheMinimumSizeAreIgnored) {
  room();
  unknown_block(3.0, 2.9, 0.1, 0.1);  // a single unknown cell: 4 frontier cells
  config.min_group_cells = 5;
  EXPECT_EQ(update(1.5, 3.0), ExplorationStatus::kComplete);
  config.min_group_cells = 4;
  frontiers.reset();
  EXPECT_EQ(update(1.5, 3.0), ExplorationStatus::kTarget);
}

TEST_F(FrontierTest, AGroupGivenUpIsNoLongerATargetAndWhenOnlySuchRemainExplorationEnds) {
  // The two groups of the first test: left (x < 3) and right (x > 4.5) of the obstacle.
  make_grid(80, 40, Cell::kUnknown);
  grid->fill_rect(0.0, 0.0, 8.0, 2.5, Cell::kFree);
  grid->fill_rect(2.98, 2.32, 4.52, 2.6, Cell::kObstacle);
  ASSERT_EQ(update(1.0, 1.0), ExplorationStatus::kTarget);
  const std::uint32_t first = frontiers->target();
  const bool first_is_left = grid->cell_x(frontiers->target_cells()[0]) < 30;
  EXPECT_EQ(frontiers->given_up_groups(), 0U);
  frontiers->give_up(first);
  // The other group is the target now, wherever the robot stands.
  ASSERT_EQ(update(1.0, 1.0), ExplorationStatus::kTarget);
  EXPECT_EQ(frontiers->given_up_groups(), 1U);
  for (const std::uint32_t c : frontiers->target_cells()) {
    EXPECT_EQ(grid->cell_x(c) < 30, !first_is_left) << grid->cell_x(c);
  }
  frontiers->give_up(frontiers->target());
  EXPECT_EQ(update(1.0, 1.0), ExplorationStatus::kComplete);
  EXPECT_EQ(frontiers->given_up_groups(), 2U);
  // New frontier beyond the given-up neighbourhood (1 m) is a target again.
  grid->fill_rect(0.0, 2.5, 8.0, 3.0, Cell::kFree);  // the frontier moves up to y = 2.9
  grid->fill_rect(2.98, 2.32, 4.52, 3.1, Cell::kObstacle);
  EXPECT_EQ(update(1.0, 1.0), ExplorationStatus::kComplete) << "0.5 m is within the radius";
  grid->fill_rect(0.0, 3.0, 8.0, 3.8, Cell::kFree);  // y = 3.7: beyond it
  grid->fill_rect(2.98, 2.32, 4.52, 3.9, Cell::kObstacle);
  EXPECT_EQ(update(1.0, 1.0), ExplorationStatus::kTarget);
  EXPECT_EQ(frontiers->given_up_groups(), 0U);
}

TEST_F(FrontierTest, ARobotNearAWallStillReachesTheOpenSpace) {
  // 0.15 m from the wall: its own cell is not a chassis cell under 0.3 m clearance.
  make_grid(100, 60, Cell::kObstacle);
  walled_room(0.0, 0.0, 10.0, 6.0);
  grid->fill_rect(8.0, 2.0, 8.5, 3.0, Cell::kUnknown);
  EXPECT_EQ(update(0.45, 3.0), ExplorationStatus::kTarget);
}

TEST_F(FrontierTest, ARobotOutsideTheGridHasNoTarget) {
  make_grid(20, 20, Cell::kFree);
  EXPECT_EQ(update(-1.0, 0.5), ExplorationStatus::kRobotOutsideGrid);
  EXPECT_EQ(frontiers->target(), FrontierMap::kNoGroup);
}

// A random known space: free with obstacle and unknown blocks, inside an unknown border.
OccupancyGrid random_known_space(Random& random) {
  OccupancyGrid grid = OccupancyGrid::create(120, 80, 0.1, 0.0, 0.0, Cell::kUnknown).value();
  grid.fill_rect(0.3, 0.3, 11.7, 7.7, Cell::kFree);
  for (int block = 0; block < 24; ++block) {
    const double x = random.uniform(0.0, 11.0);
    const double y = random.uniform(0.0, 7.0);
    const double w = random.uniform(0.1, 1.5);
    const double h = random.uniform(0.1, 1.5);
    grid.fill_rect(x, y, x + w, y + h, random.below(2) == 0 ? Cell::kObstacle : Cell::kUnknown);
  }
  return grid;
}

// The robot's wavefront on blocks of 3 x 3 cells of 0.1 m, which a clearance of 0.6 m allows.
void on_blocks_of_3(FrontierConfig& config) {
  config.clearance_m = 0.6;
  config.approach_range_m = 0.8;
  config.rho_cell_m = 0.3;
}

TEST(FrontierSearch, AWavefrontInStepsChoosesWhatOneOverAllTheKnownSpaceChooses) {
  // GIVEN random known spaces and robots, and frontier maps whose robot wavefront runs in
  // steps of 0.2 m, 0.7 m and the default length, beside one that runs over everything at once
  // (scored by distance alone, and with the size term; every fourth map with the wavefront on
  // blocks of 3 x 3 cells, which a clearance of 0.6 m allows)
  Random random(41);
  int targets = 0;
  int completes = 0;
  for (int trial = 0; trial < 300; ++trial) {
    const OccupancyGrid grid = random_known_space(random);
    const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
    double x = 0.0;
    double y = 0.0;
    do {
      x = random.uniform(0.5, 11.5);
      y = random.uniform(0.5, 7.5);
    } while (grid.at(static_cast<int>(x * 10), static_cast<int>(y * 10)) != Cell::kFree);
    std::vector<FrontierMap> maps;
    const double size_weight = trial % 2 == 0 ? 0.0 : FrontierConfig{}.size_weight;
    for (const double step : {0.0, 0.2, 0.7, FrontierConfig{}.search_step_m}) {
      FrontierConfig config;
      config.search_step_m = step;
      config.size_weight = size_weight;
      if (trial % 4 == 3) on_blocks_of_3(config);
      maps.push_back(FrontierMap::create(120, 80, 0.1, config).value());
    }
    // WHEN each chooses, then again after giving up what the exact one chose, three times
    for (int round = 0; round < 3; ++round) {
      for (FrontierMap& map : maps) map.update(grid, clearance, x, y);
      const FrontierMap& exact = maps[0];
      // THEN every one chooses the same group, with the same rho and approach cells
      for (std::size_t m = 1; m < maps.size(); ++m) {
        const FrontierMap& stepped = maps[m];
        ASSERT_EQ(stepped.status(), exact.status()) << "trial " << trial << " round " << round;
        ASSERT_EQ(stepped.target(), exact.target()) << "trial " << trial << " round " << round;
        ASSERT_TRUE(std::ranges::equal(stepped.approach_cells(), exact.approach_cells()))
            << "trial " << trial << " round " << round;
        if (exact.status() == ExplorationStatus::kTarget) {
          const FrontierGroup& a = stepped.groups()[stepped.target()];
          const FrontierGroup& b = exact.groups()[exact.target()];
          EXPECT_EQ(a.rho_m, b.rho_m);
          EXPECT_EQ(a.nearest_cell, b.nearest_cell);
        } else {
          EXPECT_EQ(stepped.given_up_groups(), exact.given_up_groups());
        }
      }
      if (exact.status() != ExplorationStatus::kTarget) {
        ++completes;
        break;
      }
      ++targets;
      const std::uint32_t chosen = exact.target();
      for (FrontierMap& map : maps) map.give_up(chosen);
    }
  }
  EXPECT_GT(targets, 300);  // the maps gave both outcomes, many times
  EXPECT_GT(completes, 5);
}

TEST(FrontierSearch, AGroupsRhoIsItsCheapestApproachInSight) {
  // GIVEN random known spaces and robots, the robot's wavefront on cells and (every other map)
  // on blocks of 3 x 3 cells, run to the end
  Random random(5);
  int measured = 0;
  for (int trial = 0; trial < 60; ++trial) {
    const OccupancyGrid grid = random_known_space(random);
    const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
    int rx = 0;
    int ry = 0;
    do {
      rx = static_cast<int>(random.below(120));
      ry = static_cast<int>(random.below(80));
    } while (grid.at(rx, ry) != Cell::kFree);
    FrontierConfig config;
    config.search_step_m = 0.0;
    if (trial % 2 == 1) on_blocks_of_3(config);
    FrontierMap frontiers = FrontierMap::create(120, 80, 0.1, config).value();
    // WHEN it measures every group
    frontiers.update(grid, clearance, grid.cell_center_x(rx), grid.cell_center_y(ry));
    // THEN each group's rho is, by brute force over its cells and their approach windows, the
    // least wavefront cost of a chassis cell (or the robot's own) in sight of the cell plus the
    // straight line to it, given by its first cell that has it
    const DistanceField& field = frontiers.robot_field();
    ASSERT_EQ(field.block(), trial % 2 == 1 ? 3 : 1);
    const std::uint32_t min_d2 = clearance.squared_cells_at_least(config.clearance_m);
    const int reach = static_cast<int>(config.approach_range_m / 0.1) + 1;
    const double reach_cells = config.approach_range_m / 0.1;
    for (const FrontierGroup& group : frontiers.groups()) {
      std::uint32_t best = DistanceField::kUnreachable;
      std::uint32_t nearest = FrontierGroup::kNoCell;
      for (std::uint32_t i = group.first; i < group.first + group.size; ++i) {
        const std::uint32_t c = frontiers.frontier_cells()[i];
        const int cx = grid.cell_x(c);
        const int cy = grid.cell_y(c);
        for (int y = cy - reach; y <= cy + reach; ++y) {
          for (int x = cx - reach; x <= cx + reach; ++x) {
            if (!grid.in_bounds(x, y) || std::hypot(x - cx, y - cy) > reach_cells) continue;
            const std::uint32_t a = grid.index(x, y);
            const bool chassis =
                grid.at(x, y) == Cell::kFree && clearance.squared_cells()[a] >= min_d2;
            if (!(chassis || (x == rx && y == ry)) || !field.reachable(a) ||
                !cell_visible(grid, grid.cell_center_x(x), grid.cell_center_y(y), cx, cy, 1.0)) {
              continue;
            }
            const auto straight = static_cast<std::uint32_t>(
                std::lround(std::hypot(x - cx, y - cy) * DistanceField::kCostUnitsPerCell));
            if (field.cost_at(a) + straight < best) {
              best = field.cost_at(a) + straight;
              nearest = c;
            }
          }
        }
      }
      ASSERT_TRUE(group.searched);
      EXPECT_EQ(group.nearest_cell, nearest) << "trial " << trial;
      if (best == DistanceField::kUnreachable) {
        EXPECT_FALSE(group.reachable()) << "trial " << trial;
      } else {
        EXPECT_EQ(group.rho_m, best * (0.1 / DistanceField::kCostUnitsPerCell))
            << "trial " << trial;
        ++measured;
      }
    }
  }
  EXPECT_GT(measured, 300);  // many groups were reachable
}

TEST(FrontierSearch, OnBlocksTheStraightLineBoundAllowsForABlocksDiagonal) {
  // GIVEN open rooms with small unknown pockets at random, and the robot's wavefront on blocks
  // of 5 x 5 cells (a clearance of 1 m allows 0.5 m), where a path of blocks may be shorter than
  // the straight line between its cells by up to a block's diagonal
  Random random(7);
  for (int trial = 0; trial < 1200; ++trial) {
    OccupancyGrid grid = OccupancyGrid::create(120, 80, 0.1, 0.0, 0.0, Cell::kObstacle).value();
    grid.fill_rect(0.3, 0.3, 11.7, 7.7, Cell::kFree);
    // One pocket on the robot's row (where a block path is no longer than the straight line
    // but its cells' offsets in their blocks are not counted), one anywhere.
    const double rx = random.uniform(1.5, 10.5);
    const double ry = random.uniform(1.5, 6.5);
    const double bx = random.uniform(1.5, 10.5);
    grid.fill_rect(bx, ry, bx + 0.1, ry + 0.1, Cell::kUnknown);
    const double ax = random.uniform(1.5, 10.5);
    const double ay = random.uniform(1.5, 6.5);
    grid.fill_rect(ax, ay, ax + 0.1, ay + 0.1, Cell::kUnknown);
    const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
    FrontierConfig config;
    config.clearance_m = 1.0;
    config.approach_range_m = 1.2;
    config.rho_cell_m = 0.5;
    config.size_weight = 0.0;
    config.search_step_m = 0.0;
    FrontierMap exact = FrontierMap::create(120, 80, 0.1, config).value();
    config.search_step_m = 0.1;
    FrontierMap stepped = FrontierMap::create(120, 80, 0.1, config).value();
    // WHEN both choose THEN they choose alike
    ASSERT_EQ(stepped.update(grid, clearance, rx, ry), exact.update(grid, clearance, rx, ry));
    ASSERT_EQ(stepped.target(), exact.target()) << "trial " << trial;
  }
}

TEST(FrontierSearch, ANearTargetLeavesTheFarKnownSpaceUnsearched) {
  // GIVEN a 40 m x 40 m known hall and an unknown pocket 2 m from the robot
  OccupancyGrid grid = OccupancyGrid::create(400, 400, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.3, 0.3, 39.7, 39.7, Cell::kFree);
  grid.fill_rect(4.0, 3.0, 4.5, 3.5, Cell::kUnknown);
  const ClearanceMap clearance = ClearanceMap::create_for(grid).value();
  FrontierMap stepped = FrontierMap::create(400, 400, 0.1, FrontierConfig{}).value();
  // WHEN it chooses
  ASSERT_EQ(stepped.update(grid, clearance, 2.0, 3.0), ExplorationStatus::kTarget);
  // THEN the pocket is the target and the wavefront stopped short of the far corner
  EXPECT_LT(stepped.groups()[stepped.target()].rho_m, 2.5);
  EXPECT_NE(stepped.robot_field().settled_limit(), DistanceField::kUnreachable);
  EXPECT_FALSE(stepped.robot_field().reachable(grid.index(350, 350)));
  // where one wavefront over everything goes
  FrontierConfig config;
  config.search_step_m = 0.0;
  FrontierMap exact = FrontierMap::create(400, 400, 0.1, config).value();
  ASSERT_EQ(exact.update(grid, clearance, 2.0, 3.0), ExplorationStatus::kTarget);
  EXPECT_TRUE(exact.robot_field().reachable(grid.index(350, 350)));
  EXPECT_TRUE(std::ranges::equal(stepped.approach_cells(), exact.approach_cells()));
}

TEST(FrontierConfigTest, BadValuesAreRefusedByName) {
  FrontierConfig config;
  config.approach_range_m = 0.3;  // not beyond the clearance
  const auto made = FrontierMap::create(10, 10, 0.1, config);
  ASSERT_FALSE(made.ok());
  EXPECT_NE(made.error().message.find("approach_range_m"), std::string::npos);
  config = FrontierConfig{};
  config.size_weight = -1.0;
  EXPECT_FALSE(FrontierMap::create(10, 10, 0.1, config).ok());
  config = FrontierConfig{};
  config.min_group_cells = 0;
  EXPECT_FALSE(FrontierMap::create(10, 10, 0.1, config).ok());
  config = FrontierConfig{};
  config.give_up_radius_m = std::nan("");
  const auto nan_radius = FrontierMap::create(10, 10, 0.1, config);
  ASSERT_FALSE(nan_radius.ok());
  EXPECT_NE(nan_radius.error().message.find("give_up_radius_m"), std::string::npos);
  config = FrontierConfig{};
  config.search_step_m = -1.0;
  const auto negative_step = FrontierMap::create(10, 10, 0.1, config);
  ASSERT_FALSE(negative_step.ok());
  EXPECT_NE(negative_step.error().message.find("search_step_m"), std::string::npos);
  EXPECT_FALSE(FrontierMap::create(0, 10, 0.1, FrontierConfig{}).ok());
}

}  // namespace
}  // namespace grip
