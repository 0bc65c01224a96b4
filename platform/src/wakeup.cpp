#include "grip/platform/wakeup.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <ctime>

#include "grip/platform/os_call.hpp"

namespace grip::platform {

Result<Wakeup> Wakeup::create() {
  const auto fd = os_call("eventfd", [] { return ::eventfd(0, EFD_NONBLOCK | EFD_CLOEXEC); });
  if (!fd.ok()) return Error{ErrorCode::kIo, fd.describe()};
  return Wakeup(fd.value);
}

Wakeup::~Wakeup() {
  if (fd_ >= 0) ::close(fd_);
}

void Wakeup::signal() noexcept {
  const std::uint64_t one = 1;
  // EAGAIN means the counter is saturated: it is signalled already.
  static_cast<void>(::write(fd_, &one, sizeof one));
}

bool Wakeup::wait(std::chrono::nanoseconds timeout) noexcept {
  pollfd p{fd_, POLLIN, 0};
  // ppoll, not poll: a timeout to the nanosecond (a waiter due shortly before an event must not
  // sleep a millisecond past it).
  const std::int64_t ns = std::max<std::int64_t>(timeout.count(), 0);
  const timespec ts{static_cast<time_t>(ns / 1'000'000'000), static_cast<long>(ns % 1'000'000'000)};
  if (::ppoll(&p, 1, &ts, nullptr) <= 0) return false;  // timeout or EINTR
  std::uint64_t count = 0;
  return ::read(fd_, &count, sizeof count) == static_cast<ssize_t>(sizeof count);
}

}  // namespace grip::platform
