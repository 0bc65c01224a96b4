#include "grip/vehicles/dd_acceleration.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "sampled_edge_ends.hpp"

namespace grip {
namespace {

class DdAccelerationTest : public ::testing::Test {
 protected:
  DdAcceleration robot = DdAcceleration::create(DdAccelerationParams{}).value();
  static constexpr double kDt = 0.02;

  DdAcceleration::State drive(DdAcceleration::State q, const DdAcceleration::Control& u,
                              double seconds) const {
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) q = robot.step(q, u, kDt);
    return q;
  }
  static DdAcceleration::State state(double x, double y, double th, double vl, double vr) {
    DdAcceleration::State q;
    q << x, y, th, vl, vr;
    return q;
  }
};

TEST_F(DdAccelerationTest, EqualAccelerationsFromRestGiveHalfATSquared) {
  const auto q = drive(robot.rest_state(0, 0, 0), {0.5, 0.5}, 2.0);
  EXPECT_NEAR(q[3], 1.0, 1e-9);
  EXPECT_NEAR(q[4], 1.0, 1e-9);
  EXPECT_NEAR(q[0], 0.5 * 0.5 * 4.0, 1e-9);
  EXPECT_NEAR(q[1], 0.0, 1e-12);
}

TEST_F(DdAccelerationTest, WheelSpeedsSaturateAtTheLimitAndTheRobotCruises) {
  // 5 s to reach 3 m/s covering 7.5 m, then 5 s at 3 m/s: 22.5 m.
  const auto q = drive(robot.rest_state(0, 0, 0), {0.6, 0.6}, 10.0);
  EXPECT_DOUBLE_EQ(q[3], 3.0);
  EXPECT_DOUBLE_EQ(q[4], 3.0);
  EXPECT_NEAR(q[0], 22.5, 0.02);  // the step in which saturation begins is integrated smoothly
}

TEST_F(DdAccelerationTest, TheTurnRateLimitBoundsTheWheelSpeedDifference) {
  const auto q = drive(robot.rest_state(0, 0, 0), {-0.6, 0.6}, 5.0);
  const double max_diff = 2.0 * 0.2 * robot.max_turn_rate_rad_s();
  EXPECT_LE(std::abs(q[4] - q[3]), max_diff + 1e-12);
  EXPECT_NEAR(q[4] - q[3], max_diff, 1e-9);
}

TEST_F(DdAccelerationTest, BrakingStopsBothWheelsTogetherAtTheMaximalDeceleration) {
  DdAcceleration::State q = state(0, 0, 0, 2.0, 1.6);
  const auto u = robot.braking_control(q);
  EXPECT_NEAR(u[0], -0.6, 1e-12);   // the faster wheel brakes at the limit
  EXPECT_NEAR(u[1], -0.48, 1e-12);  // the other is scaled to stop at the same time
  double t = 0.0;
  while (!robot.is_stopped(q)) {
    q = robot.brake_step(q, kDt);
    t += kDt;
    ASSERT_LT(t, robot.max_stopping_time_s() + kDt);
    // The ratio stays fixed, so the two wheels reach zero together.
    if (!robot.is_stopped(q)) {
      EXPECT_NEAR(q[3], 1.25 * q[4], 1e-9);
    }
  }
  EXPECT_NEAR(t, 2.0 / 0.6, kDt);
  EXPECT_EQ(q[3], 0.0);
  EXPECT_EQ(q[4], 0.0);
}

TEST_F(DdAccelerationTest, BrakingFromASubnormalWheelSpeedRestsWithoutANumberLost) {
  // A plan with a subnormal acceleration (found by fuzz_plan) leaves one wheel creeping at a
  // subnormal speed and the other at rest: braking must neither overflow nor make NaN.
  const DdAcceleration::State q = state(3.2, 3.2, 0.0, 6.6e-310, 0.0);
  const auto u = robot.braking_control(q);
  EXPECT_DOUBLE_EQ(u[0], -0.6);
  EXPECT_EQ(u[1], 0.0);
  const auto rest = robot.brake_step(q, kDt);
  ASSERT_TRUE(robot.validate_state(rest).ok());
  EXPECT_TRUE(robot.is_stopped(rest));
  EXPECT_DOUBLE_EQ(rest[0], 3.2);
}

TEST_F(DdAccelerationTest, BrakingFromTopSpeedStopsWithinTheModelsStoppingTime) {
  DdAcceleration::State q = state(0, 0, 0, -3.0, -3.0);
  int steps = 0;
  while (!robot.is_stopped(q)) {
    q = robot.brake_step(q, kDt);
    ++steps;
  }
  EXPECT_LE(steps * kDt, robot.max_stopping_time_s() + kDt);
  EXPECT_NEAR(q[0], -7.5, 1e-6);  // v^2 / (2 a) = 9 / 1.2 backwards
}

TEST(DdAccelerationSampling, ControlsAimedAtAVelocityEndEdgesBelowTheTurnRateLimitAndForward) {
  // Edges of 2.5 s from rest and from a turn at the limit: the share that ends turning at the
  // turn-rate limit, and the share that ends driving backward.
  const auto edge_ends = [](double velocity_target_share) {
    DdAccelerationParams params;
    params.velocity_target_share = velocity_target_share;
    const double limit = 2.0 * params.half_axle_m * params.max_turn_rate_rad_s;  // wheel diff
    DdAcceleration::State rest;
    rest << 0.0, 0.0, 0.0, 0.0, 0.0;
    DdAcceleration::State turning;
    turning << 0.0, 0.0, 0.0, 1.0 - 0.5 * limit, 1.0 + 0.5 * limit;
    return testing::share_of_edge_ends(
        DdAcceleration::create(params).value(), {rest, turning}, 2.5,
        [&](const DdAcceleration::State& q) { return std::abs(q[4] - q[3]) > 0.99 * limit; },
        [](const DdAcceleration::State& q) { return q[3] + q[4] < 0.0; });
  };
  // Uniform accelerations: most edges end spinning at the limit (the loops the robot drove).
  const auto [uniform_at_limit, uniform_backward] = edge_ends(0.0);
  EXPECT_GT(uniform_at_limit, 0.5);
  EXPECT_GT(uniform_backward, 0.2);
  const auto [aimed_at_limit, aimed_backward] = edge_ends(1.0);
  EXPECT_LT(aimed_at_limit, 0.1);
  EXPECT_EQ(aimed_backward, 0.0);
}

TEST_F(DdAccelerationTest, InvalidParametersAndStatesAreRefused) {
  DdAccelerationParams p;
  p.max_wheel_accel_m_s2 = 0.0;
  auto r = DdAcceleration::create(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("max_wheel_accel_m_s2"), std::string::npos);
  p = DdAccelerationParams{};
  p.velocity_target_share = 1.5;
  r = DdAcceleration::create(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("velocity_target_share"), std::string::npos);
  EXPECT_FALSE(robot.validate_state(state(0, 0, 0, 3.5, 0)));
  EXPECT_FALSE(robot.validate_state(state(0, 0, std::nan(""), 0, 0)));
  EXPECT_TRUE(robot.validate_state(state(0, 0, 0, 3.0, -3.0)));
}

}  // namespace
}  // namespace grip
