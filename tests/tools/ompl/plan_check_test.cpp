// The re-check of returned plans: a real solution passes; collisions, controls outside the
// limits, states the controls do not produce and plans that stop short are all refused.

#include "plan_check.hpp"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

#include "grip/scenes/scenes.hpp"

namespace grip::ompl_bridge {
namespace {

class PlanCheckTest : public ::testing::Test {
 protected:
  PlanCheckTest()
      : vehicle_(DdVelocity::create(DdVelocityParams{}).value()),
        scene_(std::make_unique<Scene>(make_scene(SceneId::kRooms).value())),
        fine_(make_fine_checker(vehicle_, scene_->grid, kDt).value()),
        goal_(Goal::disk(scene_->goal_x_m, scene_->goal_y_m, scene_->goal_radius_m)),
        start_(vehicle_.rest_state(scene_->start_x_m, scene_->start_y_m, scene_->start_theta_rad)) {
  }

  // GRIP's solution of the scene, as pieces, with the planner's states at the pieces' ends.
  void solve(std::vector<PlanPiece>& plan, std::vector<std::array<double, 2>>& ends) {
    PlannerConfig config;
    config.steps_per_record = 1;  // every step recorded: the pieces' ends are recorded states
    auto planner = DdVelocityPlanner::create(vehicle_, scene_->grid, config).value();
    ASSERT_TRUE(planner.set_problem(start_, goal_).ok());
    planner.solve([] { return false; });
    ASSERT_TRUE(planner.solved());
    BoundedVector<PlanStep> steps(4096);
    ASSERT_TRUE(planner.extract_plan(planner.best_state(), steps));
    std::vector<std::array<double, 2>> states;
    planner.visit_path(planner.best_state(), [&](const DdVelocity::State& q) {
      states.push_back({q[0], q[1]});
    });
    std::uint32_t total = 0;
    for (const PlanStep& s : steps) {
      const auto n = static_cast<std::uint32_t>(std::llround(s.duration_s / kDt));
      plan.push_back(PlanPiece{s.control, n});
      total += n;
      ASSERT_LT(total, states.size());
      ends.push_back(states[total]);
    }
  }

  static constexpr double kDt = 0.05;
  DdVelocity vehicle_;
  std::unique_ptr<Scene> scene_;
  CollisionChecker fine_;
  Goal goal_;
  DdVelocity::State start_;
};

TEST_F(PlanCheckTest, APlannersSolutionPassesWithItsStatesAndLength) {
  std::vector<PlanPiece> plan;
  std::vector<std::array<double, 2>> ends;
  solve(plan, ends);
  const PlanCheck c = check_plan(vehicle_, fine_, goal_, start_, plan, kDt, ends);
  EXPECT_TRUE(c.ok) << c.failure;
  EXPECT_GT(c.duration_s, 0.0);
  // At least the straight line from the start to the goal disk.
  EXPECT_GT(c.length_m,
            std::hypot(goal_.x_m() - start_[0], goal_.y_m() - start_[1]) - goal_.radius_m());
  EXPECT_LE(c.end_goal_distance_m, goal_.radius_m());
  EXPECT_LT(c.max_fine_deviation_m, 1e-3);
}

TEST_F(PlanCheckTest, StatesTheControlsDoNotProduceAreRefused) {
  std::vector<PlanPiece> plan;
  std::vector<std::array<double, 2>> ends;
  solve(plan, ends);
  ends.front()[0] += 0.01;
  const PlanCheck c = check_plan(vehicle_, fine_, goal_, start_, plan, kDt, ends);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.failure.find("its control leads to"), std::string::npos) << c.failure;
}

TEST_F(PlanCheckTest, APlanThatStopsShortOfTheGoalIsRefused) {
  std::vector<PlanPiece> plan;
  std::vector<std::array<double, 2>> ends;
  solve(plan, ends);
  plan.pop_back();
  const PlanCheck c = check_plan(vehicle_, fine_, goal_, start_, plan, kDt);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.failure.find("outside the goal radius"), std::string::npos) << c.failure;
}

TEST_F(PlanCheckTest, DrivingIntoTheWallIsRefusedAtTheFineStep) {
  // Full speed west from the start: the wall is about 1.7 m away.
  const std::vector<PlanPiece> plan{{{-3.0, -3.0}, 40}};
  const PlanCheck c = check_plan(vehicle_, fine_, goal_, start_, plan, kDt);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.failure.find("collides"), std::string::npos) << c.failure;
}

TEST_F(PlanCheckTest, ControlsOutsideTheModelsLimitsAreRefused) {
  // Each wheel within its speed limit, but the turn rate far above the model's.
  const std::vector<PlanPiece> plan{{{-1.0, 1.0}, 4}};
  const PlanCheck c = check_plan(vehicle_, fine_, goal_, start_, plan, kDt);
  EXPECT_FALSE(c.ok);
  EXPECT_NE(c.failure.find("turn rate"), std::string::npos) << c.failure;
}

TEST_F(PlanCheckTest, TheFineCheckerHasATenthOfThePlannersMargin) {
  EXPECT_DOUBLE_EQ(fine_.margin() * 10.0, step_collision_margin_m(vehicle_, kDt));
}

}  // namespace
}  // namespace grip::ompl_bridge
