#pragma once
// Calls f(vehicle) with the model of `kind` built from its default (the paper's) parameters:
// one place that turns a run-time vehicle kind into the compile-time model type.

#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip {

template <typename F>
decltype(auto) with_default_vehicle(VehicleKind kind, F&& f) {
  switch (kind) {
    case VehicleKind::kDdVelocity:
      return f(DdVelocity::create(DdVelocityParams{}).value());
    case VehicleKind::kDdAcceleration:
      return f(DdAcceleration::create(DdAccelerationParams{}).value());
    case VehicleKind::kCar:
      break;
  }
  return f(Car::create(CarParams{}).value());
}

}  // namespace grip
