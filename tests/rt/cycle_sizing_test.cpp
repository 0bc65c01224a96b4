// The rule from a cycle's budget to the planner's capacity and margins (rt/cycle_sizing.hpp).

#include "grip/rt/cycle_sizing.hpp"

#include <gtest/gtest.h>

namespace grip::rt {
namespace {

TEST(SafetyMargin, IsAFifthOfTheBudget) {
  EXPECT_DOUBLE_EQ(default_safety_margin_ms(25.0), 5.0);
  EXPECT_DOUBLE_EQ(default_safety_margin_ms(12.5), 2.5);  // time scale 2
  EXPECT_DOUBLE_EQ(default_safety_margin_ms(2.5), 0.5);   // time scale 10
}

TEST(CycleSizing, PoolsFollowTheBudgetWithinTheirBounds) {
  CycleBudget budget;
  budget.cycle_s = 0.05;
  budget.budget_ms = 25.0;
  const CycleSizing sized = size_cycle(budget).value();
  EXPECT_EQ(sized.planner.max_edges, 10'000U);  // 400 per ms
  EXPECT_EQ(sized.planner.max_trajectories, 5'000U);
  EXPECT_DOUBLE_EQ(sized.margin_ms, 5.0);
  EXPECT_EQ(sized.cycle.safety_margin_ns, 5'000'000);
  EXPECT_DOUBLE_EQ(sized.cycle.cycle_s, 0.05);
  EXPECT_DOUBLE_EQ(sized.planner.integration_step_s, 0.05);

  budget.budget_ms = 1.0;  // 400 edges: below the floor
  EXPECT_EQ(size_cycle(budget).value().planner.max_edges, 2'000U);
  budget.budget_ms = 1000.0;  // 400,000 edges: above the ceiling
  EXPECT_EQ(size_cycle(budget).value().planner.max_edges, 200'000U);
  budget.max_edges = 1234;  // given: taken as it is
  EXPECT_EQ(size_cycle(budget).value().planner.max_edges, 1234U);
}

TEST(CycleSizing, LockstepPoolsHoldFourCyclesOfGrowthAndNeedNoMargin) {
  CycleBudget budget;
  budget.budget_ms = 0.5;
  budget.margin_ms = 1.0;  // more than the budget: no matter without a deadline
  budget.lockstep_edges = 1000;
  const CycleSizing sized = size_cycle(budget).value();
  EXPECT_EQ(sized.planner.max_edges, 4'000U);
}

TEST(CycleSizing, AMarginThatLeavesNoTimeToGrowIsRefused) {
  CycleBudget budget;
  budget.budget_ms = 2.0;
  budget.margin_ms = 2.0;
  const auto refused = size_cycle(budget);
  ASSERT_FALSE(refused.ok());
  EXPECT_EQ(refused.error().code, ErrorCode::kInvalidArgument);
  EXPECT_NE(refused.error().message.find("leaves no time to grow"), std::string::npos);
}

TEST(CycleSizing, TheSeedAndTheSafetyAblationReachThePlanner) {
  CycleBudget budget;
  budget.seed = 42;
  budget.safety = false;
  const CycleSizing sized = size_cycle(budget).value();
  EXPECT_EQ(sized.planner.seed, 42U);
  EXPECT_EQ(sized.planner.safety, SafetyCheck::kNone);
  EXPECT_EQ(size_cycle(CycleBudget{}).value().planner.safety, SafetyCheck::kAtHorizon);
}

}  // namespace
}  // namespace grip::rt
