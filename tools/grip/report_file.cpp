#include "report_file.hpp"

#include <iostream>

#include "build_info.hpp"
#include "grip/platform/machine.hpp"
#include "grip/tools/atomic_file.hpp"

namespace grip::tools {

nlohmann::json produced_by_json() {
  const platform::MachineDescription m = platform::describe_machine();
  return {{"grip", {{"version", grip_version()}, {"revision", grip_revision()}}},
          {"machine",
           {{"hostname", m.hostname},
            {"kernel", m.kernel},
            {"kernel_build", m.kernel_build},
            {"architecture", m.architecture},
            {"cpu_model", m.cpu_model},
            {"online_cpus", m.online_cpus}}}};
}

bool write_report(std::string_view command, const std::string& path, nlohmann::json report,
                  int indent) {
  if (report.is_object()) report["produced_by"] = produced_by_json();
  // Whole or not at all: a crash mid-write never leaves half a JSON (atomic_file.hpp).
  if (Status s = write_file_atomically(path, report.dump(indent) + "\n"); !s) {
    std::cerr << command << ": " << s.error().message << "\n";
    return false;
  }
  return true;
}

}  // namespace grip::tools
