#pragma once
// The service manager's notification socket (systemd's sd_notify protocol, through libsystemd):
// readiness, a status line, the watchdog's keep-alive and shutdown. Every call is a no-op when
// the process was not started by a service manager (NOTIFY_SOCKET unset).
//
// Each call is one sendmsg: from ordinary threads only, never from the planning thread.

#include <chrono>
#include <string_view>

#include "grip/common/result.hpp"

namespace grip::platform {

class ServiceNotifier {
 public:
  // Reads NOTIFY_SOCKET, and WATCHDOG_USEC (with WATCHDOG_PID, when set, naming this process).
  static ServiceNotifier from_environment() noexcept;

  // Whether a service manager listens (NOTIFY_SOCKET is set).
  bool enabled() const noexcept { return enabled_; }
  // The manager's watchdog timeout (WatchdogSec=); zero when there is no watchdog. Keep-alives
  // go at least twice per timeout.
  std::chrono::microseconds watchdog_timeout() const noexcept { return watchdog_timeout_; }

  // READY=1 with a STATUS= line: start-up is complete.
  Status ready(std::string_view status) const;
  // STATUS=: one line that `systemctl status` shows.
  Status status(std::string_view status) const;
  // WATCHDOG=1: the service is alive.
  Status watchdog() const;
  // STOPPING=1: shutdown has begun.
  Status stopping() const;

 private:
  ServiceNotifier(bool enabled, std::chrono::microseconds watchdog_timeout) noexcept
      : enabled_(enabled), watchdog_timeout_(watchdog_timeout) {}
  Status notify(std::string_view message) const;

  bool enabled_;
  std::chrono::microseconds watchdog_timeout_;
};

}  // namespace grip::platform
