#pragma once
// What the planner needs from a vehicle model (the paper's Sec. V), as a C++20 concept.
//
// Every model integrates its dynamics with a fixed step: the bounded velocity components
// (wheel speeds, forward speed, steering angle) are linear in time and held at their limits
// the way a motor controller would hold them, so they are integrated exactly; the pose uses
// the midpoint rule on them. Each model provides its braking contingency (Sec. III-C).
// The planner and the simulator use the same model, never a second copy.

#include <cmath>
#include <concepts>
#include <numbers>
#include <string_view>

#include "grip/common/random.hpp"
#include "grip/common/result.hpp"
#include "grip/world/footprint.hpp"

namespace grip {

enum class VehicleKind { kDdVelocity, kDdAcceleration, kCar };

std::string_view vehicle_name(VehicleKind kind) noexcept;
Result<VehicleKind> vehicle_kind_from_name(std::string_view name);

template <typename V>
concept VehicleModel = requires(const V& v, const typename V::State& q,
                                const typename V::Control& u, double dt, Random& rng) {
  typename V::State;
  typename V::Control;
  { V::kKind } -> std::convertible_to<VehicleKind>;
  { V::kStateDim } -> std::convertible_to<int>;
  // One integration step of duration dt with control u held constant.
  { v.step(q, u, dt) } -> std::same_as<typename V::State>;
  // A control drawn uniformly within the limits (for GRIP's random plans; SteersToVelocityTarget
  // models mix in controls aimed at a velocity).
  { v.sample_control(rng) } -> std::same_as<typename V::Control>;
  // The braking contingency: the control to apply at q, and whether q is at rest.
  // brake_step integrates the maneuver for dt and lands exactly at rest when it stops within dt.
  { v.braking_control(q) } -> std::same_as<typename V::Control>;
  { v.brake_step(q, dt) } -> std::same_as<typename V::State>;
  { v.is_stopped(q) } -> std::same_as<bool>;
  // Upper bound on the time the braking maneuver takes from any admissible state [s].
  { v.max_stopping_time_s() } -> std::convertible_to<double>;
  // Bounds used to make collision checks between integration steps sound.
  { v.max_speed_m_s() } -> std::convertible_to<double>;
  { v.max_turn_rate_rad_s() } -> std::convertible_to<double>;
  { v.footprint() } -> std::convertible_to<Footprint>;
  // The tightest turn of the reference point [m]; 0 for a vehicle that turns in place. The
  // planner's rho respects it (planner/turning_rho.hpp).
  { v.min_turning_radius_m() } -> std::convertible_to<double>;
  // |velocity| of the reference point [m/s], for reports and the speed profile.
  { v.speed_m_s(q) } -> std::convertible_to<double>;
  // Whether q is finite and within the model's state limits.
  { v.validate_state(q) } -> std::same_as<Status>;
  // A state at rest at pose (x, y, theta).
  { v.rest_state(0.0, 0.0, 0.0) } -> std::same_as<typename V::State>;
};

// A model whose planner controls depend on the state and the time they are held for
// (sample_control(q, hold_s, rng)): acceleration-controlled vehicles aim them at a velocity.
template <typename V>
concept SteersToVelocityTarget = VehicleModel<V> &&
    requires(const V& v, const typename V::State& q, double hold_s, Random& rng) {
  { v.sample_control(q, hold_s, rng) } -> std::same_as<typename V::Control>;
};

// A model whose velocities change at a bounded rate (acceleration control), so that how fast
// it can move near a state follows from the state: within tau of q, before or after, its
// reference point moves no faster than speed_bound_m_s(q, tau) and it turns no faster than
// turn_rate_bound_rad_s(q, tau). Collision checks between integration steps then need only the
// margin of the state's own speed (planner/step_margin.hpp), not of the top speed.
template <typename V>
concept BoundsMotionNearState = VehicleModel<V> &&
    requires(const V& v, const typename V::State& q, double tau) {
  { v.speed_bound_m_s(q, tau) } -> std::convertible_to<double>;
  { v.turn_rate_bound_rad_s(q, tau) } -> std::convertible_to<double>;
};

// A model that speeds up and brakes at bounded rates: how fast it could drive toward space it
// has not sensed, and still stop inside what it has, follows from them (sim/braking_bound.hpp).
// The first two bound how fast the reference point's speed changes; plans may hold either.
template <typename V>
concept LimitsAcceleration = VehicleModel<V> && requires(const V& v) {
  { v.braking_decel_m_s2() } -> std::convertible_to<double>;     // the contingency's [m/s^2]
  { v.accel_bound_m_s2() } -> std::convertible_to<double>;       // the larger of the two [m/s^2]
  { v.max_reverse_speed_m_s() } -> std::convertible_to<double>;  // backing up [m/s], > 0
};

// The explicit midpoint method (second order) for a model exposing derivative(q, u). Chosen
// over RK4 for cost: the planner integrates millions of
// steps and the derivatives are dominated by sin/cos; at the default 0.05 s step the position
// error against the closed-form arcs is below a millimetre over several seconds, and the
// simulator integrates with this same routine, so plans execute as they were predicted.
template <typename V>
typename V::State midpoint_step(const V& model, const typename V::State& q,
                                const typename V::Control& u, double dt) noexcept {
  const typename V::State k1 = model.derivative(q, u);
  return q + dt * model.derivative(q + (0.5 * dt) * k1, u);
}

// Accessors shared by all models: every state starts with (x, y, theta).
template <typename State>
double state_x(const State& q) noexcept {
  return q[0];
}
template <typename State>
double state_y(const State& q) noexcept {
  return q[1];
}
template <typename State>
double state_theta(const State& q) noexcept {
  return q[2];
}

// Wraps an angle that moved by less than a turn from [-pi, pi] back into [-pi, pi].
inline double wrap_angle(double a) noexcept {
  constexpr double kTwoPi = 2.0 * std::numbers::pi;
  if (a > std::numbers::pi) return a - kTwoPi;
  if (a < -std::numbers::pi) return a + kTwoPi;
  return a;
}

// Two states of one model closer than this count as the same: the reference point within
// this distance [m], the heading (wrapped) and every other component within this much.
inline constexpr double kStateMatchTolerance = 1e-6;

// Whether a and b are the same state to within kStateMatchTolerance. A controller executes a
// plan only from the state the plan predicts (sim/plan_executor.hpp), and the planner replans
// when the vehicle will not be where its tree says: both sides decide it with this.
template <typename State>
bool states_match(const State& a, const State& b) noexcept {
  if (std::hypot(state_x(a) - state_x(b), state_y(a) - state_y(b)) > kStateMatchTolerance ||
      std::abs(wrap_angle(state_theta(a) - state_theta(b))) > kStateMatchTolerance) {
    return false;
  }
  for (int i = 3; i < static_cast<int>(a.size()); ++i) {
    if (std::abs(a[i] - b[i]) > kStateMatchTolerance) return false;
  }
  return true;
}

Status validate_positive(std::string_view name, double value);
// A fraction of the sampled controls: in [0, 1].
Status validate_share(std::string_view name, double value);
Status validate_finite_state(std::string_view vehicle, const double* values, int n);
Status validate_footprint(std::string_view vehicle, const Footprint& footprint);

}  // namespace grip
