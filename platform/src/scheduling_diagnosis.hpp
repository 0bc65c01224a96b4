#pragma once
// Private to grip_platform: turns the errno of a refused scheduling call into the errno's name
// and its likely cause on this machine, "EPERM (no CAP_SYS_NICE)", by reading what the kernel
// checks (capabilities, RLIMIT_RTPRIO, affinity, real-time runtime of the system and cgroup).

#include <string>

#include "grip/platform/scheduling.hpp"

namespace grip::platform::detail {

std::string explain_deadline_refusal(int error, const SchedulingRequest& request);
std::string explain_fifo_refusal(int error, int priority);
std::string explain_other_refusal(int error);

}  // namespace grip::platform::detail
