#pragma once
// The collision margin that makes chassis checks at discrete integration steps cover the
// continuous motion between them (the planner's checker, and anything that must check states
// exactly as the planner does).

#include <algorithm>
#include <cmath>

#include "grip/vehicles/vehicle.hpp"

namespace grip {

// [s] The planner's integration step for a replanning cycle of cycle_s: a whole fraction of
// the cycle (plans are chained at cycle boundaries), at most 50 ms.
inline double integration_step_for_cycle(double cycle_s) noexcept {
  return cycle_s / std::ceil(cycle_s / 0.05 - 1e-9);
}

// [m] Half the largest motion of any chassis point during one step of dt_s: the reference
// point moves at most max_speed * dt, a chassis point at distance `reach` from it at most
// reach * max_turn_rate * dt more. Growing the chassis by this margin on every side, a check
// every dt covers the whole trajectory (each point of it is within half a step of a check).
template <VehicleModel V>
double step_collision_margin_m(const V& vehicle, double dt_s) noexcept {
  const Footprint& f = vehicle.footprint();
  const double reach = std::hypot(std::max(f.front_m, f.rear_m), f.half_width_m);
  return 0.5 * (vehicle.max_speed_m_s() * dt_s + reach * vehicle.max_turn_rate_rad_s() * dt_s);
}

}  // namespace grip
