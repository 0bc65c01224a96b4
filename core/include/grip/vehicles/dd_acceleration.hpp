#pragma once
// Differential-drive robot with acceleration control (the paper's Sec. V, vehicle 2).
//
// State (x [m], y [m], theta [rad], v_left [m/s], v_right [m/s]); control (a_left, a_right)
// [m/s^2]. The wheel rim speeds saturate at +-max_wheel_speed and their difference at the
// turn-rate limit, as a motor controller would hold them.
// Contingency (paper): the wheel with the larger |speed| brakes at the maximal deceleration,
// the other wheel's deceleration is chosen so that both reach zero at the same time.

#include <Eigen/Core>

#include "grip/vehicles/vehicle.hpp"

namespace grip {

struct DdAccelerationParams {
  double max_wheel_speed_m_s = 3.0;                   // paper: |V| <= 3
  double max_turn_rate_rad_s = std::numbers::pi / 2;  // paper: |theta'| <= 90 deg/s
  double max_wheel_accel_m_s2 = 0.6;                  // paper: |a| <= 0.6
  // The contingency's deceleration of the faster wheel: brakes may stop a vehicle harder than
  // its drive accelerates it. Plans may hold |a| up to the larger of the two.
  double braking_decel_m_s2 = 0.6;  // paper: the acceleration bound
  double half_axle_m = 0.2;         // L
  Footprint footprint{0.25, 0.25, 0.2};
  // The share of the planner's sampled controls that steer the wheel speeds to a random target
  // (sample_control with a state), in [0, 1].
  double velocity_target_share = 0.5;

  Status validate() const;
  bool operator==(const DdAccelerationParams&) const = default;
};

class DdAcceleration {
 public:
  static constexpr VehicleKind kKind = VehicleKind::kDdAcceleration;
  static constexpr int kStateDim = 5;
  using State = Eigen::Matrix<double, 5, 1>;
  using Control = Eigen::Matrix<double, 2, 1>;

  static Result<DdAcceleration> create(const DdAccelerationParams& params);

  State step(const State& q, const Control& u, double dt) const noexcept;
  // Wheel accelerations uniform within the limits.
  Control sample_control(Random& rng) const noexcept;
  // The control for a hold of hold_s from q: with velocity_target_share, the accelerations
  // that bring the wheel speeds from q's to a random forward speed and turn rate at the end of
  // the hold (as far as the limits allow); otherwise uniform.
  Control sample_control(const State& q, double hold_s, Random& rng) const noexcept;
  Control braking_control(const State& q) const noexcept;
  State brake_step(const State& q, double dt) const noexcept;
  bool is_stopped(const State& q) const noexcept { return q[3] == 0.0 && q[4] == 0.0; }
  double max_stopping_time_s() const noexcept {
    return params_.max_wheel_speed_m_s / params_.max_wheel_accel_m_s2;
  }
  double max_speed_m_s() const noexcept { return params_.max_wheel_speed_m_s; }
  double max_turn_rate_rad_s() const noexcept { return params_.max_turn_rate_rad_s; }
  double min_turning_radius_m() const noexcept { return 0.0; }
  const Footprint& footprint() const noexcept { return params_.footprint; }
  // BoundsMotionNearState: each wheel's speed changes at most at the larger of the acceleration
  // and braking bounds.
  double speed_bound_m_s(const State& q, double tau) const noexcept {
    return std::min(0.5 * (std::abs(q[3]) + std::abs(q[4])) + accel_bound_m_s2() * tau,
                    params_.max_wheel_speed_m_s);
  }
  double turn_rate_bound_rad_s(const State& q, double tau) const noexcept {
    return std::min(
        (std::abs(q[4] - q[3]) + 2.0 * accel_bound_m_s2() * tau) / (2.0 * params_.half_axle_m),
        params_.max_turn_rate_rad_s);
  }
  // LimitsAcceleration: of the faster wheel, which bounds the reference point's speed.
  double braking_decel_m_s2() const noexcept { return params_.braking_decel_m_s2; }
  double accel_bound_m_s2() const noexcept {
    return std::max(params_.max_wheel_accel_m_s2, params_.braking_decel_m_s2);
  }
  double max_reverse_speed_m_s() const noexcept { return params_.max_wheel_speed_m_s; }
  double speed_m_s(const State& q) const noexcept { return std::abs(0.5 * (q[3] + q[4])); }
  Status validate_state(const State& q) const;
  Status validate_control(const Control& u) const;
  State rest_state(double x, double y, double theta) const noexcept {
    State q;
    q << x, y, theta, 0.0, 0.0;
    return q;
  }
  const DdAccelerationParams& params() const noexcept { return params_; }

 private:
  explicit DdAcceleration(const DdAccelerationParams& params) : params_(params) {}
  DdAccelerationParams params_;
};

}  // namespace grip
