// ExplorationTarget: the frontier target chosen from its own copy of the map, and when a target
// the vehicle gets no closer to is given up (vehicle time, no clock involved).

#include "grip/exploration/exploration_target.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <optional>
#include <vector>

#include "grip/common/random.hpp"

namespace grip {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

// Known free space below y = 2.5 m and unknown above, an obstacle on the border between x = 3
// and 4.5 m splitting the frontier into two groups (as in frontier_test.cpp), 0.1 m cells.
OccupancyGrid two_frontiers() {
  OccupancyGrid grid = OccupancyGrid::create(80, 40, 0.1, 0.0, 0.0, Cell::kUnknown).value();
  grid.fill_rect(0.0, 0.0, 8.0, 2.5, Cell::kFree);
  grid.fill_rect(2.98, 2.32, 4.52, 2.6, Cell::kObstacle);
  return grid;
}

std::vector<std::uint32_t> sorted(std::span<const std::uint32_t> cells) {
  std::vector<std::uint32_t> v(cells.begin(), cells.end());
  std::sort(v.begin(), v.end());
  return v;
}

class ExplorationTargetTest : public ::testing::Test {
 protected:
  OccupancyGrid map = two_frontiers();
  ExplorationTargetConfig config;
  std::optional<ExplorationTarget> target;

  void SetUp() override {
    config.give_up_after_s = 60.0;
    target.emplace(ExplorationTarget::create(map, config).value());
  }
};

TEST_F(ExplorationTargetTest, ChoosesWhatTheFrontierMapChoosesOnItsCopyOfTheMap) {
  // GIVEN the same map given to a FrontierMap directly
  ClearanceMap clearance = ClearanceMap::create_for(map).value();
  FrontierMap frontiers = FrontierMap::create(80, 40, 0.1, config.frontier).value();
  ASSERT_EQ(frontiers.update(map, clearance, 1.0, 1.0), ExplorationStatus::kTarget);

  // WHEN the target is chosen for a robot at the same place
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 0), ExplorationStatus::kTarget);

  // THEN it is the same group, approached from the same cells, and its position is the centre of
  // the group's cell nearest to the robot
  EXPECT_EQ(sorted(target->target_cells()), sorted(frontiers.target_cells()));
  EXPECT_EQ(sorted(target->approach_cells()), sorted(frontiers.approach_cells()));
  EXPECT_EQ(target->groups(), 2U);
  const FrontierGroup& group = frontiers.groups()[frontiers.target()];
  EXPECT_DOUBLE_EQ(target->target_x_m(), map.cell_center_x(map.cell_x(group.nearest_cell)));
  EXPECT_DOUBLE_EQ(target->target_y_m(), map.cell_center_y(map.cell_y(group.nearest_cell)));
  // AND rho toward the approach cells is the planner's (the frontier clearance as inflation)
  DistanceField rho = DistanceField::create(80, 40, 0.1).value();
  rho.compute(map, clearance, frontiers.approach_cells(), config.frontier.clearance_m);
  for (std::uint32_t c = 0; c < map.cell_count(); ++c) {
    const double x = map.cell_center_x(map.cell_x(c));
    const double y = map.cell_center_y(map.cell_y(c));
    ASSERT_DOUBLE_EQ(target->rho().distance_m(x, y), rho.distance_m(x, y)) << x << ", " << y;
  }
}

TEST_F(ExplorationTargetTest, ReadsOnlyTheMapCopiedIntoIt) {
  // GIVEN a first choice, and then the unknown part of the caller's map sensed as a wall
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 0), ExplorationStatus::kTarget);
  map.fill_rect(0.0, 2.5, 8.0, 4.0, Cell::kObstacle);
  // WHEN it chooses again before the map is copied in THEN the old map still has frontiers
  EXPECT_EQ(target->choose(1.0, 1.0, 0.0, kSecond), ExplorationStatus::kTarget);
  // WHEN the map is copied in THEN nothing is left to explore
  target->copy_map(map);
  EXPECT_EQ(target->choose(1.0, 1.0, 0.0, 2 * kSecond), ExplorationStatus::kComplete);
  EXPECT_EQ(target->status(), ExplorationStatus::kComplete);
  EXPECT_TRUE(target->target_cells().empty());
}

TEST(ExplorationTargetCopies, CopyingOnlyTheCellsWrittenChoosesAsATargetMadeFromTheWholeMap) {
  // Random sequences of map changes (sensed rectangles of free, obstacle or unknown space),
  // each copied in by its box only (its clearance updated near them), against a target created
  // from the whole map (clearance computed from scratch): the same status, groups, target and
  // approach cells and rho, choice after choice. (No give-up clock runs out in 15 s: a robot
  // beside a frontier that stays gives it up after give_up_reached_after_s, set to 60 s.) Its rho
  // goes to a planner and comes back as the planner's adopt_goal swaps them, now and then
  // recomputed by the planner on a map of its own. Seeds 7-12 with rho on blocks of 2 x 2 cells
  // (a clearance of 0.4 m allows 0.2 m), even seeds with rho cut off 2 m past the robot.
  for (std::uint64_t seed = 1; seed <= 12; ++seed) {
    SCOPED_TRACE(seed);
    Random rng(seed);
    OccupancyGrid map = two_frontiers();
    ExplorationTargetConfig config;
    config.give_up_reached_after_s = 60.0;
    config.rho_margin_m = seed % 2 == 0 ? 2.0 : 20.0;  // rho cut off short of the map, or not
    if (seed > 6) {
      config.frontier.clearance_m = 0.4;
      config.frontier.approach_range_m = 0.6;
      config.frontier.rho_cell_m = 0.2;
    }
    auto incremental = ExplorationTarget::create(map, config).value();
    const OccupancyGrid planners_map = map;
    DistanceField planners_rho = DistanceField::create(80, 40, 0.1, seed > 6 ? 2 : 1).value();
    ASSERT_EQ(incremental.rho().block(), planners_rho.block());
    for (int round = 0; round < 15; ++round) {
      CellBox written;
      for (int write = 0, n = 1 + static_cast<int>(rng.below(3)); write < n; ++write) {
        const int x0 = static_cast<int>(rng.below(75));
        const int y0 = static_cast<int>(rng.below(35));
        const CellBox box{x0, y0, x0 + static_cast<int>(rng.below(12)),
                          y0 + static_cast<int>(rng.below(12))};
        // Mostly free space, as a sensor sweep reveals it.
        const std::uint64_t draw = rng.below(4);
        const Cell value = draw < 2 ? Cell::kFree : static_cast<Cell>(draw - 1);
        for (int y = box.y0; y <= std::min(box.y1, 39); ++y)
          for (int x = box.x0; x <= std::min(box.x1, 79); ++x) map.set(x, y, value);
        written.add(box);
      }
      incremental.copy_map(map, written);
      auto whole = ExplorationTarget::create(map, config).value();
      const std::int64_t now = round * kSecond;
      const ExplorationStatus status = whole.choose(1.0, 1.0, 0.0, now);
      ASSERT_EQ(incremental.choose(1.0, 1.0, 0.0, now), status) << "round " << round;
      ASSERT_EQ(incremental.groups(), whole.groups());
      ASSERT_EQ(sorted(incremental.target_cells()), sorted(whole.target_cells()));
      ASSERT_EQ(sorted(incremental.approach_cells()), sorted(whole.approach_cells()));
      if (status != ExplorationStatus::kTarget) continue;
      for (std::uint32_t c = 0; c < map.cell_count(); ++c) {
        const double x = map.cell_center_x(map.cell_x(c));
        const double y = map.cell_center_y(map.cell_y(c));
        ASSERT_EQ(incremental.rho().distance_m(x, y), whole.rho().distance_m(x, y))
            << "round " << round << " at " << x << ", " << y;
      }
      if (rng.below(4) == 0) {
        const ClearanceMap clearance = ClearanceMap::create_for(planners_map).value();
        planners_rho.compute(planners_map, clearance, incremental.approach_cells(),
                             config.frontier.clearance_m);
      }
      std::swap(planners_rho, incremental.rho());
    }
  }
}

TEST(ExplorationTargetRho, RhoIsExactOutToTheVehiclesOwnPlusTheMarginAndThatFarBeyond) {
  // GIVEN a corridor 50 m long and 1.5 m wide, unknown past its east end, the vehicle 5 m from
  // that frontier, and a margin of 8 m
  OccupancyGrid map = OccupancyGrid::create(600, 20, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  map.fill_rect(0.0, 0.0, 50.0, 1.5, Cell::kFree);
  map.fill_rect(50.0, 0.0, 60.0, 1.5, Cell::kUnknown);
  ExplorationTargetConfig config;
  config.rho_margin_m = 8.0;
  auto target = ExplorationTarget::create(map, config).value();
  // WHEN the target is chosen
  ASSERT_EQ(target.choose(45.0, 0.75, 0.0, 0), ExplorationStatus::kTarget);
  // THEN rho equals the whole wavefront's out to the vehicle's rho plus the margin
  ClearanceMap clearance = ClearanceMap::create_for(map).value();
  DistanceField whole = DistanceField::create(600, 20, 0.1).value();
  whole.compute(map, clearance, target.approach_cells(), config.frontier.clearance_m);
  const double own_m = whole.distance_m(45.0, 0.75);
  ASSERT_NEAR(own_m, 4.5, 0.6);
  const DistanceField& rho = target.rho();
  ASSERT_NE(rho.beyond_cost(), DistanceField::kUnreachable);
  const double beyond_m = rho.beyond_cost() * (0.1 / DistanceField::kCostUnitsPerCell);
  EXPECT_GE(beyond_m, own_m + config.rho_margin_m - 0.6);
  EXPECT_LT(beyond_m, own_m + config.rho_margin_m + 0.6);
  int exact = 0;
  int beyond = 0;
  for (double x = 0.45; x < 49.6; x += 0.1) {  // cells the chassis can occupy
    const double full = whole.distance_m(x, 0.75);
    if (full < beyond_m) {
      ASSERT_EQ(rho.distance_m(x, 0.75), full) << x;
      ++exact;
    } else {
      // AND farther cells, which the wavefront did not reach, read that far
      ASSERT_EQ(rho.distance_m(x, 0.75), beyond_m) << x;
      ++beyond;
    }
  }
  EXPECT_GT(exact, 100);
  EXPECT_GT(beyond, 300);
  // AND cells the chassis cannot occupy stay unreachable
  EXPECT_EQ(rho.distance_m(45.0, 0.05), std::numeric_limits<double>::infinity());
  EXPECT_EQ(rho.distance_m(5.0, 0.05), std::numeric_limits<double>::infinity());
}

TEST_F(ExplorationTargetTest, ATargetWithoutProgressIsGivenUpAfterTheConfiguredTime) {
  // GIVEN a robot that stays where it is on an unchanged map
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 0), ExplorationStatus::kTarget);
  const std::vector<std::uint32_t> first = sorted(target->target_cells());
  // WHEN just under the give-up time has passed THEN the target stands
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 60 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(sorted(target->target_cells()), first);
  EXPECT_EQ(target->given_up_groups(), 0U);
  // WHEN more than that has passed THEN it is given up, and the next choice is the other group
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 61 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 62 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
  EXPECT_NE(sorted(target->target_cells()), first);
  // AND when that one is given up too, both are taken back once (retry_rounds: 1): the best
  // group is the target again
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 123 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 124 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  EXPECT_EQ(sorted(target->target_cells()), first);
  // AND when both are given up again, exploration ends and says why
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 185 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 186 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 247 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->choose(1.0, 1.0, 0.0, 248 * kSecond), ExplorationStatus::kComplete);
  EXPECT_EQ(target->given_up_groups(), 2U);
}

TEST_F(ExplorationTargetTest, WithoutRetryRoundsTheFirstTimeEverythingIsGivenUpEndsExploration) {
  config.retry_rounds = 0;
  target.emplace(ExplorationTarget::create(map, config).value());
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 0), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 61 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 62 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.0, 0.0, 123 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->choose(1.0, 1.0, 0.0, 124 * kSecond), ExplorationStatus::kComplete);
  EXPECT_EQ(target->given_up_groups(), 2U);
}

TEST_F(ExplorationTargetTest, ProgressOrANewMapRestartsTheGiveUpClock) {
  // GIVEN a target chosen for a robot far from it
  ASSERT_EQ(target->choose(0.5, 0.5, 0.0, 0), ExplorationStatus::kTarget);
  const std::vector<std::uint32_t> first = sorted(target->target_cells());
  // WHEN the robot comes closer by more than progress_m within the give-up time
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 50 * kSecond), ExplorationStatus::kTarget);
  // THEN the clock restarts there: 100 s after the start, the target still stands
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 100 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  EXPECT_EQ(sorted(target->target_cells()), first);
  // WHEN the map changes (newly sensed cells) THEN the clock restarts too
  target->copy_map(map);
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 150 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 200 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  // AND without either, it is given up once the time has passed
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 211 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(0.5, 1.5, 0.0, 212 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
}

TEST_F(ExplorationTargetTest, ATargetReachedThatStaysAFrontierIsGivenUpAfterItsOwnShorterTime) {
  // GIVEN a robot that stands 0.35 m from the nearest frontier cell on a map
  // that does not change (its sensor does not resolve the cell)
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 0), ExplorationStatus::kTarget);
  const std::vector<std::uint32_t> first = sorted(target->target_cells());
  // WHEN give_up_reached_after_s (3 s) has passed THEN the target still stands
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 3 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(sorted(target->target_cells()), first);
  EXPECT_EQ(target->given_up_groups(), 0U);
  // WHEN more than that has passed THEN it is given up, long before the 60 s of give_up_after_s,
  // and the next choice is the other group
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 3 * kSecond + 1), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 4 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
  EXPECT_NE(sorted(target->target_cells()), first);
  // AND the other group, 2 m away, is not reached: it stands for as long as the robot could still
  // come closer (until give_up_after_s)
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 60 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
}

TEST_F(ExplorationTargetTest, AReachedTargetWhoseNearestCellChangesIsNotGivenUp) {
  // GIVEN a robot within reach of the frontier, moving along it: each choice has another nearest
  // cell (as when the cells it reached are sensed and the next ones are nearest)
  ASSERT_EQ(target->choose(0.5, 2.1, 0.0, 0), ExplorationStatus::kTarget);
  const std::vector<std::uint32_t> first = sorted(target->target_cells());
  ASSERT_EQ(target->choose(1.5, 2.1, 0.0, 2 * kSecond), ExplorationStatus::kTarget);
  // WHEN more than give_up_reached_after_s has passed since it first reached the group, but not
  // since it reached the cell nearest now THEN the target stands
  ASSERT_EQ(target->choose(1.5, 2.1, 0.0, 4 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.5, 2.1, 0.0, 5 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  EXPECT_EQ(sorted(target->target_cells()), first);
  // AND once it stands at one cell for longer, it is given up
  ASSERT_EQ(target->choose(1.5, 2.1, 0.0, 5 * kSecond + kSecond / 10), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.5, 2.1, 0.0, 6 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
}

TEST_F(ExplorationTargetTest, AVehicleSwayingAcrossTheEdgeOfTheRangeStillReachesTheTarget) {
  // GIVEN a robot stopped where its nearest frontier cell is at the edge of the approach range
  // (0.5 m), swaying across it: 0.35 m and 0.65 m away in turn
  const std::vector<std::int64_t> times = {0, kSecond, 2 * kSecond, 3 * kSecond};
  for (std::size_t i = 0; i < times.size(); ++i) {
    ASSERT_EQ(target->choose(1.0, i % 2 == 0 ? 2.1 : 1.8, 0.0, times[i]),
              ExplorationStatus::kTarget);
  }
  const std::vector<std::uint32_t> first = sorted(target->target_cells());
  EXPECT_EQ(target->given_up_groups(), 0U);
  // WHEN more than give_up_reached_after_s has passed since it first came within the range THEN
  // the target is given up
  ASSERT_EQ(target->choose(1.0, 1.8, 0.0, 3 * kSecond + 1), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.8, 0.0, 4 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
  EXPECT_NE(sorted(target->target_cells()), first);
}

TEST_F(ExplorationTargetTest, AVehicleThatLeavesTwiceTheRangeReachesTheTargetAfresh) {
  // GIVEN a robot that reached the frontier, then drove 1.25 m away from it and came back
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 0), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 1.2, 0.0, 2 * kSecond), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 3 * kSecond), ExplorationStatus::kTarget);
  // WHEN more than give_up_reached_after_s has passed since it first reached it, but not since
  // it came back THEN the target stands
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 5 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  // AND 3 s after it came back it is given up
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 6 * kSecond + 1), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.0, 2.1, 0.0, 7 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
}

TEST_F(ExplorationTargetTest, AVehicleOnAnApproachCellIsThereEvenBeyondTheRangeOfEveryCell) {
  // GIVEN a robot 0.54 m from the frontier (the range is 0.5 m) whose cell's centre is 0.5 m from
  // it: the cell is an approach cell (rho 0), so rho can bring the robot no nearer, while the
  // path selector's coarser sight may see no target cell from there
  const double range_m = config.frontier.approach_range_m;
  ASSERT_EQ(target->choose(1.05, 1.91, 0.0, 0), ExplorationStatus::kTarget);
  ASSERT_EQ(target->rho().distance_m(1.05, 1.91), 0.0);
  for (const std::uint32_t c : target->target_cells()) {
    ASSERT_GT(std::hypot(map.cell_center_x(map.cell_x(c)) - 1.05,
                         map.cell_center_y(map.cell_y(c)) - 1.91),
              range_m);
  }
  // WHEN it stands there for give_up_reached_after_s (3 s) THEN the target still stands
  ASSERT_EQ(target->choose(1.05, 1.91, 0.0, 3 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 0U);
  // WHEN longer THEN it is given up as reached, long before give_up_after_s (60 s)
  ASSERT_EQ(target->choose(1.05, 1.91, 0.0, 3 * kSecond + 1), ExplorationStatus::kTarget);
  ASSERT_EQ(target->choose(1.05, 1.91, 0.0, 4 * kSecond), ExplorationStatus::kTarget);
  EXPECT_EQ(target->given_up_groups(), 1U);
}

TEST(ExplorationTargetConfig, BadValuesAreRefusedByName) {
  const OccupancyGrid map = two_frontiers();
  ExplorationTargetConfig config;
  config.give_up_after_s = 0.0;
  auto bad = ExplorationTarget::create(map, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("give_up_after_s"), std::string::npos) << bad.error().message;
  config = {};
  config.give_up_reached_after_s = -3.0;
  bad = ExplorationTarget::create(map, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("give_up_reached_after_s"), std::string::npos)
      << bad.error().message;
  config = {};
  config.progress_m = std::nan("");
  bad = ExplorationTarget::create(map, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("progress_m"), std::string::npos) << bad.error().message;
  config = {};
  config.rho_margin_m = 0.0;
  bad = ExplorationTarget::create(map, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("rho_margin_m"), std::string::npos) << bad.error().message;
  config = {};
  config.frontier.size_weight = -1.0;
  bad = ExplorationTarget::create(map, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("size_weight"), std::string::npos) << bad.error().message;
}

}  // namespace
}  // namespace grip
