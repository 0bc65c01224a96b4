#pragma once
// The message contract (idl/) on the receiving side: every sample is validated before anything
// uses it, and the verdict is a small value (a reason and the field it concerns), so that a
// flood of bad input costs no allocation. Rejections are counted per topic and logged at a rate
// limit by the caller. Conversions between messages and core types live here too, in one place.

#include <cstdint>
#include <string_view>

#include "goal.h"
#include "grip/planner/goal.hpp"
#include "grip/vehicles/vehicle.hpp"
#include "grip/world/occupancy_grid.hpp"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_state.h"

namespace grip::link {

enum class Rejection : std::uint8_t {
  kNone,
  kUnknownVehicleKind,  // not a value of the VehicleKind enum
  kWrongVehicleKind,    // a kind this planner or controller does not drive
  kWrongStateDim,
  kNotFinite,    // NaN or infinite number
  kOutOfLimits,  // outside the vehicle's state limits or the message's documented range
  kStampInFuture,
  kStampTooOld,
  kStampNotIncreasing,  // older than or equal to the last accepted sample
  kBadGeometry,         // map geometry not positive or not finite
  kGeometryMismatch,    // map geometry differs from the map being synchronised
  kMapTooLarge,         // a valid map with more cells than the receiver was sized for
  kPatchOutsideMap,
  kWrongLength,  // sequence length differs from what the other fields say
  kBadCellValue,
  kBadSnapshot,  // snapshot part numbering inconsistent
  kGoalOutsideMap,
  kNonPositiveDuration,
  // Incarnations (incarnation.hpp): a sender without one, or one the receiver does not follow.
  kNoIncarnation,
  kOtherIncarnation,
};
std::string_view rejection_name(Rejection r) noexcept;

struct Verdict {
  Rejection reason = Rejection::kNone;
  const char* field = "";  // the offending field, a string literal
  bool ok() const noexcept { return reason == Rejection::kNone; }
};

// Transport freshness: stamps compare DDS source timestamps with the reception time (both the
// DDS clock, which DDS itself assumes synchronised between hosts).
// Volatile topics only: a durable (TRANSIENT_LOCAL) sample is as old as its writer made it and
// still true, so durable() accepts any age (and keeps the bound on the future).
struct FreshnessLimits {
  std::int64_t max_future_ns = 1'000'000'000;  // clock skew tolerated
  std::int64_t max_age_ns = 5'000'000'000;     // older is stale, not news
  static constexpr FreshnessLimits durable() noexcept {
    return FreshnessLimits{1'000'000'000, INT64_MAX};
  }
};
Verdict check_freshness(std::int64_t source_ns, std::int64_t reception_ns,
                        const FreshnessLimits& limits) noexcept;

// Wire <-> core vehicle kinds; false for a value outside the enum.
bool from_wire(const grip_msg_VehicleKind& wire, VehicleKind& out) noexcept;
grip_msg_VehicleKind to_wire(VehicleKind kind) noexcept;

// A vehicle state for `vehicle`: kind and dimension match, numbers finite, time scale in
// (0, 1000], the state within the model's limits, and the stamp later than `last_stamp_ns`.
template <VehicleModel V>
Verdict check_vehicle_state(const grip_msg_VehicleState& msg, const V& vehicle,
                            std::uint64_t last_stamp_ns) noexcept;
template <VehicleModel V>
typename V::State state_from_wire(const grip_msg_VehicleState& msg) noexcept;
template <VehicleModel V>
void state_to_wire(const typename V::State& q, double* out, std::uint32_t& state_dim) noexcept;

// The map a synchronised subscriber holds: from the geometry fields of any update.
struct MapGeometry {
  std::uint32_t width_cells = 0;
  std::uint32_t height_cells = 0;
  double resolution_m = 0.0;
  double origin_x_m = 0.0;
  double origin_y_m = 0.0;
  bool operator==(const MapGeometry&) const = default;
};
MapGeometry geometry_of(const grip_msg_MapUpdate& msg) noexcept;
MapGeometry geometry_of(const OccupancyGrid& grid) noexcept;

// A map update: geometry valid (finite; resolution in [OccupancyGrid::kMinResolutionM,
// kMaxResolutionM], origin within kMaxOriginM, sizes within the grid's limits and
// max_map_cells: a map the planner's grids are not sized for is rejected here as kMapTooLarge,
// not at start-up), equal to `expected` when given, the patch inside the map,
// the cell sequence exactly width x height long with values 0..2, snapshot fields consistent.
Verdict check_map_update(const grip_msg_MapUpdate& msg, const MapGeometry* expected,
                         std::uint32_t max_map_cells) noexcept;

// A goal: finite, radius > 0, centre inside `grid`.
Verdict check_goal(const grip_msg_Goal& msg, const OccupancyGrid& grid) noexcept;
inline Goal goal_from_wire(const grip_msg_Goal& msg) noexcept {
  return Goal::disk(msg.x_m, msg.y_m, msg.radius_m);
}

// A plan, for the vehicle controller: the kind it drives, finite controls, durations > 0 and
// finite, a start state of the right dimension and finite. A plan without steps is valid: it
// says "nothing new from the start time" (idl/plan.idl).
Verdict check_plan(const grip_msg_Plan& msg, VehicleKind kind) noexcept;

// A planner status, for the vehicle side: the policy a terminated string, the cycle time finite
// and >= 0, the target finite.
Verdict check_planner_status(const grip_msg_PlannerStatus& msg) noexcept;

// The braking maneuver each vehicle's plans end in (its contingency, the paper's Sec. III-C).
grip_msg_ContingencyKind contingency_of(VehicleKind kind) noexcept;

}  // namespace grip::link
