#include "grip/platform/thread.hpp"

#include <gtest/gtest.h>
#include <pthread.h>
#include <sched.h>
#include <sys/mman.h>
#include <unistd.h>

#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstring>
#include <fstream>
#include <optional>
#include <string>
#include <thread>
#include <type_traits>
#include <utility>

namespace grip::platform {
namespace {

using std::chrono::milliseconds;

static_assert(!std::is_copy_constructible_v<RealtimeThread>);
static_assert(std::is_nothrow_move_constructible_v<RealtimeThread>);
static_assert(std::is_nothrow_move_assignable_v<RealtimeThread>);

std::string pthread_name() {
  std::array<char, 16> name{};
  pthread_getname_np(pthread_self(), name.data(), name.size());
  return name.data();
}

std::string proc_comm() {
  std::ifstream comm("/proc/self/task/" + std::to_string(gettid()) + "/comm");
  std::string name;
  std::getline(comm, name);
  return name;
}

bool deadline_possible() {
  const SchedulingPrivileges privileges = scheduling_privileges();
  return geteuid() == 0 && privileges.cap_sys_nice && privileges.affinity_spans_online_cpus;
}

// A configuration that is cheap to start in tests: no process-wide memory lock.
RealtimeThreadConfig config(PolicyRequest policy) {
  RealtimeThreadConfig c;
  c.name = "grip-test-rt";
  c.scheduling.request = policy;
  c.scheduling.runtime = milliseconds(2);
  c.scheduling.deadline = milliseconds(10);
  c.scheduling.period = milliseconds(10);
  c.lock_memory = false;
  return c;
}

bool contains(const std::string& text, const std::string& part) {
  return text.find(part) != std::string::npos;
}

// Another test process (ctest -j) may hold the deadline bandwidth for a moment (the admission
// control test in realtime_scheduling_test.cpp): a start that met EBUSY is retried for a second.
template <typename Body>
Result<RealtimeThread> start_when_bandwidth_free(const RealtimeThreadConfig& c, Body body) {
  for (int attempt = 1;; ++attempt) {
    Result<RealtimeThread> thread = RealtimeThread::start(c, body);
    const std::string& said =
        thread.ok() ? thread->info().scheduling.fallback_reason : thread.error().message;
    if (said.find("EBUSY") == std::string::npos || attempt == 100) return thread;
    if (thread.ok()) thread->join();
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
  }
}

TEST(RealtimeThreadName, FifteenCharactersAreAcceptedAndSixteenRefused) {
  std::optional<Status> fifteen;
  std::optional<Status> sixteen;
  std::optional<Status> empty;
  std::string seen;
  std::thread thread([&] {
    fifteen.emplace(set_thread_name("abcdefghijklmno"));
    sixteen.emplace(set_thread_name("abcdefghijklmnop"));
    empty.emplace(set_thread_name(""));
    seen = pthread_name();
  });
  thread.join();
  EXPECT_TRUE(fifteen->ok());
  ASSERT_FALSE(sixteen->ok());
  EXPECT_EQ(sixteen->error().code, ErrorCode::kInvalidArgument);
  EXPECT_TRUE(contains(sixteen->error().message, "1 to 15 characters (got 16)"))
      << sixteen->error().message;
  EXPECT_FALSE(empty->ok());
  EXPECT_EQ(seen, "abcdefghijklmno") << "a refused name must not truncate or replace the last";
}

TEST(RealtimeThread, BodySeesItsNameInPthreadAndProc) {
  std::string from_pthread;
  std::string from_proc;
  const std::string creator_name = pthread_name();
  Result<RealtimeThread> thread =
      RealtimeThread::start(config(PolicyRequest::kOther), [&](const RealtimeThreadInfo&) {
        from_pthread = pthread_name();
        from_proc = proc_comm();
      });
  ASSERT_TRUE(thread.ok()) << thread.error().message;
  thread->join();
  EXPECT_EQ(from_pthread, "grip-test-rt");
  EXPECT_EQ(from_proc, "grip-test-rt");
  EXPECT_EQ(pthread_name(), creator_name) << "the creator keeps its own name";
}

TEST(RealtimeThread, BodyRunsUnderThePolicyInfoReports) {
  // GIVEN a thread asking for the best policy
  SchedPolicy in_body = SchedPolicy::kOther;
  std::string reason_in_body;
  Result<RealtimeThread> thread =
      start_when_bandwidth_free(config(PolicyRequest::kAuto), [&](const RealtimeThreadInfo& info) {
        in_body = current_policy();
        reason_in_body = info.scheduling.fallback_reason;
      });
  ASSERT_TRUE(thread.ok()) << thread.error().message;
  // WHEN start() has returned THEN the policy is already applied and reported
  const RealtimeThreadInfo& info = thread->info();
  thread->join();

  // THEN the body ran under it; here, as root with every CPU allowed, that is SCHED_DEADLINE
  EXPECT_EQ(in_body, info.scheduling.policy);
  EXPECT_EQ(reason_in_body, info.scheduling.fallback_reason);
  EXPECT_FALSE(info.memory.locked);
  EXPECT_EQ(info.memory.reason, "not requested");
  if (deadline_possible()) {
    EXPECT_EQ(info.scheduling.policy, SchedPolicy::kDeadline) << info.scheduling.fallback_reason;
  } else {
    EXPECT_FALSE(info.scheduling.fallback_reason.empty());
  }
  EXPECT_EQ(current_policy(), SchedPolicy::kOther) << "the creating thread is untouched";
}

TEST(RealtimeThread, ExplicitFifoAtItsPriority) {
  int priority_in_body = -1;
  RealtimeThreadConfig c = config(PolicyRequest::kFifo);
  c.scheduling.fifo_priority = 30;
  Result<RealtimeThread> thread = RealtimeThread::start(c, [&](const RealtimeThreadInfo&) {
    sched_param param{};
    sched_getparam(0, &param);
    priority_in_body = param.sched_priority;
  });
  if (!scheduling_privileges().cap_sys_nice) {
    ASSERT_FALSE(thread.ok());
    return;
  }
  ASSERT_TRUE(thread.ok()) << thread.error().message;
  thread->join();
  EXPECT_EQ(thread->info().scheduling.policy, SchedPolicy::kFifo);
  EXPECT_EQ(priority_in_body, 30);
}

TEST(RealtimeThread, LockMemoryIsReportedToTheBody) {
  RealtimeThreadConfig c = config(PolicyRequest::kOther);
  c.lock_memory = true;
  bool locked_in_body = false;
  Result<RealtimeThread> thread = RealtimeThread::start(
      c, [&](const RealtimeThreadInfo& info) { locked_in_body = info.memory.locked; });
  ASSERT_TRUE(thread.ok()) << thread.error().message;
  thread->join();
  EXPECT_EQ(locked_in_body, thread->info().memory.locked);
#if !defined(__SANITIZE_ADDRESS__) && !defined(__SANITIZE_THREAD__)  // mlockall is a no-op there
  if (geteuid() == 0) {
    EXPECT_TRUE(thread->info().memory.locked) << thread->info().memory.reason;
  }
#endif
  munlockall();  // leave the other tests an unlocked process
}

TEST(RealtimeThread, BadConfigurationsAreRefusedBeforeAnyThreadStarts) {
  const auto body = [](const RealtimeThreadInfo&) { ADD_FAILURE() << "body must not run"; };
  RealtimeThreadConfig long_name = config(PolicyRequest::kOther);
  long_name.name = "grip-planner-thread";
  RealtimeThreadConfig bad_request = config(PolicyRequest::kAuto);
  bad_request.scheduling.runtime = milliseconds(20);
  RealtimeThreadConfig prefault_too_big = config(PolicyRequest::kOther);
  prefault_too_big.stack_size_bytes = 256 * 1024;
  prefault_too_big.stack_prefault_bytes = 256 * 1024;
  RealtimeThreadConfig tiny_stack = config(PolicyRequest::kOther);
  tiny_stack.stack_size_bytes = 1024;
  tiny_stack.stack_prefault_bytes = 0;

  const std::array<std::pair<const RealtimeThreadConfig*, const char*>, 4> cases{{
      {&long_name, "thread name 'grip-planner-thread' must have 1 to 15 characters"},
      {&bad_request, "scheduling.runtime (20000000 ns) must be <= scheduling.deadline"},
      {&prefault_too_big, "stack_prefault_bytes (262144) must leave 64 KiB"},
      {&tiny_stack, "must leave 64 KiB"},
  }};
  for (const auto& [bad, message] : cases) {
    const Result<RealtimeThread> thread = RealtimeThread::start(*bad, body);
    ASSERT_FALSE(thread.ok()) << message;
    EXPECT_EQ(thread.error().code, ErrorCode::kInvalidArgument);
    EXPECT_TRUE(contains(thread.error().message, message)) << thread.error().message;
  }
  const Result<RealtimeThread> no_body =
      RealtimeThread::start(config(PolicyRequest::kOther), RealtimeThread::Body{});
  ASSERT_FALSE(no_body.ok());
  EXPECT_TRUE(contains(no_body.error().message, "empty body"));
}

// The new thread inherits the creator's CPU affinity, and SCHED_DEADLINE needs every CPU.
TEST(RealtimeThread, RefusedExplicitPolicyFailsStartAndSkipsTheBody) {
  if (!deadline_possible()) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  if (sysconf(_SC_NPROCESSORS_ONLN) < 2) GTEST_SKIP() << "one CPU: pinning restricts nothing";
  std::atomic<bool> body_ran{false};
  std::optional<Result<RealtimeThread>> started;
  std::thread creator([&] {
    cpu_set_t cpu0;
    CPU_ZERO(&cpu0);
    CPU_SET(0, &cpu0);
    ASSERT_EQ(sched_setaffinity(0, sizeof(cpu0), &cpu0), 0) << std::strerror(errno);
    started.emplace(RealtimeThread::start(config(PolicyRequest::kDeadline),
                                          [&](const RealtimeThreadInfo&) { body_ran = true; }));
  });
  creator.join();
  ASSERT_TRUE(started.has_value());
  ASSERT_FALSE(started->ok());
  EXPECT_EQ(started->error().code, ErrorCode::kIo);
  EXPECT_TRUE(
      contains(started->error().message, "thread 'grip-test-rt': SCHED_DEADLINE refused: EPERM"))
      << started->error().message;
  EXPECT_TRUE(contains(started->error().message, "affinity")) << started->error().message;
  EXPECT_FALSE(body_ran.load());
}

// What the lead must design around: a SCHED_DEADLINE thread cannot create threads.
TEST(RealtimeThread, ADeadlineThreadCannotStartAnotherThread) {
  if (!deadline_possible()) GTEST_SKIP() << "SCHED_DEADLINE not available here";
  std::optional<Error> refusal;
  bool started_inner = true;
  Result<RealtimeThread> outer =
      start_when_bandwidth_free(config(PolicyRequest::kDeadline), [&](const RealtimeThreadInfo&) {
        RealtimeThreadConfig inner = config(PolicyRequest::kOther);
        inner.name = "grip-inner";
        Result<RealtimeThread> started =
            RealtimeThread::start(inner, [](const RealtimeThreadInfo&) {});
        started_inner = started.ok();
        if (!started.ok()) refusal = started.error();
      });
  ASSERT_TRUE(outer.ok()) << outer.error().message;
  outer->join();
  EXPECT_FALSE(started_inner);
  ASSERT_TRUE(refusal.has_value());
  EXPECT_EQ(refusal->code, ErrorCode::kIo);
  EXPECT_TRUE(contains(refusal->message, "pthread_create: EAGAIN")) << refusal->message;
  EXPECT_TRUE(contains(refusal->message, "runs under SCHED_DEADLINE")) << refusal->message;
}

TEST(RealtimeThread, MovingTransfersOwnershipAndTheDestructorJoins) {
  std::atomic<bool> release{false};
  std::atomic<bool> finished{false};
  {
    Result<RealtimeThread> started =
        RealtimeThread::start(config(PolicyRequest::kOther), [&](const RealtimeThreadInfo&) {
          while (!release.load()) std::this_thread::sleep_for(milliseconds(1));
          finished = true;
        });
    ASSERT_TRUE(started.ok()) << started.error().message;
    RealtimeThread moved = std::move(started).value();
    EXPECT_TRUE(moved.joinable());
    RealtimeThread assigned = std::move(moved);
    EXPECT_FALSE(moved.joinable());  // NOLINT(bugprone-use-after-move): checking the moved-from
    EXPECT_TRUE(assigned.joinable());
    EXPECT_EQ(assigned.info().scheduling.policy, SchedPolicy::kOther);
    release = true;
  }  // ~RealtimeThread joins
  EXPECT_TRUE(finished.load());
}

}  // namespace
}  // namespace grip::platform
