// libFuzzer target: a received VehicleState, validated for each vehicle model as the planner
// validates it, and when valid applied as the planner's receive side applies it (the vehicle
// clock, the state handed to the planner).

#include <cstdint>
#include <cstdlib>

#include "fuzz_bytes.hpp"
#include "grip/link/messages.hpp"
#include "grip/rt/vehicle_clock.hpp"
#include "grip/vehicles/vehicle_params.hpp"
#include "samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  const grip_msg_VehicleState msg = grip::fuzz::vehicle_state_from(in);
  const auto last_stamp = in.take<std::uint64_t>();
  const auto local_ns = in.take<std::int64_t>();
  for (const grip::VehicleKind kind :
       {grip::VehicleKind::kDdVelocity, grip::VehicleKind::kDdAcceleration,
        grip::VehicleKind::kCar}) {
    grip::with_default_vehicle(kind, [&](const auto& vehicle) {
      using V = std::remove_cvref_t<decltype(vehicle)>;
      const grip::link::Verdict verdict = grip::link::check_vehicle_state(msg, vehicle, last_stamp);
      if (!verdict.ok()) {
        if (grip::link::rejection_name(verdict.reason).empty()) std::abort();
        return;
      }
      grip::rt::VehicleClock clock;
      clock.observe(msg.stamp_ns, local_ns, msg.time_scale);
      static_cast<void>(clock.vehicle_ns(local_ns, msg.time_scale));
      const typename V::State q = grip::link::state_from_wire<V>(msg);
      if (!vehicle.validate_state(q).ok()) std::abort();  // the verdict said it was valid
      double back[grip_msg_kMaxStateDim];
      std::uint32_t dim = 0;
      grip::link::state_to_wire<V>(q, back, dim);
      if (dim != msg.state_dim) std::abort();
    });
  }
  return 0;
}
