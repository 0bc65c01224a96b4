// KinematicReach: where a car can take its reference point, forward and reversing, on
// hand-drawn maps; and ExplorationTarget passing over a frontier the car cannot turn into while a
// vehicle that turns in place is sent to it. Two cars: the paper's (0.75 m x 0.4 m, turning
// radius 0.5 m) and the compact car of tools/params/examples (1.2 m x 0.6 m, 0.9 m).

#include "grip/exploration/kinematic_reach.hpp"

#include <gtest/gtest.h>

#include "grip/exploration/exploration_target.hpp"
#include "grip/vehicles/car.hpp"

namespace grip {
namespace {

constexpr double kPi = 3.14159265358979323846;

KinematicReachConfig car_config() {
  const Car car = Car::create(CarParams{}).value();
  KinematicReachConfig config;
  config.turning_radius_m = car.min_turning_radius_m();
  config.footprint = car.footprint();
  return config;
}

// tools/params/examples/compact-car.yaml: wheelbase 0.9 m at 45 degrees of lock.
KinematicReachConfig compact_car_config() {
  KinematicReachConfig config;
  config.turning_radius_m = 0.9;
  config.footprint = Footprint{0.95, 0.25, 0.3};
  return config;
}

bool passed_at(const KinematicReach& reach, const OccupancyGrid& grid, double x, double y) {
  int cx = 0;
  int cy = 0;
  return grid.to_cell(x, y, cx, cy) && reach.passed(grid.index(cx, cy));
}

// Runs the search to its end from the car's pose.
void search(KinematicReach& reach, const OccupancyGrid& grid, double x, double y, double theta) {
  reach.update(CellBox{0, 0, grid.width() - 1, grid.height() - 1}, x, y, theta);
  for (int i = 0; i < 100 && !reach.complete(); ++i) reach.update(CellBox{}, x, y, theta);
  ASSERT_TRUE(reach.complete());
}

// Chooses from (x, y), facing east, a choice every 0.1 s, until the car's search is complete;
// the last choice's status (kRobotOutsideGrid when the search never completed).
ExplorationStatus choose_until_searched(ExplorationTarget& car, double x, double y) {
  const KinematicReach* kinematics = car.kinematics();
  if (kinematics == nullptr) return ExplorationStatus::kRobotOutsideGrid;
  for (int i = 0; i < 100; ++i) {
    const ExplorationStatus status = car.choose(x, y, 0.0, i * 100'000'000);
    if (kinematics->complete()) return status;
  }
  return ExplorationStatus::kRobotOutsideGrid;
}

// Obstacles everywhere but a corridor along y = 2 m, `main_width_m` wide from x = 0.5 to 9 m,
// and a side branch 0.8 m wide going north from x = 4 m to y = 7 m; 0.1 m cells. The compact car
// fits in either (0.1 m a side), and a point 0.3 m from every wall passes into the branch.
OccupancyGrid corridor_with_branch(double main_width_m) {
  OccupancyGrid grid = OccupancyGrid::create(100, 80, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.5, 2.0 - main_width_m / 2, 9.0, 2.0 + main_width_m / 2, Cell::kFree);
  grid.fill_rect(4.0, 2.0, 4.8, 7.0, Cell::kFree);
  return grid;
}

TEST(KinematicReach, TheCarReachesEveryCornerOfARoomButNotTheRoomBehindAWall) {
  // GIVEN a 5 m room and, behind a wall with no gap, another one
  OccupancyGrid grid = OccupancyGrid::create(120, 60, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.5, 0.5, 5.5, 5.5, Cell::kFree);
  grid.fill_rect(6.0, 0.5, 11.5, 5.5, Cell::kFree);
  KinematicReach reach = KinematicReach::create(grid, car_config()).value();
  // WHEN the car, facing east in the middle of the first, is searched from
  search(reach, grid, 3.0, 3.0, 0.0);
  // THEN its reference point gets near every corner (the chassis keeps it 0.2 m from side
  // walls and 0.6 m behind the front one) and never into the second room
  EXPECT_TRUE(passed_at(reach, grid, 1.0, 1.0));
  EXPECT_TRUE(passed_at(reach, grid, 5.0, 1.0));
  EXPECT_TRUE(passed_at(reach, grid, 1.0, 5.0));
  EXPECT_TRUE(passed_at(reach, grid, 5.0, 5.0));
  for (double x = 5.6; x < 12.0; x += 0.1) {
    for (double y = 0.0; y < 6.0; y += 0.1) ASSERT_FALSE(passed_at(reach, grid, x, y)) << x;
  }
  EXPECT_GT(reach.states_reached(), 1000U);
}

TEST(KinematicReach, FacingTheEndOfACorridorTheCarReversesToItsOtherEnd) {
  // GIVEN a corridor 0.8 m wide, too narrow for a U-turn, the car near its east end facing it
  OccupancyGrid grid = OccupancyGrid::create(90, 20, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.5, 0.6, 8.5, 1.4, Cell::kFree);
  KinematicReach reach = KinematicReach::create(grid, car_config()).value();
  // WHEN searched
  search(reach, grid, 7.5, 1.0, 0.0);
  // THEN the west end is reached (backing up all the way)
  EXPECT_TRUE(passed_at(reach, grid, 1.0, 1.0));
}

TEST(KinematicReach, ABranchTooNarrowToTurnIntoFromANarrowCorridorIsNotReached) {
  // GIVEN the compact car in a corridor 0.8 m wide, which a branch as wide leaves at a right
  // angle (a 1.2 m x 0.6 m rectangle cannot even be rotated round that corner)
  const OccupancyGrid narrow = corridor_with_branch(0.8);
  KinematicReach reach = KinematicReach::create(narrow, compact_car_config()).value();
  // WHEN searched from its west end, facing east
  search(reach, narrow, 1.5, 2.0, 0.0);
  // THEN it drives the corridor to its east end and back but never gets into the branch
  EXPECT_TRUE(passed_at(reach, narrow, 7.5, 2.0));
  EXPECT_TRUE(passed_at(reach, narrow, 0.9, 2.0));
  EXPECT_FALSE(passed_at(reach, narrow, 4.4, 3.5));
  EXPECT_FALSE(passed_at(reach, narrow, 4.4, 6.0));
}

TEST(KinematicReach, TheSameBranchOffAWideCorridorIsReached) {
  // GIVEN the same branch off a corridor 3 m wide, where the car has room to swing into it
  const OccupancyGrid wide = corridor_with_branch(3.0);
  KinematicReach reach = KinematicReach::create(wide, compact_car_config()).value();
  // WHEN searched as before
  search(reach, wide, 1.5, 2.0, 0.0);
  // THEN the branch's far end is reached
  EXPECT_TRUE(passed_at(reach, wide, 4.4, 6.0));
}

TEST(KinematicReach, TheSearchGoesOnWhereTheMapOpensUp) {
  // GIVEN the narrow corridor, searched to its end, then widened to 3 m (newly sensed space)
  OccupancyGrid grid = corridor_with_branch(0.8);
  KinematicReach reach = KinematicReach::create(grid, compact_car_config()).value();
  search(reach, grid, 1.5, 2.0, 0.0);
  ASSERT_FALSE(passed_at(reach, grid, 4.4, 6.0));
  grid.fill_rect(0.5, 0.5, 9.0, 3.5, Cell::kFree);
  // WHEN told where the map changed, the car standing where it started
  int x0 = 0;
  int y0 = 0;
  int x1 = 0;
  int y1 = 0;
  ASSERT_TRUE(grid.to_cell(0.5, 0.5, x0, y0) && grid.to_cell(8.99, 3.49, x1, y1));
  reach.update(CellBox{x0, y0, x1, y1}, 1.5, 2.0, 0.0);
  for (int i = 0; i < 100 && !reach.complete(); ++i) reach.update(CellBox{}, 1.5, 2.0, 0.0);
  // THEN the branch is reached as if the map had been wide from the start
  ASSERT_TRUE(reach.complete());
  EXPECT_TRUE(passed_at(reach, grid, 4.4, 6.0));
}

TEST(KinematicReach, EachUpdateExpandsAtMostItsBudget) {
  OccupancyGrid grid = OccupancyGrid::create(120, 120, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  grid.fill_rect(0.5, 0.5, 11.5, 11.5, Cell::kFree);
  KinematicReachConfig config = car_config();
  config.max_expansions = 100;
  KinematicReach reach = KinematicReach::create(grid, config).value();
  reach.update(CellBox{0, 0, 119, 119}, 6.0, 6.0, kPi / 2);
  // A state expanded reaches at most its six moves' ends.
  EXPECT_FALSE(reach.complete());
  EXPECT_LE(reach.states_reached(), 1U + 100U * 6U);
  int updates = 1;
  for (; updates < 100'000 && !reach.complete(); ++updates) reach.update(CellBox{}, 6.0, 6.0, 0.0);
  EXPECT_TRUE(reach.complete());
  EXPECT_TRUE(passed_at(reach, grid, 1.5, 1.5));
}

TEST(KinematicReach, BadConfigurationsAreRefusedByName) {
  const OccupancyGrid grid = corridor_with_branch(3.0);
  KinematicReachConfig config = car_config();
  config.turning_radius_m = 0.0;
  auto made = KinematicReach::create(grid, config);
  ASSERT_FALSE(made);
  EXPECT_NE(made.error().message.find("turning_radius_m"), std::string::npos);
  config = car_config();
  config.max_expansions = 0;
  made = KinematicReach::create(grid, config);
  ASSERT_FALSE(made);
  EXPECT_NE(made.error().message.find("max_expansions"), std::string::npos);
  config = car_config();
  config.footprint.half_width_m = -1.0;
  EXPECT_FALSE(KinematicReach::create(grid, config));
}

// Issue 23's "a dead end the car cannot turn in, recognised": the only frontier lies up the
// narrow branch, 2 m in (unknown beyond y = 4 m): farther from the corridor than the compact
// car's nose reaches, 0.95 m ahead of its reference point, plus the approach range.
TEST(KinematicReach, ExplorationPassesOverAFrontierTheCarCannotTurnIntoAndSaysSo) {
  OccupancyGrid map = corridor_with_branch(0.8);
  map.fill_rect(4.0, 4.0, 4.8, 7.0, Cell::kUnknown);
  ExplorationTargetConfig config;
  // A vehicle that turns in place is sent up the branch...
  auto point = ExplorationTarget::create(map, config).value();
  ASSERT_EQ(point.choose(1.5, 2.0, 0.0, 0), ExplorationStatus::kTarget);
  EXPECT_NEAR(point.target_x_m(), 4.4, 0.4);
  EXPECT_NEAR(point.target_y_m(), 4.0, 0.2);
  EXPECT_EQ(point.unreachable_groups(), 0U);
  // ...the car is not: once its search is complete, nothing reachable is left, and the group
  // is counted as out of its reach, not given up on after a minute.
  config.kinematics = compact_car_config();
  auto car = ExplorationTarget::create(map, config).value();
  EXPECT_EQ(choose_until_searched(car, 1.5, 2.0), ExplorationStatus::kComplete);
  EXPECT_EQ(car.unreachable_groups(), 1U);
  EXPECT_EQ(car.given_up_groups(), 0U);
}

// The car cannot bring its reference point within the approach range of unknown space straight
// ahead in a corridor too narrow to turn in (its nose would be in it first), but driving up to
// it is what uncovers it: that frontier stays a target.
TEST(KinematicReach, UnknownSpaceAheadInANarrowCorridorStaysATarget) {
  OccupancyGrid map = OccupancyGrid::create(100, 40, 0.1, 0.0, 0.0, Cell::kObstacle).value();
  map.fill_rect(0.5, 1.6, 9.5, 2.4, Cell::kFree);
  map.fill_rect(5.0, 1.6, 9.5, 2.4, Cell::kUnknown);
  ExplorationTargetConfig config;
  config.kinematics = car_config();
  auto car = ExplorationTarget::create(map, config).value();
  EXPECT_EQ(choose_until_searched(car, 1.5, 2.0), ExplorationStatus::kTarget);
  EXPECT_EQ(car.unreachable_groups(), 0U);
  EXPECT_NEAR(car.target_x_m(), 4.95, 0.1);
}

}  // namespace
}  // namespace grip
