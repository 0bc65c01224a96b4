#include "privileges.hpp"

#include <linux/capability.h>
#include <sys/resource.h>
#include <sys/syscall.h>
#include <unistd.h>

#include <array>

#include "grip/platform/os_call.hpp"

namespace grip::platform::detail {

bool has_effective_capability(int capability) noexcept {
  if (capability < 0 || capability >= 64) return false;
  __user_cap_header_struct header{};
  header.version = _LINUX_CAPABILITY_VERSION_3;
  header.pid = 0;  // the calling thread
  std::array<__user_cap_data_struct, _LINUX_CAPABILITY_U32S_3> data{};
  const auto got = os_call("capget", [&] { return ::syscall(SYS_capget, &header, data.data()); });
  if (!got.ok()) return false;
  const auto word = static_cast<std::size_t>(capability / 32);
  const std::uint32_t bit = std::uint32_t{1} << static_cast<unsigned>(capability % 32);
  return (data[word].effective & bit) != 0;
}

std::optional<std::uint64_t> soft_rlimit(int resource) noexcept {
  rlimit limit{};
  const auto got = os_call(
      "getrlimit", [&] { return ::getrlimit(static_cast<__rlimit_resource_t>(resource), &limit); });
  if (!got.ok() || limit.rlim_cur == RLIM_INFINITY) return std::nullopt;
  return static_cast<std::uint64_t>(limit.rlim_cur);
}

std::string rlimit_text(std::optional<std::uint64_t> limit) {
  return limit ? std::to_string(*limit) : std::string("unlimited");
}

}  // namespace grip::platform::detail
