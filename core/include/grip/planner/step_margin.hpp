#pragma once
// The collision margin that makes chassis checks at discrete integration steps cover the
// continuous motion between them (the planner's checker, and anything that must check states
// exactly as the planner does).

#include <algorithm>
#include <cmath>

#include "grip/vehicles/vehicle.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip {

// [s] The planner's integration step for a replanning cycle of cycle_s: a whole fraction of
// the cycle (plans are chained at cycle boundaries), at most 50 ms.
inline double integration_step_for_cycle(double cycle_s) noexcept {
  return cycle_s / std::ceil(cycle_s / 0.05 - 1e-9);
}

// [m] The farthest chassis point from the reference point.
template <VehicleModel V>
double chassis_reach_m(const V& vehicle) noexcept {
  const Footprint& f = vehicle.footprint();
  return std::hypot(std::max(f.front_m, f.rear_m), f.half_width_m);
}

// [m] Half the largest motion of any chassis point during one step of dt_s: the reference
// point moves at most max_speed * dt, a chassis point at distance `reach` from it at most
// reach * max_turn_rate * dt more. Growing the chassis by this margin on every side, a check
// every dt covers the whole trajectory (each point of it is within half a step of a check).
template <VehicleModel V>
double step_collision_margin_m(const V& vehicle, double dt_s) noexcept {
  return 0.5 * dt_s *
         (vehicle.max_speed_m_s() + chassis_reach_m(vehicle) * vehicle.max_turn_rate_rad_s());
}

// [m] The margin a check at state q needs: a check covers the motion within half a step before
// and after it, and a vehicle whose velocities change at a bounded rate (BoundsMotionNearState)
// moves then no faster than its bounds near q allow. At rest that is a small fraction of the
// top speed's margin, so a slow vehicle fits where a fast one may not, as it does in reality.
// Other models: step_collision_margin_m. Never more than it.
template <VehicleModel V>
double state_collision_margin_m(const V& vehicle, const typename V::State& q,
                                double dt_s) noexcept {
  if constexpr (BoundsMotionNearState<V>) {
    const double tau = 0.5 * dt_s;
    const double margin = tau * (vehicle.speed_bound_m_s(q, tau) +
                                 chassis_reach_m(vehicle) * vehicle.turn_rate_bound_rad_s(q, tau));
    const double full = step_collision_margin_m(vehicle, dt_s);
    return margin < full ? margin : full;  // and full for a state that is not finite
  } else {
    return step_collision_margin_m(vehicle, dt_s);
  }
}

// Whether the chassis at q is free grown by q's own margin (state_collision_margin_m for a step
// of dt_s, at most the checker's margin): the planner's test of every state it keeps.
template <VehicleModel V>
bool chassis_free_at(const V& vehicle, const CollisionChecker& checker, const typename V::State& q,
                     double dt_s) noexcept {
  return checker.is_free_with(state_x(q), state_y(q), state_theta(q),
                              [&] { return state_collision_margin_m(vehicle, q, dt_s); });
}

}  // namespace grip
