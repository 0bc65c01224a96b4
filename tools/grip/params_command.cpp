// `grip params`: the complete parameter set a vehicle runs with, as a parameter file: the
// built-in vehicle's (--robot) or a file's (--params) with every key it leaves out at its
// default, as every command that plans or simulates takes them (params_options.hpp; a relative
// link.dds_config comes out resolved against the file's folder). What it prints reads back to
// the same values, so it is also where a new vehicle's file starts.

#include <iostream>
#include <memory>

#include "commands.hpp"
#include "params_options.hpp"

namespace grip::tools {

void register_params_command(CLI::App& app) {
  auto o = std::make_shared<ParamsOptions>("dd-vel");
  CLI::App* cmd = app.add_subcommand(
      "params",
      "Print a vehicle's complete parameters as a parameter file (YAML): the built-in vehicle's "
      "or, with --params, a file's with every key it leaves out at its default");
  add_vehicle_options(*cmd, *o);
  cmd->callback([o]() {
    const auto p = effective_params(*o);
    if (!p) {
      std::cerr << "grip params: " << p.error().message << "\n";
      throw CLI::RuntimeError(2);
    }
    std::cout << params::to_yaml(*p);
  });
}

}  // namespace grip::tools
