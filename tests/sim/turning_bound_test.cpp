// The turning caps against hand-computed routes (a straight line, an arc, a turn on the spot, a
// car's steering onto an arc, one that steered at rest) and against the vehicles' own motion: a
// route the car or the differential drive drove under random controls is never capped below the
// speed it was driven at.

#include "grip/sim/turning_bound.hpp"

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <numbers>
#include <vector>

#include "grip/common/random.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"

namespace grip::sim {
namespace {

using Route = std::vector<std::array<double, 2>>;
constexpr double kInf = std::numeric_limits<double>::infinity();

// dd-accel's: 90 deg/s, wheels 0.2 m either side, 3 m/s and 0.6 m/s^2 at the wheels.
TurningLimits dd_limits() {
  TurningLimits l;
  l.max_turn_rate_rad_s = std::numbers::pi / 2.0;
  l.half_track_m = 0.2;
  l.max_wheel_speed_m_s = 3.0;
  l.wheel_accel_m_s2 = 0.6;
  return l;
}

// The car's: wheelbase 0.5 m, 19.5 deg/s of steering.
TurningLimits car_limits() {
  TurningLimits l;
  l.wheelbase_m = 0.5;
  l.max_steer_rate_rad_s = 19.5 * std::numbers::pi / 180.0;
  return l;
}

// Points every step_m along a circle of radius r_m (counter-clockwise, heading along it),
// starting at angle 0, appended to route and headings.
void arc(Route& route, std::vector<double>& headings, double r_m, double step_m, int points) {
  for (int k = 0; k < points; ++k) {
    const double a = step_m * k / r_m;
    route.push_back({r_m * std::sin(a), r_m - r_m * std::cos(a)});
    headings.push_back(a);
  }
}

TEST(TurningBound, AStraightRouteIsCappedOnlyByTheWheels) {
  Route route;
  std::vector<double> headings;
  for (int k = 0; k < 50; ++k) {
    route.push_back({0.02 * k, 1.0});
    headings.push_back(0.0);
  }
  const auto car = turning_caps_m_s(route, headings, car_limits());
  ASSERT_TRUE(car.ok()) << car.error().message;
  for (const double cap : *car) EXPECT_EQ(cap, kInf);
  const auto dd = turning_caps_m_s(route, headings, dd_limits());
  ASSERT_TRUE(dd.ok()) << dd.error().message;
  EXPECT_EQ((*dd)[0], kInf);  // no move yet
  for (std::size_t k = 1; k < dd->size(); ++k) EXPECT_NEAR((*dd)[k], 3.0, 1e-9) << k;
}

TEST(TurningBound, AnArcCapsTheDifferentialDriveByItsTurnRateAndWheels) {
  // Radius 1 m: the turn rate allows pi/2 m/s, the outer wheel 3 / 1.2 = 2.5 m/s. Radius 4 m:
  // 2 pi m/s and 3 / 1.05 m/s.
  for (const auto& [radius, expected] :
       {std::pair{1.0, std::numbers::pi / 2.0}, std::pair{4.0, 3.0 / 1.05}}) {
    Route route;
    std::vector<double> headings;
    arc(route, headings, radius, 0.02, 100);
    const auto caps = turning_caps_m_s(route, headings, dd_limits());
    ASSERT_TRUE(caps.ok()) << caps.error().message;
    // The chord is shorter than the arc by a factor of about 1 - (step / r)^2 / 24.
    for (std::size_t k = 1; k < caps->size(); ++k) EXPECT_NEAR((*caps)[k], expected, 1e-3) << k;
  }
  // A car holds its steering angle on an arc: nothing caps it.
  Route route;
  std::vector<double> headings;
  arc(route, headings, 1.0, 0.02, 100);
  const auto car = turning_caps_m_s(route, headings, car_limits());
  ASSERT_TRUE(car.ok());
  for (std::size_t k = 2; k < car->size(); ++k) EXPECT_GT((*car)[k], 1e3) << k;
}

TEST(TurningBound, TurningOnTheSpotAndSteeringAtRestCapAtZero) {
  // Straight to x = 0.5, a quarter turn on the spot, straight on along +y.
  Route route;
  std::vector<double> headings;
  for (int k = 0; k <= 25; ++k) {
    route.push_back({0.02 * k, 0.0});
    headings.push_back(0.0);
  }
  for (int k = 1; k <= 10; ++k) {
    route.push_back({0.5, 0.0});
    headings.push_back(std::numbers::pi / 20.0 * k);
  }
  for (int k = 1; k <= 25; ++k) {
    route.push_back({0.5, 0.02 * k});
    headings.push_back(std::numbers::pi / 2.0);
  }
  const auto dd = turning_caps_m_s(route, headings, dd_limits());
  ASSERT_TRUE(dd.ok()) << dd.error().message;
  for (std::size_t k = 26; k <= 35; ++k) EXPECT_EQ((*dd)[k], 0.0) << k;
  EXPECT_NEAR((*dd)[40], 3.0, 1e-9);
  // A car that stood, steered to full lock and drove on along a circle of 0.5 m: the
  // curvature jumps where it set off, which at any speed needs an instant of steering.
  Route car_route;
  std::vector<double> car_headings;
  for (int k = 0; k <= 25; ++k) {
    car_route.push_back({0.02 * k, 0.0});
    car_headings.push_back(0.0);
  }
  car_route.push_back(car_route.back());  // standing, steering
  car_headings.push_back(0.0);
  Route turn;
  std::vector<double> turn_headings;
  arc(turn, turn_headings, 0.5, 0.02, 20);
  for (std::size_t k = 1; k < turn.size(); ++k) {
    car_route.push_back({0.5 + turn[k][0], turn[k][1]});
    car_headings.push_back(turn_headings[k]);
  }
  const auto car = turning_caps_m_s(car_route, car_headings, car_limits());
  ASSERT_TRUE(car.ok()) << car.error().message;
  EXPECT_EQ((*car)[26], kInf);  // standing asks nothing
  // Where it set off: 45 deg of steering between two moves 0.02 m apart, at a mean angle of
  // 22.5 deg: 0.34 rad/s / (0.785 rad / 0.02 m x cos 22.5 deg) = 0.0094 m/s.
  const double delta = std::atan(0.5 / 0.5);
  const double expected = 19.5 * std::numbers::pi / 180.0 / (delta / 0.02 * std::cos(0.5 * delta));
  EXPECT_NEAR((*car)[27], expected, 1e-3 * expected);
  EXPECT_GT((*car)[30], 1e3);  // on the arc again
}

// Drives `vehicle` from rest under controls drawn uniformly within its limits, held 0.5 s each,
// and checks that no tick of the route is capped below the speed it was driven at.
template <typename V>
void expect_caps_above_the_driven_speed(const V& vehicle, const TurningLimits& limits,
                                        unsigned seed) {
  Random random(seed);
  typename V::State q = vehicle.rest_state(0.0, 0.0, 0.0);
  const double dt = 0.05;
  Route route{{q[0], q[1]}};
  std::vector<double> headings{q[2]};
  std::vector<double> speeds{0.0};
  typename V::Control u = vehicle.sample_control(random);
  for (int k = 1; k < 2000; ++k) {
    if (k % 10 == 0) u = vehicle.sample_control(random);
    // Finer integration inside the tick, as the executor's.
    for (int i = 0; i < 10; ++i) q = vehicle.step(q, u, dt / 10.0);
    route.push_back({q[0], q[1]});
    headings.push_back(q[2]);
    speeds.push_back(vehicle.speed_m_s(q));
  }
  const auto caps = turning_caps_m_s(route, headings, limits);
  ASSERT_TRUE(caps.ok()) << caps.error().message;
  int capped = 0;
  for (std::size_t k = 1; k < caps->size(); ++k) {
    // The speed over the tick lies between its ends' speeds; 2% for the chords, and 5 cm/s
    // where a tick passes through rest (its chord then no longer measures its curvature).
    const double driven = std::min(speeds[k], speeds[k - 1]);
    EXPECT_GE((*caps)[k] * 1.02 + 0.05, driven) << "tick " << k;
    capped += (*caps)[k] < 3.0 ? 1 : 0;
  }
  EXPECT_GT(capped, 100) << "the random route hardly turned: the check saw nothing";
}

TEST(TurningBound, NoRouteADrivenVehicleDroveIsCappedBelowItsSpeed) {
  const Car car = Car::create({}).value();
  const DdAcceleration dd = DdAcceleration::create({}).value();
  for (unsigned seed = 1; seed <= 5; ++seed) {
    expect_caps_above_the_driven_speed(car, car_limits(), seed);
    expect_caps_above_the_driven_speed(dd, dd_limits(), seed);
  }
}

TEST(TurningBound, BadInputIsNamed) {
  const Route route(10, {1.0, 1.0});
  const std::vector<double> headings(10, 0.0);
  TurningLimits negative = car_limits();
  negative.wheelbase_m = -0.5;
  const auto bad = turning_caps_m_s(route, headings, negative);
  ASSERT_FALSE(bad.ok());
  EXPECT_NE(bad.error().message.find("wheelbase"), std::string::npos) << bad.error().message;
  const std::vector<double> few(3, 0.0);
  const auto short_headings = turning_caps_m_s(route, few, car_limits());
  ASSERT_FALSE(short_headings.ok());
  EXPECT_NE(short_headings.error().message.find("3 headings for a route of 10 points"),
            std::string::npos)
      << short_headings.error().message;
}

}  // namespace
}  // namespace grip::sim
