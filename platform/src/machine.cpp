#include "grip/platform/machine.hpp"

#include <sys/utsname.h>
#include <unistd.h>

#include <string_view>

#include "grip/platform/proc_files.hpp"

namespace grip::platform {

namespace {

// The value of the first "key<tabs>: value" line of /proc/cpuinfo.
std::string cpuinfo_field(std::string_view cpuinfo, std::string_view key) {
  std::size_t at = 0;
  while (at < cpuinfo.size()) {
    std::size_t end = cpuinfo.find('\n', at);
    if (end == std::string_view::npos) end = cpuinfo.size();
    const std::string_view line = cpuinfo.substr(at, end - at);
    const std::size_t colon = line.find(':');
    if (line.starts_with(key) && colon != std::string_view::npos &&
        line.substr(key.size(), colon - key.size()).find_first_not_of(" \t") ==
            std::string_view::npos) {
      std::string_view value = line.substr(colon + 1);
      const std::size_t first = value.find_first_not_of(" \t");
      return first == std::string_view::npos ? std::string() : std::string(value.substr(first));
    }
    at = end + 1;
  }
  return {};
}

}  // namespace

MachineDescription describe_machine() {
  MachineDescription m;
  utsname names{};
  if (uname(&names) == 0) {
    m.hostname = names.nodename;
    m.kernel = std::string(names.sysname) + " " + names.release;
    m.kernel_build = names.version;
    m.architecture = names.machine;
  }
  if (const Result<std::string> cpuinfo = detail::read_small_file("/proc/cpuinfo")) {
    m.cpu_model = cpuinfo_field(*cpuinfo, "model name");
  }
  const long cpus = sysconf(_SC_NPROCESSORS_ONLN);
  m.online_cpus = cpus > 0 ? static_cast<int>(cpus) : 0;
  return m;
}

}  // namespace grip::platform
