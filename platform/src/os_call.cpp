#include "grip/platform/os_call.hpp"

#include <cstring>

namespace grip::platform {

// strerrorname_np and strerrordesc_np (glibc 2.32) return static strings and, unlike
// strerror, neither allocate nor depend on the locale: usable on the real-time path.
std::string_view errno_name(int error) noexcept {
  const char* name = ::strerrorname_np(error);
  return name != nullptr ? std::string_view(name) : std::string_view("unknown errno");
}

std::string_view errno_description(int error) noexcept {
  const char* description = ::strerrordesc_np(error);
  return description != nullptr ? std::string_view(description) : std::string_view("unknown error");
}

std::string describe_errno(int error) {
  std::string text(errno_name(error));
  text += " (";
  text += errno_description(error);
  text += ")";
  return text;
}

}  // namespace grip::platform
