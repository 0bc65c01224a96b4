#include "report_file.hpp"

#include <fstream>
#include <iostream>

#include "build_info.hpp"
#include "grip/platform/machine.hpp"

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
  std::ofstream out(path);
  out << report.dump(indent) << "\n";
  out.close();
  if (!out) {
    std::cerr << command << ": cannot write '" << path << "'\n";
    return false;
  }
  return true;
}

}  // namespace grip::tools
