// The replanning session without the transport: the chain of plan start times, the plans as
// sent, and a fresh tree where the vehicle will be when it is not where the tree puts it.

#include "grip/rt/replanning_session.hpp"

#include <gtest/gtest.h>

#include <cstdint>
#include <optional>

#include "grip/scenes/scenes.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {
namespace {

constexpr std::uint64_t kCycleNs = 100'000'000;

class ReplanningSessionTest : public ::testing::Test {
 protected:
  Scene scene = make_scene(SceneId::kRooms).value();
  DdVelocity robot = DdVelocity::create({}).value();
  std::optional<ReplanningSession<DdVelocity>> session;
  std::int64_t clock = 0;  // a fake clock: each read advances it

  void create(double budget_s = 0.025, double margin_s = -1.0) {
    SessionConfig config;
    config.cycle_s = 0.1;
    config.budget_s = budget_s;
    config.margin_s = margin_s;
    config.lockstep_edges = 500;
    session.emplace(ReplanningSession<DdVelocity>::create(robot, scene.grid, config).value());
  }
  VehicleSample at_rest(std::uint64_t stamp_ns) const {
    VehicleSample s;
    s.state = {scene.start_x_m, scene.start_y_m, 0.0, 0.0, 0.0};
    s.stamp_ns = stamp_ns;
    s.sequence_number = stamp_ns / kCycleNs + 1;
    s.lockstep = true;
    return s;
  }
  Goal goal() const { return Goal::disk(scene.goal_x_m, scene.goal_y_m, scene.goal_radius_m); }
  SentPlan<DdVelocity> lockstep_cycle(const VehicleSample& state) {
    session->note_state(state);
    session->set_plan_start_after(state);
    session->check_vehicle_follows();
    const CycleOutcome out = session->run(
        [this] { return clock += 20'000; }, 0,
        [](const Planner<DdVelocity>& planner) { return planner.best_state(); }, [] {});
    return session->send_plan(out);
  }
};

TEST_F(ReplanningSessionTest, LockstepPlansStartATAfterTheStateTheyAnswer) {
  create();
  ASSERT_TRUE(session->create_cycle(1.0, true, false));
  EXPECT_TRUE(session->lockstep());
  EXPECT_EQ(session->max_edges(), 2'000U);  // four cycles of 500 edges, at least the floor
  ASSERT_TRUE(session->start(at_rest(0), goal()));
  const SentPlan<DdVelocity> first = lockstep_cycle(at_rest(0));
  EXPECT_EQ(first.cycle, 1U);
  EXPECT_EQ(first.start_ns, kCycleNs);
  EXPECT_EQ(first.state_sequence, 1U);
  ASSERT_FALSE(first.steps.empty());
  EXPECT_NEAR(first.from[0], scene.start_x_m, 1e-9);  // a vehicle at rest starts where it is
  EXPECT_EQ(session->plans_committed(), 1U);
  EXPECT_EQ(session->resyncs(), 0U);
  EXPECT_EQ(session->misses(), 0U);  // lockstep has no deadline
}

TEST_F(ReplanningSessionTest, AVehicleThatStayedDespiteItsPlanGetsAFreshTreeWhereItIs) {
  create();
  ASSERT_TRUE(session->create_cycle(1.0, true, false));
  ASSERT_TRUE(session->start(at_rest(0), goal()));
  const SentPlan<DdVelocity> first = lockstep_cycle(at_rest(0));
  ASSERT_FALSE(first.steps.empty());
  // The vehicle reports, a cycle after the plan's start, that it is at rest at the start and
  // executes no plan (it refused the plan): the forecast keeps it there, the tree does not.
  const SentPlan<DdVelocity> second = lockstep_cycle(at_rest(2 * kCycleNs));
  EXPECT_EQ(session->resyncs(), 1U);
  EXPECT_EQ(second.start_ns, 3 * kCycleNs);
  EXPECT_NEAR(second.from[0], scene.start_x_m, 1e-9);
  EXPECT_NEAR(second.from[1], scene.start_y_m, 1e-9);
}

TEST_F(ReplanningSessionTest, RealTimePlansStartExactlyTApartOnTheVehiclesClock) {
  create();
  ASSERT_TRUE(session->create_cycle(1.0, false, false));
  EXPECT_EQ(session->period_wall_ns(), 100'000'000);
  VehicleSample state = at_rest(5 * kCycleNs + 1'234);  // off the cycle grid of the releases
  state.lockstep = false;
  ASSERT_TRUE(session->start(state, goal()));
  VehicleClock vehicle_clock;
  const std::int64_t local = 1'000'000'000;
  vehicle_clock.observe(state.stamp_ns, local,
                        1.0);  // the vehicle's clock: local - 0.5 s + 1234 ns
  // The first release re-anchors the chain on the state's integration grid, at or after the next
  // release; the following ones go on exactly T later.
  session->chain_plan_start(local, vehicle_clock);
  const std::uint64_t first = session->plan_start_ns();
  EXPECT_EQ((first - state.stamp_ns) % kCycleNs, 0U);
  EXPECT_GE(first, state.stamp_ns + kCycleNs);
  session->chain_plan_start(local + 100'000'000, vehicle_clock);
  EXPECT_EQ(session->plan_start_ns(), first + kCycleNs);
  // A clock estimate that jumps a second ahead re-anchors the chain (a plan must not start
  // before its release), still on the grid.
  vehicle_clock.observe(state.stamp_ns + 1'000'000'000, local, 1.0);
  session->chain_plan_start(local + 200'000'000, vehicle_clock);
  EXPECT_GE(session->plan_start_ns(), first + 10 * kCycleNs);
  EXPECT_EQ((session->plan_start_ns() - state.stamp_ns) % kCycleNs, 0U);
}

TEST_F(ReplanningSessionTest, SkippedReleasesAreMissedCycles) {
  create();
  ASSERT_TRUE(session->create_cycle(2.0, false, false));  // time scale 2: 50 ms of wall clock
  EXPECT_EQ(session->period_wall_ns(), 50'000'000);
  session->note_release(1'000'000'000);
  session->note_release(1'050'000'000);
  EXPECT_EQ(session->misses(), 0U);
  session->note_release(1'200'000'000);  // two releases skipped
  EXPECT_EQ(session->misses(), 2U);
}

TEST_F(ReplanningSessionTest, ABudgetTheMarginLeavesNoTimeIsRefusedAtStartUp) {
  create(/*budget_s=*/0.01, /*margin_s=*/0.01);
  const Status refused = session->create_cycle(1.0, false, false);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_FALSE(session->has_cycle());
  // In lockstep there is no deadline to leave a margin before.
  create(0.01, 0.01);
  EXPECT_TRUE(session->create_cycle(1.0, true, false));
}

}  // namespace
}  // namespace grip::rt
