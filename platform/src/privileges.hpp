#pragma once
// Private to grip_platform: what the kernel checks before it grants a real-time policy or a
// memory lock, read for the calling thread, so that a refusal can say which check failed.

#include <cstdint>
#include <optional>
#include <string>

namespace grip::platform::detail {

// True iff `capability` (CAP_SYS_NICE, CAP_IPC_LOCK, ...) is in the calling thread's effective
// set, read with capget (the same bits as CapEff in /proc/thread-self/status).
bool has_effective_capability(int capability) noexcept;

// The soft limit of an RLIMIT_* resource; nullopt for RLIM_INFINITY or if getrlimit failed.
std::optional<std::uint64_t> soft_rlimit(int resource) noexcept;

// "unlimited" or the number.
std::string rlimit_text(std::optional<std::uint64_t> limit);

}  // namespace grip::platform::detail
