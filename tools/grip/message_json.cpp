#include "message_json.hpp"

#include <algorithm>
#include <cstring>
#include <string>

namespace grip::tools {

namespace {

const char* kind_name(grip_msg_VehicleKind kind) {
  switch (kind) {
    case grip_msg_DD_VELOCITY:
      return "DD_VELOCITY";
    case grip_msg_DD_ACCELERATION:
      return "DD_ACCELERATION";
    case grip_msg_CAR:
      return "CAR";
  }
  return "UNKNOWN";
}

const char* contingency_name(grip_msg_ContingencyKind kind) {
  switch (kind) {
    case grip_msg_STOP_IN_PLACE:
      return "STOP_IN_PLACE";
    case grip_msg_BRAKE_STRAIGHT:
      return "BRAKE_STRAIGHT";
    case grip_msg_BRAKE_ON_CURVE:
      return "BRAKE_ON_CURVE";
  }
  return "UNKNOWN";
}

// The state array as sent: all kMaxStateDim entries, state_dim says how many count.
nlohmann::json state_array(const double (&state)[grip_msg_kMaxStateDim]) {
  nlohmann::json out = nlohmann::json::array();
  for (double v : state) out.push_back(v);
  return out;
}

}  // namespace

nlohmann::json to_json(const grip_msg_VehicleState& m) {
  return {{"stamp_ns", m.stamp_ns},
          {"sequence_number", m.sequence_number},
          {"kind", kind_name(m.kind)},
          {"state", state_array(m.state)},
          {"state_dim", m.state_dim},
          {"time_scale", m.time_scale},
          {"lockstep", m.lockstep},
          {"plan_cycle", m.plan_cycle},
          {"map_sequence", m.map_sequence},
          {"incarnation", m.incarnation},
          {"plan_incarnation", m.plan_incarnation}};
}

nlohmann::json to_json(const grip_msg_Plan& m) {
  nlohmann::json steps = nlohmann::json::array();
  for (std::uint32_t i = 0; i < m.steps._length; ++i) {
    const grip_msg_PlanStep& s = m.steps._buffer[i];
    steps.push_back({{"control", {s.control[0], s.control[1]}}, {"duration_s", s.duration_s}});
  }
  return {{"cycle", m.cycle},
          {"start_time_ns", m.start_time_ns},
          {"start_state", state_array(m.start_state)},
          {"state_dim", m.state_dim},
          {"state_sequence", m.state_sequence},
          {"committed_monotonic_ns", m.committed_monotonic_ns},
          {"kind", kind_name(m.kind)},
          {"steps", steps},
          {"contingency", contingency_name(m.contingency)},
          {"incarnation", m.incarnation},
          {"vehicle_incarnation", m.vehicle_incarnation}};
}

nlohmann::json to_json(const grip_msg_MapUpdate& m) {
  std::string cells(m.cells._length, '?');
  for (std::uint32_t i = 0; i < m.cells._length; ++i) {
    const std::uint8_t c = m.cells._buffer[i];
    if (c <= 9) cells[i] = static_cast<char>('0' + c);  // out-of-contract values stay '?'
  }
  return {{"sequence_number", m.sequence_number}, {"stamp_ns", m.stamp_ns},
          {"map_width_cells", m.map_width_cells}, {"map_height_cells", m.map_height_cells},
          {"resolution_m", m.resolution_m},       {"map_origin_x_m", m.map_origin_x_m},
          {"map_origin_y_m", m.map_origin_y_m},   {"origin_x_cell", m.origin_x_cell},
          {"origin_y_cell", m.origin_y_cell},     {"width_cells", m.width_cells},
          {"height_cells", m.height_cells},       {"snapshot_id", m.snapshot_id},
          {"snapshot_part", m.snapshot_part},     {"snapshot_parts", m.snapshot_parts},
          {"incarnation", m.incarnation},         {"cells", cells}};
}

nlohmann::json to_json(const grip_msg_MapRequest& m) {
  return {{"from_sequence", m.from_sequence}, {"stamp_ns", m.stamp_ns}};
}

nlohmann::json to_json(const grip_msg_Goal& m) {
  return {{"sequence_number", m.sequence_number},
          {"stamp_ns", m.stamp_ns},
          {"x_m", m.x_m},
          {"y_m", m.y_m},
          {"radius_m", m.radius_m}};
}

nlohmann::json to_json(const grip_msg_PlannerStatus& m) {
  return {{"cycle", m.cycle},
          {"stamp_ns", m.stamp_ns},
          {"policy", std::string(m.policy, strnlen(m.policy, sizeof m.policy))},
          {"misses", m.misses},
          {"tree_edges", m.tree_edges},
          {"edges_added", m.edges_added},
          {"cycle_time_s", m.cycle_time_s},
          {"rejected_vehicle_state", m.rejected_vehicle_state},
          {"rejected_map_update", m.rejected_map_update},
          {"rejected_goal", m.rejected_goal},
          {"map_gaps", m.map_gaps},
          {"map_heals", m.map_heals},
          {"map_sequence", m.map_sequence},
          {"map_checksum", m.map_checksum},
          {"map_in_sync", m.map_in_sync},
          {"plans_published", m.plans_published},
          {"plans_dropped", m.plans_dropped},
          {"plan_subscribers", m.plan_subscribers},
          {"vehicle_alive", m.vehicle_alive},
          {"exploring", m.exploring},
          {"exploration_complete", m.exploration_complete},
          {"frontier_groups", m.frontier_groups},
          {"frontier_groups_given_up", m.frontier_groups_given_up},
          {"frontier_groups_unreachable", m.frontier_groups_unreachable},
          {"target_x_m", m.target_x_m},
          {"target_y_m", m.target_y_m},
          {"incarnation", m.incarnation},
          {"vehicle_incarnation", m.vehicle_incarnation},
          {"vehicle_restarts", m.vehicle_restarts}};
}

nlohmann::json to_json(const grip_msg_VehicleDescription& m) {
  nlohmann::json parameters = nlohmann::json::array();
  const std::uint32_t count =
      std::min<std::uint32_t>(m.parameter_count, grip_msg_kMaxVehicleParameters);
  for (std::uint32_t i = 0; i < count; ++i) {
    const grip_msg_VehicleParameter& p = m.parameters[i];
    parameters.push_back(
        {{"name", std::string(p.name, strnlen(p.name, sizeof p.name))}, {"value", p.value}});
  }
  return {{"model", kind_name(m.model)},
          {"parameter_count", m.parameter_count},
          {"parameters", parameters}};
}

}  // namespace grip::tools
