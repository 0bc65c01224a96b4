#pragma once
// When a run loop may tell a watchdog that planning is alive (a service manager's WATCHDOG=1):
// at most once per interval, and only when planning cycles completed since the last beat. A
// planning loop that stalls (a stuck planning thread, a lockstep vehicle that stopped sending
// states) stops the beats, and the watchdog acts. Pure: the caller passes the time.

#include <cstdint>
#include <limits>

namespace grip::rt {

class LivenessBeat {
 public:
  // interval_ns <= 0: never due.
  explicit LivenessBeat(std::int64_t interval_ns) noexcept : interval_ns_(interval_ns) {}

  // True (and the beat is taken) when `interval` has passed since the last beat and `cycles`,
  // the count of completed cycles, grew since it. The first beat needs one cycle.
  bool due(std::int64_t now_ns, std::uint64_t cycles) noexcept {
    if (interval_ns_ <= 0 || cycles <= cycles_at_beat_) return false;
    if (beaten_ && now_ns - last_beat_ns_ < interval_ns_) return false;
    beaten_ = true;
    last_beat_ns_ = now_ns;
    cycles_at_beat_ = cycles;
    return true;
  }

 private:
  std::int64_t interval_ns_;
  bool beaten_ = false;
  std::int64_t last_beat_ns_ = std::numeric_limits<std::int64_t>::min();
  std::uint64_t cycles_at_beat_ = 0;
};

}  // namespace grip::rt
