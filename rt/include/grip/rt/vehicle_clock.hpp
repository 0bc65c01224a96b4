#pragma once
// The vehicle's clock as seen from the planner's computer: vehicle_ns = scale * local_ns + offset,
// with scale the simulation's time scale (1 on a real vehicle). A state stamped S and received
// at local time L gives S - scale * L, below the true offset by the delivery latency, so the
// largest of recent values is the best estimate. One thread observes, any thread reads.

#include <algorithm>
#include <array>
#include <atomic>
#include <cstddef>
#include <cstdint>
#include <limits>

#include "grip/common/saturating_cast.hpp"

namespace grip::rt {

class VehicleClock {
 public:
  // A state stamped stamp_ns (vehicle time) received at local_ns (CLOCK_MONOTONIC).
  void observe(std::uint64_t stamp_ns, std::int64_t local_ns, double scale) noexcept {
    // Saturated: a stamp far beyond int64 (validation bounds only its order) must not overflow.
    const auto candidate = saturating_cast<std::int64_t>(static_cast<double>(stamp_ns) -
                                                         scale * static_cast<double>(local_ns));
    window_[next_++ % window_.size()] = candidate;
    filled_ = std::min<std::size_t>(filled_ + 1, window_.size());
    std::int64_t best = window_[0];
    for (std::size_t i = 1; i < filled_; ++i) best = std::max(best, window_[i]);
    offset_ns_.store(best, std::memory_order_relaxed);
  }
  // The observing thread: a new vehicle (its clock starts anew); the offset is 0 again.
  void reset() noexcept {
    next_ = 0;
    filled_ = 0;
    offset_ns_.store(0, std::memory_order_relaxed);
  }
  // The vehicle's time at local_ns; the offset is 0 until the first observe().
  std::int64_t vehicle_ns(std::int64_t local_ns, double scale) const noexcept {
    const std::int64_t scaled =
        saturating_cast<std::int64_t>(scale * static_cast<double>(local_ns));
    const std::int64_t offset = offset_ns_.load(std::memory_order_relaxed);
    std::int64_t sum = 0;
    if (__builtin_add_overflow(scaled, offset, &sum)) {
      return offset > 0 ? std::numeric_limits<std::int64_t>::max()
                        : std::numeric_limits<std::int64_t>::min();
    }
    return sum;
  }

 private:
  std::array<std::int64_t, 64> window_{};  // the observing thread's
  std::size_t next_ = 0;
  std::size_t filled_ = 0;
  std::atomic<std::int64_t> offset_ns_{0};
};

}  // namespace grip::rt
