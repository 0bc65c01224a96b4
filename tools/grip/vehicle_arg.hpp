#pragma once
// A vehicle argument of the benchmarks (--robots): a built-in vehicle's name or a parameter file,
// and how each is passed to the `grip` child that runs it and named in tables and reports.

#include <filesystem>
#include <string>
#include <vector>

namespace grip::tools {

inline bool is_params_file(const std::string& robot) {
  return robot.ends_with(".yaml") || robot.ends_with(".yml");
}

// Its name in a table, a report's name and the JSON: a file's stem.
inline std::string vehicle_label(const std::string& robot) {
  return is_params_file(robot) ? std::filesystem::path(robot).stem().string() : robot;
}

// The options of a `grip` subcommand that select it: --params FILE or --robot NAME.
inline std::vector<std::string> vehicle_args(const std::string& robot) {
  return {is_params_file(robot) ? "--params" : "--robot", robot};
}

}  // namespace grip::tools
