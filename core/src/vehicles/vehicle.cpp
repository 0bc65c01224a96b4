#include "grip/vehicles/vehicle.hpp"

#include <string>

namespace grip {

std::string_view vehicle_name(VehicleKind kind) noexcept {
  switch (kind) {
    case VehicleKind::kDdVelocity:
      return "dd-vel";
    case VehicleKind::kDdAcceleration:
      return "dd-accel";
    case VehicleKind::kCar:
      return "car";
  }
  return "unknown";
}

Result<VehicleKind> vehicle_kind_from_name(std::string_view name) {
  for (VehicleKind kind :
       {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration, VehicleKind::kCar}) {
    if (vehicle_name(kind) == name) return kind;
  }
  return invalid_argument("unknown robot '" + std::string(name) +
                          "' (expected one of: dd-vel, dd-accel, car)");
}

Status validate_positive(std::string_view name, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    return invalid_argument(std::string(name) + " must be a finite number > 0 (got " +
                            std::to_string(value) + ")");
  }
  return Ok{};
}

Status validate_finite_state(std::string_view vehicle, const double* values, int n) {
  for (int i = 0; i < n; ++i) {
    if (!std::isfinite(values[i])) {
      return invalid_argument(std::string(vehicle) + " state component " + std::to_string(i) +
                              " is not finite (got " + std::to_string(values[i]) + ")");
    }
  }
  return Ok{};
}

Status validate_footprint(std::string_view vehicle, const Footprint& f) {
  const std::string prefix = std::string(vehicle) + ".footprint.";
  if (auto s = validate_positive(prefix + "half_width_m", f.half_width_m); !s) return s;
  if (!std::isfinite(f.front_m) || !std::isfinite(f.rear_m) || f.front_m + f.rear_m <= 0.0) {
    return invalid_argument(prefix + "front_m + rear_m must be finite and > 0 (got " +
                            std::to_string(f.front_m) + " + " + std::to_string(f.rear_m) + ")");
  }
  return Ok{};
}

}  // namespace grip
