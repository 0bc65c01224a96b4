#pragma once
// The braking contingency maneuver of the paper's Sec. III-C, checked against the known-free map.
// A state is unsafe iff its contingency collides (Eq. 4 with one braking maneuver per model).

#include <cmath>
#include <cstdint>

#include "grip/planner/step_margin.hpp"
#include "grip/vehicles/vehicle.hpp"
#include "grip/world/collision_checker.hpp"

namespace grip {

// Integrates the braking maneuver from q (assumed already checked) until the vehicle rests,
// checking the chassis at every step with the margin of each state (state_collision_margin_m;
// the checker's margin is the top speed's for dt); `checks` counts the collision checks made.
template <VehicleModel V>
bool contingency_is_collision_free(const V& vehicle, const CollisionChecker& checker,
                                   typename V::State q, double dt, std::uint64_t& checks) noexcept {
  // The maneuver is bounded by the model's stopping time; one extra step absorbs round-off.
  const auto max_steps =
      static_cast<std::uint32_t>(std::ceil(vehicle.max_stopping_time_s() / dt)) + 1U;
  for (std::uint32_t i = 0; i < max_steps && !vehicle.is_stopped(q); ++i) {
    q = vehicle.brake_step(q, dt);
    ++checks;
    if (!chassis_free_at(vehicle, checker, q, dt)) return false;
  }
  return vehicle.is_stopped(q);
}

// Where the braking maneuver leaves the vehicle `steps` integration steps after q (at rest it
// stays put).
template <VehicleModel V>
typename V::State braked_state(const V& vehicle, typename V::State q, std::uint64_t steps,
                               double dt) noexcept {
  for (std::uint64_t i = 0; i < steps && !vehicle.is_stopped(q); ++i) q = vehicle.brake_step(q, dt);
  return q;
}

}  // namespace grip
