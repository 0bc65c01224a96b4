#include "grip/link/vehicle_description.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <span>
#include <string>
#include <string_view>

#include "grip/common/assert.hpp"
#include "grip/link/messages.hpp"
#include "grip/vehicles/vehicle_param_fields.hpp"

namespace grip::link {

namespace {

constexpr std::size_t kNameCapacity = sizeof(grip_msg_VehicleParameter::name);

std::string number(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.6g", value);
  return text;
}

// A name from the wire, read no further than its array even when it is not terminated.
std::string_view name_of(const grip_msg_VehicleParameter& p) {
  return {p.name, strnlen(p.name, kNameCapacity)};
}

bool agree(double a, double b) {
  const double tolerance =
      std::max(kDescriptionRelativeTolerance * std::max(std::abs(a), std::abs(b)),
               kDescriptionAbsoluteTolerance);
  return std::abs(a - b) <= tolerance;  // false for NaN
}

Error differs(std::string_view key, const std::string& theirs, const std::string& mine) {
  return invalid_argument("the vehicle describes itself with vehicle." + std::string(key) + " " +
                          theirs + ", this planner's parameters say " + mine);
}

}  // namespace

grip_msg_VehicleDescription describe_vehicle(const VehicleParams& params) noexcept {
  grip_msg_VehicleDescription msg{};
  msg.model = to_wire(vehicle_kind(params));
  for_each_param(params, [&msg](std::string_view key, double value) {
    // A model with more parameters than the message holds is a contract to widen, not an input.
    GRIP_ASSERT(msg.parameter_count < grip_msg_kMaxVehicleParameters);
    GRIP_ASSERT(key.size() < kNameCapacity);
    grip_msg_VehicleParameter& p = msg.parameters[msg.parameter_count++];
    key.copy(p.name, key.size());
    p.value = value;
  });
  return msg;
}

Status check_vehicle_description(const VehicleParams& mine,
                                 const grip_msg_VehicleDescription& theirs) {
  const VehicleKind my_model = vehicle_kind(mine);
  VehicleKind their_model{};
  if (!from_wire(theirs.model, their_model)) {
    std::int32_t raw = 0;
    std::memcpy(&raw, &theirs.model, sizeof raw);
    return differs("model", "unknown (" + std::to_string(raw) + ")",
                   std::string(vehicle_name(my_model)));
  }
  if (their_model != my_model) {
    return differs("model", std::string(vehicle_name(their_model)),
                   std::string(vehicle_name(my_model)));
  }
  if (theirs.parameter_count > grip_msg_kMaxVehicleParameters) {
    return invalid_argument("the vehicle's description holds " +
                            std::to_string(theirs.parameter_count) + " parameters, at most " +
                            std::to_string(grip_msg_kMaxVehicleParameters) + " fit");
  }
  const std::span<const grip_msg_VehicleParameter> given(theirs.parameters, theirs.parameter_count);
  // Each of theirs must be one of mine, once.
  for (std::size_t i = 0; i < given.size(); ++i) {
    const std::string_view key = name_of(given[i]);
    bool known = false;
    for_each_param(mine, [&](std::string_view my_key, double) { known = known || my_key == key; });
    if (!known) {
      return invalid_argument("the vehicle describes itself with vehicle." + std::string(key) +
                              ", which this planner's " + std::string(vehicle_name(my_model)) +
                              " parameters do not have");
    }
    for (std::size_t j = 0; j < i; ++j) {
      if (name_of(given[j]) == key) {
        return invalid_argument("the vehicle's description names vehicle." + std::string(key) +
                                " twice");
      }
    }
  }
  // Each of mine must be there, and agree.
  Status verdict = Ok{};
  for_each_param(mine, [&](std::string_view key, double value) {
    if (!verdict.ok()) return;
    const auto found =
        std::find_if(given.begin(), given.end(), [&](const auto& p) { return name_of(p) == key; });
    if (found == given.end()) {
      verdict = invalid_argument("the vehicle's description lacks vehicle." + std::string(key) +
                                 " (this planner's parameters say " + number(value) + ")");
    } else if (!agree(found->value, value)) {
      verdict = differs(key, number(found->value), number(value));
    }
  });
  return verdict;
}

Result<platform::dds::Writer<grip_msg_VehicleDescription>> publish_vehicle_description(
    const platform::dds::Participant& participant, const TopicNames& topics,
    const LinkTiming& timing, const VehicleParams& params) {
  auto writer = platform::dds::Writer<grip_msg_VehicleDescription>::create(
      participant, &grip_msg_VehicleDescription_desc, topics.vehicle_description,
      vehicle_description_qos(timing));
  if (!writer) return writer.error();
  if (Status s = writer->write(describe_vehicle(params)); !s) return s.error();
  return writer;
}

}  // namespace grip::link
