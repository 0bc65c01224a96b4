#pragma once
// The vehicle's description as the planner participant watches it (link/vehicle_description.hpp):
// the receive thread checks every description against the planner's own vehicle parameters;
// start-up, on run()'s thread, waits for one that matches and refuses the vehicle on a mismatch;
// later, run()'s thread polls the verdict and stops planning when a description that differs
// arrives (a new incarnation of the vehicle, with other parameters). The planning thread never
// looks: a verdict is an atomic, and the message behind it is written once, before it.

#include <atomic>
#include <cstdint>
#include <functional>
#include <string>
#include <utility>

#include "grip/vehicles/vehicle_params.hpp"
#include "vehicle_description.h"

namespace grip::rt::dds {

enum class Described : std::uint8_t {
  kNotYet,   // no description came
  kMatches,  // every one so far matched
  kDiffers,  // one differed: for good, whatever comes after
};

class DescriptionWatch {
 public:
  explicit DescriptionWatch(VehicleParams mine) : mine_(std::move(mine)) {}

  // Receive thread. The first description that differs is kept; a difference after a match is
  // a warning too (through `warn`), since planning was under way.
  void observe(const grip_msg_VehicleDescription& theirs,
               const std::function<void(const std::string&)>& warn);

  // Any thread.
  Described verdict() const noexcept { return verdict_.load(std::memory_order_acquire); }
  // Why the vehicle was refused; only once verdict() is kDiffers.
  const std::string& mismatch() const noexcept { return mismatch_; }

 private:
  VehicleParams mine_;
  std::string mismatch_;  // written once, before verdict_ turns kDiffers (release)
  std::atomic<Described> verdict_{Described::kNotYet};
};

}  // namespace grip::rt::dds
