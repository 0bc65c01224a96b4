#include "grip/vehicles/dd_velocity.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <numbers>

namespace grip {
namespace {

class DdVelocityTest : public ::testing::Test {
 protected:
  DdVelocity robot = DdVelocity::create(DdVelocityParams{}).value();

  DdVelocity::State drive(DdVelocity::State q, const DdVelocity::Control& u, double seconds,
                          double dt = 0.02) const {
    const int steps = static_cast<int>(std::lround(seconds / dt));
    for (int i = 0; i < steps; ++i) q = robot.step(q, u, dt);
    return q;
  }
};

TEST_F(DdVelocityTest, EqualWheelSpeedsDriveStraightAtThatSpeed) {
  const auto q = drive({1.0, 2.0, 0.0}, {1.5, 1.5}, 2.0);
  EXPECT_NEAR(q[0], 4.0, 1e-9);
  EXPECT_NEAR(q[1], 2.0, 1e-9);
  EXPECT_NEAR(q[2], 0.0, 1e-12);
}

TEST_F(DdVelocityTest, OppositeWheelSpeedsTurnInPlaceAtTheHandComputedRate) {
  // theta' = (v_r - v_l) / (2 L) = 0.4 / 0.4 = 1 rad/s.
  const auto q = drive({0.0, 0.0, 0.0}, {-0.2, 0.2}, 1.0);
  EXPECT_NEAR(q[0], 0.0, 1e-12);
  EXPECT_NEAR(q[1], 0.0, 1e-12);
  EXPECT_NEAR(q[2], 1.0, 1e-9);
}

TEST_F(DdVelocityTest, ConstantWheelSpeedsFollowTheClosedFormArc) {
  // v = 1, omega = 0.5: x = v/omega sin(omega t), y = v/omega (1 - cos(omega t)).
  const double v = 1.0;
  const double omega = 0.5;
  const double half_diff = omega * 0.2;
  const double t = 3.0;
  const auto q = drive({0.0, 0.0, 0.0}, {v - half_diff, v + half_diff}, t);
  EXPECT_NEAR(q[0], v / omega * std::sin(omega * t), 1e-5);
  EXPECT_NEAR(q[1], v / omega * (1.0 - std::cos(omega * t)), 1e-5);
  EXPECT_NEAR(q[2], omega * t, 1e-9);
}

TEST_F(DdVelocityTest, AtThePlannersStepTheArcStaysWithinAMillimetreOverFiveSeconds) {
  // Top speed, top turn rate, the planner's 0.05 s step: the hardest case for the integrator.
  const double omega = robot.max_turn_rate_rad_s();
  const double v = 3.0 - omega * 0.2;
  const auto q = drive({0.0, 0.0, 0.0}, {v - omega * 0.2, v + omega * 0.2}, 5.0, 0.05);
  const double theta = std::remainder(omega * 5.0, 2.0 * std::numbers::pi);
  EXPECT_NEAR(q[0], v / omega * std::sin(omega * 5.0), 1e-3);
  EXPECT_NEAR(q[1], v / omega * (1.0 - std::cos(omega * 5.0)), 1e-3);
  EXPECT_NEAR(q[2], theta, 1e-9);
}

TEST_F(DdVelocityTest, SampledControlsStayWithinWheelAndTurnRateLimits) {
  Random rng(7);
  for (int i = 0; i < 10'000; ++i) {
    const auto u = robot.sample_control(rng);
    ASSERT_TRUE(robot.validate_control(u)) << robot.validate_control(u).error().message;
  }
}

TEST_F(DdVelocityTest, TheTopSpeedShareOfSampledControlsDrivesTheFasterWheelAtItsLimit) {
  for (const double share : {0.0, 0.8, 1.0}) {
    DdVelocityParams params;
    params.top_speed_share = share;
    const DdVelocity r = DdVelocity::create(params).value();
    Random rng(11);
    int at_limit = 0;
    int forward = 0;
    constexpr int kSamples = 20'000;
    for (int i = 0; i < kSamples; ++i) {
      const auto u = r.sample_control(rng);
      ASSERT_TRUE(r.validate_control(u)) << r.validate_control(u).error().message;
      if (std::max(std::abs(u[0]), std::abs(u[1])) > params.max_wheel_speed_m_s - 1e-9) {
        ++at_limit;
        forward += u[0] + u[1] > 0.0 ? 1 : 0;
      }
    }
    EXPECT_NEAR(static_cast<double>(at_limit) / kSamples, share, 0.01) << "share " << share;
    // Backward as often as forward: the sensor sees all around, either way explores.
    if (at_limit > 0) {
      EXPECT_NEAR(static_cast<double>(forward) / at_limit, 0.5, 0.02);
    }
  }
}

TEST_F(DdVelocityTest, ContingencyIsTrivialTheRobotStopsWhereItIs) {
  const DdVelocity::State q{3.0, 4.0, 1.0};
  EXPECT_TRUE(robot.is_stopped(q));
  EXPECT_EQ(robot.brake_step(q, 0.02), q);
  EXPECT_EQ(robot.max_stopping_time_s(), 0.0);
}

TEST_F(DdVelocityTest, InvalidParametersAreRefusedWithTheParameterNamed) {
  DdVelocityParams p;
  p.max_wheel_speed_m_s = -1.0;
  auto r = DdVelocity::create(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("max_wheel_speed_m_s"), std::string::npos);
  p = DdVelocityParams{};
  p.half_axle_m = std::nan("");
  EXPECT_FALSE(DdVelocity::create(p));
  p = DdVelocityParams{};
  p.top_speed_share = 1.5;
  auto share = DdVelocity::create(p);
  ASSERT_FALSE(share);
  EXPECT_NE(share.error().message.find("top_speed_share"), std::string::npos);
  p.top_speed_share = std::nan("");
  EXPECT_FALSE(DdVelocity::create(p));
  p = DdVelocityParams{};
  p.footprint.half_width_m = 0.0;
  auto f = DdVelocity::create(p);
  ASSERT_FALSE(f);
  EXPECT_NE(f.error().message.find("half_width_m"), std::string::npos);
}

TEST_F(DdVelocityTest, NanStatesAreRefused) {
  auto s = robot.validate_state({0.0, std::nan(""), 0.0});
  ASSERT_FALSE(s);
  EXPECT_NE(s.error().message.find("not finite"), std::string::npos);
}

}  // namespace
}  // namespace grip
