#include "description_watch.hpp"

#include "grip/link/vehicle_description.hpp"

namespace grip::rt::dds {

void DescriptionWatch::observe(const grip_msg_VehicleDescription& theirs,
                               const std::function<void(const std::string&)>& warn) {
  const Described before = verdict();
  if (before == Described::kDiffers) return;  // refused already; mismatch_ stays as it is
  const Status checked = link::check_vehicle_description(mine_, theirs);
  if (checked.ok()) {
    verdict_.store(Described::kMatches, std::memory_order_release);
    return;
  }
  mismatch_ = checked.error().message;
  verdict_.store(Described::kDiffers, std::memory_order_release);
  if (before == Described::kMatches) {
    warn("the vehicle described itself anew and differs: " + mismatch_ + "; planning stops");
  }
}

}  // namespace grip::rt::dds
