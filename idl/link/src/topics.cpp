#include "grip/link/topics.hpp"

#include <algorithm>

namespace grip::link {

namespace {

platform::dds::Qos keep_last(const LinkTiming& timing, std::int32_t depth) {
  platform::dds::Qos qos;
  qos.reliable = true;
  qos.history_depth = depth;
  qos.max_blocking_time = std::chrono::milliseconds(10);
  qos.liveliness_lease = timing.liveliness_lease;
  return qos;
}

// The periodic links: a peer silent for two cycles is late (DEADLINE_MISSED on both sides).
// An offered deadline must not exceed the requested one, so a slowed-down simulation
// (time scale < 1) offers 2 T too.
platform::dds::Qos periodic(const LinkTiming& timing, Endpoint side, std::int32_t depth) {
  platform::dds::Qos qos = keep_last(timing, depth);
  const auto two_cycles = 2 * timing.cycle;
  qos.deadline =
      side == Endpoint::kReader
          ? two_cycles
          : std::chrono::nanoseconds(static_cast<std::int64_t>(
                static_cast<double>(two_cycles.count()) / std::max(1.0, timing.time_scale)));
  return qos;
}

}  // namespace

platform::dds::Qos vehicle_state_qos(const LinkTiming& timing, Endpoint side) {
  return periodic(timing, side, 1);
}
platform::dds::Qos plan_qos(const LinkTiming& timing, Endpoint side) {
  return periodic(timing, side, kPlanHistoryDepth);
}
platform::dds::Qos map_update_qos(const LinkTiming& timing) { return keep_last(timing, 64); }
platform::dds::Qos map_request_qos(const LinkTiming& timing) { return keep_last(timing, 4); }
platform::dds::Qos goal_qos(const LinkTiming& timing) {
  platform::dds::Qos qos = keep_last(timing, 1);
  qos.transient_local = true;
  return qos;
}
platform::dds::Qos planner_status_qos(const LinkTiming& timing) { return keep_last(timing, 1); }
platform::dds::Qos vehicle_description_qos(const LinkTiming& timing) { return goal_qos(timing); }

Status check_topic_prefix(std::string_view prefix) {
  const auto refuse = [&](const char* rule) {
    return invalid_argument("topic prefix \"" + std::string(prefix) + "\" " + rule);
  };
  if (prefix.size() > kMaxTopicPrefix) {
    return refuse("is longer than 64 characters");
  }
  // ASCII only, whatever the locale: the name is on the wire.
  const auto letter = [](char c) { return (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z'); };
  const auto digit = [](char c) { return c >= '0' && c <= '9'; };
  if (!prefix.empty() && !letter(prefix.front())) return refuse("must start with a letter");
  for (const char c : prefix) {
    if (!letter(c) && !digit(c) && c != '_') {
      return refuse("may hold only letters, digits and '_'");
    }
  }
  return Ok{};
}

Result<TopicNames> TopicNames::create(std::string_view prefix) {
  if (Status s = check_topic_prefix(prefix); !s) return s.error();
  TopicNames names;
  names.prefix_ = prefix.empty() ? std::string() : std::string(prefix) + "_";
  names.vehicle_state = names.of(kVehicleStateTopic);
  names.plan = names.of(kPlanTopic);
  names.map_update = names.of(kMapUpdateTopic);
  names.map_request = names.of(kMapRequestTopic);
  names.goal = names.of(kGoalTopic);
  names.planner_status = names.of(kPlannerStatusTopic);
  names.vehicle_description = names.of(kVehicleDescriptionTopic);
  return names;
}

std::string TopicNames::of(std::string_view base) const { return prefix_ + std::string(base); }

}  // namespace grip::link
