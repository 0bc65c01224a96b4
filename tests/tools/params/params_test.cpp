// A vehicle's parameter file: what to_yaml writes reads back to the same values, the example
// files hold the built-in vehicles, and validate() checks a set built in code by the rules the
// reader applies (their refusals: params_refusal_test.cpp).

#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <limits>
#include <numbers>
#include <sstream>
#include <string>
#include <vector>

#include "grip/params/params.hpp"
#include "test_paths.hpp"

namespace {

using grip::CarParams;
using grip::DdAccelerationParams;
using grip::DdVelocityParams;
using grip::Footprint;
using grip::VehicleKind;
using grip::params::default_params;
using grip::params::GripParams;
using grip::params::parse_params;
using grip::params::to_yaml;

constexpr VehicleKind kKinds[] = {VehicleKind::kDdVelocity, VehicleKind::kDdAcceleration,
                                  VehicleKind::kCar};

const std::string kExamples = GRIP_SOURCE_DIR "/tools/params/examples/";

std::string file_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream text;
  text << in.rdbuf();
  return text.str();
}

// Every parameter away from its default, with values whose text needs all 17 digits.
GripParams all_changed(VehicleKind kind) {
  GripParams p = default_params(kind);
  const Footprint footprint{0.1 + 0.2, 1.0 / 3.0, std::numbers::pi / 10.0};
  switch (kind) {
    case VehicleKind::kDdVelocity:
      p.vehicle = DdVelocityParams{2.0 / 3.0, std::numbers::pi / 3.0, 0.25, footprint, 0.7};
      break;
    case VehicleKind::kDdAcceleration:
      p.vehicle =
          DdAccelerationParams{2.0 / 3.0, std::numbers::pi / 3.0, 0.45, 0.9, 0.25, footprint, 0.3};
      break;
    case VehicleKind::kCar:
      p.vehicle =
          CarParams{2.5, -1.0 / 3.0, 0.45, 0.9, std::numbers::pi / 5.0, 0.3, 0.7, footprint, 0.3};
      break;
  }
  p.planner.cycle_s = 0.1;
  p.planner.budget_s = 1.0 / 30.0;
  p.planner.margin_s = 0.001234;
  p.planner.tuning = {1.0000123456789, 0.7, 3.3, 0.25, 0.05};
  p.planner.max_edges = 12345;
  p.planner.lockstep_edges = 777;
  p.planner.max_map_cells = 1U << 20;
  p.planner.safety = false;
  p.sensor = {7.25, 360};
  p.exploration.path_weight.sensing_radius_m = 4.4;
  p.exploration.path_weight.length_weight_per_m = 1.0 / 30.0;
  p.exploration.path_weight.reference_speed_m_s = 4.0 / 3.0;
  p.exploration.path_weight.course_change_m = 0.1 + 0.2;
  p.exploration.frontier.approach_range_m = 0.61;
  p.exploration.frontier.size_weight = 0.25;
  p.exploration.frontier.size_cap_m = 3.5;
  p.exploration.frontier.min_group_cells = 3;
  p.exploration.frontier.give_up_radius_m = 1.5;
  p.exploration.give_up_s = 42.5;
  p.exploration.give_up_reached_s = 2.25;
  p.exploration.rho_margin_m = 31.5;
  p.exploration.target_refresh_cycles = 2;
  p.exploration.stuck_after_s = 123.4;
  p.link = {232, "/etc/grip/lab \"north\" \\ cyclone.xml", "robot_7", 0.25, "/etc/grip/security"};
  p.runtime = {grip::platform::PolicyRequest::kFifo, 42, 1, false};
  return p;
}

// The "key: value" lines of a parameter file, comments and mapping keys left out.
std::vector<std::string> value_lines(const std::string& yaml) {
  std::vector<std::string> lines;
  std::istringstream in(yaml);
  for (std::string line; std::getline(in, line);) {
    line = line.substr(0, line.find("  #"));
    if (line.empty() || line.front() == '#' || line.ends_with(":")) continue;
    lines.push_back(line);
  }
  return lines;
}

TEST(ParamsYaml, EachBuiltInVehicleReadsBackToItsDefaults) {
  for (const VehicleKind kind : kKinds) {
    const GripParams defaults = default_params(kind);
    const auto read = parse_params(to_yaml(defaults), "defaults.yaml");
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, defaults) << to_yaml(defaults);
  }
}

TEST(ParamsYaml, ASetWithEveryValueChangedReadsBackToTheSameValues) {
  for (const VehicleKind kind : kKinds) {
    // GIVEN a valid set in which every value differs from the model's default
    const GripParams changed = all_changed(kind);
    ASSERT_TRUE(grip::params::validate(changed).ok())
        << grip::params::validate(changed).error().message;
    const std::vector<std::string> lines = value_lines(to_yaml(changed));
    const std::vector<std::string> default_lines = value_lines(to_yaml(default_params(kind)));
    ASSERT_EQ(lines.size(), default_lines.size());
    for (std::size_t i = 0; i < lines.size(); ++i) {
      if (!lines[i].starts_with("  model:")) {
        EXPECT_NE(lines[i], default_lines[i]);
      }
    }

    // WHEN it is written and read back THEN every field is the same
    const auto read = parse_params(to_yaml(changed), "changed.yaml");
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, changed) << to_yaml(changed);
    EXPECT_EQ(to_yaml(*read), to_yaml(changed));
  }
}

TEST(ParamsYaml, DerivedValuesAreWrittenAsAutoAndANumberForThemIsTakenAsGiven) {
  const std::string yaml = to_yaml(default_params(VehicleKind::kCar));
  for (const char* line :
       {"  margin_s: auto", "  max_edges: auto", "  range_m: auto", "  rays: auto",
        "  sensing_radius_m: auto", "    reference_speed_m_s: auto", "    course_change_m: auto",
        "  cpu: auto"}) {
    EXPECT_NE(yaml.find(std::string(line) + "  #"), std::string::npos) << line;
  }

  const auto read = parse_params(
      "vehicle: {model: car}\n"
      "planner: {margin_s: 0.004, max_edges: 5000}\n"
      "sensor: {range_m: 0, rays: 720}\n"
      "exploration: {path_weight: {reference_speed_m_s: 0, course_change_m: 1.5}}\n"
      "runtime: {cpu: -1}\n",
      "numbers.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(read->planner.margin_s, 0.004);
  EXPECT_EQ(read->planner.max_edges, 5000U);
  EXPECT_EQ(read->sensor.range_m, 0.0);
  EXPECT_EQ(read->sensor.rays, 720U);
  EXPECT_EQ(read->exploration.path_weight.reference_speed_m_s, 0.0);
  EXPECT_EQ(read->exploration.path_weight.course_change_m, 1.5);
  EXPECT_EQ(read->runtime.cpu, -1);
}

TEST(ParamsYaml, KeysLeftOutTakeTheDefaultsOfTheModel) {
  const auto read = parse_params("vehicle:\n  model: dd-accel\nplanner:\n", "short.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  EXPECT_EQ(*read, default_params(VehicleKind::kDdAcceleration));
}

TEST(ParamsExamples, TheBuiltInVehiclesFilesHoldTheirDefaultsAsGripParamsPrintsThem) {
  for (const VehicleKind kind : kKinds) {
    const std::string path = kExamples + std::string(grip::vehicle_name(kind)) + ".yaml";
    const auto read = grip::params::load_params(path);
    ASSERT_TRUE(read.ok()) << read.error().message;
    EXPECT_EQ(*read, default_params(kind)) << path;
    EXPECT_EQ(file_text(path), to_yaml(default_params(kind))) << path;
  }
}

TEST(ParamsExamples, TheCompactCarIsThePapersCarWithItsOwnSizeAndLimits) {
  const auto read = grip::params::load_params(kExamples + "compact-car.yaml");
  ASSERT_TRUE(read.ok()) << read.error().message;
  CarParams expected;  // the paper's car
  expected.footprint = {0.95, 0.25, 0.3};
  expected.wheelbase_m = 0.9;
  expected.max_speed_m_s = 2.0;
  expected.min_speed_m_s = -0.5;
  expected.max_accel_m_s2 = 0.6;
  expected.braking_decel_m_s2 = 1.2;
  GripParams expected_params = default_params(VehicleKind::kCar);
  expected_params.vehicle = expected;
  EXPECT_EQ(*read, expected_params);
}

TEST(ParamsValidate, TheBuiltInVehiclesAreValid) {
  for (const VehicleKind kind : kKinds)
    EXPECT_TRUE(grip::params::validate(default_params(kind)).ok());
}

// The set's key for every rule, without a file to point into.
TEST(ParamsValidate, ASetBuiltInCodeIsRefusedByTheKeyOfItsFirstValueOutOfRange) {
  const auto message_for = [](GripParams p) {
    const grip::Status s = grip::params::validate(p);
    return s.ok() ? std::string("accepted") : s.error().message;
  };
  GripParams p = default_params(VehicleKind::kCar);
  std::get<CarParams>(p.vehicle).max_steer_rad = 2.0;
  EXPECT_TRUE(message_for(p).starts_with("vehicle.max_steer_rad must be")) << message_for(p);

  p = default_params(VehicleKind::kCar);
  p.planner.budget_s = 0.06;
  EXPECT_EQ(message_for(p), "planner.budget_s must be in (0, cycle_s = 0.05) (got 0.06)");

  p = default_params(VehicleKind::kCar);
  p.planner.tuning.score_base_a = 1.0;
  EXPECT_TRUE(message_for(p).starts_with("planner.score_base_a must be")) << message_for(p);

  p = default_params(VehicleKind::kDdVelocity);
  p.exploration.frontier.size_weight = -1.0;
  EXPECT_TRUE(message_for(p).starts_with("exploration.frontier.size_weight must be"))
      << message_for(p);

  // rho's clearance is the frontiers' too: the approach range must reach past it.
  p = default_params(VehicleKind::kDdVelocity);
  p.planner.tuning.rho_clearance_m = 0.6;
  EXPECT_TRUE(message_for(p).starts_with("exploration.frontier.approach_range_m must be"))
      << message_for(p);
  p.exploration.frontier.approach_range_m = 0.8;
  EXPECT_TRUE(grip::params::validate(p).ok()) << message_for(p);

  p = default_params(VehicleKind::kDdVelocity);
  p.planner.tuning.rho_cell_m = -0.1;
  EXPECT_TRUE(message_for(p).starts_with("planner.rho_cell_m must be")) << message_for(p);

  p = default_params(VehicleKind::kDdAcceleration);
  p.exploration.path_weight.reference_speed_m_s = -0.5;
  EXPECT_EQ(
      message_for(p),
      "exploration.path_weight.reference_speed_m_s must be auto or finite and >= 0 (got -0.5)");
  p = default_params(VehicleKind::kDdAcceleration);
  p.exploration.path_weight.length_weight_per_m = std::numeric_limits<double>::infinity();
  EXPECT_TRUE(message_for(p).starts_with("exploration.path_weight.length_weight_per_m must be"))
      << message_for(p);

  p = default_params(VehicleKind::kDdVelocity);
  p.sensor.rays = 8;
  EXPECT_EQ(message_for(p), "sensor.rays must be auto (0) or in [16, 100000] (got 8)");

  p = default_params(VehicleKind::kDdVelocity);
  p.link.domain = 233;
  EXPECT_TRUE(message_for(p).starts_with("link.domain must be at most 232")) << message_for(p);

  p = default_params(VehicleKind::kDdVelocity);
  p.link.topic_prefix = std::string(65, 'a');
  EXPECT_TRUE(message_for(p).starts_with("link.topic_prefix must be")) << message_for(p);

  p = default_params(VehicleKind::kDdVelocity);
  p.runtime.fifo_priority = 0;
  EXPECT_EQ(message_for(p), "runtime.fifo_priority must be in [1, 99] (got 0)");

  p = default_params(VehicleKind::kDdVelocity);
  p.runtime.cpu = 1024;
  EXPECT_EQ(message_for(p), "runtime.cpu must be auto (-1) or in [0, 1023] (got 1024)");
}

}  // namespace
