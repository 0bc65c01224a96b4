#include "scheduling_diagnosis.hpp"

#include <sched.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>
#include <optional>
#include <string_view>
#include <vector>

#include "grip/platform/os_call.hpp"
#include "grip/platform/proc_files.hpp"

namespace grip::platform::detail {
namespace {

constexpr const char* kRtRuntimeFile = "/proc/sys/kernel/sched_rt_runtime_us";
constexpr const char* kRtPeriodFile = "/proc/sys/kernel/sched_rt_period_us";

std::vector<std::string_view> split(std::string_view text, char separator) {
  std::vector<std::string_view> parts;
  while (true) {
    const std::size_t at = text.find(separator);
    parts.push_back(text.substr(0, at));
    if (at == std::string_view::npos) return parts;
    text.remove_prefix(at + 1);
  }
}

bool contains(const std::vector<std::string_view>& parts, std::string_view wanted) {
  return std::find(parts.begin(), parts.end(), wanted) != parts.end();
}

std::string number_or_unknown(std::optional<std::int64_t> value) {
  return value ? std::to_string(*value) : std::string("unknown");
}

struct CgroupRtRuntime {
  std::string file;  // ".../cpu.rt_runtime_us" of the calling thread's cgroup
  std::int64_t runtime_us;
};

// The calling thread's cgroup v1 cpu.rt_runtime_us, present only with CONFIG_RT_GROUP_SCHED on
// the v1 "cpu" hierarchy. Where it is 0, the kernel refuses SCHED_FIFO/RR with EPERM.
std::optional<CgroupRtRuntime> cgroup_rt_runtime() {
  const Result<std::string> cgroups = read_small_file("/proc/thread-self/cgroup");
  const Result<std::string> mounts = read_small_file("/proc/self/mountinfo");
  if (!cgroups.ok() || !mounts.ok()) return std::nullopt;
  std::optional<std::string_view> cgroup_path;
  for (const std::string_view line : split(*cgroups, '\n')) {  // "4:cpu,cpuacct:/a/b"
    const std::vector<std::string_view> fields = split(line, ':');
    if (fields.size() == 3 && contains(split(fields[1], ','), "cpu")) cgroup_path = fields[2];
  }
  if (!cgroup_path) return std::nullopt;
  // "36 25 0:31 <root> <mount point> <options> [optional fields] - cgroup <source> rw,cpu"
  for (const std::string_view line : split(*mounts, '\n')) {
    const std::size_t dash = line.find(" - ");
    if (dash == std::string_view::npos) continue;
    const std::vector<std::string_view> before = split(line.substr(0, dash), ' ');
    const std::vector<std::string_view> after = split(line.substr(dash + 3), ' ');
    if (before.size() < 5 || after.size() < 3 || after[0] != "cgroup") continue;
    if (!contains(split(after[2], ','), "cpu")) continue;
    std::string_view relative = *cgroup_path;
    const std::string_view root = before[3];
    if (root != "/" && relative.substr(0, root.size()) == root) relative.remove_prefix(root.size());
    std::string file(before[4]);
    if (relative != "/") file += relative;
    file += "/cpu.rt_runtime_us";
    const std::optional<std::int64_t> runtime = read_integer_file(file);
    if (!runtime) return std::nullopt;
    return CgroupRtRuntime{file, *runtime};
  }
  return std::nullopt;
}

// Why a real-time policy may be refused although the capability checks passed: no real-time
// runtime for the system or the thread's cgroup. Empty when neither is the case.
std::string rt_runtime_cause() {
  const std::optional<std::int64_t> system = read_integer_file(kRtRuntimeFile);
  if (system && *system == 0) {
    return std::string(kRtRuntimeFile) + " is 0: the system gives real-time tasks no runtime";
  }
  const std::optional<CgroupRtRuntime> cgroup = cgroup_rt_runtime();
  if (cgroup && cgroup->runtime_us == 0) {
    return "the thread's cgroup has " + cgroup->file +
           " = 0: real-time group scheduling gives it no real-time runtime (give the cgroup a "
           "budget or run the process in one that has)";
  }
  return {};
}

std::string with_name(int error, const std::string& why) {
  return std::string(errno_name(error)) + " (" + why + ")";
}

std::string per_mille_text(std::int64_t numerator, std::int64_t denominator) {
  if (denominator <= 0) return "?";
  const std::int64_t per_mille = numerator * 1000 / denominator;
  return std::to_string(per_mille / 10) + "." + std::to_string(per_mille % 10) + "%";
}

}  // namespace

std::string explain_deadline_refusal(int error, const SchedulingRequest& request) {
  const std::int64_t runtime_ns = request.runtime.count();
  const std::int64_t deadline_ns = request.deadline.count();
  const std::int64_t period_ns = request.period.count();
  switch (error) {
    case EPERM: {
      const SchedulingPrivileges privileges = scheduling_privileges();
      if (!privileges.cap_sys_nice) return with_name(error, "no CAP_SYS_NICE");
      if (!privileges.affinity_spans_online_cpus) {
        return with_name(error, "the thread's CPU affinity (CPUs " + privileges.allowed_cpus +
                                    ") does not span all online CPUs (" + privileges.online_cpus +
                                    "): SCHED_DEADLINE needs the whole root domain, so do not "
                                    "pin a deadline thread");
      }
      const std::string rt_cause = rt_runtime_cause();
      if (!rt_cause.empty()) return with_name(error, rt_cause);
      return with_name(error,
                       "refused although CAP_SYS_NICE is present and the affinity spans all "
                       "online CPUs; an exclusive cpuset may have split the root domain");
    }
    case EBUSY: {
      const std::optional<std::int64_t> rt_runtime = read_integer_file(kRtRuntimeFile);
      const std::optional<std::int64_t> rt_period = read_integer_file(kRtPeriodFile);
      return with_name(error,
                       "deadline admission control: the reservation runtime/period = " +
                           per_mille_text(runtime_ns, period_ns) +
                           " of a CPU does not fit the bandwidth left; deadline tasks may use "
                           "sched_rt_runtime_us/sched_rt_period_us = " +
                           number_or_unknown(rt_runtime) + "/" + number_or_unknown(rt_period) +
                           " of each CPU of the root domain, minus existing reservations (other "
                           "deadline threads, the fair server)");
    }
    case EINVAL: {
      const std::optional<std::int64_t> min_us =
          read_integer_file("/proc/sys/kernel/sched_deadline_period_min_us");
      const std::optional<std::int64_t> max_us =
          read_integer_file("/proc/sys/kernel/sched_deadline_period_max_us");
      return with_name(
          error, "the kernel rejected runtime " + std::to_string(runtime_ns) + " ns, deadline " +
                     std::to_string(deadline_ns) + " ns, period " + std::to_string(period_ns) +
                     " ns: it needs 1024 ns <= runtime <= deadline <= period and "
                     "the period within sched_deadline_period_{min,max}_us = [" +
                     number_or_unknown(min_us) + ", " + number_or_unknown(max_us) + "] us");
    }
    case ENOSYS:
      return with_name(error, "this kernel has no sched_setattr (SCHED_DEADLINE needs Linux 3.14)");
    case E2BIG:
      return with_name(error, "the kernel does not accept this struct sched_attr size");
    default:
      return describe_errno(error);
  }
}

std::string explain_fifo_refusal(int error, int priority) {
  switch (error) {
    case EPERM: {
      const SchedulingPrivileges privileges = scheduling_privileges();
      const std::string rt_cause = rt_runtime_cause();
      if (!privileges.cap_sys_nice) {
        const std::string limit = privileges.rlimit_rtprio == UINT64_MAX
                                      ? std::string("unlimited")
                                      : std::to_string(privileges.rlimit_rtprio);
        if (privileges.rlimit_rtprio < static_cast<std::uint64_t>(priority)) {
          return with_name(error, "no CAP_SYS_NICE and RLIMIT_RTPRIO " + limit + " < priority " +
                                      std::to_string(priority));
        }
        return with_name(error, "no CAP_SYS_NICE; RLIMIT_RTPRIO " + limit + " allows priority " +
                                    std::to_string(priority) + ", so: " +
                                    (rt_cause.empty() ? std::string("cause unknown") : rt_cause));
      }
      if (!rt_cause.empty()) return with_name(error, rt_cause);
      return with_name(error, "refused although CAP_SYS_NICE is present; cause unknown");
    }
    case EINVAL: {
      const auto min =
          os_call("sched_get_priority_min", [] { return ::sched_get_priority_min(SCHED_FIFO); });
      const auto max =
          os_call("sched_get_priority_max", [] { return ::sched_get_priority_max(SCHED_FIFO); });
      return with_name(error, "priority " + std::to_string(priority) + " is outside [" +
                                  std::to_string(min.value) + ", " + std::to_string(max.value) +
                                  "]");
    }
    default:
      return describe_errno(error);
  }
}

std::string explain_other_refusal(int error) {
  if (error == EPERM) {
    return with_name(error,
                     "without CAP_SYS_NICE a thread leaves SCHED_IDLE or drops "
                     "reset-on-fork only if RLIMIT_NICE allows its nice value");
  }
  return describe_errno(error);
}

}  // namespace grip::platform::detail
