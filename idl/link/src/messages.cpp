#include "grip/link/messages.hpp"

#include <array>
#include <cmath>
#include <cstring>

#include "grip/common/enum_names.hpp"
#include "grip/vehicles/car.hpp"
#include "grip/vehicles/dd_acceleration.hpp"
#include "grip/vehicles/dd_velocity.hpp"

namespace grip::link {

namespace {

constexpr std::array<NamedValue<Rejection>, 20> kRejectionNames{{
    {Rejection::kNone, "none"},
    {Rejection::kUnknownVehicleKind, "unknown vehicle kind"},
    {Rejection::kWrongVehicleKind, "wrong vehicle kind"},
    {Rejection::kWrongStateDim, "wrong state dimension"},
    {Rejection::kNotFinite, "not finite"},
    {Rejection::kOutOfLimits, "out of limits"},
    {Rejection::kStampInFuture, "timestamp in the future"},
    {Rejection::kStampTooOld, "timestamp too old"},
    {Rejection::kStampNotIncreasing, "timestamp not increasing"},
    {Rejection::kBadGeometry, "bad map geometry"},
    {Rejection::kGeometryMismatch, "map geometry mismatch"},
    {Rejection::kMapTooLarge, "map larger than this receiver is sized for"},
    {Rejection::kPatchOutsideMap, "patch outside the map"},
    {Rejection::kWrongLength, "wrong length"},
    {Rejection::kBadCellValue, "bad cell value"},
    {Rejection::kBadSnapshot, "bad snapshot numbering"},
    {Rejection::kGoalOutsideMap, "goal outside the map"},
    {Rejection::kNonPositiveDuration, "duration not positive"},
    {Rejection::kNoIncarnation, "no incarnation"},
    {Rejection::kOtherIncarnation, "another incarnation"},
}};

constexpr Verdict reject(Rejection reason, const char* field) noexcept { return {reason, field}; }

bool all_finite(const double* values, std::uint32_t n) noexcept {
  for (std::uint32_t i = 0; i < n; ++i) {
    if (!std::isfinite(values[i])) return false;
  }
  return true;
}

}  // namespace

std::string_view rejection_name(Rejection r) noexcept { return name_in(kRejectionNames, r); }

Verdict check_freshness(std::int64_t source_ns, std::int64_t reception_ns,
                        const FreshnessLimits& limits) noexcept {
  if (source_ns - reception_ns > limits.max_future_ns) {
    return reject(Rejection::kStampInFuture, "source_timestamp");
  }
  if (reception_ns - source_ns > limits.max_age_ns) {
    return reject(Rejection::kStampTooOld, "source_timestamp");
  }
  return {};
}

bool from_wire(const grip_msg_VehicleKind& wire, VehicleKind& out) noexcept {
  // Read as the integer on the wire: a value outside the enum must not be loaded as the enum.
  std::int32_t raw = 0;
  static_assert(sizeof raw == sizeof wire);
  std::memcpy(&raw, &wire, sizeof raw);
  switch (raw) {
    case grip_msg_DD_VELOCITY:
      out = VehicleKind::kDdVelocity;
      return true;
    case grip_msg_DD_ACCELERATION:
      out = VehicleKind::kDdAcceleration;
      return true;
    case grip_msg_CAR:
      out = VehicleKind::kCar;
      return true;
    default:
      return false;
  }
}

grip_msg_VehicleKind to_wire(VehicleKind kind) noexcept {
  switch (kind) {
    case VehicleKind::kDdVelocity:
      return grip_msg_DD_VELOCITY;
    case VehicleKind::kDdAcceleration:
      return grip_msg_DD_ACCELERATION;
    case VehicleKind::kCar:
      break;
  }
  return grip_msg_CAR;
}

template <VehicleModel V>
Verdict check_vehicle_state(const grip_msg_VehicleState& msg, const V& vehicle,
                            std::uint64_t last_stamp_ns) noexcept {
  VehicleKind kind{};
  if (!from_wire(msg.kind, kind)) return reject(Rejection::kUnknownVehicleKind, "kind");
  if (kind != V::kKind) return reject(Rejection::kWrongVehicleKind, "kind");
  if (msg.state_dim != static_cast<std::uint32_t>(V::kStateDim)) {
    return reject(Rejection::kWrongStateDim, "state_dim");
  }
  if (!all_finite(msg.state, msg.state_dim)) return reject(Rejection::kNotFinite, "state");
  if (!std::isfinite(msg.time_scale)) return reject(Rejection::kNotFinite, "time_scale");
  if (!(msg.time_scale > 0.0 && msg.time_scale <= 1000.0)) {
    return reject(Rejection::kOutOfLimits, "time_scale");
  }
  if (msg.stamp_ns <= last_stamp_ns) return reject(Rejection::kStampNotIncreasing, "stamp_ns");
  // validate_state builds a message when it fails; the verdict keeps only that it did.
  if (!vehicle.validate_state(state_from_wire<V>(msg)).ok()) {
    return reject(Rejection::kOutOfLimits, "state");
  }
  return {};
}

template <VehicleModel V>
typename V::State state_from_wire(const grip_msg_VehicleState& msg) noexcept {
  typename V::State q;
  for (int i = 0; i < V::kStateDim; ++i) q[i] = msg.state[i];
  return q;
}

template <VehicleModel V>
void state_to_wire(const typename V::State& q, double* out, std::uint32_t& state_dim) noexcept {
  for (int i = 0; i < grip_msg_kMaxStateDim; ++i) out[i] = i < V::kStateDim ? q[i] : 0.0;
  state_dim = static_cast<std::uint32_t>(V::kStateDim);
}

MapGeometry geometry_of(const grip_msg_MapUpdate& msg) noexcept {
  return MapGeometry{msg.map_width_cells, msg.map_height_cells, msg.resolution_m,
                     msg.map_origin_x_m, msg.map_origin_y_m};
}

MapGeometry geometry_of(const OccupancyGrid& grid) noexcept {
  return MapGeometry{static_cast<std::uint32_t>(grid.width()),
                     static_cast<std::uint32_t>(grid.height()), grid.resolution(), grid.origin_x(),
                     grid.origin_y()};
}

Verdict check_map_update(const grip_msg_MapUpdate& msg, const MapGeometry* expected,
                         std::uint32_t max_map_cells) noexcept {
  if (!std::isfinite(msg.resolution_m)) return reject(Rejection::kNotFinite, "resolution_m");
  if (!std::isfinite(msg.map_origin_x_m) || !std::isfinite(msg.map_origin_y_m)) {
    return reject(Rejection::kNotFinite, "map_origin");
  }
  if (!(msg.resolution_m >= OccupancyGrid::kMinResolutionM &&
        msg.resolution_m <= OccupancyGrid::kMaxResolutionM)) {
    return reject(Rejection::kBadGeometry, "resolution_m");
  }
  if (std::abs(msg.map_origin_x_m) > OccupancyGrid::kMaxOriginM ||
      std::abs(msg.map_origin_y_m) > OccupancyGrid::kMaxOriginM) {
    return reject(Rejection::kBadGeometry, "map_origin");
  }
  if (msg.map_width_cells == 0 || msg.map_height_cells == 0 ||
      msg.map_width_cells > static_cast<std::uint32_t>(OccupancyGrid::kMaxSideCells) ||
      msg.map_height_cells > static_cast<std::uint32_t>(OccupancyGrid::kMaxSideCells) ||
      static_cast<std::uint64_t>(msg.map_width_cells) * msg.map_height_cells >
          OccupancyGrid::kMaxCells) {
    return reject(Rejection::kBadGeometry, "map_width_cells x map_height_cells");
  }
  if (static_cast<std::uint64_t>(msg.map_width_cells) * msg.map_height_cells > max_map_cells) {
    return reject(Rejection::kMapTooLarge, "map_width_cells x map_height_cells");
  }
  if (expected != nullptr && !(geometry_of(msg) == *expected)) {
    return reject(Rejection::kGeometryMismatch, "map geometry");
  }
  const std::uint64_t patch_cells = static_cast<std::uint64_t>(msg.width_cells) * msg.height_cells;
  if (msg.width_cells == 0 || msg.height_cells == 0 || patch_cells > grip_msg_kMaxPatchCells ||
      static_cast<std::uint64_t>(msg.origin_x_cell) + msg.width_cells > msg.map_width_cells ||
      static_cast<std::uint64_t>(msg.origin_y_cell) + msg.height_cells > msg.map_height_cells) {
    return reject(Rejection::kPatchOutsideMap, "patch rectangle");
  }
  if (msg.cells._length != patch_cells || (patch_cells > 0 && msg.cells._buffer == nullptr)) {
    return reject(Rejection::kWrongLength, "cells");
  }
  for (std::uint32_t i = 0; i < msg.cells._length; ++i) {
    if (msg.cells._buffer[i] > grip_msg_kCellUnknown) {
      return reject(Rejection::kBadCellValue, "cells");
    }
  }
  if (msg.snapshot_id == 0 ? (msg.snapshot_part != 0 || msg.snapshot_parts != 0)
                           : (msg.snapshot_parts == 0 || msg.snapshot_part >= msg.snapshot_parts)) {
    return reject(Rejection::kBadSnapshot, "snapshot_part / snapshot_parts");
  }
  return {};
}

Verdict check_goal(const grip_msg_Goal& msg, const OccupancyGrid& grid) noexcept {
  if (!std::isfinite(msg.x_m) || !std::isfinite(msg.y_m) || !std::isfinite(msg.radius_m)) {
    return reject(Rejection::kNotFinite, "x_m / y_m / radius_m");
  }
  if (!(msg.radius_m > 0.0) || msg.radius_m > grid.width_m() + grid.height_m()) {
    return reject(Rejection::kOutOfLimits, "radius_m");
  }
  int cx = 0;
  int cy = 0;
  if (!grid.to_cell(msg.x_m, msg.y_m, cx, cy))
    return reject(Rejection::kGoalOutsideMap, "x_m, y_m");
  return {};
}

Verdict check_plan(const grip_msg_Plan& msg, VehicleKind kind) noexcept {
  VehicleKind plan_kind{};
  if (!from_wire(msg.kind, plan_kind)) return reject(Rejection::kUnknownVehicleKind, "kind");
  if (plan_kind != kind) return reject(Rejection::kWrongVehicleKind, "kind");
  const std::uint32_t dim = kind == VehicleKind::kDdVelocity ? 3U : 5U;
  if (msg.state_dim != dim) return reject(Rejection::kWrongStateDim, "state_dim");
  if (!all_finite(msg.start_state, msg.state_dim))
    return reject(Rejection::kNotFinite, "start_state");
  if (msg.steps._length > grip_msg_kMaxPlanSteps ||
      (msg.steps._length > 0 && msg.steps._buffer == nullptr)) {
    return reject(Rejection::kWrongLength, "steps");
  }
  // Read as the integer on the wire, as the kind is.
  std::int32_t contingency = 0;
  static_assert(sizeof contingency == sizeof msg.contingency);
  std::memcpy(&contingency, &msg.contingency, sizeof contingency);
  if (contingency != static_cast<std::int32_t>(contingency_of(kind))) {
    return reject(Rejection::kOutOfLimits, "contingency");
  }
  for (std::uint32_t i = 0; i < msg.steps._length; ++i) {
    const grip_msg_PlanStep& step = msg.steps._buffer[i];
    if (!all_finite(step.control, 2)) return reject(Rejection::kNotFinite, "steps.control");
    if (!std::isfinite(step.duration_s)) return reject(Rejection::kNotFinite, "steps.duration_s");
    if (!(step.duration_s > 0.0))
      return reject(Rejection::kNonPositiveDuration, "steps.duration_s");
  }
  return {};
}

Verdict check_planner_status(const grip_msg_PlannerStatus& msg) noexcept {
  if (std::memchr(msg.policy, '\0', sizeof msg.policy) == nullptr) {
    return reject(Rejection::kWrongLength, "policy");
  }
  if (!std::isfinite(msg.cycle_time_s)) return reject(Rejection::kNotFinite, "cycle_time_s");
  if (!(msg.cycle_time_s >= 0.0)) return reject(Rejection::kOutOfLimits, "cycle_time_s");
  if (!std::isfinite(msg.target_x_m) || !std::isfinite(msg.target_y_m)) {
    return reject(Rejection::kNotFinite, "target_x_m / target_y_m");
  }
  return {};
}

grip_msg_ContingencyKind contingency_of(VehicleKind kind) noexcept {
  // The differential drives brake both wheels to a stop on the spot's curve; the car brakes
  // holding its steering angle (it cannot change it faster than its steering rate).
  return kind == VehicleKind::kCar ? grip_msg_BRAKE_ON_CURVE : grip_msg_STOP_IN_PLACE;
}

#define GRIP_INSTANTIATE_MESSAGES(V)                                              \
  template Verdict check_vehicle_state<V>(const grip_msg_VehicleState&, const V&, \
                                          std::uint64_t) noexcept;                \
  template V::State state_from_wire<V>(const grip_msg_VehicleState&) noexcept;    \
  template void state_to_wire<V>(const V::State&, double*, std::uint32_t&) noexcept;
GRIP_INSTANTIATE_MESSAGES(DdVelocity)
GRIP_INSTANTIATE_MESSAGES(DdAcceleration)
GRIP_INSTANTIATE_MESSAGES(Car)
#undef GRIP_INSTANTIATE_MESSAGES

}  // namespace grip::link
