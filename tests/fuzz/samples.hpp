#pragma once
// Samples of each received message built from the fuzzer's bytes, as the DDS deserializer could
// deliver them: every number any value, enums any 32-bit value, sequences as long as the bytes
// allow (up to the contract's bound plus a little, so that over-long sequences are tried too).

#include <cstdint>
#include <vector>

#include "fuzz_bytes.hpp"
#include "goal.h"
#include "map_update.h"
#include "plan.h"
#include "planner_status.h"
#include "vehicle_description.h"
#include "vehicle_state.h"

namespace grip::fuzz {

// An enum field loaded from any 32-bit value (the contract's code reads enums as integers).
template <typename E>
void take_enum(FuzzBytes& in, E& out) {
  static_assert(sizeof(E) == sizeof(std::uint32_t));
  in.copy(&out, sizeof out);
}

inline grip_msg_VehicleState vehicle_state_from(FuzzBytes& in) {
  grip_msg_VehicleState m{};
  m.stamp_ns = in.take<std::uint64_t>();
  m.sequence_number = in.take<std::uint64_t>();
  take_enum(in, m.kind);
  for (double& v : m.state) v = in.take<double>();
  m.state_dim = in.take<std::uint8_t>();  // small values: the valid ones are 3 and 5
  m.time_scale = in.take<double>();
  m.lockstep = in.take_bool();
  m.plan_cycle = in.take<std::uint64_t>();
  m.map_sequence = in.take<std::uint64_t>();
  m.incarnation = in.take<std::uint64_t>();
  m.plan_incarnation = in.take<std::uint64_t>();
  return m;
}

inline grip_msg_Goal goal_from(FuzzBytes& in) {
  grip_msg_Goal m{};
  m.sequence_number = in.take<std::uint64_t>();
  m.stamp_ns = in.take<std::uint64_t>();
  m.x_m = in.take<double>();
  m.y_m = in.take<double>();
  m.radius_m = in.take<double>();
  return m;
}

// A map update whose cells live in `cells` (which must outlive the sample).
inline grip_msg_MapUpdate map_update_from(FuzzBytes& in, std::vector<std::uint8_t>& cells) {
  grip_msg_MapUpdate m{};
  m.sequence_number = in.take<std::uint8_t>();  // small: sequences and gaps both happen
  m.stamp_ns = in.take<std::uint64_t>();
  // Sizes from two bytes each, scaled: small maps mostly, the largest ones sometimes.
  const auto side = [&] {
    const auto raw = in.take<std::uint16_t>();
    return (raw & 0x8000U) != 0 ? static_cast<std::uint32_t>(raw) << 4 : (raw & 0xffU);
  };
  m.map_width_cells = side();
  m.map_height_cells = side();
  m.resolution_m = in.take<double>();
  m.map_origin_x_m = in.take<double>();
  m.map_origin_y_m = in.take<double>();
  m.origin_x_cell = in.take<std::uint8_t>();
  m.origin_y_cell = in.take<std::uint8_t>();
  m.width_cells = in.take<std::uint8_t>();
  m.height_cells = in.take<std::uint8_t>();
  m.snapshot_id = in.take<std::uint8_t>();
  m.snapshot_part = in.take<std::uint8_t>();
  m.snapshot_parts = in.take<std::uint8_t>();
  const std::size_t wanted = in.take<std::uint16_t>();
  cells.resize(wanted);
  in.copy(cells.data(), wanted);
  m.cells._length = static_cast<std::uint32_t>(wanted);
  m.cells._maximum = m.cells._length;
  m.cells._buffer = cells.empty() ? nullptr : cells.data();
  m.incarnation = in.take<std::uint64_t>();
  return m;
}

// A plan whose steps live in `steps`.
inline grip_msg_Plan plan_from(FuzzBytes& in, std::vector<grip_msg_PlanStep>& steps) {
  grip_msg_Plan m{};
  m.cycle = in.take<std::uint64_t>();
  m.start_time_ns = in.take<std::uint64_t>();
  for (double& v : m.start_state) v = in.take<double>();
  m.state_dim = in.take<std::uint8_t>();
  m.state_sequence = in.take<std::uint64_t>();
  m.committed_monotonic_ns = in.take<std::uint64_t>();
  take_enum(in, m.kind);
  take_enum(in, m.contingency);
  const std::size_t count = in.take<std::uint16_t>() % (grip_msg_kMaxPlanSteps + 8);
  steps.resize(count);
  for (grip_msg_PlanStep& s : steps) {
    s.control[0] = in.take<double>();
    s.control[1] = in.take<double>();
    s.duration_s = in.take<double>();
  }
  m.steps._length = static_cast<std::uint32_t>(count);
  m.steps._maximum = m.steps._length;
  m.steps._buffer = steps.empty() ? nullptr : steps.data();
  m.incarnation = in.take<std::uint64_t>();
  m.vehicle_incarnation = in.take<std::uint64_t>();
  return m;
}

inline grip_msg_PlannerStatus planner_status_from(FuzzBytes& in) {
  grip_msg_PlannerStatus m{};
  m.cycle = in.take<std::uint64_t>();
  m.stamp_ns = in.take<std::uint64_t>();
  in.take_string(m.policy);
  m.misses = in.take<std::uint64_t>();
  m.tree_edges = in.take<std::uint64_t>();
  m.edges_added = in.take<std::uint64_t>();
  m.cycle_time_s = in.take<double>();
  m.rejected_vehicle_state = in.take<std::uint64_t>();
  m.rejected_map_update = in.take<std::uint64_t>();
  m.rejected_goal = in.take<std::uint64_t>();
  m.map_gaps = in.take<std::uint64_t>();
  m.map_heals = in.take<std::uint64_t>();
  m.map_sequence = in.take<std::uint64_t>();
  m.map_checksum = in.take<std::uint64_t>();
  m.map_in_sync = in.take_bool();
  m.plans_published = in.take<std::uint64_t>();
  m.plans_dropped = in.take<std::uint64_t>();
  m.plan_subscribers = in.take<std::uint32_t>();
  m.vehicle_alive = in.take_bool();
  m.exploring = in.take_bool();
  m.exploration_complete = in.take_bool();
  m.frontier_groups = in.take<std::uint32_t>();
  m.frontier_groups_given_up = in.take<std::uint32_t>();
  m.frontier_groups_unreachable = in.take<std::uint32_t>();
  m.target_x_m = in.take<double>();
  m.target_y_m = in.take<double>();
  m.incarnation = in.take<std::uint64_t>();
  m.vehicle_incarnation = in.take<std::uint64_t>();
  m.vehicle_restarts = in.take<std::uint32_t>();
  return m;
}

inline grip_msg_VehicleDescription vehicle_description_from(FuzzBytes& in) {
  grip_msg_VehicleDescription m{};
  take_enum(in, m.model);
  m.parameter_count = in.take<std::uint8_t>();  // any count, the bound (32) exceeded too
  for (grip_msg_VehicleParameter& p : m.parameters) {
    in.take_string(p.name);
    p.value = in.take<double>();
  }
  return m;
}

}  // namespace grip::fuzz
