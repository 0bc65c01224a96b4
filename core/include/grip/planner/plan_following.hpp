#pragma once
// How a vehicle's controller moves the vehicle between plan events (idl/plan.idl): along the
// piece of the plan it executes, braking on the contingency once a plan ends until it rests, or
// at rest. One routine for the simulated controller (sim::PlanExecutor) and the planner's
// forecast of it (rt::PlanLedger): the forecast is only worth anything if the two integrate
// alike to the bit.

#include <cstdint>

#include "grip/vehicles/vehicle.hpp"

namespace grip {

enum class ControllerMode : std::uint8_t {
  kAtRest,     // no plan: stopped
  kExecuting,  // following a plan's piece
  kBraking,    // performing the braking contingency
};

// The mode a plan's end leaves the vehicle in (it ran out, or the planner was lost).
template <VehicleModel V>
ControllerMode contingency_mode(const V& vehicle, const typename V::State& q) noexcept {
  return vehicle.is_stopped(q) ? ControllerMode::kAtRest : ControllerMode::kBraking;
}

// q after h seconds in `mode` (holding `control` when executing: the piece's); braking to a stop
// ends at rest.
template <VehicleModel V>
typename V::State follow(const V& vehicle, const typename V::State& q, ControllerMode& mode,
                         const typename V::Control& control, double h) noexcept {
  switch (mode) {
    case ControllerMode::kExecuting:
      return vehicle.step(q, control, h);
    case ControllerMode::kBraking: {
      const typename V::State next = vehicle.brake_step(q, h);
      if (vehicle.is_stopped(next)) mode = ControllerMode::kAtRest;
      return next;
    }
    case ControllerMode::kAtRest:
      break;
  }
  return q;
}

}  // namespace grip
