#pragma once
// Keeping the real-time path free of page faults: lock the process's memory, prefault the
// stack, and count the faults and context switches a thread actually took.

#include <cstddef>
#include <cstdint>
#include <string>

namespace grip::platform {

struct MemoryLockOutcome {
  bool locked = false;
  std::string reason;  // empty when locked; else the errno and its likely cause
};

// mlockall(MCL_CURRENT | MCL_FUTURE): every page mapped now and later stays resident, so the
// planning path never takes a major fault. Process-wide (every thread, every later mapping,
// including each new thread's whole stack). Start-up only: builds a message on failure, e.g.
// "ENOMEM (RLIMIT_MEMLOCK is 8388608 bytes, less than the process maps, and no CAP_IPC_LOCK)".
// Calling it again is harmless (the lock is idempotent). Under ASan/TSan, whose runtimes turn
// mlockall into a no-op, it reports locked = false with that reason.
[[nodiscard]] MemoryLockOutcome lock_process_memory();

// Asks glibc to back its large allocations with transparent huge pages (2 MiB): a
// building-sized map's per-cell arrays, hundreds of MB written at start-up, then take a fault
// per 2 MiB instead of per 4 KiB, and the whole-map passes fewer TLB misses. glibc reads its
// tunable (GLIBC_TUNABLES glibc.malloc.hugetlb=1: madvise(MADV_HUGEPAGE) on its mappings) only
// at process start, so this re-executes the process once, with the same arguments and the
// tunable added, before anything else has run: call it first thing in main(). It returns, doing
// nothing, when the tunable is already set (by a previous call, or by a user who chose a value,
// 0 included), when the kernel's transparent huge pages are "never", under a sanitizer (its
// allocator ignores the tunable), or when re-executing fails; it does not return otherwise.
void prefer_huge_pages(char** argv) noexcept;

// Touches `bytes` of the calling thread's stack below the current frame, one write per 4 KiB,
// so that the first deep call on the real-time path does not fault them in. `bytes` must stay
// well below the free stack (a thread's stack size minus what is in use): more overflows it.
void prefault_stack(std::size_t bytes) noexcept;

// What the calling thread has cost the kernel since it started (getrusage(RUSAGE_THREAD)).
// Take differences around a cycle: a real-time loop should add no major faults.
struct ThreadUsage {
  std::uint64_t minor_faults;          // page faults served without I/O
  std::uint64_t major_faults;          // page faults that needed I/O
  std::uint64_t voluntary_switches;    // the thread blocked or slept
  std::uint64_t involuntary_switches;  // the thread was preempted
};
ThreadUsage thread_usage() noexcept;

}  // namespace grip::platform
