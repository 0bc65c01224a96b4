#pragma once
// A small expected-style result for operations that can fail at start-up (configuration,
// scene and map loading). C++20 has no std::expected; this is the part of it we use.
// The message is built once, when an error is returned, never on the planning path.

#include <string>
#include <utility>
#include <variant>

#include "grip/common/assert.hpp"

namespace grip {

enum class ErrorCode { kInvalidArgument, kOutOfRange, kCapacity, kParse, kIo };

struct Error {
  ErrorCode code;
  std::string message;  // names what is wrong, e.g. "car.max_speed_m_s must be > 0 (got -1)"
};

template <typename T>
class [[nodiscard]] Result {
 public:
  Result(T value) : storage_(std::in_place_index<0>, std::move(value)) {}      // NOLINT
  Result(Error error) : storage_(std::in_place_index<1>, std::move(error)) {}  // NOLINT

  bool ok() const noexcept { return storage_.index() == 0; }
  explicit operator bool() const noexcept { return ok(); }

  T& value() & {
    GRIP_ASSERT(ok());
    return std::get<0>(storage_);
  }
  const T& value() const& {
    GRIP_ASSERT(ok());
    return std::get<0>(storage_);
  }
  T&& value() && {
    GRIP_ASSERT(ok());
    return std::get<0>(std::move(storage_));
  }
  const Error& error() const {
    GRIP_ASSERT(!ok());
    return std::get<1>(storage_);
  }

  T* operator->() { return &value(); }
  const T* operator->() const { return &value(); }
  T& operator*() & { return value(); }
  const T& operator*() const& { return value(); }

 private:
  std::variant<T, Error> storage_;
};

// For operations that produce nothing but can fail.
struct Ok {};
using Status = Result<Ok>;

inline Error invalid_argument(std::string message) {
  return Error{ErrorCode::kInvalidArgument, std::move(message)};
}

}  // namespace grip
