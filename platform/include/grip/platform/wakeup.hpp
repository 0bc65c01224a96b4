#pragma once
// A wake-up signal from the real-time thread to an ordinary service thread (an eventfd): the
// real-time side's signal() is one non-blocking write that never waits, never allocates and
// never fails in a way it must handle (a counter already set stays set); the service side
// sleeps in wait() until signalled or until its timeout, for periodic work.

#include <chrono>

#include "grip/common/result.hpp"

namespace grip::platform {

class Wakeup {
 public:
  static Result<Wakeup> create();
  ~Wakeup();
  Wakeup(Wakeup&& other) noexcept : fd_(other.fd_) { other.fd_ = -1; }
  Wakeup& operator=(Wakeup&&) = delete;
  Wakeup(const Wakeup&) = delete;
  Wakeup& operator=(const Wakeup&) = delete;

  // Any thread, real-time included.
  void signal() noexcept;
  // The service thread: true when signalled (the signal is consumed), false on timeout.
  bool wait(std::chrono::nanoseconds timeout) noexcept;

 private:
  explicit Wakeup(int fd) noexcept : fd_(fd) {}
  int fd_;
};

}  // namespace grip::platform
