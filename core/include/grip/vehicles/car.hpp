#pragma once
// Car-like vehicle, forward and reverse, with acceleration and steering-velocity control
// (the paper's Sec. V, vehicle 3). Reference point: the rear axle centre.
//
// State (x [m], y [m], theta [rad], v [m/s], delta [rad]); control (a [m/s^2], delta' [rad/s]):
//   x' = v cos(theta) cos(delta)   y' = v sin(theta) cos(delta)   theta' = v sin(delta) / L
//   v' = a                         delta' = steering velocity
// v saturates in [min_speed, max_speed] (reverse is slower), delta in [-max_steer, max_steer].
// Contingency (paper): maximal deceleration to zero speed with zero steering velocity, so the
// car comes to rest with zero forward and steering velocities.

#include <Eigen/Core>

#include "grip/vehicles/vehicle.hpp"

namespace grip {

struct CarParams {
  double max_speed_m_s = 3.0;   // paper: v <= 3
  double min_speed_m_s = -0.5;  // paper: reverse down to about -0.5
  double max_accel_m_s2 = 0.6;  // paper: |a| <= 0.6
  // The contingency's deceleration: a vehicle's brakes may stop it harder than its drive
  // accelerates it. Plans may hold |a| up to the larger of the two.
  double braking_decel_m_s2 = 0.6;                                // paper: the acceleration bound
  double max_steer_rad = std::numbers::pi / 4;                    // paper: |delta| <= 45 deg
  double max_steer_rate_rad_s = 19.5 * std::numbers::pi / 180.0;  // paper: 19.5 (deg/s read)
  double wheelbase_m = 0.5;                                       // L
  Footprint footprint{0.6, 0.15, 0.2};  // 0.75 m x 0.4 m around the rear axle
  // The share of the planner's sampled controls that steer speed and steering angle to a
  // random target (sample_control with a state), in [0, 1].
  double velocity_target_share = 0.5;

  Status validate() const;
  bool operator==(const CarParams&) const = default;
};

class Car {
 public:
  static constexpr VehicleKind kKind = VehicleKind::kCar;
  static constexpr int kStateDim = 5;
  using State = Eigen::Matrix<double, 5, 1>;
  using Control = Eigen::Matrix<double, 2, 1>;

  static Result<Car> create(const CarParams& params);

  State step(const State& q, const Control& u, double dt) const noexcept;
  // Acceleration and steering rate uniform within the limits.
  Control sample_control(Random& rng) const noexcept;
  // The control for a hold of hold_s from q: with velocity_target_share, the acceleration and
  // steering rate that bring q's speed and steering angle to a random forward speed and
  // steering angle at the end of the hold (as far as the limits allow); otherwise uniform.
  Control sample_control(const State& q, double hold_s, Random& rng) const noexcept;
  Control braking_control(const State& q) const noexcept;
  State brake_step(const State& q, double dt) const noexcept;
  bool is_stopped(const State& q) const noexcept { return q[3] == 0.0; }
  double max_stopping_time_s() const noexcept {
    return std::max(params_.max_speed_m_s, -params_.min_speed_m_s) / params_.braking_decel_m_s2;
  }
  double max_speed_m_s() const noexcept {
    return std::max(params_.max_speed_m_s, -params_.min_speed_m_s);
  }
  double max_turn_rate_rad_s() const noexcept {
    return max_speed_m_s() * std::sin(params_.max_steer_rad) / params_.wheelbase_m;
  }
  // The rear axle's circle at full steering lock: L / tan(max_steer).
  double min_turning_radius_m() const noexcept {
    return params_.wheelbase_m / std::tan(params_.max_steer_rad);
  }
  const Footprint& footprint() const noexcept { return params_.footprint; }
  // BoundsMotionNearState: |v| and |delta| change at most at the larger of the acceleration
  // and braking bounds and at the steering rate.
  double speed_bound_m_s(const State& q, double tau) const noexcept {
    return std::min(std::abs(q[3]) + accel_bound_m_s2() * tau, max_speed_m_s());
  }
  double turn_rate_bound_rad_s(const State& q, double tau) const noexcept {
    const double steer =
        std::min(std::abs(q[4]) + params_.max_steer_rate_rad_s * tau, params_.max_steer_rad);
    return speed_bound_m_s(q, tau) * std::sin(steer) / params_.wheelbase_m;
  }
  // LimitsAcceleration.
  double braking_decel_m_s2() const noexcept { return params_.braking_decel_m_s2; }
  double accel_bound_m_s2() const noexcept {
    return std::max(params_.max_accel_m_s2, params_.braking_decel_m_s2);
  }
  double max_reverse_speed_m_s() const noexcept { return -params_.min_speed_m_s; }
  double speed_m_s(const State& q) const noexcept { return std::abs(q[3]); }
  Status validate_state(const State& q) const;
  Status validate_control(const Control& u) const;
  State rest_state(double x, double y, double theta) const noexcept {
    State q;
    q << x, y, theta, 0.0, 0.0;
    return q;
  }
  const CarParams& params() const noexcept { return params_; }

 private:
  explicit Car(const CarParams& params) : params_(params) {}
  CarParams params_;
};

}  // namespace grip
