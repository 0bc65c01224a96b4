// The cycle scheme of Fig. 2 with a fake clock: the planner stops itself before the deadline,
// each cycle starts where the previous plan leads after T, committed plans cover the next
// cycle and end in a collision-free contingency, and nothing better keeps the previous plan.

#include "grip/rt/replanning_cycle.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "grip/planner/contingency.hpp"
#include "grip/platform/alloc_counter.hpp"
#include "grip/scenes/scenes.hpp"

namespace grip::rt {
namespace {

// A clock that advances a fixed step each time it is read: time passes as the planner works.
struct FakeClock {
  std::int64_t now = 0;
  std::int64_t step_ns = 20'000;
  std::int64_t read() { return now += step_ns; }
};

class ReplanningCycleTest : public ::testing::Test {
 protected:
  Scene scene = make_scene(SceneId::kRooms).value();
  Car car = Car::create({}).value();
  CycleConfig config;
  std::optional<ReplanningCycle<Car>> cycle;
  FakeClock clock;
  static constexpr std::int64_t kBudgetNs = 25'000'000;

  void SetUp() override {
    config.cycle_s = 0.1;
    config.safety_margin_ns = 2'000'000;
    PlannerConfig planner;
    planner.max_edges = 20'000;
    planner.max_trajectories = 10'000;
    cycle.emplace(ReplanningCycle<Car>::create(car, scene.grid, planner, config).value());
    ASSERT_TRUE(cycle->start(car.rest_state(scene.start_x_m, scene.start_y_m, 0.0),
                             Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)));
  }
  CycleOutcome run_cycle() {
    const std::int64_t release = clock.now;
    return cycle->run([this] { return clock.read(); }, release + kBudgetNs);
  }
  // Replays the committed plan from its start for `seconds`, checking every step.
  Car::State replay(double seconds, bool& collided) const {
    Car::State q = cycle->plan_start();
    double left = seconds;
    const double dt = cycle->planner().config().integration_step_s;
    for (const PlanStep& step : cycle->plan()) {
      const Car::Control u(step.control[0], step.control[1]);
      for (long i = 0; i < std::lround(step.duration_s / dt) && left > 1e-9; ++i, left -= dt) {
        q = car.step(q, u, dt);
        collided = collided || !cycle->planner().chassis_free(q);
      }
    }
    return q;
  }
};

TEST_F(ReplanningCycleTest, ThePlannerStopsItselfBeforeTheDeadlineWithItsMargin) {
  for (int i = 0; i < 5; ++i) {
    const std::int64_t release = clock.now;
    const CycleOutcome out = cycle->run([this] { return clock.read(); }, release + kBudgetNs);
    EXPECT_LE(clock.now, release + kBudgetNs - config.safety_margin_ns + 2 * clock.step_ns);
    EXPECT_GT(out.edges_added, 0U);
  }
}

// Committing that takes 3 ms (as exploration's does at time scale 2): the first cycle, with
// nothing learned, commits past the margin; from then on growth stops early enough that the
// cycle ends within it.
TEST_F(ReplanningCycleTest, GrowthLeavesRoomForTheCommitTimeItHasMeasured) {
  constexpr std::int64_t kCommitNs = 3'000'000;
  const auto slow_choice = [this](const Planner<Car>& planner) {
    clock.now += kCommitNs;
    return planner.best_state();
  };
  for (int i = 0; i < 10; ++i) {
    const std::int64_t release = clock.now;
    const std::int64_t stop_at = release + kBudgetNs - config.safety_margin_ns;
    const CycleOutcome out =
        cycle->run([this] { return clock.read(); }, release + kBudgetNs, slow_choice);
    if (i == 0) {
      EXPECT_EQ(out.commit_reserve_ns, 0) << "nothing was measured before the first commit";
      EXPECT_GT(clock.now, stop_at + kCommitNs / 2);
      continue;
    }
    // A few clock reads past the check aside, the commit fits within the margin.
    EXPECT_GE(out.commit_reserve_ns, kCommitNs) << "cycle " << i;
    EXPECT_LE(clock.now, stop_at + 10 * clock.step_ns) << "cycle " << i;
    EXPECT_GT(out.edges_added, 0U) << "cycle " << i;
  }
}

TEST(CommitReserve, IsThePriorUntilMeasuredThenThe90thPercentileOfRecentCommits) {
  CommitReserve reserve(1'000'000);
  EXPECT_EQ(reserve.ns(), 1'000'000);
  reserve.note(600'000);  // the first measurement replaces the prior
  EXPECT_EQ(reserve.ns(), 600'000);
  // A window of 600 us commits whose last three stalled (under a tenth of 32): the stalls are
  // not the reserve. One more stall (the oldest sample, a fast one, goes) and the percentile
  // reaches them.
  constexpr std::size_t kStalls = CommitReserve::kWindow / 10;
  for (std::size_t i = 0; i < CommitReserve::kWindow; ++i) {
    reserve.note(i >= CommitReserve::kWindow - kStalls ? 9'000'000 : 600'000);
  }
  EXPECT_EQ(reserve.ns(), 600'000);
  reserve.note(9'000'000);
  EXPECT_EQ(reserve.ns(), 9'000'000);
  // The window forgets: kWindow fast commits later, only they count.
  for (std::size_t i = 0; i < CommitReserve::kWindow; ++i) reserve.note(300'000);
  EXPECT_EQ(reserve.ns(), 300'000);
}

TEST_F(ReplanningCycleTest, LockstepGrowsItsEdgesWhateverTheClockAndReproducesARun) {
  // A clock that races ahead: a deadline would end growth at once, an edge budget does not.
  const auto racing = [this] { return clock.now += 1'000'000'000; };
  const auto best = [](const Planner<Car>& planner) { return planner.best_state(); };
  std::vector<PlanStep> first_run;
  for (int i = 0; i < 10; ++i) {
    const CycleOutcome out = cycle->run_for_edges(racing, 300, best);
    ASSERT_EQ(out.retain_status, RetainStatus::kOk);
    if (!out.solved) {
      EXPECT_GE(out.edges_added, 300U);
      EXPECT_LT(out.edges_added, 310U);  // one iteration may add a few more
    }
    for (const PlanStep& step : cycle->plan()) first_run.push_back(step);
  }
  ASSERT_FALSE(first_run.empty());
  // The same start and seed again, with a different clock: the same plans, step for step.
  SetUp();
  std::vector<PlanStep> second_run;
  const auto slow = [this] { return clock.now += 1; };
  for (int i = 0; i < 10; ++i) {
    cycle->run_for_edges(slow, 300, best);
    for (const PlanStep& step : cycle->plan()) second_run.push_back(step);
  }
  ASSERT_EQ(first_run.size(), second_run.size());
  for (std::size_t i = 0; i < first_run.size(); ++i) {
    EXPECT_EQ(first_run[i].control, second_run[i].control) << i;
    EXPECT_EQ(first_run[i].duration_s, second_run[i].duration_s) << i;
  }
}

TEST_F(ReplanningCycleTest, RhoTowardAnUnchangedTargetIsRecomputedEveryRefreshCycles) {
  config.rho_refresh_cycles = 3;
  SetUp();
  const DistanceField& rho = cycle->planner().rho_field();
  // Each cycle the map changes somewhere away from the tree, as it does while exploring.
  const auto run_after_map_change = [&](int i) {
    const std::uint64_t before = scene.grid.revision();
    const double x = 14.0 + 0.1 * i;
    scene.grid.fill_rect(x, 29.0, x + 0.05, 29.05, Cell::kObstacle);
    EXPECT_NE(scene.grid.revision(), before);
    const CycleOutcome out = run_cycle();
    EXPECT_EQ(out.retain_status, RetainStatus::kOk);
    EXPECT_FALSE(out.restarted());
  };
  (void)run_cycle();  // the first cycle starts the tree (a restart computes rho)
  ASSERT_EQ(rho.source_revision(), scene.grid.revision());
  const std::uint64_t computed_at = rho.source_revision();
  run_after_map_change(1);  // kept, kept, then recomputed on the third cycle
  EXPECT_EQ(rho.source_revision(), computed_at);
  run_after_map_change(2);
  EXPECT_EQ(rho.source_revision(), computed_at);
  run_after_map_change(3);
  EXPECT_EQ(rho.source_revision(), scene.grid.revision());
  // A target set again counts as new, even when it is the same: recomputed at once.
  run_after_map_change(4);
  EXPECT_NE(rho.source_revision(), scene.grid.revision());
  cycle->set_goal(Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m));
  run_after_map_change(5);
  EXPECT_EQ(rho.source_revision(), scene.grid.revision());
}

TEST_F(ReplanningCycleTest, ATargetGivenWithItsRhoIsPlannedTowardWithoutAWavefrontHere) {
  config.rho_refresh_cycles = 3;
  SetUp();
  (void)run_cycle();
  // GIVEN rho toward target cells computed on a copy of the map (as the target thread does),
  // told apart from the planner's own by the copy's revision
  OccupancyGrid copy = scene.grid;
  for (int i = 0; i < 1000; ++i) copy.mark_changed();
  std::vector<std::uint32_t> cells;
  for (int x = 0; x < 10; ++x) {
    int cx = 0;
    int cy = 0;
    ASSERT_TRUE(copy.to_cell(scene.goal_x_m + 0.1 * x, scene.goal_y_m, cx, cy));
    cells.push_back(copy.index(cx, cy));
  }
  DistanceField field =
      DistanceField::create(copy.width(), copy.height(), copy.resolution()).value();
  field.compute(copy, ClearanceMap::create_for(copy).value(), cells,
                cycle->planner().config().rho_clearance_m);
  const DistanceField& rho = cycle->planner().rho_field();

  // WHEN the cycle is given the target with it and runs on a changed map
  cycle->set_goal(Goal::cells(cells), &field);
  const auto run_after_map_change = [&](int i) {
    const double x = 14.0 + 0.1 * i;
    scene.grid.fill_rect(x, 29.0, x + 0.05, 29.05, Cell::kObstacle);
    EXPECT_EQ(run_cycle().retain_status, RetainStatus::kOk);
  };
  // THEN the planner plans with the field given, not one of its own, counting it as fresh:
  // kept in that cycle and two more, recomputed on the third cycle after it
  for (int i = 1; i <= 3; ++i) {
    run_after_map_change(i);
    EXPECT_EQ(rho.source_revision(), copy.revision()) << "cycle " << i;
  }
  run_after_map_change(4);
  EXPECT_EQ(rho.source_revision(), scene.grid.revision());
}

TEST_F(ReplanningCycleTest, AVehicleRestingWithoutAPlanKeepsGrowingTheSameTree) {
  // Choosing the root commits nothing: the vehicle rests where the tree starts, so each cycle
  // carries the tree over instead of restarting it and its growth accumulates.
  const auto root = [](const Planner<Car>& planner) { return planner.root_state(); };
  const auto racing = [this] { return clock.now += 1'000; };
  std::uint32_t edges = cycle->planner().tree().edge_count();  // the root
  for (int i = 0; i < 3; ++i) {
    const CycleOutcome out = cycle->run_for_edges(racing, 200, root);
    EXPECT_FALSE(out.committed);
    EXPECT_FALSE(out.plan_available);
    EXPECT_FALSE(out.restarted()) << "cycle " << i;
    EXPECT_EQ(out.edges_retained, edges) << "cycle " << i;
    EXPECT_GT(out.tree_edges, edges);
    edges = out.tree_edges;
    EXPECT_EQ(cycle->next_plan_start(), cycle->plan_start());
  }
  // A plan, once there is one, starts from that same rest state.
  const Car::State rest = cycle->plan_start();
  ASSERT_TRUE(run_cycle().committed);
  EXPECT_EQ(cycle->plan_start(), rest);
}

TEST_F(ReplanningCycleTest, ARestingTreeAtItsCapacityWithoutAPlanIsSampledAfresh) {
  // GIVEN pools of 300 edges and a choice that commits nothing, so the vehicle rests at the
  // root and the tree kept there grows until it reaches its capacity
  PlannerConfig small;
  small.max_edges = 300;
  small.max_trajectories = 150;
  cycle.emplace(ReplanningCycle<Car>::create(car, scene.grid, small, config).value());
  const Car::State rest = car.rest_state(scene.start_x_m, scene.start_y_m, 0.0);
  ASSERT_TRUE(cycle->start(rest, Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)));
  const auto nothing = [](const Planner<Car>&) { return TreeState{}; };
  const auto racing = [this] { return clock.now += 1'000; };
  bool at_capacity = false;  // the last cycle filled the pools, pruned for room or grew nothing
  int restarts = 0;
  for (int i = 0; i < 30; ++i) {
    const CycleOutcome out = cycle->run_for_edges(racing, 100, nothing);
    ASSERT_FALSE(out.plan_available);
    EXPECT_EQ(cycle->plan_start(), rest);
    if (at_capacity) {
      // THEN the cycle after starts a fresh tree, says why, and grows it
      EXPECT_EQ(out.restart_cause, RestartCause::kTreeFullWithoutPlan) << "cycle " << i;
      EXPECT_EQ(out.retain_status, RetainStatus::kOk);
      EXPECT_GT(out.edges_added, 0U);
      ++restarts;
    } else {
      // and until then the tree is kept and grows
      EXPECT_FALSE(out.restarted()) << "cycle " << i;
    }
    at_capacity = out.pool_exhausted || cycle->planner().last_retain().pruned_for_room > 0 ||
                  out.edges_added == 0;
  }
  EXPECT_GT(restarts, 0) << "the tree never reached its capacity";
  EXPECT_EQ(restart_cause_name(RestartCause::kTreeFullWithoutPlan), "tree-full-without-plan");
}

TEST_F(ReplanningCycleTest, ARestingTreeLeftNoTimeToGrowWithoutAPlanIsSampledAfresh) {
  // GIVEN a vehicle resting at the root without a plan and a tree kept there that grew
  const auto nothing = [](const Planner<Car>&) { return TreeState{}; };
  const auto racing = [this] { return clock.now += 1'000; };
  ASSERT_FALSE(cycle->run_for_edges(racing, 200, nothing).restarted());
  // WHEN a cycle has no time left to grow it (its deadline is within the margin)
  const CycleOutcome starved =
      cycle->run([this] { return clock.read(); }, clock.now, nothing, [] {});
  EXPECT_FALSE(starved.restarted());
  EXPECT_EQ(starved.edges_added, 0U);
  EXPECT_FALSE(starved.plan_available);
  // THEN the next cycle starts afresh rather than retain a tree it cannot grow
  const CycleOutcome next = cycle->run_for_edges(racing, 200, nothing);
  EXPECT_EQ(next.restart_cause, RestartCause::kTreeFullWithoutPlan);
  EXPECT_EQ(next.edges_retained, 0U);
  EXPECT_GT(next.edges_added, 0U);
}

TEST_F(ReplanningCycleTest, ARestartSaysWhyTheTreeWasNotKept) {
  // Kept: no cause.
  for (int i = 0; i < 3; ++i) {
    const CycleOutcome out = run_cycle();
    ASSERT_TRUE(out.committed);
    EXPECT_FALSE(out.restarted());
    EXPECT_EQ(out.restart_cause, RestartCause::kNone);
  }
  // The vehicle will be elsewhere: a fresh tree there.
  Car::State elsewhere = cycle->next_plan_start();
  elsewhere[3] = 0.0;
  cycle->resynchronise(elsewhere);
  CycleOutcome out = run_cycle();
  EXPECT_TRUE(out.restarted());
  EXPECT_EQ(out.restart_cause, RestartCause::kVehicleOffPlans);
  EXPECT_EQ(restart_cause_name(out.restart_cause), "vehicle-off-plans");
  EXPECT_EQ(cycle->plan_start(), elsewhere);
  // A moving vehicle without a plan: nothing in the tree says where it will be.
  Car::State moving = car.rest_state(scene.start_x_m, scene.start_y_m, 0.0);
  moving[3] = 1.0;
  ASSERT_TRUE(
      cycle->start(moving, Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m)));
  out = cycle->run([this] { return clock.read(); }, clock.now);  // no time to plan
  ASSERT_FALSE(out.plan_available);
  out = run_cycle();
  EXPECT_TRUE(out.restarted());
  EXPECT_EQ(out.restart_cause, RestartCause::kNoPlan);
  EXPECT_EQ(restart_cause_name(out.restart_cause), "no-plan");
}

TEST_F(ReplanningCycleTest, ThePlansEndIsAnnouncedOnceACycleBeforeThePlanIsExtracted) {
  // The announcement comes after growth and the choice, while the previous cycle's plan is
  // still the committed one: a publishing thread wakes before the new plan exists.
  const auto best = [](const Planner<Car>& planner) { return planner.best_state(); };
  const auto racing = [this] { return clock.now += 1'000; };
  ASSERT_TRUE(run_cycle().committed);
  for (int i = 0; i < 5; ++i) {
    const TreeState before = cycle->committed();
    const std::size_t steps_before = cycle->plan().size();
    int announced = 0;
    const CycleOutcome out = cycle->run_for_edges(racing, 200, best, [&] {
      ++announced;
      EXPECT_EQ(cycle->committed().edge, before.edge) << "cycle " << i;
      EXPECT_EQ(cycle->plan().size(), steps_before) << "cycle " << i;
    });
    EXPECT_EQ(announced, 1) << "cycle " << i;
    EXPECT_EQ(out.retain_status, RetainStatus::kOk);
  }
}

TEST_F(ReplanningCycleTest, EachCycleStartsWhereThePreviousPlanLeadsAfterT) {
  int compared = 0;
  for (int i = 0; i < 30; ++i) {
    const CycleOutcome out = run_cycle();
    ASSERT_EQ(out.retain_status, RetainStatus::kOk);
    if (!out.plan_available) continue;  // the vehicle brakes: covered by another test
    ++compared;
    EXPECT_GE(out.plan_duration_s, config.cycle_s - 1e-9);
    bool collided = false;
    const Car::State predicted = replay(config.cycle_s, collided);
    EXPECT_FALSE(collided);
    (void)run_cycle();
    // Recorded states are the integrator's own values: the new root is exactly the prediction.
    EXPECT_TRUE(cycle->plan_start().isApprox(predicted, 1e-12)) << "cycle " << i;
  }
  EXPECT_GT(compared, 20);
}

TEST_F(ReplanningCycleTest, CommittedPlansEndInACollisionFreeContingency) {
  int plans = 0;
  for (int i = 0; i < 40; ++i) {
    const CycleOutcome out = run_cycle();
    if (!out.plan_available) continue;  // the vehicle brakes: covered by another test
    ++plans;
    bool collided = false;
    const Car::State end = replay(1e9, collided);
    EXPECT_FALSE(collided);
    std::uint64_t checks = 0;
    EXPECT_TRUE(contingency_is_collision_free(car, cycle->planner().checker(), end,
                                              cycle->planner().config().integration_step_s,
                                              checks));
  }
  EXPECT_GT(plans, 30);
}

TEST_F(ReplanningCycleTest, WithNoTimeToPlanThePreviousPlanContinues) {
  for (int i = 0; i < 5; ++i) ASSERT_TRUE(run_cycle().committed);
  const double before = cycle->plan().empty() ? 0.0 : cycle->plan()[0].duration_s;
  (void)before;
  // A deadline already passed: no growth at all.
  const CycleOutcome out = cycle->run([this] { return clock.read(); }, clock.now);
  EXPECT_EQ(out.edges_added, 0U);
  EXPECT_TRUE(out.plan_available);
  EXPECT_TRUE(out.kept_previous || out.committed);
  EXPECT_FALSE(out.restarted());
}

TEST_F(ReplanningCycleTest, EveryCycleEitherCommitsACollisionFreePlanOrBrakesSafely) {
  int braking_cycles = 0;
  for (int cycles = 0; cycles < 300; ++cycles) {
    const CycleOutcome out = run_cycle();
    if (out.plan_available) {
      bool collided = false;
      (void)replay(1e9, collided);
      ASSERT_FALSE(collided) << "cycle " << cycles;
      continue;
    }
    // No plan covers the next cycle: the vehicle brakes, which must be collision-free.
    ++braking_cycles;
    std::uint64_t checks = 0;
    ASSERT_TRUE(contingency_is_collision_free(car, cycle->planner().checker(), cycle->plan_start(),
                                              cycle->planner().config().integration_step_s, checks))
        << "cycle " << cycles;
  }
  EXPECT_LT(braking_cycles, 300 / 4);
}

TEST(ReplanningCycleArrival, AVelocityControlledRobotReachesTheGoalOfRooms) {
  const Scene scene = make_scene(SceneId::kRooms).value();
  const DdVelocity robot = DdVelocity::create({}).value();
  CycleConfig config;
  config.cycle_s = 0.1;
  config.safety_margin_ns = 2'000'000;
  PlannerConfig planner;
  planner.max_edges = 20'000;
  planner.max_trajectories = 10'000;
  auto cycle = ReplanningCycle<DdVelocity>::create(robot, scene.grid, planner, config).value();
  const Goal goal = Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m);
  ASSERT_TRUE(cycle.start(robot.rest_state(scene.start_x_m, scene.start_y_m, 0.0), goal));
  FakeClock clock;
  int cycles = 0;
  // A first solution is found within seconds and the vehicle follows it while later cycles
  // shorten it (Algorithm 1 prunes what does not lead to F); random-control paths are slower
  // than the 65 m route at top speed, so the bound is generous: 120 s.
  for (; cycles < 1200; ++cycles) {
    const auto& q = cycle.plan_start();
    if (goal.contains(q[0], q[1])) break;
    const std::int64_t release = clock.now;
    const CycleOutcome out = cycle.run([&] { return clock.read(); }, release + 25'000'000);
    ASSERT_NE(out.retain_status, RetainStatus::kRootInCollision) << "cycle " << cycles;
  }
  EXPECT_LT(cycles, 1200) << "did not arrive within 120 s (the route is about 65 m)";
}

#if GRIP_ALLOC_COUNTER_INTERPOSE
TEST_F(ReplanningCycleTest, CyclesAllocateNothing) {
  ASSERT_TRUE(alloc_counter::interposed());
  for (int i = 0; i < 5; ++i) (void)run_cycle();
  alloc_counter::arm();
  for (int i = 0; i < 200; ++i) (void)run_cycle();
  alloc_counter::disarm();
  EXPECT_EQ(alloc_counter::counts().allocations + alloc_counter::counts().deallocations, 0U);
}
#endif

TEST(ReplanningCycleConfig, RefusesATThatIsNotAWholeNumberOfSteps) {
  const Scene scene = make_scene(SceneId::kRooms).value();
  const Car car = Car::create({}).value();
  CycleConfig config;
  config.cycle_s = 0.07;  // 1.4 integration steps of 0.05 s
  auto cycle = ReplanningCycle<Car>::create(car, scene.grid, PlannerConfig{}, config);
  ASSERT_FALSE(cycle);
  EXPECT_NE(cycle.error().message.find("whole number of integration steps"), std::string::npos);
}

TEST(ReplanningCycleConfig, RefusesANegativeCommitPrior) {
  const Scene scene = make_scene(SceneId::kRooms).value();
  const Car car = Car::create({}).value();
  CycleConfig config;
  config.commit_reserve_prior_ns = -1;
  auto cycle = ReplanningCycle<Car>::create(car, scene.grid, PlannerConfig{}, config);
  ASSERT_FALSE(cycle);
  EXPECT_NE(cycle.error().message.find("commit_reserve_prior_ns"), std::string::npos);
}

}  // namespace
}  // namespace grip::rt
