#pragma once
// The contract's messages (idl/) as JSON, field for field with the IDL's names, for
// `grip echo`. Sequences are printed whole; map cells as a string of digits 0 (free),
// 1 (obstacle), 2 (unknown), row by row from the patch origin.

#include <nlohmann/json.hpp>

#include "goal.h"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_description.h"
#include "vehicle_state.h"

namespace grip::tools {

nlohmann::json to_json(const grip_msg_VehicleState& m);
nlohmann::json to_json(const grip_msg_Plan& m);
nlohmann::json to_json(const grip_msg_MapUpdate& m);
nlohmann::json to_json(const grip_msg_MapRequest& m);
nlohmann::json to_json(const grip_msg_Goal& m);
nlohmann::json to_json(const grip_msg_PlannerStatus& m);
// The parameters counted by parameter_count, as an array of {name, value}.
nlohmann::json to_json(const grip_msg_VehicleDescription& m);

}  // namespace grip::tools
