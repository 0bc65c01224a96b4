#pragma once
// Scheduling policy for the CALLING thread: SCHED_DEADLINE when the kernel grants it, else
// SCHED_FIFO, else SCHED_OTHER, and a sentence for every refusal that says why (which errno,
// which missing capability, limit or affinity), so that an operator can fix the machine.
//
// Start-up only: apply_scheduling allocates its messages. Call it once at the top of the thread
// it is for (RealtimeThread does), never on the planning path.
//
// What a SCHED_DEADLINE thread cannot do (the kernel refuses with EAGAIN): create threads or
// fork (clone fails), so create every thread before, from a SCHED_OTHER thread. It must also
// stay allowed on every CPU of its root domain: sched_setaffinity to a subset fails with EBUSY,
// and a thread already pinned to a subset is refused SCHED_DEADLINE with EPERM. A runtime overrun
// raises SIGXCPU for the whole process (see overrun_watcher.hpp).

#include <chrono>
#include <cstdint>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::platform {

// What a thread ends up running under.
enum class SchedPolicy { kDeadline, kFifo, kOther };

// What a thread asks for: kAuto tries kDeadline, then kFifo, then kOther; an explicit policy
// tries only itself and fails if refused.
enum class PolicyRequest { kAuto, kDeadline, kFifo, kOther };

std::string_view policy_name(SchedPolicy policy) noexcept;         // "deadline", "fifo", "other"
std::string_view kernel_policy_name(SchedPolicy policy) noexcept;  // "SCHED_DEADLINE", ...
std::string_view request_name(PolicyRequest request) noexcept;     // "auto", "deadline", ...

// "auto" | "deadline" | "fifo" | "other"; an error lists the valid names.
Result<PolicyRequest> parse_policy_request(std::string_view name);

struct SchedulingRequest {
  PolicyRequest request = PolicyRequest::kAuto;
  // SCHED_DEADLINE reservation: `runtime` of CPU time every `period`, finished within
  // `deadline` of the period's start. Needed (and validated) for kAuto and kDeadline only.
  std::chrono::nanoseconds runtime{};   // > 0, >= 1024 ns (the kernel's smallest), <= deadline
  std::chrono::nanoseconds deadline{};  // <= period
  std::chrono::nanoseconds period{};    // >= 1 ms
  // SCHED_FIFO priority, 1 (lowest) .. 99. Needed (and validated) for kAuto and kFifo only.
  int fifo_priority = 80;
  // The one CPU the thread may run on (-1: any). A SCHED_DEADLINE thread must be free to run
  // on every CPU of its root domain, so a pinned thread is never given it: kDeadline is refused
  // and kAuto starts at SCHED_FIFO.
  int cpu = -1;
};

// Ok, or kInvalidArgument naming the field: "scheduling.runtime (3000000 ns) must be <=
// scheduling.deadline (2000000 ns)".
Status validate(const SchedulingRequest& request);

struct SchedulingOutcome {
  SchedPolicy policy = SchedPolicy::kOther;
  // Empty when the first choice was granted. Otherwise every refused policy with its errno name
  // and the likely cause, in the order tried: "SCHED_DEADLINE refused: EPERM (no CAP_SYS_NICE);
  // SCHED_FIFO refused: EPERM (no CAP_SYS_NICE and RLIMIT_RTPRIO 0 < priority 80)".
  std::string fallback_reason;
};

// Applies `request` to the calling thread (see the file comment for the order). Errors:
// kInvalidArgument when validate() refuses the request; kIo when an explicitly requested policy
// is refused (the message says why, as fallback_reason would) or, for kAuto, when even
// SCHED_OTHER is refused. SCHED_DEADLINE is set with SCHED_FLAG_DL_OVERRUN while an OverrunWatcher
// runs: a thread that exhausts its runtime makes the kernel send SIGXCPU to the process.
Result<SchedulingOutcome> apply_scheduling(const SchedulingRequest& request);

// The calling thread's policy as the kernel reports it (sched_getscheduler). SCHED_RR counts as
// kFifo; SCHED_BATCH and SCHED_IDLE count as kOther.
SchedPolicy current_policy() noexcept;

// The calling thread's SCHED_DEADLINE reservation as the kernel holds it (sched_getattr); all
// zero when the thread runs under another policy.
struct DeadlineReservation {
  std::chrono::nanoseconds runtime{};
  std::chrono::nanoseconds deadline{};
  std::chrono::nanoseconds period{};
};
DeadlineReservation current_deadline_reservation() noexcept;

// What the kernel checks before granting a real-time policy, read for the calling thread.
struct SchedulingPrivileges {
  bool cap_sys_nice = false;  // CAP_SYS_NICE in the effective set: any policy is allowed
  // Soft RLIMIT_RTPRIO: without CAP_SYS_NICE, SCHED_FIFO up to this priority is allowed.
  // RLIM_INFINITY reads as UINT64_MAX.
  std::uint64_t rlimit_rtprio = 0;
  // SCHED_DEADLINE needs the thread allowed on every CPU of its root domain; checked against
  // the online CPUs (exact unless exclusive cpusets partition the machine).
  bool affinity_spans_online_cpus = false;
  std::string allowed_cpus;  // the thread's affinity, "0-1"
  std::string online_cpus;   // /sys/devices/system/cpu/online, "0-1"
};
SchedulingPrivileges scheduling_privileges();

}  // namespace grip::platform
