// libFuzzer target: a received PlannerStatus, validated as the vehicle side validates it, and
// when valid read as the simulator reads it (its policy name, its progress figures).

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <string>

#include "fuzz_bytes.hpp"
#include "grip/link/messages.hpp"
#include "samples.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  grip::fuzz::FuzzBytes in(data, size);
  const grip_msg_PlannerStatus msg = grip::fuzz::planner_status_from(in);
  if (!grip::link::check_planner_status(msg).ok()) return 0;
  const std::string policy(msg.policy);
  if (policy.size() >= sizeof msg.policy) std::abort();
  if (!(msg.cycle_time_s >= 0.0)) std::abort();
  const std::string given_up = std::to_string(msg.frontier_groups_given_up);
  static_cast<void>(given_up);
  return 0;
}
