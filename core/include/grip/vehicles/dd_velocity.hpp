#pragma once
// Differential-drive robot with velocity control (the paper's Sec. V, vehicle 1).
//
// State (x [m], y [m], theta [rad]); control (v_left, v_right): wheel rim speeds [m/s] (the
// paper's R * V_L, R * V_R, so the wheel radius is folded into the control). Kinematics:
//   x' = (v_l + v_r)/2 cos(theta)   y' = (v_l + v_r)/2 sin(theta)   theta' = (v_r - v_l)/(2 L)
// with L the half axle. The robot is reducible to a holonomic one and its contingency is
// trivial: both wheels to zero, it stops where it is.

#include <Eigen/Core>

#include "grip/vehicles/vehicle.hpp"

namespace grip {

struct DdVelocityParams {
  double max_wheel_speed_m_s = 3.0;                   // paper: |V| <= 3
  double max_turn_rate_rad_s = std::numbers::pi / 2;  // paper: |theta'| <= 90 deg/s
  double half_axle_m = 0.2;                           // L
  Footprint footprint{0.25, 0.25, 0.2};               // 0.5 m x 0.4 m around the axle centre
  // The share of the planner's sampled controls that drive the faster wheel at its limit
  // (sample_control), in [0, 1].
  double top_speed_share = 0.8;

  Status validate() const;
  bool operator==(const DdVelocityParams&) const = default;
};

class DdVelocity {
 public:
  static constexpr VehicleKind kKind = VehicleKind::kDdVelocity;
  static constexpr int kStateDim = 3;
  using State = Eigen::Matrix<double, 3, 1>;
  using Control = Eigen::Matrix<double, 2, 1>;

  static Result<DdVelocity> create(const DdVelocityParams& params);

  State derivative(const State& q, const Control& u) const noexcept;
  State step(const State& q, const Control& u, double dt) const noexcept;
  Control sample_control(Random& rng) const noexcept;
  Control braking_control(const State&) const noexcept { return Control::Zero(); }
  State brake_step(const State& q, double) const noexcept { return q; }
  bool is_stopped(const State&) const noexcept { return true; }  // no velocity in the state
  double max_stopping_time_s() const noexcept { return 0.0; }
  double max_speed_m_s() const noexcept { return params_.max_wheel_speed_m_s; }
  double max_turn_rate_rad_s() const noexcept { return params_.max_turn_rate_rad_s; }
  double min_turning_radius_m() const noexcept { return 0.0; }
  const Footprint& footprint() const noexcept { return params_.footprint; }
  double speed_m_s(const State&) const noexcept { return 0.0; }  // speed lives in the control
  double speed_m_s(const State&, const Control& u) const noexcept;
  Status validate_state(const State& q) const;
  Status validate_control(const Control& u) const;
  State rest_state(double x, double y, double theta) const noexcept { return {x, y, theta}; }
  const DdVelocityParams& params() const noexcept { return params_; }

 private:
  explicit DdVelocity(const DdVelocityParams& params) : params_(params) {}
  DdVelocityParams params_;
};

}  // namespace grip
