#pragma once
// The vehicle's description (idl/vehicle_description.idl): the vehicle side says what it is, the
// planner, which plans with its own parameters, refuses a vehicle that differs from them. A
// planner whose model has another wheelbase or a smaller footprint than the vehicle would plan
// paths the vehicle cannot follow or that its chassis does not fit through.

#include "grip/common/result.hpp"
#include "grip/link/topics.hpp"
#include "grip/platform/dds/participant.hpp"
#include "grip/platform/dds/writer.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "vehicle_description.h"

namespace grip::link {

// Values within this much agree: relative to the larger magnitude, with an absolute floor for
// values near zero. Parameter files are written by hand in decimal: only a real difference
// is refused.
inline constexpr double kDescriptionRelativeTolerance = 1e-3;
inline constexpr double kDescriptionAbsoluteTolerance = 1e-9;

// The description of a vehicle with `params`: its model and every parameter by its key
// (vehicle_param_fields.hpp).
grip_msg_VehicleDescription describe_vehicle(const VehicleParams& params) noexcept;

// Ok when `theirs` describes the vehicle `mine` says, else kInvalidArgument naming the first
// difference with both values, as the parameter file names it:
//   "the vehicle describes itself with vehicle.wheelbase_m 0.9, this planner's parameters say 0.5"
// Refused: another or an unknown model, a parameter count above kMaxVehicleParameters, a
// parameter `mine` does not have or named twice, one `mine` has and `theirs` lacks, and a value
// outside the tolerance (or not finite).
Status check_vehicle_description(const VehicleParams& mine,
                                 const grip_msg_VehicleDescription& theirs);

// The vehicle side's writer, the description written: keep it for as long as the vehicle
// lives, so that planners starting later get the description (TRANSIENT_LOCAL).
Result<platform::dds::Writer<grip_msg_VehicleDescription>> publish_vehicle_description(
    const platform::dds::Participant& participant, const TopicNames& topics,
    const LinkTiming& timing, const VehicleParams& params);

}  // namespace grip::link
