// Safety at low cost (the paper's Sec. III-C): contingency maneuvers, the check at time T only,
// and the all-leaves-safe variant.

#include <gtest/gtest.h>

#include <cmath>

#include "grip/planner/contingency.hpp"
#include "grip/planner/planner.hpp"
#include "test_support.hpp"

namespace grip {
namespace {

TEST(Contingency, ACarAtTopSpeedCannotStopBeforeAWallCloserThanItsBrakingDistance) {
  // Braking from 3 m/s at 0.6 m/s^2 takes 7.5 m; the car's nose is 0.6 m ahead of its axle.
  const OccupancyGrid grid = test::walled_room(20.0);
  const Car car = Car::create({}).value();
  const CollisionChecker checker = CollisionChecker::create(grid, car.footprint(), 0.0).value();
  Car::State q;
  std::uint64_t checks = 0;
  q << 19.7 - 0.6 - 5.0, 10.0, 0.0, 3.0, 0.0;  // 5 m of room ahead of the nose
  EXPECT_FALSE(contingency_is_collision_free(car, checker, q, 0.02, checks));
  q << 19.7 - 0.6 - 8.0, 10.0, 0.0, 3.0, 0.0;  // 8 m of room
  EXPECT_TRUE(contingency_is_collision_free(car, checker, q, 0.02, checks));
  EXPECT_GT(checks, 200U);  // the whole braking path was checked
}

TEST(Contingency, UnknownSpaceCountsAsCollisionForTheBrakingPath) {
  OccupancyGrid grid = test::walled_room(20.0);
  grid.fill_rect(12.0, 0.3, 13.0, 19.7, Cell::kUnknown);
  const auto robot = DdAcceleration::create({}).value();
  const CollisionChecker checker = CollisionChecker::create(grid, robot.footprint(), 0.0).value();
  DdAcceleration::State q;
  q << 8.5, 10.0, 0.0, 2.0, 2.0;  // the nose at 8.75 m needs 3.33 m to stop: past 12 m
  std::uint64_t checks = 0;
  EXPECT_FALSE(contingency_is_collision_free(robot, checker, q, 0.02, checks));
  q << 8.5, 10.0, 0.0, 1.5, 1.5;  // needs 1.875 m
  EXPECT_TRUE(contingency_is_collision_free(robot, checker, q, 0.02, checks));
}

// Grows a DD-acceleration tree in a small room with a long horizon (3 s), so that many states at
// time T are fast enough to be unable to stop, and counts edges whose state at T is unsafe.
class HorizonSafetyTest : public ::testing::Test {
 protected:
  OccupancyGrid grid = test::walled_room(5.0);
  DdAcceleration robot = DdAcceleration::create({}).value();

  std::size_t unsafe_states_at_horizon(SafetyCheck safety, std::size_t& crossing) {
    PlannerConfig config;
    config.safety = safety;
    // Random selection grows deep trees quickly; the safety step does not depend on selection.
    config.selection = Selection::kRandom;
    config.safety_horizon_s = 3.0;
    config.max_edges = 12000;
    config.max_trajectories = 6000;
    config.seed = 2;
    auto planner = Planner<DdAcceleration>::create(robot, grid, config).value();
    // The goal is a free cell in the corner that no chassis can reach: the tree keeps growing.
    EXPECT_TRUE(planner.set_problem(robot.rest_state(1.0, 1.0, 0.8), Goal::disk(0.35, 4.65, 0.08)));
    (void)planner.solve([&] { return planner.stats().edges_added >= 5000; });

    const auto& tree = planner.tree();
    const auto horizon = static_cast<std::uint32_t>(
        std::lround(config.safety_horizon_s / config.integration_step_s));
    std::size_t unsafe = 0;
    crossing = 0;
    planner.visit_edges([&](EdgeHandle e, const Edge& edge) {
      const std::uint32_t begin = edge.start_step;
      const std::uint32_t end = tree.end_step(e);
      if (!(begin < horizon && horizon <= end)) return;
      ++crossing;
      // Re-integrate from the recorded state before T to the state reached at T.
      const std::uint32_t k = (horizon - begin) / config.steps_per_record;
      auto q = tree.state(edge.trajectory, edge.first + k);
      const auto& c = tree.trajectory(edge.trajectory).control;
      for (std::uint32_t s = begin + k * config.steps_per_record; s < horizon; ++s) {
        q = robot.step(q, DdAcceleration::Control(c[0], c[1]), config.integration_step_s);
      }
      std::uint64_t checks = 0;
      if (!contingency_is_collision_free(robot, planner.checker(), q, config.integration_step_s,
                                         checks)) {
        ++unsafe;
      }
    });
    return unsafe;
  }
};

TEST_F(HorizonSafetyTest, WithoutTheCheckSomeStatesAtTimeTCannotStop) {
  std::size_t crossing = 0;
  EXPECT_GT(unsafe_states_at_horizon(SafetyCheck::kNone, crossing), 0U) << crossing << " crossing";
  EXPECT_GT(crossing, 0U);
}

TEST_F(HorizonSafetyTest, WithTheCheckEveryStateReachedAtTimeTHasACollisionFreeContingency) {
  std::size_t crossing = 0;
  EXPECT_EQ(unsafe_states_at_horizon(SafetyCheck::kAtHorizon, crossing), 0U);
  EXPECT_GT(crossing, 10U);  // the tree did grow past T
}

TEST(AllLeavesSafety, EveryLeafOfTheTreeCanBrakeToAStop) {
  const OccupancyGrid grid = test::walled_room(7.0);
  const auto car = Car::create({}).value();
  PlannerConfig config;
  config.safety = SafetyCheck::kAllLeaves;
  config.seed = 9;
  auto planner = Planner<Car>::create(car, grid, config).value();
  ASSERT_TRUE(planner.set_problem(car.rest_state(1.0, 1.0, 0.8), Goal::disk(0.35, 6.65, 0.08)));
  (void)planner.solve([&] { return planner.stats().edges_added >= 800; });
  std::size_t leaves = 0;
  planner.visit_edges([&](EdgeHandle, const Edge& edge) {
    if (edge.first_child != kNoHandle) return;
    ++leaves;
    const auto& q = planner.tree().state(edge.trajectory, edge.last);
    std::uint64_t checks = 0;
    EXPECT_TRUE(contingency_is_collision_free(car, planner.checker(), q, config.integration_step_s,
                                              checks));
  });
  EXPECT_GT(leaves, 100U);
  EXPECT_GT(planner.stats().contingency_checks, planner.stats().edges_added);
}

}  // namespace
}  // namespace grip
