// The lead of plan start times over a slow link: grows by what a late plan missed, counts each
// plan once, decays when plans arrive with time to spare, and stays bounded.

#include "grip/rt/plan_lead.hpp"

#include <gtest/gtest.h>

#include <cstdint>

namespace grip::rt {
namespace {

constexpr std::int64_t kCycleNs = 50'000'000;

TEST(PlanLead, NoLeadOnALinkThatDeliversInTime) {
  PlanLead lead(kCycleNs);
  for (std::uint64_t cycle = 1; cycle < 100; ++cycle) lead.observe(cycle, kCycleNs / 10);
  EXPECT_EQ(lead.lead_ns(), 0);
}

TEST(PlanLead, ALatePlanMovesLaterPlansByWhatItMissedAndAQuarterCycle) {
  PlanLead lead(kCycleNs);
  lead.observe(3, -120'000'000);
  EXPECT_EQ(lead.lead_ns(), 120'000'000 + kCycleNs / 4);
  // The same report, repeated by later states, and an older plan's, count no more.
  lead.observe(3, -120'000'000);
  lead.observe(2, -500'000'000);
  EXPECT_EQ(lead.lead_ns(), 120'000'000 + kCycleNs / 4);
  // Plans that now arrive with less than half a cycle to spare keep the lead.
  for (std::uint64_t cycle = 4; cycle < 50; ++cycle) lead.observe(cycle, kCycleNs / 3);
  EXPECT_EQ(lead.lead_ns(), 120'000'000 + kCycleNs / 4);
}

TEST(PlanLead, PlansWithTimeToSpareLetItDecayToZero) {
  PlanLead lead(kCycleNs);
  lead.observe(1, -200'000'000);
  const std::int64_t raised = lead.lead_ns();
  ASSERT_GT(raised, 0);
  lead.observe(2, raised + kCycleNs / 2);
  EXPECT_LT(lead.lead_ns(), raised);
  EXPECT_GT(lead.lead_ns(), raised / 2) << "decays slowly, not at once";
  for (std::uint64_t cycle = 3; cycle < 500; ++cycle) lead.observe(cycle, 2 * kCycleNs);
  EXPECT_EQ(lead.lead_ns(), 0);
}

TEST(PlanLead, AHostileOrHopelessMarginIsBoundedAndCycleZeroIsNoReport) {
  PlanLead lead(kCycleNs);
  lead.observe(0, -1'000'000'000);
  EXPECT_EQ(lead.lead_ns(), 0) << "cycle 0: no plan received yet";
  lead.observe(1, INT64_MIN);
  EXPECT_EQ(lead.lead_ns(), PlanLead::kMaxLeadCycles * kCycleNs);
  lead.observe(2, INT64_MIN);
  EXPECT_EQ(lead.lead_ns(), PlanLead::kMaxLeadCycles * kCycleNs);
  lead.observe(3, INT64_MAX);
  EXPECT_GE(lead.lead_ns(), 0);
  EXPECT_LT(lead.lead_ns(), PlanLead::kMaxLeadCycles * kCycleNs);
}

}  // namespace
}  // namespace grip::rt
