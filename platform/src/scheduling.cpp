#include "grip/platform/scheduling.hpp"

#include "grip/platform/overrun_watcher.hpp"

#include <linux/capability.h>
#include <pthread.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cstdint>
#include <vector>

#include "grip/common/enum_names.hpp"
#include "grip/platform/os_call.hpp"
#include "grip/platform/proc_files.hpp"
#include "privileges.hpp"
#include "scheduling_diagnosis.hpp"

namespace grip::platform {
namespace {

constexpr std::array<NamedValue<SchedPolicy>, 3> kPolicyNames{{
    {SchedPolicy::kDeadline, "deadline"},
    {SchedPolicy::kFifo, "fifo"},
    {SchedPolicy::kOther, "other"},
}};

constexpr std::array<NamedValue<SchedPolicy>, 3> kKernelPolicyNames{{
    {SchedPolicy::kDeadline, "SCHED_DEADLINE"},
    {SchedPolicy::kFifo, "SCHED_FIFO"},
    {SchedPolicy::kOther, "SCHED_OTHER"},
}};

constexpr std::array<NamedValue<PolicyRequest>, 4> kRequestNames{{
    {PolicyRequest::kAuto, "auto"},
    {PolicyRequest::kDeadline, "deadline"},
    {PolicyRequest::kFifo, "fifo"},
    {PolicyRequest::kOther, "other"},
}};

// glibc 2.36 declares neither struct sched_attr nor sched_setattr. This is the kernel's layout,
// SCHED_ATTR_SIZE_VER0 of include/uapi/linux/sched/types.h.
struct SchedAttr {
  std::uint32_t size;
  std::uint32_t sched_policy;
  std::uint64_t sched_flags;
  std::int32_t sched_nice;
  std::uint32_t sched_priority;
  std::uint64_t sched_runtime;   // [ns]
  std::uint64_t sched_deadline;  // [ns]
  std::uint64_t sched_period;    // [ns]
};
static_assert(sizeof(SchedAttr) == 48, "SCHED_ATTR_SIZE_VER0");

constexpr std::uint32_t kSchedDeadline = 6;            // include/uapi/linux/sched.h
constexpr std::uint64_t kSchedFlagDlOverrun = 0x04;    // SIGXCPU when the runtime is exhausted
constexpr std::chrono::nanoseconds kMinRuntime{1024};  // 1 << DL_SCALE in the kernel
constexpr std::chrono::milliseconds kMinPeriod{1};

// Each returns 0 or the errno of the refusal.
int set_deadline(const SchedulingRequest& request) noexcept {
  SchedAttr attr{};
  attr.size = sizeof(SchedAttr);
  attr.sched_policy = kSchedDeadline;
  // SIGXCPU on an overrun only where a watcher counts it: unwatched, it would kill the process.
  attr.sched_flags = OverrunWatcher::active() ? kSchedFlagDlOverrun : 0;
  attr.sched_runtime = static_cast<std::uint64_t>(request.runtime.count());
  attr.sched_deadline = static_cast<std::uint64_t>(request.deadline.count());
  attr.sched_period = static_cast<std::uint64_t>(request.period.count());
  // pid 0: the calling thread.
  return os_call("sched_setattr", [&] { return ::syscall(SYS_sched_setattr, 0, &attr, 0U); }).error;
}

int set_posix_policy(int policy, int priority) noexcept {
  sched_param param{};
  param.sched_priority = priority;
  return os_call_returning_error(
             "pthread_setschedparam",
             [&] { return ::pthread_setschedparam(::pthread_self(), policy, &param); })
      .error;
}

int pin_to_cpu(int cpu) noexcept {
  cpu_set_t set;
  CPU_ZERO(&set);
  CPU_SET(static_cast<std::size_t>(cpu), &set);
  return os_call_returning_error(
             "pthread_setaffinity_np",
             [&] { return ::pthread_setaffinity_np(::pthread_self(), sizeof set, &set); })
      .error;
}

std::string refused(SchedPolicy policy, const std::string& why) {
  return std::string(kernel_policy_name(policy)) + " refused: " + why;
}

std::string ns_text(std::chrono::nanoseconds duration) {
  return std::to_string(duration.count()) + " ns";
}

}  // namespace

std::string_view policy_name(SchedPolicy policy) noexcept { return name_in(kPolicyNames, policy); }

std::string_view kernel_policy_name(SchedPolicy policy) noexcept {
  return name_in(kKernelPolicyNames, policy);
}

std::string_view request_name(PolicyRequest request) noexcept {
  return name_in(kRequestNames, request);
}

Result<PolicyRequest> parse_policy_request(std::string_view name) {
  return value_named(kRequestNames, name, "scheduling policy");
}

Status validate(const SchedulingRequest& request) {
  const bool wants_deadline =
      request.request == PolicyRequest::kAuto || request.request == PolicyRequest::kDeadline;
  const bool wants_fifo =
      request.request == PolicyRequest::kAuto || request.request == PolicyRequest::kFifo;
  if (wants_deadline) {
    const std::array<std::pair<const char*, std::chrono::nanoseconds>, 3> fields{{
        {"runtime", request.runtime},
        {"deadline", request.deadline},
        {"period", request.period},
    }};
    for (const auto& [field, value] : fields) {
      if (value.count() <= 0) {
        return invalid_argument("scheduling." + std::string(field) + " must be > 0 (got " +
                                ns_text(value) + ")");
      }
    }
    if (request.runtime < kMinRuntime) {
      return invalid_argument(
          "scheduling.runtime must be >= 1024 ns, the kernel's smallest "
          "SCHED_DEADLINE runtime (got " +
          ns_text(request.runtime) + ")");
    }
    if (request.runtime > request.deadline) {
      return invalid_argument("scheduling.runtime (" + ns_text(request.runtime) +
                              ") must be <= scheduling.deadline (" + ns_text(request.deadline) +
                              ")");
    }
    if (request.deadline > request.period) {
      return invalid_argument("scheduling.deadline (" + ns_text(request.deadline) +
                              ") must be <= scheduling.period (" + ns_text(request.period) + ")");
    }
    if (request.period < kMinPeriod) {
      return invalid_argument("scheduling.period must be >= 1 ms (got " + ns_text(request.period) +
                              ")");
    }
  }
  if (request.cpu < -1 || request.cpu >= CPU_SETSIZE) {
    return invalid_argument("scheduling.cpu must be -1 (any) or in [0, " +
                            std::to_string(CPU_SETSIZE - 1) + "] (got " +
                            std::to_string(request.cpu) + ")");
  }
  if (request.cpu >= 0 && request.request == PolicyRequest::kDeadline) {
    return invalid_argument("scheduling.cpu pins the thread to CPU " + std::to_string(request.cpu) +
                            ", but SCHED_DEADLINE needs it free to run on every CPU of its root "
                            "domain: pin with policy fifo or other");
  }
  if (wants_fifo && (request.fifo_priority < 1 || request.fifo_priority > 99)) {
    return invalid_argument("scheduling.fifo_priority must be in [1, 99] (got " +
                            std::to_string(request.fifo_priority) + ")");
  }
  return Ok{};
}

Result<SchedulingOutcome> apply_scheduling(const SchedulingRequest& request) {
  if (const Status valid = validate(request); !valid.ok()) return valid.error();
  std::string reasons;
  if (request.cpu >= 0) {
    if (const int error = pin_to_cpu(request.cpu); error != 0) {
      return Error{ErrorCode::kIo, "pinning to CPU " + std::to_string(request.cpu) +
                                       " refused: " + std::string(errno_name(error)) +
                                       " (not online, or outside the thread's cpuset)"};
    }
    reasons =
        "SCHED_DEADLINE not tried: the thread is pinned to CPU " + std::to_string(request.cpu);
  }
  const int priority = request.fifo_priority;
  switch (request.request) {
    case PolicyRequest::kDeadline: {
      const int error = set_deadline(request);
      if (error == 0) return SchedulingOutcome{SchedPolicy::kDeadline, {}};
      return Error{ErrorCode::kIo, refused(SchedPolicy::kDeadline,
                                           detail::explain_deadline_refusal(error, request))};
    }
    case PolicyRequest::kFifo: {
      const int error = set_posix_policy(SCHED_FIFO, priority);
      if (error == 0) return SchedulingOutcome{SchedPolicy::kFifo, {}};
      return Error{ErrorCode::kIo,
                   refused(SchedPolicy::kFifo, detail::explain_fifo_refusal(error, priority))};
    }
    case PolicyRequest::kOther: {
      const int error = set_posix_policy(SCHED_OTHER, 0);
      if (error == 0) return SchedulingOutcome{SchedPolicy::kOther, {}};
      return Error{ErrorCode::kIo,
                   refused(SchedPolicy::kOther, detail::explain_other_refusal(error))};
    }
    case PolicyRequest::kAuto:
      break;
  }
  int error = 0;
  if (request.cpu < 0) {
    error = set_deadline(request);
    if (error == 0) return SchedulingOutcome{SchedPolicy::kDeadline, {}};
    reasons = refused(SchedPolicy::kDeadline, detail::explain_deadline_refusal(error, request));
  }
  error = set_posix_policy(SCHED_FIFO, priority);
  if (error == 0) return SchedulingOutcome{SchedPolicy::kFifo, reasons};
  reasons += "; " + refused(SchedPolicy::kFifo, detail::explain_fifo_refusal(error, priority));
  error = set_posix_policy(SCHED_OTHER, 0);
  if (error == 0) return SchedulingOutcome{SchedPolicy::kOther, reasons};
  reasons += "; " + refused(SchedPolicy::kOther, detail::explain_other_refusal(error));
  return Error{ErrorCode::kIo, reasons};
}

SchedPolicy current_policy() noexcept {
  const auto got = os_call("sched_getscheduler", [] { return ::sched_getscheduler(0); });
  if (!got.ok()) return SchedPolicy::kOther;  // cannot fail for the calling thread
  switch (got.value & ~SCHED_RESET_ON_FORK) {
    case static_cast<int>(kSchedDeadline):
      return SchedPolicy::kDeadline;
    case SCHED_FIFO:
    case SCHED_RR:
      return SchedPolicy::kFifo;
    default:
      return SchedPolicy::kOther;
  }
}

DeadlineReservation current_deadline_reservation() noexcept {
  SchedAttr attr{};
  const auto got = os_call("sched_getattr", [&] {
    return ::syscall(SYS_sched_getattr, 0, &attr, static_cast<unsigned>(sizeof attr), 0U);
  });
  if (!got.ok() || attr.sched_policy != kSchedDeadline) return {};
  return {std::chrono::nanoseconds(attr.sched_runtime),
          std::chrono::nanoseconds(attr.sched_deadline),
          std::chrono::nanoseconds(attr.sched_period)};
}

SchedulingPrivileges scheduling_privileges() {
  SchedulingPrivileges privileges;
  privileges.cap_sys_nice = detail::has_effective_capability(CAP_SYS_NICE);
  privileges.rlimit_rtprio = detail::soft_rlimit(RLIMIT_RTPRIO).value_or(UINT64_MAX);

  cpu_set_t allowed_set;
  CPU_ZERO(&allowed_set);
  std::vector<int> allowed;
  const auto got = os_call("sched_getaffinity", [&] {
    return ::sched_getaffinity(0, sizeof(allowed_set), &allowed_set);
  });
  if (got.ok()) {
    for (std::size_t cpu = 0; cpu < static_cast<std::size_t>(CPU_SETSIZE); ++cpu) {
      if (CPU_ISSET(cpu, &allowed_set)) allowed.push_back(static_cast<int>(cpu));
    }
  }
  privileges.allowed_cpus = got.ok() ? detail::format_cpu_list(allowed) : got.describe();

  const Result<std::string> online_text = detail::read_small_file("/sys/devices/system/cpu/online");
  const Result<std::vector<int>> online = online_text.ok()
                                              ? detail::parse_cpu_list(*online_text)
                                              : Result<std::vector<int>>(online_text.error());
  if (!got.ok() || !online.ok()) {
    // Cannot tell: do not blame the affinity for a refusal.
    privileges.online_cpus =
        online.ok() ? detail::format_cpu_list(*online) : online.error().message;
    privileges.affinity_spans_online_cpus = true;
    return privileges;
  }
  privileges.online_cpus = detail::format_cpu_list(*online);
  privileges.affinity_spans_online_cpus =
      std::includes(allowed.begin(), allowed.end(), online->begin(), online->end());
  return privileges;
}

}  // namespace grip::platform
