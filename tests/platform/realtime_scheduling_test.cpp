#include "grip/platform/scheduling.hpp"
#include "test_paths.hpp"

#include <gtest/gtest.h>
#include <sched.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

#include <array>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <iostream>
#include <memory>
#include <optional>
#include <semaphore>
#include <string>
#include <thread>
#include <tuple>
#include <utility>
#include <vector>

// Every test that changes a policy does so in a fresh thread that then exits, so the test's main
// thread stays SCHED_OTHER: a SCHED_DEADLINE thread could not even start the next test's thread.

extern char** environ;

namespace grip::platform {
namespace {

using std::chrono::microseconds;
using std::chrono::milliseconds;

// Runs `work` in a new thread and returns what it returned.
template <typename Work>
auto in_fresh_thread(Work work) {
  std::optional<decltype(work())> result;
  std::thread thread([&] { result.emplace(work()); });
  thread.join();
  return std::move(*result);
}

SchedulingRequest request(PolicyRequest policy) {
  SchedulingRequest r;
  r.request = policy;
  r.runtime = milliseconds(2);
  r.deadline = milliseconds(10);
  r.period = milliseconds(10);
  r.fifo_priority = 80;
  return r;
}

struct Applied {
  Result<SchedulingOutcome> outcome;
  SchedPolicy policy_after;
  int fifo_priority_after;
};

Applied apply_once_in_fresh_thread(const SchedulingRequest& r, bool pin_to_cpu0) {
  return in_fresh_thread([&] {
    if (pin_to_cpu0) {
      cpu_set_t cpu0;
      CPU_ZERO(&cpu0);
      CPU_SET(0, &cpu0);
      EXPECT_EQ(sched_setaffinity(0, sizeof(cpu0), &cpu0), 0) << std::strerror(errno);
    }
    Result<SchedulingOutcome> outcome = apply_scheduling(r);
    sched_param param{};
    sched_getparam(0, &param);
    return Applied{std::move(outcome), current_policy(), param.sched_priority};
  });
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Another test process (ctest -j) may hold the deadline bandwidth for a moment (see the
// admission control test below): an EBUSY refusal is retried for up to a second.
Applied apply_in_fresh_thread(const SchedulingRequest& r, bool pin_to_cpu0 = false) {
  for (int attempt = 1;; ++attempt) {
    Applied applied = apply_once_in_fresh_thread(r, pin_to_cpu0);
    const std::string& said =
        applied.outcome.ok() ? applied.outcome->fallback_reason : applied.outcome.error().message;
    if (!contains(said, "EBUSY") || attempt == 100) return applied;
    std::this_thread::sleep_for(milliseconds(10));
  }
}

bool deadline_possible(const SchedulingPrivileges& privileges) {
  return privileges.cap_sys_nice && privileges.affinity_spans_online_cpus;
}

TEST(RealtimeSchedulingNames, RoundTripAndUnknownNamesListTheValidOnes) {
  for (const PolicyRequest r : {PolicyRequest::kAuto, PolicyRequest::kDeadline,
                                PolicyRequest::kFifo, PolicyRequest::kOther}) {
    const Result<PolicyRequest> parsed = parse_policy_request(request_name(r));
    ASSERT_TRUE(parsed.ok()) << request_name(r);
    EXPECT_EQ(*parsed, r);
  }
  EXPECT_EQ(policy_name(SchedPolicy::kDeadline), "deadline");
  EXPECT_EQ(kernel_policy_name(SchedPolicy::kFifo), "SCHED_FIFO");
  const Result<PolicyRequest> unknown = parse_policy_request("rr");
  ASSERT_FALSE(unknown.ok());
  EXPECT_EQ(unknown.error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(unknown.error().message, "auto, deadline, fifo, other"))
      << unknown.error().message;
}

// GIVEN a request with one bad field WHEN validated or applied THEN it is refused, the message
// names the field, and the thread's policy is left alone.
struct BadRequest {
  const char* what;
  SchedulingRequest request;
  const char* field;
};

std::vector<BadRequest> bad_requests() {
  std::vector<BadRequest> cases;
  SchedulingRequest r = request(PolicyRequest::kAuto);
  r.runtime = milliseconds(0);
  cases.push_back({"zero runtime", r, "scheduling.runtime must be > 0"});
  r = request(PolicyRequest::kDeadline);
  r.deadline = milliseconds(0);
  cases.push_back({"zero deadline", r, "scheduling.deadline must be > 0"});
  r = request(PolicyRequest::kAuto);
  r.period = milliseconds(0);
  cases.push_back({"zero period", r, "scheduling.period must be > 0"});
  r = request(PolicyRequest::kAuto);
  r.runtime = milliseconds(3);
  r.deadline = milliseconds(2);
  cases.push_back({"runtime > deadline", r,
                   "scheduling.runtime (3000000 ns) must be <= "
                   "scheduling.deadline (2000000 ns)"});
  r = request(PolicyRequest::kAuto);
  r.deadline = milliseconds(20);
  cases.push_back({"deadline > period", r,
                   "scheduling.deadline (20000000 ns) must be <= "
                   "scheduling.period (10000000 ns)"});
  r = request(PolicyRequest::kAuto);
  r.runtime = microseconds(100);
  r.deadline = microseconds(500);
  r.period = microseconds(500);
  cases.push_back({"period < 1 ms", r, "scheduling.period must be >= 1 ms"});
  r = request(PolicyRequest::kAuto);
  r.runtime = std::chrono::nanoseconds(1000);
  cases.push_back({"runtime below the kernel's minimum", r, "scheduling.runtime must be >= 1024"});
  r = request(PolicyRequest::kFifo);
  r.fifo_priority = 0;
  cases.push_back({"fifo priority 0", r, "scheduling.fifo_priority must be in [1, 99] (got 0)"});
  r = request(PolicyRequest::kAuto);
  r.fifo_priority = 100;
  cases.push_back({"fifo priority 100", r, "scheduling.fifo_priority"});
  r = request(PolicyRequest::kOther);
  r.cpu = -2;
  cases.push_back({"cpu -2", r, "scheduling.cpu must be -1 (any) or in [0, "});
  r = request(PolicyRequest::kDeadline);
  r.cpu = 0;
  cases.push_back({"deadline pinned", r, "scheduling.cpu pins the thread to CPU 0"});
  return cases;
}

TEST(RealtimeScheduling, BadRequestsAreRefusedNamingTheField) {
  for (const BadRequest& bad : bad_requests()) {
    const Status valid = validate(bad.request);
    ASSERT_FALSE(valid.ok()) << bad.what;
    EXPECT_EQ(valid.error().code, ErrorCode::kInvalidArgument) << bad.what;
    EXPECT_TRUE(contains(valid.error().message, bad.field))
        << bad.what << ": " << valid.error().message;

    const Applied applied = apply_in_fresh_thread(bad.request);
    ASSERT_FALSE(applied.outcome.ok()) << bad.what;
    EXPECT_EQ(applied.outcome.error().message, valid.error().message);
    EXPECT_EQ(applied.policy_after, SchedPolicy::kOther) << bad.what << ": policy changed";
  }
}

TEST(RealtimeScheduling, FieldsAPolicyDoesNotUseAreNotValidated) {
  SchedulingRequest fifo = request(PolicyRequest::kFifo);
  fifo.runtime = milliseconds(0);  // a deadline field: irrelevant to SCHED_FIFO
  EXPECT_TRUE(validate(fifo).ok());
  SchedulingRequest other = request(PolicyRequest::kOther);
  other.period = milliseconds(0);
  other.fifo_priority = 0;
  EXPECT_TRUE(validate(other).ok());
}

TEST(RealtimeScheduling, AutoGetsDeadlineWhenTheKernelAllowsItAndSaysWhyOtherwise) {
  // GIVEN the privileges of this process
  const SchedulingPrivileges privileges = scheduling_privileges();

  // WHEN a fresh thread asks for the best policy
  const Applied applied = apply_in_fresh_thread(request(PolicyRequest::kAuto));

  // THEN it gets SCHED_DEADLINE where the kernel's checks pass, else a fallback with a reason
  ASSERT_TRUE(applied.outcome.ok()) << applied.outcome.error().message;
  std::cout << "kAuto got " << policy_name(applied.outcome->policy) << "; fallback_reason: '"
            << applied.outcome->fallback_reason << "'\n";
  EXPECT_EQ(applied.policy_after, applied.outcome->policy) << "current_policy() disagrees";
  if (geteuid() == 0 && deadline_possible(privileges)) {
    EXPECT_EQ(applied.outcome->policy, SchedPolicy::kDeadline);
    EXPECT_EQ(applied.outcome->fallback_reason, "");
  } else {
    EXPECT_NE(applied.outcome->policy, SchedPolicy::kDeadline);
    EXPECT_TRUE(contains(applied.outcome->fallback_reason, "SCHED_DEADLINE refused: E"))
        << applied.outcome->fallback_reason;
  }
}

TEST(RealtimeScheduling, ExplicitFifoGetsFifoAtTheRequestedPriority) {
  const SchedulingPrivileges privileges = scheduling_privileges();
  SchedulingRequest fifo = request(PolicyRequest::kFifo);
  fifo.fifo_priority = 42;

  const Applied applied = apply_in_fresh_thread(fifo);

  if (privileges.cap_sys_nice || privileges.rlimit_rtprio >= 42) {
    ASSERT_TRUE(applied.outcome.ok()) << applied.outcome.error().message;
    EXPECT_EQ(applied.outcome->policy, SchedPolicy::kFifo);
    EXPECT_EQ(applied.outcome->fallback_reason, "");
    EXPECT_EQ(applied.policy_after, SchedPolicy::kFifo);
    EXPECT_EQ(applied.fifo_priority_after, 42);
  } else {
    ASSERT_FALSE(applied.outcome.ok());
    EXPECT_TRUE(contains(applied.outcome.error().message, "SCHED_FIFO refused: EPERM"));
  }
}

TEST(RealtimeScheduling, ExplicitOtherAlwaysWorks) {
  const Applied applied = apply_in_fresh_thread(request(PolicyRequest::kOther));
  ASSERT_TRUE(applied.outcome.ok()) << applied.outcome.error().message;
  EXPECT_EQ(applied.outcome->policy, SchedPolicy::kOther);
  EXPECT_EQ(applied.outcome->fallback_reason, "");
  EXPECT_EQ(applied.policy_after, SchedPolicy::kOther);
}

TEST(RealtimeScheduling, ExplicitDeadlineCanBeLeftForOther) {
  const SchedulingPrivileges privileges = scheduling_privileges();
  if (!deadline_possible(privileges)) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  const auto policies = in_fresh_thread([] {
    Result<SchedulingOutcome> deadline = apply_scheduling(request(PolicyRequest::kDeadline));
    for (int attempt = 1; attempt < 100 && !deadline.ok() &&
                          contains(deadline.error().message, "EBUSY");  // see above
         ++attempt) {
      std::this_thread::sleep_for(milliseconds(10));
      deadline = apply_scheduling(request(PolicyRequest::kDeadline));
    }
    const SchedPolicy during = current_policy();
    const Result<SchedulingOutcome> other = apply_scheduling(request(PolicyRequest::kOther));
    return std::make_tuple(deadline.ok(), during, other.ok(), current_policy());
  });
  EXPECT_TRUE(std::get<0>(policies));
  EXPECT_EQ(std::get<1>(policies), SchedPolicy::kDeadline);
  EXPECT_TRUE(std::get<2>(policies));
  EXPECT_EQ(std::get<3>(policies), SchedPolicy::kOther);
}

// SCHED_DEADLINE admission needs the thread allowed on its whole root domain.
TEST(RealtimeScheduling, PinnedThreadFallsBackToFifoAndBlamesTheAffinity) {
  const SchedulingPrivileges privileges = scheduling_privileges();
  if (!deadline_possible(privileges)) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  if (privileges.online_cpus == "0") GTEST_SKIP() << "one CPU: pinning to it restricts nothing";

  // GIVEN a thread pinned to CPU 0 WHEN it asks for the best policy
  const Applied applied = apply_in_fresh_thread(request(PolicyRequest::kAuto), true);

  // THEN SCHED_DEADLINE is refused for the affinity and SCHED_FIFO is granted
  ASSERT_TRUE(applied.outcome.ok()) << applied.outcome.error().message;
  std::cout << "pinned kAuto: " << applied.outcome->fallback_reason << "\n";
  EXPECT_EQ(applied.outcome->policy, SchedPolicy::kFifo);
  EXPECT_EQ(applied.policy_after, SchedPolicy::kFifo);
  EXPECT_TRUE(contains(applied.outcome->fallback_reason, "SCHED_DEADLINE refused: EPERM"))
      << applied.outcome->fallback_reason;
  EXPECT_TRUE(contains(applied.outcome->fallback_reason, "affinity (CPUs 0)"))
      << applied.outcome->fallback_reason;
  EXPECT_FALSE(contains(applied.outcome->fallback_reason, "SCHED_FIFO refused"));
}

TEST(RealtimeScheduling, PinnedThreadAskingExplicitlyForDeadlineIsRefusedWithTheReason) {
  const SchedulingPrivileges privileges = scheduling_privileges();
  if (!deadline_possible(privileges)) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  if (privileges.online_cpus == "0") GTEST_SKIP() << "one CPU: pinning to it restricts nothing";

  const Applied applied = apply_in_fresh_thread(request(PolicyRequest::kDeadline), true);

  ASSERT_FALSE(applied.outcome.ok());
  EXPECT_EQ(applied.outcome.error().code, ErrorCode::kIo);
  EXPECT_TRUE(contains(applied.outcome.error().message, "SCHED_DEADLINE refused: EPERM"));
  EXPECT_TRUE(contains(applied.outcome.error().message, "affinity"));
  EXPECT_EQ(applied.policy_after, SchedPolicy::kOther) << "a refused request changes nothing";
}

TEST(RealtimeScheduling, ACpuRequestPinsTheThreadAndAutoStartsAtFifo) {
  // GIVEN a request pinned to the last online CPU
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  ASSERT_GE(cpus, 1);
  SchedulingRequest pinned = request(PolicyRequest::kAuto);
  pinned.cpu = static_cast<int>(cpus - 1);
  // WHEN a fresh thread applies it
  const auto [outcome, affinity] = in_fresh_thread([&] {
    Result<SchedulingOutcome> applied = apply_scheduling(pinned);
    cpu_set_t set;
    CPU_ZERO(&set);
    EXPECT_EQ(sched_getaffinity(0, sizeof set, &set), 0);
    return std::pair{std::move(applied), set};
  });
  // THEN it runs on that CPU alone, and SCHED_DEADLINE was not tried, saying so
  ASSERT_TRUE(outcome.ok()) << outcome.error().message;
  EXPECT_EQ(CPU_COUNT(&affinity), 1);
  EXPECT_TRUE(CPU_ISSET(static_cast<std::size_t>(pinned.cpu), &affinity));
  EXPECT_NE(outcome->policy, SchedPolicy::kDeadline);
  EXPECT_TRUE(contains(outcome->fallback_reason, "SCHED_DEADLINE not tried: the thread is pinned"))
      << outcome->fallback_reason;

  // AND a CPU that is not online is refused, naming it
  SchedulingRequest absent = request(PolicyRequest::kOther);
  absent.cpu = CPU_SETSIZE - 1;
  const Applied refused = apply_in_fresh_thread(absent);
  ASSERT_FALSE(refused.outcome.ok());
  EXPECT_TRUE(contains(refused.outcome.error().message, "pinning to CPU 1023 refused: EINVAL"))
      << refused.outcome.error().message;
}

// Deadline admission control: full-CPU reservations are granted until the root domain's
// bandwidth (sched_rt_runtime_us / sched_rt_period_us of every CPU) is used up.
TEST(RealtimeScheduling, AdmissionControlRefusalIsExplainedAsBandwidth) {
  const SchedulingPrivileges privileges = scheduling_privileges();
  if (!deadline_possible(privileges)) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  SchedulingRequest full_cpu = request(PolicyRequest::kDeadline);
  full_cpu.runtime = milliseconds(10);  // 100 % of a CPU; the holders sleep, so it costs nothing

  // GIVEN threads that each hold a full-CPU reservation while they wait
  const auto cpus = static_cast<std::size_t>(sysconf(_SC_NPROCESSORS_ONLN));
  std::counting_semaphore<> release(0);
  std::vector<std::thread> holders;
  std::optional<Error> refusal;
  for (std::size_t i = 0; i <= cpus && !refusal; ++i) {
    std::binary_semaphore applied(0);
    bool granted = false;
    std::string message;
    holders.emplace_back([&] {
      const Result<SchedulingOutcome> outcome = apply_scheduling(full_cpu);
      const bool holds = outcome.ok();  // `granted` is gone once `applied` is released
      granted = holds;
      if (!holds) message = outcome.error().message;
      applied.release();
      if (holds) release.acquire();  // keep the reservation until every holder is started
    });
    applied.acquire();
    if (!granted) refusal = Error{ErrorCode::kIo, message};
  }
  release.release(static_cast<std::ptrdiff_t>(holders.size()));
  for (std::thread& holder : holders) holder.join();

  // THEN one more than the machine can hold was refused, with EBUSY and the bandwidth named
  ASSERT_TRUE(refusal.has_value()) << cpus + 1 << " full-CPU reservations were all granted";
  std::cout << refusal->message << "\n";
  EXPECT_TRUE(contains(refusal->message,
                       "SCHED_DEADLINE refused: EBUSY (deadline admission "
                       "control"))
      << refusal->message;
  EXPECT_TRUE(contains(refusal->message, "100.0%")) << refusal->message;
}

// ---- The fallback chain without CAP_SYS_NICE -------------------------------------------------
// The test runs the probe program (tests/platform/probe) under setpriv as user nobody with no
// capabilities and RLIMIT_RTPRIO 0; it prints what apply_scheduling got.

constexpr const char* kProbe = GRIP_BINARY_DIR "/bin/grip_scheduling_probe";
constexpr const char* kSetpriv = "/usr/bin/setpriv";

struct ChildRun {
  int exit_status;
  std::string output;
};

// fork + execv with stdout and stderr captured and RLIMIT_RTPRIO 0, so that only missing
// capabilities and no rlimit could grant SCHED_FIFO.
ChildRun run_child(const std::vector<std::string>& arguments, const std::string& extra_env) {
  std::vector<char*> argv;
  for (const std::string& argument : arguments) argv.push_back(const_cast<char*>(argument.c_str()));
  argv.push_back(nullptr);
  std::vector<char*> envp;
  for (char** variable = environ; *variable != nullptr; ++variable) {
    if (std::strncmp(*variable, "GTEST_", 6) != 0) envp.push_back(*variable);
  }
  std::string env_entry = extra_env;
  envp.push_back(env_entry.data());
  envp.push_back(nullptr);

  std::array<int, 2> pipe_fds{};
  if (pipe(pipe_fds.data()) != 0) return {-1, std::string("pipe: ") + std::strerror(errno)};
  const pid_t child = fork();
  if (child == 0) {
    // Async-signal-safe calls only until exec.
    const rlimit no_rt{0, 0};
    setrlimit(RLIMIT_RTPRIO, &no_rt);
    dup2(pipe_fds[1], STDOUT_FILENO);
    dup2(pipe_fds[1], STDERR_FILENO);
    close(pipe_fds[0]);
    close(pipe_fds[1]);
    execve(argv[0], argv.data(), envp.data());
    _exit(127);
  }
  close(pipe_fds[1]);
  std::string output;
  std::array<char, 4096> chunk{};
  while (true) {
    const ssize_t got = read(pipe_fds[0], chunk.data(), chunk.size());
    if (got < 0 && errno == EINTR) continue;
    if (got <= 0) break;
    output.append(chunk.data(), static_cast<std::size_t>(got));
  }
  close(pipe_fds[0]);
  int status = 0;
  if (child < 0 || waitpid(child, &status, 0) != child) return {-1, output};
  return {WIFEXITED(status) ? WEXITSTATUS(status) : -1, output};
}

std::string probe_line(const std::string& output, const std::string& key) {
  const std::string marker = "GRIP_PROBE " + key + "=";
  const std::size_t at = output.find(marker);
  if (at == std::string::npos) return "<missing>";
  const std::size_t start = at + marker.size();
  return output.substr(start, output.find('\n', start) - start);
}

TEST(RealtimeScheduling, WithoutCapSysNiceAutoFallsBackToOtherAndExplainsBothRefusals) {
  if (geteuid() != 0) GTEST_SKIP() << "needs root to drop to user nobody with setpriv";
  if (access(kSetpriv, X_OK) != 0) GTEST_SKIP() << kSetpriv << " (util-linux) is not installed";
  ASSERT_EQ(access(kProbe, X_OK), 0) << kProbe << ": " << std::strerror(errno);

  // GIVEN this binary run as nobody, without CAP_SYS_NICE in any set, RLIMIT_RTPRIO 0
  const ChildRun run = run_child({kSetpriv, "--reuid=65534", "--regid=65534", "--clear-groups",
                                  "--inh-caps=-all", "--bounding-set=-sys_nice", "--", kProbe},
                                 "GRIP_PROBE=1");

  // WHEN the probe asks for the best policy THEN it gets SCHED_OTHER and both refusals explained
  ASSERT_EQ(run.exit_status, 0) << run.output;
  const std::string policy = probe_line(run.output, "policy");
  const std::string reason = probe_line(run.output, "reason");
  std::cout << "unprivileged kAuto got " << policy << "; fallback_reason: '" << reason << "'\n";
  EXPECT_EQ(policy, "other") << run.output;
  EXPECT_EQ(probe_line(run.output, "current"), "other") << run.output;
  EXPECT_TRUE(contains(reason, "SCHED_DEADLINE refused: EPERM (no CAP_SYS_NICE)")) << reason;
  EXPECT_TRUE(contains(reason,
                       "SCHED_FIFO refused: EPERM (no CAP_SYS_NICE and RLIMIT_RTPRIO 0 "
                       "< priority 80)"))
      << reason;
}

}  // namespace
}  // namespace grip::platform
