#pragma once
// Monotonic time for the real-time path: never the wall clock (it jumps), never relative
// sleeps (they drift by the time spent between reading the clock and sleeping).

#include <cstdint>

namespace grip::platform {

// Nanoseconds since the CLOCK_MONOTONIC epoch (boot, not counting suspend). int64 lasts 292
// years.
using TimePoint = std::int64_t;

// CLOCK_MONOTONIC now, in ns. Lock-free (vDSO), no allocation.
TimePoint now_ns() noexcept;

// Sleeps until CLOCK_MONOTONIC reaches `deadline_ns` (clock_nanosleep with TIMER_ABSTIME),
// resuming after signals (EINTR), so it never returns early. A deadline in the past returns at
// once. The usual loop: `next += period; sleep_until_ns(next);`.
void sleep_until_ns(TimePoint deadline_ns) noexcept;

}  // namespace grip::platform
