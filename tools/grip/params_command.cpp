// `grip params`: the complete parameter set a vehicle runs with, as a parameter file: the
// built-in vehicle's (--robot) or a file's (--params) with every key it leaves out at its
// default. What it prints reads back to the same values, so it is also where a new vehicle's
// file starts.

#include <iostream>
#include <memory>
#include <string>

#include "commands.hpp"
#include "dds_config.hpp"
#include "grip/params/params.hpp"

namespace grip::tools {

static_assert(params::kMaxDomainId == kMaxDomainId, "one end of the RTPS port mapping");

namespace {

struct ParamsOptions {
  std::string robot;  // empty: the file's model, or dd-vel
  std::string params_file;
};

Result<params::GripParams> effective_params(const ParamsOptions& o) {
  Result<VehicleKind> robot = vehicle_kind_from_name(o.robot.empty() ? "dd-vel" : o.robot);
  if (!robot) return robot.error();
  if (o.params_file.empty()) return params::default_params(*robot);
  auto loaded = params::load_params(o.params_file);
  if (!loaded) return loaded.error();
  const VehicleKind model = vehicle_kind(loaded->vehicle);
  if (!o.robot.empty() && model != *robot) {
    return invalid_argument("--robot " + o.robot + " but " + o.params_file +
                            " is for vehicle.model " + std::string(vehicle_name(model)) +
                            " (give one of the two)");
  }
  return loaded;
}

int run_params(const ParamsOptions& o) {
  const auto p = effective_params(o);
  if (!p) {
    std::cerr << "grip params: " << p.error().message << "\n";
    return 2;
  }
  std::cout << params::to_yaml(*p);
  return 0;
}

}  // namespace

void register_params_command(CLI::App& app) {
  auto o = std::make_shared<ParamsOptions>();
  CLI::App* cmd = app.add_subcommand(
      "params",
      "Print a vehicle's complete parameters as a parameter file (YAML): the built-in vehicle's "
      "or, with --params, a file's with every key it leaves out at its default");
  cmd->add_option("--robot", o->robot, "dd-vel, dd-accel or car (default: dd-vel)");
  cmd->add_option("--params", o->params_file, "A parameter file to check and complete");
  cmd->callback([o]() {
    if (const int rc = run_params(*o); rc != 0) throw CLI::RuntimeError(rc);
  });
}

}  // namespace grip::tools
