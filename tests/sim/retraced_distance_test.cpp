// The retraced distance against hand-computed runs: out and back along a corridor, a straight
// drive, a wiggle across a square's border, and a loop driven twice.

#include "grip/sim/retraced_distance.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <vector>

namespace grip::sim {
namespace {

using Trajectory = std::vector<std::array<double, 2>>;

// Samples 0.1 m apart along x from `from` to `to` (both inside squares, never on a border).
void drive_x(Trajectory& t, double from, double to, double y) {
  const int n = static_cast<int>(std::lround(std::abs(to - from) / 0.1));
  const double step = to > from ? 0.1 : -0.1;
  for (int i = t.empty() ? 0 : 1; i <= n; ++i) t.push_back({from + step * i, y});
}

TEST(RetracedDistance, OutAndBackRetracesTheWayBackButTheSquareItTurnedIn) {
  // Out from x = 0.05 to 9.95 (9.9 m) and back (9.9 m), squares of 1 m, away 2 m. Square k is
  // left outwards at x = k + 0.95 after k + 0.9 m, and entered again on the way back at
  // x = k + 0.95 after 18.9 - k m: 18 - 2k m later, at least 2 m for k <= 8. The moves ending
  // in squares 8..0 on the way back, from x = 9.05 down to 0.05, are 9.0 m.
  Trajectory t;
  drive_x(t, 0.05, 9.95, 0.5);
  drive_x(t, 9.95, 0.05, 0.5);
  const RetracedDistance r = retraced_distance(t, 1.0, 2.0);
  EXPECT_NEAR(r.distance_m, 19.8, 1e-9);
  EXPECT_NEAR(r.retraced_m, 9.0, 1e-9);
  EXPECT_NEAR(r.fraction(), 9.0 / 19.8, 1e-12);
}

TEST(RetracedDistance, DrivingOnRetracesNothing) {
  Trajectory t;
  drive_x(t, 0.05, 9.95, 0.5);
  const RetracedDistance r = retraced_distance(t, 1.0, 2.0);
  EXPECT_NEAR(r.distance_m, 9.9, 1e-9);
  EXPECT_EQ(r.retraced_m, 0.0);
}

TEST(RetracedDistance, WigglingAcrossABorderRetracesNothing) {
  Trajectory t;
  for (int i = 0; i < 10; ++i) drive_x(t, 0.85, 1.15, 0.5), drive_x(t, 1.15, 0.85, 0.5);
  const RetracedDistance r = retraced_distance(t, 1.0, 2.0);
  EXPECT_NEAR(r.distance_m, 20 * 0.3, 1e-9);
  EXPECT_EQ(r.retraced_m, 0.0);
}

TEST(RetracedDistance, ALoopDrivenTwiceRetracesItsClosingAndTheWholeSecondLap) {
  // A ring of 1 m squares around a 4 m x 4 m block, the reference point 0.5 m inside: 12 m
  // per lap from (0.5, 0.5) back to it. Away 2 m. The first lap closes by entering its start
  // square again 11.2 m after leaving it: its last 0.5 m are retraced. The second lap starts
  // there, retracing, and enters every square 12 m after it was left: all 12 m.
  Trajectory t;
  const auto lap = [&] {
    for (int i = 0; i <= 30; ++i) t.push_back({0.5 + 0.1 * i, 0.5});
    for (int i = 1; i <= 30; ++i) t.push_back({3.5, 0.5 + 0.1 * i});
    for (int i = 1; i <= 30; ++i) t.push_back({3.5 - 0.1 * i, 3.5});
    for (int i = 1; i <= 30; ++i) t.push_back({0.5, 3.5 - 0.1 * i});
  };
  lap();
  const RetracedDistance first = retraced_distance(t, 1.0, 2.0);
  lap();  // its first sample repeats the first lap's last: a move of 0
  const RetracedDistance both = retraced_distance(t, 1.0, 2.0);
  EXPECT_NEAR(first.distance_m, 12.0, 1e-9);
  EXPECT_NEAR(first.retraced_m, 0.5, 1e-9);
  EXPECT_NEAR(both.distance_m, 24.0, 1e-9);
  EXPECT_NEAR(both.retraced_m, 12.5, 1e-9);
}

TEST(RetracedDistance, NoMovementNoDistance) {
  EXPECT_EQ(retraced_distance(Trajectory{}, 1.0, 2.0).fraction(), 0.0);
  EXPECT_EQ(retraced_distance(Trajectory{{1.0, 1.0}, {1.0, 1.0}}, 1.0, 2.0).fraction(), 0.0);
}

}  // namespace
}  // namespace grip::sim
