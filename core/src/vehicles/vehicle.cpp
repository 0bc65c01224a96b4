#include "grip/vehicles/vehicle.hpp"

#include <array>
#include <string>

#include "grip/common/enum_names.hpp"
#include "grip/vehicles/vehicle_params.hpp"

namespace grip {

namespace {
constexpr std::array<NamedValue<VehicleKind>, 3> kVehicleNames{{
    {VehicleKind::kDdVelocity, "dd-vel"},
    {VehicleKind::kDdAcceleration, "dd-accel"},
    {VehicleKind::kCar, "car"},
}};
}  // namespace

std::string_view vehicle_name(VehicleKind kind) noexcept { return name_in(kVehicleNames, kind); }

Result<VehicleKind> vehicle_kind_from_name(std::string_view name) {
  return value_named(kVehicleNames, name, "robot");
}

Status validate_positive(std::string_view name, double value) {
  if (!std::isfinite(value) || value <= 0.0) {
    return invalid_argument(std::string(name) + " must be a finite number > 0 (got " +
                            std::to_string(value) + ")");
  }
  return Ok{};
}

Status validate_share(std::string_view name, double value) {
  if (!(value >= 0.0 && value <= 1.0)) {
    return invalid_argument(std::string(name) + " must be in [0, 1] (got " + std::to_string(value) +
                            ")");
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

VehicleKind vehicle_kind(const VehicleParams& params) noexcept {
  if (std::holds_alternative<DdVelocityParams>(params)) return VehicleKind::kDdVelocity;
  if (std::holds_alternative<DdAccelerationParams>(params)) return VehicleKind::kDdAcceleration;
  return VehicleKind::kCar;
}

VehicleParams default_vehicle_params(VehicleKind kind) noexcept {
  switch (kind) {
    case VehicleKind::kDdVelocity:
      return DdVelocityParams{};
    case VehicleKind::kDdAcceleration:
      return DdAccelerationParams{};
    case VehicleKind::kCar:
      break;
  }
  return CarParams{};
}

Status validate(const VehicleParams& params) {
  return std::visit([](const auto& p) { return p.validate(); }, params);
}

}  // namespace grip
