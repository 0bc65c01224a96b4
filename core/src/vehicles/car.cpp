#include "grip/vehicles/car.hpp"

#include <algorithm>
#include <string>

namespace grip {

Status CarParams::validate() const {
  if (auto s = validate_positive("car.max_speed_m_s", max_speed_m_s); !s) return s;
  if (!std::isfinite(min_speed_m_s) || min_speed_m_s > 0.0) {
    return invalid_argument("car.min_speed_m_s must be finite and <= 0 (got " +
                            std::to_string(min_speed_m_s) + ")");
  }
  if (auto s = validate_positive("car.max_accel_m_s2", max_accel_m_s2); !s) return s;
  if (auto s = validate_positive("car.braking_decel_m_s2", braking_decel_m_s2); !s) return s;
  if (auto s = validate_positive("car.max_steer_rad", max_steer_rad); !s) return s;
  if (max_steer_rad >= std::numbers::pi / 2) {
    return invalid_argument("car.max_steer_rad must be < pi/2 (got " +
                            std::to_string(max_steer_rad) + ")");
  }
  if (auto s = validate_positive("car.max_steer_rate_rad_s", max_steer_rate_rad_s); !s) return s;
  if (auto s = validate_positive("car.wheelbase_m", wheelbase_m); !s) return s;
  if (auto s = validate_share("car.velocity_target_share", velocity_target_share); !s) return s;
  return validate_footprint("car", footprint);
}

Result<Car> Car::create(const CarParams& params) {
  if (auto s = params.validate(); !s) return s.error();
  return Car(params);
}

Car::State Car::step(const State& q, const Control& u, double dt) const noexcept {
  // Speed and steering angle are linear in time and held at their bounds, so they are
  // integrated exactly; the pose with the midpoint rule on them.
  const auto speed_after = [&](double t) {
    return std::clamp(q[3] + u[0] * t, params_.min_speed_m_s, params_.max_speed_m_s);
  };
  const auto steer_after = [&](double t) {
    return std::clamp(q[4] + u[1] * t, -params_.max_steer_rad, params_.max_steer_rad);
  };
  const double inv_wheelbase = 1.0 / params_.wheelbase_m;
  const double v_half = speed_after(0.5 * dt);
  const double delta_half = steer_after(0.5 * dt);
  const double theta_half = q[2] + 0.5 * dt * q[3] * std::sin(q[4]) * inv_wheelbase;
  const double along = v_half * std::cos(delta_half);
  State next;
  next[0] = q[0] + dt * along * std::cos(theta_half);
  next[1] = q[1] + dt * along * std::sin(theta_half);
  next[2] = wrap_angle(q[2] + dt * v_half * std::sin(delta_half) * inv_wheelbase);
  next[3] = speed_after(dt);
  next[4] = steer_after(dt);
  return next;
}

Car::Control Car::sample_control(Random& rng) const noexcept {
  const double a = rng.uniform(-params_.max_accel_m_s2, params_.max_accel_m_s2);
  const double steer_rate =
      rng.uniform(-params_.max_steer_rate_rad_s, params_.max_steer_rate_rad_s);
  return {a, steer_rate};
}

Car::Control Car::sample_control(const State& q, double hold_s, Random& rng) const noexcept {
  // Uniform controls held for 1-4 s end many edges from a turn at full lock, and a third of
  // them reversing; a target ends edges at every steering angle alike, at a forward speed.
  if (!(rng.uniform01() < params_.velocity_target_share)) return sample_control(rng);
  const double speed = rng.uniform(0.0, params_.max_speed_m_s);
  const double steer = rng.uniform(-params_.max_steer_rad, params_.max_steer_rad);
  return {std::clamp((speed - q[3]) / hold_s, -params_.max_accel_m_s2, params_.max_accel_m_s2),
          std::clamp((steer - q[4]) / hold_s, -params_.max_steer_rate_rad_s,
                     params_.max_steer_rate_rad_s)};
}

Car::Control Car::braking_control(const State& q) const noexcept {
  if (q[3] == 0.0) return Control::Zero();
  return {-std::copysign(params_.braking_decel_m_s2, q[3]), 0.0};
}

Car::State Car::brake_step(const State& q, double dt) const noexcept {
  const double time_to_stop = std::abs(q[3]) / params_.braking_decel_m_s2;
  const Control u = braking_control(q);
  if (time_to_stop > dt) return step(q, u, dt);
  State rest = time_to_stop > 0.0 ? step(q, u, time_to_stop) : q;
  rest[3] = 0.0;
  return rest;
}

Status Car::validate_state(const State& q) const {
  if (auto s = validate_finite_state("car", q.data(), kStateDim); !s) return s;
  if (q[3] > params_.max_speed_m_s || q[3] < params_.min_speed_m_s) {
    return invalid_argument("car speed " + std::to_string(q[3]) + " m/s outside [" +
                            std::to_string(params_.min_speed_m_s) + ", " +
                            std::to_string(params_.max_speed_m_s) + "]");
  }
  if (std::abs(q[4]) > params_.max_steer_rad) {
    return invalid_argument("car steering angle " + std::to_string(q[4]) +
                            " rad exceeds max_steer_rad " + std::to_string(params_.max_steer_rad));
  }
  return Ok{};
}

Status Car::validate_control(const Control& u) const {
  if (auto s = validate_finite_state("car control", u.data(), 2); !s) return s;
  const double max_accel = std::max(params_.max_accel_m_s2, params_.braking_decel_m_s2);
  if (std::abs(u[0]) > max_accel + 1e-9 || std::abs(u[1]) > params_.max_steer_rate_rad_s + 1e-9) {
    return invalid_argument("car control outside its limits (a " + std::to_string(u[0]) +
                            " m/s^2, steering rate " + std::to_string(u[1]) + " rad/s)");
  }
  return Ok{};
}

}  // namespace grip
