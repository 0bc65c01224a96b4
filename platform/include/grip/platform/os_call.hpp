#pragma once
// The one checkpoint every OS call in grip_platform passes through (after iceoryx's
// IOX_POSIX_CALL): it runs the call, captures the error at once (errno, or the error number the
// pthread_* family returns), before anything else can overwrite it, and hands it back as a value
// together with the call's name. Nothing here allocates or throws, so the real-time path uses
// it too; only describe() builds a string, for start-up messages.
//
//   const auto r = os_call("mlockall", [] { return ::mlockall(MCL_CURRENT | MCL_FUTURE); });
//   if (!r.ok()) return r.describe();   // "mlockall: ENOMEM (Cannot allocate memory)"

#include <cerrno>
#include <string>
#include <string_view>
#include <type_traits>

namespace grip::platform {

// "EPERM" for EPERM; "unknown errno" for a number the C library has no name for. Static
// storage, no allocation: safe on the real-time path.
std::string_view errno_name(int error) noexcept;

// "Operation not permitted" for EPERM; "unknown error" for an unknown number. Static storage.
std::string_view errno_description(int error) noexcept;

// "EPERM (Operation not permitted)". Allocates: for start-up messages only.
std::string describe_errno(int error);

template <typename T>
struct [[nodiscard]] OsResult {
  T value;           // what the call returned
  int error;         // 0 when the call succeeded, else the errno value (EPERM, EINTR, ...)
  const char* call;  // the call's name, a string literal: "sched_setattr"

  bool ok() const noexcept { return error == 0; }
  std::string_view error_name() const noexcept { return errno_name(error); }
  // "sched_setattr: EPERM (Operation not permitted)". Allocates: for start-up messages only.
  std::string describe() const { return std::string(call) + ": " + describe_errno(error); }
};

// For calls that return -1 and set errno (system calls and most of their libc wrappers).
// errno is cleared first, so a call whose -1 is a legitimate value (getpriority) reads as ok.
template <typename Call>
auto os_call(const char* name, Call&& call) noexcept -> OsResult<std::invoke_result_t<Call&>> {
  static_assert(std::is_integral_v<std::invoke_result_t<Call&>>, "use os_call_pointer");
  errno = 0;
  const auto value = call();
  const int error = (value == -1) ? errno : 0;
  return {value, error, name};
}

// For calls that return the error number itself and leave errno alone: pthread_*,
// clock_nanosleep, posix_*. `value` repeats the returned number.
template <typename Call>
OsResult<int> os_call_returning_error(const char* name, Call&& call) noexcept {
  static_assert(std::is_same_v<std::invoke_result_t<Call&>, int>);
  const int error = call();
  return {error, error, name};
}

// For calls that return a pointer, nullptr with errno set on failure (opendir, readdir).
// errno is cleared first: readdir's end of directory (nullptr, errno untouched) is ok() with a
// null value.
template <typename Call>
auto os_call_pointer(const char* name, Call&& call) noexcept
    -> OsResult<std::invoke_result_t<Call&>> {
  static_assert(std::is_pointer_v<std::invoke_result_t<Call&>>);
  errno = 0;
  const auto value = call();
  const int error = (value == nullptr) ? errno : 0;
  return {value, error, name};
}

}  // namespace grip::platform
