#pragma once
// The topics of the contract and their QoS, in one place for every participant (the planner,
// the simulator, tests and tools), so that both ends of a link always match.
//
// Chosen for a control link (documented in README "DDS contract"):
//   vehicle state: RELIABLE, KEEP_LAST 1. Only the newest state matters, and a reliable
//     keep-last writer never blocks on a slow reader (the newest sample replaces the one not
//     yet acknowledged), yet nothing is lost on a healthy link, which lockstep simulation
//     relies on. DEADLINE: writers offer 2 T / time scale, readers request 2 T.
//   plan: the same with KEEP_LAST 4 (kPlanHistoryDepth). Plans are a chain: each starts where
//     the one before puts the vehicle at its start time, and governs only until the next one
//     starts. A controller that reads two plans at once (it was descheduled for a cycle) must
//     execute both, or the second starts from a state the vehicle never reaches.
//   map update: RELIABLE, KEEP_LAST 64: depth for bursts (a snapshot of a 1000 x 1000 map is 16
//     parts); anything lost anyway is a gap in the sequence numbers, healed by a snapshot.
//   map request: RELIABLE, KEEP_LAST 4.
//   goal: RELIABLE, KEEP_LAST 1, TRANSIENT_LOCAL: a planner that starts late still gets the goal.
//   vehicle description: RELIABLE, KEEP_LAST 1, TRANSIENT_LOCAL: written once when the vehicle
//     side starts, read by a planner that starts at any time after (and by one that starts
//     before: durable readers get it either way).
//   planner status: RELIABLE, KEEP_LAST 1.
//   All: AUTOMATIC liveliness with the given lease, so that each side notices the other's loss
//   within about one lease; max_blocking_time 10 ms (only keep-last-64 map updates can block).
//
// Names: every topic can carry a prefix, "<prefix>_grip_plan" etc., so that two vehicles (each
// with its planner) can share a DDS domain; empty by default, which leaves the names as below.
// TopicNames is the one place that builds them: every reader and writer of a grip topic takes
// its name from there.

#include <chrono>
#include <cstddef>
#include <cstdint>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

#include "grip/platform/dds/qos.hpp"

namespace grip::link {

inline constexpr const char* kVehicleStateTopic = "grip_vehicle_state";
inline constexpr const char* kPlanTopic = "grip_plan";
// Plans a reader holds: a controller may fall this many cycles behind and still run each one.
inline constexpr std::int32_t kPlanHistoryDepth = 4;
inline constexpr const char* kMapUpdateTopic = "grip_map_update";
inline constexpr const char* kMapRequestTopic = "grip_map_request";
inline constexpr const char* kGoalTopic = "grip_goal";
inline constexpr const char* kPlannerStatusTopic = "grip_planner_status";
inline constexpr const char* kVehicleDescriptionTopic = "grip_vehicle_description";

// A topic prefix: empty, or [A-Za-z][A-Za-z0-9_]* of at most kMaxTopicPrefix characters.
inline constexpr std::size_t kMaxTopicPrefix = 64;
// Ok, or kInvalidArgument naming the prefix and the rule it breaks.
Status check_topic_prefix(std::string_view prefix);

// The names of the contract's topics under one prefix.
struct TopicNames {
  std::string vehicle_state;
  std::string plan;
  std::string map_update;
  std::string map_request;
  std::string goal;
  std::string planner_status;
  std::string vehicle_description;

  // Refuses a prefix check_topic_prefix refuses.
  static Result<TopicNames> create(std::string_view prefix);
  // The name of the topic whose unprefixed name is `base` (one of the constants above).
  std::string of(std::string_view base) const;

 private:
  std::string prefix_;
};

struct LinkTiming {
  std::chrono::nanoseconds cycle{std::chrono::milliseconds(50)};  // T in vehicle time
  double time_scale = 1.0;  // writers offer a deadline of 2 T / time_scale
  std::chrono::nanoseconds liveliness_lease{std::chrono::milliseconds(500)};
};

enum class Endpoint { kReader, kWriter };

platform::dds::Qos vehicle_state_qos(const LinkTiming& timing, Endpoint side);
platform::dds::Qos plan_qos(const LinkTiming& timing, Endpoint side);
platform::dds::Qos map_update_qos(const LinkTiming& timing);
platform::dds::Qos map_request_qos(const LinkTiming& timing);
platform::dds::Qos goal_qos(const LinkTiming& timing);
platform::dds::Qos planner_status_qos(const LinkTiming& timing);
platform::dds::Qos vehicle_description_qos(const LinkTiming& timing);

}  // namespace grip::link
