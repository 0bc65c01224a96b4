// The verdict on a run the planner said was over: the ground truth's coverage decides, whatever
// frontiers the planner left; what it left and what stayed unsensed are named.

#include "grip/sim/exploration_verdict.hpp"

#include <gtest/gtest.h>

namespace grip::sim {
namespace {

TEST(ExplorationVerdict, EverythingSensedIsCompleteWithoutAReason) {
  const ExplorationVerdict v = verdict_when_planner_done(1000, 1000, 0, 0);
  EXPECT_EQ(v.result, "complete");
  EXPECT_EQ(v.reason, "");
}

TEST(ExplorationVerdict, GroupsLeftBesideCellsTheSensorCouldNotResolveStillMakeItComplete) {
  // GIVEN a planner that gave up on 6 groups and 1 reachable cell of 1,000,000 stayed unsensed
  const ExplorationVerdict v = verdict_when_planner_done(999'999, 1'000'000, 6, 0);
  // THEN the run is complete, and the reason says what was left and what stayed unsensed
  EXPECT_EQ(v.result, "complete");
  EXPECT_EQ(v.reason,
            "left 6 frontier group(s) the planner gave up on, with 1 cell(s) of reachable free "
            "space unsensed");
  // AND with nothing unsensed it says so
  EXPECT_EQ(verdict_when_planner_done(500, 500, 0, 2).reason,
            "left 2 frontier group(s) the vehicle cannot reach at its turning radius, with no "
            "reachable free space unsensed");
}

TEST(ExplorationVerdict, GroupsLeftThatHidReachableGroundMakeItStuck) {
  // GIVEN both kinds of groups left and 0.969 of the reachable space sensed (just short)
  const ExplorationVerdict v = verdict_when_planner_done(969, 1000, 1, 3);
  EXPECT_EQ(v.result, "stuck");
  EXPECT_EQ(v.reason,
            "left 1 frontier group(s) the planner gave up on and 3 frontier group(s) the vehicle "
            "cannot reach at its turning radius");
  // AND at exactly the complete coverage, it is complete
  EXPECT_EQ(verdict_when_planner_done(970, 1000, 1, 3).result, "complete");
}

TEST(ExplorationVerdict, DoneShortOfTheCoverageWithNothingLeftIsDoneEarly) {
  const ExplorationVerdict v = verdict_when_planner_done(500, 1000, 0, 0);
  EXPECT_EQ(v.result, "done-early");
  EXPECT_EQ(v.reason, "the planner said it was done at coverage 0.500");
  // AND an empty reachable set counts as all of it sensed
  EXPECT_EQ(verdict_when_planner_done(0, 0, 0, 0).result, "complete");
}

}  // namespace
}  // namespace grip::sim
