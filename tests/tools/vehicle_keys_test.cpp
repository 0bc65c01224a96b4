// The keys a vehicle describes itself with (core's parameter table, vehicle_param_fields.hpp)
// are the parameter file's: `grip params` writes each model's vehicle section with exactly
// those keys, in that order, so that a refused description names a key the user can find.

#include <gtest/gtest.h>

#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "grip/vehicles/vehicle_param_fields.hpp"
#include "grip_command.hpp"

namespace {

using grip::testing::CommandRun;
using grip::testing::run_grip;

// The keys of the `vehicle:` section of a parameter file as `grip params` writes it (two spaces
// per level, a nested mapping's keys joined with '.'), "model" aside.
std::vector<std::string> vehicle_section_keys(const std::string& yaml) {
  std::vector<std::string> keys;
  std::istringstream in(yaml);
  bool inside = false;
  std::string mapping;  // the nested mapping being read, "footprint."
  for (std::string line; std::getline(in, line);) {
    if (line == "vehicle:") {
      inside = true;
      continue;
    }
    if (!inside) continue;
    if (line.empty() || line[0] != ' ') break;  // the next section
    const std::size_t indent = line.find_first_not_of(' ');
    const std::string key = line.substr(indent, line.find(':') - indent);
    const std::string rest = line.substr(line.find(':') + 1);
    const std::size_t value = rest.find_first_not_of(' ');
    const bool nested_row = value == std::string::npos || rest[value] == '#';  // no value
    if (indent == 2) mapping.clear();
    if (indent == 2 && nested_row) {
      mapping = key + ".";
    } else if (key != "model") {
      keys.push_back(indent == 2 ? key : mapping + key);
    }
  }
  return keys;
}

TEST(VehicleKeys, EachModelDescribesItselfWithTheParameterFilesKeysInTheirOrder) {
  for (const grip::VehicleKind kind :
       {grip::VehicleKind::kDdVelocity, grip::VehicleKind::kDdAcceleration,
        grip::VehicleKind::kCar}) {
    const std::string robot(grip::vehicle_name(kind));
    const CommandRun r = run_grip("params --robot " + robot);
    ASSERT_EQ(r.status, 0) << r.output;
    std::vector<std::string> described;
    const grip::VehicleParams params = grip::default_vehicle_params(kind);
    grip::for_each_param(params,
                         [&](std::string_view key, double) { described.emplace_back(key); });
    EXPECT_EQ(vehicle_section_keys(r.output), described) << robot << ":\n" << r.output;
  }
}

}  // namespace
