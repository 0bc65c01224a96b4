// `grip bench ompl` in a build without OMPL: the command exists and says why it cannot run.

#include <iostream>

#include "commands.hpp"

namespace grip::tools {

void register_bench_ompl_command(CLI::App& bench) {
  CLI::App* cmd =
      bench.add_subcommand("ompl", "GRIP against OMPL's control planners (this build has no OMPL)");
  cmd->allow_extras();
  cmd->callback([]() {
    std::cerr << "grip bench ompl: this grip was built without OMPL (CMake found no 'ompl' "
                 "package; on Debian: apt-get install libompl-dev libboost-serialization-dev "
                 "libboost-filesystem-dev libboost-system-dev, then reconfigure)\n";
    throw CLI::RuntimeError(2);
  });
}

}  // namespace grip::tools
