#pragma once
// Counts SCHED_DEADLINE runtime overruns. A deadline thread set with SCHED_FLAG_DL_OVERRUN (as
// apply_scheduling does) that exhausts its runtime makes the kernel send SIGXCPU to the whole
// process (thread-group directed). The default action of SIGXCPU kills the process, so the
// watcher blocks it and reads it from a signalfd on an ordinary SCHED_OTHER thread named
// "grip-overrun", which counts it.
//
// Start it FIRST, before any other thread exists: a process-directed signal goes to any thread
// that does not block it, and only threads created after start() inherit the blocked mask.
// start() refuses (kInvalidArgument) when another thread does not block SIGXCPU.
//
// The count is a lower bound: SIGXCPU is a standard signal, so overruns raised while one is
// still pending merge into one. SIGXCPU from RLIMIT_CPU or from kill() is counted too. A
// SIGXCPU sent to one particular thread (raise(), pthread_kill) stays pending on that thread
// and is not counted unless that thread is the watcher.

#include <cstdint>
#include <memory>

#include "grip/common/result.hpp"

namespace grip::platform {

class OverrunWatcher {
 public:
  // Blocks SIGXCPU in the calling thread (stays blocked after stop(): an unblocked SIGXCPU
  // would kill the process), checks that every other thread blocks it too, opens the signalfd
  // and starts the watcher thread. Errors: kInvalidArgument naming a thread that does not block
  // SIGXCPU; kIo when an OS call fails.
  static Result<OverrunWatcher> start();

  OverrunWatcher(OverrunWatcher&& other) noexcept;
  OverrunWatcher& operator=(OverrunWatcher&& other) noexcept;  // stops the watcher it held
  OverrunWatcher(const OverrunWatcher&) = delete;
  OverrunWatcher& operator=(const OverrunWatcher&) = delete;
  ~OverrunWatcher();  // stop()

  // Whether a watcher is running in this process. apply_scheduling asks for SIGXCPU on overruns
  // (SCHED_FLAG_DL_OVERRUN) only then: without a watcher the signal would kill the process, so
  // an overrun is left to the kernel's throttling, uncounted.
  static bool active() noexcept;

  // SIGXCPU signals counted so far (kept after stop()); 0 for a moved-from watcher.
  std::uint64_t overruns() const noexcept;

  // Counts what is already pending, ends the watcher thread and closes its descriptors.
  // Idempotent.
  void stop() noexcept;

 private:
  struct State;
  explicit OverrunWatcher(std::unique_ptr<State> state) noexcept;
  static void watch(State& state) noexcept;
  std::unique_ptr<State> state_;
};

}  // namespace grip::platform
