#include "grip/planner/step_margin.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "grip/common/random.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip {
namespace {

constexpr double kDt = 0.05;

// The farthest any chassis corner moves between q and p (the chassis is a rectangle: a rigid
// motion moves its points farthest at a corner).
template <typename State>
double corner_motion_m(const Footprint& f, const State& q, const State& p) {
  const std::array<std::array<double, 2>, 4> corners = {{{f.front_m, f.half_width_m},
                                                         {f.front_m, -f.half_width_m},
                                                         {-f.rear_m, f.half_width_m},
                                                         {-f.rear_m, -f.half_width_m}}};
  double most = 0.0;
  for (const auto& c : corners) {
    const auto at = [&](const State& s) {
      return std::array<double, 2>{s[0] + std::cos(s[2]) * c[0] - std::sin(s[2]) * c[1],
                                   s[1] + std::sin(s[2]) * c[0] + std::cos(s[2]) * c[1]};
    };
    const auto a = at(q);
    const auto b = at(p);
    most = std::max(most, std::hypot(a[0] - b[0], a[1] - b[1]));
  }
  return most;
}

// From random states under random controls (braking included), the chassis moves no farther
// within half a step of a state than that state's margin: a check there covers the motion.
template <typename V, typename DrawState, typename DrawControl>
void margins_cover_half_a_step(const V& vehicle, DrawState draw_state, DrawControl draw_control) {
  Random rng(5);
  constexpr std::size_t kFine = 100;
  int smaller = 0;
  for (int n = 0; n < 3000; ++n) {
    typename V::State q = draw_state(rng);
    const typename V::Control u = draw_control(rng);
    std::array<typename V::State, kFine + 1> path;
    path[0] = q;
    for (std::size_t k = 1; k <= kFine; ++k) path[k] = vehicle.step(path[k - 1], u, kDt / kFine);
    // The check in the middle of the step sees half a step before and after it.
    const typename V::State& checked = path[kFine / 2];
    const double margin = state_collision_margin_m(vehicle, checked, kDt);
    ASSERT_LE(margin, step_collision_margin_m(vehicle, kDt));
    for (const auto& p : path) {
      ASSERT_LE(corner_motion_m(vehicle.footprint(), checked, p), margin + 1e-9) << "sample " << n;
    }
    smaller += margin < 0.5 * step_collision_margin_m(vehicle, kDt) ? 1 : 0;
  }
  EXPECT_GT(smaller, 300);  // slow states do get the smaller margin
}

TEST(StateCollisionMargin, ACarsCoversHalfAStepEitherSide) {
  const Car car = Car::create(CarParams{}).value();
  const CarParams& p = car.params();
  const double accel = std::max(p.max_accel_m_s2, p.braking_decel_m_s2);
  margins_cover_half_a_step(
      car,
      [&](Random& rng) {
        Car::State q;
        q << rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-3.1, 3.1),
            rng.uniform(p.min_speed_m_s, p.max_speed_m_s),
            rng.uniform(-p.max_steer_rad, p.max_steer_rad);
        return q;
      },
      [&](Random& rng) {
        return Car::Control{rng.uniform(-accel, accel),
                            rng.uniform(-p.max_steer_rate_rad_s, p.max_steer_rate_rad_s)};
      });
}

TEST(StateCollisionMargin, ADdAccelerationsCoversHalfAStepEitherSide) {
  DdAccelerationParams params;
  params.braking_decel_m_s2 = 1.2;  // brakes harder than it drives
  const DdAcceleration robot = DdAcceleration::create(params).value();
  const double room = params.half_axle_m * params.max_turn_rate_rad_s;
  margins_cover_half_a_step(
      robot,
      [&](Random& rng) {
        const double v = rng.uniform(-params.max_wheel_speed_m_s, params.max_wheel_speed_m_s);
        const double half_diff = rng.uniform(-room, room);
        DdAcceleration::State q;
        q << rng.uniform(-5.0, 5.0), rng.uniform(-5.0, 5.0), rng.uniform(-3.1, 3.1),
            std::clamp(v - half_diff, -params.max_wheel_speed_m_s, params.max_wheel_speed_m_s),
            std::clamp(v + half_diff, -params.max_wheel_speed_m_s, params.max_wheel_speed_m_s);
        return q;
      },
      [&](Random& rng) {
        return DdAcceleration::Control{rng.uniform(-1.2, 1.2), rng.uniform(-1.2, 1.2)};
      });
}

TEST(StateCollisionMargin, AtRestSmallAtTopSpeedFull) {
  const Car car = Car::create(CarParams{}).value();
  const double full = step_collision_margin_m(car, kDt);
  EXPECT_LT(state_collision_margin_m(car, car.rest_state(0.0, 0.0, 0.0), kDt), 0.05 * full);
  Car::State fast;
  fast << 0.0, 0.0, 0.0, car.params().max_speed_m_s, car.params().max_steer_rad;
  EXPECT_DOUBLE_EQ(state_collision_margin_m(car, fast, kDt), full);
  // A state that is not finite gets the full margin, never NaN.
  Car::State bad = fast;
  bad[3] = std::nan("");
  EXPECT_DOUBLE_EQ(state_collision_margin_m(car, bad, kDt), full);
  // A velocity-controlled robot can be at top speed a step after rest: always the full margin.
  const DdVelocity dd = DdVelocity::create(DdVelocityParams{}).value();
  EXPECT_DOUBLE_EQ(state_collision_margin_m(dd, dd.rest_state(0.0, 0.0, 0.0), kDt),
                   step_collision_margin_m(dd, kDt));
}

}  // namespace
}  // namespace grip
