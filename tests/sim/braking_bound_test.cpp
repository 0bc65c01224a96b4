// The braking bound against hand-computed routes: unknown space ahead, a reversal, the ramp
// from rest and after the unknown is sensed, and bad input.

#include "grip/sim/braking_bound.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

namespace grip::sim {
namespace {

using Route = std::vector<std::array<double, 2>>;

// The car's: stops from 3 m/s in 7.5 m, backs up at 0.5 m/s at most.
constexpr SpeedLimits kLimits{3.0, 0.5, 0.6, 0.6};
constexpr double kStep = 0.05;  // a speed gain of 0.03 m/s per tick at most

// 10 m x 2 m at 0.1 m; every cell sensed at tick `tick`, those with x >= unknown_from_m at
// `late_tick`.
struct Sensing {
  OccupancyGrid grid = OccupancyGrid::create(100, 20, 0.1).value();
  std::vector<std::uint32_t> ticks;
  Sensing(std::uint32_t tick, double unknown_from_m, std::uint32_t late_tick)
      : ticks(grid.cell_count(), tick) {
    for (int y = 0; y < grid.height(); ++y) {
      for (int x = 0; x < grid.width(); ++x) {
        if (grid.cell_center_x(x) > unknown_from_m) ticks[grid.index(x, y)] = late_tick;
      }
    }
  }
};

// Along y = 1.05 from x = from_m, step_m per tick, `ticks` ticks, the chassis facing +x.
void drive(Route& r, double from_m, double step_m, int ticks) {
  for (int k = 0; k < ticks; ++k) r.push_back({from_m + step_m * k, 1.05});
}
std::vector<double> facing_x(const Route& r) { return std::vector<double>(r.size(), 0.0); }

// The car's chassis around its rear axle: 0.6 m ahead, 0.15 m behind, 0.2 m to either side.
constexpr Footprint kChassis{0.6, 0.15, 0.2};

// The speed that brakes to rest within free_m, exactly.
void expect_brakes_within(double bound, double free_m) {
  EXPECT_NEAR(bound, std::sqrt(2.0 * 0.6 * free_m), 1e-9);
}

// ... where unknown space limits it: the route is looked at a point per half cell (0.05 m
// here), so the first point found touching it lies up to one such step further.
void expect_brakes_before_unknown(double bound, double free_m) {
  EXPECT_GE(bound, std::sqrt(2.0 * 0.6 * free_m) - 1e-9);
  EXPECT_LE(bound, std::sqrt(2.0 * 0.6 * (free_m + 0.05)) + 1e-9);
}

TEST(BrakingBound, UnknownAheadLimitsTheSpeedToWhatBrakesBeforeIt) {
  // Cells from x = 3.0 are sensed at tick 200. The chassis's front reaches them from x = 2.4.
  const Sensing s(0, 3.0, 200);
  Route r;
  drive(r, 0.55, 0.01, 490);
  const auto bound = braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_TRUE(bound.ok()) << bound.error().message;
  ASSERT_EQ(bound->size(), r.size());
  // From rest: 0.03 m/s more per tick (tick 1 ends with the first route point).
  EXPECT_NEAR((*bound)[0], 0.03, 1e-12);
  EXPECT_NEAR((*bound)[9], 0.30, 1e-12);
  // Tick 101 at x = 1.55, tick 181 at x = 2.35.
  expect_brakes_before_unknown((*bound)[100], 2.4 - 1.55);
  expect_brakes_before_unknown((*bound)[180], 2.4 - 2.35);
  // Tick 200: sensed. Nothing ahead limits it but the acceleration from the tick before.
  EXPECT_NEAR((*bound)[199], (*bound)[198] + 0.03, 1e-12);
  EXPECT_NEAR(bound->back(), 3.0, 1e-12);  // the top speed; the route's end reads as open
}

TEST(BrakingBound, AReversalIsAStop) {
  // Out to x = 2.55 and back: the vehicle is at rest where it reverses.
  const Sensing s(0, 100.0, 0);
  Route r;
  drive(r, 0.55, 0.01, 201);
  drive(r, 2.54, -0.01, 150);
  const auto bound = braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_TRUE(bound.ok()) << bound.error().message;
  expect_brakes_within((*bound)[100], 1.0);                       // x = 1.55
  expect_brakes_within((*bound)[180], 0.2);                       // x = 2.35
  EXPECT_NEAR((*bound)[199], std::sqrt(2.0 * 0.6 * 0.01), 1e-9);  // a tick before it
  EXPECT_EQ((*bound)[200], 0.0);                                  // there, at rest
  EXPECT_NEAR((*bound)[201], 0.03, 1e-12);                        // and away again from rest
}

TEST(BrakingBound, StandingStillAndKnownSpaceReachTheTopSpeed) {
  const Sensing s(0, 100.0, 0);
  Route r(400, {5.0, 1.0});
  const auto bound = braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_TRUE(bound.ok()) << bound.error().message;
  EXPECT_NEAR((*bound)[49], 1.5, 1e-12);
  EXPECT_NEAR((*bound)[99], 3.0, 1e-12);
  EXPECT_NEAR(bound->back(), 3.0, 1e-12);
}

TEST(BrakingBound, TheChassisCountsNotTheReferencePoint) {
  // Facing +y, the same route along x: the front points away from the unknown cells (x >= 3.0),
  // which the chassis's side reaches only from x = 2.8 (half width 0.2 m).
  const Sensing s(0, 3.0, 1000);
  Route r;
  drive(r, 0.55, 0.01, 300);
  const std::vector<double> facing_y(r.size(), std::numbers::pi / 2.0);
  const auto bound = braking_bound_m_s(r, facing_y, s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_TRUE(bound.ok()) << bound.error().message;
  expect_brakes_before_unknown((*bound)[100], 2.8 - 1.55);
}

TEST(BrakingBound, ASpeedCapIsKeptAndBrakedToFromBehind) {
  // Everything sensed; a cap of 1 m/s at tick 250 (x = 3.04), none elsewhere.
  const Sensing s(0, 100.0, 0);
  Route r;
  drive(r, 0.55, 0.01, 400);
  std::vector<double> caps;
  for (std::size_t k = 0; k < r.size(); ++k) {
    caps.push_back(k == 250 ? 1.0 : std::numeric_limits<double>::infinity());
  }
  const auto bound =
      braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep, caps);
  ASSERT_TRUE(bound.ok()) << bound.error().message;
  EXPECT_NEAR((*bound)[250], 1.0, 1e-12);
  // 1 m before it, what brakes to 1 m/s within 1 m; from rest, the ramp is lower still.
  EXPECT_NEAR((*bound)[150], std::sqrt(1.0 + 2.0 * 0.6 * 1.0), 1e-9);
  EXPECT_NEAR((*bound)[50], 1.53, 1e-9);
  // After it, the ramp from the cap again.
  EXPECT_NEAR((*bound)[260], 1.3, 1e-9);
  const auto uncapped =
      braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_TRUE(uncapped.ok());
  for (std::size_t k = 0; k < r.size(); ++k) EXPECT_LE((*bound)[k], (*uncapped)[k]) << k;
  EXPECT_GT((*uncapped)[250], 2.0);
}

TEST(BrakingBound, BadInputIsNamed) {
  const Sensing s(0, 100.0, 0);
  const Route r(10, {5.0, 1.0});
  const std::vector<std::uint32_t> too_few(10, 0);
  const auto short_ticks =
      braking_bound_m_s(r, facing_x(r), s.grid, too_few, kChassis, kLimits, kStep);
  ASSERT_FALSE(short_ticks.ok());
  EXPECT_NE(short_ticks.error().message.find("10 sensed ticks for a grid of 2000 cells"),
            std::string::npos)
      << short_ticks.error().message;
  const auto no_brakes = braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis,
                                           SpeedLimits{3.0, 0.5, 0.6, 0.0}, kStep);
  ASSERT_FALSE(no_brakes.ok());
  EXPECT_NE(no_brakes.error().message.find("braking deceleration"), std::string::npos);
  const std::vector<double> headings(3, 0.0);
  const auto few_headings =
      braking_bound_m_s(r, headings, s.grid, s.ticks, kChassis, kLimits, kStep);
  ASSERT_FALSE(few_headings.ok());
  EXPECT_NE(few_headings.error().message.find("3 headings for a route of 10 points"),
            std::string::npos)
      << few_headings.error().message;
  const std::vector<double> few_caps(4, 1.0);
  const auto short_caps =
      braking_bound_m_s(r, facing_x(r), s.grid, s.ticks, kChassis, kLimits, kStep, few_caps);
  ASSERT_FALSE(short_caps.ok());
  EXPECT_NE(short_caps.error().message.find("4 speed caps for a route of 10 points"),
            std::string::npos)
      << short_caps.error().message;
}

}  // namespace
}  // namespace grip::sim
