#include "grip/sim/plan_executor.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

#include "grip/rt/plan_ledger.hpp"

namespace grip::sim {
namespace {

constexpr std::int64_t kSecond = 1'000'000'000;

OccupancyGrid open_grid(double w_m = 20.0, double h_m = 10.0) {
  auto grid = OccupancyGrid::create(static_cast<int>(w_m * 10), static_cast<int>(h_m * 10), 0.1,
                                    0.0, 0.0, Cell::kFree);
  EXPECT_TRUE(grid.ok());
  return std::move(grid).value();
}

// As grip sim runs it: a plan that does not start where the vehicle is gets refused.
ExecutorConfig refusing() {
  ExecutorConfig config;
  config.refuse_start_mismatch = true;
  return config;
}

template <typename V>
PlanExecutor<V> make_executor(const V& vehicle, const OccupancyGrid& truth,
                              const typename V::State& start, const ExecutorConfig& config = {}) {
  auto executor = PlanExecutor<V>::create(vehicle, truth, start, 0, config);
  EXPECT_TRUE(executor.ok()) << (executor.ok() ? "" : executor.error().message);
  return std::move(executor).value();
}

PlanStep piece(double u0, double u1, double duration_s) { return PlanStep{{u0, u1}, duration_s}; }

// A vehicle at rest at (1, 1) heading +x on an open 20 m x 10 m map, with its executor (which
// points at the map: a Rig is built in place and never moved).
template <typename V>
struct Rig {
  V vehicle;
  OccupancyGrid truth = open_grid();
  PlanExecutor<V> executor = make_executor(vehicle, truth, vehicle.rest_state(1.0, 1.0, 0.0));
};

class DdVelocityExecutorTest : public ::testing::Test {
 protected:
  Rig<DdVelocity> rig{DdVelocity::create(DdVelocityParams{}).value()};
  PlanExecutor<DdVelocity>& executor = rig.executor;
};

TEST_F(DdVelocityExecutorTest, DrivingStraightAtOneMetrePerSecondForTwoSecondsEndsTwoMetresOn) {
  const std::vector<PlanStep> plan{piece(1.0, 1.0, 2.0)};
  ASSERT_EQ(executor.submit(plan, 0), PlanVerdict::kAccepted);
  executor.run_until(2 * kSecond);
  EXPECT_EQ(executor.now_ns(), 2 * kSecond);
  EXPECT_EQ(executor.stats().ticks, 40U);
  EXPECT_NEAR(executor.state()[0], 3.0, 1e-12);
  EXPECT_NEAR(executor.state()[1], 1.0, 1e-12);
  EXPECT_NEAR(executor.state()[2], 0.0, 1e-12);
  EXPECT_NEAR(executor.stats().distance_m, 2.0, 1e-12);
  // The plan just ended; a successor starting now could still come.
  EXPECT_EQ(executor.stats().contingencies, 0U);
  executor.step();
  // None came: the (trivial) contingency stopped the robot where the plan ended.
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_EQ(executor.stats().contingencies, 1U);
  EXPECT_EQ(executor.stats().plans_ran_out, 1U);
  EXPECT_DOUBLE_EQ(executor.speed_m_s(), 0.0);
  EXPECT_NEAR(executor.state()[0], 3.0, 1e-12);
  // 40 ticks at 1 m/s and one at rest, over a 3 m/s maximum.
  EXPECT_NEAR(executor.mean_speed_fraction(), 40.0 / 41.0 / 3.0, 1e-12);
  ASSERT_EQ(executor.speed_samples().size(), 41U);
  EXPECT_EQ(executor.speed_samples()[0].time_ns, kSecond / 20);
  EXPECT_DOUBLE_EQ(executor.speed_samples()[0].speed_m_s, 1.0);
  executor.run_until(3 * kSecond);
  EXPECT_NEAR(executor.state()[0], 3.0, 1e-12);  // stays stopped
  EXPECT_EQ(executor.stats().collisions, 0U);
}

TEST_F(DdVelocityExecutorTest, ARotationInPlaceTurnsByRateTimesDuration) {
  // Wheels at -+0.2 m/s on a 0.2 m half axle: 1 rad/s.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(-0.2, 0.2, 1.5)}, 0),
            PlanVerdict::kAccepted);
  executor.run_until(2 * kSecond);
  EXPECT_NEAR(executor.state()[2], 1.5, 1e-12);
  EXPECT_NEAR(executor.state()[0], 1.0, 1e-12);
}

TEST_F(DdVelocityExecutorTest, ANewPlanTakesOverExactlyAtItsStartTimeEvenInsideATick) {
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 10.0)}, 0),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond / 2);
  // Starts 1.025 s in: half-way through a tick.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.5, 0.5, 1.0)}, kSecond + kSecond / 40),
            PlanVerdict::kAccepted);
  EXPECT_EQ(executor.queued_plans(), 1U);
  executor.run_until(3 * kSecond);
  // 1.025 m at 1 m/s, then 0.5 m at 0.5 m/s, then stopped.
  EXPECT_NEAR(executor.state()[0], 1.0 + 1.025 + 0.5, 1e-12);
  EXPECT_EQ(executor.stats().plans_started, 2U);
  EXPECT_EQ(executor.stats().contingencies, 1U);
}

TEST_F(DdVelocityExecutorTest, APlanStartingWhenThePreviousEndsContinuesWithoutAContingency) {
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, 0),
            PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(2.0, 2.0, 1.0)}, kSecond),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond * 3 / 2);
  EXPECT_EQ(executor.stats().contingencies, 0U);
  EXPECT_EQ(executor.mode(), ExecutorMode::kExecuting);
  EXPECT_NEAR(executor.state()[0], 1.0 + 1.0 + 1.0, 1e-12);
}

TEST_F(DdVelocityExecutorTest, APlanSubmittedAtTheInstantThePreviousEndedTakesOverOnTime) {
  // A controller reads plans between ticks: the successor of a plan that ended with the last
  // tick, starting exactly then, is on time.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, 0),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(2.0, 2.0, 1.0)}, kSecond),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond * 3 / 2);
  EXPECT_EQ(executor.stats().contingencies, 0U);
  EXPECT_EQ(executor.stats().plans_started, 2U);
  EXPECT_NEAR(executor.state()[0], 1.0 + 1.0 + 1.0, 1e-12);
}

TEST_F(DdVelocityExecutorTest, AnEmptyPlanDropsQueuedPlansButNeverCutsTheExecutedOneShort) {
  // Braking where a plan did not end was never checked: the vehicle drives its plan to the end.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 3.0)}, 0),
            PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(-0.2, 0.2, 1.0)}, 2 * kSecond),
            PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit_empty(kSecond), PlanVerdict::kAccepted);  // drops the turn at 2 s
  EXPECT_EQ(executor.stats().plans_superseded, 1U);
  executor.run_until(kSecond * 5 / 2);
  EXPECT_EQ(executor.mode(), ExecutorMode::kExecuting);
  EXPECT_EQ(executor.stats().contingencies, 0U);
  EXPECT_NEAR(executor.state()[0], 3.5, 1e-12);
  EXPECT_NEAR(executor.state()[2], 0.0, 1e-12);  // it did not turn
  executor.run_until(4 * kSecond);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_EQ(executor.stats().plans_ran_out, 1U);
  EXPECT_NEAR(executor.state()[0], 4.0, 1e-12);  // braked where the plan ended
  EXPECT_EQ(executor.stats().plans_started, 1U);
  // A plan sent after an empty one starts as usual.
  ASSERT_EQ(executor.submit_empty(5 * kSecond), PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.5, 0.5, 1.0)}, 6 * kSecond),
            PlanVerdict::kAccepted);
  executor.run_until(7 * kSecond);
  EXPECT_NEAR(executor.state()[0], 4.5, 1e-12);
  EXPECT_EQ(executor.stats().plans_started, 2U);
  EXPECT_EQ(executor.submit_empty(kSecond), PlanVerdict::kStartsInThePast);
}

TEST_F(DdVelocityExecutorTest, ALaterSubmittedPlanSupersedesQueuedPlansStartingAtOrAfterIt) {
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, kSecond),
            PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.5, 0.5, 1.0)}, kSecond / 2),
            PlanVerdict::kAccepted);
  EXPECT_EQ(executor.queued_plans(), 1U);
  EXPECT_EQ(executor.stats().plans_superseded, 1U);
  executor.run_until(3 * kSecond);
  EXPECT_NEAR(executor.state()[0], 1.5, 1e-12);
  EXPECT_EQ(executor.stats().plans_started, 1U);
}

TEST_F(DdVelocityExecutorTest, BadPlansAreRejectedWithTheirReason) {
  const std::vector<PlanStep> good{piece(1.0, 1.0, 1.0)};
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{}, 0), PlanVerdict::kEmpty);
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 0.0)}, 0),
            PlanVerdict::kBadDuration);
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, std::nan(""))}, 0),
            PlanVerdict::kBadDuration);
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{piece(5.0, 5.0, 1.0)}, 0),
            PlanVerdict::kBadControl);  // above the 3 m/s wheel limit
  EXPECT_EQ(executor.submit(std::vector<PlanStep>(1025, piece(1.0, 1.0, 0.1)), 0),
            PlanVerdict::kTooManySteps);
  executor.run_until(kSecond);
  EXPECT_EQ(executor.submit(good, kSecond / 2), PlanVerdict::kStartsInThePast);
  const int queued = static_cast<int>(ExecutorConfig{}.max_queued_plans);
  for (int i = 0; i < queued; ++i) {
    EXPECT_EQ(executor.submit(good, (2 + i) * kSecond), PlanVerdict::kAccepted);
  }
  EXPECT_EQ(executor.submit(good, (3 + queued) * kSecond), PlanVerdict::kQueueFull);
  EXPECT_EQ(executor.stats().plans_rejected, 7U);
  EXPECT_EQ(plan_verdict_name(PlanVerdict::kQueueFull), "queue-full");
}

TEST_F(DdVelocityExecutorTest, AHostilePlanIsRefusedAndTheVehicleKeepsItsSafeBehaviour) {
  // GIVEN a vehicle executing a checked plan that ends at rest
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, 0),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond / 2);
  // WHEN plans beyond the vehicle's limits arrive: wheels past their limit, a piece lasting
  // years, infinite controls, a start so far ahead its end overflows
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{piece(3.5, 3.5, 1.0)}, kSecond),
            PlanVerdict::kBadControl);
  EXPECT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1e9)}, kSecond),
            PlanVerdict::kBadDuration);
  EXPECT_EQ(
      executor.submit(
          std::vector<PlanStep>{piece(std::numeric_limits<double>::infinity(), 1.0, 1.0)}, kSecond),
      PlanVerdict::kBadControl);
  EXPECT_EQ(executor.submit(std::vector<PlanStep>(1000, piece(1.0, 1.0, 0.5)),
                            std::numeric_limits<std::int64_t>::max() - 10),
            PlanVerdict::kBadDuration);
  // THEN each is refused and counted, and the vehicle finishes its plan and comes to rest
  EXPECT_EQ(executor.stats().plans_rejected, 4U);
  executor.run_until(3 * kSecond);
  EXPECT_NEAR(executor.state()[0], 2.0, 1e-9);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_EQ(executor.stats().collisions, 0U);
}

TEST_F(DdVelocityExecutorTest, ADifferentPredictedStartIsRecordedAndTheControlsStillRun) {
  const DdVelocity::State predicted(1.5, 1.0, 0.0);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, 0, predicted),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond);
  EXPECT_EQ(executor.stats().start_mismatches, 1U);
  EXPECT_NEAR(executor.stats().max_start_position_error_m, 0.5, 1e-12);
  EXPECT_NEAR(executor.state()[0], 2.0, 1e-12);
}

TEST(PlanExecutorRefusalTest, AMismatchingPlanIsRefusedAndTheVehicleFinishesItsOwnPlan) {
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  const OccupancyGrid truth = open_grid();
  auto executor = make_executor(robot, truth, robot.rest_state(1.0, 1.0, 0.0), refusing());
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 2.0)}, 0, std::nullopt, 7),
            PlanVerdict::kAccepted);
  // Predicted at x = 1.5 for 1 s, where the vehicle will be at x = 2.0: refused, and the
  // vehicle neither follows it nor brakes there; it drives its own plan to the end.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.5, 1.0, 2.0)}, kSecond,
                            DdVelocity::State(1.5, 1.0, 0.0), 8),
            PlanVerdict::kAccepted);
  executor.run_until(3 * kSecond / 2);
  EXPECT_EQ(executor.executing_tag(), 7U);
  EXPECT_EQ(executor.stats().start_mismatches, 1U);
  EXPECT_EQ(executor.stats().plans_refused, 1U);
  EXPECT_EQ(executor.stats().plans_started, 1U);
  EXPECT_NEAR(executor.state()[0], 2.5, 1e-12);
  EXPECT_NEAR(executor.state()[2], 0.0, 1e-12);
  executor.run_until(3 * kSecond);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_EQ(executor.executing_tag(), 0U);
  EXPECT_EQ(executor.stats().plans_ran_out, 1U);
  EXPECT_NEAR(executor.state()[0], 3.0, 1e-12);
}

TEST(PlanExecutorRefusalTest, ARestingVehicleStaysAtRestWhenItsPlanIsRefused) {
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  const OccupancyGrid truth = open_grid();
  auto executor = make_executor(robot, truth, robot.rest_state(1.0, 1.0, 0.0), refusing());
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, kSecond / 2,
                            DdVelocity::State(1.0, 1.0, 0.1), 3),
            PlanVerdict::kAccepted);
  executor.run_until(2 * kSecond);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_EQ(executor.stats().plans_refused, 1U);
  EXPECT_NEAR(executor.state()[0], 1.0, 1e-12);
  // The same plan from where the vehicle is runs.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 1.0)}, 3 * kSecond,
                            DdVelocity::State(1.0, 1.0, 0.0), 4),
            PlanVerdict::kAccepted);
  executor.run_until(7 * kSecond / 2);
  EXPECT_EQ(executor.executing_tag(), 4U);
  EXPECT_NEAR(executor.state()[0], 1.5, 1e-12);
}

// The planner's forecast of the controller (rt::PlanLedger) against the controller itself:
// plans that match and start inside a tick, a refused plan, an empty plan, a plan started from
// a braking vehicle. The forecast from a state measured part way must land exactly where the
// executor does.
TEST(PlanExecutorForecastTest, ThePlannersForecastLandsExactlyWhereTheControllerDoes) {
  const DdAcceleration robot = DdAcceleration::create(DdAccelerationParams{}).value();
  const OccupancyGrid truth = open_grid();
  const DdAcceleration::State start = robot.rest_state(1.0, 5.0, 0.0);
  auto executor = make_executor(robot, truth, start, refusing());
  rt::PlanLedger<DdAcceleration> ledger(robot, 0.05, 64);
  const auto send = [&](std::uint64_t cycle, std::int64_t at_ns, const DdAcceleration::State& from,
                        const std::vector<PlanStep>& steps) {
    ledger.record(cycle, static_cast<std::uint64_t>(at_ns), from, steps);
    const PlanVerdict v =
        steps.empty() ? executor.submit_empty(at_ns) : executor.submit(steps, at_ns, from, cycle);
    ASSERT_EQ(v, PlanVerdict::kAccepted);
  };
  const auto forecast_from = [&](const DdAcceleration::State& q, std::int64_t stamp,
                                 std::uint64_t executing, std::int64_t until) {
    const auto f = ledger.forecast(q, static_cast<std::uint64_t>(stamp), executing,
                                   static_cast<std::uint64_t>(until));
    EXPECT_TRUE(f.has_value());
    return f.value_or(rt::PlanLedger<DdAcceleration>::Forecast{});
  };
  constexpr std::int64_t kMs = 1'000'000;
  send(1, 0, start, {piece(0.6, 0.6, 1.0), piece(0.6, 0.3, 0.55), piece(-0.6, -0.6, 0.5)});
  executor.run_until(300 * kMs);
  const DdAcceleration::State measured = executor.state();
  ASSERT_EQ(executor.executing_tag(), 1U);
  // Plan 2 starts inside a tick, from where plan 1 puts the vehicle then.
  const auto at_525 = forecast_from(measured, 300 * kMs, 1, 525 * kMs);
  EXPECT_EQ(at_525.cycle, 1U);
  send(2, 525 * kMs, at_525.state, {piece(0.3, 0.6, 0.4), piece(0.6, 0.6, 2.0)});
  send(3, 750 * kMs, measured, {piece(0.6, -0.6, 1.0)});  // not where the vehicle will be
  send(4, 1200 * kMs, start, {});                         // empty: plan 2 goes on
  const auto at_1600 = forecast_from(measured, 300 * kMs, 1, 1600 * kMs);
  EXPECT_EQ(at_1600.cycle, 2U) << "an empty plan cuts no plan short";
  // Plan 2 runs out at 2.925 s: plan 5 starts from the braking vehicle.
  const auto at_3000 = forecast_from(measured, 300 * kMs, 1, 3000 * kMs);
  EXPECT_EQ(at_3000.cycle, 0U) << "braking";
  ASSERT_FALSE(robot.is_stopped(at_3000.state));
  send(5, 3000 * kMs, at_3000.state, {piece(0.6, 0.0, 0.5)});

  std::vector<std::pair<std::int64_t, DdAcceleration::State>> truth_at;
  for (std::int64_t t :
       {525 * kMs, 800 * kMs, 1000 * kMs, 1600 * kMs, 2950 * kMs, 3250 * kMs, 3800 * kMs}) {
    executor.run_until(t);
    truth_at.emplace_back(executor.now_ns(), executor.state());
  }
  EXPECT_EQ(executor.stats().plans_refused, 1U);
  EXPECT_EQ(executor.stats().plans_started, 3U);
  for (const auto& [t, q] : truth_at) {
    const auto f = forecast_from(measured, 300 * kMs, 1, t);
    for (int i = 0; i < 5; ++i) {
      EXPECT_EQ(f.state[i], q[i]) << "component " << i << " at " << t / kMs << " ms";
    }
  }
  EXPECT_EQ(forecast_from(measured, 300 * kMs, 1, 1000 * kMs).cycle, 2U);
  EXPECT_EQ(forecast_from(measured, 300 * kMs, 1, 1600 * kMs).cycle, 2U);
  EXPECT_EQ(forecast_from(measured, 300 * kMs, 1, 3250 * kMs).cycle, 5U);
  EXPECT_EQ(forecast_from(measured, 300 * kMs, 1, 3800 * kMs).cycle, 0U) << "plan 5 ran out";
}

TEST(PlanExecutorCollisionTest, DrivingIntoAWallIsOneCollisionWithItsTimeAndPlace) {
  OccupancyGrid truth = open_grid(10.0, 10.0);
  truth.fill_rect(5.05, 0.0, 10.0, 10.0, Cell::kObstacle);  // cells from x = 5.0 m on
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  auto executor = make_executor(robot, truth, robot.rest_state(2.0, 5.0, 0.0));
  // The front (0.25 m ahead) reaches the wall at x = 4.75, 2.75 s in; it stays in for 1.25 s.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(1.0, 1.0, 3.0), piece(-1.0, -1.0, 2.0),
                                                  piece(1.0, 1.0, 2.0)},
                            0),
            PlanVerdict::kAccepted);
  executor.run_until(3 * kSecond);
  EXPECT_TRUE(executor.in_collision());
  EXPECT_EQ(executor.stats().collisions, 1U);
  ASSERT_EQ(executor.collision_events().size(), 1U);
  const CollisionEvent& first = executor.collision_events()[0];
  EXPECT_EQ(first.time_ns, 2750 * kSecond / 1000);
  EXPECT_NEAR(first.x_m, 4.75, 1e-9);
  EXPECT_NEAR(first.y_m, 5.0, 1e-9);
  // Backing out (free below x = 4.75 again, at 3.3 s), then in again at 6.75 s: a second event.
  executor.run_until(8 * kSecond);
  EXPECT_EQ(executor.stats().collisions, 2U);
  ASSERT_EQ(executor.collision_events().size(), 2U);
  EXPECT_EQ(executor.collision_events()[1].time_ns, 6750 * kSecond / 1000);
  // In collision: 2.75..3.25 (11 ticks), 6.75..7.0 (6 ticks), stopped in the wall to 8.0 (20).
  EXPECT_EQ(executor.stats().ticks_in_collision, 11U + 6U + 20U);
}

TEST(PlanExecutorCollisionTest, AStartWhoseChassisTouchesAnObstacleIsRefused) {
  OccupancyGrid truth = open_grid(10.0, 10.0);
  truth.set(21, 50, Cell::kObstacle);
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  auto executor =
      PlanExecutor<DdVelocity>::create(robot, truth, robot.rest_state(2.0, 5.0, 0.0), 0);
  ASSERT_FALSE(executor.ok());
  EXPECT_NE(executor.error().message.find("(2.000000, 5.000000, 0.000000)"), std::string::npos)
      << executor.error().message;
}

TEST(PlanExecutorDynamicsTest, ADdAccelerationRobotBrakesToRestWhenItsPlanRunsOut) {
  Rig<DdAcceleration> rig{DdAcceleration::create(DdAccelerationParams{}).value()};
  auto& executor = rig.executor;
  // 0.6 m/s^2 for 2 s: 1.2 m/s after 1.2 m; braking at 0.6 m/s^2 takes 2 s and 1.2 m.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.6, 0.6, 2.0)}, 0),
            PlanVerdict::kAccepted);
  executor.run_until(2 * kSecond);
  EXPECT_NEAR(executor.state()[0], 2.2, 1e-9);
  EXPECT_NEAR(executor.speed_m_s(), 1.2, 1e-9);
  executor.step();
  EXPECT_EQ(executor.mode(), ExecutorMode::kBraking);
  executor.run_until(5 * kSecond);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_TRUE(rig.vehicle.is_stopped(executor.state()));
  EXPECT_NEAR(executor.state()[0], 3.4, 1e-6);
  EXPECT_NEAR(executor.stats().distance_m, 2.4, 1e-6);
  EXPECT_EQ(executor.stats().contingencies, 1U);
}

TEST(PlanExecutorDynamicsTest, ACarStopsWhenThePlannerFallsSilent) {
  Rig<Car> rig{Car::create(CarParams{}).value()};
  auto& executor = rig.executor;
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.6, 0.0, 10.0)}, 0),
            PlanVerdict::kAccepted);
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.6, 0.0, 10.0)}, 5 * kSecond),
            PlanVerdict::kAccepted);
  executor.run_until(kSecond);  // 0.6 m/s after 0.3 m
  executor.abandon_plans();
  EXPECT_EQ(executor.mode(), ExecutorMode::kBraking);
  EXPECT_EQ(executor.queued_plans(), 0U);
  executor.run_until(3 * kSecond);
  EXPECT_EQ(executor.mode(), ExecutorMode::kAtRest);
  EXPECT_NEAR(executor.state()[0], 1.6, 1e-6);  // 0.3 m more while braking for 1 s
  EXPECT_EQ(executor.stats().plans_abandoned, 1U);
  EXPECT_EQ(executor.stats().plans_superseded, 1U);
  EXPECT_EQ(executor.stats().plans_started, 1U);
  // The next plan is accepted and run as usual.
  ASSERT_EQ(executor.submit(std::vector<PlanStep>{piece(0.6, 0.0, 1.0)}, 3 * kSecond),
            PlanVerdict::kAccepted);
  executor.run_until(4 * kSecond);
  EXPECT_NEAR(executor.state()[3], 0.6, 1e-9);
}

TEST(PlanExecutorConfigTest, BadConfigurationsAreRefusedNamingTheField) {
  const DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  const OccupancyGrid truth = open_grid();
  ExecutorConfig config;
  config.step_s = 0.0;
  auto bad = PlanExecutor<DdVelocity>::create(robot, truth, robot.rest_state(1, 1, 0), 0, config);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("step_s"), std::string::npos);
}

}  // namespace
}  // namespace grip::sim
