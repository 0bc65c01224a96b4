#pragma once
// A vehicle as the run-time picks it: one model's parameters (a parameter file, or the paper's
// defaults), and the one place that turns them into the compile-time model type.

#include <utility>
#include <variant>

#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip {

using VehicleParams = std::variant<DdVelocityParams, DdAccelerationParams, CarParams>;

VehicleKind vehicle_kind(const VehicleParams& params) noexcept;
// The paper's vehicle of this kind (its Sec. V).
VehicleParams default_vehicle_params(VehicleKind kind) noexcept;
// The model's own check (ranges, footprint), naming the field.
Status validate(const VehicleParams& params);

// Calls f(vehicle) with the model built from `params`, which validate() accepted: callers check
// at start-up, where a bad parameter is the user's error and not a fault.
template <typename F>
decltype(auto) with_vehicle(const VehicleParams& params, F&& f) {
  return std::visit(
      [&f](const auto& p) -> decltype(auto) {
        using P = std::remove_cvref_t<decltype(p)>;
        if constexpr (std::is_same_v<P, DdVelocityParams>) {
          return std::forward<F>(f)(DdVelocity::create(p).value());
        } else if constexpr (std::is_same_v<P, DdAccelerationParams>) {
          return std::forward<F>(f)(DdAcceleration::create(p).value());
        } else {
          return std::forward<F>(f)(Car::create(p).value());
        }
      },
      params);
}

// f(vehicle) with the paper's vehicle of `kind`.
template <typename F>
decltype(auto) with_default_vehicle(VehicleKind kind, F&& f) {
  return with_vehicle(default_vehicle_params(kind), std::forward<F>(f));
}

}  // namespace grip
