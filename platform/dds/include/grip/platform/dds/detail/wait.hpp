#pragma once
// Implementation of wait_until_count (included from topic.hpp).

#include <chrono>
#include <cstdint>
#include <string>
#include <thread>

namespace grip::platform::dds {

template <typename GetCount>
Status wait_until_count(GetCount get_count, std::uint32_t count, std::chrono::nanoseconds timeout,
                        const char* what) {
  const auto deadline = std::chrono::steady_clock::now() + timeout;
  for (;;) {
    Result<std::uint32_t> current = get_count();
    if (!current.ok()) return current.error();
    if (current.value() >= count) return Ok{};
    if (std::chrono::steady_clock::now() >= deadline) {
      return Error{ErrorCode::kIo, std::string(what) + ": " + std::to_string(current.value()) +
                                       " of " + std::to_string(count) + " after timeout"};
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
}

}  // namespace grip::platform::dds
