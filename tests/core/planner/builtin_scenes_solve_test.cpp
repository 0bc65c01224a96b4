// GRIP solves every built-in scene with every vehicle, and its plan replays into the goal.

#include <gtest/gtest.h>

#include <string>
#include <tuple>

#include "grip/planner/planner.hpp"
#include "grip/scenes/scenes.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "test_support.hpp"

namespace grip {
namespace {

class BuiltInSceneSolveTest : public ::testing::TestWithParam<std::tuple<SceneId, VehicleKind>> {
 protected:
  template <VehicleModel V>
  void solve(const V& vehicle) {
    const Scene scene = make_scene(std::get<0>(GetParam())).value();
    PlannerConfig config;
    config.max_edges = 200'002;
    config.max_trajectories = 100'001;
    auto planner = Planner<V>::create(vehicle, scene.grid, config).value();
    const auto start = vehicle.rest_state(scene.start_x_m, scene.start_y_m, scene.start_theta_rad);
    const Goal goal = Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m);
    ASSERT_TRUE(planner.set_problem(start, goal));
    const auto result = planner.solve([&] { return planner.stats().edges_added >= 100'000; });
    ASSERT_EQ(result.reason, StopReason::kGoalReached)
        << "after " << planner.stats().edges_added << " edges";
    test::expect_solution_replays_into_goal(planner, start, goal);
  }
};

TEST_P(BuiltInSceneSolveTest, GripReachesTheGoalWithACollisionFreePlan) {
  with_default_vehicle(std::get<1>(GetParam()), [this](const auto& vehicle) { solve(vehicle); });
}

INSTANTIATE_TEST_SUITE_P(
    EveryScene, BuiltInSceneSolveTest,
    ::testing::Combine(::testing::Values(SceneId::kMeandros, SceneId::kLabyrinth, SceneId::kRooms),
                       ::testing::Values(VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration,
                                         VehicleKind::kCar)),
    [](const auto& param_info) {
      std::string name = std::string(scene_name(std::get<0>(param_info.param))) + "_" +
                         std::string(vehicle_name(std::get<1>(param_info.param)));
      for (char& c : name) {
        if (c == '-') c = '_';
      }
      return name;
    });

}  // namespace
}  // namespace grip
