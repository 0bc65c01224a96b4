#pragma once
// The background load `grip stress` runs the planner under: busy CPUs, memory pressure, or both.
// stress-ng runs it when installed (and preferred); otherwise threads of our own do. The report
// must say exactly which load was used, so description() spells out what runs.
//
//   Result<OverrunWatcher> watcher = OverrunWatcher::start();          // first, see its header
//   Result<LoadGenerator> load = LoadGenerator::start(LoadKind::kCpu, {});
//   if (!load) return load.error();
//   report.load = load->description();  // "stress-ng --cpu 2 --timeout 3600s --quiet (...)"
//   ... start the planner's SCHED_DEADLINE thread, run the cycles, then:
//   load->stop();
//
// Order at start-up. Call start() from an ordinary (SCHED_OTHER) thread, AFTER
// OverrunWatcher::start() (which must precede every other thread; the load threads inherit its
// blocked SIGXCPU) and BEFORE any SCHED_DEADLINE thread: start() creates threads or a process,
// which a SCHED_DEADLINE caller cannot do (EAGAIN), and the forked child would share the
// planner's pages copy-on-write otherwise. Starting it before lock_process_memory() (which
// RealtimeThread::start calls) also keeps the built-in memory buffer out of the initial lock.
//
// Everything here is start-up code (it allocates); none of it is on the real-time path. One
// thread owns a LoadGenerator: its members are not safe to call concurrently.

#include <chrono>
#include <cstddef>
#include <memory>
#include <string>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::tools {

enum class LoadKind {
  kNone,    // nothing runs
  kCpu,     // every online CPU busy
  kMemory,  // page faults and cache misses over a large buffer
  kAll,     // kCpu and kMemory together
};

std::string_view load_name(LoadKind kind) noexcept;  // "none", "cpu", "mem", "all"

// "none" | "cpu" | "mem" | "all"; an error (kInvalidArgument) lists the valid names.
Result<LoadKind> parse_load(std::string_view name);

struct LoadOptions {
  // Safety timeout: the load stops by itself after this long even if stop() is never called
  // (stress-ng's --timeout; the built-in threads check the clock). >= 1 s.
  std::chrono::seconds max_duration{3600};
  // Use stress-ng when an executable `stress-ng` is found in PATH; otherwise, or when false,
  // the built-in threads run (and description() says why stress-ng was not used).
  bool prefer_stress_ng = true;
  // Memory the kMemory / kAll load works on: 0 means 1/8 of MemTotal, capped at 2 GiB. Else at
  // least 4096 bytes; rounded down to whole 4 KiB pages. Ignored for kNone and kCpu.
  std::size_t memory_bytes = 0;
};

// Owns a running load; stops it in the destructor. Movable, not copyable.
//
// stress-ng: started as a child process in its own process group, with stdin, stdout and
// stderr on /dev/null and PR_SET_PDEATHSIG = SIGKILL, so it dies with the thread that called
// start() (keep that thread alive while the load runs: the main thread, typically). CPU load is
// `--cpu N` (N = online CPUs); memory load `--vm 1 --vm-bytes B`, which maps, writes and unmaps
// B bytes over and over (page faults and cache misses).
//
// Built-in: kCpu runs one SCHED_OTHER thread per online CPU, named "grip-load-cpu", spinning on
// integer arithmetic; kMemory runs one thread named "grip-load-mem" that writes one byte per
// 4 KiB page of a buffer mapped by start() and, after each pass, gives the pages back
// (MADV_DONTNEED, after munlock if the process locked its memory meanwhile), so that the next
// pass faults every page in again.
class LoadGenerator {
 public:
  // Starts `kind` (kNone starts nothing and always succeeds). Errors: kInvalidArgument for a
  // max_duration below 1 s or a memory_bytes below 4096; kIo when an OS call fails (reading
  // /proc/meminfo, mapping the buffer, creating a thread, the EAGAIN of a SCHED_DEADLINE
  // caller). A stress-ng that cannot be run (exec fails) is not an error: the built-in load
  // runs instead and description() says so.
  static Result<LoadGenerator> start(LoadKind kind, const LoadOptions& options);

  LoadGenerator(LoadGenerator&& other) noexcept;
  LoadGenerator& operator=(LoadGenerator&& other) noexcept;  // stops the load it held
  LoadGenerator(const LoadGenerator&) = delete;
  LoadGenerator& operator=(const LoadGenerator&) = delete;
  ~LoadGenerator();  // stop()

  // What runs, for the report: "none"; "stress-ng --cpu 2 --timeout 3600s --quiet (stress-ng
  // 0.15.06)"; "built-in: 2 CPU hog threads, stopping after 3600 s"; a built-in load that
  // replaced a preferred stress-ng ends with why, e.g. "(stress-ng not found in PATH)".
  // Unchanged by stop(). "none" for a moved-from object.
  const std::string& description() const noexcept;
  LoadKind kind() const noexcept;        // kNone for a moved-from object
  bool uses_stress_ng() const noexcept;  // false for the built-in load and kNone
  // The stress-ng process (also its process group id) until stop() reaps it; -1 otherwise.
  int child_pid() const noexcept;

  // True until stop() or until the load ended by itself (the safety timeout, or stress-ng
  // exiting). Does not reap the child.
  bool running() const noexcept;

  // stress-ng: SIGTERM to its process group, SIGKILL to the group after 1 s (or at once when the
  // leader has already exited, for stragglers), then waitpid: no child is left behind. Built-in:
  // raises the stop flag, joins the threads and unmaps the buffer. Idempotent; blocks up to
  // about 1 s.
  void stop() noexcept;

 private:
  struct State;
  explicit LoadGenerator(std::unique_ptr<State> state) noexcept;
  std::unique_ptr<State> state_;
};

}  // namespace grip::tools
