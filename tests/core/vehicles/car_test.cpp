#include "grip/vehicles/car.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "sampled_edge_ends.hpp"

namespace grip {
namespace {

class CarTest : public ::testing::Test {
 protected:
  Car car = Car::create(CarParams{}).value();
  static constexpr double kDt = 0.02;

  Car::State drive(Car::State q, const Car::Control& u, double seconds) const {
    const int steps = static_cast<int>(std::lround(seconds / kDt));
    for (int i = 0; i < steps; ++i) q = car.step(q, u, kDt);
    return q;
  }
  static Car::State state(double x, double y, double th, double v, double delta) {
    Car::State q;
    q << x, y, th, v, delta;
    return q;
  }
};

TEST_F(CarTest, AcceleratingStraightCoversHalfATSquared) {
  const auto q = drive(car.rest_state(0, 0, std::numbers::pi / 2), {0.5, 0.0}, 3.0);
  EXPECT_NEAR(q[3], 1.5, 1e-9);
  EXPECT_NEAR(q[0], 0.0, 1e-9);
  EXPECT_NEAR(q[1], 0.5 * 0.5 * 9.0, 1e-9);
}

TEST_F(CarTest, ConstantSpeedAndSteeringDriveACircleOfRadiusLOverTanDelta) {
  // theta' = v sin(delta) / L; speed along the path v cos(delta); radius L / tan(delta).
  const double delta = 0.3;
  const double v = 1.0;
  const double t = 2.0;
  const auto q = drive(state(0, 0, 0, v, delta), {0.0, 0.0}, t);
  const double omega = v * std::sin(delta) / 0.5;
  const double radius = 0.5 / std::tan(delta);
  EXPECT_NEAR(q[2], omega * t, 1e-9);
  EXPECT_NEAR(q[0], radius * std::sin(omega * t), 1e-5);
  EXPECT_NEAR(q[1], radius * (1.0 - std::cos(omega * t)), 1e-5);
}

TEST_F(CarTest, SpeedAndSteeringSaturateAtTheirLimits) {
  const auto reverse = drive(car.rest_state(0, 0, 0), {-0.6, 0.3}, 10.0);
  EXPECT_DOUBLE_EQ(reverse[3], -0.5);  // reverse is slower
  EXPECT_DOUBLE_EQ(reverse[4], std::numbers::pi / 4);
  const auto forward = drive(car.rest_state(0, 0, 0), {0.6, -0.3}, 10.0);
  EXPECT_DOUBLE_EQ(forward[3], 3.0);
  EXPECT_DOUBLE_EQ(forward[4], -std::numbers::pi / 4);
}

TEST_F(CarTest, ContingencyBrakesAtTheLimitToRestKeepingTheSteeringAngle) {
  Car::State q = state(0, 0, 0, 3.0, 0.0);
  const auto u = car.braking_control(q);
  EXPECT_DOUBLE_EQ(u[0], -0.6);
  EXPECT_DOUBLE_EQ(u[1], 0.0);
  int steps = 0;
  while (!car.is_stopped(q)) {
    q = car.brake_step(q, kDt);
    ++steps;
    ASSERT_LE(steps * kDt, car.max_stopping_time_s() + kDt);
  }
  EXPECT_NEAR(steps * kDt, 5.0, kDt);
  EXPECT_NEAR(q[0], 3.0 * 3.0 / (2.0 * 0.6), 1e-6);  // v^2 / (2 a) = 7.5 m
  EXPECT_EQ(q[3], 0.0);
}

TEST(CarBraking, BrakesHarderThanItAcceleratesWhenItsBrakesAllow) {
  CarParams p;
  p.braking_decel_m_s2 = 1.2;
  const Car car = Car::create(p).value();
  Car::State q;
  q << 0, 0, 0, 3.0, 0.0;
  EXPECT_DOUBLE_EQ(car.braking_control(q)[0], -1.2);
  EXPECT_DOUBLE_EQ(car.max_stopping_time_s(), 2.5);
  while (!car.is_stopped(q)) q = car.brake_step(q, 0.05);
  EXPECT_NEAR(q[0], 3.0 * 3.0 / (2.0 * 1.2), 1e-6);  // v^2 / (2 d) = 3.75 m
  // The executor accepts the braking control, and no more than the larger limit.
  EXPECT_TRUE(car.validate_control(Car::Control{-1.2, 0.0}));
  EXPECT_FALSE(car.validate_control(Car::Control{-1.3, 0.0}));
  // Sampled controls stay within the drive's own acceleration.
  Random rng(3);
  for (int i = 0; i < 1000; ++i) EXPECT_LE(std::abs(car.sample_control(rng)[0]), 0.6);
  p.braking_decel_m_s2 = 0.0;
  auto refused = Car::create(p);
  ASSERT_FALSE(refused);
  EXPECT_NE(refused.error().message.find("braking_decel_m_s2"), std::string::npos);
}

TEST_F(CarTest, ReversingCarBrakesForwardToRest) {
  Car::State q = state(0, 0, 0, -0.5, 0.2);
  EXPECT_DOUBLE_EQ(car.braking_control(q)[0], 0.6);
  while (!car.is_stopped(q)) q = car.brake_step(q, kDt);
  EXPECT_DOUBLE_EQ(q[4], 0.2);
  EXPECT_LT(q[0], 0.0);
}

TEST_F(CarTest, SampledControlsStayWithinLimits) {
  Random rng(3);
  for (int i = 0; i < 10'000; ++i) {
    const auto u = car.sample_control(rng);
    ASSERT_TRUE(car.validate_control(u));
  }
}

TEST(CarSampling, ControlsAimedAtAVelocityEndEdgesBelowFullLockAndForward) {
  // Edges of 2.5 s from rest and from a turn: the share that ends at full steering lock, and
  // the share that ends reversing.
  const auto edge_ends = [](double velocity_target_share) {
    CarParams params;
    params.velocity_target_share = velocity_target_share;
    Car::State rest;
    rest << 0.0, 0.0, 0.0, 0.0, 0.0;
    Car::State turning;
    turning << 0.0, 0.0, 0.0, 1.0, 0.6;
    return testing::share_of_edge_ends(
        Car::create(params).value(), {rest, turning}, 2.5,
        [&](const Car::State& q) { return std::abs(q[4]) > 0.99 * params.max_steer_rad; },
        [](const Car::State& q) { return q[3] < 0.0; });
  };
  // Uniform controls: edges from a turn pile up at full lock, and a third of them reverse.
  const auto [uniform_at_full_lock, uniform_reversing] = edge_ends(0.0);
  EXPECT_GT(uniform_at_full_lock, 0.15);
  EXPECT_GT(uniform_reversing, 0.2);
  const auto [aimed_at_full_lock, aimed_reversing] = edge_ends(1.0);
  EXPECT_LT(aimed_at_full_lock, 0.05);
  EXPECT_EQ(aimed_reversing, 0.0);
}

TEST_F(CarTest, InvalidParametersAndStatesAreRefused) {
  CarParams p;
  p.min_speed_m_s = 1.0;
  auto r = Car::create(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("min_speed_m_s"), std::string::npos);
  p = CarParams{};
  p.max_steer_rad = 2.0;
  EXPECT_FALSE(Car::create(p));
  p = CarParams{};
  p.wheelbase_m = -0.5;
  EXPECT_FALSE(Car::create(p));
  p = CarParams{};
  p.velocity_target_share = -0.1;
  r = Car::create(p);
  ASSERT_FALSE(r);
  EXPECT_NE(r.error().message.find("velocity_target_share"), std::string::npos);
  EXPECT_FALSE(car.validate_state(state(0, 0, 0, 3.5, 0)));
  EXPECT_FALSE(car.validate_state(state(0, 0, 0, 0, 1.0)));
  EXPECT_FALSE(car.validate_state(state(INFINITY, 0, 0, 0, 0)));
}

TEST(VehicleNames, RoundTripAndUnknownNamesListTheValidOnes) {
  for (VehicleKind k :
       {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration, VehicleKind::kCar}) {
    EXPECT_EQ(vehicle_kind_from_name(vehicle_name(k)).value(), k);
  }
  auto bad = vehicle_kind_from_name("tank");
  ASSERT_FALSE(bad);
  EXPECT_NE(bad.error().message.find("dd-vel, dd-accel, car"), std::string::npos);
}

}  // namespace
}  // namespace grip
