#include "grip/vehicles/dd_velocity.hpp"

#include <algorithm>
#include <string>

namespace grip {

Status DdVelocityParams::validate() const {
  if (auto s = validate_positive("dd-vel.max_wheel_speed_m_s", max_wheel_speed_m_s); !s) return s;
  if (auto s = validate_positive("dd-vel.max_turn_rate_rad_s", max_turn_rate_rad_s); !s) return s;
  if (auto s = validate_positive("dd-vel.half_axle_m", half_axle_m); !s) return s;
  if (auto s = validate_share("dd-vel.top_speed_share", top_speed_share); !s) return s;
  return validate_footprint("dd-vel", footprint);
}

Result<DdVelocity> DdVelocity::create(const DdVelocityParams& params) {
  if (auto s = params.validate(); !s) return s.error();
  return DdVelocity(params);
}

DdVelocity::State DdVelocity::derivative(const State& q, const Control& u) const noexcept {
  const double v = 0.5 * (u[0] + u[1]);
  const double omega = (u[1] - u[0]) / (2.0 * params_.half_axle_m);
  return {v * std::cos(q[2]), v * std::sin(q[2]), omega};
}

DdVelocity::State DdVelocity::step(const State& q, const Control& u, double dt) const noexcept {
  State next = midpoint_step(*this, q, u, dt);
  next[2] = wrap_angle(next[2]);
  return next;
}

DdVelocity::Control DdVelocity::sample_control(Random& rng) const noexcept {
  // Forward speed and turn rate uniform within their limits, mapped to wheel speeds; the turn
  // shrinks where a wheel would exceed its limit. But top_speed_share of the samples drive
  // forward or backward as fast as their turn rate allows (the faster wheel at its limit):
  // with uniform speeds alone the tree's edges average half of top speed, and so did the
  // vehicle, since path selection weighs length and sight, not time. Not all of them: at top
  // speed the robot turns on a radius of 1.7 m, and tight places need the slow, sharp turns.
  const double vmax = params_.max_wheel_speed_m_s;
  if (rng.uniform01() < params_.top_speed_share) {
    const double max_half_diff = std::min(params_.half_axle_m * params_.max_turn_rate_rad_s, vmax);
    const double half_diff = rng.uniform(-max_half_diff, max_half_diff);
    const double v = (rng.uniform01() < 0.5 ? -1.0 : 1.0) * (vmax - std::abs(half_diff));
    return {v - half_diff, v + half_diff};
  }
  const double v = rng.uniform(-vmax, vmax);
  const double max_diff =
      std::min(2.0 * params_.half_axle_m * params_.max_turn_rate_rad_s, 2.0 * (vmax - std::abs(v)));
  const double half_diff = 0.5 * rng.uniform(-max_diff, max_diff);
  return {v - half_diff, v + half_diff};
}

double DdVelocity::speed_m_s(const State&, const Control& u) const noexcept {
  return std::abs(0.5 * (u[0] + u[1]));
}

Status DdVelocity::validate_state(const State& q) const {
  return validate_finite_state("dd-vel", q.data(), kStateDim);
}

Status DdVelocity::validate_control(const Control& u) const {
  if (auto s = validate_finite_state("dd-vel control", u.data(), 2); !s) return s;
  const double vmax = params_.max_wheel_speed_m_s;
  const double tol = 1e-9;
  if (std::abs(u[0]) > vmax + tol || std::abs(u[1]) > vmax + tol) {
    return invalid_argument("dd-vel wheel speed exceeds max_wheel_speed_m_s " +
                            std::to_string(vmax) + " (got " + std::to_string(u[0]) + ", " +
                            std::to_string(u[1]) + ")");
  }
  const double turn = std::abs(u[1] - u[0]) / (2.0 * params_.half_axle_m);
  if (turn > params_.max_turn_rate_rad_s + tol) {
    return invalid_argument("dd-vel turn rate " + std::to_string(turn) +
                            " rad/s exceeds max_turn_rate_rad_s " +
                            std::to_string(params_.max_turn_rate_rad_s));
  }
  return Ok{};
}

}  // namespace grip
