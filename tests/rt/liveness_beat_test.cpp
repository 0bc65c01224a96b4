// A watchdog beat only for a planning loop that completes cycles, at most once per interval.

#include "grip/rt/liveness_beat.hpp"

#include <gtest/gtest.h>

namespace {

using grip::rt::LivenessBeat;

constexpr std::int64_t kInterval = 250'000'000;

TEST(LivenessBeat, TheFirstBeatWaitsForTheFirstCycle) {
  LivenessBeat beat(kInterval);
  EXPECT_FALSE(beat.due(0, 0));
  EXPECT_FALSE(beat.due(10 * kInterval, 0));
  EXPECT_TRUE(beat.due(10 * kInterval, 1));
}

TEST(LivenessBeat, BeatsComeAtMostOncePerInterval) {
  LivenessBeat beat(kInterval);
  ASSERT_TRUE(beat.due(0, 1));
  EXPECT_FALSE(beat.due(kInterval - 1, 2));
  EXPECT_TRUE(beat.due(kInterval, 3));
  EXPECT_FALSE(beat.due(kInterval + 1, 4));
}

TEST(LivenessBeat, AStalledLoopGetsNoBeatHoweverLongItWaits) {
  LivenessBeat beat(kInterval);
  ASSERT_TRUE(beat.due(0, 5));
  EXPECT_FALSE(beat.due(kInterval, 5));
  EXPECT_FALSE(beat.due(100 * kInterval, 5));
  EXPECT_TRUE(beat.due(100 * kInterval, 6));  // cycles again: beats again
}

TEST(LivenessBeat, AZeroIntervalNeverBeats) {
  LivenessBeat beat(0);
  EXPECT_FALSE(beat.due(0, 1));
  EXPECT_FALSE(beat.due(kInterval, 2));
}

}  // namespace
