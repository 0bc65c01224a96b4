// Incarnations: each start draws a new, non-zero one; a tracker follows one peer, refuses a
// second while the first speaks, and takes over another once the first has been silent for the
// takeover time (a restart, a standby planner); durable samples are never too old.

#include "grip/link/incarnation.hpp"

#include <gtest/gtest.h>

#include <set>

#include "grip/link/messages.hpp"

namespace grip::link {
namespace {

constexpr std::int64_t kLeaseNs = 500'000'000;

TEST(Incarnation, EachStartDrawsANewNonZeroOne) {
  std::set<std::uint64_t> seen;
  for (int i = 0; i < 100; ++i) {
    const std::uint64_t incarnation = new_incarnation();
    EXPECT_NE(incarnation, 0U);
    seen.insert(incarnation);
  }
  EXPECT_EQ(seen.size(), 100U);
}

TEST(IncarnationTracker, FollowsTheFirstPeerAndRefusesZero) {
  IncarnationTracker tracker(kLeaseNs, kLeaseNs);
  EXPECT_EQ(tracker.observe(0, 0), Peer::kNone);
  EXPECT_EQ(tracker.followed(), 0U);
  EXPECT_EQ(tracker.observe(7, 10), Peer::kNew);
  EXPECT_EQ(tracker.followed(), 7U);
  EXPECT_EQ(tracker.observe(7, 20), Peer::kSame);
  EXPECT_EQ(tracker.switches(), 0U);
}

TEST(IncarnationTracker, ASecondPeerIsRefusedWhileTheFirstSpeaks) {
  IncarnationTracker tracker(kLeaseNs, kLeaseNs);
  ASSERT_EQ(tracker.observe(7, 0), Peer::kNew);
  for (std::int64_t t = 100'000'000; t < 3'000'000'000; t += 100'000'000) {
    EXPECT_EQ(tracker.observe(9, t), Peer::kOther) << "at " << t;
    EXPECT_EQ(tracker.observe(7, t), Peer::kSame);
  }
  EXPECT_EQ(tracker.followed(), 7U);
  EXPECT_GT(tracker.others(), 0U);
}

TEST(IncarnationTracker, AnotherPeerTakesOverOnceTheFollowedOneIsSilentForTheLease) {
  IncarnationTracker tracker(kLeaseNs, kLeaseNs);
  ASSERT_EQ(tracker.observe(7, 0), Peer::kNew);
  EXPECT_EQ(tracker.observe(9, kLeaseNs - 1), Peer::kOther);
  EXPECT_EQ(tracker.classify(9, kLeaseNs), Peer::kNew);
  EXPECT_EQ(tracker.followed(), 7U) << "classify changes nothing";
  EXPECT_EQ(tracker.observe(9, kLeaseNs), Peer::kNew);
  EXPECT_EQ(tracker.followed(), 9U);
  EXPECT_EQ(tracker.switches(), 1U);
  // The old one, back, is now the other one.
  EXPECT_EQ(tracker.observe(7, kLeaseNs + 1), Peer::kOther);
}

TEST(IncarnationTracker, APeerStillAliveIsOnlySlowAndIsReplacedOnlyWhenHung) {
  constexpr std::int64_t kHungNs = 4 * kLeaseNs;
  IncarnationTracker tracker(kLeaseNs, kHungNs);
  ASSERT_EQ(tracker.observe(7, 0), Peer::kNew);
  // Silent for a lease but alive: a slow planner, not a dead one.
  EXPECT_EQ(tracker.observe(9, kLeaseNs, true), Peer::kOther);
  EXPECT_EQ(tracker.observe(9, kHungNs - 1, true), Peer::kOther);
  EXPECT_EQ(tracker.followed(), 7U);
  // Its liveliness lost: taken over at once.
  EXPECT_EQ(tracker.classify(9, kLeaseNs, false), Peer::kNew);
  // Alive but silent for the hung time: taken over too.
  EXPECT_EQ(tracker.observe(9, kHungNs, true), Peer::kNew);
  EXPECT_EQ(tracker.followed(), 9U);
  EXPECT_EQ(tracker.switches(), 1U);
}

TEST(StampLead, AStampFarAheadOfTheLastIsRefusedUnlessTheWallClockAllowsIt) {
  EXPECT_TRUE(stamp_lead_allowed(5'000'000'000, 1'000'000'000, 0));
  EXPECT_FALSE(stamp_lead_allowed(20'000'000'000, 1'000'000'000, 0));
  EXPECT_TRUE(stamp_lead_allowed(20'000'000'000, 1'000'000'000, 1'000'000'000));
  EXPECT_TRUE(stamp_lead_allowed(20'000'000'000, 0, 0)) << "the first state sets the mark";
  EXPECT_FALSE(stamp_lead_allowed(UINT64_MAX, 1'000'000'000, 60'000'000'000));
}

TEST(Freshness, ADurableSampleIsNeverTooOldButStillNotFromTheFuture) {
  const std::int64_t now = 100'000'000'000;
  EXPECT_EQ(check_freshness(now - 60'000'000'000, now, FreshnessLimits{}).reason,
            Rejection::kStampTooOld);
  EXPECT_TRUE(check_freshness(now - 60'000'000'000, now, FreshnessLimits::durable()).ok());
  EXPECT_EQ(check_freshness(now + 5'000'000'000, now, FreshnessLimits::durable()).reason,
            Rejection::kStampInFuture);
}

TEST(Rejection, IncarnationRejectionsHaveNames) {
  EXPECT_EQ(rejection_name(Rejection::kNoIncarnation), "no incarnation");
  EXPECT_EQ(rejection_name(Rejection::kOtherIncarnation), "another incarnation");
}

}  // namespace
}  // namespace grip::link
