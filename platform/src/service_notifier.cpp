#include "grip/platform/service_notifier.hpp"

#include <systemd/sd-daemon.h>

#include <cstdint>
#include <cstdlib>
#include <string>

#include "grip/platform/os_call.hpp"

namespace grip::platform {

ServiceNotifier ServiceNotifier::from_environment() noexcept {
  const char* socket = std::getenv("NOTIFY_SOCKET");
  const bool enabled = socket != nullptr && *socket != '\0';
  std::uint64_t usec = 0;
  // > 0: WATCHDOG_USEC is set and WATCHDOG_PID, if set, is this process.
  if (!enabled || sd_watchdog_enabled(0, &usec) <= 0) usec = 0;
  return ServiceNotifier(enabled, std::chrono::microseconds(static_cast<std::int64_t>(usec)));
}

Status ServiceNotifier::ready(std::string_view status) const {
  return notify("READY=1\nSTATUS=" + std::string(status));
}

Status ServiceNotifier::status(std::string_view status) const {
  return notify("STATUS=" + std::string(status));
}

Status ServiceNotifier::watchdog() const { return notify("WATCHDOG=1"); }

Status ServiceNotifier::stopping() const { return notify("STOPPING=1"); }

Status ServiceNotifier::notify(std::string_view message) const {
  if (!enabled_) return Ok{};
  const std::string text(message);
  // sd_notify returns a negative errno on failure, 0 when there is no socket, > 0 when sent.
  const auto r = os_call_returning_error("sd_notify", [&text] {
    const int sent = sd_notify(0, text.c_str());
    return sent < 0 ? -sent : 0;
  });
  if (!r.ok()) return Error{ErrorCode::kIo, r.describe()};
  return Ok{};
}

}  // namespace grip::platform
