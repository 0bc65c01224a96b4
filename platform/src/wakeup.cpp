#include "grip/platform/wakeup.hpp"

#include <poll.h>
#include <sys/eventfd.h>
#include <unistd.h>

#include <cstdint>

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
  const auto ms = std::chrono::ceil<std::chrono::milliseconds>(timeout).count();
  if (::poll(&p, 1, static_cast<int>(ms)) <= 0) return false;  // timeout or EINTR
  std::uint64_t count = 0;
  return ::read(fd_, &count, sizeof count) == static_cast<ssize_t>(sizeof count);
}

}  // namespace grip::platform
