#include "grip/platform/clock.hpp"

#include <cerrno>
#include <ctime>

#include "grip/common/assert.hpp"
#include "grip/platform/os_call.hpp"

namespace grip::platform {
namespace {
constexpr std::int64_t kNsPerSecond = 1'000'000'000;
}  // namespace

TimePoint now_ns() noexcept {
  timespec now{};
  const auto got = os_call("clock_gettime", [&] { return ::clock_gettime(CLOCK_MONOTONIC, &now); });
  GRIP_ASSERT(got.ok());  // CLOCK_MONOTONIC always exists; fails only for a bad pointer
  return static_cast<std::int64_t>(now.tv_sec) * kNsPerSecond + now.tv_nsec;
}

void sleep_until_ns(TimePoint deadline_ns) noexcept {
  if (deadline_ns < 0) deadline_ns = 0;  // the past: tv_nsec must not be negative
  timespec deadline{};
  deadline.tv_sec = static_cast<time_t>(deadline_ns / kNsPerSecond);
  deadline.tv_nsec = static_cast<long>(deadline_ns % kNsPerSecond);
  while (true) {
    // An absolute sleep restarted after EINTR still ends at the same instant.
    const auto slept = os_call_returning_error("clock_nanosleep", [&] {
      return ::clock_nanosleep(CLOCK_MONOTONIC, TIMER_ABSTIME, &deadline, nullptr);
    });
    if (slept.ok()) return;
    GRIP_ASSERT(slept.error == EINTR);  // EINVAL/EFAULT would mean a broken timespec
  }
}

}  // namespace grip::platform
