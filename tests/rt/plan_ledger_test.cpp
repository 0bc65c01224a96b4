#include "grip/rt/plan_ledger.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cstdint>
#include <vector>

#include "grip/vehicles/dd_velocity.hpp"

namespace grip::rt {
namespace {

constexpr std::uint64_t kMs = 1'000'000;

PlanStep piece(double u0, double u1, double duration_s) { return PlanStep{{u0, u1}, duration_s}; }

class PlanLedgerTest : public ::testing::Test {
 protected:
  DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();
  PlanLedger<DdVelocity> ledger{robot, 0.05, 16};
  DdVelocity::State origin = robot.rest_state(1.0, 1.0, 0.0);
};

TEST_F(PlanLedgerTest, AVehicleOnAPlanIsForecastAlongIt) {
  ledger.record(1, 0, origin, std::vector<PlanStep>{piece(1.0, 1.0, 2.0)});
  // Measured 0.5 m on at 0.5 s; 1 m/s straight on until the plan ends at 2 s, then at rest.
  const auto f = ledger.forecast(robot.rest_state(1.5, 1.0, 0.0), 500 * kMs, 1, 1500 * kMs);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->state[0], 2.5, 1e-12);
  EXPECT_EQ(f->cycle, 1U);
  const auto after = ledger.forecast(robot.rest_state(1.5, 1.0, 0.0), 500 * kMs, 1, 3000 * kMs);
  ASSERT_TRUE(after.has_value());
  EXPECT_NEAR(after->state[0], 3.0, 1e-12);
  EXPECT_EQ(after->cycle, 0U) << "the plan ran out";
}

TEST_F(PlanLedgerTest, APlanNotStartingWhereTheVehicleWillBeIsRefused) {
  ledger.record(1, 0, origin, std::vector<PlanStep>{piece(1.0, 1.0, 2.0)});
  // Plan 2 expects the vehicle at x = 1.9 at 1 s; it will be at 2.0: refused.
  ledger.record(2, 1000 * kMs, robot.rest_state(1.9, 1.0, 0.0),
                std::vector<PlanStep>{piece(-1.0, -1.0, 1.0)});
  const auto f = ledger.forecast(origin, 0, 1, 1500 * kMs);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->state[0], 2.5, 1e-12);
  EXPECT_EQ(f->cycle, 1U);
  // From where it will be, plan 3 (sent later, the same start) is taken.
  ledger.record(3, 1000 * kMs, robot.rest_state(2.0, 1.0, 0.0),
                std::vector<PlanStep>{piece(-1.0, -1.0, 1.0)});
  const auto g = ledger.forecast(origin, 0, 1, 1500 * kMs);
  ASSERT_TRUE(g.has_value());
  EXPECT_NEAR(g->state[0], 1.5, 1e-12);
  EXPECT_EQ(g->cycle, 3U);
}

TEST_F(PlanLedgerTest, AnEmptyPlanSupersedesQueuedPlansAndLeavesTheExecutedOneRunning) {
  ledger.record(1, 0, origin, std::vector<PlanStep>{piece(1.0, 1.0, 4.0)});
  // Plan 2 would turn on the spot from 2 s, where plan 1 puts the vehicle.
  ledger.record(2, 2000 * kMs, robot.rest_state(3.0, 1.0, 0.0),
                std::vector<PlanStep>{piece(1.0, -1.0, 1.0)});
  const auto turning = ledger.forecast(origin, 0, 1, 2500 * kMs);
  ASSERT_TRUE(turning.has_value());
  EXPECT_NEAR(turning->state[0], 3.0, 1e-12);
  EXPECT_EQ(turning->cycle, 2U);
  ledger.record(3, 1000 * kMs, origin, {});  // empty from 1 s: supersedes plan 2
  const auto f = ledger.forecast(origin, 0, 1, 3000 * kMs);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->state[0], 4.0, 1e-12);  // still on plan 1
  EXPECT_EQ(f->cycle, 1U);
  const auto after = ledger.forecast(origin, 0, 1, 5000 * kMs);
  ASSERT_TRUE(after.has_value());
  EXPECT_NEAR(after->state[0], 5.0, 1e-12);  // plan 1 ran out at 4 s: at rest there
  EXPECT_EQ(after->cycle, 0U);
}

TEST_F(PlanLedgerTest, ARunOfEmptyPlansKeepsThePlanTheVehicleGoesOnWith) {
  // A planner without a plan for many cycles sends an empty plan each cycle; the vehicle
  // drives its last plan on, and the ledger must still know it.
  ledger.record(1, 0, origin, std::vector<PlanStep>{piece(1.0, 1.0, 10.0)});
  for (std::uint64_t cycle = 2; cycle < 2 + 4 * PlanLedger<DdVelocity>::kCapacity; ++cycle) {
    ledger.record(cycle, cycle * 50 * kMs, origin, {});
  }
  const auto f = ledger.forecast(robot.rest_state(2.0, 1.0, 0.0), 1000 * kMs, 1, 5000 * kMs);
  ASSERT_TRUE(f.has_value());
  EXPECT_NEAR(f->state[0], 6.0, 1e-12);
  EXPECT_EQ(f->cycle, 1U);
  // The run still drops a plan queued behind it, as its earliest member would: plan 100 was
  // queued for 6 s, then empty plans from 5.5 s and 7 s came.
  ledger.record(100, 6000 * kMs, robot.rest_state(6.0, 1.0, 0.0),
                std::vector<PlanStep>{piece(-1.0, -1.0, 1.0)});
  ledger.record(101, 5500 * kMs, origin, {});
  ledger.record(102, 7000 * kMs, origin, {});
  const auto g = ledger.forecast(robot.rest_state(2.0, 1.0, 0.0), 1000 * kMs, 1, 7000 * kMs);
  ASSERT_TRUE(g.has_value());
  EXPECT_NEAR(g->state[0], 8.0, 1e-12);  // plan 100 never started
  EXPECT_EQ(g->cycle, 1U);
}

TEST_F(PlanLedgerTest, APlanOlderThanTheLedgerGivesNoForecast) {
  for (std::uint64_t cycle = 1; cycle <= PlanLedger<DdVelocity>::kCapacity + 1; ++cycle) {
    ledger.record(cycle, cycle * 50 * kMs, origin, std::vector<PlanStep>{piece(1.0, 1.0, 1.0)});
  }
  EXPECT_FALSE(ledger.forecast(origin, 60 * kMs, 1, 100 * kMs).has_value());
  EXPECT_TRUE(ledger.forecast(origin, 110 * kMs, 2, 150 * kMs).has_value());
  // Nothing executing and nothing sent: it stays where it rests.
  const PlanLedger<DdVelocity> empty(robot, 0.05, 16);
  EXPECT_FALSE(empty.forecast(origin, 110 * kMs, 2, 150 * kMs).has_value());
  const auto f = empty.forecast(origin, 110 * kMs, 0, 500 * kMs);
  ASSERT_TRUE(f.has_value());
  EXPECT_EQ(f->state, origin);
}

}  // namespace
}  // namespace grip::rt
