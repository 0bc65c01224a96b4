// libFuzzer target: a received VehicleDescription, checked against each vehicle model's own
// parameters as the planner checks it (the check is its whole application: a match lets
// planning start, anything else is refused with a message).

#include <cstdint>
#include <cstdlib>

#include "fuzz_bytes.hpp"
#include "grip/link/vehicle_description.hpp"
#include "samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  const grip_msg_VehicleDescription msg = grip::fuzz::vehicle_description_from(in);
  for (const grip::VehicleKind kind :
       {grip::VehicleKind::kDdVelocity, grip::VehicleKind::kDdAcceleration,
        grip::VehicleKind::kCar}) {
    const grip::VehicleParams mine = grip::default_vehicle_params(kind);
    const grip::Status s = grip::link::check_vehicle_description(mine, msg);
    if (!s.ok() && s.error().message.empty()) std::abort();
    // A described vehicle is described back identically.
    if (s.ok() && msg.parameter_count > grip_msg_kMaxVehicleParameters) std::abort();
  }
  return 0;
}
