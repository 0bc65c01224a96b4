#pragma once
// The thread the planner runs on: named, scheduled (SCHED_DEADLINE, else FIFO, else OTHER),
// with its memory locked and its stack prefaulted before the first line of its body runs.
//
//   auto loop = [&](const RealtimeThreadInfo& info) { /* the cycle loop */ };
//   Result<RealtimeThread> thread = RealtimeThread::start({"grip-plan", request}, loop);
//   if (!thread) return thread.error();  // says which check failed
//   log(thread->info().scheduling.fallback_reason);  // empty unless a policy was refused
//
// Everything here is start-up code (it allocates); the body is the real-time part.

#include <cstddef>
#include <functional>
#include <memory>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"
#include "grip/platform/memory.hpp"
#include "grip/platform/scheduling.hpp"

namespace grip::platform {

// A hint to the CPU inside a loop that polls for another thread's write: it eases the
// hyperthread sibling and the memory bus, and the loop notices the write as soon as it lands.
inline void cpu_relax() noexcept {
#if defined(__x86_64__) || defined(__i386__)
  __builtin_ia32_pause();
#elif defined(__aarch64__) || defined(__arm__)
  asm volatile("yield");
#endif
}

// Names the calling thread (pthread_setname_np): what top -H, ps -L, gdb and
// /proc/<pid>/task/<tid>/comm show. 1 to 15 characters (the kernel's TASK_COMM_LEN is 16 with
// the terminating NUL); a longer or empty name is refused with kInvalidArgument, not truncated.
Status set_thread_name(std::string_view name);

struct RealtimeThreadConfig {
  std::string name;  // 1 to 15 characters, e.g. "grip-plan"
  SchedulingRequest scheduling;
  // mlockall(MCL_CURRENT | MCL_FUTURE) on the creating thread before the thread is created
  // (process-wide, idempotent; see memory.hpp). Its outcome is reported, a failure is not fatal.
  bool lock_memory = true;
  // Stack touched in the new thread before the body runs. Must leave 64 KiB of the stack free.
  std::size_t stack_prefault_bytes = std::size_t{512} * 1024;
  // The pthread stack size; at least PTHREAD_STACK_MIN and the prefault plus 64 KiB.
  std::size_t stack_size_bytes = std::size_t{8} * 1024 * 1024;
};

// What the thread got; handed to the body and kept for info().
struct RealtimeThreadInfo {
  SchedulingOutcome scheduling;
  MemoryLockOutcome memory;  // reason "not requested" when lock_memory was false
};

// Owns one started thread; joins it in the destructor. Movable, not copyable.
class RealtimeThread {
 public:
  using Body = std::function<void(const RealtimeThreadInfo&)>;

  // Validates `config`, locks memory if asked, creates the thread and waits until, inside it,
  // the name is set, the stack prefaulted (before the policy, so that the faults do not spend a
  // deadline runtime) and the scheduling applied; the body runs after that, concurrently with
  // start()'s return. Errors: kInvalidArgument for a bad
  // name, request, stack size or an empty body; kIo when pthread refuses to create the thread
  // (e.g. EAGAIN because the caller runs under SCHED_DEADLINE) or when the scheduling request
  // is refused (an explicit policy the kernel does not grant; the thread then exits without
  // running the body). The body must not throw (std::terminate).
  static Result<RealtimeThread> start(const RealtimeThreadConfig& config, Body body);

  RealtimeThread(RealtimeThread&& other) noexcept;
  RealtimeThread& operator=(RealtimeThread&& other) noexcept;  // joins the thread it held
  RealtimeThread(const RealtimeThread&) = delete;
  RealtimeThread& operator=(const RealtimeThread&) = delete;
  ~RealtimeThread();  // joins if joinable

  bool joinable() const noexcept;
  // Waits for the body to return. Does nothing if not joinable; panics if called from the
  // thread itself.
  void join() noexcept;
  // Valid for the object's lifetime, also after join(). Panics on a moved-from object.
  const RealtimeThreadInfo& info() const noexcept;

 private:
  struct State;
  explicit RealtimeThread(std::unique_ptr<State> state) noexcept;
  static void* run(void* argument) noexcept;  // the pthread entry point
  std::unique_ptr<State> state_;
};

}  // namespace grip::platform
