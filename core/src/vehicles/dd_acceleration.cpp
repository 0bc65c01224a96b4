#include "grip/vehicles/dd_acceleration.hpp"

#include <algorithm>
#include <string>

namespace grip {

Status DdAccelerationParams::validate() const {
  if (auto s = validate_positive("dd-accel.max_wheel_speed_m_s", max_wheel_speed_m_s); !s) {
    return s;
  }
  if (auto s = validate_positive("dd-accel.max_turn_rate_rad_s", max_turn_rate_rad_s); !s) {
    return s;
  }
  if (auto s = validate_positive("dd-accel.max_wheel_accel_m_s2", max_wheel_accel_m_s2); !s) {
    return s;
  }
  if (auto s = validate_positive("dd-accel.braking_decel_m_s2", braking_decel_m_s2); !s) return s;
  if (auto s = validate_positive("dd-accel.half_axle_m", half_axle_m); !s) return s;
  if (auto s = validate_share("dd-accel.velocity_target_share", velocity_target_share); !s) {
    return s;
  }
  return validate_footprint("dd-accel", footprint);
}

Result<DdAcceleration> DdAcceleration::create(const DdAccelerationParams& params) {
  if (auto s = params.validate(); !s) return s.error();
  return DdAcceleration(params);
}

namespace {
// Wheel speeds after accelerating for `t`: linear, held at +-vmax, and with their difference
// held at the turn-rate bound (then only the common part of the acceleration acts).
void wheel_speeds_after(double vl, double vr, double al, double ar, double t, double vmax,
                        double max_diff, double& out_l, double& out_r) noexcept {
  out_l = std::clamp(vl + al * t, -vmax, vmax);
  out_r = std::clamp(vr + ar * t, -vmax, vmax);
  const double diff = out_r - out_l;
  if (std::abs(diff) > max_diff) {
    const double mean = 0.5 * (out_l + out_r);
    const double half = 0.5 * std::copysign(max_diff, diff);
    out_l = mean - half;
    out_r = mean + half;
  }
}
}  // namespace

DdAcceleration::State DdAcceleration::step(const State& q, const Control& u,
                                           double dt) const noexcept {
  // The wheel speeds are integrated exactly; the pose with the midpoint rule on them.
  const double vmax = params_.max_wheel_speed_m_s;
  const double max_diff = 2.0 * params_.half_axle_m * params_.max_turn_rate_rad_s;
  const double inv_axle = 1.0 / (2.0 * params_.half_axle_m);
  double vl_half = 0.0;
  double vr_half = 0.0;
  wheel_speeds_after(q[3], q[4], u[0], u[1], 0.5 * dt, vmax, max_diff, vl_half, vr_half);
  const double theta_half = q[2] + 0.5 * dt * (q[4] - q[3]) * inv_axle;
  const double v_half = 0.5 * (vl_half + vr_half);
  State next;
  next[0] = q[0] + dt * v_half * std::cos(theta_half);
  next[1] = q[1] + dt * v_half * std::sin(theta_half);
  next[2] = wrap_angle(q[2] + dt * (vr_half - vl_half) * inv_axle);
  wheel_speeds_after(q[3], q[4], u[0], u[1], dt, vmax, max_diff, next[3], next[4]);
  return next;
}

DdAcceleration::Control DdAcceleration::sample_control(Random& rng) const noexcept {
  const double a = params_.max_wheel_accel_m_s2;
  const double a_left = rng.uniform(-a, a);
  const double a_right = rng.uniform(-a, a);
  return {a_left, a_right};
}

DdAcceleration::Control DdAcceleration::sample_control(const State& q, double hold_s,
                                                       Random& rng) const noexcept {
  // Uniform accelerations held for 1-4 s leave the turn rate at its limit on most edges
  // (|a_r - a_l| / 2L saturates pi/2 rad/s in under a second), so the tree is made of tight
  // spirals and the vehicle loops. A target in velocity space instead ends edges at every turn
  // rate, straight ones included, and at speed: the target's speed is drawn forward.
  if (!(rng.uniform01() < params_.velocity_target_share)) return sample_control(rng);
  const double vmax = params_.max_wheel_speed_m_s;
  const double a = params_.max_wheel_accel_m_s2;
  const double speed = rng.uniform(0.0, vmax);
  const double turn_rate = rng.uniform(-params_.max_turn_rate_rad_s, params_.max_turn_rate_rad_s);
  // The target's wheel speeds within their limits: near top speed, less of a turn.
  const double room = vmax - speed;
  const double half_diff = std::clamp(params_.half_axle_m * turn_rate, -room, room);
  // Where the limit does not allow both in the hold, the turn comes first: it shapes the path,
  // and the speed follows on the next edge.
  const double half_turn_accel = std::clamp((half_diff - 0.5 * (q[4] - q[3])) / hold_s, -a, a);
  const double speed_room = a - std::abs(half_turn_accel);
  const double speed_accel =
      std::clamp((speed - 0.5 * (q[3] + q[4])) / hold_s, -speed_room, speed_room);
  return {speed_accel - half_turn_accel, speed_accel + half_turn_accel};
}

DdAcceleration::Control DdAcceleration::braking_control(const State& q) const noexcept {
  // The faster wheel brakes at the limit; the other is scaled so both stop together. With the
  // ratio fixed the wheel speed difference shrinks too, so the turn-rate bound holds.
  // Each wheel's share of the fastest speed first: decel / fastest overflows for a subnormal
  // speed, and infinity times a wheel at rest is not a number.
  const double fastest = std::max(std::abs(q[3]), std::abs(q[4]));
  if (fastest == 0.0) return Control::Zero();
  const double decel = params_.braking_decel_m_s2;
  return {-(q[3] / fastest) * decel, -(q[4] / fastest) * decel};
}

DdAcceleration::State DdAcceleration::brake_step(const State& q, double dt) const noexcept {
  const double fastest = std::max(std::abs(q[3]), std::abs(q[4]));
  const double time_to_stop = fastest / params_.braking_decel_m_s2;
  const Control u = braking_control(q);
  if (time_to_stop > dt) return step(q, u, dt);
  State rest = time_to_stop > 0.0 ? step(q, u, time_to_stop) : q;
  rest[3] = 0.0;
  rest[4] = 0.0;
  return rest;
}

Status DdAcceleration::validate_state(const State& q) const {
  if (auto s = validate_finite_state("dd-accel", q.data(), kStateDim); !s) return s;
  const double vmax = params_.max_wheel_speed_m_s;
  if (std::abs(q[3]) > vmax || std::abs(q[4]) > vmax) {
    return invalid_argument("dd-accel wheel speed exceeds max_wheel_speed_m_s " +
                            std::to_string(vmax) + " (got " + std::to_string(q[3]) + ", " +
                            std::to_string(q[4]) + ")");
  }
  return Ok{};
}

Status DdAcceleration::validate_control(const Control& u) const {
  if (auto s = validate_finite_state("dd-accel control", u.data(), 2); !s) return s;
  const double a = std::max(params_.max_wheel_accel_m_s2, params_.braking_decel_m_s2);
  if (std::abs(u[0]) > a + 1e-9 || std::abs(u[1]) > a + 1e-9) {
    return invalid_argument("dd-accel wheel acceleration exceeds " + std::to_string(a) +
                            " m/s^2 (max_wheel_accel_m_s2 or braking_decel_m_s2)");
  }
  return Ok{};
}

}  // namespace grip
