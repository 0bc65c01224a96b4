#include "grip/planner/planner.hpp"
#include "grip/vehicles/vehicle_params.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "test_support.hpp"

namespace grip {
namespace {

// Stops after n iterations (selections) of the planner.
struct StopAfterIterations {
  const PlannerStats* stats;
  std::uint64_t n;
  bool operator()() const { return stats->iterations >= n; }
};

struct StopAfterEdges {
  const PlannerStats* stats;
  std::uint64_t n;
  bool operator()() const { return stats->edges_added >= n; }
};

class GripBookkeepingTest : public ::testing::Test {
 protected:
  OccupancyGrid grid = test::walled_room(12.0);
  DdAcceleration robot = DdAcceleration::create(DdAccelerationParams{}).value();
  PlannerConfig config;
  std::optional<Planner<DdAcceleration>> planner;

  void SetUp() override {
    config.max_edges = 2000;
    config.max_trajectories = 1000;
    config.seed = 11;
    config.stop_at_goal = false;  // keep iterating once the goal is reached
    planner.emplace(Planner<DdAcceleration>::create(robot, grid, config).value());
    ASSERT_TRUE(planner->set_problem(robot.rest_state(2, 2, 0), Goal::disk(10, 10, 0.8)));
  }
  void iterate_once() {
    StopAfterIterations stop{&planner->stats(), planner->stats().iterations + 1};
    (void)planner->solve(stop);
  }
};

TEST_F(GripBookkeepingTest, FirstIterationExpandsTheRootAndAppliesEq2) {
  const EdgeHandle root = planner->tree().root();
  EXPECT_EQ(planner->peek_selection(), root);
  const double root_rho = planner->tree().edge(root).rho_m;
  iterate_once();
  ASSERT_EQ(planner->stats().edges_added, 1U);
  const EdgeHandle child = planner->tree().edge(root).first_child;
  ASSERT_NE(child, kNoHandle);
  EXPECT_EQ(planner->tree().edge(root).priority, 3.0);  // 2 * 1 + 1
  // i = 0 edges before it if it gets closer to F, else a second selection of the root.
  EXPECT_EQ(planner->tree().edge(child).priority,
            planner->tree().edge(child).rho_m < root_rho ? 0.0 : 3.0);
  EXPECT_EQ(planner->heap_size(), 2U);
}

TEST_F(GripBookkeepingTest, SelectedEdgePartsGetTwicePlusOneAndTheNewEdgeGetsTheIterationCount) {
  // A new edge closer to F than the selected edge gets p = i (Eq. 2); one that is not counts as
  // another selection of the edge it grew from (2p + 1). Both cases occur in 200 rounds.
  int closer = 0;
  int not_closer = 0;
  for (int round = 0; round < 200; ++round) {
    const EdgeHandle selected = planner->peek_selection();
    ASSERT_NE(selected, kNoHandle);
    const double p_before = planner->tree().edge(selected).priority;
    const double rho_before = planner->tree().edge(selected).rho_m;
    const std::uint16_t first_before = planner->tree().edge(selected).first;
    const std::uint64_t edges_before = planner->stats().edges_added;
    iterate_once();
    const Edge& tail = planner->tree().edge(selected);
    EXPECT_EQ(tail.priority, 2.0 * p_before + 1.0);
    if (planner->stats().edges_added == edges_before) continue;  // t_free below the minimum
    // A split keeps the tail under the selected handle and puts the head above it; the new
    // edge hangs where the split happened (or at the selected edge's end), newest child first.
    const bool was_split = tail.first != first_before;
    const EdgeHandle attach = was_split ? tail.parent : selected;
    const EdgeHandle added = planner->tree().edge(attach).first_child;
    ASSERT_NE(added, kNoHandle);
    ASSERT_NE(added, selected);
    if (planner->tree().edge(added).rho_m < rho_before) {
      ++closer;
      EXPECT_EQ(planner->tree().edge(added).priority, static_cast<double>(edges_before));
    } else {
      ++not_closer;
      EXPECT_EQ(planner->tree().edge(added).priority, 2.0 * p_before + 1.0);
    }
    if (was_split) {
      EXPECT_EQ(planner->tree().edge(attach).priority, 2.0 * p_before + 1.0);
    }
  }
  EXPECT_GT(closer, 0);
  EXPECT_GT(not_closer, 0);
}

TEST_F(GripBookkeepingTest, ScoresAreEq3InLogSpaceAndRhoIsEq1OverTheEdgesStates) {
  StopAfterEdges stop{&planner->stats(), 300};
  (void)planner->solve(stop);
  const double log_a = std::log(config.score_base_a);
  std::size_t checked = 0;
  planner->visit_edges([&](EdgeHandle e, const Edge& edge) {
    double rho = INFINITY;
    const int first = edge.parent == kNoHandle ? edge.first : edge.first + 1;
    for (int k = first; k <= edge.last; ++k) {
      const auto& q = planner->tree().state(edge.trajectory, static_cast<std::uint32_t>(k));
      rho = std::min(rho, planner->rho_field().distance_m(q[0], q[1]));
    }
    EXPECT_DOUBLE_EQ(edge.rho_m, rho);
    EXPECT_DOUBLE_EQ(planner->log_score(e),
                     edge.priority * log_a + std::log(std::max(rho, config.rho_floor_m)));
    ++checked;
  });
  EXPECT_GT(checked, 300U);
}

TEST_F(GripBookkeepingTest, TheHeapAlwaysSelectsTheMinimumScore) {
  StopAfterEdges stop{&planner->stats(), 200};
  (void)planner->solve(stop);
  const EdgeHandle next = planner->peek_selection();
  const double best = planner->log_score(next);
  planner->visit_edges([&](EdgeHandle e, const Edge&) { EXPECT_GE(planner->log_score(e), best); });
  EXPECT_EQ(planner->heap_size(), planner->tree().edge_count());
}

// End-to-end solves: every vehicle with every selection reaches the goal, and the plan, replayed
// through the model from the start, stays collision-free and ends in the goal region.
struct SolveCase {
  VehicleKind vehicle;
  Selection selection;
};

class EndToEndSolveTest : public ::testing::TestWithParam<SolveCase> {
 protected:
  template <VehicleModel V>
  void solve_and_replay(const V& vehicle) {
    const OccupancyGrid grid = test::room_with_wall();
    PlannerConfig config;
    config.selection = GetParam().selection;
    config.seed = 5;
    config.max_edges = 60'000;
    config.max_trajectories = 30'000;
    auto planner = Planner<V>::create(vehicle, grid, config).value();
    const Goal goal = Goal::disk(9.5, 2.0, 1.0);
    ASSERT_TRUE(planner.set_problem(vehicle.rest_state(2.0, 2.0, 0.0), goal));
    const auto result = planner.solve([] { return false; });
    ASSERT_EQ(result.status, SolveStatus::kExactSolution) << stop_reason_name(result.reason);
    test::expect_solution_replays_into_goal(planner, vehicle.rest_state(2.0, 2.0, 0.0), goal);
  }
};

TEST_P(EndToEndSolveTest, ReachesTheGoalAroundAWallWithACollisionFreePlan) {
  with_default_vehicle(GetParam().vehicle,
                       [this](const auto& vehicle) { solve_and_replay(vehicle); });
}

std::vector<SolveCase> all_cases() {
  std::vector<SolveCase> cases;
  for (auto v : {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration, VehicleKind::kCar}) {
    for (auto s : {Selection::kGrip, Selection::kRrt, Selection::kRrtBias}) cases.push_back({v, s});
  }
  return cases;
}

INSTANTIATE_TEST_SUITE_P(AllVehiclesAndPlanners, EndToEndSolveTest,
                         ::testing::ValuesIn(all_cases()), [](const auto& param_info) {
                           std::string name =
                               std::string(vehicle_name(param_info.param.vehicle)) + "_" +
                               std::string(selection_name(param_info.param.selection));
                           for (char& c : name) {
                             if (c == '-') c = '_';
                           }
                           return name;
                         });

// On a map finer than rho_cell_m, rho runs on blocks of its cells (half the clearance at most);
// it still goes round the wall, and a car's turning rho reads it.
TEST(RhoOnBlocks, AFineMapGetsRhoOnBlocksAndGripStillSolvesIt) {
  const OccupancyGrid grid = test::room_with_wall(0.025);
  const auto car = Car::create({}).value();
  PlannerConfig config;
  config.seed = 5;
  config.max_edges = 60'000;
  config.max_trajectories = 30'000;
  auto planner = Planner<Car>::create(car, grid, config).value();
  EXPECT_EQ(planner.rho_field().block(), 4);
  const Goal goal = Goal::disk(9.5, 2.0, 1.0);
  ASSERT_TRUE(planner.set_problem(car.rest_state(2.0, 2.0, 0.0), goal));
  // Round the wall's top (y = 8), not through it.
  EXPECT_GT(planner.rho_field().distance_m(2.0, 2.0), 2 * 6.0);
  const auto result = planner.solve([] { return false; });
  ASSERT_EQ(result.status, SolveStatus::kExactSolution) << stop_reason_name(result.reason);
  test::expect_solution_replays_into_goal(planner, car.rest_state(2.0, 2.0, 0.0), goal);

  config.rho_cell_m = 0.0;
  EXPECT_EQ(Planner<Car>::create(car, grid, config).value().rho_field().block(), 1);
}

// A corridor 0.56 m wide for a car 0.4 m wide: too narrow for the chassis grown by the margin of
// its top speed (half a step's motion at 3 m/s and full lock, 0.14 m a side), wide enough for
// the margin of the speed it can have there. The planner checks each state with its own.
TEST(StateMargins, ACarPassesACorridorTooNarrowForTheTopSpeedsMargin) {
  OccupancyGrid grid = OccupancyGrid::create(180, 60, 0.05, 0.0, 0.0, Cell::kFree).value();
  grid.fill_rect(2.0, 0.0, 6.0, 1.22, Cell::kObstacle);
  grid.fill_rect(2.0, 1.78, 6.0, 3.0, Cell::kObstacle);
  const auto car = Car::create({}).value();
  PlannerConfig config;
  config.rho_clearance_m = 0.2;  // the corridor's centre line is 0.28 m from its walls
  config.seed = 3;
  auto planner = Planner<Car>::create(car, grid, config).value();
  ASSERT_GT(2.0 * (car.footprint().half_width_m + planner.collision_margin_m()), 0.56);
  EXPECT_FALSE(planner.checker().is_free(4.0, 1.5, 0.0));  // the top speed's margin
  const auto start = car.rest_state(1.0, 1.5, 0.0);
  const Goal goal = Goal::disk(8.0, 1.5, 0.4);
  ASSERT_TRUE(planner.set_problem(start, goal));
  const auto result = planner.solve([] { return false; });
  ASSERT_EQ(result.status, SolveStatus::kExactSolution) << stop_reason_name(result.reason);
  test::expect_solution_replays_into_goal(planner, start, goal);
}

TEST(RandomSelection, GrowsATreeOfDistinctEdgesWithoutReachingAFarGoalQuickly) {
  const OccupancyGrid grid = test::room_with_wall();
  const auto robot = DdAcceleration::create({}).value();
  PlannerConfig config;
  config.selection = Selection::kRandom;
  config.max_edges = 4000;
  config.max_trajectories = 2000;
  auto planner = Planner<DdAcceleration>::create(robot, grid, config).value();
  ASSERT_TRUE(planner.set_problem(robot.rest_state(2, 2, 0), Goal::disk(9.5, 2.0, 1.0)));
  StopAfterEdges stop{&planner.stats(), 500};
  (void)planner.solve(stop);
  EXPECT_EQ(planner.stats().edges_added, 500U);
  EXPECT_GT(planner.tree().edge_count(), 500U);  // splits add head records
}

TEST(PoolExhaustion, StopsGrowingSaysSoAndStillReturnsItsBestAnswer) {
  const OccupancyGrid grid = test::room_with_wall();
  const auto robot = Car::create({}).value();
  PlannerConfig config;
  config.max_edges = 41;
  config.max_trajectories = 20;
  auto planner = Planner<Car>::create(robot, grid, config).value();
  ASSERT_TRUE(planner.set_problem(robot.rest_state(2, 2, 0), Goal::disk(9.5, 2.0, 1.0)));
  const auto result = planner.solve([] { return false; });
  EXPECT_EQ(result.reason, StopReason::kPoolExhausted);
  EXPECT_EQ(result.status, SolveStatus::kApproximateSolution);
  EXPECT_TRUE(planner.stats().pool_exhausted);
  EXPECT_LE(planner.tree().edge_count(), 41U);
  const TreeState best = planner.best_state();
  ASSERT_NE(best.edge, kNoHandle);
  // The best answer: of the states at least T (1 s) from the root, the one with the lowest
  // estimated arrival, rho plus time at a quarter of top speed. (Whether 20 trajectories from
  // rest come any closer than the start is up to the seed: 11 of 20 seeds do.)
  const auto& tree = planner.tree();
  const double speed = 0.25 * robot.max_speed_m_s();
  const auto arrival = [&](EdgeHandle e, std::uint16_t k) {
    const auto& q = tree.edge_state(e, k);
    return planner.rho_field().distance_m(q[0], q[1]) +
           speed * static_cast<double>(tree.step_of(e, k)) * config.integration_step_s;
  };
  const std::uint32_t horizon_step = 20;
  ASSERT_GE(tree.step_of(best.edge, best.index), horizon_step);
  const double best_arrival = arrival(best.edge, best.index);
  std::size_t states_after_t = 0;
  planner.visit_edges([&](EdgeHandle e, const Edge& edge) {
    for (std::uint16_t k = edge.first; k <= edge.last; ++k) {
      if (tree.step_of(e, k) < horizon_step) continue;
      ++states_after_t;
      EXPECT_LE(best_arrival, arrival(e, k) + 1e-9);
    }
  });
  EXPECT_GT(states_after_t, 20U);
  BoundedVector<PlanStep> plan(64);
  EXPECT_TRUE(planner.extract_plan(best, plan));
  EXPECT_GT(plan.size(), 0U);
}

TEST(PoolRecycling, AFullPoolIsRecycledAndTheSearchGoesOnToTheGoal) {
  // Around the wall with room for 60 trajectories at a time, over seeds: most searches need
  // more propagations than a full pool holds. Recycled, every one reaches the goal; without
  // recycling the same search (the same random stream up to the first full pool) stops there.
  const OccupancyGrid grid = test::room_with_wall();
  const auto robot = DdAcceleration::create({}).value();
  const Goal goal = Goal::disk(9.5, 2.0, 1.0);
  const auto start = robot.rest_state(2, 2, 0);
  PlannerConfig config;
  config.max_edges = 120;
  config.max_trajectories = 60;
  int needed_recycling = 0;
  for (std::uint64_t seed = 1; seed <= 10; ++seed) {
    SCOPED_TRACE(seed);
    config.seed = seed;
    config.recycle_full_pool = true;
    auto planner = Planner<DdAcceleration>::create(robot, grid, config).value();
    ASSERT_TRUE(planner.set_problem(start, goal));
    EXPECT_EQ(planner.solve(StopAfterIterations{&planner.stats(), 200'000}).reason,
              StopReason::kGoalReached);
    EXPECT_LE(planner.tree().edge_count(), config.max_edges);
    test::expect_solution_replays_into_goal(planner, start, goal);
    if (planner.stats().pool_recycles == 0) continue;
    ++needed_recycling;
    EXPECT_GT(planner.stats().edges_added, config.max_trajectories);

    config.recycle_full_pool = false;
    auto stopping = Planner<DdAcceleration>::create(robot, grid, config).value();
    ASSERT_TRUE(stopping.set_problem(start, goal));
    EXPECT_EQ(stopping.solve(StopAfterIterations{&stopping.stats(), 200'000}).reason,
              StopReason::kPoolExhausted);
    EXPECT_FALSE(stopping.solved());
  }
  EXPECT_GE(needed_recycling, 5);
}

TEST(Determinism, TheSameSeedReproducesTheRunAndAnotherSeedDoesNot) {
  const OccupancyGrid grid = test::room_with_wall();
  const auto robot = DdAcceleration::create({}).value();
  const auto run = [&](std::uint64_t seed) {
    PlannerConfig config;
    config.seed = seed;
    auto planner = Planner<DdAcceleration>::create(robot, grid, config).value();
    EXPECT_TRUE(planner.set_problem(robot.rest_state(2, 2, 0), Goal::disk(9.5, 2.0, 1.0)));
    (void)planner.solve([] { return false; });
    return std::make_pair(planner.stats().edges_added, planner.stats().collision_checks);
  };
  EXPECT_EQ(run(3), run(3));
  EXPECT_NE(run(3), run(4));
}

TEST(BadInput, InvalidConfigurationsAreRefusedWithTheParameterNamed) {
  const OccupancyGrid grid = test::walled_room(5.0);
  const auto robot = DdVelocity::create({}).value();
  const auto refused = [&](PlannerConfig c, const char* name) {
    auto p = Planner<DdVelocity>::create(robot, grid, c);
    ASSERT_FALSE(p);
    EXPECT_NE(p.error().message.find(name), std::string::npos) << p.error().message;
  };
  PlannerConfig c;
  c.max_edges = 0;
  refused(c, "max_edges");
  c = PlannerConfig{};
  c.max_trajectories = 0;
  refused(c, "max_trajectories");
  c = PlannerConfig{};
  c.score_base_a = 1.0;
  refused(c, "score_base_a");
  c = PlannerConfig{};
  c.integration_step_s = -0.01;
  refused(c, "integration_step_s");
  c = PlannerConfig{};
  c.min_plan_duration_s = c.max_plan_duration_s + 1.0;
  refused(c, "min_plan_duration_s");
  c = PlannerConfig{};
  c.safety_horizon_s = std::nan("");
  refused(c, "safety_horizon_s");
  c = PlannerConfig{};
  c.rho_floor_m = 0.0;
  refused(c, "rho_floor_m");
  c = PlannerConfig{};
  c.rho_clearance_m = -0.1;
  refused(c, "rho_clearance_m");
  c = PlannerConfig{};
  c.rho_cell_m = std::nan("");
  refused(c, "rho_cell_m");
  c = PlannerConfig{};
  c.rrt_goal_bias = 1.5;
  refused(c, "rrt_goal_bias");
}

TEST(BadInput, StartInAnObstacleGoalOutsideTheGridAndNanStatesAreRefused) {
  OccupancyGrid grid = test::walled_room(6.0);
  grid.fill_rect(2.0, 2.0, 3.0, 3.0, Cell::kObstacle);
  const auto robot = Car::create({}).value();
  auto planner = Planner<Car>::create(robot, grid, PlannerConfig{}).value();
  const Goal goal = Goal::disk(4.5, 4.5, 0.5);

  auto in_obstacle = planner.set_problem(robot.rest_state(2.5, 2.5, 0), goal);
  ASSERT_FALSE(in_obstacle);
  EXPECT_NE(in_obstacle.error().message.find("obstacle"), std::string::npos);

  auto outside = planner.set_problem(robot.rest_state(1, 1, 0), Goal::disk(40, 4, 0.5));
  ASSERT_FALSE(outside);
  EXPECT_NE(outside.error().message.find("outside the grid"), std::string::npos);

  auto nan_start = planner.set_problem(robot.rest_state(1, std::nan(""), 0), goal);
  ASSERT_FALSE(nan_start);
  EXPECT_NE(nan_start.error().message.find("not finite"), std::string::npos);

  auto bad_radius = planner.set_problem(robot.rest_state(1, 1, 0), Goal::disk(4.5, 4.5, -1));
  EXPECT_FALSE(bad_radius);

  auto goal_in_wall = planner.set_problem(robot.rest_state(1, 1, 0), Goal::disk(2.5, 2.5, 0.3));
  ASSERT_FALSE(goal_in_wall);
  EXPECT_NE(goal_in_wall.error().message.find("no free cell"), std::string::npos);

  // Refused problems leave no problem set: solve does nothing.
  const auto r = planner.solve([] { return false; });
  EXPECT_EQ(r.status, SolveStatus::kNoSolution);
  EXPECT_EQ(planner.stats().iterations, 0U);
}

}  // namespace
}  // namespace grip

namespace grip {
namespace {

TEST(ExtractPlan, RefusesABufferTooSmallForThePlanAndLeavesItEmpty) {
  const OccupancyGrid grid = test::room_with_wall();
  const auto robot = DdAcceleration::create({}).value();
  auto planner = Planner<DdAcceleration>::create(robot, grid, PlannerConfig{}).value();
  ASSERT_TRUE(planner.set_problem(robot.rest_state(2, 2, 0), Goal::disk(9.5, 2.0, 1.0)));
  (void)planner.solve([] { return false; });
  ASSERT_TRUE(planner.solved());
  BoundedVector<PlanStep> roomy(4096);
  ASSERT_TRUE(planner.extract_plan(planner.best_state(), roomy));
  ASSERT_GE(roomy.size(), 2U);
  BoundedVector<PlanStep> tight(roomy.size() - 1);
  EXPECT_FALSE(planner.extract_plan(planner.best_state(), tight));
  EXPECT_TRUE(tight.empty());
  // The pieces add up to the time at which the solution state is reached.
  double total = 0.0;
  for (const PlanStep& step : roomy) total += step.duration_s;
  const TreeState s = planner.best_state();
  EXPECT_NEAR(total, planner.tree().step_of(s.edge, s.index) * planner.config().integration_step_s,
              1e-9);
}

}  // namespace
}  // namespace grip
