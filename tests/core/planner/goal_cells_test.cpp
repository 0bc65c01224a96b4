// The goal region F given as a set of grid cells (exploration hands the planner a frontier
// group's approach cells): rho is the distance to those cells, a state is in F when its cell is
// one of them, and bad sets are refused without disturbing the current goal.

#include <gtest/gtest.h>

#include <algorithm>
#include <optional>
#include <vector>

#include "grip/planner/planner.hpp"
#include "test_support.hpp"

namespace grip {
namespace {

class GoalCellsTest : public ::testing::Test {
 protected:
  OccupancyGrid grid = test::room_with_wall();
  DdVelocity robot = DdVelocity::create({}).value();
  std::optional<DdVelocityPlanner> planner;
  std::vector<std::uint32_t> cells;  // a 0.6 m square right of the wall, and a repeat

  void SetUp() override {
    PlannerConfig config;
    config.max_edges = 20'000;
    config.max_trajectories = 10'000;
    config.steps_per_record = 1;  // what retain() needs
    planner.emplace(DdVelocityPlanner::create(robot, grid, config).value());
    for (int y = 17; y < 23; ++y) {
      for (int x = 92; x < 98; ++x) cells.push_back(grid.index(x, y));
    }
    cells.push_back(cells.front());
  }
  bool cell_in_goal(double x, double y) const {
    int cx = 0;
    int cy = 0;
    if (!grid.to_cell(x, y, cx, cy)) return false;
    return std::find(cells.begin(), cells.end(), grid.index(cx, cy)) != cells.end();
  }
};

TEST_F(GoalCellsTest, RhoIsTheDistanceToTheCellsAndTheSolutionEndsInOne) {
  ASSERT_TRUE(planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), Goal::cells(cells)));
  EXPECT_EQ(planner->rho_field().distance_m(9.45, 1.95), 0.0);
  // From the start the way leads around the wall's top end (y = 8): far more than 7.5 m.
  EXPECT_GT(planner->rho_field().distance_m(2.0, 2.0), 12.0);
  (void)planner->solve([] { return false; });  // until the goal (or the pools)
  ASSERT_TRUE(planner->solved());
  const TreeState end = planner->best_state();
  const auto& q = planner->tree().edge_state(end.edge, end.index);
  EXPECT_TRUE(cell_in_goal(q[0], q[1])) << "(" << q[0] << ", " << q[1] << ")";
}

TEST_F(GoalCellsTest, ACellOutsideTheGridOrASetWithoutFreeCellIsRefused) {
  const std::vector<std::uint32_t> outside{grid.cell_count()};
  const auto refused = planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), Goal::cells(outside));
  ASSERT_FALSE(refused.ok());
  EXPECT_NE(refused.error().message.find("outside the grid"), std::string::npos);
  const std::vector<std::uint32_t> in_wall{grid.index(60, 20), grid.index(0, 0)};
  EXPECT_FALSE(planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), Goal::cells(in_wall)).ok());

  // Refused in replanning, the current goal stays.
  ASSERT_TRUE(planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), Goal::cells(cells)));
  EXPECT_EQ(planner->retain(planner->root_state(), Goal::cells(in_wall), 1.0),
            RetainStatus::kGoalWithoutFreeCell);
  EXPECT_EQ(planner->retain(planner->root_state(), Goal::cells(outside), 1.0),
            RetainStatus::kGoalOutsideGrid);
  EXPECT_EQ(planner->rho_field().distance_m(9.45, 1.95), 0.0);
}

TEST_F(GoalCellsTest, ADiskGoalAfterACellGoalIsADiskAgain) {
  ASSERT_TRUE(planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), Goal::cells(cells)));
  const Goal disk = Goal::disk(2.0, 10.0, 0.5);
  ASSERT_TRUE(planner->set_problem(robot.rest_state(2.0, 2.0, 0.0), disk));
  EXPECT_EQ(planner->rho_field().distance_m(2.05, 10.05), 0.0);
  EXPECT_GT(planner->rho_field().distance_m(9.45, 1.95), 0.0);
  (void)planner->solve([] { return false; });
  ASSERT_TRUE(planner->solved());
  const TreeState end = planner->best_state();
  const auto& q = planner->tree().edge_state(end.edge, end.index);
  EXPECT_TRUE(disk.contains(q[0], q[1]));
}

}  // namespace
}  // namespace grip
